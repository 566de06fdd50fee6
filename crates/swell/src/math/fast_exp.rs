//! Base-2 exponential and logarithm for the per-pixel shading loops: plain arithmetic on the
//! float's bits (no table, no branch but a clamp), so that a loop of them vectorises, and with
//! errors far below what an 8-bit pixel shows ([`FAST_EXP2_MAX_REL_ERROR`],
//! [`FAST_LOG2_MAX_ABS_ERROR`], tested against the standard library).
//!
//! Both reduce the argument exactly and expand the rest in a short series: `log2` splits `x` into
//! `2^e m` with `m` in `[sqrt(1/2), sqrt(2))` and sums `2/ln 2 atanh(s)`, `s = (m - 1)/(m + 1)`
//! (`|s| <= 0.172`, so five odd terms leave < 1e-9); `exp2` splits `x` into an integer and a
//! fraction in `[-1/2, 1/2]` and sums the Taylor series of `e^(f ln 2)` to degree 7.

/// Largest relative error of [`fast_exp2`] over its range (tested).
pub const FAST_EXP2_MAX_REL_ERROR: f32 = 1e-6;
/// Largest error of [`fast_log2`] for positive normal inputs, relative to `max(1, |log2 x|)`
/// (below 1 absolute; above it the float spacing of the result dominates; tested).
pub const FAST_LOG2_MAX_ABS_ERROR: f32 = 1e-6;

/// `2^x`; inputs below -126.5 give 0 and above 127 give 2^127 (no infinities, no NaN for finite
/// input).
#[inline(always)]
pub fn fast_exp2(x: f32) -> f32 {
    let x = x.clamp(-127.0, 127.0);
    // Round to the nearest integer with the 1.5 * 2^23 trick: exact for |x| < 2^22, no branch.
    let shifted = x + 12_582_912.0;
    let i = shifted.to_bits() as i32 - 0x4B40_0000;
    let f = x - (shifted - 12_582_912.0);
    let t = f * std::f32::consts::LN_2;
    // e^t for |t| <= 0.347, Horner form of the Taylor series to t^7.
    let p = 1.0
        + t * (1.0
            + t * (0.5
                + t * (1.0 / 6.0 + t * (1.0 / 24.0 + t * (1.0 / 120.0 + t * (1.0 / 720.0 + t * (1.0 / 5040.0)))))));
    let scale = f32::from_bits(((i + 127).max(0) as u32) << 23);
    p * scale
}

/// `log2(x)` for positive normal `x`; 0 and subnormals give -126 or less (not -inf), so that
/// `fast_exp2(s * fast_log2(x))` is a small number rather than NaN.
#[inline(always)]
pub fn fast_log2(x: f32) -> f32 {
    let bits = x.max(f32::MIN_POSITIVE).to_bits();
    // Mantissa in [1, 2) and exponent; then move m >= sqrt(2) down an octave.
    let e = ((bits >> 23) & 0xFF) as i32 - 127;
    let m = f32::from_bits((bits & 0x007F_FFFF) | 0x3F80_0000);
    let big = m >= std::f32::consts::SQRT_2;
    let (m, e) = if big { (m * 0.5, e + 1) } else { (m, e) };
    let s = (m - 1.0) / (m + 1.0);
    let s2 = s * s;
    let series = s * (2.0 + s2 * (2.0 / 3.0 + s2 * (2.0 / 5.0 + s2 * (2.0 / 7.0 + s2 * (2.0 / 9.0)))));
    e as f32 + series * std::f32::consts::LOG2_E
}

/// `x^y` for `x >= 0`, `y` finite: `2^(y log2 x)`; `x = 0` with `y > 0` gives 0 (to within
/// 2^-126).
#[inline(always)]
pub fn fast_pow(x: f32, y: f32) -> f32 {
    fast_exp2(y * fast_log2(x))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exp2_matches_the_standard_library() {
        let mut worst = 0.0f32;
        let mut x = -125.0f32;
        while x < 126.0 {
            // (Below -126 the standard library returns subnormals, which this flushes.)
            let (a, b) = (fast_exp2(x), x.exp2());
            worst = worst.max(((a - b) / b).abs());
            x += 0.0137;
        }
        assert!(worst < FAST_EXP2_MAX_REL_ERROR, "worst relative error {worst}");
        assert_eq!(fast_exp2(-1000.0), 0.0);
        assert!(fast_exp2(1000.0).is_finite());
        assert_eq!(fast_exp2(0.0), 1.0);
    }

    #[test]
    fn log2_matches_the_standard_library() {
        let mut worst = 0.0f32;
        let mut x = 1e-30f32;
        while x < 1e30 {
            worst = worst.max((fast_log2(x) - x.log2()).abs() / x.log2().abs().max(1.0));
            x *= 1.0007;
        }
        assert!(worst < FAST_LOG2_MAX_ABS_ERROR, "worst absolute error {worst}");
        assert!(fast_log2(0.0) <= -126.0 && fast_log2(0.0).is_finite());
        assert_eq!(fast_log2(1.0), 0.0);
    }

    #[test]
    fn pow_of_a_specular_lobe_is_accurate_near_its_peak() {
        // Blinn-Phong lobes raise cosines near 1 to large powers: the error of log2 is multiplied
        // by the exponent, so check that product stays small where lobes are bright.
        for s in [10.0f32, 100.0, 1000.0, 5000.0] {
            for i in 0..1000 {
                let c = 1.0 - i as f32 * 1e-4;
                let (a, b) = (fast_pow(c, s), c.powf(s));
                assert!((a - b).abs() <= 1e-4 * b.max(1e-3), "{c}^{s}: {a} vs {b}");
            }
        }
        assert!(fast_pow(0.0, 3.0) < 1e-30);
    }
}
