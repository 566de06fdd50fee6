//! Draws the land beyond the terrain's field ([`FarLand`]) right after the terrain, with the same
//! shader, so that a terrain scene does not end in a void (issue 18, item 5):
//!
//! 1. **The rings** through the one shaded-draw path, always Gouraud: far away a triangle covers
//!    few pixels, so per-pixel shading would cost much and show nothing more, and flat faces of
//!    rings hundreds of metres wide would show as facets. Their first ring is the field's border,
//!    so the depth test joins them to the terrain without a crack.
//! 2. **To the horizon.** Beyond the outermost ring (or beyond the camera's far plane) the land
//!    continues flat at the outermost ring's height along each azimuth (its skyline): every pixel
//!    still at the far plane whose view ray passes under the skyline is land there, shaded at the
//!    ray's meeting with that height (normal up) and hazed like the rest. It is a ray cast per
//!    pixel, as the sea's far field is, so no band of sky `ground` colour is left under the
//!    horizon at any camera height. Where an unbounded sea also reaches the horizon, land under
//!    the water at rest is left to the sea's far field.
//!
//! The far land is not mirrored in the water's reflection ([`super::reflection_pass`]): it lies
//! towards the horizon, where a mirror image nearly meets its original, and drawing it a second
//! time would cost as much as drawing it (the frame-rate budget of the `coast` and `river`
//! presets); the water reflects the sky there instead.

use glam::{Vec2, Vec3, Vec4};
use rayon::prelude::*;

use super::far_field_pass::FAR_FIELD_DEPTH;
use super::shaded_draw::{ShadedDraw, ShadedMesh, SurfaceShader};
use super::sky_pass::SkyRays;
use super::terrain_pass::TerrainShader;
use super::FrameContext;
use crate::raster::Framebuffer;
use crate::scene::Shading;
use crate::shading::SurfaceVarying;
use crate::world::{FarLand, TerrainBody};

/// Rows per task: the fill is a band just under the horizon.
const ROWS_PER_TASK: usize = 8;

/// Draws `terrain`'s far land, if it has one, into `fb` (`draw` keeps its buffers between
/// frames). `sea` says whether an unbounded sea reaches the horizon (then the land beyond the
/// rings is drawn only where it stands above the water at rest).
pub fn draw(fb: &mut Framebuffer, frame: &FrameContext, terrain: &TerrainBody, draw: &mut ShadedDraw, sea: bool) {
    let Some(land) = &terrain.far_land else {
        return;
    };
    let clip_from_world = frame.clip_from_world;
    let shader = TerrainShader { env: &frame.env, material: &terrain.material };
    draw.draw(
        fb,
        ShadedMesh::plain(&land.positions, &land.normals, &land.indices),
        &|p| clip_from_world * Vec4::from((p, 1.0)),
        Shading::Gouraud,
        &shader,
    );
    fill_to_horizon(fb, frame, land, &shader, sea);
}

/// Step 2: the pixels still at the far plane whose ray passes under the skyline.
fn fill_to_horizon(fb: &mut Framebuffer, frame: &FrameContext, land: &FarLand, shader: &TerrainShader, sea: bool) {
    let (width, height) = (fb.width(), fb.height());
    let rays = SkyRays::new(frame.camera, width as f32 / height as f32);
    let eye = frame.env.eye;
    let from = Vec2::new(eye.x, eye.z);
    let w = width as usize;
    fb.color.par_chunks_mut(w).zip(fb.depth.par_chunks_mut(w)).enumerate().with_max_len(ROWS_PER_TASK).for_each(
        |(y, (colors, depth))| {
            let row = rays.row(1.0 - 2.0 * (y as f32 + 0.5) / height as f32);
            for (x, (c, d)) in colors.iter_mut().zip(depth.iter_mut()).enumerate() {
                if *d < 1.0 {
                    continue;
                }
                let dir = row.direction(2.0 * (x as f32 + 0.5) / width as f32 - 1.0);
                // Most such pixels are sky well above the land: one comparison sends them on.
                let run = (dir.x * dir.x + dir.z * dir.z).sqrt();
                if run <= 1e-6 || land.passes_over(eye, dir.y / run) {
                    continue;
                }
                if let Some(p) = land_beyond(land, eye, from, dir, sea) {
                    *c = shader.shade(&SurfaceVarying { position: p, normal: Vec3::Y, ..SurfaceVarying::default() });
                    *d = FAR_FIELD_DEPTH;
                }
            }
        },
    );
}

/// Where the view ray from `eye` along unit `dir` meets the land continued beyond the rings, or
/// `None` when it passes over it (or meets only land under an unbounded `sea`).
fn land_beyond(land: &FarLand, eye: Vec3, from: Vec2, dir: Vec3, sea: bool) -> Option<Vec3> {
    let horizontal = Vec2::new(dir.x, dir.z);
    let run = horizontal.length();
    if run <= 1e-6 {
        return None; // straight up or down: the rings or the sky, never the land beyond
    }
    let u = horizontal / run;
    let (distance, h) = land.skyline_at(from, u);
    if sea && h <= 0.0 {
        return None;
    }
    // Beyond the outermost ring the land is the plane y = h: a ray already under it at the ring
    // meets it there, a ray still over it meets it where it comes down to h, a rising (or level)
    // ray over it never does.
    let slope = dir.y / run;
    let at_ring = eye.y + slope * distance;
    let reach = if at_ring <= h {
        distance
    } else if slope < 0.0 {
        (eye.y - h) / -slope
    } else {
        return None;
    };
    let p = from + u * reach;
    Some(Vec3::new(p.x, h, p.y))
}
