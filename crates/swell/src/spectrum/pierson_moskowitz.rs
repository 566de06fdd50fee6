//! The Pierson-Moskowitz spectrum of a fully developed sea.
//!
//! Pierson and Moskowitz 1964 (J. Geophys. Res. 69(24), eq. 3), as given by Stewart, "Introduction to
//! Physical Oceanography", §16.3:
//!
//! ```text
//! S(w) = α g² w⁻⁵ exp(-β (w0 / w)⁴),   w0 = g / U19.5,   α = 8.1e-3,   β = 0.74
//! ```
//!
//! **Wind height.** The fit uses U19.5, the wind 19.5 m above the sea (the ships' anemometers). swell's
//! key is the 10 m wind U10; with a neutral logarithmic profile `U19.5 ≈ 1.026 U10` (Stewart §16.3),
//! which [`u19_5_from_u10`] applies. Integrating gives `m0 = α U19.5⁴ / (4 β g²)`, so
//! `Hs = 4 sqrt(m0) = 2 sqrt(α/β) U19.5²/g ≈ 0.21 U19.5²/g`, and the peak sits at
//! `w_p = (4β/5)^(1/4) g/U19.5 ≈ 0.877 g/U19.5 ≈ 0.855 g/U10`, i.e. `f_p ≈ 0.136 g/U10`: paper 003's
//! `f_m = 0.13 g/U10` is this peak rounded.

use super::G;

/// Pierson-Moskowitz's α (dimensionless).
pub const PM_ALPHA: f64 = 8.1e-3;
/// Pierson-Moskowitz's β (dimensionless).
pub const PM_BETA: f64 = 0.74;
/// `U19.5 / U10` for a neutral logarithmic wind profile over the sea (Stewart §16.3).
const U19_5_OVER_U10: f64 = 1.026;

/// The wind 19.5 m above the sea (m/s) from the 10 m wind U10 (m/s).
pub fn u19_5_from_u10(u10: f64) -> f64 {
    U19_5_OVER_U10 * u10
}

/// Pierson-Moskowitz frequency spectrum for a given wind.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PiersonMoskowitz {
    /// Wind speed 19.5 m above the sea, m/s (> 0).
    pub u19_5: f64,
}

impl PiersonMoskowitz {
    /// The spectrum for a 10 m wind `u10` (m/s).
    pub fn from_u10(u10: f64) -> Self {
        Self { u19_5: u19_5_from_u10(u10) }
    }

    /// S(w) in m² s/rad at angular frequency w (rad/s).
    pub fn density(&self, omega: f64) -> f64 {
        if omega <= 0.0 {
            return 0.0;
        }
        let w0 = G / self.u19_5;
        PM_ALPHA * G * G / omega.powi(5) * (-PM_BETA * (w0 / omega).powi(4)).exp()
    }

    /// Peak angular frequency `(4β/5)^(1/4) g / U19.5` (rad/s).
    pub fn peak_omega(&self) -> f64 {
        (0.8 * PM_BETA).powf(0.25) * G / self.u19_5
    }

    /// Significant wave height `2 sqrt(α/β) U19.5²/g` (m) of the whole spectrum.
    pub fn significant_height(&self) -> f64 {
        2.0 * (PM_ALPHA / PM_BETA).sqrt() * self.u19_5 * self.u19_5 / G
    }
}
