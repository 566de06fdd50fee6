//! The structure of foam: a tiling pattern of bubble cells that the foam coverage reveals from its
//! densest parts outwards, so whitecaps read as foam (solid on fresh crests, lace and streaks where
//! it thins behind them) instead of a grey blend.
//!
//! The idea is the one Crest uses for its whitecaps (`Crest/Shaders/OceanFoam.hlsl`,
//! `WhiteFoamTexture`: a tiling foam texture compared against the simulated foam amount, with a
//! feather): a texel shows foam when its pattern value is above a threshold that falls as the
//! coverage rises. swell makes the pattern's values **uniform** on [0, 1] (rank-equalised when
//! built), and puts the threshold where the expected foam over the tile is exactly the coverage
//! ([`FoamPattern::threshold_lanes`]): the foam an image shows has the coverage the simulation
//! (and `swell stats`) reports, whatever the pattern.
//!
//! The procedural pattern is Worley's cellular noise (Worley 1996, "A cellular texture basis
//! function", SIGGRAPH): `F2 − F1`, the distance to the second-nearest minus the nearest of
//! jittered feature points, is small along the borders between cells, which is where the foam of
//! a bursting bubble raft stays longest. Two scales (rafts and bubbles) are summed.
//!
//! [`WaterMaterial::load_foam_pattern`] builds the pattern a water material names.

use crate::error::{Error, Result};
use crate::math::Lanes;
use crate::scene::WaterMaterial;

use super::Texture;

/// Texels per side of the pattern tile (a power of two, for the wrap by mask).
pub const FOAM_PATTERN_SIDE: usize = 256;

/// Coarse cells per tile side (bubble rafts, a few metres across at the default scale).
const RAFT_CELLS: usize = 5;
/// Fine cells per tile side (the bubbles and holes inside a raft).
const BUBBLE_CELLS: usize = 13;
/// Weight of the rafts' borders against the bubbles' in the pattern, [0, 1].
const RAFT_WEIGHT: f32 = 0.6;

/// A tiling foam pattern, values uniform on [0, 1] (higher: foam stays longer there).
#[derive(Clone, Debug, PartialEq)]
pub struct FoamPattern {
    /// Row-major, [`FOAM_PATTERN_SIDE`]² values: a fixed-size array, so that an index masked to
    /// it needs no bounds check in the per-lane read.
    texels: Box<[f32; TEXELS]>,
}

/// Texels in the tile.
const TEXELS: usize = FOAM_PATTERN_SIDE * FOAM_PATTERN_SIDE;

impl Default for FoamPattern {
    fn default() -> Self {
        Self::procedural()
    }
}

impl FoamPattern {
    /// The procedural pattern: Worley `F2 − F1` borders of rafts and bubbles, equalised.
    pub fn procedural() -> Self {
        let rafts = worley_borders(RAFT_CELLS, 0x9e37_79b9);
        let bubbles = worley_borders(BUBBLE_CELLS, 0x85eb_ca6b);
        let raw = rafts.iter().zip(&bubbles).map(|(r, b)| RAFT_WEIGHT * r + (1.0 - RAFT_WEIGHT) * b).collect();
        Self::from_values(raw)
    }

    /// The pattern of `raw` values (row-major, [`FOAM_PATTERN_SIDE`]²), equalised.
    fn from_values(raw: Vec<f32>) -> Self {
        let texels = equalised(raw).into_boxed_slice().try_into().unwrap_or_else(|_| Box::new([0.5; TEXELS]));
        Self { texels }
    }

    /// The pattern of an image: its luminance resampled (nearest) to the tile, equalised (only the
    /// order of its values matters, so any grey levels serve).
    pub fn from_texture(texture: &Texture) -> Self {
        let n = FOAM_PATTERN_SIDE;
        let raw = (0..n * n)
            .map(|i| {
                let uv = glam::Vec2::new(((i % n) as f32 + 0.5) / n as f32, ((i / n) as f32 + 0.5) / n as f32);
                texture.sample(uv).dot(glam::Vec3::new(0.2126, 0.7152, 0.0722))
            })
            .collect();
        Self::from_values(raw)
    }

    /// `"procedural"` or the image file at `path`; `key` names the key that named it in errors.
    pub fn load(name: &str, key: &str) -> Result<Self> {
        match name {
            // The procedural tile depends on nothing: built once per process (about 50 ms), not
            // again for every world, which the viewer rebuilds on each material edit.
            "procedural" => {
                static PROCEDURAL: std::sync::OnceLock<FoamPattern> = std::sync::OnceLock::new();
                Ok(PROCEDURAL.get_or_init(Self::procedural).clone())
            }
            path => Texture::from_file(std::path::Path::new(path))
                .map(|t| Self::from_texture(&t))
                // A file that cannot be read is named with the key that names it.
                .map_err(|e| Error::invalid(key, format!("foam texture \"{path}\": {e}"))),
        }
    }

    /// The pattern's value at texel (`u`, `v`) in tile units (wrapped), nearest texel.
    pub fn value(&self, u: f32, v: f32) -> f32 {
        self.values_lanes(Lanes::splat(u), Lanes::splat(v)).0[0]
    }

    /// [`Self::value`] per lane: the texel index computed for all lanes at once, then one read
    /// per lane (the only per-lane step).
    #[inline(always)]
    pub fn values_lanes(&self, u: Lanes, v: Lanes) -> Lanes {
        let side = FOAM_PATTERN_SIDE as f32;
        let (u, v) = (u * side, v * side);
        // Plain loops over arrays (no closures, which would be compiled apart from the AVX2
        // kernel): the indices as vector arithmetic, the integer wrap by mask keeping negative
        // coordinates on the tile; then the reads.
        let mask = FOAM_PATTERN_SIDE as i32 - 1;
        let mut index = [0usize; crate::math::LANES];
        for (i, o) in index.iter_mut().enumerate() {
            let (x, y) = (u.0[i].floor() as i32 & mask, v.0[i].floor() as i32 & mask);
            *o = (y * FOAM_PATTERN_SIDE as i32 + x) as usize;
        }
        let mut out = [0.0f32; crate::math::LANES];
        for (o, &k) in out.iter_mut().zip(&index) {
            *o = self.texels[k & (TEXELS - 1)];
        }
        Lanes(out)
    }

    /// The threshold `e` per lane at which the pattern shows foam of coverage `coverage` in [0, 1]
    /// with an edge ramp `feather` wide ([`Self::alpha_lanes`]): the mean over the tile of
    /// `clamp((value − e) / feather, 0, 1)` for uniform values is `1 − e − feather / 2` while the
    /// ramp lies inside [0, 1], and the quadratic ends where it leaves it, so `e` inverts that
    /// mean to equal the coverage exactly.
    #[inline(always)]
    pub fn threshold_lanes(coverage: Lanes, feather: f32) -> Lanes {
        let c = coverage.max(0.0).min(1.0);
        let f = feather.max(1e-6);
        let low = 1.0 - (2.0 * f * c).sqrt();
        let high = (2.0 * f * (1.0 - c)).sqrt() - f;
        let mid = 1.0 - c - 0.5 * f;
        c.lt(0.5 * f).select(low, c.gt(1.0 - 0.5 * f).select(high, mid))
    }

    /// How much of each lane is foam, [0, 1]: the pattern at (`u`, `v`) (tile units) above the
    /// threshold for `coverage` ([`Self::threshold_lanes`]), ramped over `feather`. Its mean over
    /// a tile is the coverage.
    #[inline(always)]
    pub fn alpha_lanes(&self, u: Lanes, v: Lanes, coverage: Lanes, feather: f32) -> Lanes {
        let e = Self::threshold_lanes(coverage, feather);
        ((self.values_lanes(u, v) - e) * (1.0 / feather.max(1e-6))).max(0.0).min(1.0)
    }
}

/// Worley `F2 − F1` on a `cells`² grid of jittered points over the unit torus, mapped to [0, 1]
/// with 1 on the borders between cells (`FOAM_PATTERN_SIDE`² texels, row-major).
fn worley_borders(cells: usize, seed: u32) -> Vec<f32> {
    let n = FOAM_PATTERN_SIDE;
    let cell = 1.0 / cells as f32;
    // One feature point per cell, at a hashed offset inside it: the same on every run.
    let point = |cx: usize, cy: usize| {
        let h = hash(seed ^ (cx as u32).wrapping_mul(0x27d4_eb2d) ^ (cy as u32).wrapping_mul(0x1656_67b1));
        let jx = (h & 0xffff) as f32 / 65536.0;
        let jy = (h >> 16) as f32 / 65536.0;
        ((cx as f32 + jx) * cell, (cy as f32 + jy) * cell)
    };
    let mut out = Vec::with_capacity(n * n);
    for j in 0..n {
        for i in 0..n {
            let (x, y) = ((i as f32 + 0.5) / n as f32, (j as f32 + 0.5) / n as f32);
            let (cx, cy) = ((x * cells as f32) as usize, (y * cells as f32) as usize);
            let (mut f1, mut f2) = (f32::INFINITY, f32::INFINITY);
            // The nearest two points lie in the 5 x 5 cells around (jitter reaches a whole cell).
            for dy in 0..5 {
                for dx in 0..5 {
                    let (gx, gy) = ((cx + cells * 2 + dx - 2) % cells, (cy + cells * 2 + dy - 2) % cells);
                    let (px, py) = point(gx, gy);
                    // Distance on the torus (the tile repeats); squared until the end.
                    let (ddx, ddy) = (wrap(px - x), wrap(py - y));
                    let d = ddx * ddx + ddy * ddy;
                    if d < f1 {
                        f2 = f1;
                        f1 = d;
                    } else if d < f2 {
                        f2 = d;
                    }
                }
            }
            // Borders are where F2 − F1 is 0; a cell's centre is about half a cell from both.
            out.push((1.0 - (f2.sqrt() - f1.sqrt()) / cell).clamp(0.0, 1.0));
        }
    }
    out
}

/// A coordinate difference on the unit torus, into [-1/2, 1/2] (differences lie in (-1, 1)).
fn wrap(d: f32) -> f32 {
    if d > 0.5 {
        d - 1.0
    } else if d < -0.5 {
        d + 1.0
    } else {
        d
    }
}

/// Values replaced by their rank, scaled to (0, 1): uniform, with ties broken by index (so the
/// same on every run).
fn equalised(raw: Vec<f32>) -> Vec<f32> {
    let mut order: Vec<usize> = (0..raw.len()).collect();
    order.sort_by(|&a, &b| raw[a].total_cmp(&raw[b]).then(a.cmp(&b)));
    let mut out = vec![0.0; raw.len()];
    let n = raw.len() as f32;
    for (rank, &i) in order.iter().enumerate() {
        out[i] = (rank as f32 + 0.5) / n;
    }
    out
}

/// A 32-bit integer hash (Wang's): the jitter of the feature points.
fn hash(mut x: u32) -> u32 {
    x = (x ^ 61) ^ (x >> 16);
    x = x.wrapping_mul(9);
    x ^= x >> 4;
    x = x.wrapping_mul(0x27d4_eb2d);
    x ^ (x >> 15)
}

impl WaterMaterial {
    /// Loads (or generates) the foam pattern the material names (`foam_texture`); a file that
    /// cannot be read is an error naming `water.material.foam_texture` and the file.
    pub fn load_foam_pattern(&self) -> Result<FoamPattern> {
        FoamPattern::load(self.foam_texture.as_deref().unwrap_or("procedural"), "water.material.foam_texture")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_pattern_is_uniform_and_tiles() {
        let p = FoamPattern::procedural();
        let mean = p.texels.iter().sum::<f32>() / p.texels.len() as f32;
        assert!((mean - 0.5).abs() < 1e-3);
        // Wraps: a whole tile away is the same texel, negative coordinates too.
        assert_eq!(p.value(0.3, 0.7), p.value(1.3, -0.3));
        assert_eq!(FoamPattern::procedural(), p, "deterministic");
    }

    #[test]
    fn the_foam_over_a_tile_has_the_coverage() {
        let p = FoamPattern::procedural();
        let n = FOAM_PATTERN_SIDE;
        for feather in [0.05f32, 0.2, 0.6] {
            for c in [0.0f32, 0.01, 0.03, 0.1, 0.3, 0.5, 0.8, 0.97, 1.0] {
                let mut sum = 0.0f64;
                for j in 0..n {
                    let u = Lanes::from_fn(|i| ((i % n) as f32 + 0.5) / n as f32);
                    for start in (0..n).step_by(crate::math::LANES) {
                        let u = u + start as f32 / n as f32;
                        let v = Lanes::splat((j as f32 + 0.5) / n as f32);
                        let a = p.alpha_lanes(u, v, Lanes::splat(c), feather);
                        sum += a.0.iter().map(|&x| f64::from(x)).sum::<f64>();
                    }
                }
                let mean = sum / (n * n) as f64;
                assert!((mean - f64::from(c)).abs() < 2e-3, "feather {feather}, coverage {c}: foam {mean}");
            }
        }
    }

    #[test]
    fn thin_foam_lies_on_the_cell_borders() {
        // At low coverage the foam is the highest values: the borders, a connected lace, not a
        // scatter of single texels. Most foam texels at 5 % coverage have a foam neighbour.
        let p = FoamPattern::procedural();
        let n = FOAM_PATTERN_SIDE;
        let e = FoamPattern::threshold_lanes(Lanes::splat(0.05), 0.05).0[0];
        let foam = |i: usize, j: usize| p.texels[(j % n) * n + (i % n)] > e;
        let (mut total, mut joined) = (0, 0);
        for j in 0..n {
            for i in 0..n {
                if foam(i, j) {
                    total += 1;
                    if foam(i + 1, j) || foam(i + n - 1, j) || foam(i, j + 1) || foam(i, j + n - 1) {
                        joined += 1;
                    }
                }
            }
        }
        assert!(joined as f32 > 0.9 * total as f32, "{joined} of {total}");
    }
}
