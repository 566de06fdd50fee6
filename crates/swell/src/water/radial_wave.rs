//! A circular wave spreading from a centre: paper 002's pool surface,
//!
//! ```text
//! y = a sin(k r - w t),      r = |(x, z) - c|
//! ```
//!
//! Paper 002 draws `y = 2 sin(20 sqrt((x - 3)^2 + (z + 1)^2) - 4 t) / 200` over the pool [-1, 1]^2:
//! a = 0.01 m, k = 20 rad/m (wavelength 0.314 m), w = 4 rad/s (crests move outwards at 0.2 m/s),
//! centre (3, -1) outside the pool, so the crests cross the pool as gently curved arcs. Those are the
//! defaults. No horizontal motion, so the height query is exact. At r = 0 the surface has a cone
//! point (no tangent plane); the normal there is +Y.

use glam::{Vec2, Vec3};
use serde::{Deserialize, Serialize};

use super::wave_model::{evaluate_pointwise, PointWave, SurfacePoint, WaveModel};
use super::ModelParams;
use crate::error::{check_finite_vec, check_non_negative, check_positive, Result};
use crate::math::{fast_sin_cos, GridSpec};

/// Parameters of [`RadialWave`]: `model = "radial"`. Defaults are paper 002's constants.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RadialWaveParams {
    /// Centre (x, z) of the circles, metres; finite. Default (3, -1). Written `wave_center` in scene
    /// files (the patch has its own `center`).
    #[serde(rename = "wave_center")]
    pub center: Vec2,
    /// Amplitude a, metres; >= 0. Default 0.01.
    pub amplitude: f32,
    /// Wavenumber k = 2 pi / wavelength, rad/m; > 0. Default 20.
    pub wavenumber: f32,
    /// Angular frequency w, rad/s; >= 0 (crests move outwards at w / k). Default 4.
    pub angular_frequency: f32,
}

impl Default for RadialWaveParams {
    fn default() -> Self {
        Self { center: Vec2::new(3.0, -1.0), amplitude: 0.01, wavenumber: 20.0, angular_frequency: 4.0 }
    }
}

impl RadialWaveParams {
    /// Checks every value, naming keys under `key` (normally `water`).
    pub fn validate(&self, key: &str) -> Result<()> {
        check_finite_vec(&format!("{key}.wave_center"), &self.center.to_array())?;
        check_non_negative(&format!("{key}.amplitude"), self.amplitude)?;
        check_positive(&format!("{key}.wavenumber"), self.wavenumber)?;
        check_non_negative(&format!("{key}.angular_frequency"), self.angular_frequency)
    }
}

/// The radial wave; see the [module documentation](self).
#[derive(Clone, Debug)]
pub struct RadialWave {
    params: RadialWaveParams,
}

impl RadialWave {
    /// Builds the model, refusing invalid parameters.
    pub fn new(params: RadialWaveParams) -> Result<Self> {
        params.validate("water")?;
        Ok(Self { params })
    }

    /// The parameters, as given.
    pub fn params(&self) -> &RadialWaveParams {
        &self.params
    }
}

impl ModelParams for RadialWaveParams {
    /// Finite: paper 002's pool is the square [-1, 1]^2 around its centre.
    fn defined_everywhere(&self) -> bool {
        false
    }

    fn validate(&self) -> Result<()> {
        RadialWaveParams::validate(self, "water")
    }

    fn build(&self) -> Result<Box<dyn WaveModel>> {
        Ok(Box::new(RadialWave::new(*self)?))
    }
}

impl PointWave for RadialWave {
    /// `w t mod 2 pi`.
    type Frame = f32;

    fn frame(&self, t: f64) -> f32 {
        (f64::from(self.params.angular_frequency) * t).rem_euclid(std::f64::consts::TAU) as f32
    }

    fn sample(&self, frame: &f32, rest: Vec2) -> SurfacePoint {
        let p = &self.params;
        let d = rest - p.center;
        let r = d.length();
        let (s, c) = fast_sin_cos(p.wavenumber * r - frame);
        // grad y = a k cos(k r - w t) d / r.
        let grad = if r > 0.0 { d * (p.amplitude * p.wavenumber * c / r) } else { Vec2::ZERO };
        SurfacePoint {
            offset: Vec3::new(0.0, p.amplitude * s, 0.0),
            normal: Vec3::new(-grad.x, 1.0, -grad.y).normalize(),
        }
    }
}

impl WaveModel for RadialWave {
    /// The time derivative of the displacement ([`super::velocity_by_difference`]).
    fn surface_velocity(&self, x: f32, z: f32, t: f64) -> Vec3 {
        super::velocity_by_difference(self, x, z, t)
    }

    /// Nothing: a finite pool seen up close: its one wave is resolved wherever it is drawn.
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
    fn paper_002_surface_and_its_normals() {
        let m = RadialWave::new(RadialWaveParams::default()).unwrap();
        let eps = 1e-3;
        for i in 0..40 {
            let (x, z, t) = (i as f32 * 0.05 - 1.0, 1.0 - i as f32 * 0.045, i as f64 * 0.11);
            let paper = 2.0 * (20.0 * ((x - 3.0).powi(2) + (z + 1.0).powi(2)).sqrt() - 4.0 * t as f32).sin() / 200.0;
            assert!((m.height_at(x, z, t) - paper).abs() < 1e-6);
            let n = m.sample(&m.frame(t), Vec2::new(x, z)).normal;
            let dx = (m.height_at(x + eps, z, t) - m.height_at(x - eps, z, t)) / (2.0 * eps);
            let dz = (m.height_at(x, z + eps, t) - m.height_at(x, z - eps, t)) / (2.0 * eps);
            assert!((n - Vec3::new(-dx, 1.0, -dz).normalize()).length() < 1e-3);
        }
        let e = RadialWave::new(RadialWaveParams { wavenumber: 0.0, ..Default::default() }).unwrap_err();
        assert_eq!(e.to_string(), "water.wavenumber = 0 is outside (0, inf)");
    }
}
