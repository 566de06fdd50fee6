//! Draws the water surface with its material's shading model.
//!
//! Each model interpolates only what it needs: flat shading nothing (one colour per triangle),
//! Gouraud a colour, Phong and Blinn-Phong the world position, normal and foam
//! ([`SurfaceVarying`]), shaded per pixel.

use glam::{Vec3, Vec4};
use rayon::prelude::*;

use super::FrameContext;
use crate::raster::{draw_with, ClipVertex, Cull, DrawScratch, Framebuffer};
use crate::scene::TerrainBody;
use crate::scene::WaterBody;
use crate::shading::{shade_water, FlatBottom, NoBottom, ReflectionMap, Seabed, Shading, SurfaceVarying, WaterLook};

/// Vertex buffers of the models that do not interpolate a colour, kept between frames.
#[derive(Default)]
pub struct Scratch {
    plain: Vec<ClipVertex<()>>,
    surface: Vec<ClipVertex<SurfaceVarying>>,
    draw_plain: DrawScratch<()>,
    draw_colored: DrawScratch<Vec3>,
    draw_surface: DrawScratch<SurfaceVarying>,
}

/// Draws `water` into `fb`, reusing `clip_vertices`, `face_colors` and `scratch`; `terrain` is
/// the bottom where the material sets none, `reflection` the terrain the surface mirrors.
pub fn draw(
    fb: &mut Framebuffer,
    frame: &FrameContext,
    water: &WaterBody,
    clip_vertices: &mut Vec<ClipVertex<Vec3>>,
    face_colors: &mut Vec<Vec3>,
    scratch: &mut Scratch,
    terrain: Option<&TerrainBody>,
    reflection: Option<&ReflectionMap>,
) {
    let mesh = &water.mesh;
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
            draw_with(&mut scratch.draw_plain, fb, &scratch.plain, &mesh.indices, Cull::None, &|f| {
                faces[f.primitive as usize]
            });
        }
        Shading::Gouraud => {
            clip_vertices.resize(mesh.positions.len(), ClipVertex::default());
            clip_vertices.par_iter_mut().enumerate().for_each(|(i, cv)| {
                let (p, n) = (mesh.positions[i], mesh.normals[i]);
                *cv = ClipVertex { position: clip(p), varying: shade_water(env, &look, lobe, p, n, foam(i)) };
            });
            draw_with(&mut scratch.draw_colored, fb, clip_vertices, &mesh.indices, Cull::None, &|f| f.varying);
        }
        Shading::Phong | Shading::BlinnPhong => {
            scratch.surface.resize(mesh.positions.len(), ClipVertex::default());
            scratch.surface.par_iter_mut().enumerate().for_each(|(i, cv)| {
                let (p, n) = (mesh.positions[i], mesh.normals[i]);
                *cv =
                    ClipVertex { position: clip(p), varying: SurfaceVarying { position: p, normal: n, foam: foam(i) } };
            });
            draw_with(&mut scratch.draw_surface, fb, &scratch.surface, &mesh.indices, Cull::None, &|f| {
                let v = &f.varying;
                shade_water(env, &look, lobe, v.position, v.normal.normalize_or(Vec3::Y), v.foam)
            });
        }
    }
}
