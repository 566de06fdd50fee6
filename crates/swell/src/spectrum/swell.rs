//! A swell component: long, regular waves from a distant storm, added to the local wind sea.
//!
//! Swell is narrow in frequency and direction. swell models it as Goda's practice suggests
//! (Goda 2000, "Random Seas and Design of Maritime Structures", §2.3: a JONSWAP shape with a large
//! peak enhancement γ, and cos-2s spreading with a large s, 25 for swell of short decay distance to
//! 75 for long swell), scaled so that its own significant height is exactly the one given.

use super::jonswap::Jonswap;
use super::{frequency_moment, Spreading};

/// Peak enhancement of the swell's JONSWAP shape: a narrow, regular swell (Goda 2000 §2.3).
const SWELL_GAMMA: f64 = 7.0;

/// A swell component with its own height, period and direction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Swell {
    shape: Jonswap,
    /// Significant height Hs of the swell alone (m, >= 0).
    pub height: f64,
    /// Mean direction of travel (rad, from +X towards +Z).
    pub direction: f64,
    /// Directional spreading about `direction`.
    pub spreading: Spreading,
}

impl Swell {
    /// A swell of significant height `height` (m), peak period `period` (s, > 0), travelling towards
    /// `direction` (rad) with cos-2s spreading of exponent `spread_s` (>= 0; larger is narrower).
    pub fn new(height: f64, period: f64, direction: f64, spread_s: f64) -> Self {
        let peak_omega = std::f64::consts::TAU / period;
        let unit = Jonswap { alpha: 1.0, peak_omega, gamma: SWELL_GAMMA };
        // Normalise: the unit-α shape's variance, integrated well past both tails.
        let m0 = frequency_moment(|w| unit.density(w), 0, 0.2 * peak_omega, 8.0 * peak_omega, 20_000);
        let alpha = (height / 4.0).powi(2) / m0;
        Self { shape: Jonswap { alpha, ..unit }, height, direction, spreading: Spreading::Cos2s(spread_s) }
    }

    /// S(w) in m² s/rad at angular frequency w (rad/s).
    pub fn density(&self, omega: f64) -> f64 {
        self.shape.density(omega)
    }

    /// Peak angular frequency (rad/s).
    pub fn peak_omega(&self) -> f64 {
        self.shape.peak_omega
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_swell_has_the_significant_height_it_was_given() {
        let s = Swell::new(1.5, 12.0, 0.3, 25.0);
        let m0 = frequency_moment(|w| s.density(w), 0, 0.01, 10.0, 100_000);
        assert!((4.0 * m0.sqrt() - 1.5).abs() < 0.01, "{}", 4.0 * m0.sqrt());
    }
}
