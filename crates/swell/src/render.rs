//! Scene + settings -> framebuffer: the vertex stage, the draw calls and the sky background.

use glam::{Vec3, Vec4};
use rayon::prelude::*;

use crate::raster::{draw, ClipVertex, Cull, Framebuffer};
use crate::scene::{Camera, World};
use crate::shading::{shade_water, Environment, Shading};

/// Renders [`World`]s, keeping its buffers from frame to frame so steady-state frames do not
/// allocate.
#[derive(Default)]
pub struct Renderer {
    framebuffer: Option<Framebuffer>,
    clip_vertices: Vec<ClipVertex<Vec3>>,
    face_colors: Vec<Vec3>,
}

impl Renderer {
    /// A renderer with no buffers yet.
    pub fn new() -> Self {
        Self::default()
    }

    /// Renders `world` at its scene's `[render]` size.
    pub fn render(&mut self, world: &World) -> &Framebuffer {
        let r = world.scene.render;
        self.render_size(world, r.width, r.height)
    }

    /// Renders `world` at `width` x `height` pixels (each at least 1, checked by the caller against
    /// [`crate::scene::MAX_IMAGE_SIDE`]).
    pub fn render_size(&mut self, world: &World, width: u32, height: u32) -> &Framebuffer {
        let fb = self.framebuffer.get_or_insert_with(|| Framebuffer::new(width, height));
        if (fb.width(), fb.height()) != (width, height) {
            fb.resize(width, height);
        }
        let scene = &world.scene;
        let camera = &scene.camera;
        let aspect = width as f32 / height as f32;
        let env =
            Environment { lights: &scene.lights, ambient: scene.render.ambient, sky: &scene.sky, eye: camera.eye };
        let rays = SkyRays::new(camera, aspect);
        fb.clear_with(|x, y| {
            let ndc_x = 2.0 * (x as f32 + 0.5) / width as f32 - 1.0;
            let ndc_y = 1.0 - 2.0 * (y as f32 + 0.5) / height as f32;
            scene.sky.radiance(rays.direction(ndc_x, ndc_y))
        });

        if let Some(water) = &world.water {
            let clip_from_world = camera.clip_from_world(aspect);
            let mesh = &water.mesh;
            let material = &water.material;
            let shading = material.shading;
            // Vertex stage: clip position, and for Gouraud the lit colour.
            self.clip_vertices.resize(mesh.positions.len(), ClipVertex::default());
            self.clip_vertices.par_iter_mut().zip(mesh.positions.par_iter().zip(mesh.normals.par_iter())).for_each(
                |(cv, (&p, &n))| {
                    cv.position = clip_from_world * Vec4::from((p, 1.0));
                    cv.varying = match shading {
                        Shading::Gouraud => shade_water(&env, material, p, n),
                        Shading::Flat => Vec3::ZERO,
                    };
                },
            );
            match shading {
                Shading::Gouraud => {
                    draw(fb, &self.clip_vertices, &mesh.indices, Cull::None, &|f| f.varying);
                }
                Shading::Flat => {
                    let positions = &mesh.positions;
                    self.face_colors.resize(mesh.indices.len() / 3, Vec3::ZERO);
                    self.face_colors.par_iter_mut().zip(mesh.indices.par_chunks_exact(3)).for_each(|(c, t)| {
                        let [a, b, d] = [0, 1, 2].map(|k| positions[t[k] as usize]);
                        let n = (b - a).cross(d - a).normalize_or(Vec3::Y);
                        *c = shade_water(&env, material, (a + b + d) / 3.0, n);
                    });
                    let faces = &self.face_colors;
                    draw(fb, &self.clip_vertices, &mesh.indices, Cull::None, &|f| faces[f.primitive as usize]);
                }
            }
        }
        fb
    }
}

/// World-space view-ray directions for NDC coordinates, for drawing the sky behind everything.
struct SkyRays {
    forward: Vec3,
    right: Vec3,
    up: Vec3,
}

impl SkyRays {
    fn new(camera: &Camera, aspect: f32) -> Self {
        let forward = (camera.target - camera.eye).normalize();
        let right = forward.cross(camera.up).normalize();
        let up = right.cross(forward);
        let tan_half = (0.5 * camera.fov_y_deg.to_radians()).tan();
        Self { forward, right: right * tan_half * aspect, up: up * tan_half }
    }

    fn direction(&self, ndc_x: f32, ndc_y: f32) -> Vec3 {
        (self.forward + self.right * ndc_x + self.up * ndc_y).normalize()
    }
}
