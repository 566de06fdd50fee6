//! Scene + settings -> framebuffer. One file per pass, drawn in order into the same z-buffer:
//! [`sky_pass`] clears to the sky, [`water_pass`] draws the water surface.

mod sky_pass;
mod terrain_pass;
mod water_pass;

use glam::Vec3;

use crate::raster::{ClipVertex, Framebuffer};
use crate::scene::World;
use crate::shading::Environment;

/// Renders [`World`]s, keeping its buffers from frame to frame so steady-state frames do not
/// allocate.
#[derive(Default)]
pub struct Renderer {
    framebuffer: Option<Framebuffer>,
    /// Vertex-stage output, reused by every pass.
    clip_vertices: Vec<ClipVertex<Vec3>>,
    /// Per-triangle colours for flat shading, reused by every pass.
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
        let frame = FrameContext {
            env: Environment {
                lights: &scene.lights,
                ambient: scene.render.ambient,
                sky: &scene.sky,
                eye: scene.camera.eye,
            },
            clip_from_world: scene.camera.clip_from_world(width as f32 / height as f32),
        };
        sky_pass::draw(fb, scene);
        if let Some(terrain) = &world.terrain {
            terrain_pass::draw(fb, &frame, terrain, &mut self.clip_vertices, &mut self.face_colors);
        }
        if let Some(water) = &world.water {
            water_pass::draw(fb, &frame, water, &mut self.clip_vertices, &mut self.face_colors);
        }
        fb
    }
}

/// What every pass of one frame shares.
pub(crate) struct FrameContext<'a> {
    /// Lights, ambient, sky and eye.
    pub env: Environment<'a>,
    /// World to clip transform of the frame's camera and aspect ratio.
    pub clip_from_world: glam::Mat4,
}
