//! Gerstner (trochoidal) waves in the GPU Gems form used by paper 000.
//!
//! Each wave i has amplitude A, wavelength L, speed S, unit direction D (in the x-z plane) and the
//! artist steepness Q in [0, 1] shared by all. With `w = 2 pi / L`, `phi = S w` and
//! `theta = w D.(x0, z0) - phi t`:
//!
//! ```text
//! x = x0 + sum Q_i A_i D_x cos(theta_i)      y = sum A_i sin(theta_i)      z = z0 + sum Q_i A_i D_z cos(theta_i)
//! Q_i = Q / (w_i A_i N)                      (N = number of waves)
//! ```
//!
//! Two departures from the paper, both for physical correctness:
//! - the extracted text of paper 000 writes `w = 2 / L`; the factor pi was lost (GPU Gems ch. 1 eq. 1
//!   has `2 pi / L`), so swell uses `2 pi / L`;
//! - GPU Gems writes the phase as `w D.x + phi t`, which moves crests *against* D. swell uses
//!   `- phi t` so that `direction` is the direction of travel.
//!
//! The artist mapping makes `sum Q_i w_i A_i = Q <= 1`, the condition for crests that sharpen without
//! looping; steepness above 1 is refused.

use std::f32::consts::TAU;

use glam::{Vec2, Vec3};
use serde::{Deserialize, Serialize};

use super::slope_spectrum::push_wave_slopes;
use super::trochoidal_sum::{Phases, Trochoid, TrochoidalSum, MAX_TROCHOIDAL_WAVES};
use super::wave_model::{height_by_inversion, PointWave, SurfacePoint, WaveModel};
use super::ModelParams;
use crate::error::{check_direction, check_range, Error, Result};
use crate::math::GridSpec;

/// Most waves one [`Gerstner`] model sums (paper 000 uses up to 12; 64 leaves room for rich seas
/// while keeping per-frame phases on the stack).
pub const MAX_GERSTNER_WAVES: usize = MAX_TROCHOIDAL_WAVES;

/// One Gerstner wave as the user describes it (paper 000 §2.2).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GerstnerWave {
    /// Crest height above rest, in metres; >= 0.
    pub amplitude: f32,
    /// Crest-to-crest distance, in metres; > 0.
    pub wavelength: f32,
    /// Phase speed of the crests, in m/s; >= 0. (Deep water: `sqrt(g L / 2 pi)`, 5.59 m/s for 20 m.)
    pub speed: f32,
    /// Direction of travel in the horizontal plane as (x, z); any non-zero length, normalised on use.
    pub direction: Vec2,
    /// Artist steepness Q in [0, 1]: 0 is a sine wave, 1 the sharpest crest without loops.
    pub steepness: f32,
}

impl GerstnerWave {
    /// Checks every field, naming it under `key` (e.g. `water.waves[2]`).
    pub fn validate(&self, key: &str) -> Result<()> {
        // Upper bounds from `limits`: far past any real wave, low enough that sums of 64 waves and
        // the phase `k x - w t` stay finite in f32.
        use crate::limits::{MAX_WAVE_LENGTH_M, MAX_WAVE_SPEED};
        check_range(&format!("{key}.amplitude"), self.amplitude, 0.0, MAX_WAVE_LENGTH_M)?;
        check_range(&format!("{key}.wavelength"), self.wavelength, 1e-6, MAX_WAVE_LENGTH_M)?;
        check_range(&format!("{key}.speed"), self.speed, 0.0, MAX_WAVE_SPEED)?;
        check_range(&format!("{key}.steepness"), self.steepness, 0.0, 1.0)?;
        check_direction(&format!("{key}.direction"), self.direction)?;
        Ok(())
    }

    /// Angular wavenumber `w = 2 pi / L` in rad/m.
    pub fn wavenumber(&self) -> f32 {
        TAU / self.wavelength
    }
}

/// A sum of Gerstner waves (paper 000); evaluates analytically with exact normals.
///
/// The wave list can be edited one wave at a time ([`Gerstner::add_wave`], [`Gerstner::set_wave`],
/// [`Gerstner::remove_wave`], [`Gerstner::clear`]), as paper 000's GUI does; every edit re-validates
/// and re-derives the per-wave constants (the artist steepness mapping depends on the wave count).
#[derive(Clone, Debug)]
pub struct Gerstner {
    waves: Vec<GerstnerWave>,
    sum: TrochoidalSum,
}

impl Gerstner {
    /// Builds the model from its waves, refusing invalid ones (0 to [`MAX_GERSTNER_WAVES`] waves).
    pub fn new(waves: Vec<GerstnerWave>) -> Result<Self> {
        Self::check(&waves)?;
        let sum = Self::prepare(&waves);
        Ok(Self { waves, sum })
    }

    /// Checks a wave list: at most [`MAX_GERSTNER_WAVES`], each valid (keys `water.waves[i]`).
    pub(crate) fn check(waves: &[GerstnerWave]) -> Result<()> {
        if waves.len() > MAX_GERSTNER_WAVES {
            return Err(Error::out_of_range(
                "water.waves",
                format!("{} waves", waves.len()),
                format!("[0, {MAX_GERSTNER_WAVES}] waves"),
            ));
        }
        for (i, w) in waves.iter().enumerate() {
            w.validate(&format!("water.waves[{i}]"))?;
        }
        Ok(())
    }

    fn prepare(waves: &[GerstnerWave]) -> TrochoidalSum {
        let n = waves.len() as f32;
        TrochoidalSum::new(
            waves
                .iter()
                .map(|w| {
                    let k = w.wavenumber();
                    // Q_i A_i = Q / (w_i N): the A_i cancels, so write it without dividing by A_i. A
                    // wave of zero amplitude contributes nothing, horizontally included.
                    let horizontal = if w.amplitude > 0.0 { w.steepness / (k * n) } else { 0.0 };
                    Trochoid {
                        k: w.direction.normalize() * k,
                        omega: f64::from(w.speed) * f64::from(k),
                        phase: 0.0,
                        amplitude: w.amplitude,
                        horizontal,
                    }
                })
                .collect(),
        )
    }

    /// Replaces the whole list, validating it first (the model is unchanged on error).
    pub fn set_waves(&mut self, waves: Vec<GerstnerWave>) -> Result<()> {
        *self = Self::new(waves)?;
        Ok(())
    }

    /// Appends a wave and returns its index; refused (model unchanged) if the wave is invalid or the
    /// list already holds [`MAX_GERSTNER_WAVES`].
    pub fn add_wave(&mut self, wave: GerstnerWave) -> Result<usize> {
        let mut waves = self.waves.clone();
        waves.push(wave);
        self.set_waves(waves)?;
        Ok(self.waves.len() - 1)
    }

    /// Replaces wave `index`; refused (model unchanged) if the index or the wave is invalid.
    pub fn set_wave(&mut self, index: usize, wave: GerstnerWave) -> Result<()> {
        self.check_index(index)?;
        let mut waves = self.waves.clone();
        waves[index] = wave;
        self.set_waves(waves)
    }

    /// Removes and returns wave `index` (later waves move down by one).
    pub fn remove_wave(&mut self, index: usize) -> Result<GerstnerWave> {
        self.check_index(index)?;
        let mut waves = self.waves.clone();
        let removed = waves.remove(index);
        self.set_waves(waves)?;
        Ok(removed)
    }

    /// Removes every wave: the surface becomes the plane at rest.
    pub fn clear(&mut self) {
        self.waves.clear();
        self.sum = Self::prepare(&self.waves);
    }

    fn check_index(&self, index: usize) -> Result<()> {
        if index < self.waves.len() {
            Ok(())
        } else {
            let range = if self.waves.is_empty() {
                "none (the list is empty)".to_string()
            } else {
                format!("[0, {}]", self.waves.len() - 1)
            };
            Err(Error::out_of_range("water.waves index", index, range))
        }
    }

    /// The waves, as given.
    pub fn waves(&self) -> &[GerstnerWave] {
        &self.waves
    }
}

/// Gerstner waves as a scene gives them (paper 000): `model = "gerstner"` and a `[[water.waves]]`
/// list.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GerstnerSpec {
    /// The waves, 0 to [`MAX_GERSTNER_WAVES`] of them.
    #[serde(default)]
    pub waves: Vec<GerstnerWave>,
}

impl ModelParams for GerstnerSpec {
    /// Everywhere: a sum of trochoids, a closed form of (x, z).
    fn defined_everywhere(&self) -> bool {
        true
    }

    fn validate(&self) -> Result<()> {
        Gerstner::check(&self.waves)
    }

    fn build(&self) -> Result<Box<dyn WaveModel>> {
        Ok(Box::new(Gerstner::new(self.waves.clone())?))
    }
}

impl PointWave for Gerstner {
    type Frame = Phases;

    fn frame(&self, t: f64) -> Self::Frame {
        self.sum.phases(t)
    }

    fn sample(&self, frame: &Self::Frame, rest: Vec2) -> SurfacePoint {
        self.sum.sample(frame, rest)
    }
}

impl WaveModel for Gerstner {
    /// Linear orbital velocity of each wave ([`super::trochoidal_sum`]).
    fn surface_velocity(&self, x: f32, z: f32, t: f64) -> Vec3 {
        self.sum.velocity(t, Vec2::new(x, z))
    }

    fn slope_components(&self, out: &mut Vec<(f32, f32)>) {
        push_wave_slopes(self.waves.iter().map(|w| (w.amplitude, w.wavelength)), out);
    }

    fn evaluate(&self, grid: &GridSpec, t: f64, positions: &mut [Vec3], normals: &mut [Vec3]) {
        self.sum.evaluate(grid, t, positions, normals);
    }

    /// Inverts the horizontal motion (see [`height_by_inversion`]): within 1e-4 m of the evaluated
    /// surface for steepness up to 0.9; near Q = 1 the crest is a cusp and the error grows there.
    fn height_at(&self, x: f32, z: f32, t: f64) -> f32 {
        height_by_inversion(self, x, z, t)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn wave(a: f32, l: f32, q: f32, dir: Vec2) -> GerstnerWave {
        GerstnerWave { amplitude: a, wavelength: l, speed: 5.0, direction: dir, steepness: q }
    }

    #[test]
    fn a_single_wave_moves_points_on_an_ellipse_of_radii_qa_and_a() {
        let (a, l, q) = (0.5, 20.0, 0.8);
        let g = Gerstner::new(vec![wave(a, l, q, Vec2::new(1.0, 1.0))]).unwrap();
        let k = TAU / l;
        let qa = q / k; // Q_i A_i with N = 1
        let rest = Vec2::new(3.0, -7.0);
        let dir = Vec2::new(1.0, 1.0).normalize();
        for step in 0..50 {
            let s = g.sample(&g.frame(step as f64 * 0.13), rest);
            let h = Vec2::new(s.offset.x, s.offset.z);
            // Horizontal motion is along D only.
            assert!(h.perp_dot(dir).abs() < 1e-5);
            let e = (h.dot(dir) / qa).powi(2) + (s.offset.y / a).powi(2);
            assert!((e - 1.0).abs() < 1e-4, "not on the orbit: {e}");
        }
    }

    #[test]
    fn steepness_ka_gives_a_circle_of_radius_a() {
        let (a, l) = (0.5, 20.0);
        let q = TAU / l * a; // Q_i = 1: horizontal radius = A
        let g = Gerstner::new(vec![wave(a, l, q, Vec2::X)]).unwrap();
        for step in 0..40 {
            let s = g.sample(&g.frame(step as f64 * 0.1), Vec2::new(1.0, 2.0));
            let r = (s.offset.x.powi(2) + s.offset.y.powi(2)).sqrt();
            assert!((r - a).abs() < 1e-5, "radius {r}");
        }
    }

    #[test]
    fn crests_travel_along_the_direction_at_the_given_speed() {
        let w = wave(1.0, 40.0, 0.0, Vec2::X);
        let g = Gerstner::new(vec![w]).unwrap();
        // At t = 0 a crest (sin = 1) sits at x = L/4. After dt it must sit at L/4 + S dt.
        let dt = 1.5;
        let x = 10.0 + w.speed * dt as f32;
        let s = g.sample(&g.frame(dt), Vec2::new(x, 0.0));
        assert!((s.offset.y - 1.0).abs() < 1e-5, "{}", s.offset.y);
    }

    #[test]
    fn normals_match_finite_differences_of_the_displaced_surface() {
        let waves = vec![
            wave(0.6, 23.0, 0.7, Vec2::new(1.0, 0.3)),
            wave(0.3, 11.0, 0.7, Vec2::new(-0.2, 1.0)),
            wave(0.2, 7.0, 0.7, Vec2::new(0.7, -0.7)),
        ];
        let g = Gerstner::new(waves).unwrap();
        let f = g.frame(3.7);
        let eps = 1e-2;
        for i in 0..20 {
            let r = Vec2::new(i as f32 * 1.37 - 9.0, (i * i) as f32 * 0.11 - 5.0);
            let p = |d: Vec2| {
                let s = g.sample(&f, r + d);
                Vec3::new(r.x + d.x, 0.0, r.y + d.y) + s.offset
            };
            let dx = (p(Vec2::new(eps, 0.0)) - p(Vec2::new(-eps, 0.0))) / (2.0 * eps);
            let dz = (p(Vec2::new(0.0, eps)) - p(Vec2::new(0.0, -eps))) / (2.0 * eps);
            let fd = dz.cross(dx).normalize();
            let n = g.sample(&f, r).normal;
            assert!((n - fd).length() < 1e-3, "analytic {n} vs finite difference {fd}");
        }
    }

    #[test]
    fn out_of_range_parameters_are_refused_with_the_key_and_range() {
        let mut w = wave(1.0, 10.0, 1.7, Vec2::X);
        let e = Gerstner::new(vec![wave(1.0, 10.0, 0.5, Vec2::X), w]).unwrap_err().to_string();
        assert_eq!(e, "water.waves[1].steepness = 1.7 is outside [0, 1]");
        w.steepness = 0.5;
        w.amplitude = -1.0;
        assert!(Gerstner::new(vec![w]).unwrap_err().to_string().contains("amplitude = -1"));
        w.amplitude = 1.0;
        w.wavelength = 0.0;
        assert!(Gerstner::new(vec![w]).unwrap_err().to_string().contains("wavelength = 0"));
        w.wavelength = 5.0;
        w.direction = Vec2::ZERO;
        assert!(Gerstner::new(vec![w]).unwrap_err().to_string().contains("direction"));
        w.direction = Vec2::X;
        w.speed = f32::NAN;
        assert!(Gerstner::new(vec![w]).is_err());
    }

    #[test]
    fn zero_amplitude_is_the_plane_at_rest() {
        let g = Gerstner::new(vec![wave(0.0, 10.0, 1.0, Vec2::X)]).unwrap();
        let grid = GridSpec::centered(Vec2::splat(10.0), 8, 8).unwrap();
        let mut p = vec![Vec3::ZERO; grid.vertex_count()];
        let mut n = p.clone();
        g.evaluate(&grid, 1.0, &mut p, &mut n);
        for (idx, (p, n)) in p.iter().zip(&n).enumerate() {
            let r = grid.rest_position(idx % 9, idx / 9);
            assert_eq!(*p, Vec3::new(r.x, 0.0, r.y));
            assert_eq!(*n, Vec3::Y);
        }
    }

    #[test]
    fn height_at_agrees_with_the_evaluated_grid() {
        let waves = vec![wave(0.8, 30.0, 0.8, Vec2::new(1.0, 0.4)), wave(0.3, 9.0, 0.8, Vec2::Y)];
        let g = Gerstner::new(waves).unwrap();
        let grid = GridSpec::centered(Vec2::splat(40.0), 32, 32).unwrap();
        let mut p = vec![Vec3::ZERO; grid.vertex_count()];
        let mut n = p.clone();
        g.evaluate(&grid, 2.5, &mut p, &mut n);
        for v in p.iter().step_by(7) {
            let h = g.height_at(v.x, v.z, 2.5);
            assert!((h - v.y).abs() < 1e-4, "height_at {h} vs grid {}", v.y);
        }
    }

    #[test]
    fn evaluation_is_identical_on_one_and_two_threads() {
        let g = Gerstner::new(vec![wave(0.8, 30.0, 0.8, Vec2::new(1.0, 0.4))]).unwrap();
        let grid = GridSpec::centered(Vec2::splat(40.0), 64, 64).unwrap();
        let run = |threads| {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            let mut p = vec![Vec3::ZERO; grid.vertex_count()];
            let mut n = p.clone();
            pool.install(|| g.evaluate(&grid, 1.25, &mut p, &mut n));
            (p, n)
        };
        assert_eq!(run(1), run(2));
    }

    #[test]
    fn the_wave_list_is_edited_one_wave_at_a_time_and_revalidated() {
        let mut g = Gerstner::new(Vec::new()).unwrap();
        assert_eq!(g.add_wave(wave(0.5, 20.0, 0.6, Vec2::X)).unwrap(), 0);
        assert_eq!(g.add_wave(wave(0.2, 8.0, 0.6, Vec2::Y)).unwrap(), 1);
        // With two waves the artist mapping halves each horizontal radius: Q / (k N).
        let s = g.sample(&g.frame(0.0), Vec2::ZERO);
        assert!((s.offset.x - 0.6 / (TAU / 20.0 * 2.0)).abs() < 1e-5, "{}", s.offset.x);
        g.set_wave(1, wave(0.3, 9.0, 0.6, Vec2::new(1.0, 1.0))).unwrap();
        assert_eq!(g.waves()[1].wavelength, 9.0);
        // Invalid edits are refused with the key, and leave the model as it was.
        let before = g.waves().to_vec();
        let e = g.set_wave(0, wave(0.3, 9.0, 1.5, Vec2::X)).unwrap_err();
        assert_eq!(e.to_string(), "water.waves[0].steepness = 1.5 is outside [0, 1]");
        let e = g.remove_wave(5).unwrap_err();
        assert_eq!(e.to_string(), "water.waves index = 5 is outside [0, 1]");
        assert_eq!(g.waves(), &before[..]);
        assert_eq!(g.remove_wave(0).unwrap(), before[0]);
        assert_eq!(g.waves(), &before[1..]);
        g.clear();
        assert!(g.waves().is_empty());
        assert_eq!(g.height_at(1.0, 2.0, 3.0), 0.0);
        assert!(g.remove_wave(0).unwrap_err().to_string().contains("empty"));
    }
}
