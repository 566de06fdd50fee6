//! The pinhole camera: OpenGL look-at and perspective.

use glam::{Mat4, Vec3};
use serde::{Deserialize, Serialize};

use crate::error::{check_finite_vec, check_positive, check_range, Error, Result};

/// A perspective camera as OpenGL defines it: view space looks down −Z, clip z in [−w, w].
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Camera {
    /// Position of the eye, world metres.
    pub eye: Vec3,
    /// Point looked at, world metres; must differ from `eye`.
    pub target: Vec3,
    /// Up direction (world); not parallel to the view direction. Default +Y.
    #[serde(default = "default_up")]
    pub up: Vec3,
    /// Vertical field of view in degrees, in (0, 179]. Default 45.
    #[serde(default = "default_fov")]
    pub fov_y_deg: f32,
    /// Near clipping distance in metres, > 0. Default 0.1.
    #[serde(default = "default_near")]
    pub near: f32,
    /// Far clipping distance in metres, > `near`. Default 5000.
    #[serde(default = "default_far")]
    pub far: f32,
}

/// The camera of a scene without `[camera]`: 25 m up and 60 m back (+Z) from the origin, looking at
/// it, with the other keys at their defaults. Enough to see a sea patch of a few hundred metres.
impl Default for Camera {
    fn default() -> Self {
        Self {
            eye: Vec3::new(0.0, 25.0, 60.0),
            target: Vec3::ZERO,
            up: default_up(),
            fov_y_deg: default_fov(),
            near: default_near(),
            far: default_far(),
        }
    }
}

fn default_up() -> Vec3 {
    Vec3::Y
}
fn default_fov() -> f32 {
    45.0
}
fn default_near() -> f32 {
    0.1
}
fn default_far() -> f32 {
    5000.0
}

impl Camera {
    /// Checks the camera, naming keys under `key` (normally `camera`).
    pub fn validate(&self, key: &str) -> Result<()> {
        check_finite_vec(&format!("{key}.eye"), &self.eye.to_array())?;
        check_finite_vec(&format!("{key}.target"), &self.target.to_array())?;
        check_finite_vec(&format!("{key}.up"), &self.up.to_array())?;
        check_range(&format!("{key}.fov_y_deg"), self.fov_y_deg, 1e-3, 179.0)?;
        check_positive(&format!("{key}.near"), self.near)?;
        if !(self.far.is_finite() && self.far > self.near) {
            return Err(Error::out_of_range(
                format!("{key}.far"),
                self.far,
                format!("({}, inf) (greater than near)", self.near),
            ));
        }
        let forward = self.target - self.eye;
        // Each finite, but so far apart that the distance overflows f32: the view would be NaN.
        if !forward.length().is_finite() {
            return Err(Error::invalid(format!("{key}.target"), "is too far from camera.eye (distance overflows f32)"));
        }
        if forward.length() < 1e-6 {
            return Err(Error::invalid(format!("{key}.target"), "must differ from camera.eye"));
        }
        if forward.normalize().cross(self.up).length() < 1e-6 {
            return Err(Error::invalid(
                format!("{key}.up"),
                format!("{:?} is parallel to the view direction", self.up.to_array()),
            ));
        }
        Ok(())
    }

    /// World to view transform (OpenGL `lookAt`).
    pub fn view_from_world(&self) -> Mat4 {
        glam::camera::rh::view::look_at_mat4(self.eye, self.target, self.up)
    }

    /// View to clip transform (OpenGL `gluPerspective`) for an image of `aspect` = width / height.
    pub fn clip_from_view(&self, aspect: f32) -> Mat4 {
        gl_perspective(self.fov_y_deg.to_radians(), aspect, self.near, self.far)
    }

    /// World to clip transform.
    pub fn clip_from_world(&self, aspect: f32) -> Mat4 {
        self.clip_from_view(aspect) * self.view_from_world()
    }

    /// Angle (radians) one pixel row spans in an image of `rows` pixel rows (the supersampled
    /// count when supersampling; at least 1 is taken): what a pixel's footprint at a distance is
    /// made of.
    pub fn pixel_angle(&self, rows: u32) -> f32 {
        2.0 * (0.5 * self.fov_y_deg.to_radians()).tan() / rows.max(1) as f32
    }
}

/// `gluPerspective`: view to clip for a vertical field of view `fov_y` (radians, in (0, π)),
/// `aspect` = width / height (> 0) and clip distances 0 < `near` < `far` (metres); clip z in [−w, w].
///
/// Written out rather than taken from `glam::camera::rh::proj::opengl::perspective` because that
/// one computes cot(fov/2) as cos/sin and the depth terms in another order: the same matrix up to
/// rounding, but not bit for bit the one glam 0.29's `Mat4::perspective_rh_gl` gave, and renders,
/// bakes and their golden files are compared byte for byte across versions. This is that formula.
fn gl_perspective(fov_y: f32, aspect: f32, near: f32, far: f32) -> Mat4 {
    let inv_length = 1.0 / (near - far);
    let f = 1.0 / (0.5 * fov_y).tan();
    Mat4::from_cols(
        glam::Vec4::new(f / aspect, 0.0, 0.0, 0.0),
        glam::Vec4::new(0.0, f, 0.0, 0.0),
        glam::Vec4::new(0.0, 0.0, (near + far) * inv_length, -1.0),
        glam::Vec4::new(0.0, 0.0, (2.0 * near * far) * inv_length, 0.0),
    )
}
