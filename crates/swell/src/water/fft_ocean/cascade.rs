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
//! inverse FFTs per step. Each 2-D transform is N row FFTs over the kz index (rows in parallel), a
//! blocked transpose fused with N row FFTs over the kx index. The four pairs go through each pass
//! together (one parallel pass of column transforms, one of row transforms), which costs a column
//! buffer per pair (4 x N (N + 16) complex values). Buffers are allocated in `new`.
//!
//! ## Two passes over memory per step
//! The step is two parallel passes (two meetings of the threads), each fusing what used to be
//! passes of their own, because at 1024² the buffers do not fit in cache and passes over memory,
//! not arithmetic, set the time:
//! - **column pass**: a task owns stored rows m and their mirror rows N - m (adjacent slots of the
//!   column buffers); it evolves `h(k, t)` of row m into an L1 scratch row, fills both rows of the
//!   four packed spectra from it (`λ/|k|` comes from a table, so no square root or division), and
//!   transforms them over kz. `h(k, t)` is never stored.
//! - **row pass**: a task owns 16 output rows; it transposes them out of the column buffers, four kx
//!   at a time, transforms them over kx and, for the first cascade, updates their foam from the
//!   Jacobian terms it has just written.

use std::f64::consts::TAU;
use std::sync::Arc;

use rayon::prelude::*;
use rustfft::num_complex::Complex32;
use rustfft::{Fft, FftPlanner};

use super::evolve_simd;
use super::fill_simd;
use super::foam_simd;
use super::jacobian;
use super::transpose_simd;
use crate::math::{reduce_turns, sin_cos_turns};
use crate::spectrum::DirectionalSpectrum;
use crate::water::foam_coverage;

/// Rows handled by one parallel task of the row pass; each task owns one [`TaskScratch`].
const ROWS_PER_TASK: usize = 16;

/// Stored rows (each with its mirror row, so as many rows as [`ROWS_PER_TASK`]) handled by one
/// task of the column pass.
const PAIRS_PER_TASK: usize = ROWS_PER_TASK / 2;

/// Padding (complex values) after each row of the column-pass buffer. Its row length is otherwise
/// a power of two, so the transpose's reads down a column would all fall in the same cache set;
/// 16 values (128 bytes) move successive rows to different sets and keep rows aligned.
const WORK_ROW_PADDING: usize = 16;

/// Index of each packed field pair in [`Cascade::fields`]: (real part, imaginary part).
pub(super) const PAIR_H_DX: usize = 0;
/// (Dz, hx).
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
    /// Column pass output of each field pair, one slot (row `n + WORK_ROW_PADDING` long) per kx
    /// index, slots in the order kx index 0, N/2, 1, N-1, 2, N-2, ... so that a task of the column
    /// pass owns a contiguous chunk holding rows m and N - m together.
    work: [Vec<Complex32>; 4],
    /// Offset in `work` of the slot of each kx index.
    slot_offsets: Vec<usize>,
    /// The four packed field pairs, `[z][x]`: sample (i, j) sits at local (i L/N, j L/N).
    pub fields: [Vec<Complex32>; 4],
    /// kz (rad/m) of each column index.
    wavenumbers: Vec<f32>,
    fft: Arc<dyn Fft<f32>>,
    scratch: Vec<TaskScratch>,
    /// Whether the CPU has AVX2, checked once in `new`.
    avx2: bool,
}

/// Buffers of one parallel task, allocated in `new`.
struct TaskScratch {
    /// rustfft's scratch.
    fft: Vec<Complex32>,
    /// `h(k, t)` of the stored row being transformed (n values).
    h: Vec<Complex32>,
    /// The row's phases in turns, reduced to [-1/2, 1/2], and their sines and cosines (n each).
    turns: Vec<f32>,
    sin: Vec<f32>,
    cos: Vec<f32>,
}

/// The foam field's rows, handed to [`Cascade::row_pass`] so the foam update runs fused with it.
pub(super) struct FoamRows<'a> {
    /// Coverage in [0, 1], `[z][x]`, updated in place.
    pub values: &'a mut [f32],
    /// Factor applied to the previous coverage (persistence), in [0, 1].
    pub decay: f32,
    /// Jacobian threshold below which foam appears.
    pub threshold: f32,
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
                        // Paper 003 eq. 10: w = floor(w T / 2π) 2π / T, so every wave repeats after T.
                        Some(t) => (w * t / TAU).floor() / t,
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
        // Both passes have n / ROWS_PER_TASK tasks (one for n = 16).
        let tasks = n / ROWS_PER_TASK.min(n);
        let scratch = (0..tasks)
            .map(|_| TaskScratch {
                fft: vec![Complex32::default(); fft.get_inplace_scratch_len()],
                h: vec![Complex32::default(); n],
                turns: vec![0.0; n],
                sin: vec![0.0; n],
                cos: vec![0.0; n],
            })
            .collect();
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
        let stride = n + WORK_ROW_PADDING;
        let slot_offsets = (0..n)
            .map(|a| {
                let slot = match a {
                    0 => 0,
                    _ if a == half => 1,
                    _ if a < half => 2 * a,
                    _ => 2 * (n - a) + 1,
                };
                slot * stride
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
            work: std::array::from_fn(|_| vec![Complex32::default(); n * (n + WORK_ROW_PADDING)]),
            fields: [zero(), zero(), zero(), zero()],
            slot_offsets,
            wavenumbers,
            fft,
            scratch,
            avx2: fill_simd::available(),
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

    /// Pass 1, for time `t` (s): evolves `h(k, t)` and fills and transforms the packed spectra of
    /// the four field pairs over kz, into [`Cascade::work`]. One task owns the rows kx and -kx of
    /// the same stored row, so each `h(k, t)` is computed once, used for both, and never stored:
    /// the evolution costs no pass over memory of its own.
    pub fn column_pass(&mut self, t: f64) {
        let n = self.n;
        let stride = n + WORK_ROW_PADDING;
        let pairs = PAIRS_PER_TASK.min(n / 2);
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
        let fft = &self.fft;
        let [w0, w1, w2, w3] = &mut self.work;
        // Each task's chunk is `pairs` pairs of slots: rows (m, n - m) of every pair's buffer.
        let chunk = 2 * pairs * stride;
        w0.par_chunks_mut(chunk)
            .zip(w1.par_chunks_mut(chunk))
            .zip(w2.par_chunks_mut(chunk))
            .zip(w3.par_chunks_mut(chunk))
            .zip(self.scratch.par_iter_mut())
            .enumerate()
            .for_each(|(task, ((((b0, b1), b2), b3), scratch))| {
                for p in 0..pairs {
                    let m = task * pairs + p;
                    spec.evolve_row(m, scratch);
                    let TaskScratch { fft: fft_scratch, h, .. } = &mut *scratch;
                    for side in 0..2 {
                        if m == 0 && side == 1 {
                            // Slot 1 is the Nyquist row kx = N/2: empty, zero since `new`, never written.
                            continue;
                        }
                        let at = (2 * p + side) * stride;
                        let r = at..at + n;
                        let out = [&mut b0[r.clone()], &mut b1[r.clone()], &mut b2[r.clone()], &mut b3[r.clone()]];
                        if side == 0 {
                            spec.fill_row(m, h, out);
                        } else {
                            spec.fill_mirror_row(m, h, out);
                        }
                        for b in [&mut *b0, &mut *b1, &mut *b2, &mut *b3] {
                            fft.process_with_scratch(&mut b[r.clone()], fft_scratch);
                        }
                    }
                }
            });
        self.time = t;
    }

    /// Pass 2: transposes `[kx][z]` to `[z][kx]` block by block and transforms each row over kx,
    /// for the four pairs, into [`Cascade::fields`]; with `foam`, updates the foam of the rows
    /// just transformed while they are still in cache (the Jacobian needs only its own sample).
    pub fn row_pass(&mut self, foam: Option<FoamRows>) {
        let n = self.n;
        let rows = ROWS_PER_TASK.min(n);
        let (work, fft, slots, avx2) = (&self.work, &self.fft, &self.slot_offsets[..], self.avx2);
        let [f0, f1, f2, f3] = &mut self.fields;
        let chunk = rows * n;
        let tasks = f0
            .par_chunks_mut(chunk)
            .zip(f1.par_chunks_mut(chunk))
            .zip(f2.par_chunks_mut(chunk))
            .zip(f3.par_chunks_mut(chunk))
            .zip(self.scratch.par_iter_mut());
        let body = |task: usize, out: [&mut [Complex32]; 4], scratch: &mut TaskScratch| {
            let z0 = task * rows;
            for (block, src) in out.into_iter().zip(work) {
                // Four kx at a time: each slot's `rows` values are contiguous (one or two cache
                // lines), and each output row gets one 32-byte store per four kx; the task's
                // `rows` output lines stay in L1. (N >= 16, so N is a multiple of 4.)
                #[cfg(target_arch = "x86_64")]
                if avx2 {
                    // SAFETY: `avx2` is set only when the CPU reports AVX2.
                    unsafe { transpose_simd::transpose_rows(src, slots, z0, rows, block, n) };
                    fft.process_with_scratch(block, &mut scratch.fft);
                    continue;
                }
                for a in (0..n).step_by(4) {
                    let column = |i: usize| &src[slots[a + i] + z0..slots[a + i] + z0 + rows];
                    let (c0, c1, c2, c3) = (column(0), column(1), column(2), column(3));
                    for ((((row, &v0), &v1), &v2), &v3) in block.chunks_exact_mut(n).zip(c0).zip(c1).zip(c2).zip(c3) {
                        row[a..a + 4].copy_from_slice(&[v0, v1, v2, v3]);
                    }
                }
                fft.process_with_scratch(block, &mut scratch.fft);
            }
        };
        match foam {
            None => tasks.enumerate().for_each(|(task, ((((o0, o1), o2), o3), scratch))| {
                body(task, [o0, o1, o2, o3], scratch);
            }),
            Some(FoamRows { values, decay, threshold }) => tasks
                .zip(values.par_chunks_mut(chunk))
                .enumerate()
                .for_each(|(task, (((((o0, o1), o2), o3), scratch), foam))| {
                    body(task, [&mut *o0, &mut *o1, &mut *o2, &mut *o3], scratch);
                    let written = [&*o0, &*o1, &*o2, &*o3];
                    let (dxx, jac) = (written[PAIR_HZ_DXX], written[PAIR_DZZ_DXZ]);
                    // Foam follows the Jacobian of the rows this task has just written.
                    let mut done = 0;
                    #[cfg(target_arch = "x86_64")]
                    if avx2 {
                        // SAFETY: `avx2` is set only when the CPU reports AVX2.
                        done = unsafe { foam_simd::update(foam, dxx, jac, threshold, decay) };
                    }
                    let (foam, dxx, jac) = (&mut foam[done..], &dxx[done..], &jac[done..]);
                    for ((v, dxx), dzz_dxz) in foam.iter_mut().zip(dxx).zip(jac) {
                        *v = foam_coverage(jacobian(dxx.im, dzz_dxz.re, dzz_dxz.im), threshold).max(*v * decay);
                    }
                }),
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
    fn evolve_row(&self, m: usize, scratch: &mut TaskScratch) {
        let r = m * self.n..(m + 1) * self.n;
        let t = self.t;
        let TaskScratch { h, turns, sin, cos, .. } = scratch;
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

    /// Row kx = m of the four packed spectra, from that row's `h(k, t)`.
    #[inline(always)]
    fn fill_row(&self, m: usize, h: &[Complex32], out: [&mut [Complex32]; 4]) {
        let n = self.n;
        let l = &self.lambda_over_k[m * n..(m + 1) * n];
        let kx = self.kk[m];
        let [o0, o1, o2, o3] = out;
        let (o0, o1, o2, o3) = (&mut o0[..n], &mut o1[..n], &mut o2[..n], &mut o3[..n]);
        let (h, kk) = (&h[..n], &self.kk[..n]);
        let mut start = 0;
        #[cfg(target_arch = "x86_64")]
        if self.avx2 {
            // SAFETY: `avx2` is set only when the CPU reports AVX2.
            start = unsafe { fill_simd::fill([o0, o1, o2, o3], h, kx, kk, l, false) };
        }
        for b in start..n {
            write_multiplied([o0, o1, o2, o3], b, h[b], kx, kk[b], l[b]);
        }
    }

    /// Row kx = -m (index N - m) of the four packed spectra, from row m's `h(k, t)`:
    /// `h(-kx, kz) = conj(h(kx, -kz))`, and |k| is the same, so is `λ/k`.
    #[inline(always)]
    fn fill_mirror_row(&self, m: usize, h: &[Complex32], out: [&mut [Complex32]; 4]) {
        let n = self.n;
        let l = &self.lambda_over_k[m * n..(m + 1) * n];
        let kx = -self.kk[m];
        let [o0, o1, o2, o3] = out;
        let (o0, o1, o2, o3) = (&mut o0[..n], &mut o1[..n], &mut o2[..n], &mut o3[..n]);
        let (h, kk) = (&h[..n], &self.kk[..n]);
        write_multiplied([o0, o1, o2, o3], 0, h[0].conj(), kx, kk[0], l[0]);
        let mut start = 1;
        #[cfg(target_arch = "x86_64")]
        if self.avx2 {
            // SAFETY: as in `fill_row`.
            start = unsafe { fill_simd::fill([o0, o1, o2, o3], h, kx, kk, l, true) };
        }
        for b in start..n {
            write_multiplied([o0, o1, o2, o3], b, h[n - b].conj(), kx, kk[b], l[b]);
        }
    }
}

/// Writes entry b of the four pairs' packed spectra: each pair's spectral multiplier at (kx, kz)
/// times h, with `l = λ/|k|` (0 at k = 0).
///
/// With `A + iB` packing the multipliers are (h, Dx): `1 + i (i λ kx/k)`; (Dz, hx):
/// `i λ kz/k + i (i kx)`; (hz, Dxx): `i kz + i (-λ kx²/k)`; (Dzz, Dxz): `-λ kz²/k + i (-λ kx kz/k)`,
/// written out so that their zero parts cost nothing.
///
/// The column pass uses it for the entries `fill_simd::fill` leaves (all of them without AVX2),
/// which computes the same values four entries at a time.
#[inline(always)]
pub(super) fn write_multiplied(out: [&mut [Complex32]; 4], b: usize, h: Complex32, kx: f32, kz: f32, l: f32) {
    let s0 = 1.0 - l * kx;
    out[PAIR_H_DX][b] = Complex32::new(h.re * s0, h.im * s0);
    let (p, q) = (-kx, l * kz);
    out[PAIR_DZ_HX][b] = Complex32::new(h.re * p - h.im * q, h.re * q + h.im * p);
    let r = kz - l * kx * kx;
    out[PAIR_HZ_DXX][b] = Complex32::new(-h.im * r, h.re * r);
    let (u, v) = (-l * kz * kz, -l * kx * kz);
    out[PAIR_DZZ_DXZ][b] = Complex32::new(h.re * u - h.im * v, h.re * v + h.im * u);
}
