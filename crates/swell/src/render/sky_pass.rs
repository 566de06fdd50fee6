//! The sky seen along each pixel's view ray. The depth is cleared before the geometry passes
//! ([`clear_depth`]) and the sky drawn after them ([`draw`]), only where no geometry landed, so a
//! frame full of water does not pay for a sky it hides.

use glam::Vec3;
use rayon::prelude::*;

use crate::raster::Framebuffer;
use crate::scene::{Camera, Scene, SunDisc};

/// Clears depth to the far plane (colour is left for [`draw`]).
pub fn clear_depth(fb: &mut Framebuffer) {
    fb.depth.par_iter_mut().for_each(|d| *d = 1.0);
}

/// Fills every pixel still at the far plane with the sky of `scene` (and its sun disc, if any).
pub fn draw(fb: &mut Framebuffer, scene: &Scene, sun: Option<&SunDisc>) {
    let (width, height) = (fb.width(), fb.height());
    let rays = SkyRays::new(&scene.camera, width as f32 / height as f32);
    fb.fill_background(|x, y| {
        let ndc_x = 2.0 * (x as f32 + 0.5) / width as f32 - 1.0;
        let ndc_y = 1.0 - 2.0 * (y as f32 + 0.5) / height as f32;
        let dir = rays.direction(ndc_x, ndc_y);
        let sky = scene.sky.radiance(dir);
        match sun {
            Some(s) => sky + s.radiance(dir),
            None => sky,
        }
    });
}

/// World-space view-ray directions for NDC coordinates: a ray through NDC (x, y) is linear in x
/// and y before normalisation, so three vectors replace an inverse projection per pixel.
pub(crate) struct SkyRays {
    forward: Vec3,
    right: Vec3,
    up: Vec3,
}

impl SkyRays {
    /// Rays of `camera` for an image of `aspect` = width / height.
    pub fn new(camera: &Camera, aspect: f32) -> Self {
        let forward = (camera.target - camera.eye).normalize();
        let right = forward.cross(camera.up).normalize();
        let up = right.cross(forward);
        let tan_half = (0.5 * camera.fov_y_deg.to_radians()).tan();
        Self { forward, right: right * tan_half * aspect, up: up * tan_half }
    }

    /// Unit world direction of the ray through NDC (`ndc_x`, `ndc_y`), each in [-1, 1].
    pub fn direction(&self, ndc_x: f32, ndc_y: f32) -> Vec3 {
        (self.forward + self.right * ndc_x + self.up * ndc_y).normalize()
    }
}
