//! The evaluation shared by both Gerstner forms: a sum of trochoidal waves
//!
//! ```text
//! theta_i = k_i . r - w_i t + phi_i
//! P(r, t) = (r.x + sum H_i D_i.x cos theta_i,   sum A_i sin theta_i,   r.z + sum H_i D_i.z cos theta_i)
//! ```
//!
//! with wave vector k_i, unit direction D_i = k_i / |k_i|, amplitude A_i and horizontal orbit radius
//! H_i. The GPU Gems form (paper 000) has `phi_i = 0`, `H_i = Q_i A_i`; Tessendorf's form (paper 003
//! eq. 11, `x = x0 - sum D A sin(theta')`, `y = sum A cos(theta')`) is the same sum with
//! `theta = theta' + pi/2` and `H_i = A_i`. Normals are the cross product of the exact partial
//! derivatives, not GPU Gems' approximation (which drops the cross terms between waves of different
//! directions).
//!
//! The grid path is the hot loop of every Gerstner scene: rows go to rayon tasks, each row is
//! processed in blocks of [`BLOCK`] vertices with the waves in the outer loop. Per wave and block,
//! [`fast_sin_cos`] gives the first [`LANES`] vertices; later vertices rotate those by the constant
//! phase step along the row (resynchronised every block of 64), so the inner loop is branch-free
//! arithmetic over arrays that the compiler vectorises. The grid agrees with the point query
//! [`TrochoidalSum::sample`] to about 5e-6 of the amplitudes.

use glam::{Vec2, Vec3};
use rayon::prelude::*;

use super::wave_model::SurfacePoint;
use crate::math::{fast_sin_cos, GridSpec, Isa};

/// Most waves one sum holds; per-frame phases live on the stack in an array of this size.
pub const MAX_TROCHOIDAL_WAVES: usize = 64;

/// Vertices per block of the grid path: 8 accumulators of 64 f32 stay in L1.
const BLOCK: usize = 64;

/// Vertices whose sin/cos are computed directly at the start of each block (one AVX2 register).
const LANES: usize = 8;

/// One prepared wave: everything the inner loop needs, premultiplied.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Trochoid {
    /// Wave vector (rad/m).
    pub k: Vec2,
    /// Angular frequency (rad/s).
    pub omega: f64,
    /// Constant phase phi (rad).
    pub phase: f64,
    /// Vertical amplitude A (m).
    pub amplitude: f32,
    /// Horizontal orbit radius H (m).
    pub horizontal: f32,
}

/// Per-wave coefficients of the inner loop (derived from a [`Trochoid`]).
#[derive(Clone, Copy, Debug, Default)]
struct Coefficients {
    kx: f32,
    kz: f32,
    a: f32,
    /// H D.x and H D.z: horizontal offset per unit cos theta.
    hx: f32,
    hz: f32,
    /// A k.x and A k.z: height slope per unit cos theta.
    akx: f32,
    akz: f32,
    /// H k.x D.x, H k.x D.z (= H k.z D.x), H k.z D.z: horizontal Jacobian per unit sin theta.
    sxx: f32,
    sxz: f32,
    szz: f32,
}

/// A prepared sum of trochoidal waves.
#[derive(Clone, Debug, Default)]
pub(crate) struct TrochoidalSum {
    waves: Vec<Trochoid>,
    coefficients: Vec<Coefficients>,
}

/// Per-frame phases `(w_i t - phi_i) mod 2 pi`, computed in f64.
pub(crate) type Phases = [f32; MAX_TROCHOIDAL_WAVES];

/// Where one block of [`BLOCK`] vertices starts: column `start` of grid row `j`, at rest depth
/// coordinate `z` (m).
#[derive(Clone, Copy)]
struct BlockAt {
    start: usize,
    j: usize,
    z: f32,
}

impl TrochoidalSum {
    /// Prepares `waves` (at most [`MAX_TROCHOIDAL_WAVES`]; the callers check).
    pub fn new(waves: Vec<Trochoid>) -> Self {
        debug_assert!(waves.len() <= MAX_TROCHOIDAL_WAVES);
        let coefficients = waves
            .iter()
            .map(|w| {
                let d = w.k.normalize_or_zero();
                Coefficients {
                    kx: w.k.x,
                    kz: w.k.y,
                    a: w.amplitude,
                    hx: w.horizontal * d.x,
                    hz: w.horizontal * d.y,
                    akx: w.amplitude * w.k.x,
                    akz: w.amplitude * w.k.y,
                    sxx: w.horizontal * w.k.x * d.x,
                    sxz: w.horizontal * w.k.x * d.y,
                    szz: w.horizontal * w.k.y * d.y,
                }
            })
            .collect();
        Self { waves, coefficients }
    }

    /// The phases subtracted from `k . r` at time `t` (s).
    pub fn phases(&self, t: f64) -> Phases {
        let mut out = [0.0; MAX_TROCHOIDAL_WAVES];
        for (p, w) in out.iter_mut().zip(&self.waves) {
            *p = (w.omega * t - w.phase).rem_euclid(std::f64::consts::TAU) as f32;
        }
        out
    }

    /// Displacement and normal of the point resting at `rest`.
    pub fn sample(&self, phases: &Phases, rest: Vec2) -> SurfacePoint {
        let mut acc = [0.0f32; 8];
        for (c, &ph) in self.coefficients.iter().zip(phases.iter()) {
            let (s, co) = fast_sin_cos(c.kx * rest.x + (c.kz * rest.y - ph));
            accumulate(&mut acc, c, s, co);
        }
        finish(rest, &acc)
    }

    /// Linear orbital velocity (m/s) of the water at the surface above `rest` at time `t`: for
    /// each wave of height `a sin θ`, `a ω sin θ` along its direction (forward under the crest)
    /// and `∂η/∂t = -a ω cos θ` upward, the deep-water particle velocity of Airy theory (Dean and
    /// Dalrymple, *Water Wave Mechanics*, §4.2). The same for Gerstner waves, whose particles
    /// circle at that speed.
    pub fn velocity(&self, t: f64, rest: Vec2) -> Vec3 {
        let phases = self.phases(t);
        let mut v = Vec3::ZERO;
        for ((w, c), &ph) in self.waves.iter().zip(&self.coefficients).zip(phases.iter()) {
            let (s, co) = (c.kx * rest.x + (c.kz * rest.y - ph)).sin_cos();
            let speed = c.a * w.omega as f32;
            let d = w.k.normalize_or_zero();
            v += Vec3::new(d.x * speed * s, -speed * co, d.y * speed * s);
        }
        v
    }

    /// Writes positions and normals of every vertex of `grid` at time `t` (s); rows in parallel.
    pub fn evaluate(&self, grid: &GridSpec, t: f64, positions: &mut [Vec3], normals: &mut [Vec3]) {
        let n = grid.vertex_count();
        assert!(positions.len() == n && normals.len() == n, "buffers must hold grid.vertex_count() = {n} vertices");
        let phases = self.phases(t);
        let row = grid.verts_x();
        positions.par_chunks_mut(row).zip(normals.par_chunks_mut(row)).enumerate().for_each(|(j, (prow, nrow))| {
            let z = grid.rest_position(0, j).y;
            self.evaluate_row(grid, j, z, &phases, prow, nrow);
        });
    }

    /// One row, compiled for the widest vector instructions this CPU has ([`Isa`]). Every build of
    /// the same code gives bit-identical results: Rust never fuses a multiply and an add on its
    /// own, and every lane does the same IEEE operations in the same order.
    fn evaluate_row(&self, grid: &GridSpec, j: usize, z: f32, phases: &Phases, prow: &mut [Vec3], nrow: &mut [Vec3]) {
        Isa::run_widest(
            #[inline(always)]
            || self.evaluate_row_generic(grid, j, z, phases, prow, nrow),
        );
    }

    #[inline(always)]
    fn evaluate_row_generic(
        &self,
        grid: &GridSpec,
        j: usize,
        z: f32,
        phases: &Phases,
        prow: &mut [Vec3],
        nrow: &mut [Vec3],
    ) {
        let row = prow.len();
        for start in (0..row).step_by(BLOCK) {
            let len = BLOCK.min(row - start);
            let block = BlockAt { start, j, z };
            self.evaluate_block(grid, block, phases, &mut prow[start..start + len], &mut nrow[start..start + len]);
        }
    }

    #[inline(always)]
    fn evaluate_block(
        &self,
        grid: &GridSpec,
        block: BlockAt,
        phases: &Phases,
        positions: &mut [Vec3],
        normals: &mut [Vec3],
    ) {
        let BlockAt { start, j, z } = block;
        let xs: [f32; BLOCK] = std::array::from_fn(|i| grid.rest_position(start + i, j).x);
        let mut ox = [0.0f32; BLOCK];
        let mut oy = [0.0f32; BLOCK];
        let mut oz = [0.0f32; BLOCK];
        let mut sxx = [0.0f32; BLOCK];
        let mut sxz = [0.0f32; BLOCK];
        let mut szz = [0.0f32; BLOCK];
        let mut cx = [0.0f32; BLOCK];
        let mut cz = [0.0f32; BLOCK];
        let dx = grid.spacing().x;
        for (c, &ph) in self.coefficients.iter().zip(phases.iter()) {
            // Exact (polynomial) sin/cos for the first LANES vertices, the same expression as
            // `sample`; each later group of LANES is the previous one rotated by the phase of LANES
            // cells, k_x LANES dx: 6 operations instead of ~22, with the error of 7 rotations
            // (about 5e-6 relative) instead of 6e-7.
            let row_phase = c.kz * z - ph;
            let (step_s, step_c) = fast_sin_cos(c.kx * dx * LANES as f32);
            let mut s = [0.0f32; LANES];
            let mut co = [0.0f32; LANES];
            for l in 0..LANES {
                (s[l], co[l]) = fast_sin_cos(c.kx * xs[l] + row_phase);
            }
            for g in 0..BLOCK / LANES {
                for l in 0..LANES {
                    let i = g * LANES + l;
                    ox[i] += c.hx * co[l];
                    oz[i] += c.hz * co[l];
                    oy[i] += c.a * s[l];
                    sxx[i] += c.sxx * s[l];
                    sxz[i] += c.sxz * s[l];
                    szz[i] += c.szz * s[l];
                    cx[i] += c.akx * co[l];
                    cz[i] += c.akz * co[l];
                }
                for l in 0..LANES {
                    let (sn, cn) = (s[l] * step_c + co[l] * step_s, co[l] * step_c - s[l] * step_s);
                    s[l] = sn;
                    co[l] = cn;
                }
            }
        }
        for (i, (p, nrm)) in positions.iter_mut().zip(normals.iter_mut()).enumerate() {
            let sp = finish(Vec2::new(xs[i], z), &[ox[i], oy[i], oz[i], sxx[i], sxz[i], szz[i], cx[i], cz[i]]);
            *p = Vec3::new(xs[i], 0.0, z) + sp.offset;
            *nrm = sp.normal;
        }
    }
}

/// Adds one wave's terms to the accumulators `[ox, oy, oz, sxx, sxz, szz, cx, cz]`.
#[inline(always)]
fn accumulate(acc: &mut [f32; 8], c: &Coefficients, s: f32, co: f32) {
    acc[0] += c.hx * co;
    acc[1] += c.a * s;
    acc[2] += c.hz * co;
    acc[3] += c.sxx * s;
    acc[4] += c.sxz * s;
    acc[5] += c.szz * s;
    acc[6] += c.akx * co;
    acc[7] += c.akz * co;
}

/// Turns the accumulated sums into the displacement and the exact unit normal.
#[inline(always)]
fn finish(_rest: Vec2, acc: &[f32; 8]) -> SurfacePoint {
    let [ox, oy, oz, sxx, sxz, szz, cx, cz] = *acc;
    // dP/dx0 and dP/dz0: d(H D cos)/dr = -H D k sin, d(A sin)/dr = A k cos.
    let tangent_x = Vec3::new(1.0 - sxx, cx, -sxz);
    let tangent_z = Vec3::new(-sxz, cz, 1.0 - szz);
    let normal = tangent_z.cross(tangent_x).normalize_or(Vec3::Y);
    SurfacePoint { offset: Vec3::new(ox, oy, oz), normal }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A row of Gerstner waves gives the same bits whichever vector instructions compute it.
    #[test]
    fn isa_builds_agree() {
        let waves = (0..7)
            .map(|i| {
                let angle = 0.9 * i as f32;
                let k = 0.05 + 0.11 * i as f32;
                Trochoid {
                    k: Vec2::new(angle.cos(), angle.sin()) * k,
                    omega: (9.81 * f64::from(k)).sqrt(),
                    phase: 0.37 * f64::from(i),
                    amplitude: 0.4 / (1.0 + i as f32),
                    horizontal: 0.3 / (1.0 + i as f32),
                }
            })
            .collect();
        let sum = TrochoidalSum::new(waves);
        // 150 columns: whole blocks and a partial one.
        let grid = GridSpec::new(Vec2::new(-37.5, -10.0), Vec2::new(75.0, 20.0), 149, 4).unwrap();
        let phases = sum.phases(12.3);
        let row = |isa: Isa, j: usize| {
            let (mut p, mut n) = (vec![Vec3::ZERO; 150], vec![Vec3::ZERO; 150]);
            let z = grid.rest_position(0, j).y;
            isa.run(
                #[inline(always)]
                || sum.evaluate_row_generic(&grid, j, z, &phases, &mut p, &mut n),
            );
            p.iter().chain(&n).flat_map(|v| v.to_array().map(f32::to_bits)).collect::<Vec<_>>()
        };
        for j in 0..5 {
            let portable = row(Isa::Portable, j);
            for isa in Isa::ALL.into_iter().filter(|isa| isa.is_available()) {
                assert_eq!(row(isa, j), portable, "{isa:?}, row {j}");
            }
        }
    }
}
