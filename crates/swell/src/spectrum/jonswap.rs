//! The JONSWAP spectrum of a fetch-limited wind sea.
//!
//! Hasselmann et al. 1973 ("Measurements of wind-wave growth and swell decay during the Joint North
//! Sea Wave Project", Dtsch. Hydrogr. Z. A8(12), eqs. 2.1-2.4; paper 003 §1.2.2):
//!
//! ```text
//! S(w) = α g² w⁻⁵ exp(-5/4 (w_p/w)⁴) γ^r,     r = exp(-(w - w_p)² / (2 σ² w_p²))
//! α = 0.076 x^-0.22,    w_p = 22 (g/U10) x^(-1/3),    x = g F / U10²   (dimensionless fetch)
//! γ = 3.3,   σ = 0.07 for w <= w_p, 0.09 above
//! ```
//!
//! **Fully developed limit.** The fetch laws keep lowering the peak as the fetch grows, past the peak
//! of a fully developed (Pierson-Moskowitz) sea, which is unphysical: a sea stops growing. swell
//! clamps the dimensionless fetch where `w_p` reaches Pierson-Moskowitz's peak `0.855 g/U10` (x ≈
//! 1.7e4, about 170 km at 10 m/s) and says so here; at that fetch α ≈ 0.0089.

use super::pierson_moskowitz::PiersonMoskowitz;
use super::G;

/// JONSWAP's mean peak enhancement factor γ (Hasselmann et al. 1973).
pub const JONSWAP_GAMMA: f64 = 3.3;
/// Peak width σ below the peak frequency.
pub const JONSWAP_SIGMA_BELOW: f64 = 0.07;
/// Peak width σ above the peak frequency.
pub const JONSWAP_SIGMA_ABOVE: f64 = 0.09;

/// JONSWAP frequency spectrum.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Jonswap {
    /// Phillips-type constant α (dimensionless, > 0).
    pub alpha: f64,
    /// Peak angular frequency w_p (rad/s, > 0).
    pub peak_omega: f64,
    /// Peak enhancement γ (>= 1; 1 gives the Pierson-Moskowitz shape).
    pub gamma: f64,
}

impl Jonswap {
    /// The spectrum of a wind `u10` (m/s, > 0) blowing over `fetch` metres (> 0), with peak
    /// enhancement `gamma`; the fetch is clamped at full development (see the module doc).
    pub fn from_wind(u10: f64, fetch: f64, gamma: f64) -> Self {
        let x_full = (22.0 / Self::fully_developed_peak(u10)).powi(3);
        let x = (G * fetch / (u10 * u10)).min(x_full);
        Self { alpha: 0.076 * x.powf(-0.22), peak_omega: 22.0 * G / u10 * x.powf(-1.0 / 3.0), gamma }
    }

    /// Pierson-Moskowitz's peak `w_p U10 / g` for this wind (dimensionless, about 0.855).
    fn fully_developed_peak(u10: f64) -> f64 {
        PiersonMoskowitz::from_u10(u10).peak_omega() * u10 / G
    }

    /// S(w) in m² s/rad at angular frequency w (rad/s).
    pub fn density(&self, omega: f64) -> f64 {
        if omega <= 0.0 {
            return 0.0;
        }
        let wp = self.peak_omega;
        let sigma = if omega <= wp { JONSWAP_SIGMA_BELOW } else { JONSWAP_SIGMA_ABOVE };
        let r = (-(omega - wp).powi(2) / (2.0 * sigma * sigma * wp * wp)).exp();
        self.alpha * G * G / omega.powi(5) * (-1.25 * (wp / omega).powi(4)).exp() * self.gamma.powf(r)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_maximum_sits_at_the_peak_frequency() {
        for (u, fetch) in [(5.0, 20e3), (10.0, 100e3), (20.0, 500e3)] {
            let j = Jonswap::from_wind(u, fetch, JONSWAP_GAMMA);
            let (mut best, mut at) = (0.0, 0.0);
            for i in 1..200_000 {
                let w = i as f64 * 2e-5 * j.peak_omega;
                let s = j.density(w);
                if s > best {
                    (best, at) = (s, w);
                }
            }
            assert!((at / j.peak_omega - 1.0).abs() < 2e-3, "U {u}: max at {at}, w_p {}", j.peak_omega);
        }
    }

    #[test]
    fn gamma_one_at_full_development_is_close_to_pierson_moskowitz() {
        let u = 12.0;
        let j = Jonswap::from_wind(u, 1e9, 1.0);
        let pm = PiersonMoskowitz::from_u10(u);
        assert!((j.peak_omega / pm.peak_omega() - 1.0).abs() < 1e-9);
        let m0 = |f: &dyn Fn(f64) -> f64| super::super::frequency_moment(f, 0, 0.05, 20.0, 20_000);
        let ratio = m0(&|w| j.density(w)) / m0(&|w| pm.density(w));
        // Same shape and peak; α differs (0.0089 vs 0.0081 with 1.25 vs 0.74 scaling): within 15 %.
        assert!((ratio - 1.0).abs() < 0.15, "{ratio}");
    }

    #[test]
    fn a_longer_fetch_gives_a_higher_sea_with_a_lower_peak() {
        let m0 = |j: Jonswap| super::super::frequency_moment(|w| j.density(w), 0, 0.05, 30.0, 40_000);
        let short = Jonswap::from_wind(10.0, 10e3, 3.3);
        let long = Jonswap::from_wind(10.0, 100e3, 3.3);
        assert!(long.peak_omega < short.peak_omega);
        assert!(m0(long) > m0(short));
    }
}
