//! A fast, vectorisable `sin_cos` for the per-vertex hot loops of the analytic wave models.
//!
//! `f32::sin_cos` calls the C library once per value and stops the compiler from vectorising the
//! loop around it; with 12 waves on a 512 x 512 grid that is 3 M calls per frame. This version is
//! straight-line arithmetic (no calls, no branches, no table), so loops over rows of vertices
//! vectorise.
//!
//! Method (Cody and Waite range reduction, Cephes polynomials; Moshier, *Methods and Programs for
//! Mathematical Functions*, 1989, `sinf.c`): `q = round(x 2/pi)` by the 1.5 * 2^23 rounding trick
//! (exact for |x 2/pi| < 2^22), `r = x - q pi/2` in three parts so the reduction is exact for
//! |q| < 2^16, then degree-7 sine and degree-8 cosine polynomials on |r| <= pi/4, and the quadrant
//! (q mod 4) selects and negates them.
//!
//! **Accuracy**: absolute error below [`FAST_SIN_COS_MAX_ERROR`] for |x| <= 1e4 rad (tested against
//! `f64::sin_cos`); the error of the `f32` argument itself (half an ulp of x, 5e-4 rad at x = 1e4)
//! dominates long before that. Outside |x| <= 4e6 the result is wrong; wave phases are reduced modulo
//! 2 pi per frame, so per-vertex arguments stay far below that.

// The constants are written as published (Cephes), digits beyond f32 included, so they can be checked.
#![allow(clippy::excessive_precision)]

/// Largest absolute error of [`fast_sin_cos`] for |x| <= 1e4 rad.
pub const FAST_SIN_COS_MAX_ERROR: f32 = 6e-7;

/// 1.5 * 2^23: adding then subtracting it rounds an f32 of magnitude below 2^22 to an integer.
const ROUND_MAGIC: f32 = 12_582_912.0;

/// pi/2 split in three parts (Cephes `DP1..DP3` doubled): the first two have few significant bits,
/// so `q * part` is exact for |q| < 2^16.
const PIO2_1: f32 = 1.570_312_5;
const PIO2_2: f32 = 4.837_512_969_970_703e-4;
const PIO2_3: f32 = 7.549_789_954_891_882e-8;

/// Returns `(sin x, cos x)`; see the [module documentation](self) for range and accuracy.
#[inline(always)]
pub fn fast_sin_cos(x: f32) -> (f32, f32) {
    let shifted = x * std::f32::consts::FRAC_2_PI + ROUND_MAGIC;
    // The low mantissa bits of `shifted` hold q as an integer (two's complement modulo 2^22).
    let quadrant = shifted.to_bits();
    let q = shifted - ROUND_MAGIC;
    let r = ((x - q * PIO2_1) - q * PIO2_2) - q * PIO2_3;
    let r2 = r * r;
    let sin_r = r + r * r2 * ((-1.951_529_6e-4 * r2 + 8.332_160_9e-3) * r2 - 1.666_665_5e-1);
    let cos_r = 1.0 - 0.5 * r2 + r2 * r2 * ((2.443_315_7e-5 * r2 - 1.388_731_6e-3) * r2 + 4.166_664_6e-2);
    let swap = quadrant & 1 != 0;
    let (s, c) = if swap { (cos_r, sin_r) } else { (sin_r, cos_r) };
    // sin is negated in quadrants 2 and 3, cos in quadrants 1 and 2.
    let sin_sign = (quadrant & 2) << 30;
    let cos_sign = (quadrant.wrapping_add(1) & 2) << 30;
    (f32::from_bits(s.to_bits() ^ sin_sign), f32::from_bits(c.to_bits() ^ cos_sign))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn agrees_with_the_library_within_the_stated_error() {
        let mut worst = 0.0f64;
        let n = 400_000;
        for i in 0..=n {
            let x = -1e4 + 2e4 * (i as f64 / n as f64);
            let x = x as f32 + (i % 7) as f32 * 1e-3;
            let (s, c) = fast_sin_cos(x);
            let (se, ce) = f64::from(x).sin_cos();
            worst = worst.max((f64::from(s) - se).abs()).max((f64::from(c) - ce).abs());
        }
        assert!(worst < f64::from(FAST_SIN_COS_MAX_ERROR), "worst error {worst:e}");
    }

    #[test]
    fn exact_at_the_quadrant_points() {
        for (x, s, c) in
            [(0.0f32, 0.0f32, 1.0f32), (std::f32::consts::FRAC_PI_2, 1.0, 0.0), (-std::f32::consts::PI, 0.0, -1.0)]
        {
            let (fs, fc) = fast_sin_cos(x);
            assert!((fs - s).abs() < 1e-7 && (fc - c).abs() < 1e-7, "{x}: {fs} {fc}");
        }
    }
}
