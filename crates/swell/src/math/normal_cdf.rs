//! The standard normal distribution function Φ, read from a table: the probability that a
//! Gaussian quantity lies below a level (the FFT ocean's whitecaps: the chance that the Jacobian,
//! resolved plus unresolved, falls below the breaking threshold; `water/foam.rs`).
//!
//! A table rather than a formula, so that the scalar code and the eight-lane AVX2 code
//! (`water/fft_ocean/foam_simd.rs`, two gathers) compute the same bits with the same operations:
//! `Φ(x)` is interpolated linearly between `Φ(-8 + i / 64)`, an error below 1e-5 (`h² Φ''_max / 8`
//! with `h = 1/64`), far below what an 8-bit foam map resolves.

use std::sync::OnceLock;

/// Samples per unit of x.
pub const NORMAL_CDF_STEPS_PER_UNIT: f32 = 64.0;
/// The table covers `[-NORMAL_CDF_RANGE, NORMAL_CDF_RANGE]`; outside it Φ is 0 or 1 to 1e-15.
pub const NORMAL_CDF_RANGE: f32 = 8.0;
/// Largest table position `(x + range) · steps`: the last interval starts there.
pub const NORMAL_CDF_LAST: f32 = 2.0 * NORMAL_CDF_RANGE * NORMAL_CDF_STEPS_PER_UNIT;
/// Entries: one per step over the range, and one past the end so that the last interval has its
/// upper end.
const LEN: usize = NORMAL_CDF_LAST as usize + 2;

/// `Φ(-8 + i / 64)` for `i` in `0..LEN`, computed once: `0.5 + ∫_0^x φ`, Simpson's rule with 16
/// panels per entry (error below 1e-14), accumulated outwards from 0 in f64 so that `Φ(-x)` is
/// `1 - Φ(x)` to rounding; below 1e-9 from 0 or 1, exactly 0 or 1.
pub fn normal_cdf_table() -> &'static [f32] {
    static TABLE: OnceLock<Vec<f32>> = OnceLock::new();
    TABLE.get_or_init(|| {
        let pdf = |x: f64| (-0.5 * x * x).exp() / std::f64::consts::TAU.sqrt();
        let h = 1.0 / f64::from(NORMAL_CDF_STEPS_PER_UNIT);
        let panels = 16;
        let simpson = |a: f64| {
            let s = h / f64::from(panels);
            let inner: f64 = (1..panels).map(|p| if p % 2 == 1 { 4.0 } else { 2.0 } * pdf(a + f64::from(p) * s)).sum();
            (pdf(a) + inner + pdf(a + h)) * s / 3.0
        };
        let centre = (NORMAL_CDF_RANGE * NORMAL_CDF_STEPS_PER_UNIT) as usize;
        let mut values = vec![0.0f64; LEN];
        values[centre] = 0.5;
        for i in centre + 1..LEN {
            let a = (i - 1 - centre) as f64 * h;
            values[i] = values[i - 1] + simpson(a);
        }
        for i in (0..centre).rev() {
            values[i] = 1.0 - values[2 * centre - i];
        }
        // Φ(±6) is 1e-9 from 0 or 1: beyond that a probability is none or certain, so that
        // calm water has no foam at all rather than 1e-15 of it.
        values
            .into_iter()
            .map(|v| {
                if v < 1e-9 {
                    0.0
                } else if v > 1.0 - 1e-9 {
                    1.0
                } else {
                    v as f32
                }
            })
            .collect()
    })
}

/// Φ(x), the probability that a standard normal variable is below `x`, in [0, 1]; a NaN reads as
/// `-8` (0).
#[inline]
// `clamp` would keep a NaN; max-then-min turns it into 0, as the AVX2 code does.
#[allow(clippy::manual_clamp)]
pub fn normal_cdf(x: f32) -> f32 {
    let table = normal_cdf_table();
    // `max` before `min`, as the AVX2 code orders them: a NaN becomes 0 there and here.
    let t = ((x + NORMAL_CDF_RANGE) * NORMAL_CDF_STEPS_PER_UNIT).max(0.0).min(NORMAL_CDF_LAST);
    let i = t as i32 as usize;
    let f = t - i as f32;
    let (a, b) = (table[i], table[i + 1]);
    a + f * (b - a)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn phi_has_its_known_values() {
        // Φ at 0, ±1, ±2, 3 (Abramowitz and Stegun, table 26.1).
        for (x, want) in [
            (0.0, 0.5),
            (1.0, 0.841_344_75),
            (-1.0, 0.158_655_25),
            (2.0, 0.977_249_87),
            (-2.0, 0.022_750_13),
            (3.0, 0.998_650_1),
        ] {
            assert!((f64::from(normal_cdf(x)) - want).abs() < 1e-6, "Φ({x}) = {}", normal_cdf(x));
        }
        // Between table points (the interpolation error bound), the tails and NaN.
        assert!((f64::from(normal_cdf(-2.5077)) - 0.006_077_6).abs() < 1e-5, "{}", normal_cdf(-2.5077));
        assert_eq!(normal_cdf(-20.0), 0.0);
        assert_eq!(normal_cdf(20.0), 1.0);
        assert_eq!(normal_cdf(f32::NAN), 0.0);
        // Monotone.
        let mut last = 0.0;
        for i in -1000..1000 {
            let v = normal_cdf(i as f32 * 0.01);
            assert!(v >= last);
            last = v;
        }
    }
}
