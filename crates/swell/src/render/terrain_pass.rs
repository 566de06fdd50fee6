//! Draws the terrain: colour by height and slope, lit per face (paper 001's flat look), per vertex
//! (Gouraud) or per pixel, through the one shaded-draw path. Drawn before the water so the water's
//! depth test sees the ground.

use glam::{Vec3, Vec4};

use super::shaded_draw::{ShadedDraw, ShadedMesh, SurfaceShader};
use super::FrameContext;
use crate::raster::Framebuffer;
use crate::scene::TerrainMaterial;
use crate::shading::{shade_terrain, Environment, SurfaceVarying};
use crate::world::TerrainBody;

/// Land as [`shade_terrain`] lights it; it has no specular term, so the colour of a point does
/// not depend on the eye (which lets the reflection pass reuse it).
pub(crate) struct TerrainShader<'a> {
    /// Lights and ambient of the frame.
    pub env: &'a Environment<'a>,
    /// Colours by height and slope.
    pub material: &'a TerrainMaterial,
}

impl SurfaceShader for TerrainShader<'_> {
    fn shade(&self, p: &SurfaceVarying) -> Vec3 {
        self.env.haze(p.position, shade_terrain(self.env, self.material, p.position, p.normal))
    }
}

/// Draws `terrain` into `fb` with its material's shading model, keeping what it lit in `draw` for
/// the reflection pass.
pub fn draw(fb: &mut Framebuffer, frame: &FrameContext, terrain: &TerrainBody, draw: &mut ShadedDraw) {
    let mesh = &terrain.mesh;
    let clip_from_world = frame.clip_from_world;
    let shader = TerrainShader { env: &frame.env, material: &terrain.material };
    draw.draw(
        fb,
        ShadedMesh::plain(&mesh.positions, &mesh.normals, &mesh.indices),
        &|p| clip_from_world * Vec4::from((p, 1.0)),
        terrain.material.shading,
        &shader,
    );
}
