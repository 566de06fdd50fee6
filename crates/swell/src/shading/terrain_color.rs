//! The colour of land: sand, grass, rock and snow chosen by height and slope, lit by the scene's
//! lights (Lambert) per vertex (Gouraud) or per face (paper 001's flat diffuse look).

use glam::Vec3;
use serde::{Deserialize, Serialize};

use super::{lambert, Environment};
use crate::error::{check_positive, check_range, Result};

/// Where terrain lighting is evaluated. In a scene file: `terrain.material.shading`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum TerrainShading {
    /// Once per triangle from its face normal: paper 001 §2.2's look (intensity = cosine between
    /// the light and the face normal; with no `[[light]]` in the scene, a light at infinity
    /// straight above, as in the paper).
    Flat,
    /// Once per vertex from the vertex normal, colours interpolated across each triangle.
    #[default]
    Gouraud,
}

/// How terrain looks: `[terrain.material]`. Colours are linear RGB in [0, 1]; heights are world
/// metres (water at rest is y = 0).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct TerrainMaterial {
    /// Shading model. Default `gouraud`.
    pub shading: TerrainShading,
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
}

impl Default for TerrainMaterial {
    fn default() -> Self {
        Self {
            shading: TerrainShading::Gouraud,
            sand: Vec3::new(0.54, 0.45, 0.24),
            grass: Vec3::new(0.09, 0.20, 0.05),
            rock: Vec3::new(0.20, 0.17, 0.14),
            snow: Vec3::new(0.85, 0.87, 0.90),
            sand_height: 1.5,
            snow_height: 40.0,
            rock_slope_deg: 35.0,
            transition: 1.0,
        }
    }
}

/// Half-width (degrees) of the blend between grass or snow and rock around `rock_slope_deg`.
const ROCK_BLEND_DEG: f32 = 5.0;

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
        check_positive(&format!("{key}.transition"), self.transition)
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
        by_height.lerp(self.rock, rock * grass)
    }
}

/// Radiance leaving terrain point `p` (world m) with unit normal `n`: albedo times the Lambert
/// irradiance of the scene's lights plus ambient.
///
/// With no lights at all, light comes from infinity straight above with unit radiance (paper 001
/// §2.2: "the light source is always infinitely far above the landscape"), so a scene with only
/// terrain still shows its relief.
pub fn shade_terrain(env: &Environment, material: &TerrainMaterial, p: Vec3, n: Vec3) -> Vec3 {
    let irradiance = if env.lights.is_empty() { env.ambient + Vec3::splat(n.y.max(0.0)) } else { lambert(env, p, n) };
    material.albedo(p.y, n) * irradiance
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Sky;

    #[test]
    fn bands_follow_height_and_slope() {
        let m = TerrainMaterial::default();
        assert_eq!(m.albedo(-3.0, Vec3::Y), m.sand);
        assert_eq!(m.albedo(10.0, Vec3::Y), m.grass);
        assert_eq!(m.albedo(60.0, Vec3::Y), m.snow);
        let steep = Vec3::new(1.0, 0.5, 0.0).normalize(); // 63 degrees
        assert_eq!(m.albedo(10.0, steep), m.rock);
        assert_eq!(m.albedo(-3.0, steep), m.sand);
        let mid = m.albedo(m.sand_height, Vec3::Y);
        assert!((mid - 0.5 * (m.sand + m.grass)).length() < 1e-6);
    }

    #[test]
    fn flat_light_from_above_follows_the_face_cosine() {
        let sky = Sky::default();
        let env = Environment { lights: &[], ambient: Vec3::ZERO, sky: &sky, eye: Vec3::ZERO, sun: None, time: 0.0 };
        let m = TerrainMaterial { sand: Vec3::ONE, grass: Vec3::ONE, rock: Vec3::ONE, ..Default::default() };
        let tilted = Vec3::new(0.6, 0.8, 0.0);
        assert!((shade_terrain(&env, &m, Vec3::ZERO, tilted) - Vec3::splat(0.8)).length() < 1e-6);
        assert_eq!(shade_terrain(&env, &m, Vec3::ZERO, Vec3::Y), Vec3::ONE);
    }
}
