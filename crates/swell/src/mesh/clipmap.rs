//! The camera-following mesh of unbounded water: nested square rings (a geometry clipmap) snapped
//! to a world grid, stitched into one watertight triangle list.
//!
//! Ring `k` (level k) is a regular grid of `N x N` cells with spacing `s 2^k`; every ring but the
//! finest leaves out its middle `N/2 x N/2` cells, which the ring inside covers exactly. Each
//! ring's origin is snapped to a multiple of *twice* its own spacing (the next ring's spacing), so:
//! - vertices sit at fixed world positions: moving the camera never slides a vertex over the
//!   waves (no swimming); rings jump by whole cells, which changes the mesh only where it is coarse
//!   relative to the waves it shows far out;
//! - the edge of the hole in ring k+1 runs along vertices of ring k (every other one).
//!
//! Cracks: at the hole's edge ring k's boundary has a vertex in the middle of each coarse edge.
//! Instead of moving those vertices (Losasso and Hoppe's transition blend), the coarse cells that
//! touch the hole are cut into three triangles fanning from that middle vertex, and every vertex on
//! the hole's edge is the *fine* ring's vertex (the same index). Neighbouring triangles therefore
//! share exactly the same edges and vertices: no T-junction, no gap, whatever the displacement.
//!
//! Sources: Losasso and Hoppe 2004, "Geometry clipmaps: terrain rendering using nested regular
//! grids" (SIGGRAPH), for nested rings snapped to the grid; Asirvatham and Hoppe 2005, GPU Gems 2
//! ch. 2, for the ring layout. The stitching fan is swell's own (it suits a CPU rasterizer, which
//! has no vertex-texture fetch to blend levels with).

use glam::{Vec2, Vec3};

use crate::error::{Error, Result};
use crate::math::GridSpec;
use crate::water::WaveModel;

/// Nested rings of vertices around a centre, with buffers a [`WaveModel`] writes each frame.
///
/// Vertex `v` of level `k` is at index `offsets[k] + v` of [`Clipmap::positions`], laid out as
/// [`GridSpec`] row-major grids (each level a full `(N+1)^2` grid; the middle of the coarser
/// ones is evaluated but no triangle uses it, which keeps every level a plain grid the models'
/// vectorised kernels evaluate unchanged).
#[derive(Clone, Debug)]
pub struct Clipmap {
    levels: u32,
    ring_cells: u32,
    spacing: f32,
    /// Each level's origin in units of the finest spacing (integers, so snapping is exact).
    origins: Vec<[i64; 2]>,
    /// Each level's grid in the model's (local) frame.
    grids: Vec<GridSpec>,
    /// First vertex of each level.
    offsets: Vec<usize>,
    /// Displaced positions (m), written by [`Clipmap::displace`].
    pub positions: Vec<Vec3>,
    /// Unit normals.
    pub normals: Vec<Vec3>,
    /// Foam coverage in [0, 1] per vertex (all zero unless [`Clipmap::has_foam`]).
    pub foam: Vec<f32>,
    /// Whether the last [`Clipmap::displace`] came with foam from the model.
    pub has_foam: bool,
    /// Triangle list, counter-clockwise seen from +Y; rebuilt when a ring moves.
    pub indices: Vec<u32>,
}

impl Clipmap {
    /// `levels` rings in [1, 16] of `ring_cells` cells a side (a multiple of 4 in [8, 1024]), the
    /// finest with `spacing` m between vertices (finite, > 0), centred near local (0, 0).
    pub fn new(levels: u32, ring_cells: u32, spacing: f32) -> Result<Self> {
        if !(1..=16).contains(&levels) {
            return Err(Error::out_of_range("water.lod.levels", levels, "[1, 16]"));
        }
        if !(8..=1024).contains(&ring_cells) || !ring_cells.is_multiple_of(4) {
            return Err(Error::out_of_range("water.lod.ring_cells", ring_cells, "multiples of 4 in [8, 1024]"));
        }
        if !(spacing.is_finite() && spacing > 0.0) {
            return Err(Error::out_of_range("water.lod.spacing", spacing, "> 0 m"));
        }
        let per_level = (ring_cells as usize + 1).pow(2);
        let total = per_level * levels as usize;
        let mut c = Self {
            levels,
            ring_cells,
            spacing,
            origins: vec![[i64::MIN; 2]; levels as usize],
            grids: Vec::with_capacity(levels as usize),
            offsets: (0..levels as usize).map(|k| k * per_level).collect(),
            positions: vec![Vec3::ZERO; total],
            normals: vec![Vec3::Y; total],
            foam: vec![0.0; total],
            has_foam: false,
            indices: Vec::new(),
        };
        c.follow(Vec2::ZERO);
        Ok(c)
    }

    /// Number of rings.
    pub fn levels(&self) -> u32 {
        self.levels
    }

    /// Each level's sampling grid (local frame), finest first.
    pub fn grids(&self) -> &[GridSpec] {
        &self.grids
    }

    /// Metres between vertices of level `k`.
    pub fn level_spacing(&self, k: u32) -> f32 {
        self.spacing * (1u64 << k) as f32
    }

    /// Half the side (m) of the square the rings cover: the sea beyond is the far field.
    pub fn reach(&self) -> f32 {
        0.5 * self.ring_cells as f32 * self.level_spacing(self.levels - 1)
    }

    /// Index of the vertex of level `k` at grid (i, j), before hole-edge remapping.
    fn own(&self, k: usize, i: i64, j: i64) -> u32 {
        (self.offsets[k] + (j as usize) * (self.ring_cells as usize + 1) + i as usize) as u32
    }

    /// Where level `k - 1` sits in level `k`, in level-`k` cells (its hole's first cell).
    fn hole(&self, k: usize) -> [i64; 2] {
        let (f, c) = (self.origins[k - 1], self.origins[k]);
        let step = 1i64 << k; // level k's spacing in finest units
        [(f[0] - c[0]) / step, (f[1] - c[1]) / step]
    }

    /// The vertex at grid (i, j) of level `k`: on the edge of the hole it is the finer level's own
    /// vertex (so both levels share it exactly).
    fn vertex(&self, k: usize, i: i64, j: i64) -> u32 {
        if k > 0 {
            let h = self.hole(k);
            let half = self.ring_cells as i64 / 2;
            let (di, dj) = (i - h[0], j - h[1]);
            if (0..=half).contains(&di) && (0..=half).contains(&dj) {
                return self.vertex(k - 1, 2 * di, 2 * dj);
            }
        }
        self.own(k, i, j)
    }

    /// Moves the rings to follow the local (x, z) point `center` (m; the eye). Returns true if a
    /// ring moved (the triangles were rebuilt); positions must then be re-evaluated, which
    /// [`Clipmap::displace`] does every frame anyway.
    pub fn follow(&mut self, center: Vec2) -> bool {
        let n = self.ring_cells as i64;
        let units = |v: f32| f64::from(v) / f64::from(self.spacing);
        let (cx, cz) = (units(center.x), units(center.y));
        let origins: Vec<[i64; 2]> = (0..self.levels)
            .map(|k| {
                let two = (1i64 << (k + 1)) as f64; // twice level k's spacing, in finest units
                let snap = |c: f64| {
                    // Clamped so that a wild centre (a camera thousands of km out) cannot overflow.
                    let c = c.clamp(-1e15, 1e15);
                    ((c / two).floor() as i64) * (1i64 << (k + 1)) - (n / 2) * (1i64 << k)
                };
                [snap(cx), snap(cz)]
            })
            .collect();
        if origins == self.origins {
            return false;
        }
        self.origins = origins;
        let size = Vec2::splat(self.ring_cells as f32);
        self.grids = (0..self.levels)
            .map(|k| {
                let s = self.level_spacing(k);
                let o = self.origins[k as usize];
                let origin = Vec2::new(
                    (o[0] as f64 * f64::from(self.spacing)) as f32,
                    (o[1] as f64 * f64::from(self.spacing)) as f32,
                );
                GridSpec::new(origin, size * s, self.ring_cells, self.ring_cells).expect("ring sizes are validated")
            })
            .collect();
        self.rebuild_indices();
        true
    }

    fn rebuild_indices(&mut self) {
        let n = self.ring_cells as i64;
        let half = n / 2;
        let mut indices = std::mem::take(&mut self.indices);
        indices.clear();
        for k in 0..self.levels as usize {
            let hole = if k > 0 { Some(self.hole(k)) } else { None };
            for j in 0..n {
                for i in 0..n {
                    // Corners counter-clockwise seen from +Y: (i, j), (i, j+1), (i+1, j+1), (i+1, j).
                    let quad = [(i, j), (i, j + 1), (i + 1, j + 1), (i + 1, j)];
                    let mut edge = None;
                    if let Some(h) = hole {
                        let (di, dj) = (i - h[0], j - h[1]);
                        let inside = |d: i64| (0..half).contains(&d);
                        if inside(di) && inside(dj) {
                            continue; // the finer ring covers it
                        }
                        // The quad edge lying on the hole's edge, as the index of its first corner
                        // in `quad`, and that edge's middle vertex of the finer ring.
                        if di == half && inside(dj) {
                            edge = Some((0, self.vertex(k - 1, 2 * half, 2 * dj + 1)));
                        // left edge x = i
                        } else if di == -1 && inside(dj) {
                            edge = Some((2, self.vertex(k - 1, 0, 2 * dj + 1)));
                        // right edge x = i + 1
                        } else if dj == half && inside(di) {
                            edge = Some((3, self.vertex(k - 1, 2 * di + 1, 2 * half)));
                        // near edge z = j
                        } else if dj == -1 && inside(di) {
                            edge = Some((1, self.vertex(k - 1, 2 * di + 1, 0)));
                            // far edge z = j + 1
                        }
                    }
                    let q = quad.map(|(a, b)| self.vertex(k, a, b));
                    match edge {
                        None => indices.extend_from_slice(&[q[0], q[1], q[3], q[3], q[1], q[2]]),
                        Some((e, m)) => {
                            // Fan from the middle vertex m of edge q[e] -> q[e+1].
                            let at = |d: usize| q[(e + d) % 4];
                            indices.extend_from_slice(&[m, at(1), at(2), m, at(2), at(3), m, at(3), at(0)]);
                        }
                    }
                }
            }
        }
        self.indices = indices;
    }

    /// Displaces every ring with `model` at time `t` (s), each vertex sampled by its rest position
    /// in the model's frame; allocates nothing. Call [`WaveModel::advance`] first.
    pub fn displace(&mut self, model: &dyn WaveModel, t: f64) {
        let mut has_foam = true;
        for (k, grid) in self.grids.iter().enumerate() {
            let r = self.offsets[k]..self.offsets[k] + grid.vertex_count();
            model.evaluate(grid, t, &mut self.positions[r.clone()], &mut self.normals[r.clone()]);
            has_foam &= model.foam(grid, &mut self.foam[r]);
        }
        self.has_foam = has_foam;
    }
}

#[cfg(test)]
mod tests {
    use std::collections::HashMap;

    use super::*;

    /// Rest positions of every vertex (the grids' own positions).
    fn rest(c: &Clipmap) -> Vec<Vec2> {
        let mut out = vec![Vec2::NAN; c.positions.len()];
        for (k, g) in c.grids.iter().enumerate() {
            for j in 0..g.verts_z() {
                for i in 0..g.verts_x() {
                    out[c.offsets[k] + j * g.verts_x() + i] = g.rest_position(i, j);
                }
            }
        }
        out
    }

    /// Checks the triangle list is a watertight, consistently wound cover of the outer square:
    /// every directed edge appears once, and its reverse once too unless it is on the outer
    /// boundary; the triangles' areas sum to the square's, none is degenerate or turned over.
    fn assert_watertight(c: &Clipmap) {
        let r = rest(c);
        let mut directed: HashMap<(u32, u32), u32> = HashMap::new();
        let mut area = 0.0f64;
        for t in c.indices.chunks_exact(3) {
            let [a, b, d] = [t[0], t[1], t[2]].map(|i| r[i as usize]);
            // Counter-clockwise seen from +Y with x right and z down the page: (b - a) x (d - a) < 0 in (x, z).
            let cross = f64::from((b - a).perp_dot(d - a));
            assert!(cross < 0.0, "triangle {t:?} is degenerate or turned over: {a} {b} {d}");
            area += -0.5 * cross;
            for (u, v) in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])] {
                *directed.entry((u, v)).or_default() += 1;
            }
        }
        let outer = c.grids.last().unwrap();
        let side = f64::from(outer.size.x);
        assert!((area - side * side).abs() < 1e-6 * side * side, "area {area} vs {}", side * side);
        let on_outer = |p: Vec2| {
            let (lo, hi) = (outer.origin, outer.origin + outer.size);
            p.x == lo.x || p.x == hi.x || p.y == lo.y || p.y == hi.y
        };
        for (&(u, v), &count) in &directed {
            assert_eq!(count, 1, "edge {u}->{v} used {count} times the same way");
            if !directed.contains_key(&(v, u)) {
                let (pu, pv) = (r[u as usize], r[v as usize]);
                assert!(on_outer(pu) && on_outer(pv), "open edge {pu} -> {pv} inside the mesh: a crack");
            }
        }
    }

    #[test]
    fn the_rings_are_watertight_wherever_the_camera_is() {
        let mut c = Clipmap::new(4, 16, 0.5).unwrap();
        // Every combination of odd and even snapping of the levels appears along these centres.
        for (x, z) in [(0.0, 0.0), (0.6, -0.2), (1.3, 2.9), (-3.7, 5.1), (7.9, -8.3), (123.4, -56.7), (-1e4, 3e3)] {
            c.follow(Vec2::new(x, z));
            assert_watertight(&c);
            // The centre stays in the middle of the finest ring.
            let g = c.grids[0];
            let mid = g.origin + 0.5 * g.size;
            assert!((mid - Vec2::new(x, z)).abs().max_element() <= 2.0 * 0.5 + 1e-3, "{mid} vs ({x}, {z})");
        }
    }

    #[test]
    fn vertices_stay_put_as_the_camera_moves_by_small_steps() {
        // Moving by less than a cell keeps every ring; moving further shifts rings by whole cells,
        // so every vertex of the new mesh is a vertex of the world grid of its level.
        let mut c = Clipmap::new(3, 8, 1.0).unwrap();
        assert!(!c.follow(Vec2::new(0.3, 0.3)));
        for step in 0..50 {
            let x = 0.37 * step as f32;
            c.follow(Vec2::new(x, -0.11 * step as f32));
            for (k, g) in c.grids.iter().enumerate() {
                let s = c.level_spacing(k as u32);
                assert_eq!(g.origin.x.rem_euclid(2.0 * s), 0.0);
                assert_eq!(g.origin.y.rem_euclid(2.0 * s), 0.0);
            }
            assert_watertight(&c);
        }
    }

    #[test]
    fn bad_settings_are_refused_with_the_key() {
        assert!(Clipmap::new(0, 16, 1.0).unwrap_err().to_string().contains("water.lod.levels"));
        assert!(Clipmap::new(2, 10, 1.0).unwrap_err().to_string().contains("water.lod.ring_cells"));
        assert!(Clipmap::new(2, 16, f32::NAN).unwrap_err().to_string().contains("water.lod.spacing"));
    }
}
