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
//! `cells[0] = 1` (the paper's mesh) or finer rows across that can carry small waves travelling
//! downstream at the flow speed, tapered to zero at the banks:
//! `y = a sin(pi u) sin(2 pi (z - v t) / wavelength)`, u in [0, 1] across the river.
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
    /// Amplitude of the small waves on the rows across, metres; >= 0. Default 0.
    pub ripple_amplitude: f32,
    /// Wavelength of those waves along the river, metres; > 0. Default 0.7.
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
            ripple_amplitude: 0.0,
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

/// The river surface; see the [module documentation](self).
#[derive(Clone, Debug)]
pub struct River {
    params: RiverParams,
}

/// Per-frame constants: the banks' swing factors and the ripple phase.
#[derive(Clone, Copy, Debug)]
struct Frame {
    left_swing: f32,
    right_swing: f32,
    ripple_phase: f32,
}

impl River {
    /// Builds the model, refusing invalid parameters.
    pub fn new(params: RiverParams) -> Result<Self> {
        params.validate("water")?;
        Ok(Self { params })
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
        let k = f64::from(TAU / p.ripple_wavelength);
        Frame {
            left_swing: r.sin() as f32,
            right_swing: (r + f64::from(p.right_phase)).sin() as f32,
            ripple_phase: (k * f64::from(p.flow_speed) * t).rem_euclid(std::f64::consts::TAU) as f32,
        }
    }

    fn banks_in(&self, f: &Frame, z: f32) -> (f32, f32) {
        let p = &self.params;
        let s = (p.bank_wavenumber * z).sin();
        (f.left_swing * p.left_amplitude * s + p.left_offset, f.right_swing * p.right_amplitude * s + p.right_offset)
    }

    /// Height and its gradient (d/du across the river, d/dz along it) at fraction `u` across, `z`.
    fn ripple(&self, f: &Frame, u: f32, z: f32) -> (f32, f32, f32) {
        let p = &self.params;
        if p.ripple_amplitude == 0.0 {
            return (0.0, 0.0, 0.0);
        }
        let k = TAU / p.ripple_wavelength;
        let (sa, ca) = (PI * u).sin_cos();
        let (sb, cb) = (k * z - f.ripple_phase).sin_cos();
        let a = p.ripple_amplitude;
        (a * sa * sb, a * PI * ca * sb, a * sa * k * cb)
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
    /// Nothing: a finite river whose ripples are resolved wherever it is drawn.
    fn slope_components(&self, _out: &mut Vec<(f32, f32)>) {}

    /// Column i of row j lies at fraction `u = i / cells_x` of the way from the left to the right
    /// bank at the row's z; normals are exact for the bank-interpolated surface.
    fn evaluate(&self, grid: &GridSpec, t: f64, positions: &mut [Vec3], normals: &mut [Vec3]) {
        let n = grid.vertex_count();
        assert!(positions.len() == n && normals.len() == n, "buffers must hold grid.vertex_count() = {n} vertices");
        let f = self.frame(t);
        let row = grid.verts_x();
        let q = self.params.bank_wavenumber;
        positions.par_chunks_mut(row).zip(normals.par_chunks_mut(row)).enumerate().for_each(|(j, (prow, nrow))| {
            let z = grid.rest_position(0, j).y;
            let (l, r) = self.banks_in(&f, z);
            // d(bank x)/dz for both banks.
            let c = q * (q * z).cos();
            let (dl, dr) =
                (f.left_swing * self.params.left_amplitude * c, f.right_swing * self.params.right_amplitude * c);
            for (i, (p, nr)) in prow.iter_mut().zip(nrow.iter_mut()).enumerate() {
                let u = i as f32 / grid.cells_x as f32;
                let x = l + u * (r - l);
                let (y, dy_du, dy_dz) = self.ripple(&f, u, z);
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
        if x < l || x > r {
            return 0.0;
        }
        self.ripple(&f, (x - l) / (r - l), z).0
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
        let ripply = River::new(RiverParams { ripple_amplitude: 0.03, ..Default::default() }).unwrap();
        let grid = GridSpec::new(Vec2::new(-1.0, 0.0), Vec2::new(2.0, 12.0), 6, 960).unwrap();
        let mut p = vec![Vec3::ZERO; grid.vertex_count()];
        let mut n = p.clone();
        ripply.evaluate(&grid, 2.0, &mut p, &mut n);
        for j in 0..961 {
            let row = &p[j * 7..(j + 1) * 7];
            let (l, r) = ripply.banks(row[0].z, 2.0);
            assert!((row[0].x - l).abs() < 1e-5 && (row[6].x - r).abs() < 1e-5);
            assert!(row[0].y.abs() < 1e-6 && row[6].y.abs() < 1e-6, "banks stay at rest height");
            for v in row {
                assert!((ripply.height_at(v.x, v.z, 2.0) - v.y).abs() < 1e-5);
            }
        }
        // Normals are perpendicular to the mesh edges (finite differences of the grid).
        for j in 1..959 {
            for i in 1..5 {
                let k = j * 7 + i;
                let (du, dz) = (p[k + 1] - p[k - 1], p[k + 7] - p[k - 7]);
                let fd = dz.cross(du).normalize();
                assert!((n[k] - fd).length() < 0.05, "{} vs {fd}", n[k]);
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
}
