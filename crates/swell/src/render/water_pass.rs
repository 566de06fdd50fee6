//! Draws the water surface with its material's shading model, through the one shaded-draw path:
//! the water's optics ([`shade_water`]: Fresnel sky and terrain reflection, refraction to the
//! bottom with absorption, sun glitter, foam) are its [`SurfaceShader`].

use glam::{Vec3, Vec4};

use super::shaded_draw::{ShadedDraw, ShadedMesh, SurfaceShader};
use super::FrameContext;
use crate::raster::Framebuffer;
use crate::scene::{TerrainBody, WaterBody};
use crate::shading::{shade_water, Environment, FlatBottom, Lobe, NoBottom, ReflectionMap, Seabed, WaterLook};

/// Water as [`shade_water`] sees it, with the specular lobe of its shading model.
struct WaterShader<'a> {
    env: &'a Environment<'a>,
    look: WaterLook<'a>,
    lobe: Lobe,
}

impl SurfaceShader for WaterShader<'_> {
    fn shade(&self, position: Vec3, normal: Vec3, foam: f32) -> Vec3 {
        self.env.haze(position, shade_water(self.env, &self.look, self.lobe, position, normal, foam))
    }
}

/// Draws `water` into `fb` through `draw`; `terrain` is the bottom where the material sets none,
/// `reflection` the terrain the surface mirrors.
pub fn draw(
    fb: &mut Framebuffer,
    frame: &FrameContext,
    water: &WaterBody,
    draw: &mut ShadedDraw,
    terrain: Option<&TerrainBody>,
    reflection: Option<&ReflectionMap>,
) {
    let mesh = &water.mesh;
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
    let look = WaterLook::new(material, seabed, water.texture.as_ref(), frame.env.time).with_reflection(reflection);
    let shader = WaterShader { env: &frame.env, look, lobe: Lobe::of(material.shading) };
    let clip_from_world = frame.clip_from_world;
    draw.draw(
        fb,
        ShadedMesh {
            positions: &mesh.positions,
            normals: &mesh.normals,
            foam: mesh.has_foam.then_some(&mesh.foam[..]),
            indices: &mesh.indices,
        },
        &|p| clip_from_world * Vec4::from((p, 1.0)),
        material.shading,
        &shader,
    );
}
