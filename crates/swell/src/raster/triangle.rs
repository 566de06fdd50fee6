//! Triangle setup and scan conversion with edge functions in fixed point.
//!
//! Screen coordinates are snapped to 1/256 pixel ([`SUBPIXEL_BITS`] = 8) so that two triangles that
//! share an edge compute exactly the same edge function on it; with the top-left rule, a pixel centre
//! on a shared edge then belongs to exactly one of them: no cracks, no double blending.

use glam::Vec4;

use super::{ClipVertex, Varying};

/// Fractional bits of the fixed-point screen coordinates.
pub const SUBPIXEL_BITS: u32 = 8;
const ONE: i64 = 1 << SUBPIXEL_BITS;
const HALF: i64 = ONE / 2;

/// A triangle ready to scan: fixed-point vertices, depth, 1/w and varyings.
#[derive(Clone, Copy, Debug)]
pub struct SetupTriangle<V> {
    x: [i64; 3],
    y: [i64; 3],
    z: [f32; 3],
    inv_w: [f32; 3],
    varying: [V; 3],
    /// Twice the signed area in fixed point (after reordering, always > 0).
    area2: i64,
    /// Index of the triangle in the caller's index buffer.
    pub primitive: u32,
    /// Inclusive pixel bounds, already clamped to the viewport.
    pub min_x: u32,
    /// Inclusive pixel bounds.
    pub max_x: u32,
    /// Inclusive pixel bounds.
    pub min_y: u32,
    /// Inclusive pixel bounds.
    pub max_y: u32,
}

/// Maps clip space to window coordinates: x right, y down (top row first), depth in [0, 1].
fn to_window(p: Vec4, width: u32, height: u32) -> (f32, f32, f32, f32) {
    let inv_w = 1.0 / p.w;
    let (nx, ny, nz) = (p.x * inv_w, p.y * inv_w, p.z * inv_w);
    let sx = (0.5 * nx + 0.5) * width as f32;
    let sy = (0.5 - 0.5 * ny) * height as f32;
    (sx, sy, 0.5 * nz + 0.5, inv_w)
}

/// Sets up a triangle whose vertices are inside the clip volume (see [`super::clip`]).
///
/// Returns `None` when it covers no pixel centre, is degenerate, or is culled. A triangle whose
/// vertices run counter-clockwise in NDC (OpenGL's front face) is front-facing.
pub fn setup<V: Varying>(
    tri: &[ClipVertex<V>; 3],
    primitive: u32,
    width: u32,
    height: u32,
    cull_back: bool,
) -> Option<SetupTriangle<V>> {
    let w = tri.map(|v| to_window(v.position, width, height));
    // Clipped vertices are inside the view volume, so window coordinates are within the image;
    // a non-finite one (w = 0, or NaN from a broken model) would snap to i64::MAX and overflow the
    // edge functions. Dropping the triangle keeps NaN out of the framebuffer.
    if !w.iter().all(|p| p.0.is_finite() && p.1.is_finite() && p.2.is_finite() && p.3.is_finite()) {
        return None;
    }
    let snap = |c: f32| (c * ONE as f32).round() as i64;
    let mut x = w.map(|p| snap(p.0));
    let mut y = w.map(|p| snap(p.1));
    let mut z = w.map(|p| p.2);
    let mut inv_w = w.map(|p| p.3);
    let mut varying = tri.map(|v| v.varying);
    let area2 = (x[1] - x[0]) * (y[2] - y[0]) - (y[1] - y[0]) * (x[2] - x[0]);
    if area2 == 0 {
        return None;
    }
    // With y pointing down, OpenGL's counter-clockwise front faces have negative area here.
    let front = area2 < 0;
    if cull_back && !front {
        return None;
    }
    if area2 < 0 {
        x.swap(1, 2);
        y.swap(1, 2);
        z.swap(1, 2);
        inv_w.swap(1, 2);
        varying.swap(1, 2);
    }
    let (min_xf, max_xf) = (*x.iter().min()?, *x.iter().max()?);
    let (min_yf, max_yf) = (*y.iter().min()?, *y.iter().max()?);
    // Pixel (px, py) has its centre at (px + 1/2, py + 1/2).
    let first = |v: i64| (v - HALF + ONE - 1).div_euclid(ONE);
    let last = |v: i64| (v - HALF).div_euclid(ONE);
    let (x0, x1) = (first(min_xf).max(0), last(max_xf).min(width as i64 - 1));
    let (y0, y1) = (first(min_yf).max(0), last(max_yf).min(height as i64 - 1));
    if x0 > x1 || y0 > y1 {
        return None;
    }
    Some(SetupTriangle {
        x,
        y,
        z,
        inv_w,
        varying,
        area2: area2.abs(),
        primitive,
        min_x: x0 as u32,
        max_x: x1 as u32,
        min_y: y0 as u32,
        max_y: y1 as u32,
    })
}

/// Whether edge a -> b is a top or left edge for triangles wound clockwise on screen (y down),
/// the orientation [`setup`] leaves them in.
fn is_top_left(dx: i64, dy: i64) -> bool {
    (dy == 0 && dx > 0) || dy < 0
}

/// A covered pixel: its coordinates, depth and perspective-correct barycentric weights.
#[derive(Clone, Copy, Debug)]
pub struct Coverage {
    /// Column.
    pub x: u32,
    /// Row.
    pub y: u32,
    /// Window-space depth in [0, 1].
    pub depth: f32,
    /// Perspective-correct weights of the three (reordered) vertices, summing to 1.
    pub weights: [f32; 3],
}

impl<V: Varying> SetupTriangle<V> {
    /// The varyings at a pixel, from [`Coverage::weights`].
    pub fn interpolate(&self, weights: [f32; 3]) -> V {
        V::weighted(&self.varying[0], &self.varying[1], &self.varying[2], weights)
    }

    /// Calls `visit` for every pixel centre the triangle covers in rows `rows` (inclusive
    /// bounds, clamped to the triangle's), row by row, left to right.
    pub fn scan(&self, rows: (u32, u32), mut visit: impl FnMut(Coverage)) {
        let (y_from, y_to) = (rows.0.max(self.min_y), rows.1.min(self.max_y));
        if y_from > y_to {
            return;
        }
        // Edge k is opposite vertex k: e0 = v1 -> v2, e1 = v2 -> v0, e2 = v0 -> v1.
        let (x, y) = (&self.x, &self.y);
        let edges = [(1, 2), (2, 0), (0, 1)].map(|(a, b)| {
            let (dx, dy) = (x[b] - x[a], y[b] - y[a]);
            // Pixels exactly on an edge count only for top and left edges.
            let bias = if is_top_left(dx, dy) { 0 } else { -1 };
            (a, dx, dy, bias)
        });
        let px0 = self.min_x as i64 * ONE + HALF;
        let inv_area = 1.0 / self.area2 as f32;
        for py in y_from..=y_to {
            let pyf = py as i64 * ONE + HALF;
            let mut e = edges.map(|(a, dx, dy, bias)| dx * (pyf - y[a]) - dy * (px0 - x[a]) + bias);
            let step = edges.map(|(_, _, dy, _)| -dy * ONE);
            for px in self.min_x..=self.max_x {
                if (e[0] | e[1] | e[2]) >= 0 {
                    // Undo the bias before weighting; it only decides ties.
                    let l = [0, 1, 2].map(|k| (e[k] - edges[k].3) as f32 * inv_area);
                    let depth = l[0] * self.z[0] + l[1] * self.z[1] + l[2] * self.z[2];
                    let p = [0, 1, 2].map(|k| l[k] * self.inv_w[k]);
                    let s = 1.0 / (p[0] + p[1] + p[2]);
                    visit(Coverage { x: px, y: py, depth, weights: [p[0] * s, p[1] * s, p[2] * s] });
                }
                for k in 0..3 {
                    e[k] += step[k];
                }
            }
        }
    }
}
