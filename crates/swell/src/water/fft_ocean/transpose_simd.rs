//! The row pass's gather (`cascade.rs`, `gather_rows`) in AVX2 registers: the bases combined into
//! the four packed pairs and transposed in 4 x 4 blocks of complex values, a task's whole block of
//! output rows per call.
//!
//! A complex f32 is 64 bits, so four of them fill a 256-bit register. For four stored rows and four
//! z, a pair's values are computed as four registers (one per row, lanes along z), then transposed
//! with four 64-bit unpacks and four 128-bit lane permutes into four output rows (lanes along kx).
//! The arithmetic is the scalar code's, operation for operation (no fused multiply-add), so the
//! output is the scalar gather's, bit for bit.

use rustfft::num_complex::Complex32;

use super::cascade::{pair_factor, WorkLayout, BASES, BLOCK_PADDING, PAIR_BASES, PAIR_HZ_DXX};
use super::fill_simd::{i_times, neg_re};

/// Does what `cascade::gather_rows` does, with the same arguments: the output rows of row-pass
/// task c of the four pairs from the column buffer `work`, kx of stored row m at `kx[m]`, m in
/// [0, N/2]. Columns 4 at a time: m0 .. m0 + 4 directly, and N - m0 - 4 .. N - m0 as the mirrors
/// of rows m0 + 4 down to m0 + 1, for all four pairs while those rows' bases are in L1. The
/// bounds are checked once per block of columns, not per value.
///
/// # Safety
/// The CPU must have AVX2 (`fill_simd::available`).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
pub(super) unsafe fn gather_rows(
    work: &[Complex32],
    layout: &WorkLayout,
    kx: &[f32],
    c: usize,
    block: &mut [Complex32],
) {
    let (half, rows) = (kx.len() - 1, WorkLayout::ROWS);
    let n = 2 * half;
    let stride = n + BLOCK_PADDING;
    assert!(rows % 4 == 0 && half % 4 == 0 && (c + 1) * rows <= n && block.len() >= 4 * rows * stride);
    assert!(layout.stride == n + super::cascade::WORK_ROW_PADDING, "layout of another grid");
    let o = block.as_mut_ptr().cast::<f64>();
    let w = work.as_ptr().cast::<f32>();
    let neg_re = neg_re();
    let mut m0 = 0;
    while m0 < half {
        // Slots grow with m and j, so the last one bounds them all.
        assert!(layout.slot(m0 + 4, BASES - 1, c) + rows <= work.len());
        // Base j of row m0 + k starts at `at[k] + 2 j stride` (f32 units).
        let at: [*const f32; 5] = std::array::from_fn(|k| w.wrapping_add(2 * layout.slot(m0 + k, 0, c)));
        for (p, &(x, y)) in PAIR_BASES.iter().enumerate() {
            let xs = at.map(|a| a.wrapping_add(2 * x * layout.stride));
            let ys = at.map(|a| a.wrapping_add(2 * y * layout.stride));
            let direct: [f32; 4] = std::array::from_fn(|i| pair_factor(p, kx[m0 + i], false));
            let mirror: [f32; 4] = std::array::from_fn(|i| pair_factor(p, kx[m0 + 4 - i], true));
            let out = o.wrapping_add(p * rows * stride);
            // SAFETY: every run read is inside `work` (checked above); pair p's output rows and
            // columns m0 .. m0 + 4 <= half and n - m0 - 4 .. n - m0 <= n are inside the block.
            unsafe {
                let out = OutBlock { out, stride, m0, n };
                if p == PAIR_HZ_DXX {
                    pair_block::<true>(xs, ys, direct, mirror, out, neg_re);
                } else {
                    pair_block::<false>(xs, ys, direct, mirror, out, neg_re);
                }
            }
        }
        m0 += 4;
    }
}

/// Where [`pair_block`] writes: the block `out` (rows `stride` apart, `n` columns), columns
/// `m0 .. m0 + 4` and their mirrors.
#[cfg(target_arch = "x86_64")]
#[derive(Clone, Copy)]
struct OutBlock {
    out: *mut f64,
    stride: usize,
    m0: usize,
    n: usize,
}

/// One pair's 4 x 4 blocks for columns m0 .. m0 + 4 and their mirrors, all R rows: `xs[k]` and
/// `ys[k]` are the runs of the pair's bases x and y in row m0 + k, `direct[i]` and `mirror[i]`
/// the factors of columns m0 + i and N - m0 - 4 + i (the mirror of row m0 + 4 - i); with `ROT`,
/// `x - f (i y)`, otherwise `x - f y`.
///
/// # Safety
/// The CPU must have AVX2; the runs must hold R values each and the block `out` (rows `stride`
/// apart) must hold R rows of N columns.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[inline]
unsafe fn pair_block<const ROT: bool>(
    xs: [*const f32; 5],
    ys: [*const f32; 5],
    direct: [f32; 4],
    mirror: [f32; 4],
    out: OutBlock,
    neg_re: std::arch::x86_64::__m256,
) {
    use std::arch::x86_64::*;
    let OutBlock { out, stride, m0, n } = out;

    let conj = _mm256_setr_ps(0.0, -0.0, 0.0, -0.0, 0.0, -0.0, 0.0, -0.0);
    let (direct, mirror) = (direct.map(|f| _mm256_set1_ps(f)), mirror.map(|f| _mm256_set1_ps(f)));
    let mut z = 0;
    while z < WorkLayout::ROWS {
        // SAFETY: the caller's; z + 4 <= R.
        unsafe {
            let pair = |k: usize, f: __m256| {
                let (xv, yv) = (_mm256_loadu_ps(xs[k].add(2 * z)), _mm256_loadu_ps(ys[k].add(2 * z)));
                let t = if ROT { i_times(f, yv, neg_re) } else { _mm256_mul_ps(yv, f) };
                _mm256_sub_ps(xv, t)
            };
            let d = [pair(0, direct[0]), pair(1, direct[1]), pair(2, direct[2]), pair(3, direct[3])];
            let r = [pair(4, mirror[0]), pair(3, mirror[1]), pair(2, mirror[2]), pair(1, mirror[3])];
            let row = out.add(z * stride);
            store_transposed(row.add(m0), stride, d);
            store_transposed(row.add(n - m0 - 4), stride, r.map(|v| _mm256_xor_ps(v, conj)));
        }
        z += 4;
    }
}

/// Stores the 4 x 4 block of complex values whose column i is `v[i]` (four rows, lanes along the
/// rows) at `o`, rows `stride` complex values apart.
///
/// # Safety
/// `o .. o + 3 stride + 4` must be writable (one complex value is one f64 here).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[inline]
unsafe fn store_transposed(o: *mut f64, stride: usize, v: [std::arch::x86_64::__m256; 4]) {
    use std::arch::x86_64::*;

    let [p, q, r, s] = [_mm256_castps_pd(v[0]), _mm256_castps_pd(v[1]), _mm256_castps_pd(v[2]), _mm256_castps_pd(v[3])];
    // [p0 q0 | p2 q2], [p1 q1 | p3 q3], [r0 s0 | r2 s2], [r1 s1 | r3 s3].
    let (t0, t1) = (_mm256_unpacklo_pd(p, q), _mm256_unpackhi_pd(p, q));
    let (t2, t3) = (_mm256_unpacklo_pd(r, s), _mm256_unpackhi_pd(r, s));
    // SAFETY: the caller's.
    unsafe {
        _mm256_storeu_pd(o, _mm256_permute2f128_pd::<0x20>(t0, t2));
        _mm256_storeu_pd(o.add(stride), _mm256_permute2f128_pd::<0x20>(t1, t3));
        _mm256_storeu_pd(o.add(2 * stride), _mm256_permute2f128_pd::<0x31>(t0, t2));
        _mm256_storeu_pd(o.add(3 * stride), _mm256_permute2f128_pd::<0x31>(t1, t3));
    }
}

#[cfg(all(test, target_arch = "x86_64"))]
mod tests {
    use super::*;

    #[test]
    fn the_avx2_gather_is_bit_identical_to_the_scalar_gather() {
        if !super::super::fill_simd::available() {
            return;
        }
        // The smallest grid (a single task, half = 8) and a larger one, every task.
        for n in [16, 64] {
            let half = n / 2;
            let layout = WorkLayout::new(n);
            let rows = WorkLayout::ROWS;
            let work: Vec<Complex32> = (0..layout.len())
                .map(|i| Complex32::new((i as f32 * 0.377).sin() * 3.1, (i as f32 * 1.13).cos() - 0.25))
                .collect();
            let kx: Vec<f32> =
                (0..=half).map(|m| m as f32 * 0.41 - if m == half { 2.0 * half as f32 * 0.41 } else { 0.0 }).collect();
            let stride = n + BLOCK_PADDING;
            for c in 0..n / rows {
                let mut scalar = vec![Complex32::new(-7.0, -7.0); 4 * rows * stride];
                let mut simd = scalar.clone();
                super::super::cascade::gather_rows(&work, &layout, &kx, c, &mut scalar);
                // SAFETY: AVX2 checked above.
                unsafe { gather_rows(&work, &layout, &kx, c, &mut simd) };
                for (i, (x, y)) in scalar.iter().zip(&simd).enumerate() {
                    assert!(
                        x.re.to_bits() == y.re.to_bits() && x.im.to_bits() == y.im.to_bits(),
                        "n {n} task {c} pair {} row {} column {}: {x} against {y}",
                        i / (rows * stride),
                        i / stride % rows,
                        i % stride
                    );
                }
                // Every entry written (none left at the fill value), padding untouched.
                for (i, v) in scalar.iter().enumerate() {
                    assert_eq!(v.re == -7.0, i % stride >= n, "n {n} task {c} entry {i}");
                }
            }
        }
    }
}
