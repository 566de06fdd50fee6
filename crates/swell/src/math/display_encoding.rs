//! From linear scene radiance to display bytes: the radiometric unit, a camera's exposure (EV100,
//! set or metered), the tone curve and the transfer function, defined once here and tabulated by
//! `raster/rgba8_encoder.rs`.
//!
//! **The unit.** Every radiance in the renderer (sky, sun disc, lit surfaces, the EXR's pixels) is
//! in units of [`RADIANCE_UNIT_NITS`] = 20,000 cd/m² of luminance. So a directional light of
//! colour × intensity 1 gives an illuminance of π × 20,000 = 62.8 klux, a white Lambertian surface
//! facing it a radiance of 1, and a clear sky's zenith is about 0.3.
//!
//! **Exposure.** A camera at exposure value EV100 (ISO 100) maps the luminance `1.2 × 2^EV100`
//! cd/m² to the sensor's saturation (ISO 12232's saturation-based speed; Lagarde and de Rousiers,
//! "Moving Frostbite to Physically Based Rendering", 2014, §5.1). Metering sets EV100 so that the
//! scene's log-average luminance L (cd/m²) is exposed to 0.18 of that white, Reinhard et al.'s
//! key for a scene of normal brightness ("Photographic Tone Reproduction for Digital Images",
//! 2002): `EV100 = log2(L / (1.2 × 0.18))`. (A reflected-light meter's ISO 2720 calibration, K =
//! 12.5, exposes it to 0.104: 0.8 stop darker.)
//! The sunny-16 rule is EV100 15; the renderer's unit is white at EV100 `log2(20,000 / 1.2)` = 14.02.

use super::{linear_to_srgb, ToneCurve};

/// Luminance, cd/m², of one unit of the renderer's linear radiance (see the module documentation).
pub const RADIANCE_UNIT_NITS: f32 = 20_000.0;

/// The EV100 range `[render] ev100` accepts and metering is clamped to: −6 (a moonlit landscape)
/// to 24 (far beyond a sunlit snowfield's 16).
pub const EV100_RANGE: (f32, f32) = (-6.0, 24.0);

/// The fraction of white the metered log-average is exposed to (Reinhard et al.'s key 0.18).
const METER_KEY: f32 = 0.18;

/// The linear factor on the renderer's radiance that a camera at `ev100` applies: the unit's
/// luminance over the saturating luminance `1.2 × 2^ev100`.
pub fn ev100_exposure(ev100: f32) -> f32 {
    RADIANCE_UNIT_NITS / (1.2 * ev100.exp2())
}

/// The EV100 at which a camera applies the linear factor `exposure` (> 0): the inverse of
/// [`ev100_exposure`]. `ev100_of_exposure(1.0)` is 14.02, what `exposure` alone means.
pub fn ev100_of_exposure(exposure: f32) -> f32 {
    (RADIANCE_UNIT_NITS / (1.2 * exposure)).log2()
}

/// The EV100 that exposes a scene of log-average luminance `2^mean_log2` renderer units to 0.18
/// of white (`log2(L / (1.2 × 0.18))`, L in cd/m²), clamped to [`EV100_RANGE`]; a non-finite mean
/// gives the range's middle.
pub fn metered_ev100(mean_log2: f32) -> f32 {
    // log2(L / (1.2 × 0.18)) = log2 L + the EV100 of the exposure 0.18.
    let ev = mean_log2 + ev100_of_exposure(METER_KEY);
    if !ev.is_finite() {
        return 0.5 * (EV100_RANGE.0 + EV100_RANGE.1);
    }
    ev.clamp(EV100_RANGE.0, EV100_RANGE.1)
}

/// How linear radiance becomes a display byte: times `exposure`, the tone curve, then the sRGB
/// curve (or `c^(1/gamma)`), rounded.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DisplayEncoding {
    /// Linear factor on the renderer's radiance, > 0 and finite. With `auto_exposure` it
    /// multiplies the metered exposure (exposure compensation).
    pub exposure: f32,
    /// Meter each frame (its log-average luminance, [`metered_ev100`]) and expose for it.
    pub auto_exposure: bool,
    /// The curve from exposed radiance to display-linear [0, 1].
    pub tone_curve: ToneCurve,
    /// A pure power law `c^(1/gamma)` instead of the sRGB curve, gamma in [1, 5].
    pub gamma: Option<f32>,
}

impl DisplayEncoding {
    /// The papers' encoding: times `exposure`, clipped at 1, the sRGB curve (or `gamma`); no tone
    /// curve and no metering.
    pub const fn clipped(exposure: f32, gamma: Option<f32>) -> Self {
        Self { exposure, auto_exposure: false, tone_curve: ToneCurve::Clip, gamma }
    }

    /// This encoding with `exposure` fixed (metering resolved).
    pub fn with_exposure(self, exposure: f32) -> Self {
        Self { exposure, auto_exposure: false, ..self }
    }

    /// The byte of linear channel value `c` under this encoding, its exposure taken as is
    /// (metering is the framebuffer's, which sees the frame). NaN and negative values give 0.
    /// This is the definition that `raster::Rgba8Encoder`'s table reproduces.
    pub fn encode(&self, c: f32) -> u8 {
        let d = self.tone_curve.apply(c * self.exposure);
        let e = match self.gamma {
            None => linear_to_srgb(d),
            Some(g) => d.clamp(0.0, 1.0).powf(1.0 / g),
        };
        // NaN clamps to 0 here, so a bad sample can never reach a file as garbage.
        (e * 255.0 + 0.5).clamp(0.0, 255.0) as u8
    }

    /// Whether `other` encodes exactly as this one (exposures and gammas compared bit for bit).
    pub fn same_as(&self, other: &Self) -> bool {
        self.exposure.to_bits() == other.exposure.to_bits()
            && self.auto_exposure == other.auto_exposure
            && self.tone_curve == other.tone_curve
            && self.gamma.map(f32::to_bits) == other.gamma.map(f32::to_bits)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ev100_follows_the_meter_and_saturation_calibrations() {
        // The unit is white (factor 1) at log2(20,000 / 1.2).
        assert!((ev100_exposure((RADIANCE_UNIT_NITS / 1.2).log2()) - 1.0).abs() < 1e-5);
        for ev in [-6.0f32, 9.0, 14.0, 24.0] {
            assert!((ev100_of_exposure(ev100_exposure(ev)) - ev).abs() < 1e-4, "{ev}");
        }
        // One stop more halves it.
        assert!((ev100_exposure(15.0) / ev100_exposure(14.0) - 0.5).abs() < 1e-6);
        // A scene averaging 1,000 cd/m² (0.05 units) meters log2(1000 / 0.216) = 12.18.
        let ev = metered_ev100(0.05f32.log2());
        assert!((ev - (1000.0f32 / 0.216).log2()).abs() < 1e-4, "{ev}");
        // Metered, the average lands at 0.18 of white, whatever it was.
        for avg in [1e-3f32, 0.05, 2.0] {
            let k = ev100_exposure(metered_ev100(avg.log2()));
            assert!((avg * k - 0.18).abs() < 1e-4, "{avg}: {}", avg * k);
        }
        assert_eq!(metered_ev100(f32::NAN), 9.0);
        assert_eq!(metered_ev100(-1e9), EV100_RANGE.0);
    }

    #[test]
    fn encoding_is_exposure_then_curve_then_srgb() {
        let e = DisplayEncoding { exposure: 2.0, auto_exposure: false, tone_curve: ToneCurve::Aces, gamma: None };
        let want = (linear_to_srgb(ToneCurve::Aces.apply(0.6)) * 255.0 + 0.5) as u8;
        assert_eq!(e.encode(0.3), want);
        assert_eq!(e.encode(f32::NAN), 0);
        assert_eq!(e.encode(-1.0), 0);
        assert_eq!(e.encode(1e9), 255);
        assert_eq!(DisplayEncoding::clipped(1.0, None).encode(0.5), (linear_to_srgb(0.5) * 255.0 + 0.5) as u8);
        assert!(e.same_as(&e) && !e.same_as(&e.with_exposure(3.0)));
    }
}
