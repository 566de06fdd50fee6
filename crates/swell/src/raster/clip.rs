//! Homogeneous clipping (Sutherland-Hodgman in clip space, before the divide by w).
//!
//! Triangles are clipped against the near and far planes, which is required for correctness
//! (points behind the eye have w <= 0), and against a guard band |x|, |y| <= GUARD_BAND w, which
//! only keeps fixed-point screen coordinates in range: between the viewport and the guard band the
//! rasterizer's bounding box does the clipping for free.

use glam::Vec4;

use super::{ClipVertex, Varying};

/// Half-width of the guard band in NDC units (the viewport is 1).
pub const GUARD_BAND: f32 = 8.0;

/// Most vertices a triangle can have after clipping against the six planes.
pub const MAX_CLIPPED: usize = 9;

/// Plane equations `dot(plane, p) >= 0` for the inside of each clip plane.
const PLANES: [Vec4; 6] = [
    Vec4::new(0.0, 0.0, 1.0, 1.0),         // near: z >= -w
    Vec4::new(0.0, 0.0, -1.0, 1.0),        // far: z <= w
    Vec4::new(1.0, 0.0, 0.0, GUARD_BAND),  // x >= -G w
    Vec4::new(-1.0, 0.0, 0.0, GUARD_BAND), // x <= G w
    Vec4::new(0.0, 1.0, 0.0, GUARD_BAND),  // y >= -G w
    Vec4::new(0.0, -1.0, 0.0, GUARD_BAND), // y <= G w
];

/// Bit i set when `p` is strictly outside plane i of [`PLANES`], whose sides are at |x|, |y| =
/// `side` w: the planes' dot products written as comparisons, a few instructions instead of six
/// four-wide dot products (this runs once per vertex per draw). For a finite point they agree
/// bit for bit: `z + w < 0` exactly when `z < -w` (a rounded sum keeps the sign of the exact one
/// and is zero only when it is), and `side * w` is exact for the powers of two used here.
#[inline]
fn outcode_with_side(p: Vec4, side: f32) -> u8 {
    let (x, y, z, w) = (p.x, p.y, p.z, p.w);
    let g = side * w;
    (z < -w) as u8
        | ((z > w) as u8) << 1
        | ((x < -g) as u8) << 2
        | ((x > g) as u8) << 3
        | ((y < -g) as u8) << 4
        | ((y > g) as u8) << 5
}

/// Outcode: bit i set when the point is outside plane i.
pub fn outcode(p: Vec4) -> u8 {
    outcode_with_side(p, GUARD_BAND)
}

/// Outcode against the view volume itself (|x|, |y| <= w, -w <= z <= w; no guard band): bit i set
/// when the point is strictly outside plane i. A triangle whose three codes share a bit lies wholly
/// on the outside of that plane, so none of it is visible and it covers no pixel; per-vertex work
/// (lighting) that only such triangles use can be skipped without changing the image.
pub fn view_outcode(p: Vec4) -> u8 {
    outcode_with_side(p, 1.0)
}

/// A convex polygon of at most [`MAX_CLIPPED`] vertices.
#[derive(Clone, Copy, Debug)]
pub struct Polygon<V> {
    /// Vertices; only the first `len` are valid.
    pub vertices: [ClipVertex<V>; MAX_CLIPPED],
    /// Number of valid vertices.
    pub len: usize,
}

/// Clips triangle `tri` against every plane its vertices' outcodes cross. The result, a convex
/// polygon, is empty (len < 3) when nothing is inside.
pub fn clip_triangle<V: Varying>(tri: [ClipVertex<V>; 3], planes_crossed: u8) -> Polygon<V> {
    let mut poly = Polygon { vertices: [ClipVertex::default(); MAX_CLIPPED], len: 3 };
    poly.vertices[..3].copy_from_slice(&tri);
    let mut scratch = poly;
    for (i, plane) in PLANES.iter().enumerate() {
        if planes_crossed & (1 << i) == 0 {
            continue;
        }
        scratch.len = 0;
        for k in 0..poly.len {
            let a = poly.vertices[k];
            let b = poly.vertices[(k + 1) % poly.len];
            let (da, db) = (plane.dot(a.position), plane.dot(b.position));
            if da >= 0.0 {
                scratch.vertices[scratch.len] = a;
                scratch.len += 1;
            }
            if (da >= 0.0) != (db >= 0.0) {
                // Interpolating in clip space (before the divide) is what keeps varyings
                // perspective-correct at the new vertex.
                let t = da / (da - db);
                scratch.vertices[scratch.len] =
                    ClipVertex { position: a.position.lerp(b.position, t), varying: a.varying.lerp(&b.varying, t) };
                scratch.len += 1;
            }
        }
        std::mem::swap(&mut poly, &mut scratch);
        if poly.len < 3 {
            poly.len = 0;
            break;
        }
    }
    poly
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The view volume's planes in the order of [`PLANES`]: the same near and far planes, and the
    /// sides at |x|, |y| = w (no guard band).
    const VIEW_PLANES: [Vec4; 6] = [
        Vec4::new(0.0, 0.0, 1.0, 1.0),
        Vec4::new(0.0, 0.0, -1.0, 1.0),
        Vec4::new(1.0, 0.0, 0.0, 1.0),
        Vec4::new(-1.0, 0.0, 0.0, 1.0),
        Vec4::new(0.0, 1.0, 0.0, 1.0),
        Vec4::new(0.0, -1.0, 0.0, 1.0),
    ];

    /// The comparisons of [`outcode_with_side`] against the planes' dot products they stand for,
    /// on points on, near and far from every plane, behind the eye and at w = 0.
    #[test]
    fn outcodes_agree_with_the_plane_equations() {
        let by_dot = |p: Vec4, planes: &[Vec4; 6]| {
            planes.iter().enumerate().fold(0u8, |code, (i, plane)| code | (((plane.dot(p) < 0.0) as u8) << i))
        };
        let values =
            [-1e6, -9.0, -8.0, -1.5, -1.0, -0.3, -0.0, 0.0, 1e-30, 0.3, 1.0, 1.0 + f32::EPSILON, 8.0, 8.5, 1e6];
        let mut checked = 0;
        for &x in &values {
            for &y in &values[..values.len() / 2 + 2] {
                for &z in &values {
                    for &w in &[-2.0, -1.0, 0.0, 0.1, 1.0, 1.0 / 3.0, 7.0, 1e5] {
                        let p = Vec4::new(x, y, z, w);
                        assert_eq!(outcode(p), by_dot(p, &PLANES), "{p}");
                        assert_eq!(view_outcode(p), by_dot(p, &VIEW_PLANES), "{p}");
                        checked += 1;
                    }
                }
            }
        }
        assert!(checked > 1000);
    }

    fn v(x: f32, y: f32, z: f32, w: f32) -> ClipVertex<()> {
        ClipVertex { position: Vec4::new(x, y, z, w), varying: () }
    }

    #[test]
    fn a_triangle_crossing_the_near_plane_becomes_a_quad_in_front_of_it() {
        // One vertex behind the eye (w < 0), two in front.
        let tri = [v(0.0, 0.0, 0.5, 1.0), v(0.5, 0.0, 0.5, 1.0), v(0.0, 0.0, -3.0, -1.0)];
        let codes = tri.map(|t| outcode(t.position));
        let poly = clip_triangle(tri, codes[0] | codes[1] | codes[2]);
        assert_eq!(poly.len, 4);
        for p in &poly.vertices[..poly.len] {
            assert!(p.position.z >= -p.position.w - 1e-6, "{p:?} is behind the near plane");
            assert!(p.position.w > 0.0);
        }
    }

    #[test]
    fn a_triangle_wholly_behind_is_empty() {
        let tri = [v(0.0, 0.0, -2.0, 1.0), v(0.5, 0.0, -2.0, 1.0), v(0.0, 0.5, -2.0, 1.0)];
        let codes = tri.map(|t| outcode(t.position));
        assert_eq!(clip_triangle(tri, codes[0] | codes[1] | codes[2]).len, 0);
    }
}
