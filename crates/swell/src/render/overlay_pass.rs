//! Overlays (paper 002): the triangle edges of a surface and its vertex normals, drawn as
//! depth-tested lines over the shaded image.

use glam::{Vec3, Vec4};

use super::FrameContext;
use crate::mesh::DrawnSurface;
use crate::raster::line::draw_line;
use crate::raster::Framebuffer;

/// Wireframe colour (linear RGB): near black, visible on bright water and sky.
const WIRE_COLOR: Vec3 = Vec3::new(0.02, 0.02, 0.03);
/// Normal colour (linear RGB): yellow.
const NORMAL_COLOR: Vec3 = Vec3::new(1.0, 0.85, 0.1);
/// Lines are pulled towards the eye by this fraction of their distance, so the surface they lie on
/// does not hide them in the depth test (a polygon offset that scales with distance).
const TOWARDS_EYE: f32 = 0.003;
/// Length of a drawn normal as a fraction of the grid's smaller cell side.
const NORMAL_LENGTH_CELLS: f32 = 0.8;

/// Draws the edges and/or vertex normals of `surface` (the water as drawn: the patch, or the
/// unbounded sea's rings; world space, placed with uniform scale `scale`) into `fb`.
pub fn draw(
    fb: &mut Framebuffer,
    frame: &FrameContext,
    surface: &DrawnSurface,
    scale: f32,
    wireframe: bool,
    normals: bool,
) {
    if !wireframe && !normals {
        return;
    }
    let eye = frame.env.eye;
    let clip = |p: Vec3| frame.clip_from_world * Vec4::from((p + (eye - p) * TOWARDS_EYE, 1.0));
    let positions = surface.positions();
    let indices = surface.indices();
    if wireframe {
        for t in indices.chunks_exact(3) {
            let [a, b, c] = [0, 1, 2].map(|k| clip(positions[t[k] as usize]));
            draw_line(fb, a, b, WIRE_COLOR);
            draw_line(fb, b, c, WIRE_COLOR);
            draw_line(fb, c, a, WIRE_COLOR);
        }
    }
    if normals {
        // Only vertices some triangle uses: the rings evaluate the middle of each coarser level,
        // which the finer ring covers and nothing draws.
        let mut used = vec![false; positions.len()];
        for &i in indices {
            used[i as usize] = true;
        }
        let cells = surface.cell_sizes();
        for (((&p, &n), cell), _) in positions.iter().zip(surface.normals()).zip(cells).zip(used).filter(|x| x.1) {
            let len = NORMAL_LENGTH_CELLS * cell * scale;
            draw_line(fb, clip(p), clip(p + n * len), NORMAL_COLOR);
        }
    }
}
