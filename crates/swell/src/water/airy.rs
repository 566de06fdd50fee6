//! Airy (linear) waves: a sum of sines whose frequencies follow a dispersion relation (paper 000
//! §1.2.2, eqs. 2-3; Airy wave theory, e.g. Dean and Dalrymple, *Water Wave Mechanics*, ch. 3):
//!
//! ```text
//! y = sum A_i sin(k_i . x - w(k_i) t + phi_i),     w(k) from the chosen Dispersion
//! ```
//!
//! Unlike [`SumOfSines`](super::SumOfSines), the user gives no speed: each wave travels at the phase
//! speed its wavelength has on water of the chosen depth. No horizontal motion, so the height query
//! is exact. Evaluated with the same vectorised kernel as the Gerstner models (with zero orbit
//! radius).

use std::f32::consts::TAU;

use glam::{Vec2, Vec3};
use serde::{Deserialize, Serialize};

use super::slope_spectrum::push_wave_slopes;
use super::trochoidal_sum::{Phases, Trochoid, TrochoidalSum, MAX_TROCHOIDAL_WAVES};
use super::wave_model::{PointWave, SurfacePoint, WaveModel};
use super::ModelParams;
use crate::error::{check_direction, check_finite_vec, check_non_negative, check_positive, Error, Result};
use crate::math::GridSpec;
use crate::spectrum::Dispersion;

/// Most waves one [`Airy`] sums.
pub const MAX_AIRY_WAVES: usize = MAX_TROCHOIDAL_WAVES;

/// One linear wave.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AiryWave {
    /// Crest height above rest, in metres; >= 0.
    pub amplitude: f32,
    /// Crest-to-crest distance, in metres; > 0.
    pub wavelength: f32,
    /// Direction of travel as (x, z); non-zero, normalised on use.
    pub direction: Vec2,
    /// Phase phi in radians, finite. Default 0.
    #[serde(default)]
    pub phase: f32,
}

/// Parameters of [`Airy`]: `model = "airy"`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AiryParams {
    /// The waves, 0 to [`MAX_AIRY_WAVES`].
    #[serde(default)]
    pub waves: Vec<AiryWave>,
    /// Dispersion relation. Default deep water.
    #[serde(default)]
    pub dispersion: Dispersion,
}

impl AiryWave {
    /// Checks this one wave, naming keys under `key` (e.g. `water.waves[2]`).
    pub fn validate(&self, key: &str) -> Result<()> {
        check_non_negative(&format!("{key}.amplitude"), self.amplitude)?;
        check_positive(&format!("{key}.wavelength"), self.wavelength)?;
        check_finite_vec(&format!("{key}.phase"), &[self.phase])?;
        check_direction(&format!("{key}.direction"), self.direction)
    }
}

impl AiryParams {
    /// Checks every value, naming keys under `key` (normally `water`).
    pub fn validate(&self, key: &str) -> Result<()> {
        if self.waves.len() > MAX_AIRY_WAVES {
            return Err(Error::out_of_range(
                format!("{key}.waves"),
                format!("{} waves", self.waves.len()),
                format!("[0, {MAX_AIRY_WAVES}] waves"),
            ));
        }
        self.dispersion.validate(&format!("{key}.dispersion"))?;
        for (i, w) in self.waves.iter().enumerate() {
            w.validate(&format!("{key}.waves[{i}]"))?;
        }
        Ok(())
    }
}

/// A sum of linear waves with dispersion; see the [module documentation](self).
#[derive(Clone, Debug)]
pub struct Airy {
    params: AiryParams,
    sum: TrochoidalSum,
}

impl Airy {
    /// Builds the model, refusing invalid parameters.
    pub fn new(params: AiryParams) -> Result<Self> {
        params.validate("water")?;
        let sum = TrochoidalSum::new(
            params
                .waves
                .iter()
                .map(|w| {
                    let k = TAU / w.wavelength;
                    Trochoid {
                        k: w.direction.normalize() * k,
                        omega: f64::from(params.dispersion.omega(k)),
                        phase: f64::from(w.phase),
                        amplitude: w.amplitude,
                        horizontal: 0.0,
                    }
                })
                .collect(),
        );
        Ok(Self { params, sum })
    }

    /// The parameters, as given.
    pub fn params(&self) -> &AiryParams {
        &self.params
    }
}

impl ModelParams for AiryParams {
    /// Everywhere: a sum of sines, a closed form of (x, z).
    fn defined_everywhere(&self) -> bool {
        true
    }

    fn validate(&self) -> Result<()> {
        AiryParams::validate(self, "water")
    }

    fn build(&self) -> Result<Box<dyn WaveModel>> {
        Ok(Box::new(Airy::new(self.clone())?))
    }
}

impl PointWave for Airy {
    type Frame = Phases;

    fn frame(&self, t: f64) -> Self::Frame {
        self.sum.phases(t)
    }

    fn sample(&self, frame: &Self::Frame, rest: Vec2) -> SurfacePoint {
        self.sum.sample(frame, rest)
    }
}

impl WaveModel for Airy {
    /// Linear orbital velocity of each wave ([`super::trochoidal_sum`]).
    fn surface_velocity(&self, x: f32, z: f32, t: f64) -> Vec3 {
        self.sum.velocity(t, Vec2::new(x, z))
    }

    fn slope_components(&self, out: &mut Vec<(f32, f32)>) {
        push_wave_slopes(self.params.waves.iter().map(|w| (w.amplitude, w.wavelength)), out);
    }

    fn evaluate(&self, grid: &GridSpec, t: f64, positions: &mut [Vec3], normals: &mut [Vec3]) {
        self.sum.evaluate(grid, t, positions, normals);
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
    fn crests_travel_at_the_phase_speed_of_the_dispersion_relation() {
        let d = Dispersion::FiniteDepth { depth: 2.0 };
        let w = AiryWave { amplitude: 0.2, wavelength: 12.0, direction: Vec2::X, phase: 0.0 };
        let m = Airy::new(AiryParams { waves: vec![w], dispersion: d }).unwrap();
        let c = d.phase_speed(TAU / 12.0);
        // A crest (sin = 1) at x = L/4 at t = 0 is at L/4 + c t later.
        for t in [0.0f64, 1.3, 4.0] {
            let h = m.height_at(3.0 + c * t as f32, 5.0, t);
            assert!((h - 0.2).abs() < 1e-4, "t={t} h={h}");
        }
    }

    #[test]
    fn grid_normals_and_heights_agree_with_the_point_query_and_finite_differences() {
        let waves = vec![
            AiryWave { amplitude: 0.2, wavelength: 12.0, direction: Vec2::X, phase: 0.0 },
            AiryWave { amplitude: 0.05, wavelength: 3.0, direction: Vec2::new(0.3, 1.0), phase: 1.0 },
        ];
        let m = Airy::new(AiryParams { waves, dispersion: Dispersion::Deep }).unwrap();
        let grid = GridSpec::centered(Vec2::splat(20.0), 16, 16).unwrap();
        let mut p = vec![Vec3::ZERO; grid.vertex_count()];
        let mut n = p.clone();
        m.evaluate(&grid, 0.7, &mut p, &mut n);
        let eps = 1e-2;
        for (v, nv) in p.iter().zip(&n).step_by(3) {
            assert!((m.height_at(v.x, v.z, 0.7) - v.y).abs() < 1e-5);
            let dx = (m.height_at(v.x + eps, v.z, 0.7) - m.height_at(v.x - eps, v.z, 0.7)) / (2.0 * eps);
            let dz = (m.height_at(v.x, v.z + eps, 0.7) - m.height_at(v.x, v.z - eps, 0.7)) / (2.0 * eps);
            assert!((*nv - Vec3::new(-dx, 1.0, -dz).normalize()).length() < 1e-3);
        }
        let e = Airy::new(AiryParams {
            waves: vec![AiryWave { amplitude: 0.1, wavelength: -3.0, direction: Vec2::X, phase: 0.0 }],
            ..Default::default()
        })
        .unwrap_err();
        assert_eq!(e.to_string(), "water.waves[0].wavelength = -3 is outside (0, inf)");
    }
}
