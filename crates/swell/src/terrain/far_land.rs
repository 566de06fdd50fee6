//! Land beyond a height field, to the horizon: coarse rings around the field whose first ring is the
//! field's own border, so that a terrain scene does not end in a void (issue 18, item 5).
//!
//! **Shape.** Outside the field the land continues the field's edge (each point takes the height of
//! the nearest edge point, [`HeightField::height_at`]), so a beach stays a beach, a valley stays a
//! valley and a sea floor stays a sea floor, and far hills of fractional Brownian motion (Perlin
//! 2002, [`Perlin`]) rise out of it: `h = e + relief * ramp(d) * wet(e) * hills(x, z)`, where `d` is
//! the distance outside the field, `ramp` a smoothstep from 0 at the edge to 1 at `feature_size`
//! (so the land leaves the field without a crease), `wet` shrinks the hills under the water at rest
//! (to nothing `relief` metres deep, so a continued sea floor does not rise into a chain of
//! islands) and `hills` lies in [0, 1].
//!
//! **Mesh.** Ring 0 is the field's border vertices, bit for bit as the field's mesh has them; ring
//! k lies `d_k` metres outside the field's rectangle, the distances growing geometrically to
//! `reach` (Crest's and GPU Gems 2's geometry clipmaps grow their rings the same way: a ring covers
//! about the same part of the image whatever its distance). Each side of a ring has at most as many
//! segments as the side inside it, about one per radial step, and neighbouring rings are joined
//! side by side by a "zipper" that only uses both rings' vertices: no T-junction, so no crack
//! between the field and the far land nor between rings. Octaves of the hills finer than a ring's
//! spacing are left out there (a low-pass filter, so far land does not alias into spikes).
//!
//! Everything is a function of the field and the parameters, computed in order on one thread:
//! the same mesh on any thread count.

use glam::{Vec2, Vec3};
use serde::{Deserialize, Serialize};

use super::diamond_square::MAX_AMPLITUDE;
use super::HeightField;
use crate::error::{check_range, check_seed, Result};
use crate::math::Perlin;

/// Largest `reach` (m): 1000 km, far beyond any horizon a camera near the ground sees.
pub const MAX_FAR_LAND_REACH: f32 = 1.0e6;

/// Most rings outside the field (the geometric growth reaches any `reach` well within this).
pub const MAX_FAR_LAND_RINGS: usize = 48;

/// Ratio between successive radial steps of the rings.
const GROWTH: f32 = 1.4;

/// First radial step, in field spacings: close enough that the field's border detail carries
/// into the first ring.
const FIRST_STEP_SPACINGS: f32 = 2.0;

/// Fewest segments on a side of a ring: keeps the ring a rectangle.
const MIN_SIDE_SEGMENTS: usize = 2;

/// Octaves of the far hills (each half the size of the previous one, half as high).
const HILL_OCTAVES: u32 = 5;

/// Parameters of the land beyond the field: `[terrain.far_land]`. Present (even empty) turns the
/// far land on.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct FarLandParams {
    /// Distance (m, before the terrain's transform) from the field's edge to the outermost ring,
    /// in [1, 1e6]. Default 8000. Beyond it the renderer continues the outermost ring's heights
    /// to the horizon as a flat, hazed band.
    pub reach: f32,
    /// Height (m) of the far hills above the continued edge, in [0, 1e5]. Default 30.
    pub relief: f32,
    /// Horizontal size (m) of the largest far hills, which is also the distance over which they
    /// grow out of the field's edge, in [1, 1e6]. Default 500.
    pub feature_size: f32,
    /// Seed of the hills' noise, in [0, 2^63 - 1]. Default 1.
    pub seed: u64,
}

impl Default for FarLandParams {
    fn default() -> Self {
        Self { reach: 8000.0, relief: 30.0, feature_size: 500.0, seed: 1 }
    }
}

impl FarLandParams {
    /// Checks every field, naming keys under `key` (normally `terrain.far_land`).
    pub fn validate(&self, key: &str) -> Result<()> {
        check_range(&format!("{key}.reach"), self.reach, 1.0, MAX_FAR_LAND_REACH)?;
        check_range(&format!("{key}.relief"), self.relief, 0.0, MAX_AMPLITUDE)?;
        check_range(&format!("{key}.feature_size"), self.feature_size, 1.0, MAX_FAR_LAND_REACH)?;
        check_seed(&format!("{key}.seed"), self.seed)
    }

    /// Height (m) of the far land at model (x, z), `spacing` metres between its vertices there
    /// (octaves finer than about two spacings are left out). Inside the field: the field's height.
    pub fn height_at(&self, field: &HeightField, noise: &Perlin, x: f32, z: f32, spacing: f32) -> f32 {
        let edge = field.height_at(x, z);
        let half = 0.5 * field.extent();
        let outside = Vec2::new((x.abs() - half.x).max(0.0), (z.abs() - half.y).max(0.0)).length();
        if outside <= 0.0 || self.relief <= 0.0 {
            return edge;
        }
        let t = (outside / self.feature_size).min(1.0);
        let ramp = t * t * (3.0 - 2.0 * t);
        let wet = ((edge + self.relief) / self.relief).clamp(0.0, 1.0);
        edge + self.relief * ramp * wet * self.hills(noise, x, z, spacing)
    }

    /// The far hills' shape at model (x, z), in [0, 1]: fBm normalised by the weight of all its
    /// octaves, each octave faded out as its wavelength nears two `spacing`s.
    fn hills(&self, noise: &Perlin, x: f32, z: f32, spacing: f32) -> f32 {
        let (mut sum, mut norm) = (0.0, 0.0);
        let (mut amplitude, mut wavelength) = (1.0f32, self.feature_size);
        for octave in 0..HILL_OCTAVES {
            let weight = (wavelength / (2.0 * spacing) - 1.0).clamp(0.0, 1.0);
            // Offset each octave so that lattice zeros of different octaves do not line up.
            let shift = octave as f32 * 19.19;
            sum += weight * amplitude * noise.noise2(x / wavelength + shift, z / wavelength - shift);
            norm += amplitude;
            amplitude *= 0.5;
            wavelength *= 0.5;
        }
        // Improved noise's fBm rarely leaves ±0.6 of its normaliser: map that to [0, 1].
        (0.5 + 0.8 * sum / norm).clamp(0.0, 1.0)
    }
}

/// The far land's mesh in the field's model space: rings of vertices around the field.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct FarLandMesh {
    /// Model positions, metres: ring 0 (the field's border, in loop order) first, then each ring
    /// outwards.
    pub positions: Vec<Vec3>,
    /// Unit model normals, one per position; ring 0 has the field's own normals, so the shading
    /// is continuous across the seam.
    pub normals: Vec<Vec3>,
    /// Three indices per triangle, counter-clockwise seen from above (as the field's mesh).
    pub indices: Vec<u32>,
    /// Index of the first vertex of the outermost ring; that ring runs to the end of `positions`,
    /// in the same loop order as every ring (north side west to east, east side north to south,
    /// south side east to west, west side south to north; north is −Z).
    pub outer_start: usize,
}

/// One ring: how far outside the field and how many segments on its x sides and z sides.
#[derive(Clone, Copy, Debug)]
struct Ring {
    distance: f32,
    segments_x: usize,
    segments_z: usize,
    first: usize,
}

impl Ring {
    fn len(&self) -> usize {
        2 * (self.segments_x + self.segments_z)
    }

    /// Loop index of the first vertex of side `s` (0 north, 1 east, 2 south, 3 west).
    fn side_start(&self, s: usize) -> usize {
        match s {
            0 => 0,
            1 => self.segments_x,
            2 => self.segments_x + self.segments_z,
            _ => 2 * self.segments_x + self.segments_z,
        }
    }

    fn side_segments(&self, s: usize) -> usize {
        if s == 0 || s == 2 {
            self.segments_x
        } else {
            self.segments_z
        }
    }

    /// Vertex index of loop position `k` (wrapping: the loop is closed).
    fn vertex(&self, k: usize) -> u32 {
        (self.first + k % self.len()) as u32
    }
}

/// Builds the far land around `field` (checked parameters; `params` are validated here too).
pub fn far_land(field: &HeightField, params: &FarLandParams) -> Result<FarLandMesh> {
    params.validate("terrain.far_land")?;
    let noise = Perlin::new(params.seed);
    let spacing = field.spacing();
    let half = 0.5 * field.extent();
    let rings = ring_layout(field, params);
    let mut mesh = FarLandMesh::default();
    // Ring 0: the field's border vertices, exactly as HeightField::write_vertices makes them.
    for (i, j) in border_loop(field.cols(), field.rows()) {
        let xz = field.model_xz(i, j);
        mesh.positions.push(Vec3::new(xz.x, field.height(i, j), xz.y));
        mesh.normals.push(field.normal(i, j));
    }
    for pair in rings.windows(2) {
        let (inner, ring) = (pair[0], pair[1]);
        let step = ring.distance - inner.distance;
        let (hx, hz) = (half.x + ring.distance, half.y + ring.distance);
        for s in 0..4 {
            let n = ring.side_segments(s);
            // Corners of side s in loop order: (-,-) -> (+,-) -> (+,+) -> (-,+) -> back.
            let corners = [Vec2::new(-hx, -hz), Vec2::new(hx, -hz), Vec2::new(hx, hz), Vec2::new(-hx, hz)];
            let (a, b) = (corners[s], corners[(s + 1) % 4]);
            for k in 0..n {
                let xz = a.lerp(b, k as f32 / n as f32);
                let y = params.height_at(field, &noise, xz.x, xz.y, step.max(spacing.max_element()));
                mesh.positions.push(Vec3::new(xz.x, y, xz.y));
            }
        }
        zip_rings(&inner, &ring, &mut mesh.indices);
    }
    mesh.outer_start = rings.last().map_or(0, |r| r.first);
    let border = rings[0].len();
    mesh.normals.resize(mesh.positions.len(), Vec3::ZERO);
    accumulate_normals(&mut mesh, border);
    Ok(mesh)
}

/// The rings' distances and side segment counts, ring 0 (the border) first.
fn ring_layout(field: &HeightField, params: &FarLandParams) -> Vec<Ring> {
    let spacing = field.spacing().max_element();
    let extent = field.extent();
    let first_step = (FIRST_STEP_SPACINGS * spacing).min(params.reach);
    // Rings: d_k = first_step (g^k - 1) / (g - 1) until reach, the last one moved out to reach.
    let mut distances = vec![0.0f32];
    let mut step = first_step;
    while distances.len() <= MAX_FAR_LAND_RINGS {
        let last = *distances.last().unwrap_or(&0.0);
        if last + step >= params.reach || distances.len() == MAX_FAR_LAND_RINGS {
            distances.push(params.reach);
            break;
        }
        distances.push(last + step);
        step *= GROWTH;
    }
    let mut rings = vec![Ring { distance: 0.0, segments_x: field.cols() - 1, segments_z: field.rows() - 1, first: 0 }];
    for k in 1..distances.len() {
        let prev = rings[k - 1];
        let (d, radial) = (distances[k], distances[k] - distances[k - 1]);
        // About one segment per radial step along each side, never more than the ring inside
        // (unless that is below the minimum).
        let count = |length: f32, inside: usize| {
            ((length / radial).ceil() as usize).clamp(MIN_SIDE_SEGMENTS, inside.max(MIN_SIDE_SEGMENTS))
        };
        let segments_x = count(extent.x + 2.0 * d, prev.segments_x);
        let segments_z = count(extent.y + 2.0 * d, prev.segments_z);
        rings.push(Ring { distance: d, segments_x, segments_z, first: prev.first + prev.len() });
    }
    rings
}

/// Grid (i, j) of the field's border vertices in loop order (see [`FarLandMesh::outer_start`]):
/// row 0 west to east, column cols-1 north to south, row rows-1 east to west, column 0 south to
/// north; each corner once.
fn border_loop(cols: usize, rows: usize) -> impl Iterator<Item = (usize, usize)> {
    let (ci, rj) = (cols - 1, rows - 1);
    let north = (0..ci).map(|i| (i, 0));
    let east = (0..rj).map(move |j| (ci, j));
    let south = (0..ci).map(move |i| (ci - i, rj));
    let west = (0..rj).map(move |j| (0, rj - j));
    north.chain(east).chain(south).chain(west)
}

/// Joins `inner` to `outer` side by side: along each side the two polylines (corner to corner)
/// are walked together, always advancing the one whose next vertex is nearer the start in the
/// side's parameter, so every triangle uses an edge of one ring and a vertex of the other and the
/// rings share their edges with the strip: watertight.
fn zip_rings(inner: &Ring, outer: &Ring, indices: &mut Vec<u32>) {
    for s in 0..4 {
        let (m, n) = (inner.side_segments(s), outer.side_segments(s));
        let (a0, b0) = (inner.side_start(s), outer.side_start(s));
        let (mut i, mut j) = (0, 0);
        while i < m || j < n {
            // Advance the inner ring when its next vertex comes first: (i + 1) / m <= (j + 1) / n.
            let advance_inner = j == n || (i < m && (i + 1) * n <= (j + 1) * m);
            if advance_inner {
                indices.extend([inner.vertex(a0 + i), inner.vertex(a0 + i + 1), outer.vertex(b0 + j)]);
                i += 1;
            } else {
                indices.extend([inner.vertex(a0 + i), outer.vertex(b0 + j + 1), outer.vertex(b0 + j)]);
                j += 1;
            }
        }
    }
}

/// Vertex normals beyond ring 0 (its first `border` vertices keep the field's): the sum of the
/// face normals around each vertex, area-weighted, normalised (up where they cancel).
fn accumulate_normals(mesh: &mut FarLandMesh, border: usize) {
    let mut sums = vec![Vec3::ZERO; mesh.positions.len()];
    for t in mesh.indices.chunks_exact(3) {
        let (a, b, c) = (t[0] as usize, t[1] as usize, t[2] as usize);
        let (pa, pb, pc) = (mesh.positions[a], mesh.positions[b], mesh.positions[c]);
        let n = (pb - pa).cross(pc - pa);
        for v in [a, b, c] {
            sums[v] += n;
        }
    }
    for (n, s) in mesh.normals.iter_mut().zip(sums).skip(border) {
        *n = s.normalize_or(Vec3::Y);
    }
}

#[cfg(test)]
mod tests {
    use std::collections::HashMap;

    use super::*;

    fn field() -> HeightField {
        HeightField::from_fn(33, 17, Vec2::new(64.0, 48.0), |x, z| 0.1 * x - 0.05 * z + 2.0).unwrap()
    }

    #[test]
    fn ring_zero_is_the_fields_border_bit_for_bit() {
        let f = field();
        let m = far_land(&f, &FarLandParams::default()).unwrap();
        let border: Vec<Vec3> = border_loop(f.cols(), f.rows())
            .map(|(i, j)| {
                let xz = f.model_xz(i, j);
                Vec3::new(xz.x, f.height(i, j), xz.y)
            })
            .collect();
        assert_eq!(border.len(), 2 * (32 + 16));
        for (k, p) in border.iter().enumerate() {
            assert_eq!(m.positions[k].to_array().map(f32::to_bits), p.to_array().map(f32::to_bits), "vertex {k}");
        }
    }

    /// Every edge of the far land is shared by two triangles, except the field's border (ring 0,
    /// shared with the field's mesh) and the outermost ring: no cracks, no T-junctions.
    #[test]
    fn the_rings_are_watertight_and_wind_up() {
        let f = field();
        let m = far_land(&f, &FarLandParams { reach: 3000.0, ..Default::default() }).unwrap();
        let border = 2 * (32 + 16);
        let mut edges: HashMap<(u32, u32), i32> = HashMap::new();
        for t in m.indices.chunks_exact(3) {
            for (a, b) in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])] {
                // Directed edges: a closed, consistently wound surface has each once each way.
                *edges.entry((a, b)).or_default() += 1;
            }
            let (a, b, c) = (m.positions[t[0] as usize], m.positions[t[1] as usize], m.positions[t[2] as usize]);
            assert!((b - a).cross(c - a).y > 0.0, "triangle {t:?} winds clockwise seen from above");
        }
        let outer = m.outer_start as u32;
        for (&(a, b), &count) in &edges {
            assert_eq!(count, 1, "edge {a}-{b} used {count} times the same way");
            let opposite = edges.contains_key(&(b, a));
            let on_rim = ((a as usize) < border && (b as usize) < border) || (a >= outer && b >= outer);
            assert!(opposite || on_rim, "edge {a}-{b} is open inside the far land");
        }
        // Every border segment and every outer segment is an edge once.
        let rims = edges.keys().filter(|&&(a, b)| !edges.contains_key(&(b, a))).count();
        assert_eq!(rims, border + (m.positions.len() - m.outer_start));
    }

    #[test]
    fn the_land_continues_the_edge_and_reaches_out() {
        let f = field();
        let p = FarLandParams { reach: 2000.0, relief: 0.0, ..Default::default() };
        let m = far_land(&f, &p).unwrap();
        // Without hills every vertex has the height of the nearest edge point.
        for q in &m.positions {
            assert!((q.y - f.height_at(q.x, q.z)).abs() < 1e-4, "{q}");
        }
        let far = m.positions[m.outer_start..].iter().map(|q| q.x.abs().max(q.z.abs())).fold(f32::MAX, f32::min);
        assert!((far - (2000.0 + 24.0)).abs() < 1e-2, "outer ring at {far}");
        assert!(m.positions.iter().chain(&m.normals).all(|v| v.is_finite()));
        assert!(m.indices.len() / 3 < 4000, "{} triangles", m.indices.len() / 3);
    }

    #[test]
    fn hills_rise_on_land_and_not_from_a_deep_sea_floor() {
        let f = HeightField::from_fn(17, 17, Vec2::splat(100.0), |x, _| if x < 0.0 { -40.0 } else { 5.0 }).unwrap();
        let p = FarLandParams { relief: 30.0, feature_size: 200.0, ..Default::default() };
        let m = far_land(&f, &p).unwrap();
        let rose = m.positions.iter().filter(|q| q.x > 60.0 && q.z.abs() < 40.0).any(|q| q.y > 8.0);
        assert!(rose, "no hills on the land side");
        for q in m.positions.iter().filter(|q| q.x < -60.0) {
            assert_eq!(q.y, -40.0, "the sea floor rose at {q}");
        }
    }

    #[test]
    fn bad_keys_are_named_with_their_range() {
        let e = FarLandParams { reach: 0.0, ..Default::default() }.validate("terrain.far_land").unwrap_err();
        assert_eq!(e.to_string(), "terrain.far_land.reach = 0 is outside [1, 1000000]");
        let e = FarLandParams { relief: f32::NAN, ..Default::default() }.validate("terrain.far_land").unwrap_err();
        assert!(e.to_string().starts_with("terrain.far_land.relief = NaN"), "{e}");
        let e = FarLandParams { feature_size: -3.0, ..Default::default() }.validate("k").unwrap_err();
        assert_eq!(e.to_string(), "k.feature_size = -3 is outside [1, 1000000]");
    }

    #[test]
    fn a_two_by_two_field_still_has_far_land() {
        let f = HeightField::from_fn(2, 2, Vec2::splat(1.0), |_, _| 0.0).unwrap();
        let m = far_land(&f, &FarLandParams::default()).unwrap();
        assert!(m.indices.len() >= 3 * 8 && m.positions.iter().all(|p| p.is_finite()));
    }
}
