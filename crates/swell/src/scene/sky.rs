//! The procedural sky: what the background shows and what water reflects.

use glam::Vec3;
use serde::{Deserialize, Serialize};

use crate::error::{check_non_negative, Result};

/// A sky that blends from a horizon colour to a zenith colour with the elevation of the view ray.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Sky {
    /// Linear RGB radiance at the horizon, >= 0.
    pub horizon: Vec3,
    /// Linear RGB radiance straight up, >= 0.
    pub zenith: Vec3,
    /// Linear RGB radiance seen below the horizon where nothing is drawn (the far ground), >= 0.
    pub ground: Vec3,
}

impl Default for Sky {
    fn default() -> Self {
        Self {
            horizon: Vec3::new(0.62, 0.72, 0.82),
            zenith: Vec3::new(0.12, 0.28, 0.62),
            ground: Vec3::new(0.18, 0.20, 0.22),
        }
    }
}

impl Sky {
    /// Checks the colours, naming keys under `key` (normally `sky`).
    pub fn validate(&self, key: &str) -> Result<()> {
        for (name, c) in [("horizon", self.horizon), ("zenith", self.zenith), ("ground", self.ground)] {
            for (i, v) in c.to_array().into_iter().enumerate() {
                check_non_negative(&format!("{key}.{name}[{i}]"), v)?;
            }
        }
        Ok(())
    }

    /// Radiance seen along the unit world direction `dir`.
    pub fn radiance(&self, dir: Vec3) -> Vec3 {
        if dir.y >= 0.0 {
            // sqrt keeps the bright horizon band narrow, as in a clear sky.
            self.horizon.lerp(self.zenith, dir.y.sqrt())
        } else {
            self.horizon.lerp(self.ground, (-dir.y * 8.0).min(1.0))
        }
    }
}
