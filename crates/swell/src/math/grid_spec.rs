//! The regular grid every surface is sampled on.

use glam::Vec2;

use crate::error::{check_count, check_finite_vec, check_positive, Result};

/// Largest number of cells along one side of a grid.
///
/// 4096 cells gives 16.8 M vertices (about 0.6 GiB of positions, normals and uv): the most a 24 GiB
/// machine renders comfortably, and far beyond what real time needs.
pub const MAX_GRID_CELLS: u32 = 4096;

/// A regular grid of `cells_x` x `cells_z` quads over a rectangle of the horizontal (x, z) plane.
///
/// Vertices are numbered row by row: vertex `(i, j)` (column `i` along +X, row `j` along +Z) has index
/// `j * (cells_x + 1) + i` and rest position `origin + (i * dx, j * dz)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GridSpec {
    /// World (x, z) of vertex (0, 0), in metres.
    pub origin: Vec2,
    /// Extent along x and z, in metres; both > 0.
    pub size: Vec2,
    /// Number of cells along x, in [1, [`MAX_GRID_CELLS`]].
    pub cells_x: u32,
    /// Number of cells along z, in [1, [`MAX_GRID_CELLS`]].
    pub cells_z: u32,
}

impl GridSpec {
    /// A grid of `size` metres centred on the origin, checked.
    pub fn centered(size: Vec2, cells_x: u32, cells_z: u32) -> Result<Self> {
        Self::new(-0.5 * size, size, cells_x, cells_z)
    }

    /// A grid with vertex (0, 0) at `origin`, checked: finite positive size, cell counts in range.
    pub fn new(origin: Vec2, size: Vec2, cells_x: u32, cells_z: u32) -> Result<Self> {
        check_finite_vec("grid.origin", &origin.to_array())?;
        check_positive("grid.size[0]", size.x)?;
        check_positive("grid.size[1]", size.y)?;
        check_count("grid.cells[0]", cells_x, 1, MAX_GRID_CELLS)?;
        check_count("grid.cells[1]", cells_z, 1, MAX_GRID_CELLS)?;
        Ok(Self { origin, size, cells_x, cells_z })
    }

    /// Vertices along x (`cells_x + 1`).
    pub fn verts_x(&self) -> usize {
        self.cells_x as usize + 1
    }

    /// Vertices along z (`cells_z + 1`).
    pub fn verts_z(&self) -> usize {
        self.cells_z as usize + 1
    }

    /// Total number of vertices.
    pub fn vertex_count(&self) -> usize {
        self.verts_x() * self.verts_z()
    }

    /// Number of triangles (two per cell).
    pub fn triangle_count(&self) -> usize {
        2 * self.cells_x as usize * self.cells_z as usize
    }

    /// Cell size (dx, dz) in metres.
    pub fn spacing(&self) -> Vec2 {
        Vec2::new(self.size.x / self.cells_x as f32, self.size.y / self.cells_z as f32)
    }

    /// Rest (x, z) of vertex (i, j) in metres.
    pub fn rest_position(&self, i: usize, j: usize) -> Vec2 {
        // Multiply then add, rather than accumulate, so every vertex is exact to one rounding.
        let s = self.spacing();
        self.origin + Vec2::new(i as f32 * s.x, j as f32 * s.y)
    }
}
