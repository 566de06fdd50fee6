//! Gerstner waves in Tessendorf's form with a dispersion relation (paper 003 §1.2.1, eqs. 6-11;
//! Tessendorf, *Simulating Ocean Water*, 2001, §3.1-3.3).
//!
//! Each wave i has a wave vector k_i (direction D_i, length k_i = 2 pi / wavelength), amplitude A_i
//! and phase phi_i; its angular frequency comes from the chosen [`Dispersion`] rather than from a
//! speed the user types:
//!
//! ```text
//! x = x0 - sum D_i A_i sin(k_i . x0 - w_i t + phi_i)      y = sum A_i cos(k_i . x0 - w_i t + phi_i)
//! w_i = w(k_i)                    (deep, finite depth or capillary-gravity dispersion)
//! w_i = max(1, round(T w_i / 2 pi)) 2 pi / T               (optional: loops after T)
//! ```
//!
//! Paper 003 eq. 10 rounds down (`floor`), which freezes every wave longer than the loop; swell
//! rounds to the nearest non-zero multiple (`spectrum/loop_period.rs`).
//!
//! Each point moves on a circle of radius A_i per wave (exactly so for one deep-water wave). `k A`
//! sets the shape: 0 is flat, 1 a cusp, above 1 the crest loops over itself (paper 003, figure 3).
//! Because the horizontal motions of several waves add, swell refuses `sum k_i A_i > 1`, the bound
//! under which no combination of phases can fold the surface (and under which the height query's
//! inversion converges).

use std::f32::consts::TAU;

use glam::{Vec2, Vec3};
use serde::{Deserialize, Serialize};

use super::slope_spectrum::push_wave_slopes;
use super::trochoidal_sum::{Phases, Trochoid, TrochoidalSum, MAX_TROCHOIDAL_WAVES};
use super::wave_model::{height_by_inversion, PointWave, SurfacePoint, WaveModel};
use super::ModelParams;
use crate::error::{check_direction, check_finite_vec, check_non_negative, check_positive, Error, Result};
use crate::math::GridSpec;
use crate::spectrum::{loop_time, quantize_to_period, Dispersion};

/// Most waves one [`GerstnerTessendorf`] sums.
pub const MAX_TESSENDORF_WAVES: usize = MAX_TROCHOIDAL_WAVES;

/// One wave of Tessendorf's form.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TessendorfWave {
    /// Orbit radius and crest height A, in metres; >= 0 (with k A <= 1).
    pub amplitude: f32,
    /// Crest-to-crest distance, in metres; > 0. Sets k = 2 pi / wavelength.
    pub wavelength: f32,
    /// Direction of travel as (x, z); non-zero, normalised on use.
    pub direction: Vec2,
    /// Phase phi in radians, any finite value. Default 0.
    #[serde(default)]
    pub phase: f32,
}

/// Parameters of [`GerstnerTessendorf`]: the waves, the dispersion relation and the loop period.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TessendorfParams {
    /// The waves, 0 to [`MAX_TESSENDORF_WAVES`] of them; `sum k A <= 1`.
    #[serde(default)]
    pub waves: Vec<TessendorfWave>,
    /// How frequency follows from wavelength. Default deep water.
    #[serde(default)]
    pub dispersion: Dispersion,
    /// If set, the period T in seconds (> 0) after which the surface repeats exactly.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub loop_period: Option<f32>,
}

impl TessendorfWave {
    /// Checks this one wave, naming keys under `key` (e.g. `water.waves[2]`); the whole list's
    /// `sum k A <= 1` is checked by [`TessendorfParams::validate`].
    pub fn validate(&self, key: &str) -> Result<()> {
        check_non_negative(&format!("{key}.amplitude"), self.amplitude)?;
        check_positive(&format!("{key}.wavelength"), self.wavelength)?;
        check_finite_vec(&format!("{key}.phase"), &[self.phase])?;
        check_direction(&format!("{key}.direction"), self.direction)?;
        let k = TAU / self.wavelength;
        if k * self.amplitude > 1.0 {
            return Err(Error::out_of_range(
                format!("{key}.amplitude"),
                self.amplitude,
                format!("[0, {}] (k A <= 1 with k = 2 pi / {} m; above 1 the crest loops)", 1.0 / k, self.wavelength),
            ));
        }
        Ok(())
    }
}

impl TessendorfParams {
    /// Checks every value, naming keys under `key` (normally `water`).
    pub fn validate(&self, key: &str) -> Result<()> {
        if self.waves.len() > MAX_TESSENDORF_WAVES {
            return Err(Error::out_of_range(
                format!("{key}.waves"),
                format!("{} waves", self.waves.len()),
                format!("[0, {MAX_TESSENDORF_WAVES}] waves"),
            ));
        }
        self.dispersion.validate(&format!("{key}.dispersion"))?;
        if let Some(t) = self.loop_period {
            check_positive(&format!("{key}.loop_period"), t)?;
        }
        let mut sum_ka = 0.0;
        for (i, w) in self.waves.iter().enumerate() {
            w.validate(&format!("{key}.waves[{i}]"))?;
            sum_ka += TAU / w.wavelength * w.amplitude;
        }
        if sum_ka > 1.0 {
            return Err(Error::out_of_range(
                format!("{key}.waves"),
                format!("sum of k A = {sum_ka}"),
                "[0, 1] (above 1 the waves together can fold the surface into loops)",
            ));
        }
        Ok(())
    }
}

/// A sum of Gerstner waves in Tessendorf's form; see the [module documentation](self).
#[derive(Clone, Debug)]
pub struct GerstnerTessendorf {
    params: TessendorfParams,
    omegas: Vec<f32>,
    sum: TrochoidalSum,
}

impl GerstnerTessendorf {
    /// Builds the model, refusing invalid parameters.
    pub fn new(params: TessendorfParams) -> Result<Self> {
        params.validate("water")?;
        let mut omegas = Vec::with_capacity(params.waves.len());
        let waves = params
            .waves
            .iter()
            .map(|w| {
                let k = TAU / w.wavelength;
                let mut omega = params.dispersion.omega(k);
                if let Some(t) = params.loop_period {
                    omega = quantize_to_period(omega, t);
                }
                omegas.push(omega);
                // Tessendorf's (x0 - D A sin theta', A cos theta') is GPU Gems' (x0 + D A cos theta,
                // A sin theta) with theta = theta' + pi/2.
                Trochoid {
                    k: w.direction.normalize() * k,
                    omega: f64::from(omega),
                    phase: f64::from(w.phase) + std::f64::consts::FRAC_PI_2,
                    amplitude: w.amplitude,
                    horizontal: w.amplitude,
                }
            })
            .collect();
        Ok(Self { params, omegas, sum: TrochoidalSum::new(waves) })
    }

    /// The parameters, as given.
    pub fn params(&self) -> &TessendorfParams {
        &self.params
    }

    /// Angular frequency (rad/s) of each wave, after dispersion and loop quantisation.
    pub fn omegas(&self) -> &[f32] {
        &self.omegas
    }
}

impl ModelParams for TessendorfParams {
    /// Everywhere: a sum of trochoids, a closed form of (x, z).
    fn defined_everywhere(&self) -> bool {
        true
    }

    fn validate(&self) -> Result<()> {
        TessendorfParams::validate(self, "water")
    }

    fn build(&self) -> Result<Box<dyn WaveModel>> {
        Ok(Box::new(GerstnerTessendorf::new(self.clone())?))
    }

    fn loop_period(&self) -> Option<f64> {
        self.loop_period.map(f64::from)
    }

    fn loop_warning(&self) -> Option<String> {
        let period = f64::from(self.loop_period?);
        let omegas: Vec<f64> =
            self.waves.iter().map(|w| f64::from(self.dispersion.omega(std::f32::consts::TAU / w.wavelength))).collect();
        let longest = omegas.iter().copied().filter(|w| *w > 0.0).fold(f64::INFINITY, f64::min);
        if !longest.is_finite() {
            return None;
        }
        crate::spectrum::LoopFit::new(period, std::f64::consts::TAU / longest, omegas).warning("water.loop_period")
    }
}

impl PointWave for GerstnerTessendorf {
    type Frame = Phases;

    fn frame(&self, t: f64) -> Self::Frame {
        // A looping sea's phases come from the time within the loop, so that the loop closes bit
        // for bit (the quantised f32 frequencies alone would drift over many periods).
        self.sum.phases(self.params.loop_period.map_or(t, |p| loop_time(t, f64::from(p))))
    }

    fn sample(&self, frame: &Self::Frame, rest: Vec2) -> SurfacePoint {
        self.sum.sample(frame, rest)
    }
}

impl WaveModel for GerstnerTessendorf {
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

    /// Inverts the horizontal motion ([`height_by_inversion`]): within 1e-4 m of the evaluated
    /// surface for `sum k A` up to 0.9; at 1 the crest is a cusp and the error grows there.
    fn height_at(&self, x: f32, z: f32, t: f64) -> f32 {
        height_by_inversion(self, x, z, t)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::GRAVITY;

    fn wave(a: f32, l: f32, dir: Vec2, phase: f32) -> TessendorfWave {
        TessendorfWave { amplitude: a, wavelength: l, direction: dir, phase }
    }

    fn model(waves: Vec<TessendorfWave>, dispersion: Dispersion, loop_period: Option<f32>) -> GerstnerTessendorf {
        GerstnerTessendorf::new(TessendorfParams { waves, dispersion, loop_period }).unwrap()
    }

    #[test]
    fn one_deep_water_wave_moves_points_on_circles_of_radius_a() {
        let (a, l) = (0.6, 25.0);
        let m = model(vec![wave(a, l, Vec2::new(0.6, 0.8), 0.3)], Dispersion::Deep, None);
        let omega = (GRAVITY * TAU / l).sqrt();
        assert!((m.omegas()[0] - omega).abs() < 1e-5);
        for rest in [Vec2::new(0.0, 0.0), Vec2::new(13.0, -4.0)] {
            for step in 0..40 {
                let s = m.sample(&m.frame(step as f64 * 0.21), rest);
                let radius = (s.offset.x.powi(2) + s.offset.y.powi(2) + s.offset.z.powi(2)).sqrt();
                assert!((radius - a).abs() < 1e-5, "radius {radius}");
                // The orbit lies in the vertical plane containing the direction of travel.
                let h = Vec2::new(s.offset.x, s.offset.z);
                assert!(h.perp_dot(Vec2::new(0.6, 0.8)).abs() < 1e-5);
            }
        }
        // The crest passes x = 0 at t = phase / w and reaches distance c t later at time t.
        let m0 = model(vec![wave(a, l, Vec2::X, 0.0)], Dispersion::Deep, None);
        let c = omega / (TAU / l);
        let t = 1.7f64;
        let crest = m0.sample(&m0.frame(t), Vec2::new(c * t as f32, 0.0));
        assert!((crest.offset.y - a).abs() < 1e-4);
    }

    #[test]
    fn a_looping_period_repeats_the_surface_exactly() {
        let waves = vec![
            wave(0.3, 20.0, Vec2::X, 0.0),
            wave(0.2, 7.3, Vec2::new(1.0, 0.5), 1.0),
            wave(0.05, 2.1, Vec2::Y, 2.0),
        ];
        let period = 12.5;
        let m = model(waves, Dispersion::FiniteDepth { depth: 4.0 }, Some(period));
        let grid = GridSpec::centered(Vec2::splat(30.0), 16, 16).unwrap();
        let eval = |t: f64| {
            let mut p = vec![Vec3::ZERO; grid.vertex_count()];
            let mut n = p.clone();
            m.evaluate(&grid, t, &mut p, &mut n);
            (p, n)
        };
        let (p0, n0) = eval(3.0);
        let (p1, n1) = eval(3.0 + f64::from(period));
        let (p2, _) = eval(3.0 + 0.5 * f64::from(period));
        let max_diff = |a: &[Vec3], b: &[Vec3]| a.iter().zip(b).map(|(x, y)| (*x - *y).length()).fold(0.0f32, f32::max);
        assert!(max_diff(&p0, &p1) < 1e-4 && max_diff(&n0, &n1) < 1e-4);
        // ... and not before: half a period later the surface differs.
        assert!(max_diff(&p0, &p2) > 1e-2);
    }

    #[test]
    fn normals_match_finite_differences_and_height_at_matches_the_grid() {
        let waves = vec![
            wave(0.5, 15.0, Vec2::X, 0.0),
            wave(0.3, 9.0, Vec2::new(-0.2, 1.0), 0.5),
            wave(0.1, 4.0, Vec2::new(0.7, -0.7), 1.0),
        ];
        let m = model(waves, Dispersion::Capillary { depth: 50.0 }, None);
        let f = m.frame(2.3);
        let eps = 1e-2;
        for i in 0..20 {
            let r = Vec2::new(i as f32 * 1.37 - 9.0, (i * i) as f32 * 0.11 - 5.0);
            let p = |d: Vec2| Vec3::new(r.x + d.x, 0.0, r.y + d.y) + m.sample(&f, r + d).offset;
            let dx = (p(Vec2::new(eps, 0.0)) - p(Vec2::new(-eps, 0.0))) / (2.0 * eps);
            let dz = (p(Vec2::new(0.0, eps)) - p(Vec2::new(0.0, -eps))) / (2.0 * eps);
            let fd = dz.cross(dx).normalize();
            assert!((m.sample(&f, r).normal - fd).length() < 2e-3);
        }
        let grid = GridSpec::centered(Vec2::splat(40.0), 32, 32).unwrap();
        let mut p = vec![Vec3::ZERO; grid.vertex_count()];
        let mut n = p.clone();
        m.evaluate(&grid, 2.3, &mut p, &mut n);
        for v in p.iter().step_by(5) {
            assert!((m.height_at(v.x, v.z, 2.3) - v.y).abs() < 1e-4);
        }
    }

    #[test]
    fn zero_amplitude_is_flat_and_loops_are_refused() {
        let m = model(vec![wave(0.0, 5.0, Vec2::X, 1.0)], Dispersion::Deep, None);
        let grid = GridSpec::centered(Vec2::splat(10.0), 4, 4).unwrap();
        let mut p = vec![Vec3::ZERO; grid.vertex_count()];
        let mut n = p.clone();
        m.evaluate(&grid, 1.0, &mut p, &mut n);
        assert!(p.iter().all(|v| v.y == 0.0) && n.iter().all(|v| *v == Vec3::Y));
        let e = GerstnerTessendorf::new(TessendorfParams {
            waves: vec![wave(2.0, 10.0, Vec2::X, 0.0)],
            ..Default::default()
        })
        .unwrap_err()
        .to_string();
        assert!(e.starts_with("water.waves[0].amplitude = 2 is outside [0, 1.59"), "{e}");
        let e = GerstnerTessendorf::new(TessendorfParams {
            waves: vec![wave(1.0, 10.0, Vec2::X, 0.0), wave(1.0, 10.0, Vec2::Y, 0.0)],
            ..Default::default()
        })
        .unwrap_err()
        .to_string();
        assert!(e.starts_with("water.waves = sum of k A = 1.25") && e.contains("[0, 1]"), "{e}");
        let e = GerstnerTessendorf::new(TessendorfParams { loop_period: Some(0.0), ..Default::default() })
            .unwrap_err()
            .to_string();
        assert_eq!(e, "water.loop_period = 0 is outside (0, inf)");
    }

    #[test]
    fn identical_on_one_and_two_threads() {
        let m = model(vec![wave(0.3, 20.0, Vec2::X, 0.0), wave(0.1, 3.0, Vec2::Y, 0.0)], Dispersion::Deep, None);
        let grid = GridSpec::centered(Vec2::splat(40.0), 100, 70).unwrap();
        let run = |threads| {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            let mut p = vec![Vec3::ZERO; grid.vertex_count()];
            let mut n = p.clone();
            pool.install(|| m.evaluate(&grid, 1.25, &mut p, &mut n));
            (p, n)
        };
        assert_eq!(run(1), run(2));
    }
}
