//! One periodic patch of the FFT ocean: its initial spectrum, and the synthesis of its eight fields
//! for a time t by inverse FFTs.
//!
//! ## Spectrum layout
//! The N x N wave vectors are `k = (nx, nz) 2π/L` with `nx, nz` in (-N/2, N/2) (FFT order: index i
//! holds `i` below N/2 and `i - N` above). The Nyquist row and column (`±N/2`) are left empty so the
//! set of wave vectors is symmetric under `k -> -k`. The fields are real, so their spectra are
//! Hermitian, `h(-k) = conj(h(k))`: only the rows `nx` in [0, N/2) are evolved; the others are read
//! from their mirror.
//!
//! ## Synthesis (Tessendorf 2001 §3.4; paper 003 §1.2.2), with a sign chosen for travel along k
//! `h(k, t) = h0(k) e^{-i w t} + conj(h0(-k)) e^{+i w t}` makes the energy at k travel *along* k
//! (Tessendorf's `e^{+i w t}` first sends it along -k; the spreading is defined in the direction of
//! travel, so swell flips the sign). From h the spectral derivatives give the other fields:
//!
//! ```text
//! height      h                 choppy      Dx = λ i kx/k h,   Dz = λ i kz/k h
//! slopes      hx = i kx h,      hz = i kz h
//! Jacobian    Dxx = -λ kx²/k h, Dzz = -λ kz²/k h,  Dxz = -λ kx kz/k h
//! ```
//!
//! Tessendorf's displacement is `-i k/k h`; with it a positive λ moves water away from crests and
//! rounds them. swell uses `+i k/k h` so that a positive choppiness sharpens crests, like a Gerstner
//! wave (for `h = A cos(kx)` the displacement is `-λ A sin(kx)`; the tests check the sharpening).
//!
//! Eight real fields are packed two per complex transform (`A + iB`: the real and imaginary parts
//! of the inverse transform are A and B, because both spectra are Hermitian): four complex N x N
//! inverse transforms per step. Each is N transforms over kz (one per kx) followed by N over kx
//! (one per z). The four pairs' spectra are, for a row of fixed kx and with `g = λ h/|k|`:
//!
//! ```text
//! (h, Dx)    = h - kx g          (Dz, hx)   = i kz g - kx h
//! (hz, Dxx)  = i kz h - kx² (i g) (Dzz, Dxz) = -kz² g - kx (i kz g)
//! ```
//!
//! so each is a sum of five **bases** `h, g, i kz g, i kz h, -kz² g` times factors that depend on
//! kx alone (`i` included), and a factor constant along a row commutes with the transform over
//! kz. So only the five bases are transformed over kz, and only for the stored rows kx >= 0: each
//! base's transform over kz at -kx is the conjugate of its transform at kx
//! (`B(-kx, z) = conj(B(kx, z))`, because `h(-k) = conj(h(k))` and each base's multiplier is even
//! or odd in kz to match), so the row pass builds the pairs' rows kx and -kx from the same five.
//! That is 5 transforms of length N per stored row where transforming each pair's rows kx and -kx
//! would take 8: 6.5 N transforms per step instead of 8 N, and above all a column buffer of
//! 2.5 N² values instead of 4 N² (21 MB instead of 34 MB at 1024²).
//!
//! ## Two passes over memory per step
//! The step is two parallel passes (two meetings of the threads), each fusing what used to be
//! passes of their own, because at 1024² the buffers do not fit in cache and passes over memory,
//! not arithmetic, set the time:
//! - **column pass**: a task owns 8 stored rows m in [0, N/2); it evolves `h(k, t)` of row m into
//!   an L1 scratch row, writes the row's five bases from it into the column buffer (`λ/|k|` comes
//!   from a table, so no square root or division) and transforms them there over kz. `h(k, t)` is
//!   never stored.
//! - **row pass**: a task owns 16 output rows; it gathers them out of the column buffer into its
//!   thread's block, combining the bases into the four pairs at kx and at -kx (`x - f y`, or
//!   `x - f (i y)` for (hz, Dxx), conjugated at -kx, see [`gather_rows`]), transforms them over kx there and copies them to
//!   [`Cascade::fields`], and, for the first cascade, updates their foam from the Jacobian terms
//!   it has just written.
//!
//! Scratch buffers belong to threads, not tasks, so the gathered block stays in the thread's L2
//! from one task to the next (a block per task would be one more 34 MB buffer to stream through
//! at 1024²).

use std::f64::consts::TAU;
use std::sync::{Arc, Mutex, MutexGuard, PoisonError};

use rayon::prelude::*;
use rustfft::num_complex::Complex32;
use rustfft::{Fft, FftPlanner};

use super::evolve_simd;
use super::fill_simd;
use super::foam_simd;
use super::jacobian;
use super::transpose_simd;
use crate::math::{reduce_turns, sin_cos_turns};
use crate::spectrum::{loop_cycles, DirectionalSpectrum};
use crate::water::foam::{foam_coverage, FoamUpdate};

/// Rows handled by one parallel task of the row pass.
const ROWS_PER_TASK: usize = 16;

/// Padding (complex values) after each slot of the column buffer. Its slot length is otherwise
/// a power of two, so the row pass's reads down a column would all fall in the same cache set;
/// 16 values (128 bytes) move successive slots to different sets and keep slots aligned.
pub(super) const WORK_ROW_PADDING: usize = 16;

/// Stored rows handled by one task of the column pass: with their mirror rows, as many rows as
/// [`ROWS_PER_TASK`], so both passes have N / 16 tasks.
const STORED_ROWS_PER_TASK: usize = ROWS_PER_TASK / 2;

/// Padding (complex values) after each row of a thread's gathered block: rows N apart (a
/// multiple of 4 KB from N = 512) would fall in the same L1 set, more rows than it has ways.
pub(super) const BLOCK_PADDING: usize = 8;

/// Bases transformed over kz per stored row (module doc), in this order in the column buffer:
/// `h`, `g = λ h/|k|`, `i kz g`, `i kz h`, `-kz² g`.
pub(super) const BASES: usize = 5;

/// For each pair (`PAIR_*` order), the bases (x, y) it combines, as `x - f y` (pair
/// [`PAIR_HZ_DXX`]: `x - f (i y)`), f from [`pair_factor`].
pub(super) const PAIR_BASES: [(usize, usize); 4] = [(0, 1), (2, 0), (3, 1), (4, 2)];

/// Index of each packed field pair in [`Cascade::fields`]: (real part, imaginary part).
pub(super) const PAIR_H_DX: usize = 0;
/// (Dz, hx).
#[cfg_attr(not(test), allow(dead_code))]
pub(super) const PAIR_DZ_HX: usize = 1;
/// (hz, Dxx).
pub(super) const PAIR_HZ_DXX: usize = 2;
/// (Dzz, Dxz).
pub(super) const PAIR_DZZ_DXZ: usize = 3;

/// One periodic patch: spectrum, buffers and FFT plan.
pub(super) struct Cascade {
    /// Grid side N (power of two).
    pub n: usize,
    /// Patch side L (m).
    pub patch: f32,
    /// Expected height variance of the waves this patch holds: `sum F(k) dk²` (m²).
    pub variance: f64,
    /// Initial amplitudes h0(k) (m), rows nx in [0, N/2), all N columns.
    h0: Vec<Complex32>,
    /// `conj(h0(-k))` at k, same layout, so evolving needs no look-up of the mirror.
    h0_mirror: Vec<Complex32>,
    /// `w(k) / 2π` (Hz), quantised when the sea loops; same layout.
    cycles: Vec<f64>,
    /// `λ / |k|` (m, λ the choppiness) at each stored entry, 0 at k = 0: the time-independent part
    /// of the spectral multipliers, so filling the spectra needs no square root or division.
    lambda_over_k: Vec<f32>,
    /// Time (s) of the last [`Cascade::column_pass`].
    time: f64,
    /// Column pass output: the [`BASES`] bases of each stored row transformed over kz, laid out
    /// by [`WorkLayout`].
    work: CacheAligned,
    layout: WorkLayout,
    /// The four packed field pairs, `[z][x]`: sample (i, j) sits at local (i L/N, j L/N).
    pub fields: [Vec<Complex32>; 4],
    /// kx or kz (rad/m) of each FFT index (the same table for both).
    wavenumbers: Vec<f32>,
    fft: Arc<dyn Fft<f32>>,
    /// One [`ThreadScratch`] per thread of the largest pool that has stepped the sea (allocated by
    /// the first step, grown by a step in a larger pool), so a thread's buffers stay in its caches
    /// from task to task.
    scratch: Vec<Mutex<ThreadScratch>>,
    /// Whether the CPU has AVX2, checked once in `new`.
    avx2: bool,
}

/// Buffers of one thread of the pool, used by every task of either pass that the thread runs.
struct ThreadScratch {
    /// rustfft's scratch.
    fft: Vec<Complex32>,
    /// `h(k, t)` of the stored row being transformed (n values).
    h: Vec<Complex32>,
    /// The row pass's four pairs' gathered rows, pair p's row z at `(p R + z) (n + BLOCK_PADDING)`,
    /// transformed here, then copied into the fields.
    block: CacheAligned,
    /// The row's phases in turns, reduced to [-1/2, 1/2], and their sines and cosines (n each).
    turns: Vec<f32>,
    sin: Vec<f32>,
    cos: Vec<f32>,
}

impl ThreadScratch {
    fn new(n: usize, fft: &dyn Fft<f32>) -> Self {
        Self {
            fft: vec![Complex32::default(); fft.get_inplace_scratch_len()],
            h: vec![Complex32::default(); n],
            turns: vec![0.0; n],
            sin: vec![0.0; n],
            cos: vec![0.0; n],
            block: CacheAligned::zeros(4 * ROWS_PER_TASK * (n + BLOCK_PADDING)),
        }
    }
}

/// A buffer of complex values whose first value starts a cache line (64 bytes). The allocator
/// only promises 16 bytes, and the gather's 32-byte loads and stores then split a cache line
/// every other time, or not, depending on where a buffer happened to land: the row pass's time
/// varied by about 10 % between builds that differed only in when a buffer was allocated.
struct CacheAligned {
    data: Vec<Complex32>,
    start: usize,
    len: usize,
}

impl CacheAligned {
    /// `len` zeros, the first at a 64-byte boundary.
    fn zeros(len: usize) -> Self {
        // 8 values are 64 bytes: the boundary is at most 7 values in.
        let data = vec![Complex32::default(); len + 8];
        let start = data.as_ptr().align_offset(64);
        assert!(start < 8, "Complex32 is 8 bytes");
        Self { data, start, len }
    }

    fn as_slice(&self) -> &[Complex32] {
        &self.data[self.start..self.start + self.len]
    }

    fn as_mut_slice(&mut self) -> &mut [Complex32] {
        &mut self.data[self.start..self.start + self.len]
    }
}

/// The calling thread's buffers, out of one per thread of the pool (see
/// [`Cascade::fit_scratch_to_pool`]). The lock is never contended then; it keeps the code safe if a
/// pass ever runs with more threads than buffers (they would take turns).
fn thread_scratch(buffers: &[Mutex<ThreadScratch>]) -> MutexGuard<'_, ThreadScratch> {
    let i = rayon::current_thread_index().unwrap_or(0) % buffers.len();
    buffers[i].lock().unwrap_or_else(PoisonError::into_inner)
}

/// Wave-vector integer of FFT index i on a grid of n: i below n/2, i - n above.
fn signed_index(i: usize, n: usize) -> i32 {
    if i < n / 2 {
        i as i32
    } else {
        i as i32 - n as i32
    }
}

/// SplitMix64's finaliser (Steele, Lea and Flood 2014): a bijective 64-bit mix.
fn mix64(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// Two independent standard normal numbers for wave vector (nx, nz) of cascade `cascade`.
///
/// They depend only on (seed, cascade, nx, nz), through SplitMix64 hashes and the Box-Muller
/// transform, so a finer grid keeps every wave the coarser grid had, in place, and the result does
/// not depend on the order in which wave vectors are visited (or on threads).
pub(super) fn wave_gaussians(seed: u32, cascade: u32, nx: i32, nz: i32) -> (f64, f64) {
    let base = mix64(u64::from(seed) ^ mix64(0x9e37_79b9_7f4a_7c15 ^ u64::from(cascade)));
    let key = mix64(base ^ ((u64::from(nx as u32) << 32) | u64::from(nz as u32)));
    let bits = mix64(key ^ 0x6a09_e667_f3bc_c909);
    // Uniforms in (0, 1] and [0, 1) from the top 53 bits.
    let u1 = ((key >> 11) as f64 + 1.0) / (1u64 << 53) as f64;
    let u2 = (bits >> 11) as f64 / (1u64 << 53) as f64;
    let r = (-2.0 * u1.ln()).sqrt();
    let (s, c) = (TAU * u2).sin_cos();
    (r * c, r * s)
}

/// One row of the half spectrum while it is set up: h0, its mirror, frequencies, variance.
type SetupRow = (Vec<Complex32>, Vec<Complex32>, Vec<f64>, f64);

/// What a cascade needs to know to set itself up.
pub(super) struct CascadeSetup<'a> {
    pub spectrum: &'a DirectionalSpectrum,
    pub n: usize,
    pub patch: f32,
    /// Band of wavenumbers this cascade holds: `k_lo <= |k| < k_hi` (rad/m).
    pub band: (f64, f64),
    pub seed: u32,
    pub index: u32,
    pub choppiness: f32,
    pub loop_period: Option<f64>,
}

impl Cascade {
    pub fn new(s: &CascadeSetup) -> Self {
        let n = s.n;
        let half = n / 2;
        let dk = TAU / f64::from(s.patch);
        let in_band = |nx: i32, nz: i32| {
            let k = f64::from(nx).hypot(f64::from(nz)) * dk;
            let nyquist = nx.unsigned_abs() as usize >= half || nz.unsigned_abs() as usize >= half;
            k > 0.0 && !nyquist && k >= s.band.0 && k < s.band.1
        };
        // E|h0|² = F dk² / 2: a real cosine of variance F dk² has complex amplitudes of mean square
        // F dk² / 4 at k and at -k, and each k's coefficient sums two of them. (Tessendorf's
        // sqrt(P/2) would double the variance of a spectrum normalised so that its integral is m0.)
        let amplitude = |nx: i32, nz: i32, density: f64| {
            let (xr, xi) = wave_gaussians(s.seed, s.index, nx, nz);
            let scale = (density * dk * dk).sqrt() / 2.0;
            Complex32::new((xr * scale) as f32, (xi * scale) as f32)
        };
        // Rows in parallel (each entry depends only on its wave vector), summed in row order.
        let rows: Vec<SetupRow> = (0..half)
            .into_par_iter()
            .map(|a| {
                let nx = signed_index(a, n);
                let mut row = (Vec::with_capacity(n), Vec::with_capacity(n), Vec::with_capacity(n), 0.0);
                for b in 0..n {
                    let nz = signed_index(b, n);
                    let (kx, kz) = (f64::from(nx) * dk, f64::from(nz) * dk);
                    let (mut amp, mut mirror) = (Complex32::default(), Complex32::default());
                    if in_band(nx, nz) {
                        let (f_plus, f_minus) = (s.spectrum.density(kx, kz), s.spectrum.density(-kx, -kz));
                        amp = amplitude(nx, nz, f_plus);
                        mirror = amplitude(-nx, -nz, f_minus).conj();
                        // Rows nx > 0 stand for themselves and their mirror; row 0 holds both.
                        row.3 += (f_plus + f_minus) * dk * dk * if nx == 0 { 0.5 } else { 1.0 };
                    }
                    row.0.push(amp);
                    row.1.push(mirror);
                    let w = s.spectrum.dispersion.omega_f64(kx.hypot(kz));
                    row.2.push(match s.loop_period {
                        // A whole number of cycles per loop (the nearest, at least one), so every
                        // wave repeats after T; see `spectrum/loop_period.rs`.
                        Some(t) => loop_cycles(w, t) / t,
                        None => w / TAU,
                    });
                }
                row
            })
            .collect();
        let mut h0 = Vec::with_capacity(half * n);
        let mut h0_mirror = Vec::with_capacity(half * n);
        let mut cycles = Vec::with_capacity(half * n);
        let mut variance = 0.0;
        for (a, m, c, v) in rows {
            h0.extend(a);
            h0_mirror.extend(m);
            cycles.extend(c);
            variance += v;
        }
        let fft = FftPlanner::new().plan_fft_inverse(n);
        let wavenumbers: Vec<f32> = (0..n).map(|i| signed_index(i, n) as f32 * dk as f32).collect();
        let lambda = s.choppiness;
        let lambda_over_k = (0..half * n)
            .map(|idx| {
                let (kx, kz) = (wavenumbers[idx / n], wavenumbers[idx % n]);
                let k2 = kx * kx + kz * kz;
                if k2 > 0.0 {
                    lambda / k2.sqrt()
                } else {
                    0.0
                }
            })
            .collect();
        let zero = || vec![Complex32::default(); n * n];
        Self {
            n,
            patch: s.patch,
            variance,
            h0,
            h0_mirror,
            cycles,
            lambda_over_k,
            time: f64::NAN,
            work: CacheAligned::zeros(WorkLayout::new(n).len()),
            layout: WorkLayout::new(n),
            fields: [zero(), zero(), zero(), zero()],
            wavenumbers,
            fft,
            // Allocated by the first step, for the pool that runs it (`fit_scratch_to_pool`).
            scratch: Vec::new(),
            avx2: fill_simd::available(),
        }
    }

    /// Calls `visit(kx, kz, energy)` for every wave the cascade holds, `energy` (m²) being the
    /// variance that the wave travelling along `(kx, kz)` (rad/m) adds to the height: `2 |h0(k)|²`
    /// (its conjugate at −k carries the other half). The realised spectrum, exactly.
    pub fn for_each_wave(&self, mut visit: impl FnMut(f64, f64, f64)) {
        let n = self.n;
        for a in 0..n / 2 {
            let kx = f64::from(self.wavenumbers[a]);
            // Row 0 holds each of its waves twice (at kz and, as the mirror, at −kz).
            let weight = if a == 0 { 1.0 } else { 2.0 };
            for b in 0..n {
                let kz = f64::from(self.wavenumbers[b]);
                let idx = a * n + b;
                let (e, m) = (f64::from(self.h0[idx].norm_sqr()), f64::from(self.h0_mirror[idx].norm_sqr()));
                if e > 0.0 {
                    visit(kx, kz, weight * e);
                }
                if m > 0.0 {
                    visit(-kx, -kz, weight * m);
                }
            }
        }
    }

    /// Appends `(k rad/m, slope variance)` for every stored wave vector: `k² (|h0(k)|² + |h0(-k)|²)`,
    /// counted twice for the rows that stand for their mirror too (as the synthesis sums them).
    pub fn slope_components(&self, out: &mut Vec<(f32, f32)>) {
        let dk = std::f64::consts::TAU / f64::from(self.patch);
        for (nx, nz, h0, hm, _) in self.half_spectrum() {
            let energy = f64::from(h0.norm_sqr()) + f64::from(hm.norm_sqr());
            if energy == 0.0 {
                continue;
            }
            let k = (f64::from(nx) * dk).hypot(f64::from(nz) * dk);
            let w = if nx == 0 { 1.0 } else { 2.0 };
            out.push((k as f32, (w * k * k * energy) as f32));
        }
    }

    /// Multiplies every amplitude by `factor` (>= 0), and the expected variance by its square.
    pub fn scale_amplitudes(&mut self, factor: f64) {
        let f = factor as f32;
        for v in self.h0.iter_mut().chain(self.h0_mirror.iter_mut()) {
            *v *= f;
        }
        self.variance *= factor * factor;
    }

    /// Pass 1, for time `t` (s): evolves `h(k, t)` of each stored row and transforms the row's
    /// five bases over kz, into [`Cascade::work`]. Each `h(k, t)` is computed once, used for all
    /// five, and never stored: the evolution costs no pass over memory of its own.
    pub fn column_pass(&mut self, t: f64) {
        let n = self.n;
        self.fit_scratch_to_pool();
        let layout = self.layout;
        let spec = Spectrum {
            n,
            t,
            h0: &self.h0,
            hm: &self.h0_mirror,
            cycles: &self.cycles,
            lambda_over_k: &self.lambda_over_k,
            kk: &self.wavenumbers,
            avx2: self.avx2,
        };
        let (fft, buffers) = (&self.fft, &self.scratch[..]);
        let per_task = STORED_ROWS_PER_TASK;
        // The Nyquist row's slots, after the stored rows', are left alone.
        self.work.as_mut_slice()[..layout.slot(n / 2, 0, 0)]
            .par_chunks_mut(per_task * BASES * layout.stride)
            .enumerate()
            .for_each(|(task, chunk)| {
                let mut scratch = thread_scratch(buffers);
                for (i, slots) in chunk.chunks_exact_mut(BASES * layout.stride).enumerate() {
                    let m = task * per_task + i;
                    spec.evolve_row(m, &mut scratch);
                    let mut split = slots.chunks_exact_mut(layout.stride).map(|slot| &mut slot[..n]);
                    spec.fill_bases(m, &scratch.h, std::array::from_fn(|_| split.next().expect("BASES slots")));
                    for slot in slots.chunks_exact_mut(layout.stride) {
                        fft.process_with_scratch(&mut slot[..n], &mut scratch.fft);
                    }
                }
            });
        self.time = t;
    }

    /// Grows the per-thread scratch to the current pool's thread count: allocates at the first
    /// step and when a larger pool than before steps the sea, never otherwise.
    fn fit_scratch_to_pool(&mut self) {
        let threads = rayon::current_num_threads();
        while self.scratch.len() < threads {
            self.scratch.push(Mutex::new(ThreadScratch::new(self.n, self.fft.as_ref())));
        }
    }

    /// Pass 2: gathers `[kx][z]` into `[z][kx]` for a task's rows, combining the bases into the
    /// four pairs, and transforms each row over kx, into [`Cascade::fields`]; with `foam`, updates
    /// the foam of the rows just transformed while they are still in cache (the Jacobian needs only
    /// its own sample).
    pub fn row_pass(&mut self, foam: Option<FoamUpdate>) {
        let n = self.n;
        let rows = WorkLayout::ROWS;
        let (work, layout, fft, kx, avx2) =
            (self.work.as_slice(), self.layout, &self.fft, &self.wavenumbers[..=n / 2], self.avx2);
        let [f0, f1, f2, f3] = &mut self.fields;
        let chunk = rows * n;
        let tasks = f0
            .par_chunks_mut(chunk)
            .zip(f1.par_chunks_mut(chunk))
            .zip(f2.par_chunks_mut(chunk))
            .zip(f3.par_chunks_mut(chunk));
        let buffers = &self.scratch[..];
        let body = |task: usize, out: [&mut [Complex32]; 4]| {
            let mut scratch = thread_scratch(buffers);
            let ThreadScratch { block, fft: fft_scratch, .. } = &mut *scratch;
            let block = block.as_mut_slice();
            let mut gathered = false;
            #[cfg(target_arch = "x86_64")]
            if avx2 {
                // SAFETY: `avx2` is set only when the CPU reports AVX2.
                unsafe { transpose_simd::gather_rows(work, &layout, kx, task, block) };
                gathered = true;
            }
            if !gathered {
                gather_rows(work, &layout, kx, task, block);
            }
            let gathered_rows = block.chunks_exact_mut(n + BLOCK_PADDING);
            for (row, field) in gathered_rows.zip(out.into_iter().flat_map(|f| f.chunks_exact_mut(n))) {
                // In place in the thread's (cached) block, then one sequential copy: the fields'
                // lines are written whole and in order, which the out-of-place transform's
                // scattered last stage does not do.
                fft.process_with_scratch(&mut row[..n], fft_scratch);
                field.copy_from_slice(&row[..n]);
            }
        };
        match foam {
            None => tasks.enumerate().for_each(|(task, (((o0, o1), o2), o3))| {
                body(task, [o0, o1, o2, o3]);
            }),
            Some(FoamUpdate { out, first, second, weights: w }) => {
                tasks.zip(out.par_chunks_mut(chunk)).enumerate().for_each(|(task, ((((o0, o1), o2), o3), foam))| {
                    body(task, [&mut *o0, &mut *o1, &mut *o2, &mut *o3]);
                    let written = [&*o0, &*o1, &*o2, &*o3];
                    let (dxx, jac) = (written[PAIR_HZ_DXX], written[PAIR_DZZ_DXZ]);
                    let span = task * chunk..task * chunk + foam.len();
                    let (first, second) = (first.map(|s| &s[span.clone()]), second.map(|s| &s[span]));
                    // Foam follows the Jacobian of the rows this task has just written.
                    let mut done = 0;
                    #[cfg(target_arch = "x86_64")]
                    if avx2 {
                        // SAFETY: `avx2` is set only when the CPU reports AVX2.
                        done = unsafe { foam_simd::update(foam, first, second, dxx, jac, &w) };
                    }
                    for i in done..foam.len() {
                        let a = first.map_or(foam[i], |s| s[i]);
                        let b = second.map_or(0.0, |s| s[i]);
                        let coverage =
                            foam_coverage(jacobian(dxx[i].im, jac[i].re, jac[i].im), w.threshold, w.inv_spread);
                        foam[i] = w.apply(coverage, a, b);
                    }
                })
            }
        }
    }

    /// Wave-vector integers and the evolution data of stored entry `idx` (tests and point queries).
    pub(super) fn half_spectrum(&self) -> impl Iterator<Item = (i32, i32, Complex32, Complex32, f64)> + '_ {
        let n = self.n;
        (0..self.h0.len()).map(move |idx| {
            let (a, b) = (idx / n, idx % n);
            (signed_index(a, n), signed_index(b, n), self.h0[idx], self.h0_mirror[idx], self.cycles[idx])
        })
    }

    /// Per-thread scratch buffers allocated so far.
    #[cfg(test)]
    pub(super) fn scratch_buffers(&self) -> usize {
        self.scratch.len()
    }

    /// `h(k, t)` of the last [`Cascade::column_pass`] at wave-vector integers (nx, nz), any sign,
    /// computed as the pass computes it.
    #[cfg(test)]
    pub(super) fn evolved(&self, nx: i32, nz: i32) -> Complex32 {
        let n = self.n as i32;
        let (a, b) = (nx.rem_euclid(n) as usize, nz.rem_euclid(n) as usize);
        let half = self.n / 2;
        let at = |idx: usize| evolve_one(self.h0[idx], self.h0_mirror[idx], self.cycles[idx], self.time);
        if a < half {
            at(a * self.n + b)
        } else if a == half {
            Complex32::default()
        } else {
            at((self.n - a) * self.n + (self.n - b) % self.n).conj()
        }
    }
}

/// `h(k, t) = a e^{-iφ} + b e^{iφ}`, `φ = 2π f t`, for `a = h0(k)`, `b = conj(h0(-k))`, the
/// frequency f (Hz) and time t (s). The phase is reduced in f64 turns, so the sea stays exact for
/// any t up to about 2^51 / f.
pub(super) fn evolve_one(a: Complex32, b: Complex32, f: f64, t: f64) -> Complex32 {
    let (s, c) = sin_cos_turns(reduce_turns(f * t));
    combine(a, b, s, c)
}

/// `a e^{-iφ} + b e^{iφ}` from `(sin φ, cos φ)`.
#[inline(always)]
fn combine(a: Complex32, b: Complex32, s: f32, c: f32) -> Complex32 {
    // Grouped so that h(-k) = conj(h(k)) holds bit for bit in the self-mirrored row nx = 0.
    Complex32::new((a.re * c + a.im * s) + (b.re * c - b.im * s), (a.im * c - a.re * s) + (b.im * c + b.re * s))
}

/// What the column pass reads: the stored half spectrum and its time-independent tables.
struct Spectrum<'a> {
    n: usize,
    /// Time of the step (s).
    t: f64,
    h0: &'a [Complex32],
    hm: &'a [Complex32],
    cycles: &'a [f64],
    lambda_over_k: &'a [f32],
    /// kx or kz (rad/m) of each FFT index.
    kk: &'a [f32],
    /// Whether the CPU has AVX2 (the fill then uses `fill_simd`).
    #[cfg_attr(not(target_arch = "x86_64"), allow(dead_code))]
    avx2: bool,
}

impl Spectrum<'_> {
    /// `h(k, t)` of stored row m (kx index m < N/2) into `scratch.h` (n values).
    ///
    /// Three loops over the row, each over plain arrays without calls, so the compiler vectorises
    /// them: the phases in f64 turns reduced to f32, their sines and cosines, and the sum of the
    /// two rotated amplitudes. Same arithmetic per value as a single loop would do.
    #[inline(always)]
    fn evolve_row(&self, m: usize, scratch: &mut ThreadScratch) {
        let r = m * self.n..(m + 1) * self.n;
        let t = self.t;
        let ThreadScratch { h, turns, sin, cos, .. } = scratch;
        #[cfg(target_arch = "x86_64")]
        if self.avx2 {
            let (h0, hm, cycles) = (&self.h0[r.clone()], &self.hm[r.clone()], &self.cycles[r]);
            // SAFETY: `avx2` is set only when the CPU reports AVX2.
            let done = unsafe { evolve_simd::evolve(h, h0, hm, cycles, t) };
            for b in done..self.n {
                h[b] = evolve_one(h0[b], hm[b], cycles[b], t);
            }
            return;
        }
        for (o, &f) in turns.iter_mut().zip(&self.cycles[r.clone()]) {
            *o = reduce_turns(f * t);
        }
        for ((&c, s), co) in turns.iter().zip(sin.iter_mut()).zip(cos.iter_mut()) {
            (*s, *co) = sin_cos_turns(c);
        }
        for ((((o, &a), &b), &s), &c) in h.iter_mut().zip(&self.h0[r.clone()]).zip(&self.hm[r]).zip(&*sin).zip(&*cos) {
            *o = combine(a, b, s, c);
        }
    }

    /// The five bases of stored row m (kx index m < N/2), from that row's `h(k, t)`.
    #[inline(always)]
    fn fill_bases(&self, m: usize, h: &[Complex32], out: [&mut [Complex32]; BASES]) {
        let n = self.n;
        let l = &self.lambda_over_k[m * n..(m + 1) * n];
        let (h, kk) = (&h[..n], &self.kk[..n]);
        let [o0, o1, o2, o3, o4] = out;
        let mut out = [&mut o0[..n], &mut o1[..n], &mut o2[..n], &mut o3[..n], &mut o4[..n]];
        let mut start = 0;
        #[cfg(target_arch = "x86_64")]
        if self.avx2 {
            let [o0, o1, o2, o3, o4] = &mut out;
            // SAFETY: `avx2` is set only when the CPU reports AVX2.
            start = unsafe { fill_simd::fill([o0, o1, o2, o3, o4], h, kk, l) };
        }
        for b in start..n {
            write_bases(&mut out, b, h[b], kk[b], l[b]);
        }
    }
}

/// Writes entry b of the five bases from `h = h(k, t)`, the column's kz and `l = λ/|k|` (0 at
/// k = 0): `h`, `g = l h`, `i kz g`, `i kz h`, `i kz (i kz g) = -kz² g`.
///
/// The column pass uses it for the entries `fill_simd::fill` leaves (all of them without AVX2),
/// which computes the same values, by the same operations, four entries at a time.
#[inline(always)]
pub(super) fn write_bases(out: &mut [&mut [Complex32]; BASES], b: usize, h: Complex32, kz: f32, l: f32) {
    let g = Complex32::new(h.re * l, h.im * l);
    let c = i_times(kz, g);
    out[0][b] = h;
    out[1][b] = g;
    out[2][b] = c;
    out[3][b] = i_times(kz, h);
    out[4][b] = i_times(kz, c);
}

/// `i k v` for a real k.
#[inline(always)]
pub(super) fn i_times(k: f32, v: Complex32) -> Complex32 {
    Complex32::new(-(v.im * k), v.re * k)
}

/// The factor f of pair p (see [`PAIR_BASES`]) in the row of wavenumber kx (rad/m) of a stored row
/// m, or, with `mirror`, in its mirror row -kx, where the pair is `conj(x - f y)` of the stored
/// row's bases (for a row constant c, the mirror row's pair is `conj(conj(c(-kx)) B)`).
#[inline(always)]
pub(super) fn pair_factor(p: usize, kx: f32, mirror: bool) -> f32 {
    let f = if p == PAIR_HZ_DXX { kx * kx } else { kx };
    if mirror {
        -f
    } else {
        f
    }
}

/// Where the column pass puts each base value: one slot of `stride = N + WORK_ROW_PADDING`
/// values per stored row m and base j, at `(m BASES + j) stride`, so a task of the column pass
/// owns a contiguous chunk and transforms its bases in place. The Nyquist row m = N/2 is empty;
/// its slots, after the stored rows', stay zero, so the row pass reads kx = ±N/2 like any other.
#[derive(Clone, Copy, Debug)]
pub(super) struct WorkLayout {
    /// Slot length (complex values).
    pub stride: usize,
}

impl WorkLayout {
    /// R: output rows per row-pass task.
    pub const ROWS: usize = ROWS_PER_TASK;

    /// The layout for grid side n, a power of two >= 16 (`FFT_GRID_RANGE`), so R divides N and the
    /// column pass's stored rows per task divide N/2.
    pub fn new(n: usize) -> Self {
        assert!(n.is_power_of_two() && n >= Self::ROWS, "FFT grid {n}");
        Self { stride: n + WORK_ROW_PADDING }
    }

    /// Length of the column buffer: N/2 + 1 rows of slots.
    pub fn len(&self) -> usize {
        let n = self.stride - WORK_ROW_PADDING;
        self.slot(n / 2 + 1, 0, 0)
    }

    /// Offset of base j of stored row m (in [0, N/2]) at the first output row of row-pass task c.
    #[inline(always)]
    pub fn slot(&self, m: usize, j: usize, c: usize) -> usize {
        (m * BASES + j) * self.stride + c * Self::ROWS
    }
}

/// Writes the output rows of row-pass task c of the four pairs into `block` (pair p's row z,
/// column kx index a at `(p R + z) (n + BLOCK_PADDING) + a`) from the column buffer `work`, kx
/// (rad/m) of stored row m at `kx[m]`, m in [0, N/2]: column m < N/2 is `x - f y` of row m's
/// bases, column N - m (m >= 1) is its conjugate with the mirror factor.
///
/// `transpose_simd::gather_rows` computes the same values by the same operations in 4 x 4 blocks.
pub(super) fn gather_rows(work: &[Complex32], layout: &WorkLayout, kx: &[f32], c: usize, block: &mut [Complex32]) {
    let (half, rows) = (kx.len() - 1, WorkLayout::ROWS);
    let n = 2 * half;
    let stride = n + BLOCK_PADDING;
    let base = |m: usize, j: usize| &work[layout.slot(m, j, c)..][..rows];
    for (p, block) in block.chunks_exact_mut(rows * stride).enumerate() {
        let (x, y) = PAIR_BASES[p];
        let term = |v: Complex32, f: f32| if p == PAIR_HZ_DXX { i_times(f, v) } else { v * f };
        for m in 0..=half {
            let (xs, ys) = (base(m, x), base(m, y));
            if m < half {
                let f = pair_factor(p, kx[m], false);
                for z in 0..rows {
                    block[z * stride + m] = xs[z] - term(ys[z], f);
                }
            }
            if m > 0 {
                let f = pair_factor(p, kx[m], true);
                for z in 0..rows {
                    block[z * stride + n - m] = (xs[z] - term(ys[z], f)).conj();
                }
            }
        }
    }
}
