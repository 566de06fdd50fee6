//! Perlin-noise terrain (paper 001 §1.3.2): fractional Brownian motion of gradient noise.
//!
//! `h(x, z) = amplitude * fbm(x / scale, z / scale) / sum_o persistence^o`, with
//! `fbm = sum_{o < octaves} persistence^o noise(lacunarity^o p)` from [`Perlin`]; the division keeps
//! heights within about ± `amplitude` whatever the octave count.

use glam::{Vec2, Vec3};
use serde::{Deserialize, Serialize};

use super::diamond_square::MAX_AMPLITUDE;
use super::height_field::{HeightField, MAX_TERRAIN_SIZE};
use super::{GeneratorParams, DEFAULT_TERRAIN_EXTENT};
use crate::error::check_seed;
use crate::error::{check_count, check_positive, check_range, Result};
use crate::math::Perlin;

/// Parameters of fBm noise terrain; `[terrain]` keys for `generator = "noise"`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct NoiseTerrainParams {
    /// Heights stay within about ± `amplitude` metres, in [0, 1e5]. Default 20.
    pub amplitude: f32,
    /// Size (m) of the first octave's noise cell, i.e. of the largest features, > 0. Default 100.
    pub scale: f32,
    /// Number of octaves, in [1, 16]. Default 6.
    pub octaves: u32,
    /// Amplitude ratio between successive octaves, in [0, 1]. Default 0.5.
    pub persistence: f32,
    /// Frequency ratio between successive octaves, in [1, 4]. Default 2.
    pub lacunarity: f32,
    /// Seed of the noise permutation, in [0, 2^63 - 1]. Default 1.
    pub seed: u64,
}

impl Default for NoiseTerrainParams {
    fn default() -> Self {
        Self { amplitude: 20.0, scale: 100.0, octaves: 6, persistence: 0.5, lacunarity: 2.0, seed: 1 }
    }
}

impl NoiseTerrainParams {
    /// Checks every field, naming keys under `key`.
    pub fn validate(&self, key: &str) -> Result<()> {
        check_range(&format!("{key}.amplitude"), self.amplitude, 0.0, MAX_AMPLITUDE)?;
        check_positive(&format!("{key}.scale"), self.scale)?;
        check_count(&format!("{key}.octaves"), self.octaves, 1, 16)?;
        check_range(&format!("{key}.persistence"), self.persistence, 0.0, 1.0)?;
        check_range(&format!("{key}.lacunarity"), self.lacunarity, 1.0, 4.0)?;
        check_seed(&format!("{key}.seed"), self.seed)
    }
}

/// Generates a `size` x `size` field spanning `extent` metres.
pub fn noise_terrain(size: u32, extent: Vec2, p: &NoiseTerrainParams) -> Result<HeightField> {
    check_count("terrain.size", size, 2, MAX_TERRAIN_SIZE)?;
    p.validate("terrain")?;
    let noise = Perlin::new(p.seed);
    let norm: f32 = (0..p.octaves).map(|o| p.persistence.powi(o as i32)).sum();
    let k = p.amplitude / norm;
    HeightField::from_fn(size, size, extent, |x, z| {
        // The noise lattice plane z = 0.5 avoids the integer plane where one axis of the 3-D
        // gradients cancels.
        let q = Vec3::new(x / p.scale, z / p.scale, 0.5);
        k * noise.fbm3_with_gradient(q, p.octaves, p.persistence, p.lacunarity).0
    })
}

impl GeneratorParams for NoiseTerrainParams {
    fn validate(&self, key: &str) -> Result<()> {
        NoiseTerrainParams::validate(self, key)
    }

    fn generate(&self, size: u32, extent: Option<Vec2>) -> Result<HeightField> {
        noise_terrain(size, extent.unwrap_or(DEFAULT_TERRAIN_EXTENT), self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bounded_seeded_and_continuous() {
        let p = NoiseTerrainParams { amplitude: 8.0, scale: 20.0, ..Default::default() };
        let a = noise_terrain(65, Vec2::splat(100.0), &p).unwrap();
        assert!(a.heights().iter().all(|h| h.abs() <= 8.0 * 1.1));
        let (lo, hi) = a.min_max();
        assert!(hi - lo > 2.0, "{lo}..{hi}");
        assert_eq!(a, noise_terrain(65, Vec2::splat(100.0), &p).unwrap());
        assert_ne!(a, noise_terrain(65, Vec2::splat(100.0), &NoiseTerrainParams { seed: 2, ..p.clone() }).unwrap());
        // Neighbours 1.6 m apart on 20 m features differ by far less than the range.
        for j in 0..64 {
            for i in 0..64 {
                assert!((a.height(i + 1, j) - a.height(i, j)).abs() < 0.25 * (hi - lo));
            }
        }
    }
}
