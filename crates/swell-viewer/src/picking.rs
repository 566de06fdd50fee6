//! From a click in the view to a point on the water: the click's ray through the camera, cut with
//! the water's rest plane y = 0.
//!
//! The rest plane, not the displaced mesh: a disturbance is placed by rest position (that is how
//! every model indexes its surface), and the two differ by at most the wave height, which at the
//! spring mesh's grazing views is well under one dent radius.

use glam::{Vec2, Vec3, Vec4};
use swell::scene::Camera;

/// The world (x, z) on y = 0 under the pixel (`px`, `py`) (from the top-left corner, pixel centres
/// at +0.5) of a `width` x `height` view, or `None` if the ray misses the plane (it points at or
/// above the horizon, or the view is empty).
pub fn water_point(camera: &Camera, width: f32, height: f32, px: f32, py: f32) -> Option<Vec2> {
    if !(width >= 1.0 && height >= 1.0 && px.is_finite() && py.is_finite()) {
        return None;
    }
    // The same pixel-to-NDC mapping as the renderer's sky pass (row 0 at the top).
    let ndc_x = 2.0 * px / width - 1.0;
    let ndc_y = 1.0 - 2.0 * py / height;
    let world_from_clip = camera.clip_from_world(width / height).inverse();
    let p = world_from_clip * Vec4::new(ndc_x, ndc_y, 0.5, 1.0);
    if p.w.abs() < f32::EPSILON {
        return None;
    }
    let dir: Vec3 = p.truncate() / p.w - camera.eye;
    // Only rays going down reach the water in front of the camera (the eye is above it).
    if dir.y.is_nan() || dir.y >= 0.0 || camera.eye.y <= 0.0 {
        return None;
    }
    let s = -camera.eye.y / dir.y;
    let hit = camera.eye + dir * s;
    hit.is_finite().then(|| Vec2::new(hit.x, hit.z))
}

#[cfg(test)]
mod tests {
    use glam::Mat4;

    use super::*;

    fn camera() -> Camera {
        let mut c = swell::scene::preset("springs").unwrap().camera;
        c.eye = Vec3::new(3.0, 9.0, 30.0);
        c
    }

    /// The pixel where the renderer's projection puts world point `p`.
    fn project(c: &Camera, w: f32, h: f32, p: Vec3) -> (f32, f32) {
        let clip: Mat4 = c.clip_from_world(w / h);
        let q = clip * p.extend(1.0);
        let ndc = q.truncate() / q.w;
        ((ndc.x + 1.0) * 0.5 * w, (1.0 - ndc.y) * 0.5 * h)
    }

    #[test]
    fn a_projected_water_point_picks_back_to_itself() {
        let c = camera();
        for (x, z) in [(0.0, 0.0), (5.0, -7.0), (-12.0, 10.0), (15.5, 3.25)] {
            let (px, py) = project(&c, 1280.0, 720.0, Vec3::new(x, 0.0, z));
            let hit = water_point(&c, 1280.0, 720.0, px, py).unwrap();
            assert!((hit - Vec2::new(x, z)).length() < 1e-3 * (1.0 + x.abs() + z.abs()), "{hit} vs ({x}, {z})");
        }
        // The view's centre looks at the target's line of sight; the top rows see the sky.
        let centre = water_point(&c, 1280.0, 720.0, 640.0, 360.0).unwrap();
        let to_target = (c.target - c.eye).normalize();
        let to_hit = (Vec3::new(centre.x, 0.0, centre.y) - c.eye).normalize();
        assert!(to_hit.dot(to_target) > 0.9999);
        assert_eq!(water_point(&c, 1280.0, 720.0, 640.0, 0.0), None);
        assert_eq!(water_point(&c, 0.0, 720.0, 0.0, 0.0), None);
        assert_eq!(water_point(&c, 1280.0, 720.0, f32::NAN, 0.0), None);
        let mut under = c;
        under.eye.y = -1.0;
        under.target.y = -5.0;
        assert_eq!(water_point(&under, 1280.0, 720.0, 640.0, 700.0), None);
    }
}
