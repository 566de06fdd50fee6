//! A floating body's hull: a closed, outward-wound triangle mesh in the body's own frame, and the
//! mass properties of the solid it bounds.
//!
//! Everything the water does to a body is integrated over this mesh ([`super::water_forces`]), so
//! every shape, a box as much as an OBJ hull, is a closed triangle mesh here.

use glam::{DMat3, DVec3, Vec3};

use crate::error::{Error, Result};

/// Most triangles a hull may have: the water's forces are summed over every triangle each step,
/// so a finer hull costs time in proportion (a 4,096-triangle hull takes about 0.2 ms a step).
pub const MAX_HULL_TRIANGLES: usize = 4096;

/// How many times the sphere's icosahedron is subdivided: 320 triangles, whose volume is within
/// 2 % of the sphere's before [`Hull::sphere`] rescales it to the exact volume.
const SPHERE_SUBDIVISIONS: u32 = 2;

/// Segments around a capsule's axis and rings over each of its hemispherical ends.
const CAPSULE_SEGMENTS: u32 = 16;
const CAPSULE_RINGS: u32 = 4;

/// A box face: its outward axis and its two in-plane axes, each as (axis index, sign).
type FaceAxes = (Vec3, (usize, f32), (usize, f32));

/// A closed triangle mesh, wound counter-clockwise seen from outside (outward normals), in metres
/// in the body's frame.
#[derive(Clone, Debug, PartialEq)]
pub struct Hull {
    /// Vertex positions, m.
    pub positions: Vec<Vec3>,
    /// Three indices into `positions` per triangle.
    pub triangles: Vec<[u32; 3]>,
}

/// Volume, centroid and inertia of a solid of uniform density 1 kg/m³: multiply by the density
/// for the body's mass and inertia.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MassProperties {
    /// Volume, m³, > 0.
    pub volume: f64,
    /// Centroid (centre of mass at uniform density), m, in the hull's frame.
    pub centroid: DVec3,
    /// Inertia tensor about the centroid per unit density, m⁵ (kg·m² once multiplied by kg/m³).
    pub inertia: DMat3,
}

impl Hull {
    /// An axis-aligned box of full extents `size` (m) centred on the origin, its edges along X, Y
    /// and Z split into `split[0]`, `split[1]` and `split[2]` (>= 1) equal parts, so that the water
    /// is sampled across a large face and not only at its corners (a barge on a short wave).
    pub fn cuboid(size: Vec3, split: [u32; 3]) -> Self {
        let h = size * 0.5;
        let mut hull = Hull { positions: Vec::new(), triangles: Vec::new() };
        // Each face: an outward axis and two in-plane axes (index, sign) with u x v = outward, so the
        // winding (u, then v) is counter-clockwise seen from outside.
        let faces: [FaceAxes; 6] = [
            (Vec3::X, (2, -1.0), (1, 1.0)),
            (Vec3::NEG_X, (2, 1.0), (1, 1.0)),
            (Vec3::Y, (0, 1.0), (2, -1.0)),
            (Vec3::NEG_Y, (0, 1.0), (2, 1.0)),
            (Vec3::Z, (0, 1.0), (1, 1.0)),
            (Vec3::NEG_Z, (0, -1.0), (1, 1.0)),
        ];
        for (out, (ui, us), (vi, vs)) in faces {
            let (nu, nv) = (split[ui].max(1), split[vi].max(1));
            let base = hull.positions.len() as u32;
            // Coordinates from one table per axis, so that the faces meeting at an edge put its
            // vertices at the same bits and they weld.
            let at = |axis: usize, sign: f32, k: u32, n: u32| {
                let k = if sign < 0.0 { n - k } else { k };
                (k as f32 / n as f32 * 2.0 - 1.0) * h[axis]
            };
            for j in 0..=nv {
                for i in 0..=nu {
                    let mut p = out * h;
                    p[ui] = at(ui, us, i, nu);
                    p[vi] = at(vi, vs, j, nv);
                    hull.positions.push(p);
                }
            }
            let row = nu + 1;
            for j in 0..nv {
                for i in 0..nu {
                    let k = base + j * row + i;
                    hull.triangles.push([k, k + 1, k + row + 1]);
                    hull.triangles.push([k, k + row + 1, k + row]);
                }
            }
        }
        hull.weld();
        hull
    }

    /// A sphere of `radius` (m) about the origin: a subdivided icosahedron scaled so that its
    /// volume is the sphere's, 4/3 π r³, so that it floats at the sphere's draft.
    pub fn sphere(radius: f32) -> Self {
        let t = (1.0 + 5.0f32.sqrt()) / 2.0;
        let mut positions: Vec<Vec3> = [
            [-1.0, t, 0.0],
            [1.0, t, 0.0],
            [-1.0, -t, 0.0],
            [1.0, -t, 0.0],
            [0.0, -1.0, t],
            [0.0, 1.0, t],
            [0.0, -1.0, -t],
            [0.0, 1.0, -t],
            [t, 0.0, -1.0],
            [t, 0.0, 1.0],
            [-t, 0.0, -1.0],
            [-t, 0.0, 1.0],
        ]
        .iter()
        .map(|p| Vec3::from_array(*p).normalize())
        .collect();
        let mut triangles: Vec<[u32; 3]> = vec![
            [0, 11, 5],
            [0, 5, 1],
            [0, 1, 7],
            [0, 7, 10],
            [0, 10, 11],
            [1, 5, 9],
            [5, 11, 4],
            [11, 10, 2],
            [10, 7, 6],
            [7, 1, 8],
            [3, 9, 4],
            [3, 4, 2],
            [3, 2, 6],
            [3, 6, 8],
            [3, 8, 9],
            [4, 9, 5],
            [2, 4, 11],
            [6, 2, 10],
            [8, 6, 7],
            [9, 8, 1],
        ];
        for _ in 0..SPHERE_SUBDIVISIONS {
            let mut midpoints = std::collections::HashMap::new();
            let mut mid = |a: u32, b: u32, positions: &mut Vec<Vec3>| -> u32 {
                *midpoints.entry((a.min(b), a.max(b))).or_insert_with(|| {
                    positions.push(((positions[a as usize] + positions[b as usize]) * 0.5).normalize());
                    positions.len() as u32 - 1
                })
            };
            let mut next = Vec::with_capacity(triangles.len() * 4);
            for [a, b, c] in triangles {
                let (ab, bc, ca) = (mid(a, b, &mut positions), mid(b, c, &mut positions), mid(c, a, &mut positions));
                next.extend([[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
            }
            triangles = next;
        }
        let mut hull = Hull { positions, triangles };
        let unit_volume = hull.signed_volume();
        let exact = 4.0 / 3.0 * std::f64::consts::PI;
        let scale = radius * (exact / unit_volume).cbrt() as f32;
        hull.positions.iter_mut().for_each(|p| *p *= scale);
        hull
    }

    /// A capsule: a cylinder of `radius` and `length` (m, between the centres of its two
    /// hemispherical ends) along the body's X axis (a hull's length runs fore and aft), centred on
    /// the origin. `length` 0 is a sphere.
    pub fn capsule(radius: f32, length: f32) -> Self {
        let (segments, rings) = (CAPSULE_SEGMENTS, CAPSULE_RINGS);
        let mut positions = Vec::new();
        // Rings from the -X pole to the +X pole: `rings` on each cap, the two equators included
        // once each, so the cylinder is the band between the caps' equators.
        let mut ring_xr = Vec::new();
        for k in 1..=rings {
            let a = std::f32::consts::FRAC_PI_2 * (1.0 - k as f32 / rings as f32);
            ring_xr.push((-0.5 * length - radius * a.sin(), radius * a.cos()));
        }
        for k in 0..rings {
            let a = std::f32::consts::FRAC_PI_2 * (k as f32 / rings as f32);
            ring_xr.push((0.5 * length + radius * a.sin(), radius * a.cos()));
        }
        positions.push(Vec3::new(-0.5 * length - radius, 0.0, 0.0));
        for &(x, r) in &ring_xr {
            for s in 0..segments {
                let a = std::f32::consts::TAU * s as f32 / segments as f32;
                positions.push(Vec3::new(x, r * a.cos(), r * a.sin()));
            }
        }
        positions.push(Vec3::new(0.5 * length + radius, 0.0, 0.0));
        let last = positions.len() as u32 - 1;
        let ring = |k: u32, s: u32| 1 + k * segments + s % segments;
        let mut triangles = Vec::new();
        // Seen from -X, the angle a runs clockwise, so the caps and bands wind as below to face out.
        for s in 0..segments {
            triangles.push([0, ring(0, s + 1), ring(0, s)]);
        }
        for k in 0..ring_xr.len() as u32 - 1 {
            for s in 0..segments {
                let (a, b, c, d) = (ring(k, s), ring(k, s + 1), ring(k + 1, s + 1), ring(k + 1, s));
                triangles.push([a, b, c]);
                triangles.push([a, c, d]);
            }
        }
        let top = ring_xr.len() as u32 - 1;
        for s in 0..segments {
            triangles.push([last, ring(top, s), ring(top, s + 1)]);
        }
        Hull { positions, triangles }
    }

    /// A hull from a triangle mesh (an OBJ file's, metres, +Y up), `source` naming it in errors.
    /// Vertices at the same position are merged (an OBJ repeats a corner once per normal); the
    /// mesh must then be closed and consistently wound: every edge shared by exactly two
    /// triangles that run along it in opposite directions. A mesh wound inside out is turned.
    pub fn from_mesh(positions: &[Vec3], indices: &[u32], source: &str) -> Result<Self> {
        let refuse = |why: String| Error::invalid(source, why);
        if indices.is_empty() || !indices.len().is_multiple_of(3) {
            return Err(refuse(format!("{} indices is not a whole number of triangles (>= 4 needed)", indices.len())));
        }
        if indices.len() / 3 > MAX_HULL_TRIANGLES {
            return Err(Error::out_of_range(
                format!("{source}: triangles"),
                indices.len() / 3,
                format!("[4, {MAX_HULL_TRIANGLES}] (simplify the hull)"),
            ));
        }
        if let Some(p) = positions.iter().find(|p| !p.is_finite()) {
            return Err(refuse(format!("vertex {p} is not finite")));
        }
        let mut triangles = Vec::with_capacity(indices.len() / 3);
        for t in indices.chunks_exact(3) {
            if t.iter().any(|&i| i as usize >= positions.len()) {
                return Err(refuse(format!("triangle {t:?} names a vertex past the {} given", positions.len())));
            }
            triangles.push([t[0], t[1], t[2]]);
        }
        let mut hull = Hull { positions: positions.to_vec(), triangles };
        hull.weld();
        hull.check_closed(source)?;
        let volume = hull.signed_volume();
        let (lo, hi) = hull.bounds();
        let span = f64::from((hi - lo).max_element());
        if volume.abs() <= 1e-9 * span.powi(3) || !volume.is_finite() {
            return Err(refuse(format!("the closed mesh encloses no volume ({volume:.3e} m³)")));
        }
        if volume < 0.0 {
            hull.triangles.iter_mut().for_each(|t| t.swap(1, 2));
        }
        Ok(hull)
    }

    /// Merges vertices at exactly the same position and drops triangles left with a repeated
    /// corner (zero area).
    fn weld(&mut self) {
        let mut first = std::collections::HashMap::new();
        let mut map = Vec::with_capacity(self.positions.len());
        let mut kept = Vec::new();
        for p in &self.positions {
            let key = p.to_array().map(f32::to_bits);
            let k = *first.entry(key).or_insert_with(|| {
                kept.push(*p);
                kept.len() as u32 - 1
            });
            map.push(k);
        }
        self.positions = kept;
        self.triangles = self
            .triangles
            .iter()
            .map(|t| t.map(|i| map[i as usize]))
            .filter(|[a, b, c]| a != b && b != c && c != a)
            .collect();
    }

    /// Refuses a mesh with a boundary edge, an edge shared by more than two triangles or two
    /// triangles wound against each other: the water's pressure summed over it would not be a
    /// volume's.
    fn check_closed(&self, source: &str) -> Result<()> {
        let mut edges = std::collections::HashMap::new();
        for t in &self.triangles {
            for k in 0..3 {
                *edges.entry((t[k], t[(k + 1) % 3])).or_insert(0u32) += 1;
            }
        }
        for (&(a, b), &n) in &edges {
            let back = edges.get(&(b, a)).copied().unwrap_or(0);
            if n != 1 || back != 1 {
                let (pa, pb) = (self.positions[a as usize], self.positions[b as usize]);
                let why = if back == 0 {
                    "a hole: the edge belongs to one triangle only (the mesh must be closed)"
                } else if n > 1 {
                    "triangles wound against each other, or more than two triangles on one edge"
                } else {
                    "more than two triangles on one edge"
                };
                return Err(Error::invalid(source, format!("edge {pa} - {pb}: {why}")));
            }
        }
        Ok(())
    }

    /// Smallest and largest corner of the axis-aligned box around the vertices, m.
    pub fn bounds(&self) -> (Vec3, Vec3) {
        self.positions
            .iter()
            .fold((Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)), |(lo, hi), p| (lo.min(*p), hi.max(*p)))
    }

    /// The same hull moved by `offset` (m).
    pub fn translated(mut self, offset: Vec3) -> Self {
        self.positions.iter_mut().for_each(|p| *p += offset);
        self
    }

    /// Largest distance (m) of a vertex from the origin.
    pub fn radius(&self) -> f32 {
        self.positions.iter().map(|p| p.length()).fold(0.0, f32::max)
    }

    /// Enclosed volume (m³), positive for outward winding.
    fn signed_volume(&self) -> f64 {
        self.triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| self.positions[i as usize].as_dvec3());
                a.dot(b.cross(c)) / 6.0
            })
            .sum()
    }

    /// Volume, centroid and inertia of the enclosed solid at unit density, summed over the
    /// tetrahedra from the origin to each triangle (Mirtich 1996, "Fast and accurate computation
    /// of polyhedral mass properties"; the tetrahedron covariance as in Eberly, "Polyhedral Mass
    /// Properties (Revisited)", 2002), in `f64`.
    pub fn mass_properties(&self) -> MassProperties {
        let mut volume = 0.0;
        let mut first = DVec3::ZERO;
        // Covariance ∫ r rᵀ dV about the origin.
        let mut covariance = DMat3::ZERO;
        for t in &self.triangles {
            let [a, b, c] = t.map(|i| self.positions[i as usize].as_dvec3());
            let v = a.dot(b.cross(c)) / 6.0;
            let s = a + b + c;
            volume += v;
            first += v * s / 4.0;
            let outer = |p: DVec3| DMat3::from_cols(p * p.x, p * p.y, p * p.z);
            covariance += (outer(a) + outer(b) + outer(c) + outer(s)) * (v / 20.0);
        }
        let centroid = first / volume;
        // About the centroid (parallel axes), then I = tr(C) 1 - C.
        let c =
            covariance - DMat3::from_cols(centroid * centroid.x, centroid * centroid.y, centroid * centroid.z) * volume;
        let trace = c.x_axis.x + c.y_axis.y + c.z_axis.z;
        let inertia = DMat3::from_diagonal(DVec3::splat(trace)) - c;
        MassProperties { volume, centroid, inertia }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a - b).abs() <= tol * b.abs().max(1e-12)
    }

    #[test]
    fn a_box_has_the_closed_form_volume_and_inertia() {
        let (x, y, z) = (1.0, 0.5, 2.0);
        for split in [[1, 1, 1], [3, 2, 5]] {
            let h = Hull::cuboid(Vec3::new(x, y, z), split);
            h.check_closed("box").unwrap();
            let m = h.mass_properties();
            let v = f64::from(x * y * z);
            assert!(close(m.volume, v, 1e-6), "{}", m.volume);
            assert!(m.centroid.length() < 1e-6);
            let i = |a: f32, b: f32| v * f64::from(a * a + b * b) / 12.0;
            assert!(close(m.inertia.x_axis.x, i(y, z), 1e-5));
            assert!(close(m.inertia.y_axis.y, i(x, z), 1e-5));
            assert!(close(m.inertia.z_axis.z, i(x, y), 1e-5));
            assert!(m.inertia.x_axis.y.abs() < 1e-6);
        }
    }

    #[test]
    fn a_sphere_has_the_sphere_s_volume_and_nearly_its_inertia() {
        let h = Hull::sphere(0.7);
        h.check_closed("sphere").unwrap();
        let m = h.mass_properties();
        let v = 4.0 / 3.0 * std::f64::consts::PI * 0.7f64.powi(3);
        assert!(close(m.volume, v, 1e-6));
        assert!(close(m.inertia.y_axis.y, 0.4 * v * 0.49, 0.02), "{}", m.inertia.y_axis.y);
    }

    #[test]
    fn a_capsule_is_closed_and_has_about_its_volume() {
        let h = Hull::capsule(0.3, 1.2);
        h.check_closed("capsule").unwrap();
        let m = h.mass_properties();
        let v = std::f64::consts::PI * 0.09 * (1.2 + 0.4);
        assert!(close(m.volume, v, 0.05), "{} vs {v}", m.volume);
        // Longest along X: least inertia about X.
        assert!(m.inertia.x_axis.x < m.inertia.y_axis.y);
    }

    #[test]
    fn open_and_inside_out_meshes_are_refused_or_turned() {
        let b = Hull::cuboid(Vec3::ONE, [1, 1, 1]);
        let mut flat: Vec<u32> = b.triangles.iter().flatten().copied().collect();
        // Inside out: turned, the same volume.
        let turned: Vec<u32> = b.triangles.iter().flat_map(|t| [t[0], t[2], t[1]]).collect();
        let h = Hull::from_mesh(&b.positions, &turned, "in.obj").unwrap();
        assert!(close(h.mass_properties().volume, 1.0, 1e-6));
        // A hole.
        flat.truncate(flat.len() - 3);
        let e = Hull::from_mesh(&b.positions, &flat, "open.obj").unwrap_err().to_string();
        assert!(e.contains("open.obj") && e.contains("closed"), "{e}");
        // One face flipped.
        let mut bad: Vec<u32> = b.triangles.iter().flatten().copied().collect();
        bad.swap(1, 2);
        let e = Hull::from_mesh(&b.positions, &bad, "flip.obj").unwrap_err().to_string();
        assert!(e.contains("flip.obj"), "{e}");
        assert!(Hull::from_mesh(&[Vec3::NAN; 3], &[0, 1, 2], "nan.obj").is_err());
    }
}
