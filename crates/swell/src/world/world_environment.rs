//! The world as its floating bodies feel it: the water as drawn (the scene's wave model, placed
//! in the world) and the terrain.

use glam::{Vec2, Vec3};

use super::{TerrainBody, WaterBody};
use crate::body::BodyEnvironment;
use crate::error::Result;

/// A [`World`](super::World)'s water and terrain for [`crate::body::FloatingBodies::advance`]:
/// `prepare` moves the wave model to each body step's time, the heights and velocities are the
/// model's at the local point under the world point, carried into the world by the placement.
pub(super) struct WorldEnvironment<'a> {
    /// The water, if the scene has any.
    pub water: Option<&'a mut WaterBody>,
    /// The terrain, if the scene has any.
    pub terrain: Option<&'a TerrainBody>,
}

impl BodyEnvironment for WorldEnvironment<'_> {
    fn prepare(&mut self, t: f64) -> Result<()> {
        match &mut self.water {
            Some(w) => w.model.advance(t),
            None => Ok(()),
        }
    }

    fn water_height(&self, x: f32, z: f32, t: f64) -> Option<f32> {
        let mut rest = Vec2::NAN;
        self.water_height_near(x, z, t, &mut rest)
    }

    /// The model's [`crate::water::WaveModel::height_near`] at the local point, `rest` in the
    /// model's frame.
    fn water_height_near(&self, x: f32, z: f32, t: f64, rest: &mut Vec2) -> Option<f32> {
        let w = self.water.as_deref()?;
        let local = w.placement.to_local_xz(Vec2::new(x, z));
        // A finite patch (a pool, a spring lattice, a river's reach) holds water only over
        // itself, as the query API says (`Water::has_water_at`).
        if !super::water_query::covers(w.extent, &w.patch_grid, || local.as_dvec2()) {
            return None;
        }
        let h = w.placement.to_world_height(w.model.height_near(local.x, local.y, t, rest));
        h.is_finite().then_some(h)
    }

    fn water_velocity(&self, x: f32, z: f32, t: f64) -> Vec3 {
        let Some(w) = self.water.as_deref() else { return Vec3::ZERO };
        let local = w.placement.to_local_xz(Vec2::new(x, z));
        let v = w.model.surface_velocity(local.x, local.y, t);
        // A vector: the placement's turn and scale without its shift.
        let v = w.placement.to_world(v) - w.placement.to_world(Vec3::ZERO);
        if v.is_finite() {
            v
        } else {
            Vec3::ZERO
        }
    }

    fn ground_height(&self, x: f32, z: f32) -> Option<f32> {
        self.terrain.and_then(|t| t.ground_height(x, z))
    }
}
