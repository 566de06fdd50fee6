//! The TMA spectrum: JONSWAP in water of finite depth.
//!
//! Bouws, Günther, Rosenthal and Vincent 1985 ("Similarity of the wind wave spectrum in finite depth
//! water", J. Geophys. Res. 90(C1)): `S_TMA(w) = S_JONSWAP(w) φ(w, D)` with Kitaigorodskii's depth
//! factor, the ratio between the finite-depth and deep-water forms of the k⁻³ saturation range:
//!
//! ```text
//! φ(w, D) = [k⁻³ dk/dw] / [k∞⁻³ dk∞/dw] = tanh²(kD) / (1 + 2kD / sinh(2kD))
//! ```
//!
//! with k from `w² = g k tanh(kD)`. The closed form follows from differentiating the dispersion
//! relation; it is used here exactly rather than through the usual piecewise approximation in
//! `w_h = w sqrt(D/g)`. φ is 1 in deep water and tends to `(w_h²)/2` in very shallow water.

use super::jonswap::Jonswap;
use super::Dispersion;

/// The TMA spectrum: a JONSWAP sea over water of a given depth.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tma {
    /// The deep-water JONSWAP spectrum for the same wind and fetch.
    pub jonswap: Jonswap,
    /// Water depth D (m, > 0).
    pub depth: f64,
    /// The angular frequency (rad/s) where this spectrum peaks ([`Tma::new`] finds it). The depth
    /// factor rises with frequency, so in shallow water the peak sits above JONSWAP's.
    pub peak_omega: f64,
}

/// Kitaigorodskii's depth factor φ(w, D) in [0, 1] for angular frequency w (rad/s) and depth D (m).
///
/// The dispersion relation takes the depth as f32 (as scene files give it); depths are f32 values.
pub fn tma_depth_factor(omega: f64, depth: f64) -> f64 {
    let k = Dispersion::FiniteDepth { depth: depth as f32 }.wavenumber_f64(omega);
    let kd = k * depth;
    if kd > 20.0 {
        return 1.0;
    }
    if kd <= 0.0 {
        return 0.0;
    }
    let t = kd.tanh();
    t * t / (1.0 + 2.0 * kd / (2.0 * kd).sinh())
}

impl Tma {
    /// The TMA spectrum of `jonswap` over water `depth` metres deep (> 0), with its own peak.
    pub fn new(jonswap: Jonswap, depth: f64) -> Self {
        let mut tma = Self { jonswap, depth, peak_omega: jonswap.peak_omega };
        tma.peak_omega = tma.find_peak();
        tma
    }

    /// The maximum of S(w): a scan from JONSWAP's peak (the depth factor only moves it up) to
    /// three times it, then golden-section refinement around the best sample, to 1e-9 relative.
    fn find_peak(&self) -> f64 {
        const SAMPLES: usize = 400;
        let (lo, hi) = (0.9 * self.jonswap.peak_omega, 3.0 * self.jonswap.peak_omega);
        let step = (hi - lo) / SAMPLES as f64;
        let best = (0..=SAMPLES)
            .map(|i| lo + step * i as f64)
            .max_by(|a, b| self.density(*a).total_cmp(&self.density(*b)))
            .expect("samples");
        let (mut a, mut b) = (best - step, best + step);
        let ratio = (5f64.sqrt() - 1.0) / 2.0;
        while b - a > 1e-9 * best {
            let (c, d) = (b - ratio * (b - a), a + ratio * (b - a));
            if self.density(c) > self.density(d) {
                b = d;
            } else {
                a = c;
            }
        }
        (a + b) / 2.0
    }

    /// S(w) in m² s/rad at angular frequency w (rad/s).
    pub fn density(&self, omega: f64) -> f64 {
        self.jonswap.density(omega) * tma_depth_factor(omega, self.depth)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spectrum::{frequency_moment, G};

    #[test]
    fn the_depth_factor_matches_its_definition_by_differentiation() {
        for depth in [1.0, 4.0, 30.0] {
            let disp = Dispersion::FiniteDepth { depth: depth as f32 };
            for w in [0.3, 0.8, 1.5, 3.0] {
                let h = 1e-5 * w;
                let k = disp.wavenumber_f64(w);
                let dk = (disp.wavenumber_f64(w + h) - disp.wavenumber_f64(w - h)) / (2.0 * h);
                let kinf = w * w / G;
                let want = (dk / (k * k * k)) / ((2.0 * w / G) / (kinf * kinf * kinf));
                assert!((tma_depth_factor(w, depth) - want).abs() < 1e-6, "D {depth} w {w}");
            }
        }
    }

    #[test]
    fn the_peak_is_the_tma_spectrum_s_own_and_rises_in_shallow_water() {
        let j = Jonswap::from_wind(12.0, 150e3, 3.3);
        assert!((Tma::new(j, 1e4).peak_omega / j.peak_omega - 1.0).abs() < 1e-6);
        let mut last = j.peak_omega;
        for depth in [20.0, 8.0, 3.0] {
            let t = Tma::new(j, depth);
            let wp = t.peak_omega;
            assert!(wp > last, "depth {depth}: {wp} not above {last}");
            for w in [0.97 * wp, 0.999 * wp, 1.001 * wp, 1.03 * wp] {
                assert!(t.density(w) <= t.density(wp), "depth {depth}: S({w}) above S({wp})");
            }
            last = wp;
        }
    }

    #[test]
    fn shallow_water_lowers_the_energy_by_the_depth_factor() {
        let j = Jonswap::from_wind(12.0, 150e3, 3.3);
        let m0 = |f: &dyn Fn(f64) -> f64| frequency_moment(f, 0, 0.05, 20.0, 20_000);
        let deep = m0(&|w| j.density(w));
        let mut last = deep;
        for depth in [100.0, 20.0, 8.0, 3.0] {
            let tma = Tma::new(j, depth);
            let shallow = m0(&|w| tma.density(w));
            assert!(shallow < last, "depth {depth}: {shallow} not below {last}");
            last = shallow;
            // Pointwise, the ratio is exactly φ, which is below 1 and 1 in deep water.
            let w = j.peak_omega;
            let ratio = tma.density(w) / j.density(w);
            assert!((ratio - tma_depth_factor(w, depth)).abs() < 1e-12 && ratio < 1.0);
        }
        assert!((Tma::new(j, 1e4).density(1.0) / j.density(1.0) - 1.0).abs() < 1e-12);
        // At 3 m the 12 m/s sea keeps well under half its deep-water variance.
        assert!(last < 0.5 * deep, "{last} vs {deep}");
    }
}
