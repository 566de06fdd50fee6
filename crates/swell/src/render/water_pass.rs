//! Draws the water surface with its material's shading model, through the one shaded-draw path:
//! the water's optics ([`crate::shading::shade_water`]: Fresnel sky and terrain reflection,
//! refraction to the bottom with absorption, sun glitter, foam) are its [`SurfaceShader`].

use glam::{Vec3, Vec4};

use super::shaded_draw::{ShadedDraw, ShadedMesh, SurfaceShader};
use super::FrameContext;
use crate::raster::Framebuffer;
use crate::scene::GlitterModel;
use crate::shading::{
    shade_water_filtered, shade_water_run, Environment, FlatBottom, Lobe, NoBottom, ReflectionMap, Seabed, SunDisc,
    SunGlitter, SurfaceVarying, WaterLook,
};
use crate::water::developed_sea_wind;
use crate::world::{TerrainBody, WaterBody};

/// Water as [`crate::shading::shade_water`] sees it, with the specular lobe of its shading
/// model; where a point carries unresolved slope variance (the unbounded sea's mesh does,
/// `render/sea_lod.rs`), that variance is shaded statistically ([`shade_water_filtered`]).
struct WaterShader<'a> {
    env: &'a Environment<'a>,
    look: WaterLook<'a>,
    lobe: Lobe,
}

impl SurfaceShader for WaterShader<'_> {
    fn shade(&self, p: &SurfaceVarying) -> Vec3 {
        shade_water_filtered(self.env, &self.look, self.lobe, p.position, p.normal, p.foam, p.unresolved)
    }

    /// A row's pixels many at a time ([`shade_water_run`]), each with the unresolved slope
    /// variance interpolated from the mesh's vertices (the unbounded sea's; 0 on a patch).
    fn shade_pixels(&self, pixels: &[SurfaceVarying], out: &mut [Vec3]) {
        shade_water_run(self.env, &self.look, self.lobe, &pixels, out);
    }

    /// Many vertices or faces at a time ([`shade_water_run`]).
    fn shade_points(&self, points: &[SurfaceVarying], out: &mut [Vec3]) {
        shade_water_run(self.env, &self.look, self.lobe, &points, out);
    }
}

/// Draws `mesh` (the patch's or the unbounded sea's, world positions, the sea's with its
/// unresolved slope variance) with `water`'s material into `fb` through `draw`; `terrain` is the
/// bottom where the material sets none, `reflection` the terrain the surface mirrors.
pub fn draw(
    fb: &mut Framebuffer,
    frame: &FrameContext,
    water: &WaterBody,
    mesh: ShadedMesh,
    draw: &mut ShadedDraw,
    terrain: Option<&TerrainBody>,
    reflection: Option<&ReflectionMap>,
) {
    let material = &water.material;
    let flat_bottom;
    // An explicit flat bottom in the material wins; otherwise the scene's terrain is the bottom.
    let seabed: &dyn Seabed = match (material.bottom_depth, terrain) {
        (Some(depth), _) => {
            flat_bottom = FlatBottom { height: -depth, albedo: material.bottom_color };
            &flat_bottom
        }
        (None, Some(t)) => t,
        (None, None) => &NoBottom,
    };
    let look = WaterLook::new(material, seabed, water.texture.as_ref(), frame.env.time)
        .with_reflection(reflection)
        .with_foam(Some(&water.foam_pattern))
        .with_foam_streaks(wind_in_world(water), material.foam_streak)
        .with_pixel_angle(frame.camera.pixel_angle(frame.size.1))
        .with_foam_crests(water.placement.to_world(Vec3::ZERO).y, water.slopes.height_variance().sqrt())
        .with_glitter(sun_glitter(water, frame.env.sun.as_ref()));
    let shader = WaterShader { env: &frame.env, look, lobe: Lobe::of(material.shading) };
    let clip_from_world = frame.clip_from_world;
    draw.draw(fb, mesh, &|p| clip_from_world * Vec4::from((p, 1.0)), material.shading, &shader);
}

/// The wind of `water`'s model ([`crate::water::WaveModel::wind_direction`]) turned into the
/// world by the patch's placement (x, z), if the model has one.
fn wind_in_world(water: &WaterBody) -> Option<glam::Vec2> {
    let d = water.model.wind_direction()?;
    let w = water.placement.to_world(Vec3::new(d.x, 0.0, d.y)) - water.placement.to_world(Vec3::ZERO);
    Some(glam::Vec2::new(w.x, w.z))
}

/// The slope distribution `water` reflects the lights through ([`GlitterModel::CoxMunk`]), or
/// `None` for the material's lobe. The wind is the material's `wind_speed`, else the model's own,
/// else that of a fully developed sea peaking at the model's longest wave; with none of these
/// (no waves to judge by) the surface has no micro-roughness. `sun` is the disc drawn in the sky.
pub(super) fn sun_glitter(water: &WaterBody, sun: Option<&SunDisc>) -> Option<SunGlitter> {
    if water.material.glitter != GlitterModel::CoxMunk {
        return None;
    }
    let wind = water
        .material
        .wind_speed
        .or_else(|| water.model.wind_speed())
        .or_else(|| water.slopes.longest_wavenumber().map(developed_sea_wind));
    Some(match wind {
        Some(u10) => SunGlitter::cox_munk(u10, water.slopes.total(), wind_in_world(water), sun),
        None => SunGlitter::smooth(sun),
    })
}
