//! How a frame is turned into pixels: image size, exposure, gamma, ambient light, threads.

use glam::Vec3;
use serde::{Deserialize, Serialize};

use crate::error::{check_count, check_non_negative, check_range, Result};

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
    /// Linear scale applied before encoding, in (0, 100]. Default 1.
    pub exposure: f32,
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
}
