//! The fill of the four packed spectra (`cascade.rs`, `write_multiplied`) in AVX2 registers,
//! four wave vectors at a time.
//!
//! The compiler does not vectorise the scalar fill: each entry is four complex products stored
//! interleaved (re, im), about 26 instructions an entry. Here the complex values stay interleaved
//! in the registers; a product `h (p + i q)` is `h p + swap(h) q` with the sign of the real slot
//! flipped. Every value is computed by the same IEEE operations as the scalar code (`a - b` is
//! `a + (-b)`, additions are commutative, no fused multiply-add), so the spectra, and the sea, are
//! bit for bit those of the scalar fill: the run-time choice does not change the output.

use rustfft::num_complex::Complex32;

/// Whether [`fill`] may be called: the CPU has AVX2.
pub(super) fn available() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        std::arch::is_x86_feature_detected!("avx2")
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}

/// Writes entries b of the four packed spectra `out` (each n long) from `h(b)`, for b from 0
/// (from 1 with `mirror`) in groups of four, and returns the first b it did not write (the caller
/// writes the rest with the scalar code). `h(b) = h[b]`, or `conj(h[n - b])` with `mirror`; kx is
/// the row's, `kk[b]` the column's kz, `l[b] = λ/|k|`: see `write_multiplied` for the multipliers.
///
/// # Safety
/// The CPU must have AVX2 ([`available`]).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
pub(super) unsafe fn fill(
    out: [&mut [Complex32]; 4],
    h: &[Complex32],
    kx: f32,
    kk: &[f32],
    l: &[f32],
    mirror: bool,
) -> usize {
    use std::arch::x86_64::*;

    let n = h.len();
    assert!(kk.len() == n && l.len() == n && out.iter().all(|o| o.len() == n));
    let [o0, o1, o2, o3] = out;
    // Each of four floats twice: [a0 a0 a1 a1 a2 a2 a3 a3], one per (re, im) slot.
    let twice = _mm256_setr_epi32(0, 0, 1, 1, 2, 2, 3, 3);
    let neg_re = _mm256_setr_ps(-0.0, 0.0, -0.0, 0.0, -0.0, 0.0, -0.0, 0.0);
    let neg_all = _mm256_set1_ps(-0.0);
    let (kxv, one) = (_mm256_set1_ps(kx), _mm256_set1_ps(1.0));
    let p = _mm256_set1_ps(-kx);
    let mut b = usize::from(mirror);
    while b + 4 <= n {
        // SAFETY: b + 4 <= n values of kk, l and every out; with `mirror`, b >= 1, so h's entries
        // n - b - 3 .. n - b + 1 are in bounds.
        unsafe {
            let hv = if mirror {
                // h[n-b-3 .. n-b+1] reversed to (n-b, n-b-1, n-b-2, n-b-3), then conjugated.
                let v = _mm256_loadu_ps(h.as_ptr().add(n - b - 3).cast());
                let v = _mm256_castpd_ps(_mm256_permute4x64_pd::<0b00_01_10_11>(_mm256_castps_pd(v)));
                _mm256_xor_ps(v, _mm256_xor_ps(neg_re, neg_all))
            } else {
                _mm256_loadu_ps(h.as_ptr().add(b).cast())
            };
            let hs = _mm256_permute_ps::<0b10_11_00_01>(hv);
            let kz = _mm256_permutevar8x32_ps(_mm256_castps128_ps256(_mm_loadu_ps(kk.as_ptr().add(b))), twice);
            let lv = _mm256_permutevar8x32_ps(_mm256_castps128_ps256(_mm_loadu_ps(l.as_ptr().add(b))), twice);
            let lkx = _mm256_mul_ps(lv, kxv);
            // (h, Dx): h (1 - l kx).
            let s0 = _mm256_sub_ps(one, lkx);
            _mm256_storeu_ps(o0.as_mut_ptr().add(b).cast(), _mm256_mul_ps(hv, s0));
            // (Dz, hx): h (p + i q), p = -kx, q = l kz.
            let q = _mm256_mul_ps(lv, kz);
            let v1 = _mm256_add_ps(_mm256_mul_ps(hv, p), _mm256_xor_ps(_mm256_mul_ps(hs, q), neg_re));
            _mm256_storeu_ps(o1.as_mut_ptr().add(b).cast(), v1);
            // (hz, Dxx): h (i r), r = kz - l kx kx.
            let r = _mm256_sub_ps(kz, _mm256_mul_ps(lkx, kxv));
            _mm256_storeu_ps(o2.as_mut_ptr().add(b).cast(), _mm256_xor_ps(_mm256_mul_ps(hs, r), neg_re));
            // (Dzz, Dxz): h (u + i v), u = -l kz kz, v = -l kx kz.
            let nl = _mm256_xor_ps(lv, neg_all);
            let u = _mm256_mul_ps(_mm256_mul_ps(nl, kz), kz);
            let v = _mm256_mul_ps(_mm256_mul_ps(nl, kxv), kz);
            let v3 = _mm256_add_ps(_mm256_mul_ps(hv, u), _mm256_xor_ps(_mm256_mul_ps(hs, v), neg_re));
            _mm256_storeu_ps(o3.as_mut_ptr().add(b).cast(), v3);
        }
        b += 4;
    }
    b
}

#[cfg(all(test, target_arch = "x86_64"))]
mod tests {
    use super::*;
    use crate::water::fft_ocean::cascade::write_multiplied;

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
        for mirror in [false, true] {
            for kx in [0.0, 0.4271, -1.37] {
                let value = |b: usize| if mirror { h[(n - b) % n].conj() } else { h[b] };
                let mut scalar: [Vec<Complex32>; 4] = std::array::from_fn(|_| vec![Complex32::default(); n]);
                for b in 0..n {
                    let [a, c, d, e] = &mut scalar;
                    write_multiplied([a, c, d, e], b, value(b), kx, kk[b], l[b]);
                }
                let mut simd: [Vec<Complex32>; 4] = std::array::from_fn(|_| vec![Complex32::default(); n]);
                let [a, c, d, e] = &mut simd;
                // SAFETY: AVX2 checked above.
                let done = unsafe { fill([a, c, d, e], &h, kx, &kk, &l, mirror) };
                assert!(done > n - 4, "{done}");
                for b in usize::from(mirror)..done {
                    for p in 0..4 {
                        let (x, y) = (scalar[p][b], simd[p][b]);
                        assert!(
                            x.re.to_bits() == y.re.to_bits() && x.im.to_bits() == y.im.to_bits(),
                            "mirror {mirror} kx {kx} pair {p} entry {b}: {x} against {y}"
                        );
                    }
                }
            }
        }
    }
}
