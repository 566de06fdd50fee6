//! The foam update fused into the row pass (`cascade.rs`) in AVX2 registers, eight samples at a
//! time: `v = min(ceiling, max(fresh c, first a + second b + gain c))`
//! ([`FoamWeights::apply`](crate::water::FoamWeights::apply)) with the coverage
//! `c = Φ((threshold - J) / σ)` ([`foam_coverage`](crate::water::foam_coverage)) of the Jacobian
//! `J = (1 + Dxx)(1 + Dzz) - Dxz²` (Tessendorf 2001 §4.6; paper 003 §1.3).
//!
//! The scalar loop is not vectorised by the compiler (the Jacobian terms sit interleaved in two
//! packed complex fields, Φ is a table look-up, and `f32::max` keeps its NaN rule). Here two loads
//! per field and an odd/even shuffle take the terms apart, and two gathers read Φ's table. The
//! arithmetic is the scalar one, operation for operation: the table position's clamp is
//! `min(last, max(t, 0))` with the operands in the order that turns a NaN into 0 as `f32::max`
//! does; `maxps(kept, fresh c)` gives `fresh c` for a NaN `kept` as `(fresh c).max(kept)` does, and
//! otherwise differs from it at most in the sign of a zero, which compares equal and cannot change
//! the output.

use rustfft::num_complex::Complex32;

use crate::math::{normal_cdf_table, NORMAL_CDF_LAST, NORMAL_CDF_RANGE, NORMAL_CDF_STEPS_PER_UNIT};
use crate::water::FoamWeights;

/// Updates `foam[i] = w.apply(c_i, first[i], second[i])` for i from 0 in groups of eight, where
/// `first` is `foam` itself when `None` and `second` is 0 when `None`, with
/// `Dxx = hz_dxx[i].im`, `Dzz = dzz_dxz[i].re`, `Dxz = dzz_dxz[i].im`, and returns the first i it did
/// not update (the caller does the rest with the scalar code).
///
/// # Safety
/// The CPU must have AVX2 (`fill_simd::available`).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
pub(super) unsafe fn update(
    foam: &mut [f32],
    first: Option<&[f32]>,
    second: Option<&[f32]>,
    hz_dxx: &[Complex32],
    dzz_dxz: &[Complex32],
    w: &FoamWeights,
) -> usize {
    use std::arch::x86_64::*;

    let n = foam.len();
    assert!(hz_dxx.len() == n && dzz_dxz.len() == n);
    assert!(first.is_none_or(|s| s.len() == n) && second.is_none_or(|s| s.len() == n));
    let (zero, one) = (_mm256_setzero_ps(), _mm256_set1_ps(1.0));
    let (th, inv) = (_mm256_set1_ps(w.threshold), _mm256_set1_ps(w.inv_spread));
    let (wa, wb, gain) = (_mm256_set1_ps(w.first), _mm256_set1_ps(w.second), _mm256_set1_ps(w.gain));
    let (fresh, ceiling) = (_mm256_set1_ps(w.fresh), _mm256_set1_ps(w.ceiling));
    let table = normal_cdf_table();
    let (range, steps) = (_mm256_set1_ps(NORMAL_CDF_RANGE), _mm256_set1_ps(NORMAL_CDF_STEPS_PER_UNIT));
    let last = _mm256_set1_ps(NORMAL_CDF_LAST);
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
            let x = _mm256_mul_ps(_mm256_sub_ps(th, j), inv);
            // `maxps(a, b)` is `a > b ? a : b`: a NaN in a gives b = 0, as `f32::max` does.
            let t = _mm256_min_ps(_mm256_max_ps(_mm256_mul_ps(_mm256_add_ps(x, range), steps), zero), last);
            let index = _mm256_cvttps_epi32(t);
            let f = _mm256_sub_ps(t, _mm256_cvtepi32_ps(index));
            // Positions in [0, last], so index + 1 is inside the table (normal_cdf.rs's one past).
            let lo = _mm256_i32gather_ps::<4>(table.as_ptr(), index);
            let hi = _mm256_i32gather_ps::<4>(table.as_ptr().add(1), index);
            let c = _mm256_add_ps(lo, _mm256_mul_ps(f, _mm256_sub_ps(hi, lo)));
            let at = foam.as_mut_ptr().add(i);
            let a = _mm256_loadu_ps(first.map_or(at.cast_const(), |s| s.as_ptr().add(i)));
            let b = second.map_or(zero, |s| _mm256_loadu_ps(s.as_ptr().add(i)));
            let kept = _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(wa, a), _mm256_mul_ps(wb, b)), _mm256_mul_ps(gain, c));
            let v = _mm256_min_ps(_mm256_max_ps(kept, _mm256_mul_ps(fresh, c)), ceiling);
            _mm256_storeu_ps(at, v);
        }
        i += 8;
    }
    i
}

#[cfg(all(test, target_arch = "x86_64"))]
mod tests {
    use super::*;
    use crate::water::fft_ocean::jacobian;
    use crate::water::foam_coverage;

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
        let other: Vec<f32> = (0..n).map(|i| wave(i, 0.9).abs() * 3.0).collect();
        let third: Vec<f32> = (0..n).map(|i| wave(i, 0.23).abs()).collect();
        let weights = |threshold, inv_spread, first, second, gain, fresh, ceiling| FoamWeights {
            threshold,
            inv_spread,
            first,
            second,
            gain,
            fresh,
            ceiling,
        };
        let cases = [
            // A lattice step (in place, gain, no ceiling), a frame (two sources), no persistence.
            weights(0.3, 3.0, 0.975, 0.0, 0.1, 0.0, f32::INFINITY),
            weights(0.8, 14.0, 0.9, 0.02, 0.0, 1.0, 1.0),
            weights(1.0, 1.0, 0.0, 0.0, 0.0, 1.0, 1.0),
            weights(-0.2, 0.5, 0.5, 0.5, 0.01, 1.0, 1.0),
            weights(0.5, 1e4, 0.97, 1e-3, 0.0005, 0.0, f32::INFINITY),
        ];
        for w in cases {
            for (first, second) in [(None, None), (Some(&other[..]), Some(&third[..])), (None, Some(&third[..]))] {
                let mut simd = start.clone();
                // SAFETY: AVX2 checked above.
                let done = unsafe { update(&mut simd, first, second, &hz_dxx, &dzz_dxz, &w) };
                assert!(done > n - 8, "{done}");
                for i in 0..done {
                    let c =
                        foam_coverage(jacobian(hz_dxx[i].im, dzz_dxz[i].re, dzz_dxz[i].im), w.threshold, w.inv_spread);
                    let want = w.apply(c, first.map_or(start[i], |s| s[i]), second.map_or(0.0, |s| s[i]));
                    assert_eq!(want, simd[i], "{w:?} sample {i}");
                }
            }
        }
    }
}
