//! Triangles of at most 2 x 2 pixels, set up and covered [`LANES`] at a time.
//!
//! A dense mesh seen whole is mostly triangles smaller than a pixel: 97 % of the 513² terrain's
//! at 800 x 800 have a pixel box of 2 x 2 or less. For them the general setup (a record of 72
//! bytes, each edge set up per band, a scan loop) costs far more than the pixels. Here the
//! triangles of a setup chunk go through in groups of [`LANES`]: the bounding box, area,
//! orientation, culling, the three edge functions and the coverage of the (at most four) pixel
//! centres are worked out lane by lane in 32-bit integers, a loop the compiler vectorises
//! ([`Isa::run_widest`]); the covered pixels then become fragment entries in the caller's bins.
//!
//! The arithmetic is the general path's ([`super::triangle::setup_geometry`] and
//! [`super::triangle::SetupTriangle::scan`]) on the same fixed-point values, so the fragments
//! are bit for bit those the general path makes (`tests::lanes_agree_with_the_general_setup`).
//! 32 bits suffice where the triangle's extent is below [`SMALL`] in each axis: every edge
//! value and twice the area are then below 2^25 in magnitude. Larger triangles (a big triangle
//! whose box the viewport clamps to a few pixels) are left to the general path.

// The lane loops index several arrays by lane on purpose: that is the shape the compiler
// vectorises.
#![allow(clippy::needless_range_loop)]

use super::triangle::{is_top_left, HALF, ONE, SUBPIXEL_BITS};
use crate::math::Isa;

/// Triangles per group: a multiple of the widest vector (16 lanes of 32 bits with AVX-512).
pub(super) const LANES: usize = 16;

/// Largest extent (exclusive, in 1/256 pixel: 16 pixels) for which the lanes' 32-bit
/// arithmetic is exact.
const SMALL: i32 = 16 << SUBPIXEL_BITS;

/// What [`classify`] decided for a lane.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
#[repr(u8)]
pub(super) enum Class {
    /// Left to the general path: clipped, large, or with a box larger than 2 x 2.
    #[default]
    General,
    /// Covers no pixel centre, or is degenerate or culled: nothing to draw.
    Nothing,
    /// Handled here: its covered pixels are in [`Covers::mask`].
    Tiny,
}

/// The corners of up to [`LANES`] triangles in window space, lane `k` the `k`-th triangle:
/// fixed-point x and y in the caller's vertex order, and whether the lane holds a triangle that
/// needs no clipping (others are [`Class::General`]).
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Corners {
    /// Columns in 1/256 pixel.
    pub x: [[i32; LANES]; 3],
    /// Rows in 1/256 pixel, 0 at the top.
    pub y: [[i32; LANES]; 3],
    /// Whether the lane is a triangle wholly inside the guard band.
    pub unclipped: [bool; LANES],
}

/// Per lane: its [`Class`] and, for [`Class::Tiny`], what the fragments need.
#[derive(Clone, Copy, Debug)]
pub(super) struct Covers {
    /// What the lane is: a [`Class`] as its discriminant (a byte the lane loop can store).
    class: [u8; LANES],
    /// Covered pixels of the box, bit `2 * row + column` (row order, left to right).
    pub mask: [u8; LANES],
    /// Whether corners 1 and 2 were swapped to wind the triangle clockwise on screen.
    pub swapped: [bool; LANES],
    /// The box's first column and row.
    pub box_x: [i32; LANES],
    /// The box's first row.
    pub box_y: [i32; LANES],
    /// Edge `k` (opposite corner `k`, after the swap) at the box's first pixel centre, fill-rule
    /// bias included.
    pub edge: [[i32; LANES]; 3],
    /// Edge `k`'s step one pixel right.
    pub step_x: [[i32; LANES]; 3],
    /// Edge `k`'s step one pixel down.
    pub step_y: [[i32; LANES]; 3],
    /// Edge `k`'s fill-rule bias: 0 for top and left edges, -1 for the others.
    pub bias: [[i32; LANES]; 3],
    /// 1 / twice the area in fixed point.
    pub inv_area: [f32; LANES],
}

impl Default for Covers {
    fn default() -> Self {
        Self {
            class: [Class::General as u8; LANES],
            mask: [0; LANES],
            swapped: [false; LANES],
            box_x: [0; LANES],
            box_y: [0; LANES],
            edge: [[0; LANES]; 3],
            step_x: [[0; LANES]; 3],
            step_y: [[0; LANES]; 3],
            bias: [[0; LANES]; 3],
            inv_area: [0.0; LANES],
        }
    }
}

impl Covers {
    /// What lane `k` is.
    #[inline(always)]
    pub fn class(&self, k: usize) -> Class {
        match self.class[k] {
            c if c == Class::Nothing as u8 => Class::Nothing,
            c if c == Class::Tiny as u8 => Class::Tiny,
            _ => Class::General,
        }
    }

    /// Calls `visit(column, row, linear weights)` for each covered pixel of lane `k` (a
    /// [`Class::Tiny`] one), row by row, left to right: the pixels and weights
    /// [`super::triangle::SetupTriangle::scan`] gives for the same triangle.
    #[inline(always)]
    pub fn fragments(&self, k: usize, mut visit: impl FnMut(u32, u32, [f32; 3])) {
        let mut mask = self.mask[k];
        let bias = [self.bias[0][k] as i64, self.bias[1][k] as i64, self.bias[2][k] as i64];
        while mask != 0 {
            let bit = mask.trailing_zeros();
            mask &= mask - 1;
            let (ox, oy) = ((bit & 1) as i32, (bit >> 1) as i32);
            let e = [0, 1, 2].map(|j| (self.edge[j][k] + self.step_x[j][k] * ox + self.step_y[j][k] * oy) as i64);
            let linear = super::triangle::linear_weights(e, bias, self.inv_area[k]);
            visit((self.box_x[k] + ox) as u32, (self.box_y[k] + oy) as u32, linear);
        }
    }
}

/// Classifies the lanes of `corners` for a `width` x `height` target (back faces dropped when
/// `cull_back`), with the widest instructions this CPU has.
pub(super) fn classify(corners: &Corners, width: u32, height: u32, cull_back: bool, out: &mut Covers) {
    classify_with(Isa::widest(), corners, width, height, cull_back, out)
}

/// [`classify`] compiled for `isa` (tests compare the builds).
pub(super) fn classify_with(isa: Isa, corners: &Corners, width: u32, height: u32, cull_back: bool, out: &mut Covers) {
    isa.run(
        #[inline(always)]
        || classify_lanes(corners, width as i32, height as i32, cull_back, out),
    )
}

/// The lane loops: no branches, every lane computed (values of lanes that are not
/// [`Class::Tiny`] are meaningless and may have wrapped). Several simple loops rather than one:
/// the compiler vectorises each of them for every instruction set.
#[inline(always)]
fn classify_lanes(c: &Corners, width: i32, height: i32, cull_back: bool, out: &mut Covers) {
    // Corners 1 and 2 in clockwise order (swapped when the area is negative), and each lane's
    // first pixel centre.
    let (mut x1, mut y1, mut x2, mut y2) = ([0; LANES], [0; LANES], [0; LANES], [0; LANES]);
    let (mut px, mut py) = ([0; LANES], [0; LANES]);
    let (mut wide, mut tall) = ([false; LANES], [false; LANES]);
    for k in 0..LANES {
        let (x0, xa, xb) = (c.x[0][k], c.x[1][k], c.x[2][k]);
        let (y0, ya, yb) = (c.y[0][k], c.y[1][k], c.y[2][k]);
        let (min_x, max_x) = (x0.min(xa).min(xb), x0.max(xa).max(xb));
        let (min_y, max_y) = (y0.min(ya).min(yb), y0.max(ya).max(yb));
        // Pixel centres in the box, clamped to the target (`setup_geometry`'s `first` and
        // `last`: an arithmetic shift is a floor division by ONE).
        // Wrapping arithmetic throughout: lanes left to the general path may hold anything, and
        // must not stop a debug build; the caller's lanes have coordinates far inside i32.
        let bx0 = (min_x.wrapping_add(ONE - 1 - HALF) >> SUBPIXEL_BITS).max(0);
        let bx1 = (max_x.wrapping_sub(HALF) >> SUBPIXEL_BITS).min(width - 1);
        let by0 = (min_y.wrapping_add(ONE - 1 - HALF) >> SUBPIXEL_BITS).max(0);
        let by1 = (max_y.wrapping_sub(HALF) >> SUBPIXEL_BITS).min(height - 1);
        let empty = (bx0 > bx1) | (by0 > by1);
        // Extents as unsigned differences: exact whatever the coordinates (max >= min).
        let extent = |lo: i32, hi: i32| (hi as u32).wrapping_sub(lo as u32);
        let small = (extent(min_x, max_x) < SMALL as u32) & (extent(min_y, max_y) < SMALL as u32);
        let area = xa
            .wrapping_sub(x0)
            .wrapping_mul(yb.wrapping_sub(y0))
            .wrapping_sub(ya.wrapping_sub(y0).wrapping_mul(xb.wrapping_sub(x0)));
        // With y down, OpenGL's counter-clockwise front faces have negative area.
        let swapped = area < 0;
        let dropped = (area == 0) | (cull_back & !swapped);
        let fits = (bx1.wrapping_sub(bx0) <= 1) & (by1.wrapping_sub(by0) <= 1);
        let unclipped = c.unclipped[k];
        let nothing = unclipped & (empty | (small & dropped));
        let tiny = unclipped & !empty & small & !dropped & fits;
        // The two are exclusive: a sum of discriminants, with no branch.
        out.class[k] = nothing as u8 * Class::Nothing as u8 + tiny as u8 * Class::Tiny as u8;
        (x1[k], x2[k]) = if swapped { (xb, xa) } else { (xa, xb) };
        (y1[k], y2[k]) = if swapped { (yb, ya) } else { (ya, yb) };
        (px[k], py[k]) = (bx0.wrapping_mul(ONE).wrapping_add(HALF), by0.wrapping_mul(ONE).wrapping_add(HALF));
        wide[k] = tiny & (bx1 > bx0);
        tall[k] = tiny & (by1 > by0);
        out.swapped[k] = swapped;
        out.box_x[k] = bx0;
        out.box_y[k] = by0;
        out.inv_area[k] = 1.0 / area.wrapping_abs() as f32;
    }
    // Edge k runs between the two corners other than k: 1 -> 2, 2 -> 0, 0 -> 1.
    let mut inside = [[true; LANES]; 4];
    edge_lanes((&x1, &y1), (&x2, &y2), (&px, &py), 0, &mut inside, out);
    edge_lanes((&x2, &y2), (&c.x[0], &c.y[0]), (&px, &py), 1, &mut inside, out);
    edge_lanes((&c.x[0], &c.y[0]), (&x1, &y1), (&px, &py), 2, &mut inside, out);
    for k in 0..LANES {
        let (wide, tall) = (wide[k], tall[k]);
        let tiny = out.class[k] == Class::Tiny as u8;
        out.mask[k] = (inside[0][k] & tiny) as u8
            | ((inside[1][k] & wide) as u8) << 1
            | ((inside[2][k] & tall) as u8) << 2
            | ((inside[3][k] & wide & tall) as u8) << 3;
    }
}

/// Edge `j` of every lane, from corner `a` to corner `b`, at the first pixel centre `p`: its
/// value, steps and fill-rule bias into `out`, and whether each of the four pixel centres is on
/// its inner side into `inside` (and-ed with the other edges').
#[inline(always)]
fn edge_lanes(
    a: (&[i32; LANES], &[i32; LANES]),
    b: (&[i32; LANES], &[i32; LANES]),
    p: (&[i32; LANES], &[i32; LANES]),
    j: usize,
    inside: &mut [[bool; LANES]; 4],
    out: &mut Covers,
) {
    for k in 0..LANES {
        let (dx, dy) = (b.0[k].wrapping_sub(a.0[k]), b.1[k].wrapping_sub(a.1[k]));
        // Pixels exactly on an edge count only for top and left edges.
        let bias = is_top_left(dx, dy) as i32 - 1;
        let e = dx
            .wrapping_mul(p.1[k].wrapping_sub(a.1[k]))
            .wrapping_sub(dy.wrapping_mul(p.0[k].wrapping_sub(a.0[k])))
            .wrapping_add(bias);
        let (sx, sy) = (dy.wrapping_mul(-ONE), dx.wrapping_mul(ONE));
        inside[0][k] &= e >= 0;
        inside[1][k] &= e.wrapping_add(sx) >= 0;
        inside[2][k] &= e.wrapping_add(sy) >= 0;
        inside[3][k] &= e.wrapping_add(sx).wrapping_add(sy) >= 0;
        out.edge[j][k] = e;
        out.step_x[j][k] = sx;
        out.step_y[j][k] = sy;
        out.bias[j][k] = bias;
    }
}

#[cfg(test)]
mod tests {
    use super::super::triangle::{setup_geometry, WindowVertex};
    use super::*;

    /// A small deterministic generator (xorshift), so the test needs no crate and no seed file.
    struct Rng(u64);

    impl Rng {
        fn next(&mut self) -> u64 {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            self.0
        }
        fn range(&mut self, lo: i32, hi: i32) -> i32 {
            lo + (self.next() % (hi - lo) as u64) as i32
        }
    }

    /// Random triangles, mostly of a pixel or two, some larger, some off the target's edges,
    /// some with corners on pixel centres and shared edges: the lanes' fragments are the
    /// general setup's, bit for bit, with every instruction set this CPU has; and what they
    /// drop, the general setup drops.
    #[test]
    fn lanes_agree_with_the_general_setup() {
        let (width, height) = (40u32, 30u32);
        let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
        let (mut tiny, mut nothing, mut general) = (0, 0, 0);
        for round in 0..3000 {
            let cull_back = round % 3 == 0;
            let mut corners = Corners::default();
            for k in 0..LANES {
                let (cx, cy) =
                    (rng.range(-3 * ONE, (width as i32 + 3) * ONE), rng.range(-3 * ONE, (height as i32 + 3) * ONE));
                let size = match rng.range(0, 10) {
                    0 => 40 * ONE,
                    1 => 4 * ONE,
                    _ => 2 * ONE,
                };
                for v in 0..3 {
                    let (mut x, mut y) = (cx + rng.range(-size, size + 1), cy + rng.range(-size, size + 1));
                    if rng.range(0, 4) == 0 {
                        // On a pixel centre or a pixel edge: the fill rule decides.
                        x = x / (ONE / 2) * (ONE / 2);
                        y = y / (ONE / 2) * (ONE / 2);
                    }
                    corners.x[v][k] = x;
                    corners.y[v][k] = y;
                }
                corners.unclipped[k] = rng.range(0, 20) != 0;
            }
            for isa in Isa::ALL.into_iter().filter(|isa| isa.is_available()) {
                let mut covers = Covers::default();
                classify_with(isa, &corners, width, height, cull_back, &mut covers);
                for k in 0..LANES {
                    let w =
                        [0, 1, 2].map(|v| WindowVertex { x: corners.x[v][k], y: corners.y[v][k], z: 0.5, inv_w: 1.0 });
                    let general_setup = setup_geometry(&w, 0, width, height, cull_back);
                    match covers.class(k) {
                        Class::General => {
                            general += 1;
                            assert!(corners.unclipped[k] || covers.mask[k] == 0);
                        }
                        Class::Nothing => {
                            nothing += 1;
                            assert!(
                                general_setup.is_none(),
                                "{isa:?} lane {k}: dropped a triangle the general setup keeps"
                            );
                        }
                        Class::Tiny => {
                            tiny += 1;
                            let (t, swapped) =
                                general_setup.expect("a tiny lane is a triangle the general setup keeps");
                            assert_eq!(swapped, covers.swapped[k]);
                            let mut expected = Vec::new();
                            t.scan((0, height - 1), |c| expected.push((c.x, c.y, c.linear.map(f32::to_bits))));
                            let mut got = Vec::new();
                            covers.fragments(k, |x, y, l| got.push((x, y, l.map(f32::to_bits))));
                            assert_eq!(got, expected, "{isa:?} lane {k}: {:?}", w);
                        }
                    }
                }
            }
        }
        // Every class was exercised, and plenty of covered pixels among the tiny lanes.
        assert!(tiny > 10_000 && nothing > 1_000 && general > 1_000, "{tiny} {nothing} {general}");
    }
}
