//! How much memory a scene will take once built and rendered, known before anything is built.
//!
//! The per-buffer figures and the budget live in [`crate::limits`]; this adds them up for a scene,
//! asking each water model for its own state ([`crate::water::ModelParams::estimate_bytes`]).

use super::{Scene, TerrainGenerator, DEFAULT_TERRAIN_SIZE};
use crate::limits::{estimate_frame_bytes, estimate_grid_bytes, TERRAIN_BYTES_PER_VERTEX, WATER_BYTES_PER_VERTEX};

impl Scene {
    /// Estimated peak bytes of building and rendering the scene one frame at a time: water grid,
    /// the water model's own state (FFT cascades, a spring lattice), terrain grid (a heightmap is
    /// counted when its header is read, since its size is only known from the file), and
    /// framebuffer, supersampled where asked.
    ///
    /// Reads no file and allocates nothing; [`Scene::validate`] compares it with
    /// [`crate::limits::MEMORY_BUDGET_BYTES`] before anything is built. Saturating: it may be
    /// asked about sizes that are each in range but together absurd.
    pub fn estimate_bytes(&self) -> u64 {
        let r = &self.render;
        let mut bytes = estimate_frame_bytes(r.width, r.height);
        // Supersampling renders into a frame `supersample` times larger on each side, then filters
        // it down into the frame above.
        let ss = r.supersample.max(1);
        if ss > 1 {
            bytes = bytes.saturating_add(estimate_frame_bytes(r.width.saturating_mul(ss), r.height.saturating_mul(ss)));
        }
        if let Some(w) = &self.water {
            let [x, z] = w.surface.cells;
            bytes = bytes.saturating_add(estimate_grid_bytes(x, z, WATER_BYTES_PER_VERTEX));
            bytes = bytes.saturating_add(w.model.estimate_bytes());
            // The unbounded sea's rings (issue 17), each a full grid of its own.
            if self.water_extent() == Some(super::WaterExtent::Unbounded) {
                let (levels, n) = (u64::from(w.surface.lod.levels), w.surface.lod.ring_cells);
                bytes = bytes.saturating_add(levels.saturating_mul(estimate_grid_bytes(n, n, WATER_BYTES_PER_VERTEX)));
            }
        }
        if let Some(t) = &self.terrain {
            let side = match t.generator {
                // Known only once the header is read; that read checks the real size again.
                TerrainGenerator::Heightmap(_) => 0,
                _ => t.size.unwrap_or(DEFAULT_TERRAIN_SIZE),
            };
            if side >= 2 {
                bytes = bytes.saturating_add(estimate_grid_bytes(side - 1, side - 1, TERRAIN_BYTES_PER_VERTEX));
            }
        }
        bytes
    }
}
