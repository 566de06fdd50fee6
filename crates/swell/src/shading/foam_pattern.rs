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
//! a bursting bubble raft stays longest. Two scales (rafts and bubbles) are summed, and blended
//! with smooth patches (white noise blurred) on a tile 13/5 times larger: thin foam comes in
//! bodies with lacy edges rather than an even net, and the two tiles repeat together only every 13
//! lace tiles. The blend is mapped back to uniform values ([`uniform_blend`]).
//!
//! # Filtered with distance
//!
//! A cell border thinner than a pixel shimmers and breaks into specks (issue 38 measured the
//! foam of `ocean` at 8 to 10 grey levels RMS from a 4 x 4 supersampled frame between 40 and
//! 200 m, where the sea without foam was within 1). Like a texture's mip-map, the pattern is kept
//! at [`FOAM_PATTERN_LEVELS`] levels of detail, level `k` box-blurred over `2^k` texels and then
//! **equalised again**, so that every level still shows exactly the coverage it is given while its
//! features are never finer than `2^k` texels: the lace of bubbles becomes the soft patches it
//! looks like from afar. [`FoamPattern::filtered_alpha_lanes`] picks the level whose blur matches
//! a pixel's footprint (blending the two nearest) and past the last level hands over to the plain
//! coverage, the mean every level shares. With this the foam-only difference from the supersampled
//! frame is 3 to 5 levels in every band (`tests/foam_filtering.rs`).
//!
//! [`WaterMaterial::load_foam_pattern`] builds the pattern a water material names.

use crate::error::{Error, Result};
use crate::math::{fast_log2, Lanes};
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

/// Width (texels of the patches' own tile) of the box that smooths white noise into the patches
/// of foam bodies; three passes make a bump about this wide.
const PATCH_WIDTH: usize = 24;
/// Weight of the patches against the lace of cell borders, (0.5, 1): the highest values (what a
/// thin coverage shows) are lace inside a patch, so sparse foam comes in bodies with lacy edges.
const PATCH_WEIGHT: f32 = 0.55;
/// Size of the patches' tile over the lace's: 13 / 5, so the two repeat together only every 13
/// lace tiles (78 m at the default `foam_scale`) and the eye finds no grid of repeated shapes.
const PATCH_TILE: f32 = 13.0 / 5.0;

/// Levels of detail of the pattern: level `k` has no feature finer than `2^k` texels (the last,
/// 6, a quarter of the tile).
pub const FOAM_PATTERN_LEVELS: usize = 7;

/// Per level, log2 of how many full-size texels one of its texels spans: levels 0 and 1 are full
/// size, then each is halved, so a level (blurred over `2^k` texels) keeps two texels per blur
/// width. Why: a batch of pixels whose footprint matches a level then reads neighbouring texels,
/// as a mip-map's does; with every level full size (3.6 MB for the lace and the patches) those
/// reads were scattered over the tile and cost the `ocean` frame 4 ms.
const LEVEL_SHIFT: [u32; FOAM_PATTERN_LEVELS] = {
    let mut s = [0; FOAM_PATTERN_LEVELS];
    let mut k = 1;
    while k < FOAM_PATTERN_LEVELS {
        s[k] = k as u32 - 1;
        k += 1;
    }
    s
};

/// Where each level starts in a [`Mips`] (and, last, its length).
const LEVEL_OFFSET: [usize; FOAM_PATTERN_LEVELS + 1] = {
    let mut o = [0; FOAM_PATTERN_LEVELS + 1];
    let mut k = 0;
    while k < FOAM_PATTERN_LEVELS {
        let side = FOAM_PATTERN_SIDE >> LEVEL_SHIFT[k];
        o[k + 1] = o[k] + side * side;
        k += 1;
    }
    o
};

/// Values of all the levels of one tile.
const MIP_TEXELS: usize = LEVEL_OFFSET[FOAM_PATTERN_LEVELS];

/// All the levels of one tile, level `k` row-major at [`LEVEL_OFFSET`]`[k]`, `FOAM_PATTERN_SIDE >>
/// LEVEL_SHIFT[k]` texels a side: a fixed-size array, so that an index clamped to it needs no
/// bounds check in the per-lane read.
type Mips = Box<[f32; MIP_TEXELS]>;

/// A tiling foam pattern, values uniform on [0, 1] (higher: foam stays longer there), at
/// [`FOAM_PATTERN_LEVELS`] levels of detail.
#[derive(Clone, Debug, PartialEq)]
pub struct FoamPattern {
    /// The lace of cell borders (or an image's pattern), every level.
    levels: Mips,
    /// The procedural pattern's patches of foam bodies, every level, on a tile [`PATCH_TILE`]
    /// times larger, blended with `levels` ([`uniform_blend`]); `None` for an image's pattern,
    /// shown as drawn.
    patches: Option<Mips>,
    /// Per level, the mean steepness of the values shown, |gradient| per full-size texel: how
    /// many texels the ramp of a given feather spans there.
    steepness: [f32; FOAM_PATTERN_LEVELS],
}

/// Texels in the full-size tile.
const TEXELS: usize = FOAM_PATTERN_SIDE * FOAM_PATTERN_SIDE;

impl Default for FoamPattern {
    fn default() -> Self {
        Self::procedural()
    }
}

impl FoamPattern {
    /// The procedural pattern: Worley `F2 − F1` borders of rafts and bubbles, equalised, blended
    /// with smooth patches.
    pub fn procedural() -> Self {
        let rafts = worley_borders(RAFT_CELLS, 0x9e37_79b9);
        let bubbles = worley_borders(BUBBLE_CELLS, 0x85eb_ca6b);
        let raw = rafts.iter().zip(&bubbles).map(|(r, b)| RAFT_WEIGHT * r + (1.0 - RAFT_WEIGHT) * b).collect();
        let patches = mip_levels(smooth_patches(PATCH_WIDTH, 0x27d4_eb2d));
        Self::from_levels(mip_levels(raw), Some(patches))
    }

    /// The pattern of `raw` values (row-major, [`FOAM_PATTERN_SIDE`]²), equalised, and its
    /// coarser levels: each the finest blurred over `2^k` texels, equalised again.
    fn from_values(raw: Vec<f32>) -> Self {
        Self::from_levels(mip_levels(raw), None)
    }

    /// The pattern of `levels` (and `patches`, blended in), with the steepness of what it shows.
    fn from_levels(levels: Mips, patches: Option<Mips>) -> Self {
        let steepness = std::array::from_fn(|k| {
            let lace = level_steepness(&levels, k);
            match &patches {
                // In the middle of the blend (most of its range) its slope is (W dP + V dL) / W,
                // the patches' per lace texel 1 / PATCH_TILE of their own: the sum of the two
                // means is the blend's where the two gradients line up, a bound that keeps the
                // ramp at least a pixel wide.
                Some(p) => {
                    (PATCH_WEIGHT * level_steepness(p, k) / PATCH_TILE + (1.0 - PATCH_WEIGHT) * lace) / PATCH_WEIGHT
                }
                None => lace,
            }
        });
        Self { levels, patches, steepness }
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
            // The procedural tile depends on nothing: built once per process (about 80 ms), not
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

    /// The pattern's value at texel (`u`, `v`) in tile units (wrapped), nearest texel, at full
    /// detail.
    pub fn value(&self, u: f32, v: f32) -> f32 {
        self.values_lanes(Lanes::splat(u), Lanes::splat(v), 0).0[0]
    }

    /// [`Self::value`] per lane at level of detail `level` (clamped to the last).
    #[inline(always)]
    pub fn values_lanes(&self, u: Lanes, v: Lanes, level: usize) -> Lanes {
        let level = level.min(FOAM_PATTERN_LEVELS - 1);
        self.with_patches(read_level(&self.levels, &texel_coords(u, v), level), u, v, level)
    }

    /// `lace` (values of the lace at (`u`, `v`), tile units) blended with the patches at `level`,
    /// if the pattern has them.
    #[inline(always)]
    fn with_patches(&self, lace: Lanes, u: Lanes, v: Lanes, level: usize) -> Lanes {
        match &self.patches {
            Some(patches) => {
                let inv = 1.0 / PATCH_TILE;
                uniform_blend(read_level(patches, &texel_coords(u * inv, v * inv), level), lace)
            }
            None => lace,
        }
    }
}

/// Per lane, the full-size texel (column, row) that (`u`, `v`) (tile units) falls in, wrapped to
/// the tile.
struct TexelCoords {
    x: [i32; crate::math::LANES],
    y: [i32; crate::math::LANES],
}

/// The texel (`u`, `v`) (tile units) falls in, nearest texel, per lane.
#[inline(always)]
fn texel_coords(u: Lanes, v: Lanes) -> TexelCoords {
    // Plain loops over arrays (no closures, which would be compiled apart from the SIMD kernel),
    // the rounding by the 1.5 * 2^23 trick rather than a saturating `as i32` (a few vector
    // instructions instead of a dozen): the coordinate is wrapped to the tile first, so it lies in
    // [-0.5, 256] where that trick is exact, whatever the distance, and an input that is not
    // finite still gives an index the mask keeps on the tile.
    const MAGIC: f32 = 12_582_912.0;
    let side = FOAM_PATTERN_SIDE as f32;
    let texel = |w: f32| {
        let t = (w - w.floor()) * side - 0.5;
        ((t + MAGIC).to_bits() as i32).wrapping_sub(MAGIC.to_bits() as i32)
    };
    let mut at = TexelCoords { x: [0; crate::math::LANES], y: [0; crate::math::LANES] };
    for i in 0..crate::math::LANES {
        at.x[i] = texel(u.0[i]);
        at.y[i] = texel(v.0[i]);
    }
    at
}

/// The values of `mips` at level `level` at the texels `at`: one read per lane (the only per-lane
/// step).
#[inline(always)]
fn read_level(mips: &[f32; MIP_TEXELS], at: &TexelCoords, level: usize) -> Lanes {
    let shift = LEVEL_SHIFT[level];
    let log_side = FOAM_PATTERN_SIDE.trailing_zeros() - shift;
    let mask = (FOAM_PATTERN_SIDE as i32 >> shift) - 1;
    let offset = LEVEL_OFFSET[level];
    let mut out = [0.0f32; crate::math::LANES];
    for (i, o) in out.iter_mut().enumerate() {
        let (x, y) = ((at.x[i] >> shift) & mask, (at.y[i] >> shift) & mask);
        let k = offset + ((y << log_side) | x) as usize;
        *o = mips[k.min(MIP_TEXELS - 1)];
    }
    Lanes(out)
}

/// `a` and `b`, two independent values uniform on [0, 1], blended with weights [`PATCH_WEIGHT`]
/// and its complement and mapped through the blend's distribution function (piecewise
/// quadratic, linear in the middle): uniform on [0, 1] again, so the threshold of a coverage
/// still shows that coverage.
#[inline(always)]
fn uniform_blend(a: Lanes, b: Lanes) -> Lanes {
    const W: f32 = PATCH_WEIGHT;
    const V: f32 = 1.0 - PATCH_WEIGHT;
    let s = a * W + b * V;
    // W > V: below V and above W one tail of the trapezoid each; between, its flat top.
    let low = s * s * (0.5 / (W * V));
    let high = 1.0 - (1.0 - s) * (1.0 - s) * (0.5 / (W * V));
    let mid = (s - 0.5 * V) * (1.0 / W);
    s.lt(V).select(low, s.gt(W).select(high, mid))
}

impl FoamPattern {
    /// The threshold `e` per lane at which the pattern shows foam of coverage `coverage` in [0, 1]
    /// with an edge ramp `feather` wide ([`Self::alpha_lanes`]): the mean over the tile of
    /// `clamp((value − e) / feather, 0, 1)` for uniform values is `1 − e − feather / 2` while the
    /// ramp lies inside [0, 1], and the quadratic ends where it leaves it, so `e` inverts that
    /// mean to equal the coverage exactly.
    #[inline(always)]
    pub fn threshold_lanes(coverage: Lanes, feather: impl Into<Lanes>) -> Lanes {
        let c = coverage.max(0.0).min(1.0);
        let f = feather.into().max(1e-6);
        let low = 1.0 - (f * c * 2.0).sqrt();
        let high = (f * (1.0 - c) * 2.0).sqrt() - f;
        let mid = 1.0 - c - f * 0.5;
        c.lt(f * 0.5).select(low, c.gt(1.0 - f * 0.5).select(high, mid))
    }

    /// How much of each lane is foam, [0, 1]: the pattern at (`u`, `v`) (tile units) above the
    /// threshold for `coverage` ([`Self::threshold_lanes`]), ramped over `feather`, at full
    /// detail. Its mean over a tile is the coverage.
    #[inline(always)]
    pub fn alpha_lanes(&self, u: Lanes, v: Lanes, coverage: Lanes, feather: f32) -> Lanes {
        Self::ramped(self.values_lanes(u, v, 0), coverage, Lanes::splat(feather))
    }

    /// [`Self::alpha_lanes`] for a pixel whose footprint spans `texels` texels of the tile per
    /// lane (>= 0; 0: a point): the level of detail whose blur matches the footprint, blended
    /// with the next between powers of two, and past the last level ([`FOAM_PATTERN_LEVELS`])
    /// blended into the plain coverage over one more octave. At each level the ramp is widened
    /// to span at least the footprint (`feather` grows up to 1 with the footprint times the
    /// level's steepness), so a foam edge is never sharper than a pixel. Every level, every
    /// feather and the coverage have the same mean; the blend of two levels' values is close to
    /// uniform, so the coverage is kept closely, not exactly, between levels.
    #[inline(always)]
    pub fn filtered_alpha_lanes(&self, u: Lanes, v: Lanes, coverage: Lanes, feather: f32, texels: Lanes) -> Lanes {
        let last = FOAM_PATTERN_LEVELS - 1;
        // log2 of the footprint, 0 for a texel or less (the fast log is far better than an octave).
        let lod = Lanes::from_fn(|i| fast_log2(texels.0[i].max(1.0)));
        let mut finest = f32::INFINITY;
        for &l in &lod.0 {
            finest = finest.min(l);
        }
        if finest >= last as f32 + 1.0 {
            return coverage;
        }
        // One pair of levels per batch (its lanes are neighbours, their footprints within an
        // octave but at the horizon): the finest lane's level and the next, each lane blending the
        // two by its own fraction (clamped: a lane more than an octave coarser shows the next).
        // The values are blended rather than the foam they show, one threshold instead of two:
        // two levels are blurs of one another, so their blend stays close to uniform (over the
        // tiles the mean foam is the coverage within 5 % of min(c, 1 - c), and the `ocean`
        // frame's within 3 % of a 4 x 4 supersampled frame's in every band).
        let level = (finest as usize).min(last);
        let frac = (lod - level as f32).max(0.0).min(1.0);
        let at = texel_coords(u, v);
        let ramp = |level: usize| (texels * self.steepness[level]).max(feather).min(1.0);
        // The patches are smooth at every level: read once, at the coarser one.
        let (value, feather) = if level < last {
            let (l0, l1) = (read_level(&self.levels, &at, level), read_level(&self.levels, &at, level + 1));
            let (r0, r1) = (ramp(level), ramp(level + 1));
            (self.with_patches(l0 + (l1 - l0) * frac, u, v, level + 1), r0 + (r1 - r0) * frac)
        } else {
            (self.with_patches(read_level(&self.levels, &at, last), u, v, last), ramp(last))
        };
        let a = Self::ramped(value, coverage, feather);
        // Past the last level, over one more octave, the plain coverage takes over.
        let beyond = (lod - last as f32).max(0.0).min(1.0);
        a + (coverage - a) * beyond
    }

    /// How much of each lane is foam for pattern values `value`: above the threshold of
    /// `coverage` ([`Self::threshold_lanes`]), ramped over `feather`, in [0, 1].
    #[inline(always)]
    fn ramped(value: Lanes, coverage: Lanes, feather: Lanes) -> Lanes {
        let e = Self::threshold_lanes(coverage, feather);
        ((value - e) / feather.max(1e-6)).max(0.0).min(1.0)
    }
}

/// The mean magnitude of the gradient of level `level` of `mips`, per full-size texel, by
/// central differences on the torus.
fn level_steepness(mips: &[f32; MIP_TEXELS], level: usize) -> f32 {
    let n = FOAM_PATTERN_SIDE >> LEVEL_SHIFT[level];
    let values = level_values(mips, level);
    let at = |i: usize, j: usize| f64::from(values[(j % n) * n + (i % n)]);
    let mut sum = 0.0f64;
    for j in 0..n {
        for i in 0..n {
            let gx = 0.5 * (at(i + 1, j) - at(i + n - 1, j));
            let gy = 0.5 * (at(i, j + 1) - at(i, j + n - 1));
            sum += (gx * gx + gy * gy).sqrt();
        }
    }
    (sum / (n * n) as f64) as f32 / (1u32 << LEVEL_SHIFT[level]) as f32
}

/// `values` (a [`FOAM_PATTERN_SIDE`]² tile, row-major) averaged over `width` x `width` texels
/// about each texel, wrapping around the tile: a running sum along rows, then along columns.
fn box_blurred(values: &[f32], width: usize) -> Vec<f32> {
    let n = FOAM_PATTERN_SIDE;
    let pass = |src: &[f32], stride: usize, step: usize| {
        let mut out = vec![0.0f32; n * n];
        for line in 0..n {
            let at = |i: usize| src[line * stride + (i % n) * step];
            // Window [i - width/2, i - width/2 + width), summed in f64 (no drift along the line).
            let start = n - width / 2;
            let mut sum: f64 = (0..width).map(|t| f64::from(at(start + t))).sum();
            for i in 0..n {
                out[line * stride + i * step] = (sum / width as f64) as f32;
                sum += f64::from(at(start + i + width)) - f64::from(at(start + i));
            }
        }
        out
    };
    let rows = pass(values, n, 1);
    pass(&rows, 1, n)
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

/// The values of level `level` of `mips`, row-major.
fn level_values(mips: &[f32], level: usize) -> &[f32] {
    &mips[LEVEL_OFFSET[level]..LEVEL_OFFSET[level + 1]]
}

/// The [`FOAM_PATTERN_LEVELS`] levels of `raw` (a full-size tile, row-major): level 0 `raw`
/// equalised, level `k` that blurred over `2^k` texels, sampled at the centre of each of its
/// (coarser) texels and equalised again.
fn mip_levels(raw: Vec<f32>) -> Mips {
    let n = FOAM_PATTERN_SIDE;
    let finest = equalised(raw);
    let mut mips = vec![0.5f32; MIP_TEXELS];
    mips[..LEVEL_OFFSET[1]].copy_from_slice(&finest);
    for k in 1..FOAM_PATTERN_LEVELS {
        let blurred = box_blurred(&finest, 1 << k);
        // A blurred value at texel j is the mean over a window centred on j's lower edge: the
        // centre of a coarse texel of `stride` full-size ones is the edge at half its width.
        let stride = 1usize << LEVEL_SHIFT[k];
        let (side, centre) = (n / stride, stride / 2);
        let sampled =
            (0..side * side).map(|i| blurred[((i / side) * stride + centre) * n + (i % side) * stride + centre]);
        mips[LEVEL_OFFSET[k]..LEVEL_OFFSET[k + 1]].copy_from_slice(&equalised(sampled.collect()));
    }
    mips.into_boxed_slice().try_into().unwrap_or_else(|_| unreachable!("MIP_TEXELS values were built"))
}

/// Smooth random patches over the tile: white noise box-blurred three times over `width` texels
/// (close to a Gaussian), equalised to [0, 1].
fn smooth_patches(width: usize, seed: u32) -> Vec<f32> {
    let noise: Vec<f32> = (0..TEXELS as u32).map(|i| (hash(i ^ seed) >> 8) as f32 / 16_777_216.0).collect();
    let smooth = box_blurred(&box_blurred(&box_blurred(&noise, width), width), width);
    equalised(smooth)
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
    fn every_level_is_uniform_and_tiles() {
        let p = FoamPattern::procedural();
        let patches = p.patches.as_ref().expect("the procedural pattern has patches");
        for k in 0..FOAM_PATTERN_LEVELS {
            for values in [level_values(&p.levels[..], k), level_values(&patches[..], k)] {
                // Uniform: the values are the ranks, so every decile holds a tenth of them.
                let mut deciles = [0usize; 10];
                for &v in values {
                    deciles[((v * 10.0) as usize).min(9)] += 1;
                }
                for d in deciles {
                    assert!((d as f32 - 0.1 * values.len() as f32).abs() <= 1.0, "level {k}: {deciles:?}");
                }
            }
        }
        // Wraps: a whole tile away is the same texel, negative coordinates too, at every level.
        for k in 0..FOAM_PATTERN_LEVELS {
            let at = |u: f32, v: f32| p.values_lanes(Lanes::splat(u), Lanes::splat(v), k).0[0];
            assert_eq!(at(0.3, 0.7), at(0.3 + PATCH_TILE * 5.0, 0.7 - PATCH_TILE * 5.0), "level {k}");
        }
        let lace = FoamPattern::from_values(worley_borders(BUBBLE_CELLS, 7));
        assert_eq!(lace.value(0.3, 0.7), lace.value(1.3, -0.3), "a pattern without patches wraps on its tile");
        assert_eq!(FoamPattern::procedural(), p, "deterministic");
    }

    #[test]
    fn coarser_levels_have_no_fine_detail() {
        // Level k of white noise is blurred over 2^k texels and equalised again: its features are
        // about 2^k texels wide, so its values change about 2^k times more slowly than the
        // finest level's as measured over 2 texels (the central differences of the steepness),
        // which see white noise itself as a 2-texel blur: 2^(k-1) times.
        let noise = (0..TEXELS as u32).map(|i| hash(i ^ 0x1234_5678) as f32).collect();
        let p = FoamPattern::from_values(noise);
        for k in 1..FOAM_PATTERN_LEVELS {
            let ratio = p.steepness[0] / p.steepness[k];
            assert!(ratio > 0.8 * (1 << (k - 1)) as f32, "level {k}: {ratio} times smoother");
        }
        // The procedural pattern's cells are wider than the first blurs: it smooths from there.
        let p = FoamPattern::procedural();
        for k in 1..FOAM_PATTERN_LEVELS {
            assert!(p.steepness[k] <= p.steepness[k - 1] * 1.01, "level {k}: {:?}", p.steepness);
        }
        assert!(p.steepness[0] > 5.0 * p.steepness[FOAM_PATTERN_LEVELS - 1], "{:?}", p.steepness);
    }

    /// Mean foam of `alpha` (tile units to foam per lane) over the 13 lace tiles after which the
    /// lace and the patches repeat together, on an irregular grid of `m`² points.
    fn joint_mean(m: usize, alpha: impl Fn(Lanes, Lanes) -> Lanes) -> f64 {
        let span = 13.0;
        let mut sum = 0.0f64;
        for j in 0..m {
            let v = Lanes::splat((j as f32 + 0.37) * span / m as f32);
            for start in (0..m).step_by(crate::math::LANES) {
                let u = Lanes::from_fn(|i| ((start + i) as f32 + 0.61) * span / m as f32);
                let a = alpha(u, v);
                sum += a.0.iter().take(m - start).map(|&x| f64::from(x)).sum::<f64>();
            }
        }
        sum / (m * m) as f64
    }

    #[test]
    fn the_foam_has_the_coverage_at_every_distance() {
        // At full detail (the lace blended with the patches is uniform again) and filtered for
        // any footprint (a blend of two levels is close to uniform): the foam shown is the
        // coverage asked for.
        let p = FoamPattern::procedural();
        for feather in [0.05f32, 0.3] {
            for c in [0.0f32, 0.01, 0.05, 0.2, 0.5, 0.9, 1.0] {
                let full = joint_mean(832, |u, v| p.alpha_lanes(u, v, Lanes::splat(c), feather));
                assert!((full - f64::from(c)).abs() < 3e-3, "feather {feather}, coverage {c}: foam {full}");
                for texels in [1.5f32, 3.0, 6.0, 12.0, 24.0, 48.0, 96.0, 192.0] {
                    let filtered = joint_mean(416, |u, v| {
                        p.filtered_alpha_lanes(u, v, Lanes::splat(c), feather, Lanes::splat(texels))
                    });
                    let tolerance = 3e-3 + 0.05 * f64::from(c.min(1.0 - c));
                    assert!(
                        (filtered - f64::from(c)).abs() < tolerance,
                        "feather {feather}, coverage {c}, footprint {texels} texels: foam {filtered}"
                    );
                }
            }
        }
        // Beyond the coarsest level, the coverage itself.
        let far =
            p.filtered_alpha_lanes(Lanes::splat(0.2), Lanes::splat(0.7), Lanes::splat(0.3), 0.05, Lanes::splat(1e4));
        assert_eq!(far.0[0], 0.3);
    }

    #[test]
    fn thin_foam_lies_on_the_cell_borders() {
        // At low coverage the foam is the highest values: the borders, a connected lace, not a
        // scatter of single texels. Most foam texels at 5 % coverage have a foam neighbour.
        let p = FoamPattern::procedural();
        let n = FOAM_PATTERN_SIDE;
        let e = FoamPattern::threshold_lanes(Lanes::splat(0.05), 0.05).0[0];
        let foam = |i: usize, j: usize| p.levels[(j % n) * n + (i % n)] > e;
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
