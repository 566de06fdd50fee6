//! Overlays (paper 002): the triangle edges of a surface and its vertex normals, drawn as
//! depth-tested lines over the shaded image.

use glam::{Vec3, Vec4};

use super::FrameContext;
use crate::mesh::SurfaceMesh;
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

/// Draws `mesh`'s edges and/or vertex normals into `fb`.
pub fn draw(fb: &mut Framebuffer, frame: &FrameContext, mesh: &SurfaceMesh, wireframe: bool, normals: bool) {
    if !wireframe && !normals {
        return;
    }
    let eye = frame.env.eye;
    let clip = |p: Vec3| frame.clip_from_world * Vec4::from((p + (eye - p) * TOWARDS_EYE, 1.0));
    if wireframe {
        for t in mesh.indices.chunks_exact(3) {
            let [a, b, c] = [0, 1, 2].map(|k| clip(mesh.positions[t[k] as usize]));
            draw_line(fb, a, b, WIRE_COLOR);
            draw_line(fb, b, c, WIRE_COLOR);
            draw_line(fb, c, a, WIRE_COLOR);
        }
    }
    if normals {
        let g = &mesh.grid;
        let cell = (g.size.x / g.cells_x as f32).min(g.size.y / g.cells_z as f32);
        let len = NORMAL_LENGTH_CELLS * cell;
        for (&p, &n) in mesh.positions.iter().zip(&mesh.normals) {
            draw_line(fb, clip(p), clip(p + n * len), NORMAL_COLOR);
        }
    }
}
