//! Draws the water surface with its material's shading model.

use glam::{Vec3, Vec4};
use rayon::prelude::*;

use super::FrameContext;
use crate::raster::{draw as raster_draw, ClipVertex, Cull, Framebuffer};
use crate::scene::WaterBody;
use crate::shading::{shade_water, Shading};

/// Draws `water` into `fb`, reusing `clip_vertices` and `face_colors` as scratch.
pub fn draw(
    fb: &mut Framebuffer,
    frame: &FrameContext,
    water: &WaterBody,
    clip_vertices: &mut Vec<ClipVertex<Vec3>>,
    face_colors: &mut Vec<Vec3>,
) {
    let mesh = &water.mesh;
    let material = &water.material;
    let env = &frame.env;
    let clip_from_world = frame.clip_from_world;
    // Vertex stage: clip position, and for Gouraud the lit colour.
    clip_vertices.resize(mesh.positions.len(), ClipVertex::default());
    clip_vertices.par_iter_mut().zip(mesh.positions.par_iter().zip(mesh.normals.par_iter())).for_each(
        |(cv, (&p, &n))| {
            cv.position = clip_from_world * Vec4::from((p, 1.0));
            cv.varying = match material.shading {
                Shading::Gouraud => shade_water(env, material, p, n),
                Shading::Flat => Vec3::ZERO,
            };
        },
    );
    // Foam (FFT ocean): blend towards a diffuse white surface by coverage. A minimal placeholder
    // until foam gets its own shading; 0.8 is the albedo of whitecap foam (Koepke 1984).
    if mesh.has_foam && material.shading == Shading::Gouraud {
        let (foam, positions, normals) = (&mesh.foam, &mesh.positions, &mesh.normals);
        clip_vertices.par_iter_mut().enumerate().for_each(|(i, cv)| {
            let f = foam[i].clamp(0.0, 1.0);
            if f > 0.0 {
                cv.varying = cv.varying.lerp(0.8 * crate::shading::lambert(env, positions[i], normals[i]), f);
            }
        });
    }
    match material.shading {
        Shading::Gouraud => raster_draw(fb, clip_vertices, &mesh.indices, Cull::None, &|f| f.varying),
        Shading::Flat => {
            let positions = &mesh.positions;
            face_colors.resize(mesh.indices.len() / 3, Vec3::ZERO);
            face_colors.par_iter_mut().zip(mesh.indices.par_chunks_exact(3)).for_each(|(c, t)| {
                let [a, b, d] = [0, 1, 2].map(|k| positions[t[k] as usize]);
                let n = (b - a).cross(d - a).normalize_or(Vec3::Y);
                *c = shade_water(env, material, (a + b + d) / 3.0, n);
            });
            let faces = &*face_colors;
            raster_draw(fb, clip_vertices, &mesh.indices, Cull::None, &|f| faces[f.primitive as usize]);
        }
    }
}
