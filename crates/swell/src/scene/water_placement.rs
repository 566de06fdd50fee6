//! Where the water patch sits in the world: paper 000's object transform, restricted to what a
//! water surface at rest on y = 0 allows — a turn about +Y (yaw) and a uniform scale, both about
//! the patch centre.
//!
//! The wave model and the sampling grid live in the patch's own frame ("local"); the world sees
//!
//! ```text
//! world = c + s Ry(yaw) (local - c)          c = (center.x, 0, center.z)
//! ```
//!
//! so the waves turn and grow with the patch (heights scale by s too: a uniform scale). With yaw 0
//! and scale 1 local and world coincide, which keeps every scene written before these keys
//! existed exactly as it was (the centre then moves the patch over a fixed wave field, as before).
//!
//! Rotations about X or Z are refused by design, not missing: they would tilt the water at rest
//! off y = 0, and the crate's conventions (water at rest at y = 0) and the water optics (the
//! reflection plane y = 0, depth measured down from y = 0) rely on that plane.
//! `Ry` is the same rotation as [`crate::math::Transform`]'s about Y: positive angles turn
//! counter-clockwise looking down the +Y axis.

use glam::{DQuat, DVec2, DVec3, Quat, Vec2, Vec3};
use rayon::prelude::*;

use crate::error::{check_finite_vec, check_range, Error, Result};
use crate::math::MAX_SCALE;
use crate::mesh::SurfaceMesh;

/// A checked water placement: centre, turn and uniform scale, mapping the model's frame to the
/// world as `world = c + s Ry(yaw) (local - c)`, `c = (center.x, 0, center.z)` (paper 000's object
/// transform without X/Z turns; see `docs/scene-format.md`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WaterPlacement {
    /// Pivot (x, z) in world metres: the patch centre.
    pub center: Vec2,
    /// Turn about +Y through the centre, radians.
    pub yaw: f32,
    /// Uniform scale factor about the centre, in (0, [`MAX_SCALE`]].
    pub scale: f32,
}

impl WaterPlacement {
    /// Checks and builds a placement; errors name `water.center`, `water.yaw_deg` and
    /// `water.uniform_scale`.
    pub fn new(center: Vec2, yaw_deg: f32, scale: f32) -> Result<Self> {
        check_finite_vec("water.center", &center.to_array())?;
        check_range("water.yaw_deg", yaw_deg, -360.0, 360.0)?;
        if !(scale.is_finite() && scale > 0.0 && scale <= MAX_SCALE) {
            return Err(Error::out_of_range("water.uniform_scale", scale, format!("(0, {MAX_SCALE}]")));
        }
        Ok(Self { center, yaw: yaw_deg.to_radians(), scale })
    }

    /// Whether world and local coincide (no work to do).
    pub fn is_identity(&self) -> bool {
        self.yaw == 0.0 && self.scale == 1.0
    }

    fn rotation(&self) -> Quat {
        Quat::from_rotation_y(self.yaw)
    }

    fn pivot(&self) -> Vec3 {
        Vec3::new(self.center.x, 0.0, self.center.y)
    }

    /// A local point (m) in the world.
    pub fn to_world(&self, local: Vec3) -> Vec3 {
        self.pivot() + self.scale * (self.rotation() * (local - self.pivot()))
    }

    /// The local (x, z) of a world (x, z): the point of the wave field that lands there.
    pub fn to_local_xz(&self, world: Vec2) -> Vec2 {
        let p = Vec3::new(world.x - self.center.x, 0.0, world.y - self.center.y);
        let l = self.rotation().conjugate() * p / self.scale;
        Vec2::new(l.x + self.center.x, l.z + self.center.y)
    }

    /// [`WaterPlacement::to_local_xz`] in double precision, for world points far from the origin
    /// (an engine's coordinates at 10^6 m, where f32 steps are 6 cm): the query API's `_f64`
    /// variants take the model's spatial period off this before narrowing to the models' f32.
    pub fn to_local_xz_f64(&self, world: DVec2) -> DVec2 {
        let c = self.center.as_dvec2();
        let d = world - c;
        let l =
            DQuat::from_rotation_y(f64::from(self.yaw)).conjugate() * DVec3::new(d.x, 0.0, d.y) / f64::from(self.scale);
        DVec2::new(l.x, l.z) + c
    }

    /// A local height (m above rest) as a world height: the uniform scale applies to heights too.
    pub fn to_world_height(&self, local_height: f32) -> f32 {
        self.scale * local_height
    }

    /// Carries a mesh displaced in the local frame into the world, in place and in parallel:
    /// positions by the full map, normals by the rotation alone (a uniform scale keeps them).
    pub fn apply(&self, mesh: &mut SurfaceMesh) {
        self.apply_to(&mut mesh.positions, &mut mesh.normals);
    }

    /// [`WaterPlacement::apply`] on bare buffers: positions (m) by the full map, normals by the
    /// rotation alone, in place and in parallel.
    pub fn apply_to(&self, positions: &mut [Vec3], normals: &mut [Vec3]) {
        if self.is_identity() {
            return;
        }
        let (r, pivot, s) = (self.rotation(), self.pivot(), self.scale);
        positions.par_iter_mut().for_each(|p| *p = pivot + s * (r * (*p - pivot)));
        normals.par_iter_mut().for_each(|n| *n = r * *n);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::GridSpec;

    #[test]
    fn to_local_inverts_to_world_and_a_quarter_turn_swaps_axes() {
        let p = WaterPlacement::new(Vec2::new(5.0, -2.0), 90.0, 2.0).unwrap();
        // Ry(90 deg) carries +X to -Z (counter-clockwise seen from +Y).
        let w = p.to_world(Vec3::new(6.0, 0.5, -2.0));
        assert!((w - Vec3::new(5.0, 1.0, -4.0)).length() < 1e-5, "{w}");
        for q in [Vec2::new(1.0, 2.0), Vec2::new(-30.0, 7.5)] {
            let w = p.to_world(Vec3::new(q.x, 0.0, q.y));
            assert!((p.to_local_xz(Vec2::new(w.x, w.z)) - q).length() < 1e-4);
        }
    }

    #[test]
    fn placing_a_mesh_is_bit_identical_on_one_and_two_threads() {
        let p = WaterPlacement::new(Vec2::new(1.5, -0.5), 33.0, 1.7).unwrap();
        let run = |n: usize| {
            let mut m = SurfaceMesh::new(GridSpec::centered(Vec2::splat(9.0), 40, 40).unwrap());
            for (k, q) in m.positions.iter_mut().enumerate() {
                q.y = (k as f32 * 0.37).sin();
            }
            rayon::ThreadPoolBuilder::new().num_threads(n).build().unwrap().install(|| p.apply(&mut m));
            (m.positions, m.normals)
        };
        assert_eq!(run(1), run(2));
    }

    #[test]
    fn bad_values_name_their_key_and_identity_changes_nothing() {
        let e = WaterPlacement::new(Vec2::ZERO, 400.0, 1.0).unwrap_err();
        assert_eq!(e.to_string(), "water.yaw_deg = 400 is outside [-360, 360]");
        let e = WaterPlacement::new(Vec2::ZERO, 0.0, 0.0).unwrap_err();
        assert!(e.to_string().starts_with("water.uniform_scale = 0 is outside (0, "), "{e}");
        assert!(WaterPlacement::new(Vec2::ZERO, 0.0, f32::NAN).is_err());
        let p = WaterPlacement::new(Vec2::new(3.0, 4.0), 0.0, 1.0).unwrap();
        assert!(p.is_identity());
        let mut m = SurfaceMesh::new(GridSpec::centered(Vec2::splat(4.0), 2, 2).unwrap());
        let before = m.positions.clone();
        p.apply(&mut m);
        assert_eq!(m.positions, before);
    }
}
