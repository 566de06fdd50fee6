//! Paper 001's "simple" algorithm (§1.3.1): random heights, then neighbour averaging.
//!
//! Step 1 fills the map with uniform random heights in ±`amplitude`; step 2 replaces each height by
//! the mean of itself and its neighbours, `passes` times. The paper notes it looks like broken plain
//! with a small range and jagged peaks with a large one, and that repeating step 2 helps: every
//! pass averages over a wider area: for independent heights the standard deviation falls to 1/3
//! after one pass and roughly as `1 / sqrt(8.4 passes)` after several (the 2-D kernel is close to a
//! Gaussian of variance `2 passes / 3` per axis).

use glam::Vec2;
use serde::{Deserialize, Serialize};

use super::diamond_square::MAX_AMPLITUDE;
use super::height_field::{HeightField, MAX_TERRAIN_SIZE};
use super::lattice_random::lattice_random;
use super::smoothing::{smooth, MAX_SMOOTHING_PASSES};
use super::{GeneratorParams, DEFAULT_TERRAIN_EXTENT};
use crate::error::check_seed;
use crate::error::{check_count, check_range, Result};

/// Parameters of the random-then-average generator; `[terrain]` keys for `generator = "random-average"`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RandomAverageParams {
    /// Random heights are uniform in ±`amplitude` metres before averaging, in [0, 1e5]. Default 20.
    pub amplitude: f32,
    /// Averaging passes (paper 001 step 2), in [0, 64]. Default 4.
    pub passes: u32,
    /// Seed, in [0, 2^63 - 1]. Default 1.
    pub seed: u64,
}

impl Default for RandomAverageParams {
    fn default() -> Self {
        Self { amplitude: 20.0, passes: 4, seed: 1 }
    }
}

impl RandomAverageParams {
    /// Checks every field, naming keys under `key`.
    pub fn validate(&self, key: &str) -> Result<()> {
        check_range(&format!("{key}.amplitude"), self.amplitude, 0.0, MAX_AMPLITUDE)?;
        check_count(&format!("{key}.passes"), self.passes, 0, MAX_SMOOTHING_PASSES)?;
        check_seed(&format!("{key}.seed"), self.seed)
    }
}

/// Generates a `size` x `size` field spanning `extent` metres.
pub fn random_average(size: u32, extent: Vec2, p: &RandomAverageParams) -> Result<HeightField> {
    check_count("terrain.size", size, 2, MAX_TERRAIN_SIZE)?;
    p.validate("terrain")?;
    let n = size as usize;
    let mut h: Vec<f32> =
        (0..n * n).map(|k| p.amplitude * lattice_random(p.seed, 0, (k % n) as u32, (k / n) as u32)).collect();
    smooth(&mut h, n, n, p.passes);
    HeightField::new(size, size, extent, h)
}

impl GeneratorParams for RandomAverageParams {
    fn validate(&self, key: &str) -> Result<()> {
        RandomAverageParams::validate(self, key)
    }

    fn generate(&self, size: u32, extent: Option<Vec2>) -> Result<HeightField> {
        random_average(size, extent.unwrap_or(DEFAULT_TERRAIN_EXTENT), self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn std_dev(f: &HeightField) -> f32 {
        let h = f.heights();
        let mean = h.iter().sum::<f32>() / h.len() as f32;
        (h.iter().map(|x| (x - mean).powi(2)).sum::<f32>() / h.len() as f32).sqrt()
    }

    #[test]
    fn more_passes_give_smoother_bounded_terrain() {
        let p = |passes| RandomAverageParams { amplitude: 10.0, passes, seed: 3 };
        let raw = random_average(64, Vec2::ONE, &p(0)).unwrap();
        assert!(raw.heights().iter().all(|h| h.abs() <= 10.0));
        // Uniform on ±10: standard deviation 10 / sqrt(3).
        assert!((std_dev(&raw) - 5.77).abs() < 0.2, "{}", std_dev(&raw));
        let one = random_average(64, Vec2::ONE, &p(1)).unwrap();
        let four = random_average(64, Vec2::ONE, &p(4)).unwrap();
        assert!(std_dev(&one) < 0.5 * std_dev(&raw) && std_dev(&four) < 0.6 * std_dev(&one));
        assert_eq!(four, random_average(64, Vec2::ONE, &p(4)).unwrap());
    }
}
