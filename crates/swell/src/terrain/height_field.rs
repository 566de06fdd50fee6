//! The regular height grid every terrain generator produces (paper 001 §1.2.1, "регулярная сетка
//! высот"): one height per vertex over a rectangle of the model's (x, z) plane.

use glam::{Vec2, Vec3};
use rayon::prelude::*;

use crate::error::{check_count, check_positive, Error, Result};
use crate::math::{GridSpec, MAX_GRID_CELLS};

/// Most vertices along one side of a height field: one more than [`MAX_GRID_CELLS`], so that every
/// field can become a mesh. 4097 x 4097 heights take 64 MiB.
pub const MAX_TERRAIN_SIZE: u32 = MAX_GRID_CELLS + 1;

/// Heights in metres on a `cols` x `rows` vertex grid spanning `extent` metres, centred on the
/// model origin.
///
/// Vertex (i, j) (column i along +X, row j along +Z) sits at model
/// `(-extent.x / 2 + i * dx, height(i, j), -extent.y / 2 + j * dz)` with `dx = extent.x / (cols - 1)`;
/// heights are stored row-major, like [`GridSpec`]'s vertices. Heights are finite.
#[derive(Clone, Debug, PartialEq)]
pub struct HeightField {
    cols: usize,
    rows: usize,
    extent: Vec2,
    heights: Vec<f32>,
}

impl HeightField {
    /// A field from its heights (row-major, `cols * rows` of them), checked: each side in
    /// [2, [`MAX_TERRAIN_SIZE`]], extent positive, every height finite.
    pub fn new(cols: u32, rows: u32, extent: Vec2, heights: Vec<f32>) -> Result<Self> {
        check_count("terrain.size", cols, 2, MAX_TERRAIN_SIZE)?;
        check_count("terrain.size", rows, 2, MAX_TERRAIN_SIZE)?;
        check_positive("terrain.extent[0]", extent.x)?;
        check_positive("terrain.extent[1]", extent.y)?;
        let (cols, rows) = (cols as usize, rows as usize);
        if heights.len() != cols * rows {
            return Err(Error::invalid(
                "terrain",
                format!("{} heights given for a {cols} x {rows} grid (needs {})", heights.len(), cols * rows),
            ));
        }
        if let Some(k) = heights.iter().position(|h| !h.is_finite()) {
            return Err(Error::invalid("terrain", format!("height {k} is {} (must be finite)", heights[k])));
        }
        Ok(Self { cols, rows, extent, heights })
    }

    /// A field with `height(x, z)` evaluated at every vertex's model (x, z), rows in parallel.
    ///
    /// `height` must return finite metres; each vertex depends only on its position, so the result
    /// is the same on any thread count.
    pub fn from_fn(cols: u32, rows: u32, extent: Vec2, height: impl Fn(f32, f32) -> f32 + Sync) -> Result<Self> {
        check_count("terrain.size", cols, 2, MAX_TERRAIN_SIZE)?;
        check_count("terrain.size", rows, 2, MAX_TERRAIN_SIZE)?;
        let layout = Self { cols: cols as usize, rows: rows as usize, extent, heights: Vec::new() };
        let mut heights = vec![0.0; layout.cols * layout.rows];
        heights.par_chunks_mut(layout.cols).enumerate().for_each(|(j, row)| {
            for (i, h) in row.iter_mut().enumerate() {
                let p = layout.model_xz(i, j);
                *h = height(p.x, p.y);
            }
        });
        Self::new(cols, rows, extent, heights)
    }

    /// Vertices along x.
    pub fn cols(&self) -> usize {
        self.cols
    }

    /// Vertices along z.
    pub fn rows(&self) -> usize {
        self.rows
    }

    /// Horizontal extent (x, z) in metres.
    pub fn extent(&self) -> Vec2 {
        self.extent
    }

    /// All heights, metres, row-major.
    pub fn heights(&self) -> &[f32] {
        &self.heights
    }

    /// Distance between neighbouring vertices along x and z, metres.
    pub fn spacing(&self) -> Vec2 {
        Vec2::new(self.extent.x / (self.cols - 1) as f32, self.extent.y / (self.rows - 1) as f32)
    }

    /// Model (x, z) of vertex (i, j), metres.
    pub fn model_xz(&self, i: usize, j: usize) -> Vec2 {
        -0.5 * self.extent + Vec2::new(i as f32, j as f32) * self.spacing()
    }

    /// The vertex grid as a [`GridSpec`] centred on the model origin (`cols - 1` x `rows - 1` cells).
    pub fn grid(&self) -> GridSpec {
        GridSpec::centered(self.extent, self.cols as u32 - 1, self.rows as u32 - 1)
            .expect("a height field's size and extent are checked when it is made")
    }

    /// Height of vertex (i, j), metres (`i < cols`, `j < rows`).
    pub fn height(&self, i: usize, j: usize) -> f32 {
        self.heights[j * self.cols + i]
    }

    /// Lowest and highest height, metres.
    pub fn min_max(&self) -> (f32, f32) {
        self.heights.iter().fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), &h| (lo.min(h), hi.max(h)))
    }

    /// Height at model (x, z) in metres, bilinear between the four surrounding vertices; points
    /// outside the extent take the height of the nearest edge point.
    pub fn height_at(&self, x: f32, z: f32) -> f32 {
        let (fi, fj, ti, tj) = self.cell_of(x, z);
        let h = |di: usize, dj: usize| self.height(fi + di, fj + dj);
        let bottom = h(0, 0) + (h(1, 0) - h(0, 0)) * ti;
        let top = h(0, 1) + (h(1, 1) - h(0, 1)) * ti;
        bottom + (top - bottom) * tj
    }

    /// Whether model (x, z) lies within the extent (edges included).
    pub fn contains(&self, x: f32, z: f32) -> bool {
        x.abs() <= 0.5 * self.extent.x && z.abs() <= 0.5 * self.extent.y
    }

    /// The cell holding (x, z), clamped to the grid, and the position within it in [0, 1]^2.
    fn cell_of(&self, x: f32, z: f32) -> (usize, usize, f32, f32) {
        let s = self.spacing();
        let gx = ((x + 0.5 * self.extent.x) / s.x).clamp(0.0, (self.cols - 1) as f32);
        let gz = ((z + 0.5 * self.extent.y) / s.y).clamp(0.0, (self.rows - 1) as f32);
        let fi = (gx.floor() as usize).min(self.cols - 2);
        let fj = (gz.floor() as usize).min(self.rows - 2);
        (fi, fj, gx - fi as f32, gz - fj as f32)
    }

    /// Unit model-space normal at vertex (i, j) from central differences (one-sided at the edges):
    /// `normalize(-dh/dx, 1, -dh/dz)`.
    pub fn normal(&self, i: usize, j: usize) -> Vec3 {
        let s = self.spacing();
        let (i0, i1) = (i.saturating_sub(1), (i + 1).min(self.cols - 1));
        let (j0, j1) = (j.saturating_sub(1), (j + 1).min(self.rows - 1));
        let dhdx = (self.height(i1, j) - self.height(i0, j)) / ((i1 - i0) as f32 * s.x);
        let dhdz = (self.height(i, j1) - self.height(i, j0)) / ((j1 - j0) as f32 * s.y);
        Vec3::new(-dhdx, 1.0, -dhdz).normalize()
    }

    /// Model-space positions and normals of every vertex, written into caller-owned buffers of
    /// `cols * rows` elements, rows in parallel.
    pub fn write_vertices(&self, positions: &mut [Vec3], normals: &mut [Vec3]) {
        let n = self.cols * self.rows;
        assert!(positions.len() == n && normals.len() == n, "buffers must hold cols * rows = {n} vertices");
        positions.par_chunks_mut(self.cols).zip(normals.par_chunks_mut(self.cols)).enumerate().for_each(
            |(j, (prow, nrow))| {
                for i in 0..self.cols {
                    let xz = self.model_xz(i, j);
                    prow[i] = Vec3::new(xz.x, self.height(i, j), xz.y);
                    nrow[i] = self.normal(i, j);
                }
            },
        );
    }

    /// Adds `offset` metres to every height.
    pub fn offset_heights(&mut self, offset: f32) {
        self.heights.iter_mut().for_each(|h| *h += offset);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bilinear_height_reproduces_planes_and_clamps_outside() {
        let f = HeightField::from_fn(5, 3, Vec2::new(8.0, 4.0), |x, z| 2.0 * x - 0.5 * z + 1.0).unwrap();
        assert_eq!(f.model_xz(0, 0), Vec2::new(-4.0, -2.0));
        assert_eq!(f.model_xz(4, 2), Vec2::new(4.0, 2.0));
        for (x, z) in [(0.3, -1.7), (3.9, 1.2), (-4.0, 2.0), (1.0, 0.0)] {
            assert!((f.height_at(x, z) - (2.0 * x - 0.5 * z + 1.0)).abs() < 1e-5);
        }
        assert!((f.height_at(10.0, 0.0) - f.height_at(4.0, 0.0)).abs() < 1e-6);
        let n = f.normal(2, 1);
        assert!((n - Vec3::new(-2.0, 1.0, 0.5).normalize()).length() < 1e-5, "{n}");
    }

    #[test]
    fn bad_fields_are_refused() {
        assert!(HeightField::new(1, 2, Vec2::ONE, vec![0.0; 2]).is_err());
        assert!(HeightField::new(2, 2, Vec2::ONE, vec![0.0; 3]).is_err());
        let e = HeightField::new(2, 2, Vec2::ONE, vec![0.0, f32::NAN, 0.0, 0.0]).unwrap_err();
        assert!(e.to_string().contains("NaN"), "{e}");
        assert!(HeightField::new(2, 2, Vec2::new(0.0, 1.0), vec![0.0; 4]).is_err());
    }
}
