//! What a terrain generator's parameters offer the scene: checks without generating, the size rule,
//! and the generation itself.
//!
//! Each generator implements [`GeneratorParams`] for its parameter type in its own file; the
//! scene's table of generators (`scene/terrain_spec.rs`, one line per generator) dispatches to it.

use glam::Vec2;

use super::{HeightField, MAX_TERRAIN_SIZE};
use crate::error::{check_count, Result};

/// Vertices per side when `terrain.size` is not given.
pub const DEFAULT_TERRAIN_SIZE: u32 = 257;

/// Extent (m) when `terrain.extent` is not given (and, for heightmaps, not in the sidecar).
pub const DEFAULT_TERRAIN_EXTENT: Vec2 = Vec2::new(200.0, 200.0);

/// A terrain generator's parameters as a scene holds them (`[terrain]` with `generator = "..."`).
pub trait GeneratorParams {
    /// Checks every parameter, naming keys under `key` (normally `terrain`), without generating.
    fn validate(&self, key: &str) -> Result<()>;

    /// Checks `size` (vertices per side) given as `key`: by default in [2, [`MAX_TERRAIN_SIZE`]].
    fn check_size(&self, key: &str, size: u32) -> Result<()> {
        check_count(key, size, 2, MAX_TERRAIN_SIZE)
    }

    /// Generates the field: `size` vertices per side (checked), over `extent` metres when the
    /// scene gives one ([`DEFAULT_TERRAIN_EXTENT`] otherwise), centred on the model origin.
    fn generate(&self, size: u32, extent: Option<Vec2>) -> Result<HeightField>;
}
