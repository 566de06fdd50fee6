//! Mouse camera controls (paper 002 §3: left drag orbits, right drag zooms with the distance
//! clamped, plus wheel zoom and middle-drag pan), as pure functions on [`Camera`] so they are
//! tested without a window.
//!
//! Every control keeps the camera valid for [`Camera::validate`]: the eye never reaches the target
//! and never crosses the up axis (the polar angle stays within [`MIN_POLAR_RAD`] of either pole).

use std::f32::consts::PI;

use glam::{Quat, Vec3};
use swell::scene::Camera;

/// Orbit angle per point of mouse drag, radians (a drag across a 630-point view turns 2 pi).
pub const ORBIT_RAD_PER_POINT: f32 = 0.01;

/// Closest the view direction comes to the up axis when orbiting, radians (1 degree): at the pole
/// itself `up` would be parallel to the view direction and the look-at frame undefined.
pub const MIN_POLAR_RAD: f32 = PI / 180.0;

/// Zoom per point of right-button drag: dragging down by `d` points multiplies the distance by
/// `exp(d * ZOOM_PER_POINT)` (100 points double it).
pub const ZOOM_PER_POINT: f32 = std::f32::consts::LN_2 / 100.0;

/// Zoom per point of wheel scroll: scrolling up by `s` points divides the distance by
/// `exp(s * WHEEL_ZOOM_PER_POINT)` (one 50-point notch is about 10 %).
pub const WHEEL_ZOOM_PER_POINT: f32 = 0.002;

/// Nearest the eye may come to the target, as a fraction of the initial distance. Paper 002 clamps
/// its unit-sized pool scene to [0.5, 10] absolute units; swell scenes span metres to kilometres,
/// so the clamp is relative to the scene's own camera distance.
pub const MIN_DISTANCE_FACTOR: f32 = 0.5;

/// Farthest the eye may go from the target, as a multiple of the initial distance (see
/// [`MIN_DISTANCE_FACTOR`]).
pub const MAX_DISTANCE_FACTOR: f32 = 10.0;

/// Turns the eye about the target: `yaw` about the up axis, `pitch` towards the up axis (both in
/// radians; positive pitch raises the eye). The distance to the target is unchanged and the polar
/// angle is clamped to [`MIN_POLAR_RAD`, pi - `MIN_POLAR_RAD`].
pub fn orbit(camera: &Camera, yaw: f32, pitch: f32) -> Camera {
    let up = camera.up.normalize();
    let offset = camera.eye - camera.target;
    let distance = offset.length();
    let yawed = Quat::from_axis_angle(up, yaw) * offset;
    let polar = (yawed.dot(up) / distance).clamp(-1.0, 1.0).acos();
    let new_polar = (polar - pitch).clamp(MIN_POLAR_RAD, PI - MIN_POLAR_RAD);
    // Tilt in the plane of up and the offset; the axis is horizontal and perpendicular to both.
    let axis = up.cross(yawed).try_normalize().unwrap_or_else(|| up.any_orthonormal_vector());
    // A positive angle about up x offset turns the offset away from up (increases the polar angle).
    let tilted = Quat::from_axis_angle(axis, new_polar - polar) * yawed;
    Camera { eye: camera.target + tilted.normalize() * distance, ..*camera }
}

/// Moves the eye along the view ray so its distance to the target is multiplied by `factor`
/// (> 0), then clamped to `[min_distance, max_distance]`.
pub fn zoom(camera: &Camera, factor: f32, min_distance: f32, max_distance: f32) -> Camera {
    let offset = camera.eye - camera.target;
    let distance = offset.length();
    let new_distance = (distance * factor).clamp(min_distance, max_distance);
    Camera { eye: camera.target + offset * (new_distance / distance), ..*camera }
}

/// Slides eye and target together parallel to the image plane so that a point at the target's
/// depth follows the mouse: `dx`, `dy` are the drag in pixels (x right, y down) of a view
/// `view_height_px` pixels high.
pub fn pan(camera: &Camera, dx: f32, dy: f32, view_height_px: f32) -> Camera {
    let forward = camera.target - camera.eye;
    let distance = forward.length();
    let right = forward.cross(camera.up).normalize();
    let up = right.cross(forward).normalize();
    // Height of the view frustum at the target's depth, divided among the pixels.
    let metres_per_px = 2.0 * distance * (0.5 * camera.fov_y_deg.to_radians()).tan() / view_height_px.max(1.0);
    let shift = (-dx * right + dy * up) * metres_per_px;
    Camera { eye: camera.eye + shift, target: camera.target + shift, ..*camera }
}

/// The viewer's camera state: the scene's own camera to return to (`r`) and the zoom limits
/// derived from it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraRig {
    /// The camera `r` returns to.
    pub home: Camera,
    /// Closest allowed eye-target distance, metres.
    pub min_distance: f32,
    /// Farthest allowed eye-target distance, metres.
    pub max_distance: f32,
}

impl CameraRig {
    /// A rig whose home is `camera` and whose zoom limits are [`MIN_DISTANCE_FACTOR`] and
    /// [`MAX_DISTANCE_FACTOR`] times its distance.
    pub fn new(camera: Camera) -> Self {
        let d = (camera.eye - camera.target).length();
        Self { home: camera, min_distance: MIN_DISTANCE_FACTOR * d, max_distance: MAX_DISTANCE_FACTOR * d }
    }

    /// Left drag of (`dx`, `dy`) points: drag right turns the eye left about the target (the scene
    /// follows the mouse), drag down raises the eye.
    pub fn drag_orbit(&self, camera: &Camera, dx: f32, dy: f32) -> Camera {
        orbit(camera, -dx * ORBIT_RAD_PER_POINT, dy * ORBIT_RAD_PER_POINT)
    }

    /// Right drag of `dy` points: down moves away, up moves closer, within the limits.
    pub fn drag_zoom(&self, camera: &Camera, dy: f32) -> Camera {
        zoom(camera, (dy * ZOOM_PER_POINT).exp(), self.min_distance, self.max_distance)
    }

    /// Wheel scroll of `scroll_y` points: up (positive) moves closer, within the limits.
    pub fn wheel_zoom(&self, camera: &Camera, scroll_y: f32) -> Camera {
        zoom(camera, (-scroll_y * WHEEL_ZOOM_PER_POINT).exp(), self.min_distance, self.max_distance)
    }
}

/// Unit vector from the target to the eye, for tests and the camera panel's readout.
pub fn eye_direction(camera: &Camera) -> Vec3 {
    (camera.eye - camera.target).normalize()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sea_camera() -> Camera {
        swell::scene::preset("sea").unwrap().camera
    }

    fn assert_close(a: Vec3, b: Vec3, tol: f32) {
        assert!((a - b).length() <= tol, "{a:?} != {b:?}");
    }

    #[test]
    fn orbit_keeps_target_and_distance_and_stays_valid() {
        let c = sea_camera();
        let d0 = (c.eye - c.target).length();
        let mut cam = c;
        for k in 0..200 {
            // Large drags in every direction, including past both poles.
            cam = orbit(&cam, 0.3 * (k as f32).sin(), if k < 100 { 0.2 } else { -0.25 });
            assert_eq!(cam.target, c.target);
            assert!(((cam.eye - cam.target).length() - d0).abs() < 1e-3 * d0);
            cam.validate("camera").unwrap();
            let polar = eye_direction(&cam).dot(Vec3::Y).clamp(-1.0, 1.0).acos();
            assert!((MIN_POLAR_RAD - 1e-4..=PI - MIN_POLAR_RAD + 1e-4).contains(&polar), "polar {polar}");
        }
    }

    #[test]
    fn a_full_turn_of_yaw_returns_and_yaw_keeps_the_height() {
        let c = sea_camera();
        let quarter = orbit(&c, std::f32::consts::FRAC_PI_2, 0.0);
        assert!((quarter.eye.y - c.eye.y).abs() < 1e-3);
        // A quarter turn about +Y takes the offset (0, h, 60) to (60, h, 0) (right-handed).
        let off = quarter.eye - quarter.target;
        assert!(off.x > 59.0 && off.z.abs() < 1e-2, "{off:?}");
        let back = orbit(&c, 2.0 * PI, 0.0);
        assert_close(back.eye, c.eye, 1e-3);
    }

    #[test]
    fn pitch_moves_the_eye_towards_the_pole() {
        let c = sea_camera();
        let up = orbit(&c, 0.0, 0.1);
        assert!(up.eye.y > c.eye.y);
        let down = orbit(&c, 0.0, -0.1);
        assert!(down.eye.y < c.eye.y);
        // Pitch undoes itself when no clamp is hit.
        assert_close(orbit(&up, 0.0, -0.1).eye, c.eye, 1e-3);
    }

    #[test]
    fn zoom_scales_the_distance_and_clamps_it() {
        let c = sea_camera();
        let rig = CameraRig::new(c);
        let d0 = (c.eye - c.target).length();
        let closer = zoom(&c, 0.8, rig.min_distance, rig.max_distance);
        assert!(((closer.eye - closer.target).length() - 0.8 * d0).abs() < 1e-3);
        assert_close(eye_direction(&closer), eye_direction(&c), 1e-5);
        let mut cam = c;
        for _ in 0..100 {
            cam = rig.drag_zoom(&cam, 50.0);
        }
        assert!(((cam.eye - cam.target).length() - MAX_DISTANCE_FACTOR * d0).abs() < 1e-2);
        for _ in 0..100 {
            cam = rig.wheel_zoom(&cam, 120.0);
        }
        assert!(((cam.eye - cam.target).length() - MIN_DISTANCE_FACTOR * d0).abs() < 1e-3);
        cam.validate("camera").unwrap();
    }

    #[test]
    fn pan_moves_the_target_point_with_the_mouse() {
        let c = sea_camera();
        let (w, h) = (1280.0, 720.0);
        let moved = pan(&c, 100.0, -40.0, h);
        // Eye and target move by the same vector, parallel to the image plane.
        let shift = moved.target - c.target;
        assert_close(moved.eye - c.eye, shift, 1e-4);
        assert!(shift.dot((c.target - c.eye).normalize()).abs() < 1e-3);
        // The old target, seen from the new camera, sits 100 px right and 40 px up of the centre.
        let clip = moved.clip_from_world(w / h) * c.target.extend(1.0);
        let ndc = clip.truncate() / clip.w;
        let px = (ndc.x * 0.5 * w, -ndc.y * 0.5 * h);
        assert!((px.0 - 100.0).abs() < 0.05 && (px.1 + 40.0).abs() < 0.05, "{px:?}");
    }

    #[test]
    fn drag_directions_follow_the_mouse() {
        let c = sea_camera();
        let rig = CameraRig::new(c);
        // Dragging right turns the eye to the left of where it looked: towards -x from +z.
        assert!(rig.drag_orbit(&c, 50.0, 0.0).eye.x < c.eye.x);
        assert!(rig.drag_orbit(&c, 0.0, 50.0).eye.y > c.eye.y);
        let d = |cam: &Camera| (cam.eye - cam.target).length();
        assert!(d(&rig.drag_zoom(&c, 20.0)) > d(&c));
        assert!(d(&rig.wheel_zoom(&c, 20.0)) < d(&c));
    }
}
