//! A displaced regular grid with per-vertex normals, uv and a triangle list.

use glam::{Vec2, Vec3};

use crate::math::GridSpec;
use crate::water::WaveModel;

/// A regular grid of vertices over a [`GridSpec`], with buffers a [`WaveModel`] writes each frame.
///
/// Triangles wind counter-clockwise seen from +Y (OpenGL's front face), two per cell. The index
/// buffer and uv never change after [`SurfaceMesh::new`]; only positions and normals do.
#[derive(Clone, Debug)]
pub struct SurfaceMesh {
    /// The grid the vertices rest on.
    pub grid: GridSpec,
    /// World positions in metres, row-major (see [`GridSpec`]).
    pub positions: Vec<Vec3>,
    /// Unit normals, one per vertex.
    pub normals: Vec<Vec3>,
    /// Texture coordinates in [0, 1]^2: u along +X, v along +Z.
    pub uvs: Vec<Vec2>,
    /// Triangle list, three vertex indices per triangle.
    pub indices: Vec<u32>,
    /// Foam coverage in [0, 1] per vertex; all zero unless the model reports foam.
    pub foam: Vec<f32>,
    /// Whether the last [`SurfaceMesh::displace`] came with foam from the model.
    pub has_foam: bool,
}

impl SurfaceMesh {
    /// A flat mesh at rest (y = 0, normals +Y) over `grid`.
    pub fn new(grid: GridSpec) -> Self {
        let (nx, nz) = (grid.verts_x(), grid.verts_z());
        let mut positions = Vec::with_capacity(grid.vertex_count());
        let mut uvs = Vec::with_capacity(grid.vertex_count());
        for j in 0..nz {
            for i in 0..nx {
                let r = grid.rest_position(i, j);
                positions.push(Vec3::new(r.x, 0.0, r.y));
                uvs.push(Vec2::new(i as f32 / grid.cells_x as f32, j as f32 / grid.cells_z as f32));
            }
        }
        let mut indices = Vec::with_capacity(3 * grid.triangle_count());
        for j in 0..nz - 1 {
            for i in 0..nx - 1 {
                let a = (j * nx + i) as u32;
                let b = a + nx as u32; // (i, j + 1)
                let c = a + 1; // (i + 1, j)
                let d = b + 1; // (i + 1, j + 1)
                indices.extend_from_slice(&[a, b, c, c, b, d]);
            }
        }
        let normals = vec![Vec3::Y; positions.len()];
        let foam = vec![0.0; positions.len()];
        Self { grid, positions, normals, uvs, indices, foam, has_foam: false }
    }

    /// Displaces the mesh with `model` at time `t` (s), in place and without allocating.
    ///
    /// Call [`WaveModel::advance`] for `t` first when the model is stateful ([`crate::world::World`]
    /// does).
    pub fn displace(&mut self, model: &dyn WaveModel, t: f64) {
        model.evaluate(&self.grid, t, &mut self.positions, &mut self.normals);
        self.has_foam = model.foam(&self.grid, &mut self.foam);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn triangles_face_up_and_cover_the_grid() {
        let grid = GridSpec::centered(Vec2::new(4.0, 2.0), 4, 2).unwrap();
        let m = SurfaceMesh::new(grid);
        assert_eq!(m.positions.len(), 15);
        assert_eq!(m.indices.len(), 3 * 16);
        let mut area = 0.0;
        for t in m.indices.chunks(3) {
            let [a, b, c] = [0, 1, 2].map(|k| m.positions[t[k] as usize]);
            let n = (b - a).cross(c - a);
            assert!(n.y > 0.0 && n.x == 0.0 && n.z == 0.0, "triangle {t:?} faces {n}");
            area += 0.5 * n.y;
        }
        assert!((area - 8.0).abs() < 1e-5);
        assert_eq!(m.positions[0], Vec3::new(-2.0, 0.0, -1.0));
        assert_eq!(m.positions[14], Vec3::new(2.0, 0.0, 1.0));
        assert_eq!(m.uvs[14], Vec2::ONE);
    }
}
