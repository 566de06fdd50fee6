//! How water looks: `[water.material]` (colour, shading model, optics, bottom, foam, texture).

use glam::{Vec2, Vec3};
use serde::{Deserialize, Serialize};

use super::{GlitterModel, Shading, WaterPlacement};
use crate::error::{check_finite_vec, check_positive, check_range, Error, Result};
use crate::water::SurfaceFlow;

/// Most one absorption coefficient may be, 1/m: light is then gone within a millimetre.
pub const MAX_ABSORPTION: f32 = 1000.0;

/// The texture names that are generated rather than read from a file.
pub const PROCEDURAL_TEXTURES: [&str; 2] = ["procedural", "streaks"];

/// The look of a water body: `[water.material]`. Every key has a default.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct WaterMaterial {
    /// Linear RGB colour of light scattered back from the water body, components in [0, 1]; it is
    /// also the colour seen where no bottom is visible (deep water).
    pub color: Vec3,
    /// Shading model. Default `gouraud`.
    pub shading: Shading,
    /// Refractive index of water relative to air, in [1, 3]. Default 1.333 (fresh water, 20 °C).
    pub refractive_index: f32,
    /// How the water reflects the lights (the sun glitter). Default `cox-munk`: through the
    /// surface's slope distribution, in the lights' own units.
    pub glitter: GlitterModel,
    /// Strength of the lights' reflection (the sun glitter), in [0, 100]: 1 is physical with
    /// `cox-munk`; 0 turns it off. Default 1.
    pub specular: f32,
    /// Specular exponent of the Phong / Blinn-Phong lobe (`glitter = "lobe"` only), in
    /// [1, 100000]. Default 400 (a calm, mirror-like surface gives a small bright glitter).
    pub shininess: f32,
    /// Wind speed 10 m above the water, m/s, in [0.5, 60], that sets the micro-roughness of
    /// `cox-munk` glitter: the slopes below the model's waves that bring its total slope variance
    /// to Cox and Munk's for this wind. Absent: the model's own wind (the FFT ocean's
    /// `wind_speed`), or for models without one the wind of a fully developed sea whose peak is
    /// the model's longest wave (Pierson and Moskowitz 1964); models with no waves to judge by
    /// (pool, springs, river, noise) then get no micro-roughness.
    pub wind_speed: Option<f32>,
    /// Beer-Lambert absorption coefficient per linear RGB channel, 1/m, each in
    /// [0, [`MAX_ABSORPTION`]]. Default [0.45, 0.064, 0.0145]: pure water at about 650, 550 and
    /// 450 nm (Pope and Fry 1997), so red fades within metres and blue carries far.
    pub absorption: Vec3,
    /// Depth in metres of a flat bottom below the water at rest (y = −depth), > 0; absent means
    /// deep water (no bottom seen).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub bottom_depth: Option<f32>,
    /// Linear RGB albedo of the flat bottom, components in [0, 1]. Default sand [0.55, 0.47, 0.33].
    pub bottom_color: Vec3,
    /// Linear RGB albedo of foam, components in [0, 1]. Default [0.85, 0.88, 0.9].
    pub foam_color: Vec3,
    /// Structure of foam: `"procedural"` (bubble rafts and their borders,
    /// [`FoamPattern`](crate::shading::FoamPattern)) or an image file path (PNG or JPEG, relative
    /// to the scene file; only the order of its grey levels matters); absent means `"procedural"`.
    /// The wave model's foam coverage reveals it from its highest values down, so the foam shown
    /// has the model's coverage.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub foam_texture: Option<String>,
    /// Size of one foam-pattern tile on the water, metres, in [0.1, 1000]. Default 6.
    pub foam_scale: f32,
    /// Width of the soft edge of foam cells, as a fraction of the pattern's range, in
    /// [0.01, 1]: small gives crisp lace, 1 a soft blend. Default 0.15.
    pub foam_feather: f32,
    /// How many times longer than wide the foam pattern's cells are drawn along the wind, in
    /// [1, 16]: foam torn off crests is drawn out downwind into streaks. 1 keeps them round;
    /// water whose model has no wind ([`crate::water::WaveModel::wind_direction`]) keeps them
    /// round whatever this is. Default 3.
    pub foam_streak: f32,
    /// Linear RGB colour of light scattered through thin, backlit crests (subsurface scattering),
    /// components in [0, 1]. Default [0.05, 0.32, 0.26] (the green of sunlit crests).
    pub scatter_color: Vec3,
    /// Strength of that scattering, in [0, 10]; 0 turns it off. Default 4.
    pub scatter_strength: f32,
    /// Height over which crests thicken into the scattering, metres, in [0.01, 100]: the
    /// scattering grows linearly from nothing at `y = −scatter_height` to 1 at rest and 2 at
    /// `y = scatter_height` (capped at 3). Default 2.5.
    pub scatter_height: f32,
    /// Texture of the water colour: `"procedural"` (a tiling water pattern), `"streaks"` (a
    /// tiling pattern of streaks along +Z, flowing water) or an image file path (PNG or JPEG,
    /// sRGB, relative to the scene file); absent means none, except on a river, which takes
    /// `"streaks"` ([`WaterMaterial::with_flow`]).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub texture: Option<String>,
    /// Size of one texture tile on the water, metres, > 0. Default 8.
    pub texture_scale: f32,
    /// How much the texture replaces `color`, in [0, 1]. Default 1 (the texel is the colour).
    pub texture_mix: f32,
    /// Velocity at which the texture slides over the surface, [x, z] m/s (paper 004's flowing
    /// river). Default [0, 0].
    pub flow_velocity: Vec2,
    /// Strength of the foam that shallow water makes, in [0, 1]; 0 turns it off. Where a bottom
    /// (terrain or `bottom_depth`) is in sight, crests whiten where they reach the depth-limited
    /// breaking height (breaker index 0.78, McCowan 1894): the surf zone, and the swash a wave
    /// pushes up the beach; both move with the waves. Default 1.
    pub shore_foam: f32,
}

impl Default for WaterMaterial {
    fn default() -> Self {
        Self {
            color: Vec3::new(0.02, 0.11, 0.16),
            shading: Shading::Gouraud,
            refractive_index: 1.333,
            glitter: GlitterModel::CoxMunk,
            specular: 1.0,
            shininess: 400.0,
            wind_speed: None,
            absorption: Vec3::new(0.45, 0.064, 0.0145),
            bottom_depth: None,
            bottom_color: Vec3::new(0.55, 0.47, 0.33),
            foam_color: Vec3::new(0.85, 0.88, 0.9),
            foam_texture: None,
            foam_scale: 6.0,
            foam_feather: 0.15,
            foam_streak: 3.0,
            scatter_color: Vec3::new(0.05, 0.32, 0.26),
            scatter_strength: 4.0,
            scatter_height: 2.5,
            texture: None,
            texture_scale: 8.0,
            texture_mix: 1.0,
            flow_velocity: Vec2::ZERO,
            shore_foam: 1.0,
        }
    }
}

impl WaterMaterial {
    /// Checks every field, naming keys under `key` (normally `water.material`).
    pub fn validate(&self, key: &str) -> Result<()> {
        let unit_rgb = |name: &str, c: Vec3| -> Result<()> {
            for (i, v) in c.to_array().into_iter().enumerate() {
                check_range(&format!("{key}.{name}[{i}]"), v, 0.0, 1.0)?;
            }
            Ok(())
        };
        unit_rgb("color", self.color)?;
        unit_rgb("bottom_color", self.bottom_color)?;
        unit_rgb("foam_color", self.foam_color)?;
        unit_rgb("scatter_color", self.scatter_color)?;
        check_range(&format!("{key}.foam_scale"), self.foam_scale, 0.1, 1000.0)?;
        check_range(&format!("{key}.foam_feather"), self.foam_feather, 0.01, 1.0)?;
        check_range(&format!("{key}.foam_streak"), self.foam_streak, 1.0, 16.0)?;
        check_range(&format!("{key}.scatter_strength"), self.scatter_strength, 0.0, 10.0)?;
        check_range(&format!("{key}.scatter_height"), self.scatter_height, 0.01, 100.0)?;
        check_range(&format!("{key}.refractive_index"), self.refractive_index, 1.0, 3.0)?;
        check_range(&format!("{key}.specular"), self.specular, 0.0, 100.0)?;
        check_range(&format!("{key}.shininess"), self.shininess, 1.0, 100_000.0)?;
        if let Some(u) = self.wind_speed {
            check_range(&format!("{key}.wind_speed"), u, 0.5, 60.0)?;
        }
        for (i, a) in self.absorption.to_array().into_iter().enumerate() {
            check_range(&format!("{key}.absorption[{i}]"), a, 0.0, MAX_ABSORPTION)?;
        }
        if let Some(d) = self.bottom_depth {
            check_positive(&format!("{key}.bottom_depth"), d)?;
        }
        check_positive(&format!("{key}.texture_scale"), self.texture_scale)?;
        check_range(&format!("{key}.texture_mix"), self.texture_mix, 0.0, 1.0)?;
        check_range(&format!("{key}.shore_foam"), self.shore_foam, 0.0, 1.0)?;
        check_finite_vec(&format!("{key}.flow_velocity"), &self.flow_velocity.to_array())?;
        if let Some(t) = &self.texture {
            if t.trim().is_empty() {
                return Err(Error::invalid(format!("{key}.texture"), "is empty; give \"procedural\" or an image path"));
            }
        }
        if let Some(t) = &self.foam_texture {
            if t.trim().is_empty() {
                return Err(Error::invalid(
                    format!("{key}.foam_texture"),
                    "is empty; give \"procedural\" or an image path",
                ));
            }
        }
        Ok(())
    }

    /// Makes a relative texture path relative to `dir`, the directory of the scene file that names
    /// it (as terrain heightmaps are).
    pub fn resolve_paths(&mut self, dir: &std::path::Path) {
        if let Some(t) = &mut self.texture {
            if !PROCEDURAL_TEXTURES.contains(&t.as_str()) && std::path::Path::new(t).is_relative() {
                *t = dir.join(&*t).to_string_lossy().into_owned();
            }
        }
        if let Some(t) = &mut self.foam_texture {
            if t != "procedural" && std::path::Path::new(t).is_relative() {
                *t = dir.join(&*t).to_string_lossy().into_owned();
            }
        }
    }

    /// The material a water body with `flow` (its model's [`SurfaceFlow`], e.g. the river's) is
    /// drawn with, on a patch placed by `placement`: the texture defaults to `"streaks"`, it repeats
    /// every `texture_length` and slides at the flow's velocity, both turned and scaled with the
    /// patch (the material's own `texture_scale` and `flow_velocity` give way to the model's).
    /// Without a flow, the material as it is.
    pub fn with_flow(&self, flow: Option<SurfaceFlow>, placement: &WaterPlacement) -> WaterMaterial {
        let Some(flow) = flow else { return self.clone() };
        // Ry(yaw) carries local (x, z) to (x cos + z sin, −x sin + z cos), as the placement does.
        let (s, c) = placement.yaw.sin_cos();
        let v = flow.velocity;
        let turned = Vec2::new(v.x * c + v.y * s, -v.x * s + v.y * c);
        WaterMaterial {
            texture: Some(self.texture.clone().unwrap_or_else(|| "streaks".into())),
            texture_scale: flow.texture_length * placement.scale,
            flow_velocity: turned * placement.scale,
            ..self.clone()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn foam_and_scattering_keys_are_checked_with_their_path_value_and_range() {
        type Spoil = fn(&mut WaterMaterial);
        let bad: [(&str, Spoil); 11] = [
            ("water.material.foam_scale", |m| m.foam_scale = 0.0),
            ("water.material.foam_feather", |m| m.foam_feather = 1.5),
            ("water.material.foam_feather", |m| m.foam_feather = f32::NAN),
            ("water.material.foam_streak", |m| m.foam_streak = 0.5),
            ("water.material.foam_streak", |m| m.foam_streak = 17.0),
            ("water.material.foam_streak", |m| m.foam_streak = f32::INFINITY),
            ("water.material.scatter_strength", |m| m.scatter_strength = -1.0),
            ("water.material.scatter_height", |m| m.scatter_height = 0.0),
            ("water.material.scatter_color[1]", |m| m.scatter_color.y = 2.0),
            ("water.material.foam_texture", |m| m.foam_texture = Some(" ".into())),
            ("water.material.scatter_strength", |m| m.scatter_strength = 11.0),
        ];
        for (key, spoil) in bad {
            let mut m = WaterMaterial::default();
            spoil(&mut m);
            let e = m.validate("water.material").unwrap_err().to_string();
            assert!(e.contains(key), "{key}: {e}");
        }
        let e = WaterMaterial { foam_feather: 1.5, ..Default::default() }.validate("water.material").unwrap_err();
        let e = e.to_string();
        assert!(e.contains("1.5") && e.contains("0.01") && e.contains('1'), "value and range: {e}");
        WaterMaterial::default().validate("water.material").unwrap();
    }

    #[test]
    fn a_foam_texture_that_cannot_be_read_names_its_key_and_file() {
        let m = WaterMaterial { foam_texture: Some("/nonexistent/foam.png".into()), ..Default::default() };
        let e = m.load_foam_pattern().unwrap_err().to_string();
        assert!(e.contains("water.material.foam_texture") && e.contains("/nonexistent/foam.png"), "{e}");
        // Relative to the scene file, as the colour texture is; "procedural" stays a name.
        let mut m = WaterMaterial { foam_texture: Some("foam.png".into()), ..Default::default() };
        m.resolve_paths(std::path::Path::new("/scenes"));
        assert_eq!(m.foam_texture.as_deref(), Some("/scenes/foam.png"));
        let mut m = WaterMaterial { foam_texture: Some("procedural".into()), ..Default::default() };
        m.resolve_paths(std::path::Path::new("/scenes"));
        assert_eq!(m.foam_texture.as_deref(), Some("procedural"));
    }
}
