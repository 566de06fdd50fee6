//! Colour and depth buffers.

use glam::Vec3;
use rayon::prelude::*;

use crate::math::linear_to_srgb;

/// A linear-RGB colour buffer with a depth buffer, top row first.
#[derive(Clone, Debug)]
pub struct Framebuffer {
    width: u32,
    height: u32,
    /// Linear RGB per pixel, row-major, top row first.
    pub color: Vec<Vec3>,
    /// Window-space depth per pixel in [0, 1] (0 = near plane), cleared to 1.
    pub depth: Vec<f32>,
}

impl Framebuffer {
    /// A black framebuffer with depth cleared to the far plane. Sizes are the caller's to check
    /// ([`crate::scene::MAX_IMAGE_SIDE`]).
    pub fn new(width: u32, height: u32) -> Self {
        let n = width as usize * height as usize;
        Self { width, height, color: vec![Vec3::ZERO; n], depth: vec![1.0; n] }
    }

    /// Width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// Changes the size, reusing the allocation where it is large enough. Contents are unspecified.
    pub fn resize(&mut self, width: u32, height: u32) {
        let n = width as usize * height as usize;
        self.width = width;
        self.height = height;
        self.color.resize(n, Vec3::ZERO);
        self.depth.resize(n, 1.0);
    }

    /// Clears depth to the far plane and sets every colour to `background(x, y)`, rows in parallel.
    pub fn clear_with(&mut self, background: impl Fn(u32, u32) -> Vec3 + Sync) {
        let w = self.width as usize;
        self.depth.par_iter_mut().for_each(|d| *d = 1.0);
        self.color.par_chunks_mut(w).enumerate().for_each(|(y, row)| {
            for (x, c) in row.iter_mut().enumerate() {
                *c = background(x as u32, y as u32);
            }
        });
    }

    /// Encodes to RGBA8 (alpha 255): colour times `exposure`, then the sRGB curve, or the power
    /// law `c^(1/gamma)` when `gamma` is given. `out` is resized to `4 * width * height`.
    pub fn encode_rgba8(&self, exposure: f32, gamma: Option<f32>, out: &mut Vec<u8>) {
        out.resize(self.color.len() * 4, 0);
        let encode = |c: f32| -> u8 {
            let c = c * exposure;
            let e = match gamma {
                None => linear_to_srgb(c),
                Some(g) => c.clamp(0.0, 1.0).powf(1.0 / g),
            };
            // NaN clamps to 0 here, so a bad sample can never reach a file as garbage.
            (e * 255.0 + 0.5).clamp(0.0, 255.0) as u8
        };
        out.par_chunks_mut(4 * self.width as usize).zip(self.color.par_chunks(self.width as usize)).for_each(
            |(dst, src)| {
                for (px, c) in dst.chunks_exact_mut(4).zip(src) {
                    px[0] = encode(c.x);
                    px[1] = encode(c.y);
                    px[2] = encode(c.z);
                    px[3] = 255;
                }
            },
        );
    }
}
