//! The one shaded-draw path: a triangle mesh, a shading model and a surface shader in, pixels out.
//!
//! Every pass that draws lit geometry (water, terrain, the terrain's mirror image, the OBJ
//! comparison mode) comes through [`ShadedDraw::draw`], so the choice between the shading models
//! is written once:
//!
//! - [`Shading::Flat`]: the shader runs once per triangle, at its centroid with its face normal
//!   and mean foam; the rasterizer interpolates nothing.
//! - [`Shading::Gouraud`]: the shader runs once per vertex and the rasterizer interpolates the
//!   colour. Only vertices of triangles that may be seen are lit (the image is the same: a
//!   triangle wholly outside one plane of the view covers no pixel), which on a large patch seen
//!   from close up is most of the saving.
//! - [`Shading::Phong`] and [`Shading::BlinnPhong`]: the rasterizer interpolates position, normal
//!   and foam ([`SurfaceVarying`]) and the shader runs per pixel with the renormalised normal.
//!
//! A pass says what its surface looks like through [`SurfaceShader`]; which lobe the shading model
//! implies is the shader's business (the water's depends on it, the terrain's and the OBJ light's
//! have no specular term).

use std::sync::atomic::{AtomicBool, Ordering};

use glam::{Vec3, Vec4};
use rayon::prelude::*;

use crate::raster::clip::view_outcode;
use crate::raster::{draw_deferred_with, draw_with, ClipVertex, Cull, DrawScratch, Framebuffer};
use crate::scene::Shading;
use crate::shading::SurfaceVarying;

/// Triangles per task of [`mark_visible_vertices`].
const MARK_TASK: usize = 4096;

/// Vertices per task of the Gouraud lighting: the lit vertices come in runs (the rows in view),
/// so fixed-size tasks balance better than rayon's adaptive splitting.
const SHADE_TASK: usize = 4096;

/// Points per [`SurfaceShader::shade_points`] call, gathered in arrays on the stack: a task's
/// worth in `Vec`s was 240 KiB, which the allocator maps and unmaps on every call (above its
/// 128 KiB threshold), a page fault per 4 KiB touched, every frame.
const SHADE_RUN: usize = 256;

/// What a surface looks like: the radiance (linear RGB) leaving a surface point towards the eye,
/// given as a [`SurfaceVarying`]: world position (m), unit normal, foam coverage in [0, 1] and
/// the slope variance the mesh and the pixel leave unresolved.
pub(crate) trait SurfaceShader: Sync {
    /// Radiance at one surface point (unit normal).
    fn shade(&self, point: &SurfaceVarying) -> Vec3;

    /// Radiance at a run of surface points (unit normals), into `out` (as many): the vertices of
    /// a Gouraud draw, the faces of a flat one. The default shades each with [`Self::shade`]; a
    /// shader may shade several at once with the same result.
    fn shade_points(&self, points: &[SurfaceVarying], out: &mut [Vec3]) {
        for (p, o) in points.iter().zip(out.iter_mut()) {
            *o = self.shade(p);
        }
    }

    /// Per-pixel shading of a run of pixels (one row's covered pixels, left to right): `out[i]`
    /// gets the radiance of `pixels[i]`, interpolated across its triangle, whose normal is not
    /// yet unit length. The default shades each with [`Self::shade`]; a shader may shade several
    /// at once instead, as long as each pixel's colour depends on that pixel alone.
    fn shade_pixels(&self, pixels: &[SurfaceVarying], out: &mut [Vec3]) {
        for (v, o) in pixels.iter().zip(out.iter_mut()) {
            *o = self.shade(&SurfaceVarying { normal: v.normal.normalize_or(Vec3::Y), ..*v });
        }
    }
}

/// A triangle mesh as the shaded draw reads it: world positions (m), unit vertex normals, optional
/// per-vertex foam in [0, 1] and unresolved slope variance, and counter-clockwise index triples.
#[derive(Clone, Copy)]
pub(crate) struct ShadedMesh<'a> {
    /// World positions, metres.
    pub positions: &'a [Vec3],
    /// Unit normals, one per position.
    pub normals: &'a [Vec3],
    /// Foam coverage per position, or `None` for a surface without foam (shaded with 0).
    pub foam: Option<&'a [f32]>,
    /// Unresolved slope variance per position ([`SurfaceVarying::unresolved`]), interpolated for
    /// per-pixel shading, or `None` for a point-sampled surface (0).
    pub unresolved: Option<&'a [f32]>,
    /// Three indices per triangle.
    pub indices: &'a [u32],
}

impl<'a> ShadedMesh<'a> {
    /// A mesh without foam or unresolved slopes (terrain, far land, an OBJ model).
    pub fn plain(positions: &'a [Vec3], normals: &'a [Vec3], indices: &'a [u32]) -> Self {
        Self { positions, normals, foam: None, unresolved: None, indices }
    }

    /// Foam coverage of vertex `i` (0 where the mesh has none).
    #[inline]
    fn foam_at(&self, i: usize) -> f32 {
        self.foam.map_or(0.0, |f| f[i])
    }

    /// Unresolved slope variance of vertex `i` (0 where the mesh has none).
    #[inline]
    fn unresolved_at(&self, i: usize) -> f32 {
        self.unresolved.map_or(0.0, |u| u[i])
    }

    /// Vertex `i` as a surface point.
    #[inline]
    fn point(&self, i: usize) -> SurfaceVarying {
        SurfaceVarying {
            position: self.positions[i],
            normal: self.normals[i],
            foam: self.foam_at(i),
            unresolved: self.unresolved_at(i),
        }
    }
}

/// The vertex buffers and draw scratch of one shaded mesh, kept between frames so steady-state
/// frames do not allocate. One per pass: [`ShadedDraw::redraw`] reuses what the last draw lit.
#[derive(Default)]
pub(crate) struct ShadedDraw {
    shading: Shading,
    plain: Vec<ClipVertex<()>>,
    colored: Vec<ClipVertex<Vec3>>,
    surface: Vec<ClipVertex<SurfaceVarying>>,
    /// Per-triangle colours (flat shading).
    faces: Vec<Vec3>,
    draw_plain: DrawScratch<()>,
    draw_colored: DrawScratch<Vec3>,
    draw_surface: DrawScratch<SurfaceVarying>,
    /// [`view_outcode`] of each vertex (Gouraud).
    outcodes: Vec<u8>,
    /// Whether a vertex belongs to a triangle not wholly outside the view (Gouraud).
    visible: Vec<AtomicBool>,
}

impl ShadedDraw {
    /// Draws `mesh` into `fb` with `shading`, each point's colour from `shader`, positions taken
    /// to clip space by `clip`, with a depth test and no culling.
    pub fn draw<S: SurfaceShader>(
        &mut self,
        fb: &mut Framebuffer,
        mesh: ShadedMesh,
        clip: &(dyn Fn(Vec3) -> Vec4 + Sync),
        shading: Shading,
        shader: &S,
    ) {
        self.shading = shading;
        let n = mesh.positions.len();
        match shading {
            Shading::Flat => {
                self.plain.resize(n, ClipVertex::default());
                self.plain.par_iter_mut().zip(mesh.positions.par_iter()).for_each(|(cv, &p)| cv.position = clip(p));
                let positions = mesh.positions;
                self.faces.resize(mesh.indices.len() / 3, Vec3::ZERO);
                self.faces.par_chunks_mut(SHADE_TASK).zip(mesh.indices.par_chunks(3 * SHADE_TASK)).for_each(
                    |(faces, tris)| {
                        let mut points = [SurfaceVarying::default(); SHADE_RUN];
                        for (faces, tris) in faces.chunks_mut(SHADE_RUN).zip(tris.chunks(3 * SHADE_RUN)) {
                            for (p, t) in points.iter_mut().zip(tris.chunks_exact(3)) {
                                // Indexed one by one: `[0, 1, 2].map` is not always inlined here.
                                let (i, j, k) = (t[0] as usize, t[1] as usize, t[2] as usize);
                                let (a, b, d) = (positions[i], positions[j], positions[k]);
                                // Triangles wind counter-clockwise seen from their front, so this
                                // normal points out of it (up, for water and terrain).
                                *p = SurfaceVarying {
                                    position: (a + b + d) / 3.0,
                                    normal: (b - a).cross(d - a).normalize_or(Vec3::Y),
                                    foam: (mesh.foam_at(i) + mesh.foam_at(j) + mesh.foam_at(k)) / 3.0,
                                    unresolved: (mesh.unresolved_at(i) + mesh.unresolved_at(j) + mesh.unresolved_at(k))
                                        / 3.0,
                                };
                            }
                            shader.shade_points(&points[..faces.len()], faces);
                        }
                    },
                );
                let faces = &self.faces;
                draw_with(&mut self.draw_plain, fb, &self.plain, mesh.indices, Cull::None, &|f| {
                    faces[f.primitive as usize]
                });
            }
            Shading::Gouraud => {
                self.colored.resize(n, ClipVertex::default());
                self.project_and_light(mesh, clip, shader);
                draw_with(&mut self.draw_colored, fb, &self.colored, mesh.indices, Cull::None, &|f| f.varying);
            }
            Shading::Phong | Shading::BlinnPhong => {
                self.surface.resize(n, ClipVertex::default());
                self.surface.par_iter_mut().enumerate().for_each(|(i, cv)| {
                    let varying = mesh.point(i);
                    *cv = ClipVertex { position: clip(varying.position), varying };
                });
                self.draw_surface_pixels(fb, mesh, shader);
            }
        }
    }

    /// Draws the mesh of the last [`ShadedDraw::draw`] again into `fb` with the same shading,
    /// positions taken to clip space by another `clip` (the mirrored view of the terrain's
    /// reflection). Flat colours are reused as they are; Gouraud lights the vertices this view
    /// sees (the colour of a vertex does not depend on the view for the shaders that are
    /// redrawn, so vertices lit for both views get the same colour); per-pixel shading runs
    /// `shader` again at the real (unmirrored) positions.
    pub fn redraw<S: SurfaceShader>(
        &mut self,
        fb: &mut Framebuffer,
        mesh: ShadedMesh,
        clip: &(dyn Fn(Vec3) -> Vec4 + Sync),
        shader: &S,
    ) {
        match self.shading {
            Shading::Flat => {
                self.plain.par_iter_mut().zip(mesh.positions.par_iter()).for_each(|(cv, &p)| cv.position = clip(p));
                let faces = &self.faces;
                draw_with(&mut self.draw_plain, fb, &self.plain, mesh.indices, Cull::None, &|f| {
                    faces[f.primitive as usize]
                });
            }
            Shading::Gouraud => {
                self.project_and_light(mesh, clip, shader);
                draw_with(&mut self.draw_colored, fb, &self.colored, mesh.indices, Cull::None, &|f| f.varying);
            }
            Shading::Phong | Shading::BlinnPhong => {
                self.surface.par_iter_mut().zip(mesh.positions.par_iter()).for_each(|(cv, &p)| cv.position = clip(p));
                self.draw_surface_pixels(fb, mesh, shader);
            }
        }
    }

    /// Gouraud's vertex stage: clip positions and outcodes of every vertex, then the colour of
    /// each vertex of a triangle that may be seen.
    fn project_and_light<S: SurfaceShader>(
        &mut self,
        mesh: ShadedMesh,
        clip: &(dyn Fn(Vec3) -> Vec4 + Sync),
        shader: &S,
    ) {
        let n = mesh.positions.len();
        self.outcodes.resize(n, 0);
        self.colored.par_iter_mut().zip(self.outcodes.par_iter_mut()).enumerate().for_each(|(i, (cv, oc))| {
            let position = clip(mesh.positions[i]);
            *oc = view_outcode(position);
            cv.position = position;
        });
        mark_visible_vertices(mesh.indices, &self.outcodes, &mut self.visible);
        let visible = &self.visible;
        // Visible vertices in blocks, each shaded as one run (the water shades many at a time).
        self.colored.par_chunks_mut(SHADE_TASK).enumerate().for_each(|(block, colored)| {
            let base = block * SHADE_TASK;
            let (mut lit, mut points, mut colors) =
                ([0; SHADE_RUN], [SurfaceVarying::default(); SHADE_RUN], [Vec3::ZERO; SHADE_RUN]);
            let mut n = 0;
            // Runs of up to SHADE_RUN visible vertices, each shaded when full or at the block's end.
            let end = base + colored.len();
            for (i, seen) in visible[base..end].iter().enumerate().map(|(k, v)| (base + k, v)) {
                if seen.load(Ordering::Relaxed) {
                    (lit[n], points[n]) = (i - base, mesh.point(i));
                    n += 1;
                }
                if n == SHADE_RUN || (n > 0 && i + 1 == end) {
                    shader.shade_points(&points[..n], &mut colors[..n]);
                    for (&i, &c) in lit[..n].iter().zip(&colors[..n]) {
                        colored[i].varying = c;
                    }
                    n = 0;
                }
            }
        });
    }

    /// Per-pixel shading of the surface vertices already in `self.surface`.
    /// Per-pixel shading, deferred: each visible pixel is shaded once, whatever the overdraw.
    fn draw_surface_pixels<S: SurfaceShader>(&mut self, fb: &mut Framebuffer, mesh: ShadedMesh, shader: &S) {
        draw_deferred_with(&mut self.draw_surface, fb, &self.surface, mesh.indices, Cull::None, &|pixels, out| {
            shader.shade_pixels(pixels, out)
        });
    }
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

    /// Every shading model draws the same flat, evenly lit quad the same colour, and redrawing
    /// through another transform keeps it.
    #[test]
    fn every_shading_model_goes_through_the_one_path() {
        struct Even;
        impl SurfaceShader for Even {
            fn shade(&self, p: &SurfaceVarying) -> Vec3 {
                Vec3::new(p.normal.y, 0.5, p.foam)
            }
        }
        let positions = [
            Vec3::new(-1.0, 0.0, -1.0),
            Vec3::new(1.0, 0.0, -1.0),
            Vec3::new(1.0, 0.0, 1.0),
            Vec3::new(-1.0, 0.0, 1.0),
        ];
        let normals = [Vec3::Y; 4];
        let foam = [0.25; 4];
        // Counter-clockwise seen from above (+Y).
        let indices = [0, 2, 1, 0, 3, 2];
        let mesh = ShadedMesh {
            positions: &positions,
            normals: &normals,
            foam: Some(&foam),
            unresolved: None,
            indices: &indices,
        };
        // Looking straight down: x to the right, z down the image.
        let clip = |p: Vec3| Vec4::new(p.x * 0.5, -p.z * 0.5, 0.0, 1.0);
        for shading in Shading::ALL {
            let mut fb = Framebuffer::new(8, 8);
            fb.clear_with(|_, _| Vec3::ZERO);
            let mut draw = ShadedDraw::default();
            draw.draw(&mut fb, mesh, &clip, *shading, &Even);
            let centre = fb.color[4 * 8 + 4];
            assert!((centre - Vec3::new(1.0, 0.5, 0.25)).abs().max_element() < 1e-5, "{shading:?}: {centre}");
            let mirrored = |p: Vec3| Vec4::new(-p.x * 0.5, p.z * 0.5, 0.0, 1.0);
            let mut again = Framebuffer::new(8, 8);
            again.clear_with(|_, _| Vec3::ZERO);
            draw.redraw(&mut again, mesh, &mirrored, &Even);
            assert_eq!(again.color[4 * 8 + 4], centre, "{shading:?}");
        }
    }
}
