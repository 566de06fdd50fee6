//! How a frame is turned into pixels: image size, exposure (linear, EV100 or metered), tone curve,
//! gamma, ambient light, threads.

use glam::Vec3;
use serde::{Deserialize, Serialize};

use crate::error::{check_count, check_non_negative, check_range, Error, Result};
use crate::math::{ev100_exposure, DisplayEncoding, ToneCurve, EV100_RANGE};

/// Largest image side in pixels. 16384² pixels at 16 bytes of colour and 4 of depth is 5 GiB, the
/// most a 24 GiB machine holds with room for everything else.
pub const MAX_IMAGE_SIDE: u32 = 16384;

/// Most rayon threads a scene may ask for.
pub const MAX_THREADS: u32 = 256;

/// The `[render]` section of a scene.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RenderSettings {
    /// Image width in pixels, in [1, [`MAX_IMAGE_SIDE`]]. Default 1280.
    pub width: u32,
    /// Image height in pixels, in [1, [`MAX_IMAGE_SIDE`]]. Default 720.
    pub height: u32,
    /// Linear factor on the radiance before the tone curve, in [1e-6, 100]. Default 1. With
    /// `ev100` it multiplies the camera's exposure, with `auto_exposure` the metered one
    /// (exposure compensation: 2 is one stop brighter).
    pub exposure: f32,
    /// The camera's exposure value at ISO 100, in [-6, 24]: the luminance `1.2 × 2^ev100` cd/m²
    /// is exposed to 1 before the tone curve (the sunny-16 rule's sunlit scene is 15). Absent:
    /// `exposure` alone, which is EV100 14.02 (the renderer's unit, 20,000 cd/m², exposed to 1;
    /// [`crate::math::RADIANCE_UNIT_NITS`]).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub ev100: Option<f32>,
    /// Meter every frame as a camera does: EV100 from the frame's log-average luminance L
    /// (cd/m²), `log2(L / (1.2 × 0.18))`, so that the average lands at 0.18 of white. Each
    /// frame is metered alone (no adaptation over time), so a frame's image depends only on
    /// the frame. Not with `ev100`. Default false.
    pub auto_exposure: bool,
    /// The curve from exposed radiance to the display: `aces` (default; highlights roll off to
    /// white) or `clip`.
    pub tone_curve: ToneCurve,
    /// Display gamma in [1, 5] for a pure power-law encoding (`c^(1/gamma)`); absent means the sRGB
    /// curve, which is what monitors expect.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub gamma: Option<f32>,
    /// Ambient light (linear RGB, >= 0) added to every lit surface. Default 0.15 grey-blue.
    pub ambient: Vec3,
    /// Worker threads, 0 = one per core; in [0, [`MAX_THREADS`]]. The image does not depend on it.
    pub threads: u32,
    /// Supersampling factor per axis, in [1, [`MAX_SUPERSAMPLE`]]: the frame is rendered at
    /// `supersample` times the size and box-filtered down in linear colour. Default 1 (off).
    pub supersample: u32,
    /// Draw the triangle edges of the water over the image (paper 002). Default false.
    pub wireframe: bool,
    /// Draw each water vertex's normal as a short line (paper 002). Default false.
    pub normals: bool,
}

/// Largest supersampling factor per axis (16 samples per pixel).
pub const MAX_SUPERSAMPLE: u32 = 4;

impl Default for RenderSettings {
    fn default() -> Self {
        Self {
            width: 1280,
            height: 720,
            exposure: 1.0,
            ev100: None,
            auto_exposure: false,
            tone_curve: ToneCurve::Aces,
            gamma: None,
            ambient: Vec3::new(0.13, 0.15, 0.18),
            threads: 0,
            supersample: 1,
            wireframe: false,
            normals: false,
        }
    }
}

impl RenderSettings {
    /// Checks every field, naming keys under `key` (normally `render`).
    pub fn validate(&self, key: &str) -> Result<()> {
        check_count(&format!("{key}.width"), self.width, 1, MAX_IMAGE_SIDE)?;
        check_count(&format!("{key}.height"), self.height, 1, MAX_IMAGE_SIDE)?;
        check_range(&format!("{key}.exposure"), self.exposure, 1e-6, 100.0)?;
        if let Some(ev) = self.ev100 {
            check_range(&format!("{key}.ev100"), ev, EV100_RANGE.0, EV100_RANGE.1)?;
            if self.auto_exposure {
                return Err(Error::invalid(
                    format!("{key}.ev100"),
                    format!("{ev} fixes the exposure but auto_exposure = true meters each frame; set one of them"),
                ));
            }
        }
        if let Some(g) = self.gamma {
            check_range(&format!("{key}.gamma"), g, 1.0, 5.0)?;
        }
        for (i, c) in self.ambient.to_array().into_iter().enumerate() {
            check_non_negative(&format!("{key}.ambient[{i}]"), c)?;
        }
        check_count(&format!("{key}.threads"), self.threads, 0, MAX_THREADS)?;
        // The supersampled frame must itself fit the image-size limit.
        let max_ss = (MAX_IMAGE_SIDE / self.width.max(self.height)).clamp(1, MAX_SUPERSAMPLE);
        check_count(&format!("{key}.supersample"), self.supersample, 1, max_ss)
    }

    /// How a frame of these settings is encoded for display: `exposure` times EV100's factor
    /// ([`ev100_exposure`]) when `ev100` is set, metered per frame with `auto_exposure`.
    pub fn display_encoding(&self) -> DisplayEncoding {
        DisplayEncoding {
            exposure: self.exposure * self.ev100.map_or(1.0, ev100_exposure),
            auto_exposure: self.auto_exposure,
            tone_curve: self.tone_curve,
            gamma: self.gamma,
        }
    }
}
