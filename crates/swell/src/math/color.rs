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

/// CIE xyY (chromaticity x, y and luminance Y) to linear sRGB (Rec. 709 primaries, D65 white):
/// `X = x Y / y`, `Z = (1 − x − y) Y / y`, then the standard XYZ-to-sRGB matrix (IEC 61966-2-1).
/// Out-of-gamut components are clamped to 0; a `y` of 0 gives black.
pub fn xyy_to_linear_srgb(x: f32, y: f32, luminance: f32) -> glam::Vec3 {
    if y <= 0.0 || !luminance.is_finite() {
        return glam::Vec3::ZERO;
    }
    let big_x = x * luminance / y;
    let big_z = (1.0 - x - y) * luminance / y;
    let big_y = luminance;
    glam::Vec3::new(
        3.2406 * big_x - 1.5372 * big_y - 0.4986 * big_z,
        -0.9689 * big_x + 1.8758 * big_y + 0.0415 * big_z,
        0.0557 * big_x - 0.2040 * big_y + 1.0570 * big_z,
    )
    .max(glam::Vec3::ZERO)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn d65_white_is_grey_in_srgb() {
        // D65's chromaticity (0.3127, 0.3290) is sRGB's white: equal channels equal to Y.
        let c = xyy_to_linear_srgb(0.3127, 0.3290, 0.5);
        assert!((c - glam::Vec3::splat(0.5)).abs().max_element() < 2e-3, "{c}");
        // A bluish sky chromaticity has more blue than red.
        let b = xyy_to_linear_srgb(0.27, 0.28, 1.0);
        assert!(b.z > b.x);
        assert_eq!(xyy_to_linear_srgb(0.3, 0.0, 1.0), glam::Vec3::ZERO);
    }

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
