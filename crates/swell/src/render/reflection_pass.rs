//! Draws the terrain mirrored about the water at rest into the reflection image the water pass
//! reads ([`ReflectionMap`]), only when there is something to mirror: an eye and some terrain
//! above the water.
//!
//! It runs right after [`super::terrain_pass`] and redraws its mesh through the same
//! [`ShadedDraw`]: a reflection shows the terrain as it is lit, so only the positions are mirrored.
//!
//! Water that is a finite patch covers part of the image only (a river is a strip down its
//! middle), and only that part of the mirror image is ever read: mirrored triangles wholly
//! outside the water's screen rectangle ([`water_screen_box`], with a margin for the ripples'
//! distortion) are left out, so land that rises beside the water (a valley's sides) costs the
//! reflection little.

use glam::{Vec3, Vec4};
use rayon::prelude::*;

use super::shaded_draw::{ShadedDraw, ShadedMesh};
use super::terrain_pass::TerrainShader;
use super::FrameContext;
use crate::raster::Framebuffer;
use crate::scene::Shading;
use crate::shading::ReflectionMap;
use crate::world::TerrainBody;

/// Margin (NDC units, the image being 2 wide) added around the water's screen rectangle: the
/// water pass reads the mirror image displaced by the surface's slopes.
const BOX_MARGIN_NDC: f32 = 0.2;

/// The reflection image and the kept triangles' indices, kept between frames.
#[derive(Default)]
pub struct Scratch {
    image: Option<Framebuffer>,
    /// Per terrain vertex: which sides of the water's rectangle its mirror image lies beyond.
    outcodes: Vec<u8>,
    /// Indices of the mirrored triangles that may reach the water's rectangle.
    indices: Vec<u32>,
}

/// The NDC rectangle `[x_min, y_min, x_max, y_max]` covered by the finite water whose world
/// vertices are `positions` under `clip_from_world`, widened by a margin, or `None` (no
/// culling) when a vertex lies behind the eye or there is none.
pub fn water_screen_box(positions: &[Vec3], clip_from_world: glam::Mat4) -> Option<[f32; 4]> {
    let mut b = [f32::INFINITY, f32::INFINITY, f32::NEG_INFINITY, f32::NEG_INFINITY];
    for &p in positions {
        let c = clip_from_world * Vec4::from((p, 1.0));
        if c.w <= 1e-6 {
            return None;
        }
        let (x, y) = (c.x / c.w, c.y / c.w);
        b = [b[0].min(x), b[1].min(y), b[2].max(x), b[3].max(y)];
    }
    let m = BOX_MARGIN_NDC;
    b[0].is_finite().then_some([b[0] - m, b[1] - m, b[2] + m, b[3] + m])
}

/// Which sides of `bounds` (NDC) clip-space `c` lies beyond (bit 0 left, 1 below, 2 right,
/// 3 above); 0 for a point at or behind the eye, which is never culled.
fn outcode(c: Vec4, bounds: &[f32; 4]) -> u8 {
    if c.w <= 0.0 {
        return 0;
    }
    u8::from(c.x < bounds[0] * c.w)
        | u8::from(c.y < bounds[1] * c.w) << 1
        | u8::from(c.x > bounds[2] * c.w) << 2
        | u8::from(c.y > bounds[3] * c.w) << 3
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
    water_box: Option<[f32; 4]>,
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
    let mirrored = |p| ReflectionMap::mirrored_clip(&clip_from_world, k, p);
    // Flat colours are looked up by triangle number, so only the other models may drop some.
    let indices = match water_box {
        Some(bounds) if terrain.material.shading != Shading::Flat => {
            scratch.outcodes.resize(mesh.positions.len(), 0);
            scratch.outcodes.par_iter_mut().zip(mesh.positions.par_iter()).for_each(|(o, &p)| {
                *o = outcode(mirrored(p), &bounds);
            });
            let codes = &scratch.outcodes;
            scratch.indices.clear();
            for t in mesh.indices.chunks_exact(3) {
                if codes[t[0] as usize] & codes[t[1] as usize] & codes[t[2] as usize] == 0 {
                    scratch.indices.extend_from_slice(t);
                }
            }
            &scratch.indices[..]
        }
        _ => &mesh.indices[..],
    };
    draw.redraw(image, ShadedMesh::plain(&mesh.positions, &mesh.normals, indices), &mirrored, &shader);
    Some(ReflectionMap::new(image, camera, clip_from_world))
}
