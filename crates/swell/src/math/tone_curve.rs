//! The tone curves between scene radiance (after exposure) and display-linear values: what
//! `[render] tone_curve` selects.
//!
//! A physical sun glitter is thousands of times brighter than the sky beside it, and a display
//! shows at most 1; clipping each channel at 1 turns every bright region into flat, often
//! hue-shifted patches. A filmic curve keeps the mid-tones nearly as they were and rolls the
//! highlights off so that they reach white gradually. The ACES curve here is Krzysztof
//! Narkowicz's fit of the ACES reference rendering and sRGB output transforms ("ACES Filmic Tone
//! Mapping Curve", 2016): a ratio of quadratics per channel, `f(y) = y (2.51 y + 0.03) / (y (2.43
//! y + 0.59) + 0.14)`, taken at `y = 0.6 x`, the exposure at which his fit matches ACES (scene
//! grey 0.18 to display 0.14); monotone for x >= 0 and 1 from x = 12.07 on. Per channel, so that the
//! encoding stays one monotone table per channel (`raster/rgba8_encoder.rs`); the price is that
//! saturated highlights desaturate towards white as they clip, which is what film does too.

crate::closed_set! {
    /// How exposed scene radiance becomes display-linear values in [0, 1] (`[render] tone_curve`).
    #[derive(Default)]
    pub enum ToneCurve: "a tone curve" {
        /// Narkowicz's (2016) fit of the ACES filmic curve: mid-tones nearly kept (0.18 to 0.14,
        /// 0.5 to 0.44), highlights rolled off to reach white at an exposed radiance of 12.07.
        #[default]
        Aces = "aces",
        /// Each channel clipped to [0, 1]: what the papers' OpenGL framebuffers show.
        Clip = "clip",
    }
}

/// Exposed radiance above which [`ToneCurve::Aces`] is white: the positive root of
/// `0.08 y² − 0.56 y − 0.14 = 0`, where the fitted ratio reaches 1, over the 0.6 of its exposure.
pub const ACES_WHITE: f32 = 7.241_66 / ACES_EXPOSURE;

/// The exposure at which Narkowicz's fit matches the ACES transforms.
const ACES_EXPOSURE: f32 = 0.6;

impl ToneCurve {
    /// Display-linear value in [0, 1] of exposed radiance `x` (>= 0; negative values and NaN give
    /// 0). Non-decreasing in `x`.
    #[inline]
    pub fn apply(self, x: f32) -> f32 {
        // `max` maps NaN to 0 as well: f32::max returns the non-NaN operand.
        let x = x.max(0.0);
        match self {
            Self::Aces => {
                if x >= ACES_WHITE {
                    return 1.0;
                }
                // In f64, so that the rounding of the ratio cannot make the curve step down between
                // neighbouring floats (the byte tables rely on it never decreasing).
                let y = f64::from(x) * f64::from(ACES_EXPOSURE);
                ((y * (2.51 * y + 0.03) / (y * (2.43 * y + 0.59) + 0.14)) as f32).min(1.0)
            }
            Self::Clip => x.min(1.0),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_aces_fit_keeps_mid_tones_rolls_highlights_off_and_never_decreases() {
        let c = ToneCurve::Aces;
        assert!((c.apply(0.18) - 0.1398).abs() < 1e-3, "{}", c.apply(0.18));
        assert!((c.apply(0.5) - 0.4380).abs() < 1e-3, "{}", c.apply(0.5));
        assert!((c.apply(1.0) - 0.6733).abs() < 1e-3, "{}", c.apply(1.0));
        assert_eq!(c.apply(ACES_WHITE), 1.0);
        assert!(c.apply(ACES_WHITE * 0.99) > 0.999);
        assert_eq!(c.apply(1e30), 1.0);
        assert_eq!(c.apply(f32::INFINITY), 1.0);
        assert_eq!(c.apply(-1.0), 0.0);
        assert_eq!(c.apply(f32::NAN), 0.0);
        let mut last = 0.0;
        for i in 0..300_000 {
            let v = c.apply(i as f32 * 5e-5);
            assert!(v >= last, "decreases at {}", i as f32 * 5e-5);
            last = v;
        }
        assert_eq!(ToneCurve::Clip.apply(0.5), 0.5);
        assert_eq!(ToneCurve::Clip.apply(3.0), 1.0);
    }
}
