//! The dispersion relation of gravity waves, deep or of finite depth, as the FFT ocean needs it.
//!
//! Linear (Airy) wave theory: `w² = g k tanh(k D)` for water of depth D, which tends to the deep-water
//! `w² = g k` when `k D` is large (Tessendorf 2001, "Simulating Ocean Water", §3.2, eq. 14; paper 003
//! §1.2.2). Capillary terms are left out: they matter only below ~2 cm wavelengths, shorter than any
//! ocean grid cell. (A fuller dispersion module with capillarity lives apart; this is the minimal one.)

use super::G;

/// `tanh(k D)` equals 1 to f64 precision beyond this `k D`; deep-water formulas are used there.
const DEEP_KD: f64 = 20.0;

/// Gravity-wave dispersion over water of a given depth (or infinitely deep).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OceanDispersion {
    /// Water depth D in metres (> 0), or `None` for deep water.
    pub depth: Option<f64>,
}

impl OceanDispersion {
    /// Deep water: `w² = g k`.
    pub const DEEP: Self = Self { depth: None };

    /// Angular frequency w (rad/s) of wavenumber k (rad/m, >= 0).
    pub fn omega(&self, k: f64) -> f64 {
        match self.depth {
            Some(d) if k * d < DEEP_KD => (G * k * (k * d).tanh()).sqrt(),
            _ => (G * k).sqrt(),
        }
    }

    /// Group velocity `dw/dk` (m/s) at wavenumber k (rad/m, > 0).
    ///
    /// Differentiating `w² = g k tanh(kD)`: `2 w dw/dk = g (tanh(kD) + kD sech²(kD))`.
    pub fn group_velocity(&self, k: f64) -> f64 {
        match self.depth {
            Some(d) if k * d < DEEP_KD => {
                let kd = k * d;
                let sech = 1.0 / kd.cosh();
                G * (kd.tanh() + kd * sech * sech) / (2.0 * self.omega(k))
            }
            _ => 0.5 * (G / k).sqrt(),
        }
    }

    /// Wavenumber k (rad/m) of angular frequency w (rad/s, >= 0): the inverse of [`Self::omega`].
    ///
    /// Newton's method on `g k tanh(kD) - w² = 0`, started from the larger of the deep and shallow
    /// limits (`w²/g` and `w/sqrt(gD)`), which lies above the root, so the iteration decreases
    /// monotonically (the function is concave in k).
    pub fn wavenumber(&self, omega: f64) -> f64 {
        let deep = omega * omega / G;
        let Some(d) = self.depth else { return deep };
        if deep * d >= DEEP_KD || omega <= 0.0 {
            return deep;
        }
        let mut k = deep.max(omega / (G * d).sqrt());
        for _ in 0..50 {
            let t = (k * d).tanh();
            let f = G * k * t - omega * omega;
            let df = G * (t + k * d * (1.0 - t * t));
            let step = f / df;
            k -= step;
            if step.abs() <= 1e-14 * k {
                break;
            }
        }
        k
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wavenumber_inverts_omega_and_group_velocity_is_its_derivative() {
        for depth in [None, Some(0.5), Some(5.0), Some(200.0)] {
            let disp = OceanDispersion { depth };
            for k in [0.001, 0.02, 0.3, 1.0, 7.0] {
                let w = disp.omega(k);
                assert!((disp.wavenumber(w) - k).abs() < 1e-9 * k.max(1.0), "{depth:?} {k}");
                let h = 1e-6 * k;
                let fd = (disp.omega(k + h) - disp.omega(k - h)) / (2.0 * h);
                assert!((disp.group_velocity(k) - fd).abs() < 1e-6 * fd, "{depth:?} {k}");
            }
        }
    }

    #[test]
    fn shallow_water_waves_travel_at_sqrt_g_d() {
        let d = 2.0;
        let disp = OceanDispersion { depth: Some(d) };
        let k = 1e-4;
        assert!((disp.omega(k) / k - (G * d).sqrt()).abs() < 1e-6);
    }
}
