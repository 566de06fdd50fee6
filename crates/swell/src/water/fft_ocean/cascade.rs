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
//! buffer per pair (4 x N (N + 16) complex values) and saves six meetings of the threads per step.
//! Buffers are allocated in `new`.

use std::f64::consts::TAU;
use std::sync::Arc;

use rayon::prelude::*;
use rustfft::num_complex::Complex32;
use rustfft::{Fft, FftPlanner};

use crate::math::{reduce_turns, sin_cos_turns};
use crate::spectrum::DirectionalSpectrum;

/// Rows handled by one parallel task; each task owns one FFT scratch buffer.
const ROWS_PER_TASK: usize = 16;

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
    /// `h(k, t)` of the last step; same layout.
    ht: Vec<Complex32>,
    /// Column pass output of each field pair, `[kx index][z]`, rows `n + WORK_ROW_PADDING` long.
    work: [Vec<Complex32>; 4],
    /// The four packed field pairs, `[z][x]`: sample (i, j) sits at local (i L/N, j L/N).
    pub fields: [Vec<Complex32>; 4],
    /// kz (rad/m) of each column index.
    wavenumbers: Vec<f32>,
    choppiness: f32,
    fft: Arc<dyn Fft<f32>>,
    scratch: Vec<Vec<Complex32>>,
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
        let rows = ROWS_PER_TASK.min(n);
        let scratch = (0..n / rows).map(|_| vec![Complex32::default(); fft.get_inplace_scratch_len()]).collect();
        let zero = || vec![Complex32::default(); n * n];
        Self {
            n,
            patch: s.patch,
            variance,
            h0,
            h0_mirror,
            cycles,
            ht: vec![Complex32::default(); half * n],
            work: std::array::from_fn(|_| vec![Complex32::default(); n * (n + WORK_ROW_PADDING)]),
            fields: [zero(), zero(), zero(), zero()],
            wavenumbers: (0..n).map(|i| signed_index(i, n) as f32 * dk as f32).collect(),
            choppiness: s.choppiness,
            fft,
            scratch,
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

    /// Step 1: `h(k, t)` for the stored half spectrum.
    pub fn evolve(&mut self, t: f64) {
        let chunk = ROWS_PER_TASK * self.n;
        self.ht
            .par_chunks_mut(chunk)
            .zip(self.h0.par_chunks(chunk))
            .zip(self.h0_mirror.par_chunks(chunk))
            .zip(self.cycles.par_chunks(chunk))
            .for_each(|(((ht, h0), hm), f)| {
                for (((out, a), b), &f) in ht.iter_mut().zip(h0).zip(hm).zip(f) {
                    let (s, c) = sin_cos_turns(reduce_turns(f * t));
                    // a e^{-iφ} + b e^{iφ}
                    // Grouped so that h(-k) = conj(h(k)) holds bit for bit in the self-mirrored row nx = 0.
                    *out = Complex32::new(
                        (a.re * c + a.im * s) + (b.re * c - b.im * s),
                        (a.im * c - a.re * s) + (b.im * c + b.re * s),
                    );
                }
            });
    }

    /// Step 2: the four packed inverse transforms, into [`Cascade::fields`]: one parallel pass of
    /// column transforms for all four pairs, then one of row transforms (two meetings of the
    /// threads per step instead of eight, and each row of `h(k, t)` is read once for all pairs).
    pub fn synthesize(&mut self) {
        self.column_passes();
        self.row_passes();
    }

    /// Fills `[kx][kz]` rows with the spectrum of each field pair and transforms each over kz.
    fn column_passes(&mut self) {
        let n = self.n;
        let stride = n + WORK_ROW_PADDING;
        let rows = ROWS_PER_TASK.min(n);
        let (ht, kk, lambda, fft) = (&self.ht, &self.wavenumbers, self.choppiness, &self.fft);
        let [w0, w1, w2, w3] = &mut self.work;
        let chunk = rows * stride;
        w0.par_chunks_mut(chunk)
            .zip(w1.par_chunks_mut(chunk))
            .zip(w2.par_chunks_mut(chunk))
            .zip(w3.par_chunks_mut(chunk))
            .zip(self.scratch.par_iter_mut())
            .enumerate()
            .for_each(|(task, ((((b0, b1), b2), b3), scratch))| {
                for r in 0..rows {
                    let a = task * rows + r;
                    let row = r * stride..r * stride + n;
                    let spec = RowSpec { a, n, ht, kk, lambda };
                    fill_rows(
                        [&mut b0[row.clone()], &mut b1[row.clone()], &mut b2[row.clone()], &mut b3[row.clone()]],
                        &spec,
                    );
                    for b in [&mut *b0, &mut *b1, &mut *b2, &mut *b3] {
                        fft.process_with_scratch(&mut b[row.clone()], scratch);
                    }
                }
            });
    }

    /// Transposes `[kx][z]` to `[z][kx]` block by block and transforms each row over kx, for the
    /// four pairs in one parallel pass.
    fn row_passes(&mut self) {
        let n = self.n;
        let stride = n + WORK_ROW_PADDING;
        let rows = ROWS_PER_TASK.min(n);
        let (work, fft) = (&self.work, &self.fft);
        let [f0, f1, f2, f3] = &mut self.fields;
        let chunk = rows * n;
        f0.par_chunks_mut(chunk)
            .zip(f1.par_chunks_mut(chunk))
            .zip(f2.par_chunks_mut(chunk))
            .zip(f3.par_chunks_mut(chunk))
            .zip(self.scratch.par_iter_mut())
            .enumerate()
            .for_each(|(task, ((((o0, o1), o2), o3), scratch))| {
                let z0 = task * rows;
                for (block, src) in [(o0, &work[0]), (o1, &work[1]), (o2, &work[2]), (o3, &work[3])] {
                    // Tiles of TILE kx by `rows` z: the tile's source lines (TILE rows of `work`,
                    // rows * 8 bytes each) stay in L1 while the writes run along the output rows.
                    const TILE: usize = 64;
                    for a0 in (0..n).step_by(TILE) {
                        let a1 = (a0 + TILE).min(n);
                        let src_rows = &src[a0 * stride..a1 * stride];
                        for (r, row) in block.chunks_exact_mut(n).enumerate() {
                            for (out, s) in row[a0..a1].iter_mut().zip(src_rows.chunks_exact(stride)) {
                                *out = s[z0 + r];
                            }
                        }
                    }
                    fft.process_with_scratch(block, scratch);
                }
            });
    }

    /// Wave-vector integers and the evolution data of stored entry `idx` (tests and point queries).
    pub(super) fn half_spectrum(&self) -> impl Iterator<Item = (i32, i32, Complex32, Complex32, f64)> + '_ {
        let n = self.n;
        (0..self.h0.len()).map(move |idx| {
            let (a, b) = (idx / n, idx % n);
            (signed_index(a, n), signed_index(b, n), self.h0[idx], self.h0_mirror[idx], self.cycles[idx])
        })
    }

    /// `h(k, t)` of the last [`Cascade::evolve`] at wave-vector integers (nx, nz), any sign.
    #[cfg(test)]
    pub(super) fn evolved(&self, nx: i32, nz: i32) -> Complex32 {
        let n = self.n as i32;
        let (a, b) = (nx.rem_euclid(n) as usize, nz.rem_euclid(n) as usize);
        let half = self.n / 2;
        if a < half {
            self.ht[a * self.n + b]
        } else if a == half {
            Complex32::default()
        } else {
            self.ht[(self.n - a) * self.n + (self.n - b) % self.n].conj()
        }
    }
}

/// What [`fill_row`] reads: row `a` (kx index) of an n x n spectrum built from the stored half
/// spectrum `ht`, with the wavenumbers `kk` and the choppiness.
struct RowSpec<'a> {
    a: usize,
    n: usize,
    ht: &'a [Complex32],
    kk: &'a [f32],
    lambda: f32,
}

/// Writes row `a` of the four field pairs' packed spectra into `out` (n values each): each pair's
/// multiplier times `h(k, t)`, with rows of negative kx taken from their mirrors. One sweep for
/// the four pairs, so `h` is read and `1/k` computed once per wave vector.
#[inline(always)]
fn fill_rows(out: [&mut [Complex32]; 4], s: &RowSpec) {
    let (a, n) = (s.a, s.n);
    let half = n / 2;
    if a == half {
        for o in out {
            o.fill(Complex32::default());
        }
        return;
    }
    if a < half {
        let src = &s.ht[a * n..(a + 1) * n];
        fill_rows_from(out, s, |b| src[b]);
    } else {
        // Row -kx is the mirror of row kx: h(-k) = conj(h(k)), column -kz.
        let src = &s.ht[(n - a) * n..(n - a + 1) * n];
        let mask = n - 1;
        fill_rows_from(out, s, |b| src[(n - b) & mask].conj());
    }
}

/// [`fill_rows`] for a row whose `h(k, t)` at column b is `h(b)`.
#[inline(always)]
fn fill_rows_from(out: [&mut [Complex32]; 4], s: &RowSpec, h: impl Fn(usize) -> Complex32) {
    let [o0, o1, o2, o3] = out;
    let n = s.n;
    let kx = s.kk[s.a];
    let kz = &s.kk[..n];
    let (o0, o1, o2, o3) = (&mut o0[..n], &mut o1[..n], &mut o2[..n], &mut o3[..n]);
    for b in 0..n {
        let h = h(b);
        let m = pair_multipliers(kx, kz[b], s.lambda);
        o0[b] = h * m[PAIR_H_DX];
        o1[b] = h * m[PAIR_DZ_HX];
        o2[b] = h * m[PAIR_HZ_DXX];
        o3[b] = h * m[PAIR_DZZ_DXZ];
    }
}

/// Spectral multipliers of the four field pairs at (kx, kz), indexed by `PAIR_*`: each pair's
/// packed spectrum is its multiplier times h.
///
/// With `A + iB` packing: (h, Dx): `1 + i (i λ kx/k)`; (Dz, hx): `i λ kz/k + i (i kx)`;
/// (hz, Dxx): `i kz + i (-λ kx²/k)`; (Dzz, Dxz): `-λ kz²/k + i (-λ kx kz/k)`.
#[inline(always)]
fn pair_multipliers(kx: f32, kz: f32, lambda: f32) -> [Complex32; 4] {
    let k2 = kx * kx + kz * kz;
    let inv_k = if k2 > 0.0 { 1.0 / k2.sqrt() } else { 0.0 };
    let l = lambda * inv_k;
    [
        Complex32::new(1.0 - l * kx, 0.0),
        Complex32::new(-kx, l * kz),
        Complex32::new(0.0, kz - l * kx * kx),
        Complex32::new(-l * kz * kz, -l * kx * kz),
    ]
}
