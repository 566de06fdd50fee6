//! The row pass's transpose (`cascade.rs`) in AVX2 registers: 4 x 4 blocks of complex values.
//!
//! A complex f32 is 64 bits, so four of them fill a 256-bit register, and a 4 x 4 block transposes
//! with four 64-bit unpacks and four 128-bit lane permutes (values are moved, not computed, so the
//! output is the scalar transpose's, bit for bit).

use rustfft::num_complex::Complex32;

/// Writes `block[z * n + a + i] = columns[i][z]` for z in `0..rows`, i in 0..4: four kx columns
/// (each `rows` values, a multiple of 4) into four entries of each of `rows` output rows of length
/// `n`.
///
/// # Safety
/// The CPU must have AVX2 (`fill_simd::available`).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
pub(super) unsafe fn transpose4(columns: [&[Complex32]; 4], block: &mut [Complex32], n: usize, a: usize) {
    use std::arch::x86_64::*;

    let rows = columns[0].len();
    assert!(rows % 4 == 0 && columns.iter().all(|c| c.len() == rows) && a + 4 <= n && block.len() >= rows * n);
    let [c0, c1, c2, c3] = columns;
    for z in (0..rows).step_by(4) {
        // SAFETY: z + 4 <= rows values of every column; rows (z .. z + 4) * n + a + 4 <= block.len().
        unsafe {
            let ld = |c: &[Complex32]| _mm256_loadu_pd(c.as_ptr().add(z).cast());
            let (p, q, r, s) = (ld(c0), ld(c1), ld(c2), ld(c3));
            // One complex is one f64 here: output rows are n f64 apart.
            // [p0 q0 | p2 q2], [p1 q1 | p3 q3], [r0 s0 | r2 s2], [r1 s1 | r3 s3].
            let (t0, t1) = (_mm256_unpacklo_pd(p, q), _mm256_unpackhi_pd(p, q));
            let (t2, t3) = (_mm256_unpacklo_pd(r, s), _mm256_unpackhi_pd(r, s));
            let out = block.as_mut_ptr().add(z * n + a).cast::<f64>();
            _mm256_storeu_pd(out, _mm256_permute2f128_pd::<0x20>(t0, t2));
            _mm256_storeu_pd(out.add(n), _mm256_permute2f128_pd::<0x20>(t1, t3));
            _mm256_storeu_pd(out.add(2 * n), _mm256_permute2f128_pd::<0x31>(t0, t2));
            _mm256_storeu_pd(out.add(3 * n), _mm256_permute2f128_pd::<0x31>(t1, t3));
        }
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
        let (n, rows, a) = (32, 16, 8);
        let cols: Vec<Vec<Complex32>> =
            (0..4).map(|i| (0..rows).map(|z| Complex32::new(i as f32, z as f32 + 0.5)).collect()).collect();
        let mut block = vec![Complex32::new(-1.0, -1.0); rows * n];
        // SAFETY: AVX2 checked above.
        unsafe { transpose4([&cols[0], &cols[1], &cols[2], &cols[3]], &mut block, n, a) };
        for z in 0..rows {
            for x in 0..n {
                let want = if (a..a + 4).contains(&x) { cols[x - a][z] } else { Complex32::new(-1.0, -1.0) };
                assert_eq!(block[z * n + x], want, "row {z} column {x}");
            }
        }
    }
}
