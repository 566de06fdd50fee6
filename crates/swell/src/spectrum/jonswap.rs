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
//! clamps the dimensionless fetch where `w_p` reaches Pierson-Moskowitz's peak `0.855 g/U10` (x_full
//! ≈ 1.7e4, about 170 km at 10 m/s). Clamping alone would leave the fully developed sea about 30 %
//! higher in Hs than Pierson-Moskowitz's (α = 0.0089 instead of 0.0081, and the peak enhanced by
//! γ = 3.3), although that *is* the fully developed sea: the JONSWAP fits were made on growing
//! seas, and the peak enhancement fades as a sea matures (Donelan et al. 1985 measure γ falling
//! with wave age). So over the last decade of fetch, `x_full / 10 <= x <= x_full`, swell blends
//! α and γ geometrically from the fetch laws to Pierson-Moskowitz's (α = 0.0081, γ = 1), with a
//! smoothstep weight in `log x`: at and beyond full development the spectrum *is*
//! Pierson-Moskowitz's (same shape, since `5/4 w_p⁴ = β w0⁴`), and the sea still grows with fetch
//! all the way there.

use super::pierson_moskowitz::{PiersonMoskowitz, PM_ALPHA};
use super::G;

/// JONSWAP's mean peak enhancement factor γ (Hasselmann et al. 1973).
pub const JONSWAP_GAMMA: f64 = 3.3;
/// Peak width σ below the peak frequency.
pub const JONSWAP_SIGMA_BELOW: f64 = 0.07;
/// Peak width σ above the peak frequency.
pub const JONSWAP_SIGMA_ABOVE: f64 = 0.09;

/// Weight in [0, 1] of the fully developed (Pierson-Moskowitz) α and γ at the dimensionless fetch
/// `q = x / x_full` (<= 1): 0 below a tenth of full development, 1 at it, a smoothstep in `log10 q`
/// between (see the module documentation).
fn maturity(q: f64) -> f64 {
    let s = (1.0 + q.log10()).clamp(0.0, 1.0);
    s * s * (3.0 - 2.0 * s)
}

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
        let w = maturity(x / x_full);
        let alpha = (0.076 * x.powf(-0.22)).powf(1.0 - w) * PM_ALPHA.powf(w);
        Self { alpha, peak_omega: 22.0 * G / u10 * x.powf(-1.0 / 3.0), gamma: gamma.powf(1.0 - w) }
    }

    /// Whether this spectrum is Pierson-Moskowitz's (γ = 1 and α = 0.0081, a fully developed sea).
    pub fn is_fully_developed(&self) -> bool {
        self.gamma == 1.0 && self.alpha == PM_ALPHA
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
    fn beyond_full_development_the_sea_is_pierson_moskowitz() {
        let m0 = |f: &dyn Fn(f64) -> f64| super::super::frequency_moment(f, 0, 0.05, 20.0, 20_000);
        for u in [8.0, 12.0, 20.0] {
            let pm = PiersonMoskowitz::from_u10(u);
            for fetch in [5e6, 1e9] {
                let j = Jonswap::from_wind(u, fetch, JONSWAP_GAMMA);
                assert!(j.is_fully_developed(), "U {u} fetch {fetch}: {j:?}");
                assert!((j.peak_omega / pm.peak_omega() - 1.0).abs() < 1e-9);
                let ratio = m0(&|w| j.density(w)) / m0(&|w| pm.density(w));
                assert!((ratio - 1.0).abs() < 1e-9, "U {u}: {ratio}");
            }
        }
    }

    #[test]
    fn the_sea_grows_with_fetch_all_the_way_to_full_development() {
        let m0 = |j: Jonswap| super::super::frequency_moment(|w| j.density(w), 0, 0.02, 30.0, 40_000);
        let u = 12.0;
        let mut last = 0.0;
        for i in 0..60 {
            let fetch = 1e3 * 1.12f64.powi(i);
            let e = m0(Jonswap::from_wind(u, fetch, JONSWAP_GAMMA));
            assert!(e >= last, "fetch {fetch}: {e} < {last}");
            last = e;
        }
        // Young seas keep the fetch laws and γ = 3.3.
        let young = Jonswap::from_wind(u, 20e3, JONSWAP_GAMMA);
        assert_eq!(young.gamma, JONSWAP_GAMMA);
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
