//! A river between two oscillating banks, after paper 004.
//!
//! The river runs along +Z. Each bank is a polyline of N vertices (one per grid row); its lateral
//! position oscillates (paper 004 eqs. 1-2, with r = bank_phase + bank_rate t advancing with time):
//!
//! ```text
//! x_left(z, t)  = sin(r)          A_left  sin(q z) + offset_left        (paper: sin(r) LeftA sin(z) - 2)
//! x_right(z, t) = sin(r + 0.411)  A_right sin(q z) + offset_right       (paper: sin(r + 0.411) RightA sin(z) + 0.2)
//! ```
//!
//! Paper 004's right-bank formula reads `sin(l + 0.411)`; `l` is a misprint for `r` (the text says r
//! sets the rate of both banks). Its coordinates are unitless; swell takes them as metres (a stream
//! 2.2 m wide) and makes every constant a parameter (`q` = 1 rad/m is the paper's `sin(z)`).
//!
//! Between the banks the grid's columns are spread evenly, so the mesh is N - 1 quads across with
//! `cells[0] = 1` (the paper's mesh) or finer rows across that carry the flow's ripples, tapered to
//! zero at the banks (u in [0, 1] across the river):
//!
//! ```text
//! y = sin(pi u) a / sqrt(M) sum_i (lambda_i / lambda) sin(k_i . (x, z - v t) + phi_i)
//! ```
//!
//! M = 12 short waves, wavelengths lambda_i from `ripple_wavelength` (lambda) to four times it,
//! headings spread over ±75° about the flow, so every component has the same steepness and the sum
//! is a rough, crossing pattern rather than one train of crests across the river (which reads as
//! the rungs of a ladder). The pattern is frozen and carried downstream at the surface's speed v =
//! `flow_speed`: the features on a river's surface (boils, the ripples its bed raises) travel with
//! the surface current, which is what large-scale particle image velocimetry measures rivers by
//! (Fujita, Muste and Kruger 1998). So the flow shows in the normals and what they reflect, not only
//! in a texture that clear water hides. A component shorter than four grid spacings (across: the
//! row's width over `cells[0]`; along: the grid's z spacing) fades out of the mesh, and is gone at
//! two, so a coarse grid shows the long ripples instead of aliasing the short ones into crawling
//! moiré; [`WaveModel::height_at`] answers the full pattern.
//!
//! The water appears to flow because the renderer slides a tiling texture downstream:
//! [`River::uv_offset`] is the offset (in texture repeats) at time t, and
//! [`ModelParams::surface_flow`] hands the flow to the scene, whose water material then slides
//! its texture (a procedural pattern of streaks by default, `[water.material] texture` to choose
//! another or an image file) at `flow_speed`, one repeat per `texture_length`. The grid's x extent is not
//! used: x comes from the banks; the grid's z extent and rows give the river's length and N.

use std::f32::consts::{PI, TAU};

use glam::{Vec2, Vec3};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use super::wave_model::WaveModel;
use super::ModelParams;
use crate::error::{check_finite_vec, check_non_negative, check_positive, Error, Result};
use crate::math::GridSpec;

/// Parameters of [`River`]: `model = "river"`. Defaults follow paper 004 where it gives values.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RiverParams {
    /// Swing A_left of the left bank, metres; >= 0. Default 0.5 (not given in the paper).
    pub left_amplitude: f32,
    /// Swing A_right of the right bank, metres; >= 0. Default 0.5 (not given in the paper).
    pub right_amplitude: f32,
    /// Mean x of the left bank, metres. Default -2 (paper 004).
    pub left_offset: f32,
    /// Mean x of the right bank, metres; the banks may not touch:
    /// `left_offset + left_amplitude < right_offset - right_amplitude`. Default 0.2 (paper 004).
    pub right_offset: f32,
    /// Phase lead of the right bank's swing, radians. Default 0.411 (paper 004).
    pub right_phase: f32,
    /// Rate at which r advances, rad/s; >= 0. Default 0.5.
    pub bank_rate: f32,
    /// Value of r at t = 0, radians; finite. Default 0 (paper 004 starts from r = 0).
    pub bank_phase: f32,
    /// Spatial frequency q of the bank shape along the river, rad/m; >= 0. Default 1 (paper 004's `sin(z)`).
    pub bank_wavenumber: f32,
    /// Downstream (+Z) water speed, m/s; finite. Default 0.8.
    pub flow_speed: f32,
    /// Length of one texture repeat along the river, metres; > 0. Default 2.
    pub texture_length: f32,
    /// Amplitude a of the flow's ripples, metres; >= 0: each of the 12 components has amplitude
    /// `a λ_i / (λ sqrt(12))`, so the pattern's rms slope is `π a sqrt(2) / λ` where the grid
    /// resolves it all. 0 turns them off. Default 0.006 (rms slope 0.038 at the default λ).
    pub ripple_amplitude: f32,
    /// Shortest wavelength λ of the ripples, metres; > 0 (the longest is 4 λ). Default 0.7.
    pub ripple_wavelength: f32,
}

impl Default for RiverParams {
    fn default() -> Self {
        Self {
            left_amplitude: 0.5,
            right_amplitude: 0.5,
            left_offset: -2.0,
            right_offset: 0.2,
            right_phase: 0.411,
            bank_rate: 0.5,
            bank_phase: 0.0,
            bank_wavenumber: 1.0,
            flow_speed: 0.8,
            texture_length: 2.0,
            ripple_amplitude: 0.006,
            ripple_wavelength: 0.7,
        }
    }
}

impl RiverParams {
    /// Checks every value, naming keys under `key` (normally `water`).
    pub fn validate(&self, key: &str) -> Result<()> {
        check_non_negative(&format!("{key}.left_amplitude"), self.left_amplitude)?;
        check_non_negative(&format!("{key}.right_amplitude"), self.right_amplitude)?;
        check_finite_vec(&format!("{key}.left_offset"), &[self.left_offset])?;
        check_finite_vec(&format!("{key}.right_offset"), &[self.right_offset])?;
        check_finite_vec(&format!("{key}.right_phase"), &[self.right_phase])?;
        check_non_negative(&format!("{key}.bank_rate"), self.bank_rate)?;
        check_finite_vec(&format!("{key}.bank_phase"), &[self.bank_phase])?;
        check_non_negative(&format!("{key}.bank_wavenumber"), self.bank_wavenumber)?;
        check_finite_vec(&format!("{key}.flow_speed"), &[self.flow_speed])?;
        check_positive(&format!("{key}.texture_length"), self.texture_length)?;
        check_non_negative(&format!("{key}.ripple_amplitude"), self.ripple_amplitude)?;
        check_positive(&format!("{key}.ripple_wavelength"), self.ripple_wavelength)?;
        let min_right = self.left_offset + self.left_amplitude + self.right_amplitude;
        if self.right_offset <= min_right {
            return Err(Error::out_of_range(
                format!("{key}.right_offset"),
                self.right_offset,
                format!("({min_right}, inf) (left_offset + left_amplitude + right_amplitude: the banks would touch)"),
            ));
        }
        Ok(())
    }
}

/// Number of short waves in the flow's ripple pattern.
const RIPPLE_COMPONENTS: usize = 12;
/// Longest ripple wavelength over the shortest (`ripple_wavelength`).
const RIPPLE_SPAN: f32 = 4.0;
/// Widest heading of a ripple's wave vector from the flow axis, radians (75°): crests from across
/// the stream to nearly along it, so no one direction of crest dominates.
const RIPPLE_MAX_HEADING: f32 = 75.0 * PI / 180.0;

/// One component of the ripple pattern, in the model's frame.
#[derive(Clone, Copy, Debug)]
struct Ripple {
    /// Wave vector (kx, kz), rad/m.
    k: Vec2,
    /// Amplitude, metres.
    amplitude: f32,
    /// Phase at t = 0, radians.
    phase: f64,
}

/// The river surface; see the [module documentation](self).
#[derive(Clone, Debug)]
pub struct River {
    params: RiverParams,
    ripples: [Ripple; RIPPLE_COMPONENTS],
}

/// Per-frame constants: the banks' swing factors and each ripple's phase `phi_i - kz_i v t`.
#[derive(Clone, Copy, Debug)]
struct Frame {
    left_swing: f32,
    right_swing: f32,
    ripple_phase: [f32; RIPPLE_COMPONENTS],
}

/// The ripple components of `p`: wavelengths in geometric steps from λ to 4 λ, headings and
/// phases from low-discrepancy sequences (golden ratio), so the same keys give the same pattern.
fn ripples(p: &RiverParams) -> [Ripple; RIPPLE_COMPONENTS] {
    // 1/φ and 1/φ²: successive multiples are spread evenly over [0, 1) and never line up.
    const HEADING_STEP: f32 = 0.618_034;
    const PHASE_STEP: f64 = 0.381_966;
    let norm = (RIPPLE_COMPONENTS as f32).sqrt();
    std::array::from_fn(|i| {
        let span = i as f32 / (RIPPLE_COMPONENTS - 1) as f32;
        let wavelength = p.ripple_wavelength * RIPPLE_SPAN.powf(span);
        let heading = (2.0 * (i as f32 * HEADING_STEP).fract() - 1.0) * RIPPLE_MAX_HEADING;
        let k = TAU / wavelength * Vec2::new(heading.sin(), heading.cos());
        Ripple {
            k,
            amplitude: p.ripple_amplitude * wavelength / (p.ripple_wavelength * norm),
            phase: std::f64::consts::TAU * (i as f64 * PHASE_STEP).fract(),
        }
    })
}

/// How much of a ripple with wave vector `k` a mesh with spacings `dx` (across) and `dz` (along)
/// keeps: all of it with four or more vertices per wavelength along each axis, none at two (the
/// Nyquist limit), linear between.
fn resolved_gain(k: Vec2, dx: f32, dz: f32) -> f32 {
    let rho = (k.x.abs() * dx).max(k.y.abs() * dz) / PI;
    (2.0 - 2.0 * rho).clamp(0.0, 1.0)
}

impl River {
    /// Builds the model, refusing invalid parameters.
    pub fn new(params: RiverParams) -> Result<Self> {
        params.validate("water")?;
        Ok(Self { params, ripples: ripples(&params) })
    }

    /// The parameters, as given.
    pub fn params(&self) -> &RiverParams {
        &self.params
    }

    /// Offset of the water texture along the river at time `t` (s), in texture repeats in [0, 1):
    /// `flow_speed t / texture_length` modulo 1. A renderer samples the texture at
    /// `v = z / texture_length - uv_offset(t)` so the pattern moves downstream at the flow speed.
    pub fn uv_offset(&self, t: f64) -> f32 {
        (f64::from(self.params.flow_speed) * t / f64::from(self.params.texture_length)).rem_euclid(1.0) as f32
    }

    /// x of the left and right banks at `z` (m) and time `t` (s).
    pub fn banks(&self, z: f32, t: f64) -> (f32, f32) {
        let f = self.frame(t);
        self.banks_in(&f, z)
    }

    fn frame(&self, t: f64) -> Frame {
        let p = &self.params;
        let r = (f64::from(p.bank_phase) + f64::from(p.bank_rate) * t).rem_euclid(std::f64::consts::TAU);
        // The pattern moves by v t downstream; reduced modulo a turn in f64 so hours keep f32 precision.
        let shift = f64::from(p.flow_speed) * t;
        Frame {
            left_swing: r.sin() as f32,
            right_swing: (r + f64::from(p.right_phase)).sin() as f32,
            ripple_phase: std::array::from_fn(|i| {
                let c = &self.ripples[i];
                (c.phase - f64::from(c.k.y) * shift).rem_euclid(std::f64::consts::TAU) as f32
            }),
        }
    }

    fn banks_in(&self, f: &Frame, z: f32) -> (f32, f32) {
        let p = &self.params;
        let s = (p.bank_wavenumber * z).sin();
        (f.left_swing * p.left_amplitude * s + p.left_offset, f.right_swing * p.right_amplitude * s + p.right_offset)
    }

    /// The ripple pattern (before the taper across) and its gradient (d/dx, d/dz) at (x, z), each
    /// component weighted by its entry in `gains` (1 keeps it whole, 0 drops it).
    fn pattern(&self, f: &Frame, x: f32, z: f32, gains: &[f32; RIPPLE_COMPONENTS]) -> (f32, f32, f32) {
        let (mut s, mut sx, mut sz) = (0.0, 0.0, 0.0);
        for ((c, phase), &g) in self.ripples.iter().zip(f.ripple_phase).zip(gains) {
            if g == 0.0 {
                continue;
            }
            let (sn, cs) = (c.k.x * x + c.k.y * z + phase).sin_cos();
            let a = g * c.amplitude;
            s += a * sn;
            sx += a * cs * c.k.x;
            sz += a * cs * c.k.y;
        }
        (s, sx, sz)
    }
}

impl ModelParams for RiverParams {
    /// Finite: the river runs between its two banks.
    fn defined_everywhere(&self) -> bool {
        false
    }

    fn validate(&self) -> Result<()> {
        RiverParams::validate(self, "water")
    }

    fn build(&self) -> Result<Box<dyn WaveModel>> {
        Ok(Box::new(River::new(*self)?))
    }

    /// Downstream (+Z) at `flow_speed`, repeating every `texture_length`: the renderer's sliding
    /// texture moves by [`River::uv_offset`] repeats per unit of time.
    fn surface_flow(&self) -> Option<super::SurfaceFlow> {
        Some(super::SurfaceFlow { velocity: Vec2::new(0.0, self.flow_speed), texture_length: self.texture_length })
    }
}

impl WaveModel for River {
    /// The flow, downstream at `flow_speed` between the banks; still water outside them.
    fn surface_velocity(&self, x: f32, z: f32, t: f64) -> Vec3 {
        let (l, r) = self.banks(z, t);
        if x < l || x > r {
            return Vec3::ZERO;
        }
        Vec3::new(0.0, 0.0, self.params.flow_speed)
    }

    /// Nothing: the river is drawn as its own patch, never as the sea's rings, so it has no far
    /// field to filter; ripples its grid cannot hold leave the mesh in `evaluate` instead.
    fn slope_components(&self, _out: &mut Vec<(f32, f32)>) {}

    /// Column i of row j lies at fraction `u = i / cells_x` of the way from the left to the right
    /// bank at the row's z; normals are exact for the bank-interpolated surface.
    fn evaluate(&self, grid: &GridSpec, t: f64, positions: &mut [Vec3], normals: &mut [Vec3]) {
        let n = grid.vertex_count();
        assert!(positions.len() == n && normals.len() == n, "buffers must hold grid.vertex_count() = {n} vertices");
        let f = self.frame(t);
        let row = grid.verts_x();
        let q = self.params.bank_wavenumber;
        let dz = grid.spacing().y;
        let rippled = self.params.ripple_amplitude > 0.0 && grid.cells_x > 1;
        positions.par_chunks_mut(row).zip(normals.par_chunks_mut(row)).enumerate().for_each(|(j, (prow, nrow))| {
            let z = grid.rest_position(0, j).y;
            let (l, r) = self.banks_in(&f, z);
            // d(bank x)/dz for both banks.
            let c = q * (q * z).cos();
            let (dl, dr) =
                (f.left_swing * self.params.left_amplitude * c, f.right_swing * self.params.right_amplitude * c);
            // This row's spacing across: the ripples it cannot hold fade out.
            let dx = (r - l) / grid.cells_x as f32;
            let gains: [f32; RIPPLE_COMPONENTS] = std::array::from_fn(|i| resolved_gain(self.ripples[i].k, dx, dz));
            for (i, (p, nr)) in prow.iter_mut().zip(nrow.iter_mut()).enumerate() {
                let u = i as f32 / grid.cells_x as f32;
                let x = l + u * (r - l);
                let (y, dy_du, dy_dz) = if rippled {
                    // y = T(u) S(x(u, z), z) with T = sin(pi u) and x = l + u (r - l).
                    let (s, sx, sz) = self.pattern(&f, x, z, &gains);
                    let (tn, tc) = (PI * u).sin_cos();
                    (tn * s, PI * tc * s + tn * sx * (r - l), tn * (sx * (dl + u * (dr - dl)) + sz))
                } else {
                    (0.0, 0.0, 0.0)
                };
                *p = Vec3::new(x, y, z);
                // Surface P(u, z) = (l + u (r - l), y, z): tangents dP/du and dP/dz.
                let tu = Vec3::new(r - l, dy_du, 0.0);
                let tz = Vec3::new(dl + u * (dr - dl), dy_dz, 1.0);
                *nr = tz.cross(tu).normalize_or(Vec3::Y);
            }
        });
    }

    /// Height of the water at world (x, z): the ripple at that fraction across (exact), and 0 (the
    /// rest plane) outside the banks.
    fn height_at(&self, x: f32, z: f32, t: f64) -> f32 {
        let f = self.frame(t);
        let (l, r) = self.banks_in(&f, z);
        if x < l || x > r || self.params.ripple_amplitude == 0.0 {
            return 0.0;
        }
        (PI * (x - l) / (r - l)).sin() * self.pattern(&f, x, z, &[1.0; RIPPLE_COMPONENTS]).0
    }
}

impl River {
    /// Where the banks put the surface point at fraction `u` across, row z (used by tests and tools).
    pub fn point(&self, u: f32, z: f32, t: f64) -> Vec2 {
        let (l, r) = self.banks(z, t);
        Vec2::new(l + u * (r - l), z)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn banks_follow_paper_004_and_the_mesh_spans_them() {
        let m = River::new(RiverParams::default()).unwrap();
        for k in 0..20 {
            let (z, t) = (k as f32 * 0.7, k as f64 * 0.9);
            let r = 0.5 * t;
            let (l, rb) = m.banks(z, t);
            assert!((l - ((r.sin() as f32) * 0.5 * z.sin() - 2.0)).abs() < 1e-5);
            assert!((rb - (((r + 0.411).sin() as f32) * 0.5 * z.sin() + 0.2)).abs() < 1e-5);
            assert!(l < rb);
        }
        // 24 rows across a stream about 2.2 m wide hold even the shortest ripples whole.
        let ripply = River::new(RiverParams { ripple_amplitude: 0.03, ..Default::default() }).unwrap();
        let grid = GridSpec::new(Vec2::new(-1.0, 0.0), Vec2::new(2.0, 12.0), 24, 960).unwrap();
        let w = grid.verts_x();
        let mut p = vec![Vec3::ZERO; grid.vertex_count()];
        let mut n = p.clone();
        ripply.evaluate(&grid, 2.0, &mut p, &mut n);
        let mut rippled = 0;
        for j in 0..961 {
            let row = &p[j * w..(j + 1) * w];
            let (l, r) = ripply.banks(row[0].z, 2.0);
            assert!((row[0].x - l).abs() < 1e-5 && (row[w - 1].x - r).abs() < 1e-5);
            assert!(row[0].y.abs() < 1e-6 && row[w - 1].y.abs() < 1e-6, "banks stay at rest height");
            for v in row {
                assert!((ripply.height_at(v.x, v.z, 2.0) - v.y).abs() < 1e-5);
                rippled += usize::from(v.y.abs() > 1e-3);
            }
        }
        assert!(rippled > p.len() / 2, "only {rippled} of {} vertices off the rest plane", p.len());
        // Normals are perpendicular to the mesh edges (finite differences of the grid).
        for j in 1..959 {
            for i in 1..w - 1 {
                let k = j * w + i;
                let (du, dz) = (p[k + 1] - p[k - 1], p[k + w] - p[k - w]);
                let fd = dz.cross(du).normalize();
                assert!((n[k] - fd).length() < 0.02, "{} vs {fd}", n[k]);
            }
        }
    }

    #[test]
    fn texture_offset_advances_with_the_flow() {
        let m = River::new(RiverParams { flow_speed: 0.8, texture_length: 2.0, ..Default::default() }).unwrap();
        assert_eq!(m.uv_offset(0.0), 0.0);
        assert!((m.uv_offset(1.0) - 0.4).abs() < 1e-6);
        assert!((m.uv_offset(3.0) - 0.2).abs() < 1e-6);
        let e = River::new(RiverParams { right_offset: -1.0, ..Default::default() }).unwrap_err();
        assert!(e.to_string().starts_with("water.right_offset = -1 is outside (-1, inf)"), "{e}");
    }

    /// Heights of the mesh along the lines i across (all of them), rows in order of z.
    fn profiles(m: &River, grid: &GridSpec, t: f64) -> Vec<Vec<f32>> {
        let mut p = vec![Vec3::ZERO; grid.vertex_count()];
        let mut n = p.clone();
        m.evaluate(grid, t, &mut p, &mut n);
        let w = grid.verts_x();
        (1..w - 1).map(|i| (0..grid.verts_z()).map(|j| p[j * w + i].y).collect()).collect()
    }

    /// The shift (m, downstream) that best lays the profiles at `t0` onto those at `t0 + dt`:
    /// the least mean squared difference over their overlap, for shifts in steps of 1 mm, the later
    /// profile read between its samples linearly.
    fn measured_shift(a: &[Vec<f32>], b: &[Vec<f32>], dz: f32, max_shift: f32) -> f32 {
        let misfit = |s: f32| -> f32 {
            let (mut sum, mut count) = (0.0, 0.0);
            for (pa, pb) in a.iter().zip(b) {
                for (j, &ha) in pa.iter().enumerate() {
                    let x = j as f32 + s / dz;
                    let (k, f) = (x.floor() as usize, x.fract());
                    if k + 1 < pb.len() {
                        sum += (ha - (pb[k] * (1.0 - f) + pb[k + 1] * f)).powi(2);
                        count += 1.0;
                    }
                }
            }
            sum / count
        };
        let steps = (max_shift / 1e-3) as usize;
        let best = (0..=steps).min_by(|&i, &j| misfit(i as f32 * 1e-3).total_cmp(&misfit(j as f32 * 1e-3)));
        best.unwrap() as f32 * 1e-3
    }

    #[test]
    fn the_ripples_travel_downstream_at_flow_speed_on_fine_and_coarse_grids() {
        // Straight, still banks: only the ripples move.
        let still = RiverParams { bank_rate: 0.0, left_amplitude: 0.0, right_amplitude: 0.0, ..Default::default() };
        // The preset's mesh (0.125 m along, 24 across) and the scene default's (200 m in 256 rows:
        // 0.78 m along, where the short ripples must fade rather than alias into wrong motion).
        for (flow_speed, length, rows, dt) in [(0.8, 96.0, 768, 0.4), (0.8, 200.0, 256, 5.0), (2.5, 96.0, 768, 0.4)] {
            let m = River::new(RiverParams { flow_speed, ..still }).unwrap();
            let grid = GridSpec::new(Vec2::new(-1.0, 0.0), Vec2::new(2.0, length), 24, rows).unwrap();
            let dz = grid.spacing().y;
            let a = profiles(&m, &grid, 1.0);
            let b = profiles(&m, &grid, 1.0 + dt);
            let expected = flow_speed * dt as f32;
            let shift = measured_shift(&a, &b, dz, 2.0 * expected);
            let speed = shift / dt as f32;
            assert!((speed / flow_speed - 1.0).abs() < 0.1, "{rows} rows, {flow_speed} m/s: measured {speed} m/s");
            // The mesh really moves: not a still surface that any shift fits.
            let change: f32 = a.iter().flatten().zip(b.iter().flatten()).map(|(x, y)| (x - y).abs()).sum::<f32>()
                / a.iter().flatten().map(|x| x.abs()).sum::<f32>();
            assert!(change > 0.5, "{rows} rows: heights changed by {change} of their mean");
        }
    }

    #[test]
    fn ripples_a_grid_cannot_hold_fade_out_of_the_mesh_before_they_alias() {
        let k = Vec2::new(0.0, TAU / 0.7);
        // Four vertices per wavelength and more: whole; two (Nyquist) and fewer: gone.
        assert_eq!(resolved_gain(k, 0.01, 0.7 / 4.5), 1.0);
        assert!(resolved_gain(k, 0.01, 0.7 / 4.0) > 0.9999);
        assert!(resolved_gain(k, 0.01, 0.7 / 2.0) < 1e-5);
        assert_eq!(resolved_gain(k, 0.01, 0.7 / 1.9), 0.0);
        assert!((resolved_gain(k, 0.01, 0.7 / 3.0) - 2.0 / 3.0).abs() < 1e-5);
        // Across, the row's spacing counts the same way.
        assert_eq!(resolved_gain(Vec2::new(TAU / 0.7, 0.0), 0.7 / 2.0, 0.01), 0.0);
        // On the scene default's grid (0.78 m along) the mesh keeps only the long ripples: its
        // heights change between neighbouring rows by no more than those ripples' slopes allow.
        let m = River::new(RiverParams { bank_rate: 0.0, ..Default::default() }).unwrap();
        let grid = GridSpec::new(Vec2::new(-1.0, 0.0), Vec2::new(2.0, 200.0), 24, 256).unwrap();
        let dz = grid.spacing().y;
        let kept: f32 = m.ripples.iter().map(|c| resolved_gain(c.k, 2.2 / 24.0, dz) * c.amplitude * c.k.y.abs()).sum();
        assert!(kept > 0.0, "the long ripples stay");
        for line in profiles(&m, &grid, 3.0) {
            for pair in line.windows(2) {
                assert!((pair[1] - pair[0]).abs() <= kept * dz * 1.01, "{pair:?}: steeper than the kept ripples");
            }
        }
    }
}
