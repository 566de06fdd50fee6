//! What per-pixel shading interpolates across a triangle.

use glam::Vec3;

use crate::raster::Varying;

/// World position, normal, foam and unresolved slope variance of a vertex, interpolated
/// perspective-correctly for Phong and Blinn-Phong shading. The interpolated normal is not unit
/// length: shaders normalise it.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SurfaceVarying {
    /// World position, metres.
    pub position: Vec3,
    /// World normal (unit at the vertices).
    pub normal: Vec3,
    /// Foam coverage in [0, 1].
    pub foam: f32,
    /// Slope variance (both axes summed, >= 0, dimensionless) of the waves the mesh and the pixel
    /// cannot resolve, which the shading takes statistically; 0 for a point-sampled surface. The
    /// unbounded sea computes it per vertex (`render/sea_lod.rs`): it varies smoothly with distance,
    /// so interpolating it costs a pixel one weighted sum instead of a footprint, a logarithm and a
    /// table look-up (a quarter of the `sea` preset's water shading).
    pub unresolved: f32,
}

impl Varying for SurfaceVarying {
    fn lerp(&self, other: &Self, t: f32) -> Self {
        Self {
            position: self.position.lerp(other.position, t),
            normal: self.normal.lerp(other.normal, t),
            foam: self.foam + (other.foam - self.foam) * t,
            unresolved: self.unresolved + (other.unresolved - self.unresolved) * t,
        }
    }

    fn weighted(a: &Self, b: &Self, c: &Self, w: [f32; 3]) -> Self {
        Self {
            position: a.position * w[0] + b.position * w[1] + c.position * w[2],
            normal: a.normal * w[0] + b.normal * w[1] + c.normal * w[2],
            foam: a.foam * w[0] + b.foam * w[1] + c.foam * w[2],
            unresolved: a.unresolved * w[0] + b.unresolved * w[1] + c.unresolved * w[2],
        }
    }
}
