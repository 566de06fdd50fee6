//! Draws the terrain: colour by height and slope, lit per vertex (Gouraud) or per face (paper
//! 001's flat look). Drawn before the water so the water's depth test sees the ground.

use glam::{Vec3, Vec4};
use rayon::prelude::*;

use super::FrameContext;
use crate::raster::{draw as raster_draw, ClipVertex, Cull, Framebuffer};
use crate::scene::TerrainBody;
use crate::shading::{shade_terrain, TerrainShading};

/// Draws `terrain` into `fb`, reusing `clip_vertices` and `face_colors` as scratch.
pub fn draw(
    fb: &mut Framebuffer,
    frame: &FrameContext,
    terrain: &TerrainBody,
    clip_vertices: &mut Vec<ClipVertex<Vec3>>,
    face_colors: &mut Vec<Vec3>,
) {
    let mesh = &terrain.mesh;
    let material = &terrain.material;
    let env = &frame.env;
    let clip_from_world = frame.clip_from_world;
    clip_vertices.resize(mesh.positions.len(), ClipVertex::default());
    clip_vertices.par_iter_mut().zip(mesh.positions.par_iter().zip(mesh.normals.par_iter())).for_each(
        |(cv, (&p, &n))| {
            cv.position = clip_from_world * Vec4::from((p, 1.0));
            cv.varying = match material.shading {
                TerrainShading::Gouraud => shade_terrain(env, material, p, n),
                TerrainShading::Flat => Vec3::ZERO,
            };
        },
    );
    match material.shading {
        TerrainShading::Gouraud => raster_draw(fb, clip_vertices, &mesh.indices, Cull::None, &|f| f.varying),
        TerrainShading::Flat => {
            // Paper 001 §2.2: one intensity per triangle from its plane's normal.
            let positions = &mesh.positions;
            face_colors.resize(mesh.indices.len() / 3, Vec3::ZERO);
            face_colors.par_iter_mut().zip(mesh.indices.par_chunks_exact(3)).for_each(|(c, t)| {
                let [a, b, d] = [0, 1, 2].map(|k| positions[t[k] as usize]);
                // Triangles wind counter-clockwise seen from above, so this normal points up.
                let n = (b - a).cross(d - a).normalize_or(Vec3::Y);
                *c = shade_terrain(env, material, (a + b + d) / 3.0, n);
            });
            let faces = &*face_colors;
            raster_draw(fb, clip_vertices, &mesh.indices, Cull::None, &|f| faces[f.primitive as usize]);
        }
    }
}
