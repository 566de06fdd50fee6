//! Dispersion relations of surface gravity(-capillary) waves: angular frequency `w(k)` of a wave of
//! wavenumber `k`, its phase and group speeds, and paper 003's quantisation to a looping period.
//!
//! Sources: paper 000 eq. 3 and paper 003 §1.2.1 eqs. 7-10; Tessendorf, *Simulating Ocean Water*
//! (2001) §3.2; Lamb, *Hydrodynamics* §267-268 for the capillary term. With `g` = [`GRAVITY`],
//! surface tension [`SURFACE_TENSION`] and density [`WATER_DENSITY`]:
//!
//! ```text
//! deep water         w^2 = g k
//! finite depth D     w^2 = g k tanh(k D)
//! capillary-gravity  w^2 = (g k + sigma/rho k^3) tanh(k D)
//! ```
//!
//! Paper 003 writes the short-wave relation as `w^2 = g k (1 + k^2 L^2)`; that is the same law with
//! `L^2 = sigma / (rho g)` (L = 2.7 mm, the capillary length), so swell uses the explicit sigma/rho
//! form of paper 000.
//!
//! Everything is computed in `f64`. The `f32` methods serve the wave models that evaluate per
//! vertex; the `_f64` ones ([`Dispersion::omega_f64`], [`Dispersion::group_speed_f64`],
//! [`Dispersion::wavenumber_f64`]) serve the spectra and the FFT ocean, which set up in f64 (phases
//! `w t` must stay accurate to 1e-7 relative over minutes, and a spectrum's integral needs `dw/dk`
//! and the inverse `k(w)`).

use serde::{Deserialize, Serialize};
use std::f64::consts::TAU;

use crate::error::{check_positive, Result};
use crate::GRAVITY;

/// Beyond this `k D`, `tanh(k D)` equals 1 to f64 precision; the f64 methods use the deep-water
/// formulas there.
const DEEP_KD: f64 = 20.0;

/// Surface tension of clean water against air at about 20 °C, in N/m (paper 000 §1.2.2, paper 003).
pub const SURFACE_TENSION: f32 = 0.074;

/// Density of fresh water, in kg/m³.
pub const WATER_DENSITY: f32 = 1000.0;

/// Which dispersion relation gives a wave's angular frequency from its wavenumber.
///
/// In a scene file: `dispersion = { type = "deep" }`, `{ type = "finite-depth", depth = 10.0 }` or
/// `{ type = "capillary", depth = 100.0 }`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "kebab-case", deny_unknown_fields)]
pub enum Dispersion {
    /// Deep water, `w^2 = g k`: valid when the depth exceeds about half a wavelength and the waves
    /// are longer than a few centimetres. The default.
    #[default]
    Deep,
    /// Water of finite depth, `w^2 = g k tanh(k D)` (shallow water, paper 003 eq. 8).
    FiniteDepth {
        /// Water depth D in metres, > 0.
        depth: f32,
    },
    /// Gravity-capillary waves over depth D, `w^2 = (g k + sigma/rho k^3) tanh(k D)` (paper 000
    /// eq. 3); surface tension dominates below about 1.7 cm.
    Capillary {
        /// Water depth D in metres, > 0 (use a large value such as 100 for deep water).
        depth: f32,
    },
}

impl Dispersion {
    /// Checks the depth, naming it `key.depth` (e.g. `water.dispersion.depth`).
    pub fn validate(&self, key: &str) -> Result<()> {
        match *self {
            Dispersion::Deep => Ok(()),
            Dispersion::FiniteDepth { depth } | Dispersion::Capillary { depth } => {
                check_positive(&format!("{key}.depth"), depth)
            }
        }
    }

    /// `w^2 / k` (m/s²) and its derivative with respect to k, in f64.
    fn omega_squared_over_k(&self, k: f64) -> (f64, f64) {
        let g = f64::from(GRAVITY);
        match *self {
            Dispersion::Deep => (g, 0.0),
            Dispersion::FiniteDepth { depth } => {
                let d = f64::from(depth);
                let th = (k * d).tanh();
                (g * th, g * d * (1.0 - th * th))
            }
            Dispersion::Capillary { depth } => {
                let d = f64::from(depth);
                let th = (k * d).tanh();
                let s = f64::from(SURFACE_TENSION) / f64::from(WATER_DENSITY);
                let a = g + s * k * k;
                (a * th, 2.0 * s * k * th + a * d * (1.0 - th * th))
            }
        }
    }

    /// Angular frequency w (rad/s) of a wave of wavenumber `k` = 2 pi / wavelength (rad/m, >= 0).
    pub fn omega(&self, k: f32) -> f32 {
        let k = f64::from(k.max(0.0));
        (k * self.omega_squared_over_k(k).0).sqrt() as f32
    }

    /// Phase speed `w / k` (m/s) of the crests; the k -> 0 limit for k = 0 (`sqrt(g D)` for finite
    /// depth, infinite for deep water).
    pub fn phase_speed(&self, k: f32) -> f32 {
        let k = f64::from(k.max(0.0));
        if k == 0.0 {
            return match *self {
                Dispersion::Deep => f32::INFINITY,
                Dispersion::FiniteDepth { depth } | Dispersion::Capillary { depth } => {
                    (f64::from(GRAVITY) * f64::from(depth)).sqrt() as f32
                }
            };
        }
        (self.omega_squared_over_k(k).0 / k).sqrt() as f32
    }

    /// Group speed `dw/dk` (m/s): the speed at which a wave group, and its energy, travels.
    pub fn group_speed(&self, k: f32) -> f32 {
        let k = f64::from(k.max(0.0));
        if k == 0.0 {
            return self.phase_speed(0.0);
        }
        // w = sqrt(k F(k)) with F = w^2/k, so dw/dk = (F + k F') / (2 w).
        let (f, df) = self.omega_squared_over_k(k);
        ((f + k * df) / (2.0 * (k * f).sqrt())) as f32
    }

    /// Deep water (`None`) or water of depth D m (`Some(D)`, > 0): the relations a spectral ocean
    /// uses (no capillarity: it matters only below ~2 cm wavelengths, shorter than any ocean cell).
    pub fn for_depth(depth: Option<f32>) -> Self {
        match depth {
            Some(depth) => Dispersion::FiniteDepth { depth },
            None => Dispersion::Deep,
        }
    }

    /// Angular frequency w (rad/s) of wavenumber k (rad/m, >= 0), in f64.
    ///
    /// Beyond `k D` = [`DEEP_KD`] `tanh(k D)` is 1 to f64 precision and the deep-water form is used.
    pub fn omega_f64(&self, k: f64) -> f64 {
        let g = f64::from(GRAVITY);
        match *self {
            Dispersion::Deep => (g * k).sqrt(),
            Dispersion::FiniteDepth { depth } => {
                let d = f64::from(depth);
                if k * d < DEEP_KD {
                    (g * k * (k * d).tanh()).sqrt()
                } else {
                    (g * k).sqrt()
                }
            }
            Dispersion::Capillary { .. } => (k.max(0.0) * self.omega_squared_over_k(k.max(0.0)).0).sqrt(),
        }
    }

    /// Group speed `dw/dk` (m/s) at wavenumber k (rad/m, > 0), in f64.
    ///
    /// Differentiating `w² = g k tanh(kD)`: `2 w dw/dk = g (tanh(kD) + kD sech²(kD))`.
    pub fn group_speed_f64(&self, k: f64) -> f64 {
        let g = f64::from(GRAVITY);
        match *self {
            Dispersion::FiniteDepth { depth } if k * f64::from(depth) < DEEP_KD => {
                let kd = k * f64::from(depth);
                let sech = 1.0 / kd.cosh();
                g * (kd.tanh() + kd * sech * sech) / (2.0 * self.omega_f64(k))
            }
            Dispersion::Deep | Dispersion::FiniteDepth { .. } => 0.5 * (g / k).sqrt(),
            Dispersion::Capillary { .. } => {
                let (f, df) = self.omega_squared_over_k(k);
                (f + k * df) / (2.0 * (k * f).sqrt())
            }
        }
    }

    /// Wavenumber k (rad/m) of angular frequency w (rad/s, >= 0): the inverse of
    /// [`Dispersion::omega_f64`].
    ///
    /// Newton's method on `w²(k) - w² = 0`, started from the larger of the deep and shallow
    /// gravity-wave limits (`w²/g` and `w/sqrt(gD)`), which lies at or above the root (capillarity
    /// only raises w(k)). `w²(k)` increases with k; where it is convex (capillarity) the iterates
    /// decrease monotonically to the root, where it is concave (gravity, finite depth) the first
    /// step lands at or below the root and the iterates then increase monotonically to it.
    pub fn wavenumber_f64(&self, omega: f64) -> f64 {
        let g = f64::from(GRAVITY);
        let deep = omega * omega / g;
        let d = match *self {
            Dispersion::Deep => return deep,
            Dispersion::FiniteDepth { depth } => f64::from(depth),
            Dispersion::Capillary { depth } => f64::from(depth),
        };
        let gravity_only = matches!(self, Dispersion::FiniteDepth { .. });
        if omega <= 0.0 || (gravity_only && deep * d >= DEEP_KD) {
            return deep;
        }
        let mut k = deep.max(omega / (g * d).sqrt());
        for _ in 0..50 {
            let (f, df) = if gravity_only {
                let t = (k * d).tanh();
                (g * k * t - omega * omega, g * (t + k * d * (1.0 - t * t)))
            } else {
                let (a, da) = self.omega_squared_over_k(k);
                (k * a - omega * omega, a + k * da)
            };
            let step = f / df;
            k -= step;
            if step.abs() <= 1e-14 * k {
                break;
            }
        }
        k
    }

    /// Period (s) of a wave of length `wavelength` (m, > 0).
    pub fn period_of_wavelength(&self, wavelength: f32) -> f32 {
        (TAU / f64::from(self.omega((TAU / f64::from(wavelength)) as f32))) as f32
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_100_m_wave_has_the_textbook_periods() {
        // Deep water: T = sqrt(2 pi L / g) = 8.003 s for L = 100 m.
        assert!((Dispersion::Deep.period_of_wavelength(100.0) - 8.003).abs() < 5e-4);
        // At 10 m depth the same wave is slower: 10.72 s.
        let shallow = Dispersion::FiniteDepth { depth: 10.0 };
        assert!((shallow.period_of_wavelength(100.0) - 10.72).abs() < 5e-3);
        // Very deep finite depth tends to deep water; very shallow to sqrt(g D).
        let deep = Dispersion::FiniteDepth { depth: 1e4 };
        assert!((deep.omega(0.3) - Dispersion::Deep.omega(0.3)).abs() < 1e-6);
        let k = 1e-3;
        assert!((Dispersion::FiniteDepth { depth: 1.0 }.phase_speed(k) - GRAVITY.sqrt()).abs() < 1e-3);
    }

    #[test]
    fn the_slowest_capillary_gravity_wave_is_1_73_cm_at_0_232_m_per_s() {
        let d = Dispersion::Capillary { depth: 100.0 };
        // Scan wavelengths 5 mm .. 10 cm for the minimum phase speed.
        let (mut best_l, mut best_c) = (0.0, f32::INFINITY);
        for i in 0..=9500 {
            let l = 0.005 + i as f32 * 1e-5;
            let c = d.phase_speed(std::f32::consts::TAU / l);
            if c < best_c {
                (best_l, best_c) = (l, c);
            }
        }
        assert!((best_l - 0.0173).abs() < 1e-4, "slowest wavelength {best_l}");
        assert!((best_c - 0.232).abs() < 5e-4, "slowest speed {best_c}");
        // At the minimum of the phase speed, group and phase speeds coincide.
        let k = std::f32::consts::TAU / best_l;
        assert!((d.group_speed(k) - best_c).abs() < 2e-3);
    }

    #[test]
    fn group_speed_is_the_derivative_of_omega() {
        for d in [Dispersion::Deep, Dispersion::FiniteDepth { depth: 3.0 }, Dispersion::Capillary { depth: 0.5 }] {
            for k in [0.05f32, 0.7, 3.0, 40.0, 400.0] {
                let h = k * 1e-3;
                let fd = (d.omega(k + h) - d.omega(k - h)) / (2.0 * h);
                assert!((d.group_speed(k) - fd).abs() < 1e-3 * fd.abs().max(1.0), "{d:?} k={k}");
            }
        }
        // Deep water: group speed is half the phase speed.
        assert!((Dispersion::Deep.group_speed(0.1) * 2.0 - Dispersion::Deep.phase_speed(0.1)).abs() < 1e-5);
    }

    #[test]
    fn bad_depths_are_refused_with_the_key() {
        let e = Dispersion::FiniteDepth { depth: -1.0 }.validate("water.dispersion").unwrap_err();
        assert_eq!(e.to_string(), "water.dispersion.depth = -1 is outside (0, inf)");
    }

    #[test]
    fn wavenumber_inverts_omega_and_group_speed_is_its_derivative() {
        for disp in [
            Dispersion::Deep,
            Dispersion::FiniteDepth { depth: 0.5 },
            Dispersion::FiniteDepth { depth: 5.0 },
            Dispersion::FiniteDepth { depth: 200.0 },
            Dispersion::Capillary { depth: 3.0 },
        ] {
            for k in [0.001, 0.02, 0.3, 1.0, 7.0, 400.0] {
                let w = disp.omega_f64(k);
                assert!((disp.wavenumber_f64(w) - k).abs() < 1e-9 * k.max(1.0), "{disp:?} {k}");
                let h = 1e-6 * k;
                let fd = (disp.omega_f64(k + h) - disp.omega_f64(k - h)) / (2.0 * h);
                assert!((disp.group_speed_f64(k) - fd).abs() < 1e-6 * fd, "{disp:?} {k}");
                // The f64 and f32 forms agree.
                assert!((f64::from(disp.omega(k as f32)) - w).abs() <= 1e-6 * w, "{disp:?} {k}");
            }
        }
    }

    #[test]
    fn shallow_water_waves_travel_at_sqrt_g_d() {
        let d = 2.0;
        let disp = Dispersion::for_depth(Some(d));
        let k = 1e-4;
        let g = f64::from(GRAVITY);
        assert!((disp.omega_f64(k) / k - (g * f64::from(d)).sqrt()).abs() < 1e-6);
        assert_eq!(Dispersion::for_depth(None), Dispersion::Deep);
    }
}
