//! The statistical (FFT) ocean: Tessendorf's sea synthesised from an oceanographic spectrum.
//!
//! Paper 003 §1.2.2 (after Tessendorf 2001, "Simulating Ocean Water") calls this the best of the
//! methods it surveys: a random sea whose wave heights follow a measured spectrum, synthesised each
//! frame by inverse FFTs over a square periodic patch of side L on an N x N grid.
//!
//! - **Spectrum**: [`crate::spectrum::DirectionalSpectrum`] in physical units, so heights are metres
//!   (`4 sqrt(m0)` is the significant wave height, and the tests check the realised sea against it).
//! - **Randomness**: each wave vector's Gaussian pair is a hash of (seed, cascade, wave vector), so
//!   the same seed gives the same sea on any thread count, and a finer grid keeps the large waves.
//! - **Outputs per step** ([`FftOcean::advance`]): height, choppy horizontal displacement (positive
//!   choppiness sharpens crests), slopes and the Jacobian terms as spectral derivatives, and foam.
//! - **Cascades**: 1-4 patches of sides `L / 4.36^c`, each holding its own band of wavenumbers so no
//!   wave is counted twice; their sum hides the tiling of a single patch.
//! - **Looping**: with a loop period T, frequencies are quantised so the sea repeats after T.
//! - **Sampling** ([`WaveModel::evaluate`]): fields are sampled bilinearly, periodically, at each
//!   mesh vertex's rest position; normals come from the sampled spectral derivatives.
//!
//! The synthesis itself (layout, packing, sign conventions) is documented in `fft_ocean/cascade.rs`.

mod blender;
mod cascade;
mod evolve_simd;
mod fill_simd;
mod foam_simd;
mod params;
mod transpose_simd;

use std::time::Instant;

use glam::{Vec2, Vec3};
use rayon::prelude::*;
use serde::Serialize;

pub use self::blender::{BlenderOcean, BLENDER_RESOLUTION_RANGE};
use self::cascade::{Cascade, CascadeSetup, PAIR_H_DX};
pub use self::params::{
    FftOceanParams, InlineSpectrumTable, SpectrumFiles, SwellParams, FFT_GRID_RANGE, MAX_CASCADES,
    MAX_SPECTRUM_FILE_BYTES,
};
use super::foam::{FoamField, FOAM_MIN_SPREAD};
use super::slope_spectrum::cox_munk_slope_variance;
use super::wave_model::{WaveModel, INVERSION_MAX_ITERATIONS, INVERSION_TOLERANCE};
use crate::error::Result;
use crate::math::{fast_floor, GridSpec};
use crate::spectrum::{loop_time, DirectionalSpectrum, GriddedSpectrum};

/// Ratio of the sides of successive cascades: sqrt(19) ≈ 4.36, irrational so the tiles of different
/// cascades never line up, and large enough that each cascade adds a decade of short waves.
pub const CASCADE_SCALE: f32 = 4.358_899;

/// What the first patch's side is divided by for cascade `c`: `CASCADE_SCALE^c`, or with
/// `tile_cascades` that rounded to a whole number (1, 4, 19, 83), so every patch divides the first
/// and the sum repeats over the first patch (maps that tile) while the tiles of different cascades
/// still line up only at the first patch's corners.
fn cascade_divisor(c: usize, tile_cascades: bool) -> f32 {
    let scale = CASCADE_SCALE.powi(c as i32);
    if tile_cascades {
        scale.round()
    } else {
        scale
    }
}

/// Fraction of a cascade's Nyquist wavenumber `π N / L` where the next, smaller cascade takes over.
/// Half: the upper half of a grid's band is resolved by few samples per wave, the next cascade
/// resolves it better.
const CASCADE_HANDOVER: f64 = 0.5;

/// Wall-clock time of each stage of the last [`FftOcean::advance`], milliseconds.
///
/// The step runs as two fused passes (see `fft_ocean/cascade.rs`), so the stages are the passes:
/// the evolution is timed with the column transforms it feeds, and foam with the row transforms.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct StageTimes {
    /// Column pass: evolving `h(k, t)` from `h0` (phases), writing the five bases the eight
    /// fields are built from and their transforms over kz.
    pub evolve_ms: f64,
    /// Row pass: gathering the bases into the eight fields' packed pairs (a transpose), their
    /// transforms over kx, with the Jacobian and the frame's foam of the first cascade fused in.
    pub fft_ms: f64,
    /// The foam lattice's steps that this time needed (the first cascade synthesised at the
    /// lattice times, `water/foam.rs`): 0 when none was due.
    pub foam_ms: f64,
}

/// The sea state realised on the grid at the last [`FftOcean::advance`] (for `swell stats`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct SeaState {
    /// Time of the fields, s.
    pub time: f64,
    /// Significant height `4 sqrt(var(h))` realised on the grid, m.
    pub hs_realised: f64,
    /// The spectrum's own expectation `4 sqrt(m0)` over the grid's wave vectors, m.
    pub hs_expected: f64,
    /// Peak period of the spectrum, s.
    pub peak_period: f64,
    /// Mean height, m (0 up to rounding: the mean is not synthesised).
    pub mean_height: f64,
    /// Lowest and highest height on the grid, m.
    pub min_height: f64,
    /// Highest height on the grid, m.
    pub max_height: f64,
    /// Mean foam coverage in [0, 1].
    pub foam_coverage: f64,
}

/// The FFT ocean. See the module documentation.
pub struct FftOcean {
    params: FftOceanParams,
    spectrum: DirectionalSpectrum,
    cascades: Vec<Cascade>,
    foam: FoamField,
    time: f64,
    stage_times: StageTimes,
}

/// The eight fields at a point: h, Dx, Dz, hx, hz, Dxx, Dzz, Dxz (metres, or dimensionless slopes).
type Fields = [f32; 8];

impl FftOcean {
    /// Validates `params`, builds the spectrum and the cascades and synthesises the fields of
    /// time 0 (the foam is computed by the first [`WaveModel::advance`]).
    ///
    /// Setup costs O(cascades N²) spectrum evaluations and allocates every buffer the steps use.
    ///
    /// With `[water.blender]` the Blender keys are mapped onto swell's ([`FftOceanParams::resolved`])
    /// and, as Blender does, every field is scaled so that the largest |height| at t = 0 is
    /// `wave_scale` metres.
    pub fn new(params: &FftOceanParams) -> Result<Self> {
        params.validate("water")?;
        let params = &params.resolved();
        let spectrum = params.spectrum()?;
        let n = params.grid as usize;
        let count = params.cascades as usize;
        let patches: Vec<f32> =
            (0..count).map(|c| params.patch_size / cascade_divisor(c, params.tile_cascades)).collect();
        let handover = |c: usize| CASCADE_HANDOVER * std::f64::consts::PI * n as f64 / f64::from(patches[c]);
        let cascades = (0..count)
            .map(|c| {
                let lo = if c == 0 { 0.0 } else { handover(c - 1) };
                let hi = if c + 1 == count { f64::INFINITY } else { handover(c) };
                Cascade::new(&CascadeSetup {
                    spectrum: &spectrum,
                    n,
                    patch: patches[c],
                    band: (lo, hi),
                    seed: params.seed,
                    index: c as u32,
                    choppiness: params.choppiness,
                    loop_period: params.loop_period.map(f64::from),
                })
            })
            .collect();
        // The unresolved Jacobian's spread is set below, once the amplitudes are final.
        let loop_period = params.loop_period.map(f64::from);
        let foam = FoamField::new(n, params.foam_threshold, FOAM_MIN_SPREAD, params.foam_fade_s, loop_period);
        let mut ocean = Self {
            params: params.clone(),
            spectrum,
            cascades,
            foam,
            time: f64::NAN,
            stage_times: StageTimes::default(),
        };
        if let Some(b) = &params.blender {
            ocean.normalise_max_height(b.wave_scale);
        }
        // After the normalisation: what the first cascade resolves is final.
        let spread = ocean.unresolved_jacobian_spread();
        ocean.foam.set_spread(spread);
        // The fields of t = 0, so that the ocean can be sampled at once; the foam (whose lattice
        // may need many steps) waits for the first `advance`, which the time NaN forces.
        ocean.synthesise(0.0);
        Ok(ocean)
    }

    /// Scales every cascade's amplitudes so that the largest |height| on the first cascade's grid
    /// at t = 0 (the others sampled there) is `max_height` m; the caller synthesises again. Blender's
    /// "normalise factor"; a flat sea stays flat.
    fn normalise_max_height(&mut self, max_height: f32) {
        self.synthesise(0.0);
        let state = self.sea_state();
        let highest = state.max_height.max(-state.min_height);
        if !(highest > 0.0 && highest.is_finite()) {
            return;
        }
        let factor = f64::from(max_height) / highest;
        for c in &mut self.cascades {
            c.scale_amplitudes(factor);
        }
    }

    /// Spread σ (dimensionless) of the Jacobian that the first cascade, where foam lives, does not
    /// resolve: `λ sqrt(s_total - s_resolved)`, with `s_total` the sea's slope variance that Cox and
    /// Munk measured at the wind speed and `s_resolved` what the first cascade realises
    /// (`water/foam.rs`).
    fn unresolved_jacobian_spread(&self) -> f32 {
        let total = f64::from(cox_munk_slope_variance(self.params.wind_speed));
        let mut components = Vec::new();
        self.cascades[0].slope_components(&mut components);
        let resolved: f64 = components.iter().map(|c| f64::from(c.1)).sum();
        let lambda = f64::from(self.params.choppiness);
        (lambda * lambda * (total - resolved).max(0.0)).sqrt() as f32
    }

    /// The parameters, as validated.
    pub fn params(&self) -> &FftOceanParams {
        &self.params
    }

    /// The directional spectrum the sea follows.
    pub fn spectrum(&self) -> &DirectionalSpectrum {
        &self.spectrum
    }

    /// Time (s) of the fields, set by the last [`WaveModel::advance`].
    pub fn time(&self) -> f64 {
        self.time
    }

    /// How long each stage of the last step took.
    pub fn stage_times(&self) -> StageTimes {
        self.stage_times
    }

    /// Synthesises every field and the foam for time `t` (s); no allocation, except the
    /// per-thread scratch at the first step and when a larger thread pool than before runs it.
    ///
    /// With a loop period the fields are those of `t` reduced into the first period
    /// ([`loop_time`]), so a loop's frame N is its frame 0 bit for bit. Foam with persistence first
    /// brings its lattice to `t` (the first cascade alone, stepped at the lattice times; see
    /// `water/foam.rs`), then every cascade is synthesised at `t`.
    fn step(&mut self, t: f64) {
        let t0 = Instant::now();
        let local = self.params.loop_period.map_or(t, |p| loop_time(t, f64::from(p)));
        if self.params.foam {
            if let Some(steps) = self.foam.plan(local) {
                // Foam follows the largest cascade alone: its grid is where foam is stored, and
                // the smaller cascades' short waves, sampled on it, would alias into speckle and
                // make the threshold depend on the number of cascades.
                for k in steps.indices() {
                    let first = &mut self.cascades[0];
                    first.column_pass(self.foam.lattice_time(k));
                    first.row_pass(Some(self.foam.lattice_update(k)));
                }
            }
        }
        let t1 = Instant::now();
        for c in &mut self.cascades {
            c.column_pass(local);
        }
        let t2 = Instant::now();
        // The frame's own foam is updated inside the first cascade's row pass.
        let mut foam = self.params.foam.then(|| self.foam.frame_update(local));
        for c in &mut self.cascades {
            c.row_pass(foam.take());
        }
        let t3 = Instant::now();
        self.time = t;
        let ms = |a: Instant, b: Instant| (b - a).as_secs_f64() * 1e3;
        self.stage_times = StageTimes { evolve_ms: ms(t1, t2), fft_ms: ms(t2, t3), foam_ms: ms(t0, t1) };
    }

    /// Synthesises the fields (not the foam) for time `t` (s), as at the start of a loop.
    fn synthesise(&mut self, t: f64) {
        for c in &mut self.cascades {
            c.column_pass(t);
            c.row_pass(None);
        }
    }

    /// The eight fields summed over cascades at the rest point (x, z) (m), at the last step's time.
    fn fields_at(&self, x: f32, z: f32) -> Fields {
        let mut acc = [0.0; 8];
        for c in &self.cascades {
            let f = sample(c, x, z);
            for (a, v) in acc.iter_mut().zip(f) {
                *a += v;
            }
        }
        acc
    }

    /// If `grid` samples exactly the single cascade's grid points (a whole number of sample
    /// spacings apart, origin on a grid point), the field index of its vertex (0, 0) and the
    /// stride in samples: evaluation then reads samples directly, which is what bilinear
    /// sampling gives there and about three times faster. The unbounded sea's clipmap rings are
    /// such grids at strides 1, 2, 4, ... when its finest spacing is the sample spacing.
    fn aligned_index(&self, grid: &GridSpec) -> Option<Aligned> {
        let [c] = self.cascades.as_slice() else { return None };
        let dx = c.patch / c.n as f32;
        let s = grid.spacing();
        let (u, v) = (grid.origin.x / dx, grid.origin.y / dx);
        let stride = (s.x / dx).round();
        let close = |a: f32, b: f32| (a - b).abs() <= 1e-6 * b.abs().max(1.0);
        let whole = stride >= 1.0 && stride <= c.n as f32 && close(s.x, stride * dx) && close(s.y, s.x);
        (whole && close(u, u.round()) && close(v, v.round())).then(|| Aligned {
            i0: u.round() as i64,
            j0: v.round() as i64,
            stride: stride as i64,
        })
    }

    /// The eight fields of the single cascade at sample (i, j), wrapped periodically.
    fn fields_at_sample(&self, i: i64, j: i64) -> Fields {
        let c = &self.cascades[0];
        let mask = c.n as i64 - 1;
        let idx = (j & mask) as usize * c.n + (i & mask) as usize;
        let mut out = [0.0; 8];
        for (p, field) in c.fields.iter().enumerate() {
            out[2 * p] = field[idx].re;
            out[2 * p + 1] = field[idx].im;
        }
        out
    }

    /// Displacement (Dx, h, Dz) in metres of the water that rests at (x, z), at the time of the last
    /// [`WaveModel::advance`]: the displaced point is `(x + Dx, h, z + Dz)`.
    pub fn displacement_at(&self, x: f32, z: f32) -> Vec3 {
        let f = self.fields_at(x, z);
        Vec3::new(f[1], f[0], f[2])
    }

    /// The sea state realised on the first cascade's grid (plus the others sampled there).
    pub fn sea_state(&self) -> SeaState {
        let first = &self.cascades[0];
        let n = first.n;
        let dx = first.patch / n as f32;
        let heights: Vec<f64> = (0..n * n)
            .into_par_iter()
            .map(|idx| {
                let (i, j) = (idx % n, idx / n);
                let mut h = first.fields[PAIR_H_DX][idx].re;
                for c in &self.cascades[1..] {
                    h += sample(c, i as f32 * dx, j as f32 * dx)[0];
                }
                f64::from(h)
            })
            .collect();
        let count = heights.len() as f64;
        let mean = heights.iter().sum::<f64>() / count;
        let var = heights.iter().map(|h| (h - mean).powi(2)).sum::<f64>() / count;
        let variance: f64 = self.cascades.iter().map(|c| c.variance).sum();
        SeaState {
            time: self.time,
            hs_realised: 4.0 * var.sqrt(),
            hs_expected: 4.0 * variance.sqrt(),
            peak_period: self.spectrum.peak_period(),
            mean_height: mean,
            min_height: heights.iter().copied().fold(f64::INFINITY, f64::min),
            max_height: heights.iter().copied().fold(f64::NEG_INFINITY, f64::max),
            foam_coverage: if self.params.foam { f64::from(self.foam.mean()) } else { 0.0 },
        }
    }

    /// The realised directional spectrum: every wave of every cascade ([`Cascade::for_each_wave`])
    /// binned onto `grid`'s frequencies and directions (wavespectra's conventions: Hz, degrees the
    /// waves come from, m²/Hz/deg). A wave goes to the nearest direction and to the frequency bin
    /// between the midpoints of its neighbours; the density is the bin's energy over
    /// `numpy.gradient(freq)` and the direction step, so that wavespectra's sums give back the
    /// energy. Waves outside the grid's first and last bins are left out.
    pub fn realised_spectrum(&self, grid: &GriddedSpectrum) -> GriddedSpectrum {
        let mut out = GriddedSpectrum::zeros(grid.freq_hz.clone(), grid.dir_deg.clone());
        let f = &out.freq_hz;
        let (nf, nd) = (f.len(), out.dir_deg.len());
        if nf < 2 || nd == 0 {
            return out;
        }
        let dd = out.dd();
        let df = out.df();
        let lower = f[0] - 0.5 * (f[1] - f[0]);
        let upper = f[nf - 1] + 0.5 * (f[nf - 1] - f[nf - 2]);
        let mids: Vec<f64> = f.windows(2).map(|w| 0.5 * (w[0] + w[1])).collect();
        let dispersion = self.spectrum.dispersion;
        let mut energy = vec![0.0; nf * nd];
        for c in &self.cascades {
            c.for_each_wave(|kx, kz, e| {
                let hz = dispersion.omega_f64(kx.hypot(kz)) / std::f64::consts::TAU;
                if !(lower..upper).contains(&hz) {
                    return;
                }
                // The bin of the nearest frequency: past every midpoint at or below it.
                let i = mids.partition_point(|&m| m <= hz);
                let from = kz.atan2(kx).to_degrees() - 90.0;
                let j = ((from - out.dir_deg[0]) / dd).round().rem_euclid(nd as f64) as usize % nd;
                energy[i * nd + j] += e;
            });
        }
        for (i, row) in energy.chunks_exact(nd).enumerate() {
            for (j, e) in row.iter().enumerate() {
                out.efth[i * nd + j] = e / (df[i] * dd);
            }
        }
        out
    }

    /// (h, Dx, Dz) at rest point (x, z) and any time t, by summing every wave directly in f64.
    ///
    /// O(cascades N²) per call: the slow, obviously right oracle the FFT is tested against, and
    /// what [`WaveModel::height_at`] uses for a time other than the last step's.
    pub fn exact_displacement(&self, x: f64, z: f64, t: f64) -> [f64; 3] {
        let f = self.exact_fields(x, z, t);
        [f[0], f[1], f[2]]
    }

    /// All eight fields (h, Dx, Dz, hx, hz, Dxx, Dzz, Dxz) at rest point (x, z), time t, summed
    /// wave by wave (a naive inverse DFT evaluated at one point).
    fn exact_fields(&self, x: f64, z: f64, t: f64) -> [f64; 8] {
        let lambda = f64::from(self.params.choppiness);
        let mut out = [0.0; 8];
        for c in &self.cascades {
            let dk = std::f64::consts::TAU / f64::from(c.patch);
            for (nx, nz, h0, hm, f) in c.half_spectrum() {
                if h0.norm_sqr() == 0.0 && hm.norm_sqr() == 0.0 {
                    continue;
                }
                let (kx, kz) = (f64::from(nx) * dk, f64::from(nz) * dk);
                let k = kx.hypot(kz);
                let (s, co) = (std::f64::consts::TAU * (f * t).fract()).sin_cos();
                // c = h0 e^{-iφ} + hm e^{iφ}
                let (a, b) = ((f64::from(h0.re), f64::from(h0.im)), (f64::from(hm.re), f64::from(hm.im)));
                let cr = a.0 * co + a.1 * s + b.0 * co - b.1 * s;
                let ci = a.1 * co - a.0 * s + b.1 * co + b.0 * s;
                let (es, ec) = (kx * x + kz * z).sin_cos();
                // c e^{ik.x}: its real part is the wave, its imaginary part gives Re(i m c e^{ik.x}) = -m vi.
                let (vr, vi) = (cr * ec - ci * es, cr * es + ci * ec);
                // Row nx = 0 holds both k and -k; other rows stand for their mirror too.
                let w = if nx == 0 { 1.0 } else { 2.0 };
                let l = lambda / k;
                let terms = [
                    vr,
                    -l * kx * vi,
                    -l * kz * vi,
                    -kx * vi,
                    -kz * vi,
                    -l * kx * kx * vr,
                    -l * kz * kz * vr,
                    -l * kx * kz * vr,
                ];
                for (o, v) in out.iter_mut().zip(terms) {
                    *o += w * v;
                }
            }
        }
        out
    }
}

/// `J = (1 + Dxx)(1 + Dzz) - Dxz²`, the Jacobian of the horizontal map (Tessendorf 2001 §3.5).
fn jacobian(dxx: f32, dzz: f32, dxz: f32) -> f32 {
    (1.0 + dxx) * (1.0 + dzz) - dxz * dxz
}

/// A grid that lies on the cascade's samples ([`FftOcean::aligned_index`]): vertex (i, j) is
/// sample (`i0 + i * stride`, `j0 + j * stride`), wrapped periodically.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Aligned {
    i0: i64,
    j0: i64,
    stride: i64,
}

impl Aligned {
    /// The sample of vertex (`i`, `j`).
    fn sample(self, i: usize, j: usize) -> (i64, i64) {
        (self.i0 + i as i64 * self.stride, self.j0 + j as i64 * self.stride)
    }
}

/// Bilinear, periodic sample of a cascade's eight fields at the local point (x, z) (m).
fn sample(c: &Cascade, x: f32, z: f32) -> Fields {
    let n = c.n;
    let inv_dx = n as f32 / c.patch;
    let (u, v) = (x * inv_dx, z * inv_dx);
    let (fu, fv) = (fast_floor(u), fast_floor(v));
    let (tx, tz) = (u - fu, v - fv);
    let mask = n as i64 - 1;
    let i0 = (fu as i64 & mask) as usize;
    let j0 = (fv as i64 & mask) as usize;
    let (i1, j1) = ((i0 + 1) & mask as usize, (j0 + 1) & mask as usize);
    let w = [(1.0 - tx) * (1.0 - tz), tx * (1.0 - tz), (1.0 - tx) * tz, tx * tz];
    let idx = [j0 * n + i0, j0 * n + i1, j1 * n + i0, j1 * n + i1];
    let mut out = [0.0; 8];
    for (p, field) in c.fields.iter().enumerate() {
        let (mut re, mut im) = (0.0, 0.0);
        for (wk, &ik) in w.iter().zip(&idx) {
            re += wk * field[ik].re;
            im += wk * field[ik].im;
        }
        out[2 * p] = re;
        out[2 * p + 1] = im;
    }
    // Packed order (h, Dx), (Dz, hx), (hz, Dxx), (Dzz, Dxz) -> h, Dx, Dz, hx, hz, Dxx, Dzz, Dxz.
    out
}

/// Unit normal of the displaced surface from the eight fields: the cross product of the tangents
/// `dP/dz = (Dxz, hz, 1 + Dzz)` and `dP/dx = (1 + Dxx, hx, Dxz)` of `P = (x + Dx, h, z + Dz)`.
fn normal_of(f: &Fields) -> Vec3 {
    let tangent_x = Vec3::new(1.0 + f[5], f[3], f[7]);
    let tangent_z = Vec3::new(f[7], f[4], 1.0 + f[6]);
    tangent_z.cross(tangent_x).normalize_or(Vec3::Y)
}

impl WaveModel for FftOcean {
    /// Every stored wave vector of every cascade: `k^2 (|h0(k)|^2 + |h0(-k)|^2)`, counted twice
    /// for the rows that stand for their mirror too (as [`FftOcean::exact_displacement`] sums).
    fn slope_components(&self, out: &mut Vec<(f32, f32)>) {
        for c in &self.cascades {
            c.slope_components(out);
        }
    }

    /// Samples the fields of the last [`WaveModel::advance`] at every vertex's rest position; `t`
    /// must be that step's time (the World always advances first), the fields are not re-synthesised.
    fn evaluate(&self, grid: &GridSpec, t: f64, positions: &mut [Vec3], normals: &mut [Vec3]) {
        let n = grid.vertex_count();
        assert!(positions.len() == n && normals.len() == n, "buffers must hold grid.vertex_count() = {n} vertices");
        let _ = t;
        let row = grid.verts_x();
        let aligned = self.aligned_index(grid);
        positions.par_chunks_mut(row).zip(normals.par_chunks_mut(row)).enumerate().for_each(|(j, (prow, nrow))| {
            for (i, (p, nrm)) in prow.iter_mut().zip(nrow.iter_mut()).enumerate() {
                let rest = grid.rest_position(i, j);
                let f = match aligned {
                    Some(a) => {
                        let (si, sj) = a.sample(i, j);
                        self.fields_at_sample(si, sj)
                    }
                    None => self.fields_at(rest.x, rest.y),
                };
                *p = Vec3::new(rest.x + f[1], f[0], rest.y + f[2]);
                *nrm = normal_of(&f);
            }
        });
    }

    /// Height above (x, z): inverts the horizontal displacement on the same bilinear fields
    /// [`WaveModel::evaluate`] draws, so it agrees with the rendered mesh
    /// ([`FftOcean::height_near`] from the point itself). For a `t` other than the last step's it
    /// sums the waves directly ([`FftOcean::exact_displacement`], O(N²) per iteration).
    fn height_at(&self, x: f32, z: f32, t: f64) -> f32 {
        let mut rest = Vec2::new(x, z);
        self.height_near(x, z, t, &mut rest)
    }

    /// [`WaveModel::height_at`] from the rest point `rest` (a body's vertex's answer of the step
    /// before), which it leaves at the rest point found. At the last step's time the iteration is
    /// Newton's, with the Jacobian `1 + ∂D/∂r` from the fields' own derivatives (Dxx, Dxz, Dzz):
    /// two or three steps from a cold start, one from a warm one, where the damped fixed-point
    /// iteration took tens near choppy crests. Where the Jacobian nears a fold (its determinant
    /// below 0.1) or a step does not reduce the residual, the step is the damped one (0.75 of the
    /// residual), which converges wherever the surface does not loop.
    fn height_near(&self, x: f32, z: f32, t: f64, rest: &mut Vec2) -> f32 {
        let target = Vec2::new(x, z);
        // A guess farther than any displacement is no guess (a body that jumped, a first step).
        if !rest.is_finite() || (*rest - target).length_squared() > 1.0e4 {
            *rest = target;
        }
        let exact = t != self.time;
        let mut best = (f32::INFINITY, 0.0, *rest);
        let mut previous = f32::INFINITY;
        for _ in 0..INVERSION_MAX_ITERATIONS {
            let (d, jacobian) = if exact {
                let d = self.exact_displacement(f64::from(rest.x), f64::from(rest.y), t);
                (Vec3::new(d[1] as f32, d[0] as f32, d[2] as f32), None)
            } else {
                let f = self.fields_at(rest.x, rest.y);
                // dP/dr of P = r + (Dx, Dz): columns d/dx and d/dz.
                let j = glam::Mat2::from_cols(Vec2::new(1.0 + f[5], f[7]), Vec2::new(f[7], 1.0 + f[6]));
                (Vec3::new(f[1], f[0], f[2]), Some(j))
            };
            let residual_vector = *rest + Vec2::new(d.x, d.z) - target;
            let residual = residual_vector.length();
            if residual < best.0 {
                best = (residual, d.y, *rest);
            }
            if residual < INVERSION_TOLERANCE {
                break;
            }
            let newton = jacobian
                .filter(|j| j.determinant() > 0.1 && residual < previous)
                .map(|j| j.inverse() * residual_vector);
            *rest -= newton.unwrap_or(0.75 * residual_vector);
            previous = residual;
        }
        *rest = best.2;
        best.1
    }

    /// The first patch's side when every cascade's patch divides it (one cascade, or
    /// `tile_cascades`): the sum of the cascades then repeats over it.
    fn spatial_period(&self) -> Option<f32> {
        let first = self.cascades[0].patch;
        let divides = |c: &Cascade| {
            let ratio = f64::from(first) / f64::from(c.patch);
            (ratio - ratio.round()).abs() < 1e-5 * ratio
        };
        self.cascades.iter().all(divides).then_some(first)
    }

    fn advance(&mut self, t: f64) -> Result<()> {
        if t != self.time {
            self.step(t);
        }
        Ok(())
    }

    fn wind_direction(&self) -> Option<Vec2> {
        let a = self.params.wind_direction_deg.to_radians();
        Some(Vec2::new(a.cos(), a.sin()))
    }

    fn wind_speed(&self) -> Option<f32> {
        Some(self.params.wind_speed)
    }

    fn foam(&self, grid: &GridSpec, out: &mut [f32]) -> bool {
        if !self.params.foam {
            return false;
        }
        let first = &self.cascades[0];
        let n = first.n;
        let inv_dx = n as f32 / first.patch;
        let values = &self.foam.values;
        let mask = n as i64 - 1;
        let aligned = self.aligned_index(grid);
        out.par_chunks_mut(grid.verts_x()).enumerate().for_each(|(j, row)| {
            if let Some(a) = aligned {
                let jj = (a.sample(0, j).1 & mask) as usize * n;
                for (i, o) in row.iter_mut().enumerate() {
                    *o = values[jj + (a.sample(i, j).0 & mask) as usize];
                }
                return;
            }
            for (i, o) in row.iter_mut().enumerate() {
                let r = grid.rest_position(i, j) * inv_dx;
                let (fu, fv) = (fast_floor(r.x), fast_floor(r.y));
                let (tx, tz) = (r.x - fu, r.y - fv);
                let (i0, j0) = ((fu as i64 & mask) as usize, (fv as i64 & mask) as usize);
                let (i1, j1) = ((i0 + 1) & mask as usize, (j0 + 1) & mask as usize);
                let top = values[j0 * n + i0] * (1.0 - tx) + values[j0 * n + i1] * tx;
                let bottom = values[j1 * n + i0] * (1.0 - tx) + values[j1 * n + i1] * tx;
                *o = top * (1.0 - tz) + bottom * tz;
            }
        });
        true
    }
}

#[cfg(test)]
mod tabulated_tests;
#[cfg(test)]
mod tests;
