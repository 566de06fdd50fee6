//! How land looks: `[terrain.material]`, sand, grass, rock and snow chosen by height and slope.

use glam::Vec3;
use serde::{Deserialize, Serialize};

use super::Shading;
use crate::error::{check_positive, check_range, Result};

/// How terrain looks: `[terrain.material]`. Colours are linear RGB in [0, 1]; heights are world
/// metres (water at rest is y = 0).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct TerrainMaterial {
    /// Shading model. Default `gouraud`. `flat` is paper 001 §2.2's look (intensity = cosine
    /// between the light and the face normal; with no `[[light]]` in the scene, a light at
    /// infinity straight above, as in the paper); `phong` and `blinn-phong` light each pixel
    /// (land has no specular term, so the two agree).
    pub shading: Shading,
    /// Beach and underwater floor. Default [0.54, 0.45, 0.24] (sRGB ~(194, 178, 133)).
    pub sand: Vec3,
    /// Gentle slopes between `sand_height` and `snow_height`. Default [0.09, 0.20, 0.05].
    pub grass: Vec3,
    /// Slopes steeper than `rock_slope_deg`. Default [0.20, 0.17, 0.14].
    pub rock: Vec3,
    /// Heights above `snow_height`. Default [0.85, 0.87, 0.90].
    pub snow: Vec3,
    /// Sand below this world height (m), grass above. Default 1.5.
    pub sand_height: f32,
    /// Snow above this world height (m), > `sand_height`. Default 40.
    pub snow_height: f32,
    /// Faces steeper than this (degrees from horizontal, in [0, 90]) are rock. Default 35.
    pub rock_slope_deg: f32,
    /// Width (m) of the blend between height bands, > 0. Default 1.
    pub transition: f32,
    /// Height (m) above the water at rest, in [0, 100], up to which the ground is wet and
    /// darker: the swash zone that the waves' run-up keeps wet, and everything under the water.
    /// Set it to the run-up (about the waves' crest height at the shore). 0 turns the band off;
    /// a scene without water has none. Default 0.5.
    pub wet_height: f32,
}

impl Default for TerrainMaterial {
    fn default() -> Self {
        Self {
            shading: Shading::Gouraud,
            sand: Vec3::new(0.54, 0.45, 0.24),
            grass: Vec3::new(0.09, 0.20, 0.05),
            rock: Vec3::new(0.20, 0.17, 0.14),
            snow: Vec3::new(0.85, 0.87, 0.90),
            sand_height: 1.5,
            snow_height: 40.0,
            rock_slope_deg: 35.0,
            transition: 1.0,
            wet_height: 0.5,
        }
    }
}

/// Half-width (degrees) of the blend between grass or snow and rock around `rock_slope_deg`.
const ROCK_BLEND_DEG: f32 = 5.0;

/// Albedo of wet ground over that of the same ground dry: water filling the pores and coating
/// the grains traps light by internal reflection (Twomey, Bohren and Mergenthaler 1986 measure
/// wet sand at roughly half to two thirds of its dry reflectance).
pub const WET_DARKENING: f32 = 0.6;
/// Fraction of `wet_height` where the wet band starts to dry out towards its top edge.
const WET_FADE_FROM: f32 = 0.6;

fn smoothstep(edge0: f32, edge1: f32, x: f32) -> f32 {
    let t = ((x - edge0) / (edge1 - edge0)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

impl TerrainMaterial {
    /// Checks every field, naming keys under `key` (normally `terrain.material`).
    pub fn validate(&self, key: &str) -> Result<()> {
        for (name, c) in [("sand", self.sand), ("grass", self.grass), ("rock", self.rock), ("snow", self.snow)] {
            for (i, v) in c.to_array().into_iter().enumerate() {
                check_range(&format!("{key}.{name}[{i}]"), v, 0.0, 1.0)?;
            }
        }
        check_range(&format!("{key}.sand_height"), self.sand_height, -1.0e5, 1.0e5)?;
        check_range(&format!("{key}.snow_height"), self.snow_height, self.sand_height, 1.0e5)?;
        check_range(&format!("{key}.rock_slope_deg"), self.rock_slope_deg, 0.0, 90.0)?;
        check_positive(&format!("{key}.transition"), self.transition)?;
        check_range(&format!("{key}.wet_height"), self.wet_height, 0.0, 100.0)
    }

    /// Surface colour (albedo) at world height `y` (m) with unit normal `n`: sand, grass, snow by
    /// height (smooth over `transition` metres), then rock where the slope passes
    /// `rock_slope_deg` (smooth over ±5°).
    pub fn albedo(&self, y: f32, n: Vec3) -> Vec3 {
        let half = 0.5 * self.transition;
        let grass = smoothstep(self.sand_height - half, self.sand_height + half, y);
        let snow = smoothstep(self.snow_height - half, self.snow_height + half, y);
        let by_height = self.sand.lerp(self.grass, grass).lerp(self.snow, snow);
        let slope_deg = n.y.clamp(-1.0, 1.0).abs().acos().to_degrees();
        let rock = smoothstep(self.rock_slope_deg - ROCK_BLEND_DEG, self.rock_slope_deg + ROCK_BLEND_DEG, slope_deg);
        // Sand stays sand however steep (underwater banks): rock replaces only land cover.
        let dry = by_height.lerp(self.rock, rock * grass);
        dry * (1.0 - (1.0 - WET_DARKENING) * self.wetness(y))
    }

    /// How wet the ground at world height `y` is, [0, 1]: 1 up to `WET_FADE_FROM` of
    /// `wet_height` (and everywhere under the water at rest), drying smoothly to 0 at
    /// `wet_height`; 0 everywhere when `wet_height` is 0.
    pub fn wetness(&self, y: f32) -> f32 {
        if self.wet_height <= 0.0 {
            return 0.0;
        }
        1.0 - smoothstep(WET_FADE_FROM * self.wet_height, self.wet_height, y)
    }
}
