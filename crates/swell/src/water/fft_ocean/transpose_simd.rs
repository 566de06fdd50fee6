//! The row pass's transpose (`cascade.rs`) in AVX2 registers: 4 x 4 blocks of complex values,
//! a task's whole block of output rows per call.
//!
//! A complex f32 is 64 bits, so four of them fill a 256-bit register, and a 4 x 4 block transposes
//! with four 64-bit unpacks and four 128-bit lane permutes (values are moved, not computed, so the
//! output is the scalar transpose's, bit for bit).

use rustfft::num_complex::Complex32;

/// Writes `block[z * n + a] = src[slots[a] + z0 + z]` for every kx index a in 0..n and z in
/// `0..rows`: the task's `rows` output rows (each n long) out of the column buffer `src`, whose
/// slot of kx index a starts at `slots[a]`. Four kx at a time, in 4 x 4 blocks; the bounds are
/// checked once per call, not per block.
///
/// # Safety
/// The CPU must have AVX2 (`fill_simd::available`).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
pub(super) unsafe fn transpose_rows(
    src: &[Complex32],
    slots: &[usize],
    z0: usize,
    rows: usize,
    block: &mut [Complex32],
    n: usize,
) {
    use std::arch::x86_64::*;

    assert!(rows % 4 == 0 && n % 4 == 0 && slots.len() == n && block.len() >= rows * n);
    assert!(slots.iter().all(|&s| s + z0 + rows <= src.len()));
    let out = block.as_mut_ptr().cast::<f64>();
    let mut a = 0;
    while a < n {
        // SAFETY: slots[a..a + 4] + z0 + rows <= src.len() (checked above), and output rows
        // (z .. z + 4) * n + a + 4 <= rows * n <= block.len().
        unsafe {
            let c0 = src.as_ptr().add(slots[a] + z0).cast::<f64>();
            let c1 = src.as_ptr().add(slots[a + 1] + z0).cast::<f64>();
            let c2 = src.as_ptr().add(slots[a + 2] + z0).cast::<f64>();
            let c3 = src.as_ptr().add(slots[a + 3] + z0).cast::<f64>();
            let mut z = 0;
            while z < rows {
                let (p, q) = (_mm256_loadu_pd(c0.add(z)), _mm256_loadu_pd(c1.add(z)));
                let (r, s) = (_mm256_loadu_pd(c2.add(z)), _mm256_loadu_pd(c3.add(z)));
                // One complex is one f64 here: output rows are n f64 apart.
                // [p0 q0 | p2 q2], [p1 q1 | p3 q3], [r0 s0 | r2 s2], [r1 s1 | r3 s3].
                let (t0, t1) = (_mm256_unpacklo_pd(p, q), _mm256_unpackhi_pd(p, q));
                let (t2, t3) = (_mm256_unpacklo_pd(r, s), _mm256_unpackhi_pd(r, s));
                let o = out.add(z * n + a);
                _mm256_storeu_pd(o, _mm256_permute2f128_pd::<0x20>(t0, t2));
                _mm256_storeu_pd(o.add(n), _mm256_permute2f128_pd::<0x20>(t1, t3));
                _mm256_storeu_pd(o.add(2 * n), _mm256_permute2f128_pd::<0x31>(t0, t2));
                _mm256_storeu_pd(o.add(3 * n), _mm256_permute2f128_pd::<0x31>(t1, t3));
                z += 4;
            }
        }
        a += 4;
    }
}

#[cfg(all(test, target_arch = "x86_64"))]
mod tests {
    use super::*;

    #[test]
    fn the_avx2_transpose_writes_each_column_into_its_place_in_every_row() {
        if !super::super::fill_simd::available() {
            return;
        }
        let (n, rows, z0, stride) = (32, 16, 16, 48);
        // Slots in a shuffled order with a padded stride, as in the column buffers.
        let slots: Vec<usize> = (0..n).map(|a| ((a * 7) % n) * stride).collect();
        let src: Vec<Complex32> = (0..n * stride).map(|i| Complex32::new(i as f32, -(i as f32) - 0.5)).collect();
        let mut block = vec![Complex32::new(-1.0, -1.0); rows * n];
        // SAFETY: AVX2 checked above.
        unsafe { transpose_rows(&src, &slots, z0, rows, &mut block, n) };
        for z in 0..rows {
            for a in 0..n {
                assert_eq!(block[z * n + a], src[slots[a] + z0 + z], "row {z} column {a}");
            }
        }
    }
}
