//! Draws the terrain mirrored about the water at rest into the reflection image the water pass
//! reads ([`ReflectionMap`]), only when there is something to mirror: an eye and some terrain
//! above the water.
//!
//! It runs right after [`super::terrain_pass`] and reuses its per-vertex and per-face colours: a
//! reflection shows the terrain as it is lit, so only the positions are mirrored.

use glam::Vec3;
use rayon::prelude::*;

use super::FrameContext;
use crate::raster::{draw_with, ClipVertex, Cull, DrawScratch, Framebuffer};
use crate::scene::{Camera, TerrainBody};
use crate::shading::{ReflectionMap, TerrainShading};

/// The reflection image and the draw call's buffers, kept between frames.
#[derive(Default)]
pub struct Scratch {
    image: Option<Framebuffer>,
    draw: DrawScratch<Vec3>,
}

/// Renders `terrain` mirrored at `width` x `height` pixels (the frame's render size, so a flat
/// water pixel reads its own pixel) and returns the map to read it, or `None` when nothing can be
/// mirrored. `clip_vertices` and `face_colors` must hold what [`super::terrain_pass::draw`] left
/// for `terrain`; the positions of `clip_vertices` are overwritten.
pub fn draw<'a>(
    scratch: &'a mut Scratch,
    width: u32,
    height: u32,
    frame: &FrameContext,
    camera: &Camera,
    terrain: &TerrainBody,
    clip_vertices: &mut [ClipVertex<Vec3>],
    face_colors: &[Vec3],
) -> Option<ReflectionMap<'a>> {
    let mesh = &terrain.mesh;
    // An eye under the water sees the surface from below; terrain wholly under it mirrors nothing.
    if camera.eye.y <= 0.0 || !mesh.positions.par_iter().any(|p| p.y > 0.0) {
        return None;
    }
    let image = scratch.image.get_or_insert_with(|| Framebuffer::new(width, height));
    if (image.width(), image.height()) != (width, height) {
        image.resize(width, height);
    }
    image.depth.par_iter_mut().for_each(|d| *d = 1.0);
    let clip_from_world = frame.clip_from_world;
    let k = ReflectionMap::depth_scale(camera, width as f32 / height as f32);
    clip_vertices
        .par_iter_mut()
        .zip(mesh.positions.par_iter())
        .for_each(|(cv, &p)| cv.position = ReflectionMap::mirrored_clip(&clip_from_world, k, p));
    match terrain.material.shading {
        TerrainShading::Gouraud => {
            draw_with(&mut scratch.draw, image, clip_vertices, &mesh.indices, Cull::None, &|f| f.varying)
        }
        TerrainShading::Flat => draw_with(&mut scratch.draw, image, clip_vertices, &mesh.indices, Cull::None, &|f| {
            face_colors[f.primitive as usize]
        }),
    }
    Some(ReflectionMap::new(image, camera, clip_from_world))
}
