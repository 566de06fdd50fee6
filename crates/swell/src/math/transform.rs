//! Per-object placement: translate, rotate about X, Y and Z, and scale (papers 000 and 001, whose
//! GUIs move, turn and scale the sea and the landscape).

use glam::{EulerRot, Mat3, Mat4, Quat, Vec3};
use serde::{Deserialize, Serialize};

use crate::error::{check_finite_vec, check_range, Error, Result};

/// Largest scale factor along one axis; beyond it a 4097-vertex terrain overflows nothing, but
/// nothing useful needs more.
pub const MAX_SCALE: f32 = 1.0e4;

/// Where an object sits in the world. In a scene file: `[terrain.transform]`.
///
/// `world_from_model = T(translate) * Rz * Ry * Rx * S(scale)`: the object is scaled in its own
/// frame, then rotated about X, then Y, then Z (fixed world axes, right-handed, positive angles
/// counter-clockwise looking down the axis), then moved.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Transform {
    /// Offset in world metres. Default (0, 0, 0).
    pub translate: Vec3,
    /// Rotations about the X, Y and Z axes in degrees, each in [-360, 360]. Default (0, 0, 0).
    pub rotate_deg: Vec3,
    /// Scale factor along the model's X, Y and Z axes, each in (0, [`MAX_SCALE`]]. Default (1, 1, 1).
    pub scale: Vec3,
}

impl Default for Transform {
    fn default() -> Self {
        Self::IDENTITY
    }
}

impl Transform {
    /// No change.
    pub const IDENTITY: Self = Self { translate: Vec3::ZERO, rotate_deg: Vec3::ZERO, scale: Vec3::ONE };

    /// Checks every field, naming keys under `key` (e.g. `terrain.transform`).
    pub fn validate(&self, key: &str) -> Result<()> {
        check_finite_vec(&format!("{key}.translate"), &self.translate.to_array())?;
        for (i, a) in self.rotate_deg.to_array().into_iter().enumerate() {
            check_range(&format!("{key}.rotate_deg[{i}]"), a, -360.0, 360.0)?;
        }
        for (i, s) in self.scale.to_array().into_iter().enumerate() {
            if !(s.is_finite() && s > 0.0 && s <= MAX_SCALE) {
                return Err(Error::out_of_range(format!("{key}.scale[{i}]"), s, format!("(0, {MAX_SCALE}]")));
            }
        }
        Ok(())
    }

    /// The rotation alone, `Rz * Ry * Rx`.
    pub fn rotation(&self) -> Quat {
        let r = self.rotate_deg * (std::f32::consts::PI / 180.0);
        // Extrinsic X then Y then Z equals intrinsic Z-Y-X: glam's ZYX takes the angles in that order.
        Quat::from_euler(EulerRot::ZYX, r.z, r.y, r.x)
    }

    /// The model-to-world matrix `T * R * S`.
    pub fn world_from_model(&self) -> Mat4 {
        Mat4::from_scale_rotation_translation(self.scale, self.rotation(), self.translate)
    }

    /// The world-to-model matrix, the exact inverse of [`Transform::world_from_model`]
    /// (`S^-1 * R^T * T^-1`, built directly rather than by a general 4x4 inversion).
    pub fn model_from_world(&self) -> Mat4 {
        Mat4::from_scale(self.scale.recip())
            * Mat4::from_quat(self.rotation().conjugate())
            * Mat4::from_translation(-self.translate)
    }

    /// The matrix that carries model normals to world normals: the inverse transpose of the linear
    /// part, `R * S^-1` (normals must be re-normalised after it when the scale is not uniform).
    pub fn world_from_model_normals(&self) -> Mat3 {
        Mat3::from_quat(self.rotation()) * Mat3::from_diagonal(self.scale.recip())
    }

    /// Whether vertical lines stay vertical (no rotation about X or Z), so that a height field
    /// stays a height field in the world.
    pub fn keeps_up(&self) -> bool {
        self.rotate_deg.x.rem_euclid(360.0) == 0.0 && self.rotate_deg.z.rem_euclid(360.0) == 0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample() -> Transform {
        Transform {
            translate: Vec3::new(3.0, -2.0, 7.5),
            rotate_deg: Vec3::new(20.0, -35.0, 110.0),
            scale: Vec3::new(2.0, 0.5, 3.0),
        }
    }

    #[test]
    fn world_from_model_and_model_from_world_invert_each_other() {
        let t = sample();
        let round = t.model_from_world() * t.world_from_model();
        assert!(round.abs_diff_eq(Mat4::IDENTITY, 1e-5), "{round}");
        let p = Vec3::new(1.5, -4.0, 0.25);
        let back = t.model_from_world().transform_point3(t.world_from_model().transform_point3(p));
        assert!((back - p).length() < 1e-5);
    }

    #[test]
    fn steps_compose_in_the_documented_order() {
        // Scale then rotate 90 degrees about Y then translate: model +X (scaled by 2) ends on world -Z.
        let t = Transform {
            translate: Vec3::new(10.0, 0.0, 0.0),
            rotate_deg: Vec3::new(0.0, 90.0, 0.0),
            scale: Vec3::new(2.0, 1.0, 1.0),
        };
        let p = t.world_from_model().transform_point3(Vec3::X);
        assert!((p - Vec3::new(10.0, 0.0, -2.0)).length() < 1e-5, "{p}");
        // Rotation about X happens before rotation about Z: +Y -> (X by 90) +Z -> (Z by 90) +Z.
        let t = Transform { rotate_deg: Vec3::new(90.0, 0.0, 90.0), ..Transform::IDENTITY };
        let p = t.world_from_model().transform_point3(Vec3::Y);
        assert!((p - Vec3::Z).length() < 1e-5, "{p}");
        // Composition of two transforms is the product of their matrices.
        let (a, b) = (sample(), t);
        let q = Vec3::new(0.3, 1.0, -2.0);
        let chained = a.world_from_model().transform_point3(b.world_from_model().transform_point3(q));
        let product = (a.world_from_model() * b.world_from_model()).transform_point3(q);
        assert!((chained - product).length() < 1e-4);
    }

    #[test]
    fn normals_stay_perpendicular_to_transformed_surfaces() {
        let t = sample();
        let (u, v) = (Vec3::new(1.0, 0.3, 0.0), Vec3::new(0.0, -0.2, 1.0));
        let n = v.cross(u);
        let m = t.world_from_model();
        let nw = t.world_from_model_normals() * n;
        assert!(nw.dot(m.transform_vector3(u)).abs() < 1e-5);
        assert!(nw.dot(m.transform_vector3(v)).abs() < 1e-5);
    }

    #[test]
    fn bad_values_name_the_key() {
        let t = Transform { scale: Vec3::new(1.0, 0.0, 1.0), ..Transform::IDENTITY };
        assert_eq!(
            t.validate("terrain.transform").unwrap_err().to_string(),
            "terrain.transform.scale[1] = 0 is outside (0, 10000]"
        );
        let t = Transform { rotate_deg: Vec3::new(0.0, 400.0, 0.0), ..Transform::IDENTITY };
        assert!(t.validate("x").unwrap_err().to_string().starts_with("x.rotate_deg[1] = 400"));
    }
}
