//! A river channel carved between two banks (paper 004: a river between two bank lines that
//! follow sines). The banks meander as `meander_amplitude * sin(2 pi s / meander_wavelength)`
//! along the flow; across it the ground is the bed inside the channel and rises smoothly over
//! `bank_width` to the bank height outside. Beyond the banks the ground may go on rising, by
//! `valley_height` over `valley_width` on each side, so the river runs in a valley (issue 18): land
//! higher on both sides, as a river that cut its bed has (a smoothstep profile, the same as the
//! banks', so the valley floor, its sides and the land above join without a crease).

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
    /// Horizontal run (m) of each valley side, from the top of the bank to the valley's rim,
    /// in [0, 1e5]. Default 0 (no valley: the land stays at the bank height).
    pub valley_width: f32,
    /// Height (m) of the valley's rim above the bank height, in [0, 1e5]. Default 0.
    pub valley_height: f32,
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
            valley_width: 0.0,
            valley_height: 0.0,
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
        check_positive(&format!("{key}.meander_wavelength"), self.meander_wavelength)?;
        check_range(&format!("{key}.valley_width"), self.valley_width, 0.0, MAX_AMPLITUDE)?;
        check_range(&format!("{key}.valley_height"), self.valley_height, 0.0, MAX_AMPLITUDE)
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
        let bank = self.bed_height + (self.bank_height - self.bed_height) * smoothstep(t);
        if self.valley_width <= 0.0 || self.valley_height <= 0.0 {
            return bank;
        }
        let v = ((outside - self.bank_width) / self.valley_width).clamp(0.0, 1.0);
        bank + self.valley_height * smoothstep(v)
    }
}

/// `3t² − 2t³`: 0 and 1 at t = 0 and 1 with zero slope at both ends.
fn smoothstep(t: f32) -> f32 {
    t * t * (3.0 - 2.0 * t)
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

    #[test]
    fn a_valley_rises_on_both_sides_beyond_the_banks() {
        let p = ChannelParams { valley_width: 30.0, valley_height: 12.0, ..Default::default() };
        // Flow along +X: the bed at |z| <= 10, banks to |z| = 16, the valley side to |z| = 46.
        for z in [-1.0f32, 1.0] {
            assert_eq!(p.height_at(5.0, 5.0 * z), -1.5);
            assert_eq!(p.height_at(5.0, 16.0 * z), 2.0);
            assert!((p.height_at(5.0, 31.0 * z) - 8.0).abs() < 1e-4);
            assert_eq!(p.height_at(5.0, 46.0 * z), 14.0);
            assert_eq!(p.height_at(5.0, 90.0 * z), 14.0);
        }
        let mut last = f32::MIN;
        for k in 0..100 {
            let h = p.height_at(0.0, k as f32);
            assert!(h >= last, "the valley side falls at z = {k}");
            last = h;
        }
        let e = ChannelParams { valley_height: -1.0, ..Default::default() }.validate("terrain").unwrap_err();
        assert_eq!(e.to_string(), "terrain.valley_height = -1 is outside [0, 100000]");
        let e = ChannelParams { valley_width: f32::INFINITY, ..Default::default() }.validate("terrain").unwrap_err();
        assert!(e.to_string().starts_with("terrain.valley_width = inf"), "{e}");
    }
}
