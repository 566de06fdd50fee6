//! The rasterizer: clip-space triangles in, depth-tested shaded pixels out.
//!
//! It knows nothing about what it draws (euc's lesson): the caller supplies clip-space vertices
//! carrying any [`Varying`] and a fragment shader. Stages, each in its own file:
//!
//! 1. [`clip`]: homogeneous clipping against the near and far planes and a guard band;
//! 2. [`triangle`]: setup in 24.8 fixed point, edge functions with the top-left fill rule;
//! 3. [`pipeline`]: setup in parallel, binning into horizontal bands, bands rasterized in parallel;
//!    triangles of at most 2 x 2 pixels are set up and covered 16 at a time (`tiny_triangles`) and
//!    binned as fragments;
//! 4. [`framebuffer`]: linear colour and depth, encoded to RGBA8 at the end (`rgba8_encoder`);
//! 5. [`line`]: depth-tested lines for overlays.
//!
//! Each pixel belongs to exactly one band and each band draws its triangles in submission order, so
//! the image is bit-identical for any number of threads.

pub mod clip;
mod framebuffer;
pub mod line;
mod pipeline;
pub mod reference;
mod rgba8_encoder;
mod tiny_triangles;
pub mod triangle;

pub use framebuffer::Framebuffer;
pub use pipeline::{draw, draw_deferred_with, draw_with, Cull, DrawScratch, Fragment};

use glam::Vec4;

/// Per-vertex data interpolated across a triangle (colour, normal, world position, uv...).
pub trait Varying: Copy + Default + Send + Sync {
    /// `self * (1 - t) + other * t`, used by the clipper.
    fn lerp(&self, other: &Self, t: f32) -> Self;
    /// `a * w[0] + b * w[1] + c * w[2]` with weights summing to 1, used per pixel.
    fn weighted(a: &Self, b: &Self, c: &Self, w: [f32; 3]) -> Self;
}

impl Varying for () {
    fn lerp(&self, _: &Self, _: f32) -> Self {}
    fn weighted(_: &Self, _: &Self, _: &Self, _: [f32; 3]) -> Self {}
}

impl Varying for glam::Vec3 {
    fn lerp(&self, other: &Self, t: f32) -> Self {
        glam::Vec3::lerp(*self, *other, t)
    }
    fn weighted(a: &Self, b: &Self, c: &Self, w: [f32; 3]) -> Self {
        *a * w[0] + *b * w[1] + *c * w[2]
    }
}

/// A vertex after the vertex stage: clip-space position (OpenGL convention) and its varyings.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ClipVertex<V> {
    /// Clip-space position; visible points satisfy −w <= x, y, z <= w.
    pub position: Vec4,
    /// Data to interpolate.
    pub varying: V,
}
