//! A plain sum of sine waves: the surface height is `y = sum A_i sin(k_i D_i.(x, z) - w_i t)`.
//!
//! No horizontal motion, so the height query is exact. This is the simplest model of paper 000
//! (§2.1) and paper 003 (§1.1.2), and the baseline every other model is compared with.

use std::f32::consts::TAU;

use glam::{Vec2, Vec3};
use serde::{Deserialize, Serialize};

use super::slope_spectrum::push_wave_slopes;
use super::wave_model::{evaluate_pointwise, PointWave, SurfacePoint, WaveModel};
use super::ModelParams;
use crate::error::{check_direction, check_range, Error, Result};
use crate::math::GridSpec;

/// Most waves one [`SumOfSines`] sums.
pub const MAX_SINE_WAVES: usize = 64;

/// One sine wave.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SineWave {
    /// Crest height above rest, in metres; >= 0.
    pub amplitude: f32,
    /// Crest-to-crest distance, in metres; > 0.
    pub wavelength: f32,
    /// Phase speed, in m/s; >= 0.
    pub speed: f32,
    /// Direction of travel as (x, z); non-zero, normalised on use.
    pub direction: Vec2,
}

impl SineWave {
    /// Checks every field, naming it under `key` (e.g. `water.sines[0]`).
    pub fn validate(&self, key: &str) -> Result<()> {
        // Upper bounds from `limits`: far past any real wave, low enough that sums of 64 waves and
        // the phase `k x - w t` stay finite in f32.
        use crate::limits::{MAX_WAVE_LENGTH_M, MAX_WAVE_SPEED};
        check_range(&format!("{key}.amplitude"), self.amplitude, 0.0, MAX_WAVE_LENGTH_M)?;
        check_range(&format!("{key}.wavelength"), self.wavelength, 1e-6, MAX_WAVE_LENGTH_M)?;
        check_range(&format!("{key}.speed"), self.speed, 0.0, MAX_WAVE_SPEED)?;
        check_direction(&format!("{key}.direction"), self.direction)?;
        Ok(())
    }
}

/// A sum of sine waves; see the [module documentation](self).
#[derive(Clone, Debug)]
pub struct SumOfSines {
    waves: Vec<SineWave>,
    /// (wave vector k D in rad/m, amplitude in m, angular frequency in rad/s) per wave.
    prepared: Vec<(Vec2, f32, f64)>,
}

impl SumOfSines {
    /// Builds the model, refusing invalid waves (0 to [`MAX_SINE_WAVES`] of them).
    pub fn new(waves: Vec<SineWave>) -> Result<Self> {
        Self::check(&waves)?;
        let prepared = waves
            .iter()
            .map(|w| {
                let k = TAU / w.wavelength;
                (w.direction.normalize() * k, w.amplitude, f64::from(w.speed) * f64::from(k))
            })
            .collect();
        Ok(Self { waves, prepared })
    }

    /// Checks a wave list: at most [`MAX_SINE_WAVES`], each valid (keys `water.waves[i]`).
    fn check(waves: &[SineWave]) -> Result<()> {
        if waves.len() > MAX_SINE_WAVES {
            return Err(Error::out_of_range(
                "water.waves",
                format!("{} waves", waves.len()),
                format!("[0, {MAX_SINE_WAVES}] waves"),
            ));
        }
        for (i, w) in waves.iter().enumerate() {
            w.validate(&format!("water.waves[{i}]"))?;
        }
        Ok(())
    }

    /// The waves, as given.
    pub fn waves(&self) -> &[SineWave] {
        &self.waves
    }
}

/// A plain sum of sines as a scene gives it: `model = "sines"` and a `[[water.waves]]` list.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SinesSpec {
    /// The waves, 0 to [`MAX_SINE_WAVES`] of them.
    #[serde(default)]
    pub waves: Vec<SineWave>,
}

impl ModelParams for SinesSpec {
    /// Everywhere: a sum of sines, a closed form of (x, z).
    fn defined_everywhere(&self) -> bool {
        true
    }

    fn validate(&self) -> Result<()> {
        SumOfSines::check(&self.waves)
    }

    fn build(&self) -> Result<Box<dyn WaveModel>> {
        Ok(Box::new(SumOfSines::new(self.waves.clone())?))
    }
}

impl PointWave for SumOfSines {
    type Frame = [f32; MAX_SINE_WAVES];

    fn frame(&self, t: f64) -> Self::Frame {
        let mut phase = [0.0; MAX_SINE_WAVES];
        for (p, &(_, _, omega)) in phase.iter_mut().zip(&self.prepared) {
            *p = (omega * t).rem_euclid(std::f64::consts::TAU) as f32;
        }
        phase
    }

    fn sample(&self, frame: &Self::Frame, rest: Vec2) -> SurfacePoint {
        let (mut y, mut dydx, mut dydz) = (0.0f32, 0.0f32, 0.0f32);
        for (&(k, a, _), &phase_t) in self.prepared.iter().zip(frame.iter()) {
            let (s, c) = (k.dot(rest) - phase_t).sin_cos();
            y += a * s;
            dydx += a * k.x * c;
            dydz += a * k.y * c;
        }
        SurfacePoint { offset: Vec3::new(0.0, y, 0.0), normal: Vec3::new(-dydx, 1.0, -dydz).normalize() }
    }
}

impl WaveModel for SumOfSines {
    /// The time derivative of the displacement ([`super::velocity_by_difference`]).
    fn surface_velocity(&self, x: f32, z: f32, t: f64) -> Vec3 {
        super::velocity_by_difference(self, x, z, t)
    }

    fn slope_components(&self, out: &mut Vec<(f32, f32)>) {
        push_wave_slopes(self.waves.iter().map(|w| (w.amplitude, w.wavelength)), out);
    }

    fn evaluate(&self, grid: &GridSpec, t: f64, positions: &mut [Vec3], normals: &mut [Vec3]) {
        evaluate_pointwise(self, grid, t, positions, normals);
    }

    /// Exact: the surface has no horizontal motion.
    fn height_at(&self, x: f32, z: f32, t: f64) -> f32 {
        self.sample(&self.frame(t), Vec2::new(x, z)).offset.y
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn height_and_normal_of_one_wave_are_the_textbook_ones() {
        let w = SineWave { amplitude: 0.5, wavelength: 10.0, speed: 2.0, direction: Vec2::X };
        let m = SumOfSines::new(vec![w]).unwrap();
        let k = TAU / 10.0;
        for i in 0..10 {
            let (x, t) = (i as f32 * 0.77, i as f64 * 0.3);
            let theta = k * x - k * 2.0 * t as f32;
            assert!((m.height_at(x, 4.0, t) - 0.5 * theta.sin()).abs() < 1e-4);
            let n = m.sample(&m.frame(t), Vec2::new(x, 4.0)).normal;
            let slope = 0.5 * k * theta.cos();
            assert!((n - Vec3::new(-slope, 1.0, 0.0).normalize()).length() < 1e-4);
        }
    }

    #[test]
    fn bad_direction_is_refused() {
        let w = SineWave { amplitude: 0.5, wavelength: 10.0, speed: 2.0, direction: Vec2::ZERO };
        let e = SumOfSines::new(vec![w]).unwrap_err().to_string();
        assert!(e.starts_with("water.waves[0].direction"), "{e}");
    }
}
