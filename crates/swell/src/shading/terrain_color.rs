//! The colour of land: sand, grass, rock and snow chosen by height and slope, lit by the scene's
//! lights (Lambert) per vertex (Gouraud) or per face (paper 001's flat diffuse look).

use glam::Vec3;

use super::{lambert, Environment};
use crate::scene::TerrainMaterial;

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
        let m = TerrainMaterial { wet_height: 0.0, ..Default::default() };
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
        let sky = crate::shading::SkyRadiance::new(&Sky::default());
        let env = Environment { lights: &[], ambient: Vec3::ZERO, sky: &sky, eye: Vec3::ZERO, sun: None, time: 0.0 };
        let m = TerrainMaterial {
            sand: Vec3::ONE,
            grass: Vec3::ONE,
            rock: Vec3::ONE,
            wet_height: 0.0,
            ..Default::default()
        };
        let tilted = Vec3::new(0.6, 0.8, 0.0);
        assert!((shade_terrain(&env, &m, Vec3::ZERO, tilted) - Vec3::splat(0.8)).length() < 1e-6);
        assert_eq!(shade_terrain(&env, &m, Vec3::ZERO, Vec3::Y), Vec3::ONE);
    }

    #[test]
    fn ground_the_waves_wet_is_darker_up_to_wet_height() {
        use crate::scene::WET_DARKENING;
        let m = TerrainMaterial { wet_height: 1.2, ..Default::default() };
        let dry = TerrainMaterial { wet_height: 0.0, ..m };
        // Under the water and low in the swash zone: wet sand.
        for y in [-3.0, 0.0, 0.5] {
            assert!((m.albedo(y, Vec3::Y) - WET_DARKENING * dry.albedo(y, Vec3::Y)).length() < 1e-6, "{y}");
        }
        // Above the run-up: as dry; between, drying out without a step.
        assert_eq!(m.albedo(1.2, Vec3::Y), dry.albedo(1.2, Vec3::Y));
        let mut last = m.wetness(0.6);
        for k in 1..=60 {
            let w = m.wetness(0.6 + k as f32 * 0.01);
            assert!(w <= last && last - w < 0.05, "{last} -> {w}");
            last = w;
        }
        let e = TerrainMaterial { wet_height: -1.0, ..m }.validate("terrain.material").unwrap_err().to_string();
        assert!(e.contains("terrain.material.wet_height") && e.contains("-1"), "{e}");
    }
}
