//! Triangle setup and scan conversion with edge functions in fixed point.
//!
//! Screen coordinates are snapped to 1/256 pixel ([`SUBPIXEL_BITS`] = 8) so that two triangles that
//! share an edge compute exactly the same edge function on it; with the top-left rule, a pixel centre
//! on a shared edge then belongs to exactly one of them: no cracks, no double blending.

use glam::Vec4;

use super::{ClipVertex, Varying};

/// Fractional bits of the fixed-point screen coordinates.
pub const SUBPIXEL_BITS: u32 = 8;
/// One pixel in fixed point.
pub(super) const ONE: i32 = 1 << SUBPIXEL_BITS;
/// Half a pixel: pixel centres sit at `px * ONE + HALF`.
pub(super) const HALF: i32 = ONE / 2;

/// Boxes at least this many pixels wide (less one) have each row's covered run solved for
/// ([`SetupTriangle::scan`]); narrower ones test every pixel.
const SPAN_MIN_WIDTH: i64 = 8;

/// A triangle ready to scan: fixed-point vertices, depth, 1/w and varyings.
#[derive(Clone, Copy, Debug)]
pub struct SetupTriangle<V> {
    x: [i32; 3],
    y: [i32; 3],
    z: [f32; 3],
    inv_w: [f32; 3],
    varying: [V; 3],
    /// 1 / (twice the signed area in fixed point); after reordering the area is always > 0.
    inv_area: f32,
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

/// A vertex in window space: x and y in 24.8 fixed point (x right, y down), depth in [0, 1], 1/w.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct WindowVertex {
    /// Column in 1/256 pixel.
    pub x: i32,
    /// Row in 1/256 pixel, 0 at the top edge.
    pub y: i32,
    /// Window-space depth.
    pub z: f32,
    /// 1 / clip w.
    pub inv_w: f32,
}

/// Rounds half away from zero with a cast: `f32::round` is a libm call on baseline x86-64, and
/// this runs once per vertex. Identical results to `round`: from 2^23 on every f32 is already
/// an integer (and adding 0.5 would round to even).
#[inline]
fn round_to_i32(v: f32) -> i32 {
    if v.abs() >= 8_388_608.0 {
        v as i32
    } else {
        (v + 0.5f32.copysign(v)) as i32
    }
}

/// Maps a clip-space point inside the guard band to window coordinates: x right, y down (top row
/// first), depth in [0, 1], snapped to 1/256 pixel.
pub fn to_window(p: Vec4, width: u32, height: u32) -> WindowVertex {
    let inv_w = 1.0 / p.w;
    let (nx, ny, nz) = (p.x * inv_w, p.y * inv_w, p.z * inv_w);
    let sx = (0.5 * nx + 0.5) * width as f32;
    let sy = (0.5 - 0.5 * ny) * height as f32;
    WindowVertex { x: round_to_i32(sx * ONE as f32), y: round_to_i32(sy * ONE as f32), z: 0.5 * nz + 0.5, inv_w }
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
    let (t, swapped) =
        setup_clip_geometry([tri[0].position, tri[1].position, tri[2].position], primitive, width, height, cull_back)?;
    Some(t.with_varying([tri[0].varying, tri[1].varying, tri[2].varying], swapped))
}

/// [`setup`] without the varyings: the triangle, and whether its vertices 1 and 2 were swapped
/// to wind it clockwise (the caller's varyings follow the same order).
pub(super) fn setup_clip_geometry(
    p: [Vec4; 3],
    primitive: u32,
    width: u32,
    height: u32,
    cull_back: bool,
) -> Option<(SetupTriangle<()>, bool)> {
    let w = p.map(|p| to_window(p, width, height));
    // A non-finite vertex (w = 0, or NaN from a broken model) would cast to an arbitrary fixed-point
    // coordinate; dropping the triangle keeps NaN out of the framebuffer.
    if !w.iter().all(|v| v.z.is_finite() && v.inv_w.is_finite()) {
        return None;
    }
    setup_geometry(&w, primitive, width, height, cull_back)
}

/// [`setup`] for vertices already in window space ([`to_window`]).
#[inline]
pub fn setup_window<V: Varying>(
    w: &[WindowVertex; 3],
    varying: [V; 3],
    primitive: u32,
    width: u32,
    height: u32,
    cull_back: bool,
) -> Option<SetupTriangle<V>> {
    let (t, swapped) = setup_geometry(w, primitive, width, height, cull_back)?;
    Some(t.with_varying(varying, swapped))
}

/// [`setup_window`] without the varyings: the triangle, and whether its vertices 1 and 2 were
/// swapped. The draw call keeps the varyings apart, by vertex index: a triangle record then
/// takes 72 bytes whatever the varying (108 with an RGB colour), and writing the records at setup
/// and reading them back per band is memory traffic that dominates dense meshes.
#[inline]
pub(super) fn setup_geometry(
    w: &[WindowVertex; 3],
    primitive: u32,
    width: u32,
    height: u32,
    cull_back: bool,
) -> Option<(SetupTriangle<()>, bool)> {
    let mut x = [w[0].x, w[1].x, w[2].x];
    let mut y = [w[0].y, w[1].y, w[2].y];
    // Bounds first: most triangles of a dense mesh that miss every pixel centre leave here.
    let (min_xf, max_xf) = (x[0].min(x[1]).min(x[2]), x[0].max(x[1]).max(x[2]));
    let (min_yf, max_yf) = (y[0].min(y[1]).min(y[2]), y[0].max(y[1]).max(y[2]));
    // Pixel (px, py) has its centre at (px + 1/2, py + 1/2).
    let first = |v: i32| (v - HALF + ONE - 1).div_euclid(ONE);
    let last = |v: i32| (v - HALF).div_euclid(ONE);
    let (x0, x1) = (first(min_xf).max(0), last(max_xf).min(width as i32 - 1));
    let (y0, y1) = (first(min_yf).max(0), last(max_yf).min(height as i32 - 1));
    if x0 > x1 || y0 > y1 {
        return None;
    }
    let area2 = (x[1] - x[0]) as i64 * (y[2] - y[0]) as i64 - (y[1] - y[0]) as i64 * (x[2] - x[0]) as i64;
    if area2 == 0 {
        return None;
    }
    // With y pointing down, OpenGL's counter-clockwise front faces have negative area here.
    let front = area2 < 0;
    if cull_back && !front {
        return None;
    }
    let mut z = [w[0].z, w[1].z, w[2].z];
    let mut inv_w = [w[0].inv_w, w[1].inv_w, w[2].inv_w];
    let swapped = area2 < 0;
    if swapped {
        x.swap(1, 2);
        y.swap(1, 2);
        z.swap(1, 2);
        inv_w.swap(1, 2);
    }
    let t = SetupTriangle {
        x,
        y,
        z,
        inv_w,
        varying: [(); 3],
        inv_area: 1.0 / area2.abs() as f32,
        primitive,
        min_x: x0 as u32,
        max_x: x1 as u32,
        min_y: y0 as u32,
        max_y: y1 as u32,
    };
    Some((t, swapped))
}

impl SetupTriangle<()> {
    /// This triangle carrying `varying` (in the caller's vertex order; `swapped` as
    /// [`setup_geometry`] returned it).
    #[inline]
    fn with_varying<V>(&self, mut varying: [V; 3], swapped: bool) -> SetupTriangle<V> {
        if swapped {
            varying.swap(1, 2);
        }
        let Self { x, y, z, inv_w, inv_area, primitive, min_x, max_x, min_y, max_y, .. } = *self;
        SetupTriangle { x, y, z, inv_w, varying, inv_area, primitive, min_x, max_x, min_y, max_y }
    }
}

/// Window-space depth at linear weights `l` of corners at depths `z`: affine in screen space.
/// [`SetupTriangle::depth`] and the small-triangle path share it, so both give the same bits.
#[inline(always)]
pub(super) fn depth_at(z: &[f32; 3], l: [f32; 3]) -> f32 {
    l[0] * z[0] + l[1] * z[1] + l[2] * z[2]
}

/// Perspective-correct weights from linear ones `l` of corners with 1/w `inv_w`: each weight
/// divided by its corner's w and the three renormalised.
#[inline(always)]
pub(super) fn perspective_weights(inv_w: &[f32; 3], l: [f32; 3]) -> [f32; 3] {
    let p = [l[0] * inv_w[0], l[1] * inv_w[1], l[2] * inv_w[2]];
    let s = 1.0 / (p[0] + p[1] + p[2]);
    [p[0] * s, p[1] * s, p[2] * s]
}

/// Linear (screen-space) weights at a pixel from its edge values `e` (biased by `bias` for the
/// fill rule, which only decides ties and is undone here) and 1 / twice the area.
#[inline(always)]
pub(super) fn linear_weights(e: [i64; 3], bias: [i64; 3], inv_area: f32) -> [f32; 3] {
    [(e[0] - bias[0]) as f32 * inv_area, (e[1] - bias[1]) as f32 * inv_area, (e[2] - bias[2]) as f32 * inv_area]
}

/// Whether edge a -> b is a top or left edge for triangles wound clockwise on screen (y down),
/// the orientation [`setup`] leaves them in.
#[inline(always)]
pub(super) fn is_top_left<T: Copy + Default + Ord>(dx: T, dy: T) -> bool {
    // `&` and `|`, not `&&` and `||`: no branch (a dense mesh's edges go every way, so a branch
    // here mispredicts about as often as not), and the small-triangle lanes vectorise it.
    let zero = T::default();
    (dy == zero) & (dx > zero) | (dy < zero)
}

/// A covered pixel: its coordinates and linear (screen-space) barycentric weights.
#[derive(Clone, Copy, Debug)]
pub struct Coverage {
    /// Column.
    pub x: u32,
    /// Row.
    pub y: u32,
    /// Screen-space barycentric weights of the three (reordered) vertices, summing to 1. Depth
    /// is affine in them ([`SetupTriangle::depth`]); varyings need
    /// [`SetupTriangle::perspective_weights`].
    pub linear: [f32; 3],
}

impl<V: Varying> SetupTriangle<V> {
    /// Window-space depth at a pixel: affine in screen space, so the linear weights give it.
    #[inline]
    pub fn depth(&self, l: [f32; 3]) -> f32 {
        depth_at(&self.z, l)
    }

    /// Perspective-correct weights from linear ones: each divided by its vertex's w and
    /// renormalised (one division per pixel, only for pixels that pass the depth test).
    #[inline]
    pub fn perspective_weights(&self, l: [f32; 3]) -> [f32; 3] {
        perspective_weights(&self.inv_w, l)
    }

    /// The varyings at a pixel, from perspective-correct weights.
    #[inline]
    pub fn interpolate(&self, weights: [f32; 3]) -> V {
        V::weighted(&self.varying[0], &self.varying[1], &self.varying[2], weights)
    }

    /// Calls `visit` for every pixel centre the triangle covers in rows `rows` (inclusive
    /// bounds, clamped to the triangle's), row by row, left to right.
    #[inline]
    pub fn scan(&self, rows: (u32, u32), mut visit: impl FnMut(Coverage)) {
        let (y_from, y_to) = (rows.0.max(self.min_y), rows.1.min(self.max_y));
        if y_from > y_to {
            return;
        }
        // Edge k is opposite vertex k: e0 = v1 -> v2, e1 = v2 -> v0, e2 = v0 -> v1. Written out
        // per edge rather than with array `map`, which the compiler does not always inline here.
        let (x, y) = (&self.x, &self.y);
        let px0 = self.min_x as i64 * ONE as i64 + HALF as i64;
        let py0 = y_from as i64 * ONE as i64 + HALF as i64;
        let edge = |a: usize, b: usize| {
            let (dx, dy) = ((x[b] - x[a]) as i64, (y[b] - y[a]) as i64);
            // Pixels exactly on an edge count only for top and left edges.
            let bias = is_top_left(dx, dy) as i64 - 1;
            let start = dx * (py0 - y[a] as i64) - dy * (px0 - x[a] as i64) + bias;
            (start, -dy * ONE as i64, dx * ONE as i64, bias)
        };
        let (mut r0, sx0, sy0, b0) = edge(1, 2);
        let (mut r1, sx1, sy1, b1) = edge(2, 0);
        let (mut r2, sx2, sy2, b2) = edge(0, 1);
        let inv = self.inv_area;
        let last = (self.max_x - self.min_x) as i64;
        // Undo the bias before weighting; it only decides ties.
        let weights = |e0: i64, e1: i64, e2: i64| linear_weights([e0, e1, e2], [b0, b1, b2], inv);
        // Half-open ranges below: an inclusive range's iterator keeps an `exhausted` flag, one
        // more compare and branch per pixel in the hottest loops. Two loops, not one with a
        // per-pixel choice: one loop cost the unbounded sea's raster 13 % more (callgrind).
        if last < SPAN_MIN_WIDTH {
            // A narrow box (a dense mesh's triangles cover a pixel or two): testing its few pixels
            // costs less than solving for the run, which takes up to three divisions a row.
            for py in y_from..y_to + 1 {
                let (mut e0, mut e1, mut e2) = (r0, r1, r2);
                for px in self.min_x..self.max_x + 1 {
                    if (e0 | e1 | e2) >= 0 {
                        visit(Coverage { x: px, y: py, linear: weights(e0, e1, e2) });
                    }
                    e0 += sx0;
                    e1 += sx1;
                    e2 += sx2;
                }
                r0 += sy0;
                r1 += sy1;
                r2 += sy2;
            }
            return;
        }
        for py in y_from..y_to + 1 {
            let (lo, hi) = covered_run([(r0, sx0), (r1, sx1), (r2, sx2)], last);
            if lo <= hi {
                let (mut e0, mut e1, mut e2) = (r0 + sx0 * lo, r1 + sx1 * lo, r2 + sx2 * lo);
                for px in self.min_x + lo as u32..self.min_x + hi as u32 + 1 {
                    visit(Coverage { x: px, y: py, linear: weights(e0, e1, e2) });
                    e0 += sx0;
                    e1 += sx1;
                    e2 += sx2;
                }
            }
            r0 += sy0;
            r1 += sy1;
            r2 += sy2;
        }
    }
}

/// The covered run of a row, as offsets from the box's first column within `[0, last]`: edge `k`
/// has value `r` there and grows by `s` a pixel, and a pixel is covered where all three are >= 0.
/// Each edge is linear in x, so the run's ends follow exactly (integer division) instead of being
/// searched for: thin triangles, the norm towards a horizon, cover a third of their box or less.
/// `lo > hi` when the row has none.
#[inline(always)]
fn covered_run(edges: [(i64, i64); 3], last: i64) -> (i64, i64) {
    let (mut lo, mut hi) = (0i64, last);
    for (r, s) in edges {
        match s.cmp(&0) {
            std::cmp::Ordering::Greater if r < 0 => lo = lo.max((-r + s - 1) / s),
            std::cmp::Ordering::Less if r < 0 => hi = -1,
            std::cmp::Ordering::Less => hi = hi.min(r / -s),
            std::cmp::Ordering::Equal if r < 0 => hi = -1,
            _ => {}
        }
    }
    (lo, hi)
}
