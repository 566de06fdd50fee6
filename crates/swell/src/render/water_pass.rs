//! Draws the water surface with its material's shading model.
//!
//! Each model interpolates only what it needs: flat shading nothing (one colour per triangle),
//! Gouraud a colour, Phong and Blinn-Phong the world position, normal and foam
//! ([`SurfaceVarying`]), shaded per pixel.

use std::sync::atomic::{AtomicBool, Ordering};

use glam::{Vec3, Vec4};
use rayon::prelude::*;

use super::sea_lod::FootprintFilter;
use super::FrameContext;
use crate::raster::clip::view_outcode;
use crate::raster::{draw_with, ClipVertex, Cull, DrawScratch, Framebuffer};
use crate::scene::TerrainBody;
use crate::scene::WaterBody;
use crate::shading::{
    shade_water, shade_water_filtered, FlatBottom, NoBottom, ReflectionMap, Seabed, Shading, SurfaceVarying, WaterLook,
};

/// Triangles per task of [`mark_visible_vertices`].
const MARK_TASK: usize = 4096;

/// Vertices per task of the Gouraud lighting.
const SHADE_TASK: usize = 4096;

/// Vertex buffers of the models that do not interpolate a colour, kept between frames.
#[derive(Default)]
pub struct Scratch {
    plain: Vec<ClipVertex<()>>,
    surface: Vec<ClipVertex<SurfaceVarying>>,
    draw_plain: DrawScratch<()>,
    draw_colored: DrawScratch<Vec3>,
    draw_surface: DrawScratch<SurfaceVarying>,
    /// [`view_outcode`] of each vertex (Gouraud).
    outcodes: Vec<u8>,
    /// Whether a vertex belongs to a triangle not wholly outside the view (Gouraud).
    visible: Vec<AtomicBool>,
}

/// Sets `visible[v]` for every vertex of a triangle whose vertices' outcodes share no bit (it may
/// cover a pixel), and clears it for the rest. Parallel over triangles; the stores only ever write
/// `true` after the clear, so the result does not depend on their order or the thread count.
// Out of line so that profiles name it.
#[inline(never)]
fn mark_visible_vertices(indices: &[u32], outcodes: &[u8], visible: &mut Vec<AtomicBool>) {
    visible.resize_with(outcodes.len(), AtomicBool::default);
    visible.par_iter_mut().for_each(|v| *v.get_mut() = false);
    let visible = &*visible;
    // Blocks of triangles per task, each a plain loop: per-triangle work is a few instructions.
    indices.par_chunks(3 * MARK_TASK).for_each(|block| {
        for t in block.chunks_exact(3) {
            let (a, b, c) = (t[0] as usize, t[1] as usize, t[2] as usize);
            if outcodes[a] & outcodes[b] & outcodes[c] == 0 {
                for v in [a, b, c] {
                    visible[v].store(true, Ordering::Relaxed);
                }
            }
        }
    });
}

/// The triangles the water pass draws: the patch's [`crate::mesh::SurfaceMesh`] or the unbounded
/// sea's [`crate::mesh::Clipmap`], world positions and normals.
pub struct Surface<'a> {
    /// World positions (m).
    pub positions: &'a [Vec3],
    /// Unit normals.
    pub normals: &'a [Vec3],
    /// Foam per vertex, read only when `has_foam`.
    pub foam: &'a [f32],
    /// Whether `foam` holds the model's foam.
    pub has_foam: bool,
    /// Triangle list.
    pub indices: &'a [u32],
}

impl<'a> Surface<'a> {
    /// The patch mesh.
    pub fn of_mesh(m: &'a crate::mesh::SurfaceMesh) -> Self {
        Self { positions: &m.positions, normals: &m.normals, foam: &m.foam, has_foam: m.has_foam, indices: &m.indices }
    }

    /// The unbounded sea's rings.
    pub fn of_clipmap(c: &'a crate::mesh::Clipmap) -> Self {
        Self { positions: &c.positions, normals: &c.normals, foam: &c.foam, has_foam: c.has_foam, indices: &c.indices }
    }
}

/// Draws `water` into `fb`, reusing `clip_vertices`, `face_colors` and `scratch`; `terrain` is
/// the bottom where the material sets none, `reflection` the terrain the surface mirrors;
/// `filter` (the unbounded sea's) adds, per pixel, the slope variance the pixel cannot resolve.
#[allow(clippy::too_many_arguments)]
pub fn draw(
    fb: &mut Framebuffer,
    frame: &FrameContext,
    water: &WaterBody,
    mesh: &Surface,
    filter: Option<&FootprintFilter>,
    clip_vertices: &mut Vec<ClipVertex<Vec3>>,
    face_colors: &mut Vec<Vec3>,
    scratch: &mut Scratch,
    terrain: Option<&TerrainBody>,
    reflection: Option<&ReflectionMap>,
) {
    let material = &water.material;
    let env = &frame.env;
    let clip_from_world = frame.clip_from_world;
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
    let look = WaterLook::new(material, seabed, water.texture.as_ref(), env.time).with_reflection(reflection);
    let lobe = material.shading.lobe();
    let foam = |i: usize| if mesh.has_foam { mesh.foam[i] } else { 0.0 };
    let clip = |p: Vec3| clip_from_world * Vec4::from((p, 1.0));
    match material.shading {
        Shading::Flat => {
            scratch.plain.resize(mesh.positions.len(), ClipVertex::default());
            scratch.plain.par_iter_mut().zip(mesh.positions.par_iter()).for_each(|(cv, &p)| cv.position = clip(p));
            let positions = &mesh.positions;
            face_colors.resize(mesh.indices.len() / 3, Vec3::ZERO);
            face_colors.par_iter_mut().zip(mesh.indices.par_chunks_exact(3)).for_each(|(c, t)| {
                let (a, b, d) = (positions[t[0] as usize], positions[t[1] as usize], positions[t[2] as usize]);
                let n = (b - a).cross(d - a).normalize_or(Vec3::Y);
                let f = (foam(t[0] as usize) + foam(t[1] as usize) + foam(t[2] as usize)) / 3.0;
                *c = shade_water(env, &look, lobe, (a + b + d) / 3.0, n, f);
            });
            let faces = &*face_colors;
            draw_with(&mut scratch.draw_plain, fb, &scratch.plain, mesh.indices, Cull::None, &|f| {
                faces[f.primitive as usize]
            });
        }
        Shading::Gouraud => {
            // Lighting a vertex is the costly part, and on a large patch many vertices belong only
            // to triangles wholly outside the view: light only the others (the image is the same).
            let n = mesh.positions.len();
            clip_vertices.resize(n, ClipVertex::default());
            scratch.outcodes.resize(n, 0);
            clip_vertices.par_iter_mut().zip(scratch.outcodes.par_iter_mut()).enumerate().for_each(|(i, (cv, oc))| {
                let position = clip(mesh.positions[i]);
                *oc = view_outcode(position);
                *cv = ClipVertex { position, varying: Vec3::ZERO };
            });
            mark_visible_vertices(mesh.indices, &scratch.outcodes, &mut scratch.visible);
            let visible = &scratch.visible;
            // Tasks of a fixed size: the lit vertices come in runs (the rows in view).
            clip_vertices.par_iter_mut().enumerate().with_max_len(SHADE_TASK).for_each(|(i, cv)| {
                if visible[i].load(Ordering::Relaxed) {
                    cv.varying = shade_water(env, &look, lobe, mesh.positions[i], mesh.normals[i], foam(i));
                }
            });
            draw_with(&mut scratch.draw_colored, fb, clip_vertices, mesh.indices, Cull::None, &|f| f.varying);
        }
        Shading::Phong | Shading::BlinnPhong => {
            scratch.surface.resize(mesh.positions.len(), ClipVertex::default());
            scratch.surface.par_iter_mut().enumerate().for_each(|(i, cv)| {
                let (p, n) = (mesh.positions[i], mesh.normals[i]);
                *cv =
                    ClipVertex { position: clip(p), varying: SurfaceVarying { position: p, normal: n, foam: foam(i) } };
            });
            draw_with(&mut scratch.draw_surface, fb, &scratch.surface, mesh.indices, Cull::None, &|f| {
                let v = &f.varying;
                let n = v.normal.normalize_or(Vec3::Y);
                match filter {
                    Some(filter) => {
                        let unresolved = filter.variance(v.position, n);
                        shade_water_filtered(env, &look, lobe, v.position, n, v.foam, unresolved)
                    }
                    None => shade_water(env, &look, lobe, v.position, n, v.foam),
                }
            });
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_vertices_of_triangles_that_may_be_seen_are_lit() {
        // Vertex outcodes: 0 inside; 0b100 left of the view; 0b1000 right of it; 0b1 behind the eye.
        let outcodes = [0, 0b100, 0b100, 0b100, 0b1000, 0b1, 0b1100];
        let indices = [
            1, 2, 3, // wholly left of the view: not seen
            0, 1, 2, // one vertex inside: all three lit
            3, 4, 5, // left, right, behind: no common plane, may cross the view: lit
            2, 3, 6, // left, left, left+right: all outside the left plane: not seen on its own
        ];
        let mut visible = Vec::new();
        mark_visible_vertices(&indices, &outcodes, &mut visible);
        let lit: Vec<bool> = visible.iter().map(|v| v.load(Ordering::Relaxed)).collect();
        assert_eq!(lit, [true, true, true, true, true, true, false]);
        // Reusing the buffer clears what the last frame marked.
        mark_visible_vertices(&indices[..3], &outcodes, &mut visible);
        assert!(visible.iter().all(|v| !v.load(Ordering::Relaxed)));
    }

    #[test]
    fn view_outcodes_mark_the_planes_a_point_is_outside_of() {
        assert_eq!(view_outcode(Vec4::new(0.0, 0.0, 0.0, 1.0)), 0);
        assert_eq!(view_outcode(Vec4::new(1.0, -1.0, 1.0, 1.0)), 0, "the boundary is inside");
        assert_eq!(view_outcode(Vec4::new(-1.5, 0.0, 0.0, 1.0)), 0b100);
        assert_eq!(view_outcode(Vec4::new(1.5, 2.0, 0.0, 1.0)), 0b10_1000);
        assert_eq!(view_outcode(Vec4::new(0.0, 0.0, -2.0, 1.0)), 0b1, "in front of the near plane");
        assert_eq!(view_outcode(Vec4::new(0.0, 0.0, 2.0, 1.0)), 0b10, "beyond the far plane");
    }
}
