//! The Phillips spectrum in Tessendorf's form, in physical units.
//!
//! Tessendorf 2001 ("Simulating Ocean Water", §3.3, eq. 23; paper 003 §1.2.2) writes
//! `P(k) = A exp(-1/(k L)²) / k⁴ |k̂·ŵ|²` with `L = V²/g` the largest wave a wind of speed V raises,
//! and suggests a factor `exp(-k² l²)` to remove waves shorter than l. Tessendorf leaves A as an
//! arbitrary "numeric constant". swell fixes it from Phillips's own saturation range (Phillips 1958,
//! `S(w) = α g² w⁻⁵`, α = 8.1e-3): converting to wavenumber with `w² = g k` gives the omnidirectional
//! `Φ(k) = (α/2) k⁻³`, so
//!
//! ```text
//! Φ(k) = (α/2) k⁻³ exp(-1/(k L)²) exp(-k² l²)        F(k, θ) = Φ(k) D(θ) / k
//! ```
//!
//! with `D` a normalised spreading (Tessendorf's `|k̂·ŵ|²` is [`super::SpreadingFunction::Cos2`]). Then
//! heights come out in metres and the tail agrees with Pierson-Moskowitz's.

use super::G;

/// Phillips's saturation constant α (Phillips 1958; the value Pierson and Moskowitz fitted, 8.1e-3).
pub const PHILLIPS_ALPHA: f64 = 8.1e-3;

/// Tessendorf's Phillips spectrum, omnidirectional part, in wavenumber.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Phillips {
    /// Wind speed V (m/s, > 0), here the 10 m wind U10.
    pub wind_speed: f64,
    /// Small-wave cutoff l (m, >= 0): waves much shorter than 2πl are removed; 0 keeps them all.
    pub small_wave_cutoff: f64,
}

impl Phillips {
    /// Largest wave scale `L = V²/g` (m).
    pub fn largest_wave(&self) -> f64 {
        self.wind_speed * self.wind_speed / G
    }

    /// Omnidirectional wavenumber spectrum Φ(k) (m³/rad) at k (rad/m, >= 0).
    pub fn density_k(&self, k: f64) -> f64 {
        if k <= 0.0 {
            return 0.0;
        }
        let kl = k * self.largest_wave();
        let cut = k * self.small_wave_cutoff;
        0.5 * PHILLIPS_ALPHA / (k * k * k) * (-1.0 / (kl * kl)).exp() * (-cut * cut).exp()
    }

    /// Wavenumber of the maximum of Φ (rad/m): `dΦ/dk = 0` gives `k = sqrt(2/3) / L` (without cutoff).
    pub fn peak_wavenumber(&self) -> f64 {
        (2.0f64 / 3.0).sqrt() / self.largest_wave()
    }
}
