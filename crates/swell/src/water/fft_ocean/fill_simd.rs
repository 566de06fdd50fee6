//! The fill of the five bases (`cascade.rs`, `write_bases`) in AVX2 registers, four wave vectors
//! at a time.
//!
//! The compiler does not vectorise the scalar fill: each `i kz v` swaps the interleaved (re, im)
//! slots and flips a sign. Here the complex values stay interleaved in the registers; `i k v` is
//! `swap(v) k` with the sign of the real slot flipped. Every value is computed by the same IEEE
//! operations as the scalar code (no fused multiply-add, products commuted only), so the bases,
//! and the sea, are bit for bit those of the scalar fill: the run-time choice does not change the
//! output.

use rustfft::num_complex::Complex32;

use super::cascade::BASES;

/// Whether [`fill`] (and the other AVX2 kernels of the FFT ocean) may be called: the CPU has AVX2.
pub(super) fn available() -> bool {
    crate::math::Isa::Avx2.is_available()
}

/// Writes entries b of the five bases `out` (each n long) from `h[b]`, the column's kz `kk[b]`
/// and `l[b] = λ/|k|`, for b from 0 in groups of four, and returns the first b it did not write
/// (the caller writes the rest with the scalar code).
///
/// # Safety
/// The CPU must have AVX2 ([`available`]).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
pub(super) unsafe fn fill(out: [&mut [Complex32]; BASES], h: &[Complex32], kk: &[f32], l: &[f32]) -> usize {
    use std::arch::x86_64::*;

    let n = h.len();
    assert!(kk.len() == n && l.len() == n && out.iter().all(|o| o.len() == n));
    let [o0, o1, o2, o3, o4] = out;
    // Each of four floats twice: [a0 a0 a1 a1 a2 a2 a3 a3], one per (re, im) slot.
    let twice = _mm256_setr_epi32(0, 0, 1, 1, 2, 2, 3, 3);
    let neg_re = neg_re();
    let mut b = 0;
    while b + 4 <= n {
        // SAFETY: b + 4 <= n values of h, kk, l and every out.
        unsafe {
            let hv = _mm256_loadu_ps(h.as_ptr().add(b).cast());
            let kz = _mm256_permutevar8x32_ps(_mm256_castps128_ps256(_mm_loadu_ps(kk.as_ptr().add(b))), twice);
            let lv = _mm256_permutevar8x32_ps(_mm256_castps128_ps256(_mm_loadu_ps(l.as_ptr().add(b))), twice);
            let g = _mm256_mul_ps(hv, lv);
            let c = i_times(kz, g, neg_re);
            _mm256_storeu_ps(o0.as_mut_ptr().add(b).cast(), hv);
            _mm256_storeu_ps(o1.as_mut_ptr().add(b).cast(), g);
            _mm256_storeu_ps(o2.as_mut_ptr().add(b).cast(), c);
            _mm256_storeu_ps(o3.as_mut_ptr().add(b).cast(), i_times(kz, hv, neg_re));
            _mm256_storeu_ps(o4.as_mut_ptr().add(b).cast(), i_times(kz, c, neg_re));
        }
        b += 4;
    }
    b
}

/// The sign mask of the real slots of four interleaved complex values.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
pub(super) fn neg_re() -> std::arch::x86_64::__m256 {
    std::arch::x86_64::_mm256_setr_ps(-0.0, 0.0, -0.0, 0.0, -0.0, 0.0, -0.0, 0.0)
}

/// `i k v` for four interleaved complex values v and real k (each twice): (re, im) -> (-(im k), re k),
/// the operations of the scalar `cascade::i_times`.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[inline]
pub(super) fn i_times(
    k: std::arch::x86_64::__m256,
    v: std::arch::x86_64::__m256,
    neg_re: std::arch::x86_64::__m256,
) -> std::arch::x86_64::__m256 {
    use std::arch::x86_64::*;
    _mm256_xor_ps(_mm256_mul_ps(_mm256_permute_ps::<0b10_11_00_01>(v), k), neg_re)
}

#[cfg(all(test, target_arch = "x86_64"))]
mod tests {
    use super::*;
    use crate::water::fft_ocean::cascade::write_bases;

    #[test]
    fn the_avx2_fill_is_bit_identical_to_the_scalar_fill() {
        if !available() {
            return;
        }
        let n = 37; // not a multiple of 4: the scalar tail runs too
        let h: Vec<Complex32> =
            (0..n).map(|i| Complex32::new((i as f32 * 0.737).sin() * 1.3, (i as f32 * 1.91).cos() * 0.7)).collect();
        let kk: Vec<f32> = (0..n).map(|i| (i as f32 - 18.0) * 0.0713).collect();
        let l: Vec<f32> = (0..n).map(|i| 0.9 / (0.05 + (i as f32 * 0.31).sin().abs())).collect();
        let mut scalar: [Vec<Complex32>; BASES] = std::array::from_fn(|_| vec![Complex32::default(); n]);
        {
            let [a, c, d, e, f] = &mut scalar;
            let mut out = [&mut a[..], &mut c[..], &mut d[..], &mut e[..], &mut f[..]];
            for b in 0..n {
                write_bases(&mut out, b, h[b], kk[b], l[b]);
            }
        }
        let mut simd: [Vec<Complex32>; BASES] = std::array::from_fn(|_| vec![Complex32::default(); n]);
        let [a, c, d, e, f] = &mut simd;
        // SAFETY: AVX2 checked above.
        let done = unsafe { fill([a, c, d, e, f], &h, &kk, &l) };
        assert!(done > n - 4, "{done}");
        for b in 0..done {
            for j in 0..BASES {
                let (x, y) = (scalar[j][b], simd[j][b]);
                assert!(
                    x.re.to_bits() == y.re.to_bits() && x.im.to_bits() == y.im.to_bits(),
                    "base {j} entry {b}: {x} against {y}"
                );
            }
        }
        // The bases are what their names say, so the pairs' combinations in `cascade.rs` hold.
        for b in 0..n {
            let (hb, kz, g) = (h[b], kk[b], h[b] * l[b]);
            let i = Complex32::new(0.0, 1.0);
            let expect = [hb, g, i * kz * g, i * kz * hb, -kz * kz * g];
            for j in 0..BASES {
                assert!((scalar[j][b] - expect[j]).norm() <= 1e-5 * (1.0 + expect[j].norm()), "base {j} entry {b}");
            }
        }
    }
}
