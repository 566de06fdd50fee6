//! What per-pixel shading interpolates across a triangle.

use glam::Vec3;

use crate::raster::Varying;

/// World position, normal and foam of a vertex, interpolated perspective-correctly for Phong and
/// Blinn-Phong shading. The interpolated normal is not unit length: shaders normalise it.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SurfaceVarying {
    /// World position, metres.
    pub position: Vec3,
    /// World normal (unit at the vertices).
    pub normal: Vec3,
    /// Foam coverage in [0, 1].
    pub foam: f32,
}

impl Varying for SurfaceVarying {
    fn lerp(&self, other: &Self, t: f32) -> Self {
        Self {
            position: self.position.lerp(other.position, t),
            normal: self.normal.lerp(other.normal, t),
            foam: self.foam + (other.foam - self.foam) * t,
        }
    }

    fn weighted(a: &Self, b: &Self, c: &Self, w: [f32; 3]) -> Self {
        Self {
            position: a.position * w[0] + b.position * w[1] + c.position * w[2],
            normal: a.normal * w[0] + b.normal * w[1] + c.normal * w[2],
            foam: a.foam * w[0] + b.foam * w[1] + c.foam * w[2],
        }
    }
}
