//! Colour and depth buffers.

use glam::Vec3;
use rayon::prelude::*;

use crate::math::linear_to_srgb;

/// A linear-RGB colour buffer with a depth buffer, top row first.
#[derive(Clone, Debug)]
pub struct Framebuffer {
    width: u32,
    height: u32,
    /// Linear RGB per pixel, row-major, top row first.
    pub color: Vec<Vec3>,
    /// Window-space depth per pixel in [0, 1] (0 = near plane), cleared to 1.
    pub depth: Vec<f32>,
}

impl Framebuffer {
    /// A black framebuffer with depth cleared to the far plane. Sizes are the caller's to check
    /// ([`crate::scene::MAX_IMAGE_SIDE`]).
    pub fn new(width: u32, height: u32) -> Self {
        let n = width as usize * height as usize;
        Self { width, height, color: vec![Vec3::ZERO; n], depth: vec![1.0; n] }
    }

    /// Width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// Changes the size, reusing the allocation where it is large enough. Contents are unspecified.
    pub fn resize(&mut self, width: u32, height: u32) {
        let n = width as usize * height as usize;
        self.width = width;
        self.height = height;
        self.color.resize(n, Vec3::ZERO);
        self.depth.resize(n, 1.0);
    }

    /// Clears depth to the far plane and sets every colour to `background(x, y)`, rows in parallel.
    pub fn clear_with(&mut self, background: impl Fn(u32, u32) -> Vec3 + Sync) {
        let w = self.width as usize;
        self.depth.par_iter_mut().for_each(|d| *d = 1.0);
        self.color.par_chunks_mut(w).enumerate().for_each(|(y, row)| {
            for (x, c) in row.iter_mut().enumerate() {
                *c = background(x as u32, y as u32);
            }
        });
    }

    /// Sets the colour of every pixel whose depth is still the far plane (1) to `background(x,
    /// y)`, rows in parallel: drawing the background after the geometry shades only what shows.
    pub fn fill_background(&mut self, background: impl Fn(u32, u32) -> Vec3 + Sync) {
        let w = self.width as usize;
        self.color.par_chunks_mut(w).zip(self.depth.par_chunks(w)).enumerate().for_each(|(y, (row, depth))| {
            for (x, (c, &d)) in row.iter_mut().zip(depth).enumerate() {
                if d >= 1.0 {
                    *c = background(x as u32, y as u32);
                }
            }
        });
    }

    /// Encodes to RGBA8 (alpha 255): colour times `exposure`, then the sRGB curve, or the power
    /// law `c^(1/gamma)` when `gamma` is given. `out` is resized to `4 * width * height`.
    pub fn encode_rgba8(&self, exposure: f32, gamma: Option<f32>, out: &mut Vec<u8>) {
        out.resize(self.color.len() * 4, 0);
        let table = ByteThresholds::new(exposure, gamma);
        let encode = |c: f32| match &table {
            Some(t) => t.encode(c),
            None => encode_channel(c, exposure, gamma),
        };
        out.par_chunks_mut(4 * self.width as usize).zip(self.color.par_chunks(self.width as usize)).for_each(
            |(dst, src)| {
                for (px, c) in dst.chunks_exact_mut(4).zip(src) {
                    px[0] = encode(c.x);
                    px[1] = encode(c.y);
                    px[2] = encode(c.z);
                    px[3] = 255;
                }
            },
        );
    }

    /// Makes `self` the box-filtered reduction of `src` by `factor` per axis: each pixel is the
    /// mean of a `factor` x `factor` block of linear colours (averaging after gamma encoding would
    /// darken edges), and the nearest depth of the block. `self` is resized to `src`'s size
    /// divided by `factor` (rounded down; `factor` >= 1).
    pub fn downsample_from(&mut self, src: &Framebuffer, factor: u32) {
        let factor = factor.max(1);
        self.resize(src.width / factor, src.height / factor);
        let (w, f) = (self.width as usize, factor as usize);
        if w == 0 {
            return;
        }
        let sw = src.width as usize;
        let scale = 1.0 / (f * f) as f32;
        self.color.par_chunks_mut(w).zip(self.depth.par_chunks_mut(w)).enumerate().for_each(|(y, (row, drow))| {
            for x in 0..w {
                let (mut sum, mut near) = (Vec3::ZERO, 1.0f32);
                for sy in y * f..(y + 1) * f {
                    let base = sy * sw + x * f;
                    for i in base..base + f {
                        sum += src.color[i];
                        near = near.min(src.depth[i]);
                    }
                }
                row[x] = sum * scale;
                drow[x] = near;
            }
        });
    }
}

/// One linear channel to a byte: times `exposure`, the sRGB curve or `c^(1/gamma)`, rounded.
fn encode_channel(c: f32, exposure: f32, gamma: Option<f32>) -> u8 {
    let c = c * exposure;
    let e = match gamma {
        None => linear_to_srgb(c),
        Some(g) => c.clamp(0.0, 1.0).powf(1.0 / g),
    };
    // NaN clamps to 0 here, so a bad sample can never reach a file as garbage.
    (e * 255.0 + 0.5).clamp(0.0, 255.0) as u8
}

/// [`encode_channel`] without a `powf` per channel: the encoding is non-decreasing in the linear
/// value, so it is fully described by the smallest linear value reaching each byte 1..=255,
/// found once per frame by bisection over the f32 bit patterns (non-negative floats order as
/// their bits). A channel is then encoded by counting thresholds at or below it.
/// Callgrind: the encoding of a 1280 x 720 frame was 271 M instructions (three `powf` per pixel),
/// more than half the `ocean` frame's rendering.
///
/// The count starts from a table indexed by the top 16 bits of the value (sign, exponent and 7
/// mantissa bits: buckets 0.8 % wide), holding the count at the bucket's lower end; adjacent
/// thresholds are about that far apart or more (sRGB: 0.85 % at the top byte, far more below), so a
/// compare or two finishes it. A binary search over
/// the 255 thresholds (8 unpredictable branches per channel) was 7 % of a viewer `ocean` frame.
struct ByteThresholds {
    /// `lower[k - 1]`: the smallest linear value encoded as k or more; NaN where none is.
    lower: [f32; 255],
    /// `start[b]`: how many thresholds are at or below `f32::from_bits(b << 16)`, for the
    /// non-negative bit patterns (b < 0x8000).
    start: Box<[u8; BUCKETS]>,
}

/// Buckets of [`ByteThresholds::start`]: every non-negative f32 bit pattern shifted right by 16.
const BUCKETS: usize = 0x8000;

impl ByteThresholds {
    /// `None` when the encoding is not known to be non-decreasing (exposure not positive and
    /// finite, gamma not positive and finite): the caller then encodes each channel directly.
    fn new(exposure: f32, gamma: Option<f32>) -> Option<Self> {
        let valid_gamma = gamma.is_none_or(|g| g.is_finite() && g > 0.0);
        if !(exposure.is_finite() && exposure > 0.0 && valid_gamma) {
            return None;
        }
        let f = |bits: u32| encode_channel(f32::from_bits(bits), exposure, gamma);
        let top = f32::INFINITY.to_bits();
        let mut lower = [f32::NAN; 255];
        for (k, slot) in (1..=255u8).zip(lower.iter_mut()) {
            if f(top) < k {
                break;
            }
            // Smallest bit pattern in [0, top] whose encoding reaches k.
            let (mut lo, mut hi) = (0u32, top);
            while lo < hi {
                let mid = lo + (hi - lo) / 2;
                if f(mid) >= k {
                    hi = mid;
                } else {
                    lo = mid + 1;
                }
            }
            *slot = f32::from_bits(lo);
        }
        // Negative values and NaN encode to 0 (they clamp to 0 first), as does 0 itself.
        if f(0) != 0 {
            return None;
        }
        // One merge-like sweep: bucket starts and thresholds both increase.
        let mut start = Box::new([0u8; BUCKETS]);
        let mut k = 0;
        for (b, slot) in start.iter_mut().enumerate() {
            let c = f32::from_bits((b as u32) << 16);
            while k < lower.len() && lower[k] <= c {
                k += 1;
            }
            *slot = k as u8;
        }
        Some(Self { lower, start })
    }

    #[inline]
    fn encode(&self, c: f32) -> u8 {
        // Negative values, zero and NaN all encode to 0 (every threshold is positive).
        if !(c > 0.0) {
            return 0;
        }
        // Non-negative, so the index is below BUCKETS; NaN thresholds (none reachable) stop the count.
        let mut k = self.start[(c.to_bits() >> 16) as usize] as usize;
        while k < self.lower.len() && self.lower[k] <= c {
            k += 1;
        }
        k as u8
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn downsampling_averages_linear_colour_in_blocks() {
        let mut src = Framebuffer::new(4, 2);
        src.color = (0..8).map(|i| Vec3::splat(i as f32)).collect();
        src.depth[5] = 0.25;
        let mut dst = Framebuffer::new(1, 1);
        dst.downsample_from(&src, 2);
        assert_eq!((dst.width(), dst.height()), (2, 1));
        // Blocks {0, 1, 4, 5} and {2, 3, 6, 7}.
        assert_eq!(dst.color, vec![Vec3::splat(2.5), Vec3::splat(4.5)]);
        assert_eq!(dst.depth, vec![0.25, 1.0]);
    }

    #[test]
    fn byte_thresholds_encode_exactly_like_the_direct_curve() {
        for (exposure, gamma) in [(1.0, None), (1.7, None), (1.0, Some(1.0)), (0.6, Some(2.2))] {
            let table = ByteThresholds::new(exposure, gamma).unwrap();
            // Dense over the range where bytes change, plus the special values.
            let mut values: Vec<f32> = (0..200_000).map(|i| i as f32 / 150_000.0).collect();
            values.extend([-1.0, -0.0, 0.0, f32::NAN, f32::INFINITY, f32::NEG_INFINITY, 1e30, 1e-40]);
            // Each threshold and its neighbours, where a bucket's start count must be finished exactly.
            for t in table.lower.iter().filter(|t| t.is_finite()) {
                values.extend([*t, f32::from_bits(t.to_bits() - 1), f32::from_bits(t.to_bits() + 1)]);
            }
            // Every bucket's lower end.
            values.extend((0..BUCKETS as u32).map(|b| f32::from_bits(b << 16)).filter(|c| !c.is_nan()));
            for c in values {
                assert_eq!(table.encode(c), encode_channel(c, exposure, gamma), "c = {c}, {exposure} {gamma:?}");
            }
        }
        assert!(ByteThresholds::new(0.0, None).is_none());
        assert!(ByteThresholds::new(1.0, Some(f32::NAN)).is_none());
    }
}
