//! The foam update fused into the row pass (`cascade.rs`) in AVX2 registers, eight samples at a
//! time: `v = max(coverage(J), previous decay - floor)` ([`foam_update`](crate::water::foam::foam_update))
//! with the Jacobian
//! `J = (1 + Dxx)(1 + Dzz) - Dxz²` (Tessendorf 2001 §4.6; paper 003 §1.3) and
//! [`foam_coverage`](crate::water::foam_coverage)'s ramp.
//!
//! The scalar loop is not vectorised by the compiler (the Jacobian terms sit interleaved in two
//! packed complex fields, and `f32::max` / `clamp` keep their NaN rules): about 7 instructions a
//! sample. Here two loads per field and an odd/even shuffle take the terms apart. The arithmetic is
//! the scalar one, operation for operation (the clamp is `min(1, max(0, x))` with the operands in
//! the order that keeps a NaN or a negative zero as `clamp` does); the final `max` of two
//! non-negative, non-NaN values differs from `f32::max` at most in the sign of a zero, which
//! compares equal and cannot change the output.

use rustfft::num_complex::Complex32;

use crate::water::FOAM_RAMP;

/// Updates `foam[i] = max(coverage(J_i), previous[i] decay - floor)` for i from 0 in groups of
/// eight, where `previous` is `source` or, without one, `foam` itself, with
/// `Dxx = hz_dxx[i].im`, `Dzz = dzz_dxz[i].re`, `Dxz = dzz_dxz[i].im`, and returns the first i it did
/// not update (the caller does the rest with the scalar code).
///
/// # Safety
/// The CPU must have AVX2 (`fill_simd::available`).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
pub(super) unsafe fn update(
    foam: &mut [f32],
    source: Option<&[f32]>,
    hz_dxx: &[Complex32],
    dzz_dxz: &[Complex32],
    threshold: f32,
    decay: f32,
    floor: f32,
) -> usize {
    use std::arch::x86_64::*;

    let n = foam.len();
    assert!(hz_dxx.len() == n && dzz_dxz.len() == n && source.is_none_or(|s| s.len() == n));
    let (zero, one) = (_mm256_setzero_ps(), _mm256_set1_ps(1.0));
    let (th, ramp, dec) = (_mm256_set1_ps(threshold), _mm256_set1_ps(FOAM_RAMP), _mm256_set1_ps(decay));
    let low = _mm256_set1_ps(floor);
    let mut i = 0;
    while i + 8 <= n {
        // SAFETY: i + 8 <= n entries of every slice.
        unsafe {
            // Two registers of four complex values -> the eight real (even) or imaginary (odd) parts,
            // in order (the shuffle works within 128-bit lanes; the permute restores the order).
            let parts = |src: &[Complex32]| {
                let a = _mm256_loadu_ps(src.as_ptr().add(i).cast());
                let b = _mm256_loadu_ps(src.as_ptr().add(i + 4).cast());
                let order = |v: __m256| _mm256_castpd_ps(_mm256_permute4x64_pd::<0b11_01_10_00>(_mm256_castps_pd(v)));
                (order(_mm256_shuffle_ps::<0b10_00_10_00>(a, b)), order(_mm256_shuffle_ps::<0b11_01_11_01>(a, b)))
            };
            let (_, dxx) = parts(hz_dxx);
            let (dzz, dxz) = parts(dzz_dxz);
            let j =
                _mm256_sub_ps(_mm256_mul_ps(_mm256_add_ps(one, dxx), _mm256_add_ps(one, dzz)), _mm256_mul_ps(dxz, dxz));
            let ramped = _mm256_div_ps(_mm256_sub_ps(th, j), ramp);
            // `maxps(a, b)` is `a > b ? a : b`: with a = 0 a NaN or -0 in b passes, as in `clamp`.
            let coverage = _mm256_min_ps(one, _mm256_max_ps(zero, ramped));
            let at = foam.as_mut_ptr().add(i);
            let previous = source.map_or(at.cast_const(), |s| s.as_ptr().add(i));
            let kept = _mm256_sub_ps(_mm256_mul_ps(_mm256_loadu_ps(previous), dec), low);
            _mm256_storeu_ps(at, _mm256_max_ps(coverage, kept));
        }
        i += 8;
    }
    i
}

#[cfg(all(test, target_arch = "x86_64"))]
mod tests {
    use super::*;
    use crate::water::fft_ocean::jacobian;
    use crate::water::foam::{foam_coverage, foam_update};

    #[test]
    fn the_avx2_foam_update_equals_the_scalar_update() {
        if !super::super::fill_simd::available() {
            return;
        }
        let n = 45; // not a multiple of 8: the scalar tail runs too
        let wave = |i: usize, f: f32| (i as f32 * f).sin();
        let hz_dxx: Vec<Complex32> = (0..n).map(|i| Complex32::new(wave(i, 0.3), wave(i, 0.71) * 0.9)).collect();
        let dzz_dxz: Vec<Complex32> = (0..n).map(|i| Complex32::new(wave(i, 1.3) * 0.8, wave(i, 0.17) * 0.6)).collect();
        let start: Vec<f32> = (0..n).map(|i| if i % 5 == 0 { 0.0 } else { wave(i, 0.5).abs() }).collect();
        let other: Vec<f32> = (0..n).map(|i| wave(i, 0.9).abs()).collect();
        let cases = [(0.3, 0.9, 0.0), (0.8, 0.0, 0.0), (1.0, 1.0, 0.0), (-0.2, 0.5, 0.01), (0.5, 0.97, 0.0005)];
        for ((threshold, decay, floor), source) in cases.into_iter().flat_map(|c| [(c, None), (c, Some(&other[..]))]) {
            let mut simd = start.clone();
            // SAFETY: AVX2 checked above.
            let done = unsafe { update(&mut simd, source, &hz_dxx, &dzz_dxz, threshold, decay, floor) };
            assert!(done > n - 8, "{done}");
            for i in 0..done {
                let coverage = foam_coverage(jacobian(hz_dxx[i].im, dzz_dxz[i].re, dzz_dxz[i].im), threshold);
                let want = foam_update(coverage, source.map_or(start[i], |s| s[i]), decay, floor);
                assert_eq!(want, simd[i], "threshold {threshold} decay {decay} floor {floor} sample {i}");
            }
        }
    }
}
