//! Colour transfer functions. Rendering works in linear RGB; only the final encoding is non-linear.

/// The sRGB opto-electronic transfer function (IEC 61966-2-1): linear [0, 1] to encoded [0, 1].
///
/// Values outside [0, 1] are clamped first, so HDR input never wraps.
pub fn linear_to_srgb(c: f32) -> f32 {
    let c = c.clamp(0.0, 1.0);
    if c <= 0.003_130_8 {
        12.92 * c
    } else {
        1.055 * c.powf(1.0 / 2.4) - 0.055
    }
}

/// The inverse of [`linear_to_srgb`]: encoded [0, 1] to linear [0, 1].
pub fn srgb_to_linear(c: f32) -> f32 {
    let c = c.clamp(0.0, 1.0);
    if c <= 0.040_45 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn srgb_round_trips_and_hits_known_points() {
        for i in 0..=100 {
            let x = i as f32 / 100.0;
            assert!((srgb_to_linear(linear_to_srgb(x)) - x).abs() < 1e-5);
        }
        // 18 % grey encodes to about 0.46 (118/255).
        assert!((linear_to_srgb(0.18) - 0.4613).abs() < 1e-3);
        assert!((linear_to_srgb(2.0) - 1.0).abs() < 1e-6);
        assert_eq!(linear_to_srgb(-1.0), 0.0);
    }
}
