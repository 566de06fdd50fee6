//! Directional spreading functions D(θ): how a wind sea's energy is shared over directions.
//!
//! θ is the angle (rad, in (-π, π]) between a wave's direction of travel and the wind's (or the
//! swell's mean direction). Each function is normalised, `∫ D dθ = 1` over the circle, so spreading
//! never changes the sea's energy; the tests check this numerically.

use std::f64::consts::PI;

use serde::{Deserialize, Serialize};

use super::G;

crate::closed_set! {
    /// The spreading functions a scene can name (`spreading = "..."` of the FFT ocean).
    #[derive(Default)]
    pub enum SpreadingFunction: "a spreading function" {
        /// Tessendorf's `|k̂·ŵ|²` (Tessendorf 2001 §3.3, eq. 23), normalised to `(2/π) cos²θ` on the
        /// downwind half-plane and **zero against the wind**: Tessendorf's own factor keeps waves
        /// travelling against the wind as strong as those with it, which no wind raises; swell
        /// suppresses them and renormalises.
        Cos2 = "cos2",
        /// Mitsuyasu's cos-2s (Mitsuyasu et al. 1975, J. Phys. Oceanogr. 5; as in Goda 2000, "Random
        /// Seas and Design of Maritime Structures", §2.3.2):
        /// `D = N(s) cos^(2s)(θ/2)`, `N(s) = 2^(2s-1) Γ(s+1)² / (π Γ(2s+1))`, with
        /// `s = s_p (w/w_p)^5` below the peak and `s_p (w/w_p)^-2.5` above, `s_p = 11.5 (w_p U10/g)^-2.5`.
        #[default]
        Mitsuyasu = "mitsuyasu",
        /// Donelan, Hamilton and Hui 1985 (Phil. Trans. R. Soc. A 315), with Banner's 1990 extension
        /// above 1.6 w_p: `D = β / (2 tanh(βπ)) sech²(βθ)`, `β = 2.61 r^1.3` for `r = w/w_p < 0.95`,
        /// `2.28 r^-1.3` for `0.95 <= r < 1.6`, `10^(-0.4 + 0.8393 exp(-0.567 ln r²))` above.
        DonelanBanner = "donelan-banner",
    }
}

/// A directional spreading as a spectrum evaluates it: one of the named functions, or a
/// fixed-shape one that swell and Blender's keys set up (never named in a scene file).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Spreading {
    /// A function a scene names ([`SpreadingFunction`]).
    Named(SpreadingFunction),
    /// cos-2s with a fixed exponent s (>= 0), e.g. for swell, which is narrow in direction.
    Cos2s(f64),
    /// Blender's Ocean modifier alignment (`[water.blender]`): `|cos θ|^exponent`, times `against`
    /// (in [0, 1]) where the wave runs against the wind (cos θ < 0), normalised over the circle
    /// with `∫ |cos θ|^p dθ = 2 sqrt(π) Γ((p+1)/2) / Γ(p/2+1)` (Gradshteyn and Ryzhik 3.621.5).
    /// Blender does not normalise; swell does, so alignment never changes the sea's energy.
    CosPower {
        /// p >= 0; 0 spreads waves evenly over every direction.
        exponent: f64,
        /// Factor in [0, 1] on the half-plane against the wind.
        against: f64,
    },
}

impl From<SpreadingFunction> for Spreading {
    fn from(f: SpreadingFunction) -> Self {
        Spreading::Named(f)
    }
}

impl Default for Spreading {
    fn default() -> Self {
        Spreading::Named(SpreadingFunction::default())
    }
}

// By name, as the named functions are: the others are set up from other keys and never written.
impl Serialize for Spreading {
    fn serialize<S: serde::Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        match self {
            Spreading::Named(f) => f.serialize(s),
            other => Err(serde::ser::Error::custom(format!("{other:?} has no name in a scene file"))),
        }
    }
}

impl<'de> Deserialize<'de> for Spreading {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> std::result::Result<Self, D::Error> {
        SpreadingFunction::deserialize(d).map(Spreading::Named)
    }
}

impl Spreading {
    /// D(θ) in 1/rad for a wave of angular frequency `omega` in a sea with peak `peak_omega` (rad/s)
    /// raised by a 10 m wind `u10` (m/s). `theta` is relative to the mean direction, any real value.
    pub fn density(&self, theta: f64, omega: f64, peak_omega: f64, u10: f64) -> f64 {
        let theta = wrap_angle(theta);
        let r = omega / peak_omega;
        match *self {
            Spreading::Named(SpreadingFunction::Cos2) => {
                let c = theta.cos();
                if c > 0.0 {
                    2.0 / PI * c * c
                } else {
                    0.0
                }
            }
            Spreading::Named(SpreadingFunction::Mitsuyasu) => {
                let sp = 11.5 * (peak_omega * u10 / G).powf(-2.5);
                let s = if r <= 1.0 { sp * r.powi(5) } else { sp * r.powf(-2.5) };
                cos_2s(theta, s)
            }
            Spreading::Named(SpreadingFunction::DonelanBanner) => {
                let beta = if r < 0.95 {
                    2.61 * r.powf(1.3)
                } else if r < 1.6 {
                    2.28 * r.powf(-1.3)
                } else {
                    10f64.powf(-0.4 + 0.8393 * (-0.567 * (r * r).ln()).exp())
                };
                // Vanishing β (w -> 0) is the isotropic limit 1/(2π).
                if beta < 1e-9 {
                    return 1.0 / (2.0 * PI);
                }
                let sech = 1.0 / (beta * theta).cosh();
                beta / (2.0 * (beta * PI).tanh()) * sech * sech
            }
            Spreading::Cos2s(s) => cos_2s(theta, s),
            Spreading::CosPower { exponent: p, against } => {
                let c = theta.cos();
                let ln_circle = (4.0 * PI).ln() / 2.0 + ln_gamma((p + 1.0) / 2.0) - ln_gamma(p / 2.0 + 1.0);
                let norm = ln_circle.exp() * (1.0 + against) / 2.0;
                // powf(0, 0) = 1: with p = 0 every direction, the crosswind included, counts alike.
                let d = c.abs().powf(p) / norm;
                if c < 0.0 {
                    d * against
                } else {
                    d
                }
            }
        }
    }
}

/// `N(s) cos^(2s)(θ/2)`, normalised over the circle.
fn cos_2s(theta: f64, s: f64) -> f64 {
    let c = (0.5 * theta).cos().abs();
    let ln_n = (2.0 * s - 1.0) * std::f64::consts::LN_2 + 2.0 * ln_gamma(s + 1.0) - ln_gamma(2.0 * s + 1.0);
    if c <= 0.0 {
        return 0.0;
    }
    (ln_n + 2.0 * s * c.ln()).exp() / PI
}

/// θ wrapped into (-π, π].
fn wrap_angle(theta: f64) -> f64 {
    let t = (theta + PI).rem_euclid(2.0 * PI) - PI;
    if t == -PI {
        PI
    } else {
        t
    }
}

/// ln Γ(x) for x > 0, to about 1e-12: the recurrence `Γ(x) = Γ(x+1)/x` lifts x above 10, then
/// Stirling's series (Abramowitz and Stegun 6.1.41) to the x⁻⁷ term.
fn ln_gamma(mut x: f64) -> f64 {
    let mut shift = 0.0;
    while x < 10.0 {
        shift -= x.ln();
        x += 1.0;
    }
    let inv = 1.0 / x;
    let inv2 = inv * inv;
    let series = inv * (1.0 / 12.0 - inv2 * (1.0 / 360.0 - inv2 * (1.0 / 1260.0 - inv2 / 1680.0)));
    shift + (x - 0.5) * x.ln() - x + 0.5 * (2.0 * PI).ln() + series
}

#[cfg(test)]
mod tests {
    use super::*;

    fn integral(f: impl Fn(f64) -> f64) -> f64 {
        let n = 20_000;
        let h = 2.0 * PI / n as f64;
        (0..n).map(|i| f(-PI + (i as f64 + 0.5) * h) * h).sum()
    }

    #[test]
    fn ln_gamma_matches_factorials_and_half_integers() {
        let mut fact = 1.0f64;
        for n in 1..20 {
            assert!((ln_gamma(n as f64) - fact.ln()).abs() < 1e-11, "{n}");
            fact *= n as f64;
        }
        assert!((ln_gamma(0.5) - PI.sqrt().ln()).abs() < 1e-11);
    }

    #[test]
    fn every_spreading_integrates_to_one() {
        let wp = 0.8;
        for spreading in [
            Spreading::Named(SpreadingFunction::Cos2),
            Spreading::Named(SpreadingFunction::Mitsuyasu),
            Spreading::Named(SpreadingFunction::DonelanBanner),
            Spreading::Cos2s(25.0),
            Spreading::CosPower { exponent: 0.0, against: 1.0 },
            Spreading::CosPower { exponent: 2.0, against: 0.25 },
            Spreading::CosPower { exponent: 37.0, against: 0.0 },
        ] {
            for r in [0.3, 0.7, 0.95, 1.0, 1.3, 2.0, 4.0] {
                let total = integral(|t| spreading.density(t, r * wp, wp, 10.0));
                // 1e-5: cos-2s with small s has an infinite slope at θ = ±π, which slows the quadrature.
                assert!((total - 1.0).abs() < 1e-5, "{spreading:?} at w/w_p = {r}: {total}");
            }
        }
    }

    #[test]
    fn spreading_peaks_downwind_and_cos2_has_nothing_upwind() {
        for spreading in [
            Spreading::Named(SpreadingFunction::Cos2),
            Spreading::Named(SpreadingFunction::Mitsuyasu),
            Spreading::Named(SpreadingFunction::DonelanBanner),
        ] {
            let d = |t: f64| spreading.density(t, 1.0, 1.0, 10.0);
            assert!(d(0.0) > d(0.5) && d(0.5) > d(1.5) && d(1.5) >= d(3.0), "{spreading:?}");
        }
        assert_eq!(Spreading::Named(SpreadingFunction::Cos2).density(2.0, 1.0, 1.0, 10.0), 0.0);
        assert_eq!(wrap_angle(-PI), PI);
        assert!(
            (Spreading::Named(SpreadingFunction::Cos2).density(0.3 + 4.0 * PI, 1.0, 1.0, 10.0)
                - Spreading::Named(SpreadingFunction::Cos2).density(0.3, 1.0, 1.0, 10.0))
            .abs()
                < 1e-12
        );
    }
}
