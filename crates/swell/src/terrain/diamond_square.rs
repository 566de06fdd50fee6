//! Diamond-square (paper 001 §1.3.4 and §2.1): midpoint displacement on a (2^n + 1)^2 grid.
//!
//! From the four corners, each level halves the squares: the **diamond** step sets every square's
//! centre to the mean of its four corners plus a random offset; the **square** step sets every edge
//! midpoint to the mean of its (up to four) diamond neighbours plus a random offset. The random range
//! is multiplied by `roughness` after each level (paper 001: halved, i.e. proportional to the segment
//! length as midpoint displacement requires). Optional smoothing passes follow (paper 001 §2.1).
//!
//! Departures from the paper, on purpose:
//! - the paper pins every border vertex to zero so the land sinks at the edges; swell does so when
//!   `edge_height` is set (paper: 0), and otherwise lets the border vary, averaging the three
//!   neighbours that exist (the paper's "ignore points outside the map" option);
//! - an optional `center` fixes the first diamond value, which makes valleys (low centre) and
//!   mountains (high centre) on demand;
//! - each offset comes from a hash of (seed, level, x, y) ([`super::lattice_random`]) rather than from a
//!   sequential generator, so a level's points are independent and computed in parallel with a
//!   result that is bit-identical on any number of threads.

use glam::Vec2;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use super::height_field::{HeightField, MAX_TERRAIN_SIZE};
use super::lattice_random::LatticeRandom;
use super::smoothing::{smooth, MAX_SMOOTHING_PASSES};
use super::{GeneratorParams, DEFAULT_TERRAIN_EXTENT};
use crate::error::{check_count, check_finite_vec, check_non_negative, check_range, check_seed, Error, Result};

/// Largest offset range (m) a scene may ask for; ten times Everest's height above sea level.
pub const MAX_AMPLITUDE: f32 = 1.0e5;

/// Parameters of diamond-square. In a scene file: the keys of `[terrain]` when
/// `generator = "diamond-square"`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct DiamondSquareParams {
    /// Heights (m) of the corners at model (-x, -z), (+x, -z), (-x, +z), (+x, +z); kept exactly when
    /// `smoothing` is 0. Default all 0.
    pub corners: [f32; 4],
    /// Height (m) forced at the centre instead of the first random diamond value; absent = random.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub center: Option<f32>,
    /// Height (m) every border vertex is pinned to (paper 001 §2.1 pins them to 0, so the land
    /// sinks at the edges); absent = borders are generated like the interior. The corners keep
    /// `corners`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub edge_height: Option<f32>,
    /// Offsets of the first level are uniform in ±`amplitude` metres, in [0, [`MAX_AMPLITUDE`]].
    /// Default 20.
    pub amplitude: f32,
    /// Factor applied to the offset range after each level, in [0, 1]: 0.5 is paper 001's halving
    /// (offsets proportional to the square's size). As in fractional Brownian motion (Fournier,
    /// Fussell and Carpenter, CACM 1982) `roughness = 2^-H` for a Hurst exponent H, the surface's
    /// fractal dimension being about `3 - H`: higher is rougher, lower smoother. Default 0.5.
    pub roughness: f32,
    /// Neighbour-averaging passes after generation (paper 001 §2.1), in [0, 64]. Default 0.
    pub smoothing: u32,
    /// Seed of the random offsets, in [0, 2^63 - 1]. Default 1.
    pub seed: u64,
}

impl Default for DiamondSquareParams {
    fn default() -> Self {
        Self {
            corners: [0.0; 4],
            center: None,
            edge_height: None,
            amplitude: 20.0,
            roughness: 0.5,
            smoothing: 0,
            seed: 1,
        }
    }
}

impl DiamondSquareParams {
    /// Checks every field, naming keys under `key` (normally `terrain`).
    pub fn validate(&self, key: &str) -> Result<()> {
        check_finite_vec(&format!("{key}.corners"), &self.corners)?;
        if let Some(c) = self.center {
            check_range(&format!("{key}.center"), c, -MAX_AMPLITUDE, MAX_AMPLITUDE)?;
        }
        if let Some(e) = self.edge_height {
            check_range(&format!("{key}.edge_height"), e, -MAX_AMPLITUDE, MAX_AMPLITUDE)?;
        }
        check_non_negative(&format!("{key}.amplitude"), self.amplitude)?;
        check_range(&format!("{key}.amplitude"), self.amplitude, 0.0, MAX_AMPLITUDE)?;
        check_range(&format!("{key}.roughness"), self.roughness, 0.0, 1.0)?;
        check_count(&format!("{key}.smoothing"), self.smoothing, 0, MAX_SMOOTHING_PASSES)?;
        check_seed(&format!("{key}.seed"), self.seed)
    }
}

/// Checks that `size` is 2^n + 1 with n >= 1 and at most [`MAX_TERRAIN_SIZE`]; the error states the
/// rule and the nearest valid sizes.
pub fn check_diamond_square_size(key: &str, size: u32) -> Result<()> {
    let cells = size.wrapping_sub(1);
    if (3..=MAX_TERRAIN_SIZE).contains(&size) && cells.is_power_of_two() {
        return Ok(());
    }
    let max_n = (MAX_TERRAIN_SIZE - 1).ilog2();
    let valid: Vec<u32> = (1..=max_n).map(|n| (1u32 << n) + 1).collect();
    let nearest = valid.iter().copied().min_by_key(|&v| v.abs_diff(size)).unwrap_or(3);
    Err(Error::invalid(
        key,
        format!(
            "{size} is not a diamond-square size: the grid must be 2^n + 1 vertices per side \
             (n in [1, {}]: {}) so every square has a centre vertex at every level; nearest: {nearest}",
            max_n,
            valid.iter().map(u32::to_string).collect::<Vec<_>>().join(", ")
        ),
    ))
}

/// Generates a `size` x `size` field spanning `extent` metres; `size` must be 2^n + 1.
///
/// Work is O(size^2); levels run one after another, the points of one step in parallel.
pub fn diamond_square(size: u32, extent: Vec2, p: &DiamondSquareParams) -> Result<HeightField> {
    check_diamond_square_size("terrain.size", size)?;
    p.validate("terrain")?;
    let n = size as usize;
    let cells = n - 1;
    let mut h = vec![0.0f32; n * n];
    h[0] = p.corners[0];
    h[cells] = p.corners[1];
    h[cells * n] = p.corners[2];
    h[cells * n + cells] = p.corners[3];
    let random = LatticeRandom::new(p.seed);
    let (mut step, mut level, mut range) = (cells, 0u32, p.amplitude);
    while step > 1 {
        let forced_center = if level == 0 { p.center } else { None };
        Level { n, step, level, range, random, forced_center, edge: p.edge_height }.run(&mut h);
        range *= p.roughness;
        step /= 2;
        level += 1;
    }
    smooth(&mut h, n, n, p.smoothing);
    HeightField::new(size, size, extent, h)
}

/// One level: squares of `step` cells split into four.
///
/// The grid is cut into bands of `half = step / 2` rows. The first row of an even band (row
/// `k * step`) holds the level's corners; the first row of an odd band (row `k * step + half`) holds
/// its square centres. Each step writes rows of one parity while reading only rows of the other
/// parity (and, within the row it writes, only columns it does not write), so bands are processed
/// in parallel with plain borrows and every point sees exactly the values the sequential
/// algorithm would.
struct Level {
    /// Vertices per side.
    n: usize,
    /// Side of the squares being split, in cells.
    step: usize,
    level: u32,
    /// Offsets are uniform in ±range metres.
    range: f32,
    random: LatticeRandom,
    forced_center: Option<f32>,
    /// Pinned border height, if any.
    edge: Option<f32>,
}

impl Level {
    fn offset(&self, x: usize, y: usize) -> f32 {
        self.range * self.random.at(self.level, x as u32, y as u32)
    }

    fn run(&self, h: &mut [f32]) {
        let (n, step, half) = (self.n, self.step, self.step / 2);
        let mut corner_rows: Vec<&mut [f32]> = Vec::with_capacity(n / step + 1);
        let mut centre_rows: Vec<&mut [f32]> = Vec::with_capacity(n / step);
        for (b, band) in h.chunks_mut(n * half).enumerate() {
            let row = &mut band[..n];
            if b % 2 == 0 {
                corner_rows.push(row);
            } else {
                centre_rows.push(row);
            }
        }
        // Diamond step: centre (x, y) = mean of its four corners + offset.
        {
            let corners: Vec<&[f32]> = corner_rows.iter().map(|r| &**r).collect();
            centre_rows.par_iter_mut().enumerate().for_each(|(k, row)| {
                let (up, down) = (corners[k], corners[k + 1]);
                let y = k * step + half;
                for x in (half..n).step_by(step) {
                    row[x] = match self.forced_center {
                        Some(c) => c,
                        None => {
                            0.25 * (up[x - half] + up[x + half] + down[x - half] + down[x + half]) + self.offset(x, y)
                        }
                    };
                }
            });
        }
        // Square step on corner rows: edge midpoints between two corners of the same row, with the
        // centres above and below (missing outside the map: paper 001 §1.3.4 leaves them out).
        {
            let centres: Vec<&[f32]> = centre_rows.iter().map(|r| &**r).collect();
            corner_rows.par_iter_mut().enumerate().for_each(|(k, row)| {
                let (above, below) = (k.checked_sub(1).map(|a| centres[a]), centres.get(k).copied());
                let y = k * step;
                for x in (half..n).step_by(step) {
                    let mut sum = row[x - half] + row[x + half];
                    let mut count = 2.0;
                    for r in [above, below].into_iter().flatten() {
                        sum += r[x];
                        count += 1.0;
                    }
                    row[x] = match self.edge {
                        Some(e) if y == 0 || y == n - 1 => e,
                        _ => sum / count + self.offset(x, y),
                    };
                }
            });
        }
        // Square step on centre rows: edge midpoints between two corners above and below, with the
        // centres left and right in the same row.
        {
            let corners: Vec<&[f32]> = corner_rows.iter().map(|r| &**r).collect();
            centre_rows.par_iter_mut().enumerate().for_each(|(k, row)| {
                let (up, down) = (corners[k], corners[k + 1]);
                let y = k * step + half;
                for x in (0..n).step_by(step) {
                    let mut sum = up[x] + down[x];
                    let mut count = 2.0;
                    if x >= half {
                        sum += row[x - half];
                        count += 1.0;
                    }
                    if x + half < n {
                        sum += row[x + half];
                        count += 1.0;
                    }
                    row[x] = match self.edge {
                        Some(e) if x == 0 || x == n - 1 => e,
                        _ => sum / count + self.offset(x, y),
                    };
                }
            });
        }
    }
}

impl GeneratorParams for DiamondSquareParams {
    fn validate(&self, key: &str) -> Result<()> {
        DiamondSquareParams::validate(self, key)
    }

    /// Diamond-square needs 2^n + 1 vertices per side.
    fn check_size(&self, key: &str, size: u32) -> Result<()> {
        check_diamond_square_size(key, size)
    }

    fn generate(&self, size: u32, extent: Option<Vec2>) -> Result<HeightField> {
        diamond_square(size, extent.unwrap_or(DEFAULT_TERRAIN_EXTENT), self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn params(roughness: f32, seed: u64) -> DiamondSquareParams {
        DiamondSquareParams { corners: [1.0, -2.0, 3.5, 7.0], roughness, seed, ..Default::default() }
    }

    #[test]
    fn only_two_to_the_n_plus_one_sizes_are_accepted() {
        for size in [3, 5, 9, 17, 33, 65, 129, 257] {
            assert!(diamond_square(size, Vec2::ONE, &params(0.5, 1)).is_ok(), "{size}");
        }
        for size in [0, 1, 2, 4, 6, 100, 256, 258, 1000, 4096, 8193] {
            let e = diamond_square(size, Vec2::ONE, &params(0.5, 1)).unwrap_err().to_string();
            assert!(e.starts_with(&format!("terrain.size: {size} is not")), "{e}");
            assert!(e.contains("2^n + 1") && e.contains("257, 513, 1025"), "{e}");
        }
        let e = diamond_square(1000, Vec2::ONE, &params(0.5, 1)).unwrap_err().to_string();
        assert!(e.ends_with("nearest: 1025"), "{e}");
    }

    #[test]
    fn deterministic_per_seed_and_keeps_corners() {
        let a = diamond_square(65, Vec2::splat(100.0), &params(0.5, 42)).unwrap();
        let b = diamond_square(65, Vec2::splat(100.0), &params(0.5, 42)).unwrap();
        let c = diamond_square(65, Vec2::splat(100.0), &params(0.5, 43)).unwrap();
        assert_eq!(a, b);
        assert_ne!(a.heights(), c.heights());
        assert_eq!([a.height(0, 0), a.height(64, 0), a.height(0, 64), a.height(64, 64)], [1.0, -2.0, 3.5, 7.0]);
        // Every vertex was written: with amplitude 20 m no interior point stays exactly 0.
        assert!(a.heights().iter().filter(|&&h| h == 0.0).count() <= 1);
    }

    #[test]
    fn a_forced_centre_and_pinned_edges_are_kept() {
        let p = DiamondSquareParams { center: Some(-15.0), edge_height: Some(0.5), ..params(0.5, 3) };
        let f = diamond_square(33, Vec2::ONE, &p).unwrap();
        assert_eq!(f.height(16, 16), -15.0);
        for k in 1..32 {
            assert_eq!([f.height(k, 0), f.height(k, 32), f.height(0, k), f.height(32, k)], [0.5; 4]);
        }
        assert_eq!(f.height(32, 32), 7.0);
        assert!(f.height(5, 7) != 0.5);
    }

    /// Mean absolute difference between horizontal neighbours.
    fn neighbour_difference(f: &HeightField) -> f32 {
        let mut sum = 0.0;
        for j in 0..f.rows() {
            for i in 0..f.cols() - 1 {
                sum += (f.height(i + 1, j) - f.height(i, j)).abs();
            }
        }
        sum / (f.rows() * (f.cols() - 1)) as f32
    }

    #[test]
    fn height_differences_grow_with_roughness() {
        let mut last = 0.0;
        for r in [0.3, 0.5, 0.7, 0.9] {
            let f = diamond_square(129, Vec2::ONE, &params(r, 9)).unwrap();
            let d = neighbour_difference(&f);
            assert!(d > 1.5 * last, "roughness {r}: neighbour difference {d} vs {last}");
            last = d;
        }
        // Roughness 0 leaves only the first level's offsets: a smooth, piecewise-linear surface.
        let f = diamond_square(129, Vec2::ONE, &params(0.0, 9)).unwrap();
        assert!(neighbour_difference(&f) < 0.5, "{}", neighbour_difference(&f));
    }

    #[test]
    fn smoothing_lowers_differences() {
        let raw = diamond_square(65, Vec2::ONE, &params(0.7, 5)).unwrap();
        let smooth = diamond_square(65, Vec2::ONE, &DiamondSquareParams { smoothing: 2, ..params(0.7, 5) }).unwrap();
        assert!(neighbour_difference(&smooth) < 0.7 * neighbour_difference(&raw));
    }

    #[test]
    fn one_and_two_threads_give_identical_fields() {
        let run = |threads| {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            pool.install(|| {
                diamond_square(257, Vec2::splat(500.0), &DiamondSquareParams { smoothing: 1, ..params(0.55, 11) })
            })
            .unwrap()
        };
        let (a, b) = (run(1), run(2));
        assert!(a.heights().iter().zip(b.heights()).all(|(x, y)| x.to_bits() == y.to_bits()));
    }
}
