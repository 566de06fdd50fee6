//! A river channel carved between two banks (paper 004: a river between two bank lines that
//! follow sines). The banks meander as `meander_amplitude * sin(2 pi s / meander_wavelength)`
//! along the flow; across it the ground is the bed inside the channel and rises smoothly over
//! `bank_width` to the bank height outside.

use glam::Vec2;
use serde::{Deserialize, Serialize};

use super::diamond_square::MAX_AMPLITUDE;
use super::height_field::{HeightField, MAX_TERRAIN_SIZE};
use super::{GeneratorParams, DEFAULT_TERRAIN_EXTENT};
use crate::error::{check_count, check_finite_vec, check_non_negative, check_positive, check_range, Error, Result};

/// Parameters of a carved channel; `[terrain]` keys for `generator = "channel"`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ChannelParams {
    /// Height (m) of the river bed, in [-1e5, 1e5]. Default -1.5 (1.5 m below water at rest).
    pub bed_height: f32,
    /// Height (m) of the land beside the river, in [-1e5, 1e5]. Default 2.
    pub bank_height: f32,
    /// Width (m) of the flat bed, > 0. Default 20.
    pub width: f32,
    /// Horizontal run (m) of each bank from the bed to the bank height, > 0. Default 6.
    pub bank_width: f32,
    /// Direction (x, z) the river runs along; non-zero. Default +X.
    pub direction: Vec2,
    /// Sideways swing (m) of the channel's centre line, >= 0. Default 0 (straight).
    pub meander_amplitude: f32,
    /// Distance (m) along the river of one full swing, > 0. Default 120.
    pub meander_wavelength: f32,
}

impl Default for ChannelParams {
    fn default() -> Self {
        Self {
            bed_height: -1.5,
            bank_height: 2.0,
            width: 20.0,
            bank_width: 6.0,
            direction: Vec2::X,
            meander_amplitude: 0.0,
            meander_wavelength: 120.0,
        }
    }
}

impl ChannelParams {
    /// Checks every field, naming keys under `key`.
    pub fn validate(&self, key: &str) -> Result<()> {
        check_range(&format!("{key}.bed_height"), self.bed_height, -MAX_AMPLITUDE, MAX_AMPLITUDE)?;
        check_range(&format!("{key}.bank_height"), self.bank_height, -MAX_AMPLITUDE, MAX_AMPLITUDE)?;
        check_positive(&format!("{key}.width"), self.width)?;
        check_positive(&format!("{key}.bank_width"), self.bank_width)?;
        check_finite_vec(&format!("{key}.direction"), &self.direction.to_array())?;
        if self.direction.length_squared() == 0.0 {
            return Err(Error::invalid(format!("{key}.direction"), "[0, 0] has no direction; give a non-zero [x, z]"));
        }
        check_non_negative(&format!("{key}.meander_amplitude"), self.meander_amplitude)?;
        check_positive(&format!("{key}.meander_wavelength"), self.meander_wavelength)
    }

    /// Ground height (m) at model (x, z).
    pub fn height_at(&self, x: f32, z: f32) -> f32 {
        let along = self.direction.normalize();
        let across = along.perp();
        let p = Vec2::new(x, z);
        let s = p.dot(along);
        let centre = self.meander_amplitude * (std::f32::consts::TAU * s / self.meander_wavelength).sin();
        let outside = (p.dot(across) - centre).abs() - 0.5 * self.width;
        let t = (outside / self.bank_width).clamp(0.0, 1.0);
        // Smoothstep: banks leave the bed and meet the land without a crease.
        self.bed_height + (self.bank_height - self.bed_height) * t * t * (3.0 - 2.0 * t)
    }
}

/// A `size` x `size` channel field spanning `extent` metres.
pub fn channel(size: u32, extent: Vec2, p: &ChannelParams) -> Result<HeightField> {
    check_count("terrain.size", size, 2, MAX_TERRAIN_SIZE)?;
    p.validate("terrain")?;
    HeightField::from_fn(size, size, extent, |x, z| p.height_at(x, z))
}

impl GeneratorParams for ChannelParams {
    fn validate(&self, key: &str) -> Result<()> {
        ChannelParams::validate(self, key)
    }

    fn generate(&self, size: u32, extent: Option<Vec2>) -> Result<HeightField> {
        channel(size, extent.unwrap_or(DEFAULT_TERRAIN_EXTENT), self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bed_inside_banks_outside_following_the_meander() {
        let p = ChannelParams { meander_amplitude: 10.0, meander_wavelength: 80.0, ..Default::default() };
        // Flow along +X, across is +Z; at x = 20 (a quarter wavelength) the centre is at z = 10.
        assert_eq!(p.height_at(20.0, 10.0), -1.5);
        assert_eq!(p.height_at(20.0, 19.9), -1.5);
        assert_eq!(p.height_at(20.0, 10.0 + 10.0 + 6.0), 2.0);
        assert_eq!(p.height_at(20.0, -10.0), 2.0);
        let mid = p.height_at(20.0, 10.0 + 10.0 + 3.0);
        assert!((mid - 0.25).abs() < 1e-5, "{mid}");
        let f = channel(65, Vec2::splat(160.0), &p).unwrap();
        assert_eq!(f.min_max(), (-1.5, 2.0));
    }
}
