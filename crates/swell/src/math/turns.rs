//! Phases measured in turns (the FFT ocean's per-wave clocks): exact f64 reduction to [-1/2, 1/2],
//! then sine and cosine of a turn, branch-free so loops over waves vectorise.
//!
//! `fast_trig` holds the grid evaluators' radian-based `fast_sin_cos`; both are polynomial and within
//! 7e-7. Unifying them is an open item (docs/ARCHITECTURE.md).

use std::f32::consts::TAU;

/// Adding and subtracting 1.5 * 2^52 rounds an f64 of magnitude below 2^51 to the nearest integer
/// with plain additions (which vectorise, unlike a call to `round`).
const ROUND_MAGIC: f64 = 6_755_399_441_055_744.0;

/// The f32 counterpart, 1.5 * 2^23: rounds values of magnitude below 2^22.
const ROUND_MAGIC_F32: f32 = 12_582_912.0;

/// The fractional part of `turns` in [-0.5, 0.5] (nearest-integer reduction), as f32.
///
/// Exact for |turns| < 2^51; phases are kept in f64 turns up to here so that a sea stays exact for
/// hours of simulated time, then reduced once and handed to f32 work.
#[inline(always)]
pub fn reduce_turns(turns: f64) -> f32 {
    let r = turns - ((turns + ROUND_MAGIC) - ROUND_MAGIC);
    (r as f32).clamp(-0.5, 0.5)
}

/// `(sin, cos)` of the angle `2π c` for c in turns, |c| <= 0.5 (see [`reduce_turns`]).
///
/// Splits c into a quarter turn q and a remainder of at most 1/8 turn (π/4), where the Taylor
/// series to x⁷ (sine) and x⁸ (cosine) are within 3.2e-7 (the next terms, (π/4)^9/9! and
/// (π/4)^10/10!), then rotates by q quarter turns. Branch-free so that loops over waves vectorise.
#[inline(always)]
pub fn sin_cos_turns(c: f32) -> (f32, f32) {
    // |4c| <= 2, far inside the magic constant's range; the result is the nearest quarter turn.
    let q = (4.0 * c + ROUND_MAGIC_F32) - ROUND_MAGIC_F32;
    let x = TAU * (c - 0.25 * q);
    let x2 = x * x;
    let s = x * (1.0 - x2 / 6.0 * (1.0 - x2 / 20.0 * (1.0 - x2 / 42.0)));
    let co = 1.0 - x2 / 2.0 * (1.0 - x2 / 12.0 * (1.0 - x2 / 30.0 * (1.0 - x2 / 56.0)));
    // Rotation by q quarter turns: (s, c), (c, -s), (-s, -c), (-c, s) for q = 0..3 (mod 4), as
    // arithmetic on masks rather than branches.
    let qi = (q as i32) & 3;
    let swap = (qi & 1) as f32;
    let (s1, c1) = (s + swap * (co - s), co + swap * (s - co));
    let sin = s1 * (1 - 2 * ((qi >> 1) & 1)) as f32;
    let cos = c1 * (1 - 2 * (((qi + 1) >> 1) & 1)) as f32;
    (sin, cos)
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
    fn matches_the_standard_library_over_the_whole_turn() {
        for i in -20_000..=20_000 {
            let c = i as f32 / 40_000.0;
            let (s, co) = sin_cos_turns(c);
            let (es, ec) = (f64::from(c) * std::f64::consts::TAU).sin_cos();
            assert!((f64::from(s) - es).abs() < 6e-7 && (f64::from(co) - ec).abs() < 6e-7, "{c}: {s} {co}");
        }
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
