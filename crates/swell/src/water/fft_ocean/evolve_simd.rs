//! The evolution of one stored row (`cascade.rs`, `Spectrum::evolve_row`) in AVX2 registers:
//! `h(k, t) = h0(k) e^{-iφ} + conj(h0(-k)) e^{iφ}`, `φ = 2π f t`, eight wave vectors at a time.
//!
//! The scalar loops are not vectorised by the compiler at the x86-64 baseline (the quadrant's swap
//! and sign flips stay scalar): about 23 instructions per wave vector for the phase and its sine
//! and cosine alone. Here the phase `f t` is formed and reduced in f64 four at a time (exactly as
//! [`reduce_turns`](crate::math::reduce_turns)), narrowed to f32, and the sine and cosine are
//! evaluated eight at a time with the Cephes polynomials of
//! [`sin_cos_turns`](crate::math::sin_cos_turns) (Moshier 1989, `sinf.c`); the quadrant's swap is a
//! blend and its signs an exclusive or. The two rotated amplitudes are summed with the complex
//! values interleaved, as in `combine`. Every value goes through the same IEEE operations in the
//! same order as the scalar code (no fused multiply-add; `a - b` is `a + (-b)`), so the result is
//! bit for bit the scalar one and the run-time choice does not change the sea.

use rustfft::num_complex::Complex32;

/// Writes `h[b] = h0[b] e^{-iφ} + hm[b] e^{iφ}`, `φ = 2π cycles[b] t`, for b from 0 in groups of
/// eight, and returns the first b it did not write (the caller does the rest with the scalar code).
///
/// # Safety
/// The CPU must have AVX2 (`fill_simd::available`).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
pub(super) unsafe fn evolve(h: &mut [Complex32], h0: &[Complex32], hm: &[Complex32], cycles: &[f64], t: f64) -> usize {
    use std::arch::x86_64::*;

    let n = h.len();
    assert!(h0.len() == n && hm.len() == n && cycles.len() == n);
    // Constants of `reduce_turns` and `sin_cos_turns`, as f32/f64 values identical to theirs.
    let magic64 = _mm256_set1_pd(6_755_399_441_055_744.0);
    let magic32 = _mm256_set1_ps(12_582_912.0);
    let tv = _mm256_set1_pd(t);
    let (half, neg_half) = (_mm256_set1_ps(0.5), _mm256_set1_ps(-0.5));
    let (four, quarter, tau) = (_mm256_set1_ps(4.0), _mm256_set1_ps(0.25), _mm256_set1_ps(std::f32::consts::TAU));
    let (s1, s2, s3) = (_mm256_set1_ps(-1.951_529_6e-4), _mm256_set1_ps(8.332_161e-3), _mm256_set1_ps(1.666_665_5e-1));
    let (c1, c2, c3) = (_mm256_set1_ps(2.443_315_7e-5), _mm256_set1_ps(1.388_731_6e-3), _mm256_set1_ps(4.166_664_6e-2));
    let one = _mm256_set1_ps(1.0);
    let (one_i, two_i) = (_mm256_set1_epi32(1), _mm256_set1_epi32(2));
    // Each of the low (high) four lanes twice: [x0 x0 x1 x1 x2 x2 x3 x3], one per (re, im) slot.
    let lo = _mm256_setr_epi32(0, 0, 1, 1, 2, 2, 3, 3);
    let hi = _mm256_setr_epi32(4, 4, 5, 5, 6, 6, 7, 7);
    let neg_re = _mm256_setr_ps(-0.0, 0.0, -0.0, 0.0, -0.0, 0.0, -0.0, 0.0);
    let neg_im = _mm256_setr_ps(0.0, -0.0, 0.0, -0.0, 0.0, -0.0, 0.0, -0.0);
    let mut b = 0;
    while b + 8 <= n {
        // SAFETY: b + 8 <= n entries of every slice.
        unsafe {
            // Phases in f64 turns, reduced to the nearest integer's remainder, narrowed to f32.
            let reduce = |at: usize| {
                let x = _mm256_mul_pd(_mm256_loadu_pd(cycles.as_ptr().add(at)), tv);
                let r = _mm256_sub_pd(x, _mm256_sub_pd(_mm256_add_pd(x, magic64), magic64));
                _mm256_cvtpd_ps(r)
            };
            let c = _mm256_set_m128(reduce(b + 4), reduce(b));
            let c = _mm256_max_ps(_mm256_min_ps(c, half), neg_half);
            // Quadrant and remainder, then the polynomials (same grouping as `sin_cos_reduced`).
            let q = _mm256_sub_ps(_mm256_add_ps(_mm256_mul_ps(four, c), magic32), magic32);
            let r = _mm256_mul_ps(tau, _mm256_sub_ps(c, _mm256_mul_ps(quarter, q)));
            let quadrant = _mm256_cvttps_epi32(q);
            let r2 = _mm256_mul_ps(r, r);
            let sp = _mm256_sub_ps(_mm256_mul_ps(_mm256_add_ps(_mm256_mul_ps(s1, r2), s2), r2), s3);
            let sin_r = _mm256_add_ps(r, _mm256_mul_ps(_mm256_mul_ps(r, r2), sp));
            let cp = _mm256_add_ps(_mm256_mul_ps(_mm256_sub_ps(_mm256_mul_ps(c1, r2), c2), r2), c3);
            let cos_r =
                _mm256_add_ps(_mm256_sub_ps(one, _mm256_mul_ps(half, r2)), _mm256_mul_ps(_mm256_mul_ps(r2, r2), cp));
            let swap = _mm256_castsi256_ps(_mm256_cmpeq_epi32(_mm256_and_si256(quadrant, one_i), one_i));
            let (s, co) = (_mm256_blendv_ps(sin_r, cos_r, swap), _mm256_blendv_ps(cos_r, sin_r, swap));
            let sin_sign = _mm256_slli_epi32::<30>(_mm256_and_si256(quadrant, two_i));
            let cos_sign = _mm256_slli_epi32::<30>(_mm256_and_si256(_mm256_add_epi32(quadrant, one_i), two_i));
            let s = _mm256_xor_ps(s, _mm256_castsi256_ps(sin_sign));
            let co = _mm256_xor_ps(co, _mm256_castsi256_ps(cos_sign));
            // a e^{-iφ} + b e^{iφ} = (a c + swap(a) s, im negated) + (b c + swap(b) s, re negated).
            for (half_index, idx) in [(0, lo), (4, hi)] {
                let (cd, sd) = (_mm256_permutevar8x32_ps(co, idx), _mm256_permutevar8x32_ps(s, idx));
                let a = _mm256_loadu_ps(h0.as_ptr().add(b + half_index).cast());
                let m = _mm256_loadu_ps(hm.as_ptr().add(b + half_index).cast());
                let swap_s = |v: __m256| _mm256_mul_ps(_mm256_permute_ps::<0b10_11_00_01>(v), sd);
                let ta = _mm256_add_ps(_mm256_mul_ps(a, cd), _mm256_xor_ps(swap_s(a), neg_im));
                let tb = _mm256_add_ps(_mm256_mul_ps(m, cd), _mm256_xor_ps(swap_s(m), neg_re));
                _mm256_storeu_ps(h.as_mut_ptr().add(b + half_index).cast(), _mm256_add_ps(ta, tb));
            }
        }
        b += 8;
    }
    b
}

#[cfg(all(test, target_arch = "x86_64"))]
mod tests {
    use super::*;
    use crate::water::fft_ocean::cascade::evolve_one;

    #[test]
    fn the_avx2_evolution_is_bit_identical_to_the_scalar_evolution() {
        if !super::super::fill_simd::available() {
            return;
        }
        let n = 203; // not a multiple of 8: the scalar tail runs too
        let h0: Vec<Complex32> =
            (0..n).map(|i| Complex32::new((i as f32 * 0.737).sin() * 1.3, (i as f32 * 1.91).cos() * 0.7)).collect();
        let hm: Vec<Complex32> =
            (0..n).map(|i| Complex32::new((i as f32 * 0.291).cos() * 0.4, (i as f32 * 2.3).sin() * 1.1)).collect();
        // Frequencies over the range of gravity waves, some quantised to loop, and a zero.
        let cycles: Vec<f64> =
            (0..n).map(|i| if i == 7 { 0.0 } else { 0.01 + (i as f64 * 0.173).sin().abs() * 3.0 }).collect();
        for t in [0.0, 0.37, 1.0 / 8.0, 1234.5678, -17.25, 3.15e9, 1e12 + 0.3] {
            let mut simd = vec![Complex32::default(); n];
            // SAFETY: AVX2 checked above.
            let done = unsafe { evolve(&mut simd, &h0, &hm, &cycles, t) };
            assert!(done > n - 8, "{done}");
            for b in 0..done {
                let want = evolve_one(h0[b], hm[b], cycles[b], t);
                let got = simd[b];
                assert!(
                    want.re.to_bits() == got.re.to_bits() && want.im.to_bits() == got.im.to_bits(),
                    "t {t} entry {b}: {want} against {got}"
                );
            }
        }
        // Quarter turns exactly, where the quadrant's swap and signs decide the result.
        let cycles: Vec<f64> = (0..n).map(|i| i as f64 * 0.25).collect();
        let mut simd = vec![Complex32::default(); n];
        // SAFETY: as above.
        let done = unsafe { evolve(&mut simd, &h0, &hm, &cycles, 1.0) };
        for b in 0..done {
            let want = evolve_one(h0[b], hm[b], cycles[b], 1.0);
            assert_eq!((want.re.to_bits(), want.im.to_bits()), (simd[b].re.to_bits(), simd[b].im.to_bits()), "{b}");
        }
    }
}
