//! The far land of a [`super::TerrainBody`] in the world: the rings of [`far_land`] placed by the
//! terrain's transform (the seam vertices go through the very same arithmetic as the field's, so
//! they stay bit-identical), and its skyline, the outermost ring's distance and height by azimuth,
//! which the renderer continues to the horizon.

use glam::{Vec2, Vec3};

use crate::error::Result;
use crate::math::Transform;
use crate::terrain::{far_land, FarLandParams, HeightField};

/// Azimuth samples of the skyline (about half a degree each).
const SKYLINE_BINS: usize = 720;

/// The land beyond the terrain's field, in world space.
#[derive(Clone, Debug)]
pub struct FarLand {
    /// World positions, metres; the first ones are the field's border vertices, equal bit for bit
    /// to the terrain mesh's.
    pub positions: Vec<Vec3>,
    /// Unit world normals, one per position.
    pub normals: Vec<Vec3>,
    /// Three indices per triangle, counter-clockwise seen from above.
    pub indices: Vec<u32>,
    /// World (x, z) the skyline's azimuths are measured around: the field's centre.
    centre: Vec2,
    /// Per azimuth bin (bin b faces [`from_diamond`]`(4 b / SKYLINE_BINS)` in (x, z)): horizontal
    /// distance (m) from `centre` to the outermost ring, and the ring's height (m) there.
    skyline: Vec<(f32, f32)>,
    /// Highest skyline height (m) and nearest skyline distance (m) from `centre`: a ray that
    /// rises over the one at the other is over the whole skyline (the renderer's early out).
    highest: f32,
    nearest: f32,
}

impl FarLand {
    /// Builds the far land of `field` with `params`, placed by `transform` (the terrain's).
    pub fn new(field: &HeightField, params: &FarLandParams, transform: &Transform) -> Result<Self> {
        let mesh = far_land(field, params)?;
        let world_from_model = transform.world_from_model();
        let normal_matrix = transform.world_from_model_normals();
        // The same per-vertex operations as TerrainBody's mesh, so shared vertices coincide.
        let positions: Vec<Vec3> = mesh.positions.iter().map(|&p| world_from_model.transform_point3(p)).collect();
        let normals = mesh.normals.iter().map(|&n| (normal_matrix * n).normalize_or(Vec3::Y)).collect();
        let c = world_from_model.transform_point3(Vec3::ZERO);
        let centre = Vec2::new(c.x, c.z);
        let skyline = skyline(centre, &positions[mesh.outer_start..]);
        let highest = skyline.iter().map(|s| s.1).fold(f32::NEG_INFINITY, f32::max);
        let nearest = skyline.iter().map(|s| s.0).fold(f32::INFINITY, f32::min);
        Ok(Self { positions, normals, indices: mesh.indices, centre, skyline, highest, nearest })
    }

    /// Whether every ray from `eye` whose slope (rise per horizontal metre) is `slope` or more
    /// passes over the whole skyline, so never meets the land beyond the rings: true when it is
    /// already over the highest skyline height at the nearest skyline distance (from the eye).
    pub fn passes_over(&self, eye: Vec3, slope: f32) -> bool {
        let nearest = (self.nearest - (Vec2::new(eye.x, eye.z) - self.centre).length()).max(0.0);
        slope >= 0.0 && eye.y + slope * nearest > self.highest
    }

    /// The outermost ring seen from `from` (world x, z) along the horizontal direction `dir`
    /// (any length): its horizontal distance (m, >= 0) from `from` and its height (m), linear
    /// between the skyline's half-degree samples. Measured around the field's centre, which for
    /// the distances the rings reach differs little from the eye.
    pub fn skyline_at(&self, from: Vec2, dir: Vec2) -> (f32, f32) {
        let bins = self.skyline.len();
        if bins == 0 {
            return (0.0, 0.0);
        }
        let u = dir.normalize_or(Vec2::X);
        let at = diamond(u) * (bins as f32 / 4.0);
        let b = (at as usize).min(bins - 1);
        let t = (at - b as f32).clamp(0.0, 1.0);
        let (d0, h0) = self.skyline[b];
        let (d1, h1) = self.skyline[(b + 1) % bins];
        let distance = d0 + (d1 - d0) * t - (from - self.centre).dot(u);
        (distance.max(0.0), h0 + (h1 - h0) * t)
    }
}

/// For each azimuth bin around `centre`, the nearest crossing of the closed loop `outer`
/// (world positions) by the horizontal ray from `centre`: distance and interpolated height.
fn skyline(centre: Vec2, outer: &[Vec3]) -> Vec<(f32, f32)> {
    let xz = |p: Vec3| Vec2::new(p.x, p.z);
    let farthest = outer.iter().map(|&p| (xz(p) - centre).length()).fold(0.0, f32::max);
    let mean = outer.iter().map(|p| p.y).sum::<f32>() / outer.len().max(1) as f32;
    (0..SKYLINE_BINS)
        .map(|b| {
            let u = from_diamond(4.0 * b as f32 / SKYLINE_BINS as f32);
            let mut best: Option<(f32, f32)> = None;
            for k in 0..outer.len() {
                let (p, q) = (outer[k], outer[(k + 1) % outer.len()]);
                let (a, e) = (xz(p) - centre, xz(q) - xz(p));
                // centre + t u = p + s e: solve by cross products (Cramer).
                let den = u.perp_dot(e);
                if den.abs() < 1e-12 {
                    continue;
                }
                let (t, s) = (a.perp_dot(e) / den, a.perp_dot(u) / den);
                if t > 0.0 && (0.0..=1.0).contains(&s) && best.is_none_or(|(d, _)| t < d) {
                    best = Some((t, p.y + (q.y - p.y) * s));
                }
            }
            // A loop the ray misses (a transform that folds the rings edge-on): the farthest
            // distance and the mean height, still finite.
            best.unwrap_or((farthest, mean))
        })
        .collect()
}

/// The "diamond angle" of a unit (or any non-zero) direction: a monotonic stand-in for its
/// azimuth in [0, 4), a quarter turn per unit, that needs one division instead of an arctangent
/// (the skyline is looked up per pixel).
fn diamond(u: Vec2) -> f32 {
    let (x, y) = (u.x, u.y);
    let p = if y >= 0.0 {
        if x >= 0.0 {
            y / (x + y)
        } else {
            1.0 - x / (-x + y)
        }
    } else if x < 0.0 {
        2.0 - y / (-x - y)
    } else {
        3.0 + x / (x - y)
    };
    if p.is_finite() {
        p.rem_euclid(4.0)
    } else {
        0.0
    }
}

/// The unit direction whose [`diamond`] angle is `p` in [0, 4).
fn from_diamond(p: f32) -> Vec2 {
    let (quarter, f) = (p.floor(), p - p.floor());
    let v = match quarter as i32 {
        0 => Vec2::new(1.0 - f, f),
        1 => Vec2::new(-f, 1.0 - f),
        2 => Vec2::new(f - 1.0, -f),
        _ => Vec2::new(f, f - 1.0),
    };
    v.normalize_or(Vec2::X)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_skyline_is_the_outer_ring() {
        let field = HeightField::from_fn(9, 9, Vec2::splat(100.0), |x, _| x * 0.1).unwrap();
        let params = FarLandParams { reach: 1000.0, relief: 0.0, ..Default::default() };
        let t = Transform { translate: Vec3::new(30.0, 2.0, -10.0), ..Transform::IDENTITY };
        let land = FarLand::new(&field, &params, &t).unwrap();
        // East (+X): the ring is 1050 m out; its height continues the east edge (5 m) + 2 m.
        let (d, h) = land.skyline_at(Vec2::new(30.0, -10.0), Vec2::X);
        assert!((d - 1050.0).abs() < 0.5 && (h - 7.0).abs() < 1e-3, "{d} {h}");
        let (d, h) = land.skyline_at(Vec2::new(30.0, -10.0), -Vec2::X);
        assert!((d - 1050.0).abs() < 0.5 && (h + 3.0).abs() < 1e-3, "{d} {h}");
        // From 50 m east of the centre, looking east, the ring is 50 m nearer.
        let (d, _) = land.skyline_at(Vec2::new(80.0, -10.0), Vec2::X);
        assert!((d - 1000.0).abs() < 0.5, "{d}");
        // A diagonal reaches the corner region, farther than either side.
        let (d, _) = land.skyline_at(Vec2::new(30.0, -10.0), Vec2::ONE);
        assert!(d > 1050.0 * 1.3, "{d}");
        // Rising over the highest point at the nearest distance: over the whole skyline.
        assert!(land.passes_over(Vec3::new(30.0, 10.0, -10.0), 0.01));
        assert!(!land.passes_over(Vec3::new(30.0, 10.0, -10.0), -0.001));
        assert!(!land.passes_over(Vec3::new(30.0, -20.0, -10.0), 0.01));
    }

    #[test]
    fn the_diamond_angle_is_monotonic_and_inverts() {
        let mut last = -1.0;
        for k in 0..3600 {
            let a = (k as f32 / 10.0).to_radians();
            let p = diamond(Vec2::from_angle(a));
            assert!(p > last && (0.0..4.0).contains(&p), "{k}: {p}");
            assert!((from_diamond(p) - Vec2::from_angle(a)).length() < 1e-4, "{k}");
            last = p;
        }
        assert_eq!(diamond(Vec2::ZERO), 0.0);
    }
}
