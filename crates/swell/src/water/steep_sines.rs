//! Paper 003's steep sum of sines (§1.1.2, eqs. 1-3, after GPU Gems ch. 1 §1.2.3):
//!
//! ```text
//! S_i = (pos . D_i - v_i t) freq_i         f_i = A_i ((sin S_i + 1) / 2)^k_i         y = sum f_i
//! ```
//!
//! Raising the sine, shifted into [0, 1], to a power k >= 1 narrows the crests and widens the
//! troughs. Heights lie in [0, sum A_i]: every crest rises above the rest plane and every trough
//! touches it. One departure from the paper: it writes `S = (pos . dir) freq + velocity freq t`,
//! which moves crests against `dir`; swell subtracts so that `direction` is the direction of travel,
//! as for every other model. No horizontal motion, so the height query is exact.

use glam::{Vec2, Vec3};
use serde::{Deserialize, Serialize};

use super::wave_model::{evaluate_pointwise, PointWave, SurfacePoint, WaveModel};
use super::ModelParams;
use crate::error::{check_direction, check_non_negative, check_positive, check_range, Error, Result};
use crate::math::{fast_sin_cos, GridSpec};

/// Most waves one [`SteepSines`] sums.
pub const MAX_STEEP_SINE_WAVES: usize = 64;

/// Largest exponent k: beyond it the crest is a spike one grid cell wide on any practical grid.
pub const MAX_STEEP_SINE_EXPONENT: f32 = 64.0;

/// One steep sine wave (paper 003 eq. 2).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SteepSineWave {
    /// Crest height above the rest plane, metres; >= 0.
    pub amplitude: f32,
    /// Spatial frequency `freq` = 2 pi / wavelength, rad/m; > 0.
    pub frequency: f32,
    /// Crest speed `velocity`, m/s; >= 0.
    pub velocity: f32,
    /// Direction of travel as (x, z); non-zero, normalised on use.
    pub direction: Vec2,
    /// Sharpness exponent k in [1, 64]: 1 is a raised sine, larger values give narrower crests.
    pub exponent: f32,
}

/// Parameters of [`SteepSines`]: `model = "steep-sines"` and a `[[water.waves]]` list.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SteepSinesParams {
    /// The waves, 0 to [`MAX_STEEP_SINE_WAVES`].
    #[serde(default)]
    pub waves: Vec<SteepSineWave>,
}

impl SteepSineWave {
    /// Checks this one wave, naming keys under `key` (e.g. `water.waves[2]`).
    pub fn validate(&self, key: &str) -> Result<()> {
        check_non_negative(&format!("{key}.amplitude"), self.amplitude)?;
        check_positive(&format!("{key}.frequency"), self.frequency)?;
        check_non_negative(&format!("{key}.velocity"), self.velocity)?;
        check_range(&format!("{key}.exponent"), self.exponent, 1.0, MAX_STEEP_SINE_EXPONENT)?;
        check_direction(&format!("{key}.direction"), self.direction)
    }
}

impl SteepSinesParams {
    /// Checks every value, naming keys under `key` (normally `water`).
    pub fn validate(&self, key: &str) -> Result<()> {
        if self.waves.len() > MAX_STEEP_SINE_WAVES {
            return Err(Error::out_of_range(
                format!("{key}.waves"),
                format!("{} waves", self.waves.len()),
                format!("[0, {MAX_STEEP_SINE_WAVES}] waves"),
            ));
        }
        for (i, w) in self.waves.iter().enumerate() {
            w.validate(&format!("{key}.waves[{i}]"))?;
        }
        Ok(())
    }
}

/// The steep sum of sines; see the [module documentation](self).
#[derive(Clone, Debug)]
pub struct SteepSines {
    params: SteepSinesParams,
    /// (freq D in rad/m, A, k, angular frequency v freq in rad/s) per wave.
    prepared: Vec<(Vec2, f32, f32, f64)>,
}

impl SteepSines {
    /// Builds the model, refusing invalid parameters.
    pub fn new(params: SteepSinesParams) -> Result<Self> {
        params.validate("water")?;
        let prepared = params
            .waves
            .iter()
            .map(|w| {
                (
                    w.direction.normalize() * w.frequency,
                    w.amplitude,
                    w.exponent,
                    f64::from(w.velocity) * f64::from(w.frequency),
                )
            })
            .collect();
        Ok(Self { params, prepared })
    }

    /// The parameters, as given.
    pub fn params(&self) -> &SteepSinesParams {
        &self.params
    }
}

impl ModelParams for SteepSinesParams {
    /// Everywhere: a sum of powered sines, a closed form of (x, z).
    fn defined_everywhere(&self) -> bool {
        true
    }

    fn validate(&self) -> Result<()> {
        SteepSinesParams::validate(self, "water")
    }

    fn build(&self) -> Result<Box<dyn WaveModel>> {
        Ok(Box::new(SteepSines::new(self.clone())?))
    }
}

impl PointWave for SteepSines {
    type Frame = [f32; MAX_STEEP_SINE_WAVES];

    fn frame(&self, t: f64) -> Self::Frame {
        let mut phase = [0.0; MAX_STEEP_SINE_WAVES];
        for (p, w) in phase.iter_mut().zip(&self.prepared) {
            *p = (w.3 * t).rem_euclid(std::f64::consts::TAU) as f32;
        }
        phase
    }

    fn sample(&self, frame: &Self::Frame, rest: Vec2) -> SurfacePoint {
        let (mut y, mut dx, mut dz) = (0.0f32, 0.0f32, 0.0f32);
        for (&(kv, a, k, _), &ph) in self.prepared.iter().zip(frame.iter()) {
            let (s, c) = fast_sin_cos(kv.dot(rest) - ph);
            let u = (0.5 * (s + 1.0)).clamp(0.0, 1.0);
            let u_k1 = u.powf(k - 1.0);
            y += a * u_k1 * u;
            // d/dpos of A u^k = A k u^(k-1) (cos S / 2) freq D.
            let slope = a * k * u_k1 * 0.5 * c;
            dx += slope * kv.x;
            dz += slope * kv.y;
        }
        SurfacePoint { offset: Vec3::new(0.0, y, 0.0), normal: Vec3::new(-dx, 1.0, -dz).normalize() }
    }
}

impl WaveModel for SteepSines {
    /// The time derivative of the displacement ([`super::velocity_by_difference`]).
    fn surface_velocity(&self, x: f32, z: f32, t: f64) -> Vec3 {
        super::velocity_by_difference(self, x, z, t)
    }

    /// `A ((sin S + 1) / 2)^e` is a sine of amplitude A/2 for e = 1; sharper crests (larger e)
    /// are counted as that sine, a lower bound on their slopes.
    fn slope_components(&self, out: &mut Vec<(f32, f32)>) {
        for w in &self.params.waves {
            out.push((w.frequency, 0.5 * (0.5 * w.amplitude * w.frequency).powi(2)));
        }
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

    fn wave(k: f32) -> SteepSineWave {
        SteepSineWave { amplitude: 0.4, frequency: 0.5, velocity: 2.0, direction: Vec2::new(1.0, 1.0), exponent: k }
    }

    #[test]
    fn heights_follow_the_formula_and_normals_the_slope() {
        let m = SteepSines::new(SteepSinesParams { waves: vec![wave(2.5)] }).unwrap();
        let d = Vec2::new(1.0, 1.0).normalize();
        let eps = 1e-3;
        for i in 0..30 {
            let (x, z, t) = (i as f32 * 0.9 - 11.0, i as f32 * 0.37, i as f64 * 0.4);
            let s = (Vec2::new(x, z).dot(d) - 2.0 * t as f32) * 0.5;
            let expected = 0.4 * ((s.sin() + 1.0) / 2.0).powf(2.5);
            assert!((m.height_at(x, z, t) - expected).abs() < 1e-5);
            assert!(m.height_at(x, z, t) >= 0.0 && m.height_at(x, z, t) <= 0.4 + 1e-6);
            let n = m.sample(&m.frame(t), Vec2::new(x, z)).normal;
            let dx = (m.height_at(x + eps, z, t) - m.height_at(x - eps, z, t)) / (2.0 * eps);
            let dz = (m.height_at(x, z + eps, t) - m.height_at(x, z - eps, t)) / (2.0 * eps);
            assert!((n - Vec3::new(-dx, 1.0, -dz).normalize()).length() < 2e-3);
        }
    }

    #[test]
    fn an_exponent_below_one_is_refused() {
        let e = SteepSines::new(SteepSinesParams { waves: vec![wave(0.5)] }).unwrap_err();
        assert_eq!(e.to_string(), "water.waves[0].exponent = 0.5 is outside [1, 64]");
    }
}
