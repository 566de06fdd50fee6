//! `[water] extent` and `[water.lod]`: whether the water is a finite patch or a sea that reaches
//! the horizon, and how finely the camera-following mesh of an unbounded sea is sampled.
//!
//! ```toml
//! [water]
//! model = "fft"
//! extent = "unbounded"     # or "patch"; default: unbounded for models defined everywhere
//! [water.lod]
//! levels = 8               # clipmap rings, each twice the size and spacing of the one inside
//! ring_cells = 96          # cells along a side of each ring, a multiple of 4
//! spacing = 0.5            # metres between vertices of the finest ring
//! ```
//!
//! `size` and `cells` keep their meaning for the patch: bakes and exports sample that finite grid
//! whatever the extent (issue 17).

use serde::{Deserialize, Serialize};

use super::WaterModelSpec;
use crate::error::{Error, Result};
use crate::math::GridSpec;

/// How far the water reaches.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum WaterExtent {
    /// The water covers the whole plane y = 0 to the horizon: a camera-following level-of-detail
    /// mesh near the eye ([`crate::mesh::Clipmap`]) and a statistically shaded far field beyond
    /// it (`shading/slope_variance.rs`).
    Unbounded,
    /// The water is the finite `size` x `cells` patch around `center`.
    Patch,
}

impl WaterExtent {
    /// The names `water.extent` accepts.
    pub const NAMES: &'static [&'static str] = &["unbounded", "patch"];

    /// The extent a scene gets when it does not say: unbounded for the models defined over the
    /// whole plane ([`crate::water::ModelParams::defined_everywhere`]: the FFT ocean, whose
    /// cascades tile, and the closed forms), a patch for water that is finite by nature (the
    /// radial pool, the spring lattice, the river) and for water its terrain holds
    /// (`held_by_terrain`: a lake, whose terrain rises above the water all along its border). An
    /// island or a coast, whose terrain's border lies partly under water, sits in an unbounded
    /// sea ([`crate::world::TerrainBody::border_under_water`] decides, once the terrain is built).
    pub fn default_for(model: &WaterModelSpec, held_by_terrain: bool) -> Self {
        if model.params().defined_everywhere() && !held_by_terrain {
            WaterExtent::Unbounded
        } else {
            WaterExtent::Patch
        }
    }

    /// Checks that `model` can be unbounded when this extent asks for it: the finite-by-nature
    /// models cannot (key `water.extent`, the value, the model and the valid set named).
    pub fn validate(self, model: &WaterModelSpec) -> Result<()> {
        if self == WaterExtent::Unbounded && !model.params().defined_everywhere() {
            let finite: Vec<&str> = crate::scene::WATER_MODELS
                .iter()
                .filter(|name| WaterModelSpec::default_for(name).is_some_and(|m| !m.params().defined_everywhere()))
                .copied()
                .collect();
            return Err(Error::invalid(
                "water.extent",
                format!(
                    "\"unbounded\" is not possible for model \"{}\", which is finite by nature (as are {}); \
                     valid: \"patch\"",
                    model.name(),
                    finite.join(", ")
                ),
            ));
        }
        Ok(())
    }
}

/// Most clipmap rings [`LodSettings::levels`] accepts.
pub const MAX_LOD_LEVELS: u32 = 16;
/// Fewest and most cells along a ring's side ([`LodSettings::ring_cells`]).
pub const LOD_RING_CELLS: (u32, u32) = (8, 1024);
/// Smallest and largest finest-ring vertex spacing (m) ([`LodSettings::spacing`]).
pub const LOD_SPACING_M: (f32, f32) = (0.001, 100.0);

/// Most vertices the rings may hold together (`levels x (ring_cells + 1)^2`): a 2048² patch's
/// worth, about 120 MB with the index buffer, so that no LOD setting can exhaust memory.
pub const MAX_LOD_VERTICES: u64 = 2049 * 2049;

/// `[water.lod]`: the camera-following mesh of unbounded water ([`crate::mesh::Clipmap`]).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct LodSettings {
    /// Clipmap rings, in [1, 16]; ring k has `spacing * 2^k` between vertices. Default 8.
    pub levels: u32,
    /// Cells along a side of each ring, a multiple of 4 in [8, 1024]. Default 96.
    pub ring_cells: u32,
    /// Metres between the vertices of the finest ring, in [0.001, 100]; `None` (the default)
    /// takes it from the patch: its `size / cells`, so the sea near the eye is sampled as the
    /// patch was.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub spacing: Option<f32>,
}

impl Default for LodSettings {
    fn default() -> Self {
        Self { levels: 8, ring_cells: 96, spacing: None }
    }
}

impl LodSettings {
    /// The finest ring's vertex spacing (m), the one default of `[water.lod]` that depends on the
    /// scene, resolved here once for every user: `spacing` when given, else the patch's smaller
    /// cell side (so the sea near the eye is sampled as the patch was), clamped to
    /// [`LOD_SPACING_M`] so that any valid patch gives valid rings.
    pub fn resolved_spacing(&self, patch: &GridSpec) -> f32 {
        self.spacing.unwrap_or_else(|| {
            let s = patch.spacing();
            s.x.min(s.y).clamp(LOD_SPACING_M.0, LOD_SPACING_M.1)
        })
    }

    /// Checks every key, naming it (`water.lod.levels`), its value and the valid range.
    pub fn validate(&self) -> Result<()> {
        if !(1..=MAX_LOD_LEVELS).contains(&self.levels) {
            return Err(Error::out_of_range("water.lod.levels", self.levels, format!("[1, {MAX_LOD_LEVELS}]")));
        }
        let (lo, hi) = LOD_RING_CELLS;
        if !(lo..=hi).contains(&self.ring_cells) || !self.ring_cells.is_multiple_of(4) {
            return Err(Error::out_of_range(
                "water.lod.ring_cells",
                self.ring_cells,
                format!("multiples of 4 in [{lo}, {hi}]"),
            ));
        }
        let vertices = u64::from(self.levels) * u64::from(self.ring_cells + 1).pow(2);
        if vertices > MAX_LOD_VERTICES {
            // The largest ring side that fits this many levels, rounded down to a multiple of 4.
            let side = ((MAX_LOD_VERTICES / u64::from(self.levels)) as f64).sqrt() as u64 - 1;
            return Err(Error::out_of_range(
                "water.lod.ring_cells",
                self.ring_cells,
                format!(
                    "multiples of 4 in [{lo}, {}] with {} levels (at most {MAX_LOD_VERTICES} ring vertices)",
                    side / 4 * 4,
                    self.levels
                ),
            ));
        }
        if let Some(s) = self.spacing {
            let (lo, hi) = LOD_SPACING_M;
            if !(s.is_finite() && (lo..=hi).contains(&s)) {
                return Err(Error::out_of_range("water.lod.spacing", s, format!("[{lo}, {hi}] m")));
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Scene;

    fn scene(keys: &str, model: &str) -> Result<Scene> {
        Scene::from_toml(&format!("version = 1\n[water]\nmodel = '{model}'\n{keys}\n"), "t")
    }

    #[test]
    fn models_defined_everywhere_are_unbounded_unless_asked_or_held_by_terrain() {
        for model in crate::scene::WATER_MODELS {
            let s = scene("", model).unwrap();
            let w = s.water.as_ref().unwrap();
            let expected =
                if !w.model.params().defined_everywhere() { WaterExtent::Patch } else { WaterExtent::Unbounded };
            assert_eq!(s.water_extent(), Some(expected), "{model}");
            assert_eq!(WaterExtent::default_for(&w.model, true), WaterExtent::Patch, "{model}");
        }
        let s = scene("extent = 'patch'", "fft").unwrap();
        assert_eq!(s.water_extent(), Some(WaterExtent::Patch));
        // Round trip keeps the key.
        assert_eq!(Scene::from_toml(&s.to_toml(), "again").unwrap(), s);
    }

    #[test]
    fn bad_extent_and_lod_keys_name_the_key_the_value_and_the_valid_set() {
        let e = scene("extent = 'infinite'", "fft").unwrap_err().to_string();
        assert!(e.contains("water.extent") && e.contains("infinite") && e.contains("unbounded"), "{e}");
        let e = scene("extent = 'unbounded'", "springs").unwrap_err().to_string();
        assert!(e.contains("water.extent") && e.contains("patch"), "{e}");
        for (keys, message) in [
            ("[water.lod]\nlevels = 0", "water.lod.levels = 0 is outside [1, 16]"),
            ("[water.lod]\nring_cells = 30", "water.lod.ring_cells = 30 is outside multiples of 4 in [8, 1024]"),
            ("[water.lod]\nspacing = -1.0", "water.lod.spacing = -1 is outside [0.001, 100] m"),
            (
                "[water.lod]\nlevels = 16\nring_cells = 1024",
                "water.lod.ring_cells = 1024 is outside multiples of 4 in [8, 508] with 16 levels (at most 4198401 ring vertices)",
            ),
        ] {
            let e = scene(keys, "gerstner").unwrap_err().to_string();
            assert_eq!(e, format!("t: {message}"));
        }
        let e = scene("[water.lod]\nrings = 3", "gerstner").unwrap_err().to_string();
        assert!(e.contains("water.lod") && e.contains("rings"), "{e}");
    }
}
