//! A set of Gerstner waves generated from a few weather-like numbers (paper 000 §2.4-2.5; GPU Gems
//! ch. 1 §1.2.4): a wind direction, a spread of directions around it, a median wavelength and
//! amplitude, a wave count and a seed.
//!
//! - wavelengths are drawn log-uniformly between half and twice the median (GPU Gems' range);
//! - each amplitude keeps the median's amplitude/wavelength ratio: `A = L A_med / L_med` (paper 000
//!   §2.4), so every wave has the same steepness shape;
//! - directions are drawn uniformly within ± spread/2 of the wind;
//! - speeds are the phase speeds of the chosen [`Dispersion`] (deep water by default), so long waves
//!   outrun short ones as on real water;
//! - paper 000 §2.5: 4-8 waves make a lake, 9-12 a sea.
//!
//! The same parameters and seed always give the same waves (ChaCha8 stream of the seed).

use std::f32::consts::TAU;

use glam::Vec2;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};

use super::gerstner::{GerstnerWave, MAX_GERSTNER_WAVES};
use super::{Gerstner, ModelParams, WaveModel};
use crate::error::{check_count, check_non_negative, check_positive, check_range, check_seed, Error, Result};
use crate::spectrum::Dispersion;

/// Parameters of [`wave_set`]. In a scene file: `model = "wave-set"` with these keys in `[water]`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct WaveSetParams {
    /// Direction the waves travel, in degrees: the (x, z) direction `(cos a, sin a)`, so 0 is +X
    /// and 90 is +Z; any finite value. Default 0.
    pub wind_direction_deg: f32,
    /// Full angle of the fan of directions around the wind, degrees in [0, 360]. Default 60.
    pub spread_deg: f32,
    /// Median wavelength in metres, > 0. Default 20.
    pub median_wavelength: f32,
    /// Amplitude of a wave of median length in metres, >= 0, with `2 pi A / L <= 1`. Default 0.25.
    pub median_amplitude: f32,
    /// Number of waves, in [1, 64]. Default 10.
    pub count: u32,
    /// Seed of the random choices. Default 1.
    pub seed: u64,
    /// Artist steepness Q shared by all waves, in [0, 1] (see [`GerstnerWave::steepness`]). Default 0.6.
    pub steepness: f32,
    /// Dispersion relation giving each wave's speed. Default deep water.
    pub dispersion: Dispersion,
}

impl Default for WaveSetParams {
    fn default() -> Self {
        Self {
            wind_direction_deg: 0.0,
            spread_deg: 60.0,
            median_wavelength: 20.0,
            median_amplitude: 0.25,
            count: 10,
            seed: 1,
            steepness: 0.6,
            dispersion: Dispersion::Deep,
        }
    }
}

impl WaveSetParams {
    /// Checks every value, naming keys under `key` (normally `water`).
    pub fn validate(&self, key: &str) -> Result<()> {
        if !self.wind_direction_deg.is_finite() {
            return Err(Error::out_of_range(
                format!("{key}.wind_direction_deg"),
                self.wind_direction_deg,
                "finite degrees",
            ));
        }
        check_range(&format!("{key}.spread_deg"), self.spread_deg, 0.0, 360.0)?;
        check_positive(&format!("{key}.median_wavelength"), self.median_wavelength)?;
        check_non_negative(&format!("{key}.median_amplitude"), self.median_amplitude)?;
        let max_a = self.median_wavelength / TAU;
        if self.median_amplitude > max_a {
            return Err(Error::out_of_range(
                format!("{key}.median_amplitude"),
                self.median_amplitude,
                format!("[0, {max_a}] (2 pi A / L <= 1 for L = {} m)", self.median_wavelength),
            ));
        }
        check_count(&format!("{key}.count"), self.count, 1, MAX_GERSTNER_WAVES as u32)?;
        check_range(&format!("{key}.steepness"), self.steepness, 0.0, 1.0)?;
        check_seed(&format!("{key}.seed"), self.seed)?;
        self.dispersion.validate(&format!("{key}.dispersion"))
    }
}

/// Generates the waves described by `params`, longest first; see the [module documentation](self).
pub fn wave_set(params: &WaveSetParams) -> Result<Vec<GerstnerWave>> {
    params.validate("water")?;
    let mut rng = ChaCha8Rng::seed_from_u64(params.seed);
    let ratio = params.median_amplitude / params.median_wavelength;
    let wind = params.wind_direction_deg.to_radians();
    let half_spread = 0.5 * params.spread_deg.to_radians();
    let mut waves: Vec<GerstnerWave> = (0..params.count)
        .map(|_| {
            let wavelength = params.median_wavelength * 2.0f32.powf(rng.gen_range(-1.0f32..=1.0));
            let angle = wind + half_spread * rng.gen_range(-1.0f32..=1.0);
            let k = TAU / wavelength;
            GerstnerWave {
                amplitude: ratio * wavelength,
                wavelength,
                speed: params.dispersion.phase_speed(k),
                direction: Vec2::new(angle.cos(), angle.sin()),
                steepness: params.steepness,
            }
        })
        .collect();
    waves.sort_by(|a, b| b.wavelength.total_cmp(&a.wavelength));
    Ok(waves)
}

/// `model = "wave-set"` builds Gerstner waves ([`Gerstner`]) from these.
impl ModelParams for WaveSetParams {
    /// Everywhere: generated Gerstner waves, a closed form of (x, z).
    fn defined_everywhere(&self) -> bool {
        true
    }

    fn validate(&self) -> Result<()> {
        // Drawing the waves is cheap (at most a few dozen), and checks them as the build will.
        Gerstner::check(&wave_set(self)?)
    }

    fn build(&self) -> Result<Box<dyn WaveModel>> {
        Ok(Box::new(Gerstner::new(wave_set(self)?)?))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::water::Gerstner;

    #[test]
    fn waves_follow_the_wind_the_median_ratio_and_the_seed() {
        let p = WaveSetParams { wind_direction_deg: 90.0, spread_deg: 40.0, count: 12, seed: 7, ..Default::default() };
        let waves = wave_set(&p).unwrap();
        assert_eq!(waves.len(), 12);
        assert_eq!(waves, wave_set(&p).unwrap());
        assert_ne!(waves, wave_set(&WaveSetParams { seed: 8, ..p }).unwrap());
        for w in &waves {
            assert!((w.amplitude / w.wavelength - 0.25 / 20.0).abs() < 1e-6);
            assert!(w.wavelength >= 10.0 - 1e-3 && w.wavelength <= 40.0 + 1e-3);
            // Within 20 degrees of +Z.
            assert!(w.direction.y >= 20f32.to_radians().cos() - 1e-5, "{:?}", w.direction);
            let c = (crate::GRAVITY * w.wavelength / TAU).sqrt();
            assert!((w.speed - c).abs() < 1e-4);
        }
        assert!(Gerstner::new(waves).is_ok());
    }

    #[test]
    fn bad_parameters_name_key_value_and_range() {
        let e = wave_set(&WaveSetParams { count: 0, ..Default::default() }).unwrap_err();
        assert_eq!(e.to_string(), "water.count = 0 is outside [1, 64]");
        let e = wave_set(&WaveSetParams { median_amplitude: 5.0, ..Default::default() }).unwrap_err();
        assert!(e.to_string().starts_with("water.median_amplitude = 5 is outside [0, 3.18"), "{e}");
        let e = wave_set(&WaveSetParams { spread_deg: -1.0, ..Default::default() }).unwrap_err();
        assert_eq!(e.to_string(), "water.spread_deg = -1 is outside [0, 360]");
    }
}
