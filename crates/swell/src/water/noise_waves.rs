//! A water surface of drifting, evolving gradient noise (paper 003 §1.1.1; Perlin, *Improving
//! Noise*, 2002):
//!
//! ```text
//! y = A / N fbm( (x - v_x t) / s, (z - v_z t) / s, e t ),     N = sum_{o < octaves} persistence^o
//! ```
//!
//! fBm sums `octaves` layers of [`Perlin`] noise, each `lacunarity` times finer and `persistence`
//! times weaker than the last; dividing by N keeps |y| within about A whatever the octaves. The
//! pattern drifts with velocity v and changes in place at rate e through the third noise
//! coordinate. Cheap and smooth but not physical (paper 003 says as much): no dispersion, no
//! direction of travel beyond the drift. Normals come from fBm's analytic gradient, so they match
//! finite differences. No horizontal motion, so the height query is exact.
//!
//! Time enters the noise coordinates in `f32`: the pattern stays smooth while `|v| t / s` and `e t`
//! stay below about 1e5 (more than a day at the defaults).

use glam::{Vec2, Vec3};
use serde::{Deserialize, Serialize};

use super::wave_model::{evaluate_pointwise, PointWave, SurfacePoint, WaveModel};
use super::ModelParams;
use crate::error::{
    check_count, check_finite_vec, check_non_negative, check_positive, check_range, check_seed, Result,
};
use crate::math::{GridSpec, Perlin};

/// Most fBm octaves (beyond 12 the finest octave is far below any grid cell).
pub const MAX_NOISE_OCTAVES: u32 = 12;

/// Parameters of [`NoiseWaves`]: `model = "noise"`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct NoiseParams {
    /// Largest height A above or below rest, metres; >= 0. Default 0.3.
    pub amplitude: f32,
    /// Size s of the coarsest features (one noise lattice cell), metres; > 0. Default 8.
    pub scale: f32,
    /// Number of fBm layers, in [1, 12]. Default 5.
    pub octaves: u32,
    /// Amplitude ratio between successive octaves, in (0, 1]. Default 0.5.
    pub persistence: f32,
    /// Frequency ratio between successive octaves, in [1, 4]. Default 2.
    pub lacunarity: f32,
    /// Drift velocity (x, z) of the pattern, m/s; finite. Default (1, 0.3).
    pub drift: Vec2,
    /// Rate e at which the pattern changes in place, lattice cells per second; >= 0. Default 0.15.
    pub evolution: f32,
    /// Seed of the noise field. Default 1.
    pub seed: u64,
}

impl Default for NoiseParams {
    fn default() -> Self {
        Self {
            amplitude: 0.3,
            scale: 8.0,
            octaves: 5,
            persistence: 0.5,
            lacunarity: 2.0,
            drift: Vec2::new(1.0, 0.3),
            evolution: 0.15,
            seed: 1,
        }
    }
}

impl NoiseParams {
    /// Checks every value, naming keys under `key` (normally `water`).
    pub fn validate(&self, key: &str) -> Result<()> {
        check_non_negative(&format!("{key}.amplitude"), self.amplitude)?;
        check_positive(&format!("{key}.scale"), self.scale)?;
        check_count(&format!("{key}.octaves"), self.octaves, 1, MAX_NOISE_OCTAVES)?;
        if !(self.persistence > 0.0 && self.persistence <= 1.0) {
            return Err(crate::error::Error::out_of_range(
                format!("{key}.persistence"),
                crate::error::Human(self.persistence),
                "(0, 1]",
            ));
        }
        check_range(&format!("{key}.lacunarity"), self.lacunarity, 1.0, 4.0)?;
        check_finite_vec(&format!("{key}.drift"), &self.drift.to_array())?;
        check_non_negative(&format!("{key}.evolution"), self.evolution)?;
        check_seed(&format!("{key}.seed"), self.seed)
    }
}

/// The noise surface; see the [module documentation](self).
#[derive(Clone, Debug)]
pub struct NoiseWaves {
    params: NoiseParams,
    noise: Perlin,
    /// A / (N s): height per unit noise is A / N; slopes carry one more 1 / s.
    height_scale: f32,
}

/// Per-frame noise-space offset: (-v_x t / s, -v_z t / s, e t).
#[derive(Clone, Copy, Debug)]
pub struct NoiseFrame(Vec3);

impl NoiseWaves {
    /// Builds the model, refusing invalid parameters.
    pub fn new(params: NoiseParams) -> Result<Self> {
        params.validate("water")?;
        let norm: f32 = (0..params.octaves).map(|o| params.persistence.powi(o as i32)).sum();
        Ok(Self { params, noise: Perlin::new(params.seed), height_scale: params.amplitude / norm })
    }

    /// The parameters, as given.
    pub fn params(&self) -> &NoiseParams {
        &self.params
    }
}

impl ModelParams for NoiseParams {
    /// Everywhere: Perlin fBm is defined at every (x, z).
    fn defined_everywhere(&self) -> bool {
        true
    }

    fn validate(&self) -> Result<()> {
        NoiseParams::validate(self, "water")
    }

    fn build(&self) -> Result<Box<dyn WaveModel>> {
        Ok(Box::new(NoiseWaves::new(*self)?))
    }
}

impl PointWave for NoiseWaves {
    type Frame = NoiseFrame;

    fn frame(&self, t: f64) -> NoiseFrame {
        let p = &self.params;
        let s = f64::from(p.scale);
        NoiseFrame(Vec3::new(
            (-f64::from(p.drift.x) * t / s) as f32,
            (-f64::from(p.drift.y) * t / s) as f32,
            (f64::from(p.evolution) * t) as f32,
        ))
    }

    fn sample(&self, frame: &NoiseFrame, rest: Vec2) -> SurfacePoint {
        let p = &self.params;
        let q = Vec3::new(rest.x / p.scale, rest.y / p.scale, 0.0) + frame.0;
        let (n, g) = self.noise.fbm3_with_gradient(q, p.octaves, p.persistence, p.lacunarity);
        let slope = self.height_scale / p.scale;
        SurfacePoint {
            offset: Vec3::new(0.0, self.height_scale * n, 0.0),
            normal: Vec3::new(-slope * g.x, 1.0, -slope * g.y).normalize(),
        }
    }
}

impl WaveModel for NoiseWaves {
    /// The time derivative of the displacement ([`super::velocity_by_difference`]).
    fn surface_velocity(&self, x: f32, z: f32, t: f64) -> Vec3 {
        super::velocity_by_difference(self, x, z, t)
    }

    /// Nothing: perlin fBm has no list of waves to split at a cut-off: its octaves are shaded as sampled.
    fn slope_components(&self, _out: &mut Vec<(f32, f32)>) {}

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
    fn bounded_drifting_seeded_and_normals_match_finite_differences() {
        let m = NoiseWaves::new(NoiseParams::default()).unwrap();
        let eps = 2e-3;
        for i in 0..60 {
            let (x, z, t) = (i as f32 * 1.7 - 40.0, i as f32 * 0.77 - 9.0, i as f64 * 0.3);
            let h = m.height_at(x, z, t);
            assert!(h.abs() <= 0.3 * 1.1, "{h}");
            let n = m.sample(&m.frame(t), Vec2::new(x, z)).normal;
            let dx = (m.height_at(x + eps, z, t) - m.height_at(x - eps, z, t)) / (2.0 * eps);
            let dz = (m.height_at(x, z + eps, t) - m.height_at(x, z - eps, t)) / (2.0 * eps);
            assert!((n - Vec3::new(-dx, 1.0, -dz).normalize()).length() < 5e-3, "{n} vs fd");
        }
        // With no evolution the pattern only drifts: the height at x + v t later equals now.
        let p = NoiseParams { evolution: 0.0, drift: Vec2::new(2.0, 0.0), ..Default::default() };
        let m = NoiseWaves::new(p).unwrap();
        assert!((m.height_at(3.0 + 2.0 * 1.5, 4.0, 1.5) - m.height_at(3.0, 4.0, 0.0)).abs() < 1e-5);
        let other = NoiseWaves::new(NoiseParams { seed: 2, ..p }).unwrap();
        assert_ne!(other.height_at(3.3, 4.1, 0.0), m.height_at(3.3, 4.1, 0.0));
        let e = NoiseWaves::new(NoiseParams { octaves: 0, ..p }).unwrap_err();
        assert_eq!(e.to_string(), "water.octaves = 0 is outside [1, 12]");
    }
}
