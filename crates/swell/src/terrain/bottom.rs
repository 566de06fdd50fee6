//! Simple bottoms for man-made and gentle water bodies: a flat floor (paper 002's pool, with its
//! sand bottom 0.2 below the surface) and a plane sloping up to a beach.

use glam::Vec2;
use serde::{Deserialize, Serialize};

use super::diamond_square::MAX_AMPLITUDE;
use super::height_field::{HeightField, MAX_TERRAIN_SIZE};
use super::{GeneratorParams, DEFAULT_TERRAIN_EXTENT};
use crate::error::{check_count, check_finite_vec, check_range, Error, Result};

/// A flat floor; `[terrain]` keys for `generator = "flat"`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct FlatParams {
    /// Height of the floor in metres (before the transform), in [-1e5, 1e5]. Default -2 (2 m below
    /// water at rest).
    pub height: f32,
}

impl Default for FlatParams {
    fn default() -> Self {
        Self { height: -2.0 }
    }
}

impl FlatParams {
    /// Checks every field, naming keys under `key`.
    pub fn validate(&self, key: &str) -> Result<()> {
        check_range(&format!("{key}.height"), self.height, -MAX_AMPLITUDE, MAX_AMPLITUDE)
    }
}

/// A floor rising along a direction; `[terrain]` keys for `generator = "slope"`.
///
/// With `t` in [0, 1] the position along `direction` across the extent (0 at the first corner the
/// direction leaves, 1 at the last it reaches), `h = start_height + (end_height - start_height) *
/// t^exponent`. `exponent` 1 is a plane; above 1 the floor stays low and rises late (a shelf
/// ending in a steeper beach), below 1 it rises early and flattens towards the end.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SlopeParams {
    /// Height (m) where the slope starts (t = 0), in [-1e5, 1e5]. Default -10.
    pub start_height: f32,
    /// Height (m) where it ends (t = 1), in [-1e5, 1e5]. Default 2.
    pub end_height: f32,
    /// Horizontal direction (x, z) in which the floor rises from start to end; non-zero. Default +X.
    pub direction: Vec2,
    /// Shape exponent, in [0.1, 10]; 1 is a plane. Default 1.
    pub exponent: f32,
}

impl Default for SlopeParams {
    fn default() -> Self {
        Self { start_height: -10.0, end_height: 2.0, direction: Vec2::X, exponent: 1.0 }
    }
}

impl SlopeParams {
    /// Checks every field, naming keys under `key`.
    pub fn validate(&self, key: &str) -> Result<()> {
        check_range(&format!("{key}.start_height"), self.start_height, -MAX_AMPLITUDE, MAX_AMPLITUDE)?;
        check_range(&format!("{key}.end_height"), self.end_height, -MAX_AMPLITUDE, MAX_AMPLITUDE)?;
        check_finite_vec(&format!("{key}.direction"), &self.direction.to_array())?;
        if self.direction.length_squared() == 0.0 {
            return Err(Error::invalid(format!("{key}.direction"), "[0, 0] has no direction; give a non-zero [x, z]"));
        }
        check_range(&format!("{key}.exponent"), self.exponent, 0.1, 10.0)
    }
}

/// A `size` x `size` flat field spanning `extent` metres.
pub fn flat(size: u32, extent: Vec2, p: &FlatParams) -> Result<HeightField> {
    check_count("terrain.size", size, 2, MAX_TERRAIN_SIZE)?;
    p.validate("terrain")?;
    HeightField::new(size, size, extent, vec![p.height; size as usize * size as usize])
}

/// A `size` x `size` sloping field spanning `extent` metres.
pub fn slope(size: u32, extent: Vec2, p: &SlopeParams) -> Result<HeightField> {
    check_count("terrain.size", size, 2, MAX_TERRAIN_SIZE)?;
    p.validate("terrain")?;
    let d = p.direction.normalize();
    // The corners' projections on d bound the field: half the extent's projection either way.
    let reach = 0.5 * (extent.x * d.x.abs() + extent.y * d.y.abs());
    HeightField::from_fn(size, size, extent, |x, z| {
        let t = ((Vec2::new(x, z).dot(d) + reach) / (2.0 * reach)).clamp(0.0, 1.0);
        p.start_height + (p.end_height - p.start_height) * t.powf(p.exponent)
    })
}

impl GeneratorParams for FlatParams {
    fn validate(&self, key: &str) -> Result<()> {
        FlatParams::validate(self, key)
    }

    fn generate(&self, size: u32, extent: Option<Vec2>) -> Result<HeightField> {
        flat(size, extent.unwrap_or(DEFAULT_TERRAIN_EXTENT), self)
    }
}

impl GeneratorParams for SlopeParams {
    fn validate(&self, key: &str) -> Result<()> {
        SlopeParams::validate(self, key)
    }

    fn generate(&self, size: u32, extent: Option<Vec2>) -> Result<HeightField> {
        slope(size, extent.unwrap_or(DEFAULT_TERRAIN_EXTENT), self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slope_runs_from_start_to_end_along_its_direction() {
        let p = SlopeParams { start_height: -10.0, end_height: 2.0, direction: Vec2::new(0.0, -3.0), exponent: 1.0 };
        let f = slope(5, Vec2::new(40.0, 20.0), &p).unwrap();
        // Rising towards -z: row 0 (z = -10) is the end, row 4 (z = +10) the start.
        assert!((f.height(2, 0) - 2.0).abs() < 1e-5 && (f.height(0, 4) + 10.0).abs() < 1e-5);
        assert!((f.height_at(7.0, 0.0) + 4.0).abs() < 1e-5);
        let flat = flat(3, Vec2::ONE, &FlatParams { height: -0.2 }).unwrap();
        assert!(flat.heights().iter().all(|&h| h == -0.2));
    }
}
