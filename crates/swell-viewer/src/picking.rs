//! From a click in the view to a point on the water: the click's ray through the camera, cut with
//! the water's rest plane y = 0 ([`water_point`]) or with the drawn surface ([`surface_point`]).
//!
//! The rest plane, not the displaced mesh, for a disturbance: it is placed by rest position (that
//! is how every model indexes its surface), and the two differ by at most the wave height, which
//! at the spring mesh's grazing views is well under one dent radius. A dropped body is placed on
//! the surface the ray meets first instead: on a rough sea seen at a low angle the rest plane lies
//! metres behind the crest under the pointer.

use glam::{Vec2, Vec3, Vec4};
use swell::scene::Camera;

/// A ray from the eye: points `origin + s direction` for s >= 0 (`direction` not normalised).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    /// Where it starts (the camera's eye), world m.
    pub origin: Vec3,
    /// Its direction, world; finite and non-zero.
    pub direction: Vec3,
}

impl Ray {
    /// The point at parameter `s`.
    pub fn at(&self, s: f32) -> Vec3 {
        self.origin + self.direction * s
    }

    /// Where the ray meets the plane y = `height`, if it goes towards it (not along it or away).
    pub fn plane_hit(&self, height: f32) -> Option<Vec3> {
        let s = (height - self.origin.y) / self.direction.y;
        (s.is_finite() && s >= 0.0).then(|| self.at(s)).filter(|p| p.is_finite())
    }
}

/// The ray through the pixel (`px`, `py`) (from the top-left corner, pixel centres at +0.5) of a
/// `width` x `height` view, or `None` for an empty view or a point that is not finite.
pub fn view_ray(camera: &Camera, width: f32, height: f32, px: f32, py: f32) -> Option<Ray> {
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
    let direction: Vec3 = p.truncate() / p.w - camera.eye;
    (direction.is_finite() && direction != Vec3::ZERO).then_some(Ray { origin: camera.eye, direction })
}

/// The world (x, z) on y = 0 under the pixel (`px`, `py`) (from the top-left corner, pixel centres
/// at +0.5) of a `width` x `height` view, or `None` if the ray misses the plane (it points at or
/// above the horizon, or the view is empty).
pub fn water_point(camera: &Camera, width: f32, height: f32, px: f32, py: f32) -> Option<Vec2> {
    let ray = view_ray(camera, width, height, px, py)?;
    // Only rays going down reach the water in front of the camera (the eye is above it).
    if ray.direction.y >= 0.0 || camera.eye.y <= 0.0 {
        return None;
    }
    ray.plane_hit(0.0).map(|hit| Vec2::new(hit.x, hit.z))
}

/// How far above and below y = 0 (m) [`surface_point`] looks for the surface along a ray: more
/// than any crest or trough the models make (the stormiest FFT sea's are about 10 m), and a bound
/// on the search, which samples the ray only between these heights.
pub const SURFACE_SEARCH_HEIGHT_M: f32 = 30.0;

/// Samples of the ray between the search heights: at a grazing 3° the samples are 20 m apart, a
/// crest narrower than that may be stepped over (the ray then meets the surface behind it).
const SURFACE_SEARCH_SAMPLES: u32 = 512;

/// The first point where `ray` goes below the surface `height(x, z)` (the drawn water, or the
/// ground where it is higher; `None` where there is neither, counted as y = 0), found by stepping
/// the ray between ±[`SURFACE_SEARCH_HEIGHT_M`] and bisecting the first step that crosses.
/// `None` if the ray does not go down; the rest-plane hit if it never crosses (a surface that
/// stays above or below every sample).
pub fn surface_point(ray: &Ray, height: impl Fn(f32, f32) -> Option<f32>) -> Option<Vec3> {
    if ray.direction.y.is_nan() || ray.direction.y >= 0.0 {
        return None;
    }
    let plane = ray.plane_hit(0.0)?;
    let above = |s: f32| {
        let p = ray.at(s);
        p.y - height(p.x, p.z).filter(|h| h.is_finite()).unwrap_or(0.0)
    };
    // The stretch of the ray between the search heights (from the eye, if it is below the top).
    let s_of = |y: f32| ((y - ray.origin.y) / ray.direction.y).max(0.0);
    let (start, end) = (s_of(SURFACE_SEARCH_HEIGHT_M), s_of(-SURFACE_SEARCH_HEIGHT_M));
    if end <= start || above(start) <= 0.0 {
        // The eye is under the search band or under the surface: the plane is all there is.
        return Some(plane);
    }
    let step = (end - start) / SURFACE_SEARCH_SAMPLES as f32;
    let mut lo = start;
    for k in 1..=SURFACE_SEARCH_SAMPLES {
        let hi = start + step * k as f32;
        if above(hi) <= 0.0 {
            let (mut a, mut b) = (lo, hi);
            for _ in 0..30 {
                let m = 0.5 * (a + b);
                if above(m) > 0.0 {
                    a = m;
                } else {
                    b = m;
                }
            }
            let p = ray.at(0.5 * (a + b));
            return Some(if p.is_finite() { p } else { plane });
        }
        lo = hi;
    }
    Some(plane)
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

    #[test]
    fn a_ray_meets_the_first_crest_it_passes_under_not_the_rest_plane() {
        let c = camera();
        let ray = view_ray(&c, 1280.0, 720.0, 640.0, 500.0).unwrap();
        // Flat water: the surface point is the rest-plane point.
        let flat = surface_point(&ray, |_, _| Some(0.0)).unwrap();
        let plane = water_point(&c, 1280.0, 720.0, 640.0, 500.0).unwrap();
        assert!((Vec2::new(flat.x, flat.z) - plane).length() < 1e-3 && flat.y.abs() < 1e-4, "{flat} vs {plane}");
        // Waves 1 m high along z: the point found is on the surface, and no sample of the ray
        // before it is under the water (it is the first crossing).
        let wave = |_: f32, z: f32| Some((0.7 * z).sin());
        let p = surface_point(&ray, wave).unwrap();
        assert!((p.y - wave(p.x, p.z).unwrap()).abs() < 1e-3, "{p}");
        let s_hit = (p - ray.origin).length() / ray.direction.length();
        for k in 0..1000 {
            let q = ray.at(s_hit * k as f32 / 1000.0);
            assert!(q.y > wave(q.x, q.z).unwrap() - 1e-3, "the ray was under the water at {q} before {p}");
        }
        // Ground rising out of the water 5 m before the rest-plane point (a beach) is met where
        // it rises to the ray, in front of that point.
        let d = (plane - Vec2::new(c.eye.x, c.eye.z)).normalize();
        let foot = plane - 5.0 * d;
        let beach = |x: f32, z: f32| Some(((Vec2::new(x, z) - foot).dot(d) * 0.5).max(0.0));
        let p = surface_point(&ray, beach).unwrap();
        assert!(p.y > 0.1 && (p.y - beach(p.x, p.z).unwrap()).abs() < 1e-3, "{p}");
        assert!((Vec2::new(p.x, p.z) - foot).dot(d) < 5.0, "{p} not in front of the plane point {plane}");
        // Rays up into the sky find nothing; a surface it never crosses gives the plane point.
        let up = view_ray(&c, 1280.0, 720.0, 640.0, 0.0).unwrap();
        assert_eq!(surface_point(&up, |_, _| Some(0.0)), None);
        let never = surface_point(&ray, |_, _| Some(-100.0)).unwrap();
        assert!((Vec2::new(never.x, never.z) - plane).length() < 1e-3);
        assert_eq!(view_ray(&c, 0.0, 720.0, 1.0, 1.0), None);
    }
}
