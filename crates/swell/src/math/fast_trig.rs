//! Fast, vectorisable sine and cosine for the hot loops: per vertex in the analytic wave models
//! ([`fast_sin_cos`], argument in radians) and per wave in the FFT ocean ([`sin_cos_turns`], phase
//! in turns, after [`reduce_turns`]).
//!
//! `f32::sin_cos` calls the C library once per value and stops the compiler from vectorising the
//! loop around it; with 12 waves on a 512 x 512 grid that is 3 M calls per frame. These versions are
//! straight-line arithmetic (no calls, no branches, no table), so loops over rows of vertices or
//! waves vectorise.
//!
//! Method (Cody and Waite range reduction, Cephes polynomials; Moshier, *Methods and Programs for
//! Mathematical Functions*, 1989, `sinf.c`): reduce the angle to a remainder r with |r| <= pi/4 and
//! a quadrant q, evaluate the degree-7 sine and degree-8 cosine polynomials of r, and let q (mod 4)
//! select and negate them. The two entry points differ only in the reduction:
//!
//! - radians: `q = round(x 2/pi)` by the 1.5 * 2^23 rounding trick (exact for |x 2/pi| < 2^22),
//!   `r = x - q pi/2` in three parts so the reduction is exact for |q| < 2^16;
//! - turns: phases are kept in f64 turns and reduced exactly to c in [-1/2, 1/2] ([`reduce_turns`]),
//!   then `q = round(4 c)` and `r = 2 pi (c - q/4)`, where `c - q/4` is exact.
//!
//! **Accuracy**: absolute error below [`FAST_SIN_COS_MAX_ERROR`] for |x| <= 1e4 rad and for every
//! turn (tested against `f64::sin_cos`); for large radian arguments the error of the `f32` argument
//! itself (half an ulp of x, 5e-4 rad at x = 1e4) dominates long before that. Outside |x| <= 4e6
//! the radian result is wrong; wave phases are reduced modulo 2 pi per frame, so per-vertex
//! arguments stay far below that.

// The constants are written as published (Cephes), digits beyond f32 included, so they can be checked.
#![allow(clippy::excessive_precision)]

/// Largest absolute error of [`fast_sin_cos`] for |x| <= 1e4 rad.
pub const FAST_SIN_COS_MAX_ERROR: f32 = 6e-7;

/// 1.5 * 2^23: adding then subtracting it rounds an f32 of magnitude below 2^22 to an integer.
const ROUND_MAGIC: f32 = 12_582_912.0;

/// The f64 counterpart, 1.5 * 2^52: rounds an f64 of magnitude below 2^51 with plain additions
/// (which vectorise, unlike a call to `round`).
const ROUND_MAGIC_F64: f64 = 6_755_399_441_055_744.0;

/// pi/2 split in three parts (Cephes `DP1..DP3` doubled): the first two have few significant bits,
/// so `q * part` is exact for |q| < 2^16.
const PIO2_1: f32 = 1.570_312_5;
const PIO2_2: f32 = 4.837_512_969_970_703e-4;
const PIO2_3: f32 = 7.549_789_954_891_882e-8;

/// Returns `(sin x, cos x)` for x in radians; see the [module documentation](self) for range and
/// accuracy.
#[inline(always)]
pub fn fast_sin_cos(x: f32) -> (f32, f32) {
    let shifted = x * std::f32::consts::FRAC_2_PI + ROUND_MAGIC;
    // The low mantissa bits of `shifted` hold q as an integer (two's complement modulo 2^22).
    let quadrant = shifted.to_bits();
    let q = shifted - ROUND_MAGIC;
    let r = ((x - q * PIO2_1) - q * PIO2_2) - q * PIO2_3;
    sin_cos_reduced(r, quadrant)
}

/// The fractional part of `turns` in [-0.5, 0.5] (nearest-integer reduction), as f32.
///
/// Exact for |turns| < 2^51; phases are kept in f64 turns up to here so that a sea stays exact for
/// hours of simulated time, then reduced once and handed to f32 work.
#[inline(always)]
pub fn reduce_turns(turns: f64) -> f32 {
    let r = turns - ((turns + ROUND_MAGIC_F64) - ROUND_MAGIC_F64);
    (r as f32).clamp(-0.5, 0.5)
}

/// `(sin, cos)` of the angle `2π c` for c in turns, |c| <= 0.5 (see [`reduce_turns`]); same
/// polynomials and accuracy as [`fast_sin_cos`].
#[inline(always)]
pub fn sin_cos_turns(c: f32) -> (f32, f32) {
    // |4c| <= 2, far inside the magic constant's range; the result is the nearest quarter turn.
    let q = (4.0 * c + ROUND_MAGIC) - ROUND_MAGIC;
    let r = std::f32::consts::TAU * (c - 0.25 * q);
    sin_cos_reduced(r, q as i32 as u32)
}

/// Sine and cosine of `r + quadrant π/2` for |r| <= π/4: the Cephes polynomials, then the quadrant
/// (its two low bits, two's complement) swaps and negates them.
#[inline(always)]
fn sin_cos_reduced(r: f32, quadrant: u32) -> (f32, f32) {
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

/// `x.floor()` for |x| < 2^31 without a call into libm (the x86-64 baseline has no floor
/// instruction): truncate, then step down for negative non-integers.
#[inline(always)]
pub fn fast_floor(x: f32) -> f32 {
    let t = x as i32 as f32;
    if t > x {
        t - 1.0
    } else {
        t
    }
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

    #[test]
    fn turns_match_the_standard_library_over_the_whole_turn() {
        for i in -20_000..=20_000 {
            let c = i as f32 / 40_000.0;
            let (s, co) = sin_cos_turns(c);
            let (es, ec) = (f64::from(c) * std::f64::consts::TAU).sin_cos();
            let err = (f64::from(s) - es).abs().max((f64::from(co) - ec).abs());
            assert!(err < f64::from(FAST_SIN_COS_MAX_ERROR), "{c}: {s} {co}");
        }
        assert_eq!(sin_cos_turns(0.25), (1.0, 0.0));
        assert_eq!(sin_cos_turns(-0.5), (0.0, -1.0));
    }

    #[test]
    fn fast_floor_is_floor() {
        for x in [-3.5f32, -3.0, -0.25, 0.0, 0.25, 2.0, 2.999, 1e6 + 0.5] {
            assert_eq!(fast_floor(x), x.floor(), "{x}");
        }
    }

    #[test]
    fn reduction_keeps_the_fraction_for_large_phases() {
        assert_eq!(reduce_turns(12_345_678.25), 0.25);
        assert_eq!(reduce_turns(-3.75), 0.25);
        assert!((reduce_turns(1e9 + 0.1) - 0.1).abs() < 1e-6);
    }
}
