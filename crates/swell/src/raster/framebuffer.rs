//! Colour and depth buffers.

use std::sync::{Arc, Mutex};

use glam::Vec3;
use rayon::prelude::*;

use super::rgba8_encoder::Rgba8Encoder;
use crate::math::{ev100_exposure, fast_log2, metered_ev100, DisplayEncoding};

/// Rows per task of [`Framebuffer::fill_background_rows`].
const BACKGROUND_ROWS: usize = 8;

/// Metering samples every `METER_STRIDE`-th pixel of every `METER_STRIDE`-th row: 57,600 of a
/// 1280 x 720 frame, plenty for an average and a tenth of a millisecond.
const METER_STRIDE: usize = 4;
/// Luminance floor of metering, renderer units (0.1 cd/m²): black pixels count as very dark
/// rather than as minus infinity.
const METER_FLOOR: f32 = 5e-6;
/// Metered exposures are rounded to this fraction of a stop, so that a frame and its neighbours
/// share an encoding table (and a moving speck cannot change every byte).
const METER_STEPS_PER_STOP: f32 = 64.0;

/// A linear-RGB colour buffer with a depth buffer, top row first.
#[derive(Clone, Debug)]
pub struct Framebuffer {
    width: u32,
    height: u32,
    /// Linear RGB per pixel, row-major, top row first.
    pub color: Vec<Vec3>,
    /// Window-space depth per pixel in [0, 1] (0 = near plane), cleared to 1.
    pub depth: Vec<f32>,
    /// The last [`Framebuffer::encode_rgba8`]'s table, reused while the encoding stays.
    encoder: EncoderCache,
}

/// The encoding table of the last encoding, kept so that steady-state frames neither
/// rebuild it (a serial step of about 8,000 curve evaluations) nor allocate. Behind a mutex
/// because encoding takes `&self`; a clone starts empty.
#[derive(Default)]
struct EncoderCache(Mutex<Option<Arc<Rgba8Encoder>>>);

impl EncoderCache {
    /// The table for `encoding` (metering resolved), built on first use or when it changes;
    /// `None` when [`Rgba8Encoder::new`] refuses it.
    fn get(&self, encoding: &DisplayEncoding) -> Option<Arc<Rgba8Encoder>> {
        // A poisoned lock only means a panic elsewhere mid-update; the slot is rebuilt below.
        let mut slot = self.0.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(t) = slot.as_ref().filter(|t| t.encodes(encoding)) {
            return Some(Arc::clone(t));
        }
        *slot = Rgba8Encoder::new(encoding).map(Arc::new);
        slot.clone()
    }
}

impl Clone for EncoderCache {
    fn clone(&self) -> Self {
        Self::default()
    }
}

impl std::fmt::Debug for EncoderCache {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("EncoderCache")
    }
}

impl Framebuffer {
    /// A black framebuffer with depth cleared to the far plane. Sizes are the caller's to check
    /// ([`crate::scene::MAX_IMAGE_SIDE`]).
    pub fn new(width: u32, height: u32) -> Self {
        let n = width as usize * height as usize;
        Self { width, height, color: vec![Vec3::ZERO; n], depth: vec![1.0; n], encoder: EncoderCache::default() }
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

    /// Fills the background, rows in parallel: `row(y, colors, depth)` may write any pixel of row
    /// `y`'s `colors` whose `depth` is still the far plane (1). Drawn after the geometry, it
    /// shades only what shows; a background smooth along the row can be evaluated many pixels at
    /// a time, or sparsely and interpolated.
    // Out of line so that profiles name it (the sky pass).
    #[inline(never)]
    pub fn fill_background_rows(&mut self, row: impl Fn(u32, &mut [Vec3], &[f32]) + Sync) {
        let w = self.width as usize;
        if w == 0 {
            return;
        }
        // A few rows per task: the background is usually a band (the sky above the horizon), and
        // rayon's adaptive split would leave one thread most of it.
        let rows = self.color.par_chunks_mut(w).zip(self.depth.par_chunks(w)).enumerate().with_max_len(BACKGROUND_ROWS);
        rows.for_each(|(y, (colors, depth))| row(y as u32, colors, depth));
    }

    /// Encodes to RGBA8 (alpha 255) with `encoding` ([`DisplayEncoding::encode`]: exposure, tone
    /// curve, sRGB or power law); with `auto_exposure`, the exposure is first metered from this
    /// frame ([`Self::metered_ev100`]) and multiplied by `encoding.exposure`. `out` is resized to
    /// `4 * width * height`. Returns the encoding used, metering resolved.
    pub fn encode_rgba8(&self, encoding: &DisplayEncoding, out: &mut Vec<u8>) -> DisplayEncoding {
        let encoding = match encoding.auto_exposure {
            true => encoding.with_exposure(encoding.exposure * ev100_exposure(self.metered_ev100())),
            false => *encoding,
        };
        out.resize(self.color.len() * 4, 0);
        let w = self.width as usize;
        if w == 0 {
            return encoding;
        }
        let table = self.encoder.get(&encoding);
        out.par_chunks_mut(4 * w).zip(self.color.par_chunks(w)).for_each(|(dst, src)| match &table {
            Some(t) => t.encode_row(src, dst),
            None => {
                for (px, c) in dst.chunks_exact_mut(4).zip(src) {
                    let e = |v: f32| encoding.encode(v);
                    px.copy_from_slice(&[e(c.x), e(c.y), e(c.z), 255]);
                }
            }
        });
        encoding
    }

    /// The EV100 that exposes this frame's log-average to 0.18 of white ([`metered_ev100`]): the mean
    /// log2 luminance (Rec. 709 weights, floored at 0.1 cd/m²; NaN pixels skipped) over a fixed
    /// grid of every fourth pixel of every fourth row, summed in row order in f64, so the result
    /// depends on the pixels only; rounded to 1/64 stop. An empty frame meters the range's middle.
    pub fn metered_ev100(&self) -> f32 {
        let w = self.width as usize;
        let (mut sum, mut n) = (0.0f64, 0u32);
        for row in self.color.chunks(w.max(1)).step_by(METER_STRIDE) {
            for c in row.iter().step_by(METER_STRIDE) {
                let y = 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z;
                if y.is_nan() {
                    continue;
                }
                sum += f64::from(fast_log2(y.clamp(METER_FLOOR, f32::MAX)));
                n += 1;
            }
        }
        let mean = if n == 0 { f32::NAN } else { (sum / f64::from(n)) as f32 };
        (metered_ev100(mean) * METER_STEPS_PER_STOP).round() / METER_STEPS_PER_STOP
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::ToneCurve;

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
    fn encoding_follows_exposure_and_gamma_changes_and_falls_back_to_the_curve() {
        let mut fb = Framebuffer::new(11, 3);
        fb.color =
            (0..33).map(|i| Vec3::new(i as f32 / 40.0, (i as f32 * 0.37).fract(), 1.0 / (1.0 + i as f32))).collect();
        fb.color[5] = Vec3::new(f32::NAN, -1.0, f32::INFINITY);
        let mut out = Vec::new();
        let aces =
            |exposure| DisplayEncoding { tone_curve: ToneCurve::Aces, ..DisplayEncoding::clipped(exposure, None) };
        // The cached table must follow each change; exposure 0 has no table (direct curve).
        let encodings = [
            DisplayEncoding::clipped(1.0, None),
            DisplayEncoding::clipped(2.0, None),
            DisplayEncoding::clipped(2.0, Some(2.2)),
            aces(2.0),
            DisplayEncoding::clipped(1.0, None),
            DisplayEncoding::clipped(0.0, None),
            aces(1.0),
        ];
        for enc in encodings {
            assert_eq!(fb.encode_rgba8(&enc, &mut out), enc);
            for (px, c) in out.chunks_exact(4).zip(&fb.color) {
                assert_eq!(px, [enc.encode(c.x), enc.encode(c.y), enc.encode(c.z), 255], "{c} at {enc:?}");
            }
        }
    }

    #[test]
    fn metering_exposes_the_log_average_and_ignores_nan() {
        let mut fb = Framebuffer::new(64, 32);
        // Half the sampled pixels at 0.02, half at 0.08 units: log-average 0.04 (800 cd/m²).
        for (i, c) in fb.color.iter_mut().enumerate() {
            let row = i / 64;
            *c = Vec3::splat(if (row / 4) % 2 == 0 { 0.02 } else { 0.08 });
        }
        fb.color[0] = Vec3::NAN;
        let ev = fb.metered_ev100();
        assert!((ev - (800.0f32 / 0.216).log2()).abs() < 0.02, "{ev}");
        let enc = DisplayEncoding { auto_exposure: true, ..DisplayEncoding::clipped(1.0, None) };
        let mut out = Vec::new();
        let used = fb.encode_rgba8(&enc, &mut out);
        assert!(!used.auto_exposure && (used.exposure - crate::math::ev100_exposure(ev)).abs() < 1e-6);
        // Compensation multiplies the metered exposure.
        let plus = fb.encode_rgba8(&DisplayEncoding { exposure: 2.0, ..enc }, &mut out);
        assert!((plus.exposure / used.exposure - 2.0).abs() < 1e-6);
        assert_eq!(Framebuffer::new(0, 0).metered_ev100(), 9.0);
    }
}
