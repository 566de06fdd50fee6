//! The sky seen along each pixel's view ray. The depth is cleared before the geometry passes
//! ([`clear_depth`]) and the sky drawn after them ([`draw`]), only where no geometry landed, so a
//! frame full of water does not pay for a sky it hides.

use glam::Vec3;
use rayon::prelude::*;

use crate::raster::Framebuffer;
use crate::scene::{Camera, SkyRadiance, SunDisc};

/// Clears depth to the far plane (colour is left for [`draw`]).
pub fn clear_depth(fb: &mut Framebuffer) {
    fb.depth.par_iter_mut().for_each(|d| *d = 1.0);
}

/// Fills every pixel still at the far plane with `sky` seen by `camera` (and its sun disc, if any).
pub fn draw(fb: &mut Framebuffer, camera: &Camera, sky: &SkyRadiance, sun: Option<&SunDisc>) {
    let (width, height) = (fb.width(), fb.height());
    let rays = SkyRays::new(camera, width as f32 / height as f32);
    fb.fill_background(|y| {
        let ndc_y = 1.0 - 2.0 * (y as f32 + 0.5) / height as f32;
        let row = rays.row(ndc_y);
        move |x| {
            let ndc_x = 2.0 * (x as f32 + 0.5) / width as f32 - 1.0;
            let dir = row.direction(ndc_x);
            match sun {
                Some(s) => sky.radiance(dir) + s.radiance(dir),
                None => sky.radiance(dir),
            }
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

    /// The rays of the image row at `ndc_y` in [-1, 1].
    pub fn row(&self, ndc_y: f32) -> SkyRow {
        SkyRow { forward: self.forward, right: self.right, up_y: self.up * ndc_y }
    }
}

/// The view rays of one image row: [`SkyRays`] with the row's share computed once.
pub(crate) struct SkyRow {
    forward: Vec3,
    right: Vec3,
    /// The up vector scaled to the row.
    up_y: Vec3,
}

impl SkyRow {
    /// Unit world direction of the ray through NDC x `ndc_x` in [-1, 1] on this row.
    #[inline]
    pub fn direction(&self, ndc_x: f32) -> Vec3 {
        // The same sum, in the same order, as computed per pixel before the row was factored out.
        (self.forward + self.right * ndc_x + self.up_y).normalize()
    }
}
