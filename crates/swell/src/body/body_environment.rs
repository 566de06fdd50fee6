//! What a floating body feels of the world around it: the water's surface and motion and the
//! ground below, asked at world points and step times. [`crate::world::World`] answers it from
//! the water as drawn and the terrain; tests answer it with still or closed-form water.

use glam::Vec3;

use crate::error::Result;
use crate::water::WaveModel;

/// The water and the ground as floating bodies see them, in world coordinates (m, +Y up), at the
/// time of a body step.
///
/// [`BodyEnvironment::prepare`] is called once per step, before the bodies (in parallel) ask the
/// other methods for that step's time `t`; answers must depend only on (x, z) and `t`.
pub trait BodyEnvironment: Sync {
    /// Moves whatever has state (a spectral or stepped water model) to time `t` (s); `t` never
    /// decreases between calls on one environment. The default does nothing.
    fn prepare(&mut self, _t: f64) -> Result<()> {
        Ok(())
    }

    /// Height (m) of the water surface above world (x, z) at time `t` (s), `None` where there is
    /// no water (beyond a finite pool, on a river's banks).
    fn water_height(&self, x: f32, z: f32, t: f64) -> Option<f32>;

    /// [`BodyEnvironment::water_height`] given `rest`, the answer's rest point in the water
    /// model's frame for the same hull vertex at the step before (NaN at first), which it updates:
    /// see [`WaveModel::height_near`]. The default ignores it.
    fn water_height_near(&self, x: f32, z: f32, t: f64, _rest: &mut glam::Vec2) -> Option<f32> {
        self.water_height(x, z, t)
    }

    /// Velocity (m/s, world) of the water at the surface above world (x, z) at time `t` (s).
    fn water_velocity(&self, x: f32, z: f32, t: f64) -> Vec3;

    /// Height (m) of the ground at world (x, z), `None` where there is none (open sea).
    fn ground_height(&self, x: f32, z: f32) -> Option<f32>;
}

/// Still water at rest (y = 0) everywhere and no ground: the hydrostatic case of the tests and of
/// an embedder that only wants a body to settle.
#[derive(Clone, Copy, Debug, Default)]
pub struct StillWater;

impl BodyEnvironment for StillWater {
    fn water_height(&self, _x: f32, _z: f32, _t: f64) -> Option<f32> {
        Some(0.0)
    }

    fn water_velocity(&self, _x: f32, _z: f32, _t: f64) -> Vec3 {
        Vec3::ZERO
    }

    fn ground_height(&self, _x: f32, _z: f32) -> Option<f32> {
        None
    }
}

/// A wave model's water in its own frame (the world's, unturned and unscaled) with no ground: the
/// environment of an embedder who holds a [`WaveModel`] and no scene, and of the tests.
pub struct ModelWater<'a> {
    /// The model, advanced to each step's time.
    pub model: &'a mut dyn WaveModel,
}

impl BodyEnvironment for ModelWater<'_> {
    fn prepare(&mut self, t: f64) -> Result<()> {
        self.model.advance(t)
    }

    fn water_height(&self, x: f32, z: f32, t: f64) -> Option<f32> {
        Some(self.model.height_at(x, z, t))
    }

    fn water_height_near(&self, x: f32, z: f32, t: f64, rest: &mut glam::Vec2) -> Option<f32> {
        Some(self.model.height_near(x, z, t, rest))
    }

    fn water_velocity(&self, x: f32, z: f32, t: f64) -> Vec3 {
        self.model.surface_velocity(x, z, t)
    }

    fn ground_height(&self, _x: f32, _z: f32) -> Option<f32> {
        None
    }
}
