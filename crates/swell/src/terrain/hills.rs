//! The hill algorithm (paper 001 §1.3.3): many random round hills, normalised, then "valley-ised".
//!
//! Start from zero; `count` times pick a centre on the map or up to `radius_max` beyond its border
//! and a radius in [`radius_min`, `radius_max`], and raise the paraboloid `r^2 - d^2` (d = distance
//! to the centre) where it is positive; normalise the sum to [0, 1]; raise it to the power
//! `flatten` (paper: "make the slopes gentler"; squaring, the usual choice, flattens valleys and
//! keeps peaks); multiply by `height` metres.

use glam::Vec2;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};

use super::diamond_square::MAX_AMPLITUDE;
use super::height_field::{HeightField, MAX_TERRAIN_SIZE};
use super::{GeneratorParams, DEFAULT_TERRAIN_EXTENT};
use crate::error::check_seed;
use crate::error::{check_count, check_positive, check_range, Error, Result};

/// Most hills one terrain may have.
pub const MAX_HILLS: u32 = 100_000;

/// Parameters of the hill algorithm; `[terrain]` keys for `generator = "hills"`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct HillsParams {
    /// Number of hills, in [1, 100000]. Default 200.
    pub count: u32,
    /// Smallest hill radius (m), > 0. Default 5.
    pub radius_min: f32,
    /// Largest hill radius (m), >= `radius_min`. Default 30.
    pub radius_max: f32,
    /// Height (m) of the highest point after normalisation, in [0, 1e5]; the lowest is 0. Default 20.
    pub height: f32,
    /// Exponent applied to the normalised heights, in [1, 8]: 1 keeps them, 2 (default) is the
    /// classic valley flattening.
    pub flatten: f32,
    /// Seed of the hill positions and radii, in [0, 2^63 - 1]. Default 1.
    pub seed: u64,
}

impl Default for HillsParams {
    fn default() -> Self {
        Self { count: 200, radius_min: 5.0, radius_max: 30.0, height: 20.0, flatten: 2.0, seed: 1 }
    }
}

impl HillsParams {
    /// Checks every field, naming keys under `key`.
    pub fn validate(&self, key: &str) -> Result<()> {
        check_count(&format!("{key}.count"), self.count, 1, MAX_HILLS)?;
        check_positive(&format!("{key}.radius_min"), self.radius_min)?;
        check_positive(&format!("{key}.radius_max"), self.radius_max)?;
        if self.radius_max < self.radius_min {
            return Err(Error::out_of_range(
                format!("{key}.radius_max"),
                self.radius_max,
                format!("[radius_min = {}, inf)", self.radius_min),
            ));
        }
        check_range(&format!("{key}.height"), self.height, 0.0, MAX_AMPLITUDE)?;
        check_range(&format!("{key}.flatten"), self.flatten, 1.0, 8.0)?;
        check_seed(&format!("{key}.seed"), self.seed)
    }
}

/// Generates a `size` x `size` field spanning `extent` metres.
pub fn hills(size: u32, extent: Vec2, p: &HillsParams) -> Result<HeightField> {
    check_count("terrain.size", size, 2, MAX_TERRAIN_SIZE)?;
    p.validate("terrain")?;
    // Hills are drawn in sequence from one generator, so the list is fixed by the seed; each vertex
    // then sums them in list order, the same on any thread.
    let mut rng = ChaCha8Rng::seed_from_u64(p.seed);
    let reach = 0.5 * extent + Vec2::splat(p.radius_max);
    let hills: Vec<(Vec2, f32)> = (0..p.count)
        .map(|_| {
            let c = Vec2::new(rng.gen_range(-reach.x..=reach.x), rng.gen_range(-reach.y..=reach.y));
            (c, rng.gen_range(p.radius_min..=p.radius_max))
        })
        .collect();
    let raw = HeightField::from_fn(size, size, extent, |x, z| {
        let q = Vec2::new(x, z);
        hills.iter().map(|&(c, r)| (r * r - q.distance_squared(c)).max(0.0)).sum()
    })?;
    let (lo, hi) = raw.min_max();
    let span = if hi > lo { hi - lo } else { 1.0 };
    HeightField::new(
        size,
        size,
        extent,
        raw.heights().iter().map(|h| p.height * ((h - lo) / span).powf(p.flatten)).collect(),
    )
}

impl GeneratorParams for HillsParams {
    fn validate(&self, key: &str) -> Result<()> {
        HillsParams::validate(self, key)
    }

    fn generate(&self, size: u32, extent: Option<Vec2>) -> Result<HeightField> {
        hills(size, extent.unwrap_or(DEFAULT_TERRAIN_EXTENT), self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn normalised_to_the_height_and_flattened() {
        let p = HillsParams { count: 50, radius_min: 3.0, radius_max: 12.0, height: 10.0, flatten: 1.0, seed: 4 };
        let f = hills(65, Vec2::splat(64.0), &p).unwrap();
        let (lo, hi) = f.min_max();
        assert!(lo.abs() < 1e-5 && (hi - 10.0).abs() < 1e-4, "{lo}..{hi}");
        let g = hills(65, Vec2::splat(64.0), &HillsParams { flatten: 2.0, ..p.clone() }).unwrap();
        // Squaring a [0, 1] field lowers every point in between: valleys flatten, peaks stay.
        let mean = |f: &HeightField| f.heights().iter().sum::<f32>() / f.heights().len() as f32;
        assert!(mean(&g) < mean(&f));
        assert!((g.min_max().1 - 10.0).abs() < 1e-4);
        assert_eq!(g, hills(65, Vec2::splat(64.0), &HillsParams { flatten: 2.0, ..p }).unwrap());
        let e = HillsParams { radius_max: 1.0, ..Default::default() }.validate("terrain").unwrap_err();
        assert!(e.to_string().starts_with("terrain.radius_max = 1 is outside [radius_min = 5"), "{e}");
    }
}
