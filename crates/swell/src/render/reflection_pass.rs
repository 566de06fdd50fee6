//! Draws the terrain mirrored about the water at rest into the reflection image the water pass
//! reads ([`ReflectionMap`]), only when there is something to mirror: an eye and some terrain
//! above the water.
//!
//! It runs right after [`super::terrain_pass`] and redraws its mesh through the same
//! [`ShadedDraw`]: a reflection shows the terrain as it is lit, so only the positions are mirrored.

use rayon::prelude::*;

use super::shaded_draw::{ShadedDraw, ShadedMesh};
use super::terrain_pass::TerrainShader;
use super::FrameContext;
use crate::raster::Framebuffer;
use crate::scene::TerrainBody;
use crate::shading::ReflectionMap;

/// The reflection image, kept between frames.
#[derive(Default)]
pub struct Scratch {
    image: Option<Framebuffer>,
}

/// Renders `terrain` mirrored at the frame's render size (so a flat water pixel reads its own
/// pixel) and returns the map to read it, or `None` when nothing can be mirrored. `draw` must hold
/// what [`super::terrain_pass::draw`] left for `terrain`: the mirror shows the terrain as it is
/// lit, so flat and Gouraud colours are reused and only the positions are mirrored.
pub fn draw<'a>(
    scratch: &'a mut Scratch,
    frame: &FrameContext,
    terrain: &TerrainBody,
    draw: &mut ShadedDraw,
) -> Option<ReflectionMap<'a>> {
    let mesh = &terrain.mesh;
    let camera = frame.camera;
    // An eye under the water sees the surface from below; terrain wholly under it mirrors nothing.
    if camera.eye.y <= 0.0 || !mesh.positions.par_iter().any(|p| p.y > 0.0) {
        return None;
    }
    let (width, height) = frame.size;
    let image = scratch.image.get_or_insert_with(|| Framebuffer::new(width, height));
    if (image.width(), image.height()) != (width, height) {
        image.resize(width, height);
    }
    image.depth.par_iter_mut().for_each(|d| *d = 1.0);
    let clip_from_world = frame.clip_from_world;
    let k = ReflectionMap::depth_scale(camera, width as f32 / height as f32);
    let shader = TerrainShader { env: &frame.env, material: &terrain.material };
    draw.redraw(
        image,
        ShadedMesh { positions: &mesh.positions, normals: &mesh.normals, foam: None, indices: &mesh.indices },
        &|p| ReflectionMap::mirrored_clip(&clip_from_world, k, p),
        &shader,
    );
    Some(ReflectionMap::new(image, camera, clip_from_world))
}
