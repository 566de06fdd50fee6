//! PNG stills and GIF animations.

use std::path::Path;

use super::frame_batches::render_then_encode;
use super::median_cut::median_cut_palette;
use super::ordered_dither::dither_to_palette;
use super::write_atomically;
use crate::error::{Error, Result};

/// Writes an RGBA8 image (top row first) as PNG, atomically.
pub fn write_png(path: &Path, width: u32, height: u32, rgba: &[u8]) -> Result<()> {
    debug_assert_eq!(rgba.len(), 4 * width as usize * height as usize);
    write_atomically(path, |out| {
        let encoder = image::codecs::png::PngEncoder::new(out);
        image::ImageEncoder::write_image(encoder, rgba, width, height, image::ExtendedColorType::Rgba8)
            .map_err(|e| Error::Image { path: path.into(), message: e.to_string() })
    })
}

/// Highest frame rate a GIF plays as written, frames per second: GIF delays are whole hundredths
/// of a second, and players (browsers among them) show delays under 2/100 s as 10/100 s.
pub const MAX_GIF_FPS: f64 = 50.0;

/// GIF delay (hundredths of a second) of frame `k` of an animation at `fps` frames per second:
/// frame k starts at `round(100 k / fps)`, so a 24 fps animation alternates 4 and 5 hundredths
/// (4, 4, 5, 4, 4, 4, 5, ...) and keeps 24 frames per second on average instead of 25.
pub fn gif_delay_cs(k: usize, fps: f64) -> u16 {
    let start = |k: usize| (100.0 * k as f64 / fps).round();
    (start(k + 1) - start(k)).clamp(1.0, 65535.0) as u16
}

/// Writes a looping GIF animation of `frame_count` frames at `fps` frames per second (in (0,
/// [`MAX_GIF_FPS`]], delays from [`gif_delay_cs`]), atomically.
///
/// `render(k, rgba)` fills `rgba` with frame k (RGBA8, `width` x `height`, top row first; alpha
/// is ignored, every pixel is opaque); `progress()` is called after each frame is written. Frames
/// are rendered in order and turned into GIF frames ([`gif_frame`]) a batch at a time in
/// parallel, so memory stays bounded however many frames there are, and the file does not depend
/// on the number of threads.
pub fn write_gif(
    path: &Path,
    width: u16,
    height: u16,
    frame_count: usize,
    fps: f64,
    mut render: impl FnMut(usize, &mut Vec<u8>) -> Result<()>,
    mut progress: impl FnMut(),
) -> Result<()> {
    let gif_err = |e: gif::EncodingError| Error::Image { path: path.into(), message: e.to_string() };
    let frames: Vec<u32> = (0..frame_count as u32).collect();
    write_atomically(path, |out| {
        let mut enc = gif::Encoder::new(out, width, height, &[]).map_err(gif_err)?;
        enc.set_repeat(gif::Repeat::Infinite).map_err(gif_err)?;
        render_then_encode(
            &frames,
            |k, rgba| render(k as usize, rgba),
            |k, rgba| {
                let mut f = gif_frame(width, height, rgba);
                f.delay = gif_delay_cs(k as usize, fps);
                Ok(f)
            },
            |_, f| {
                enc.write_lzw_pre_encoded_frame(&f).map_err(gif_err)?;
                progress();
                Ok(())
            },
        )
    })
}

/// Largest peak-to-peak amplitude of the GIF frames' ordered dither, in 8-bit levels: the dither
/// follows the palette's spacing ([`dither_to_palette`]), a few levels in a sea's blues, more in
/// a sunset; past this an isolated colour (the sun, a highlight) would turn to visible grain.
pub const GIF_MAX_DITHER_LEVELS: u8 = 24;

/// One GIF frame of an RGBA8 image (alpha ignored), LZW-compressed and ready to write: its own
/// palette of 256 colours by median cut ([`median_cut_palette`]), the pixels mapped onto it with
/// ordered dithering ([`dither_to_palette`], [`GIF_MAX_DITHER_LEVELS`]); an image of at most 256
/// colours keeps them exactly, undithered. Depends on the image alone.
pub fn gif_frame(width: u16, height: u16, rgba: &[u8]) -> gif::Frame<'static> {
    debug_assert_eq!(rgba.len(), 4 * usize::from(width) * usize::from(height));
    let w = usize::from(width);
    let (palette, exact) = median_cut_palette(rgba, w, 256);
    let indices = if exact {
        // The palette is sorted (the colours came out of a sort): each pixel's colour is in it.
        let key = |p: &[u8]| [p[0], p[1], p[2]];
        rgba.chunks_exact(4).map(|p| palette.binary_search(&key(p)).unwrap_or(0) as u8).collect()
    } else {
        dither_to_palette(rgba, w, &palette, GIF_MAX_DITHER_LEVELS)
    };
    let flat: Vec<u8> = palette.iter().flatten().copied().collect();
    let mut frame = gif::Frame::from_palette_pixels(width, height, indices, flat, None);
    frame.make_lzw_pre_encoded();
    frame
}

/// Writes a map of `channels` (1 = grey, 3 = RGB) samples per pixel as an 8- or 16-bit PNG,
/// atomically. `samples` are in [0, 1] (clamped), row-major, first row first; each is quantised to
/// `round(s * (2^bits - 1))`.
pub fn write_png_map(path: &Path, width: u32, height: u32, channels: u8, bits: u8, samples: &[f32]) -> Result<()> {
    debug_assert_eq!(samples.len(), channels as usize * width as usize * height as usize);
    let color = match (channels, bits) {
        (1, 8) => image::ExtendedColorType::L8,
        (3, 8) => image::ExtendedColorType::Rgb8,
        (1, 16) => image::ExtendedColorType::L16,
        (3, 16) => image::ExtendedColorType::Rgb16,
        _ => {
            return Err(Error::invalid(
                "--png",
                format!("{channels} channels of {bits} bits; valid: 1 or 3 channels of 8 or 16 bits"),
            ))
        }
    };
    let max = ((1u32 << bits) - 1) as f32;
    let quantise = |s: f32| (s.clamp(0.0, 1.0) * max).round();
    let bytes: Vec<u8> = if bits == 8 {
        samples.iter().map(|&s| quantise(s) as u8).collect()
    } else {
        // image takes 16-bit samples in native byte order and writes them big-endian.
        samples.iter().flat_map(|&s| (quantise(s) as u16).to_ne_bytes()).collect()
    };
    write_atomically(path, |out| {
        let encoder = image::codecs::png::PngEncoder::new(out);
        image::ImageEncoder::write_image(encoder, &bytes, width, height, color)
            .map_err(|e| Error::Image { path: path.into(), message: e.to_string() })
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gif_delays_keep_the_frame_rate_on_average() {
        for fps in [24.0, 30.0, 12.5, 50.0, 7.0] {
            let frames = (fps * 12.0) as usize; // 12 s
            let total: u32 = (0..frames).map(|k| u32::from(gif_delay_cs(k, fps))).sum();
            // Frame k starts within half a hundredth of k / fps: 12 s take 1200 hundredths.
            assert!((f64::from(total) - 1200.0).abs() <= 0.5, "{fps} fps: {total}");
        }
        let d: Vec<u16> = (0..6).map(|k| gif_delay_cs(k, 24.0)).collect();
        assert_eq!(d, [4, 4, 5, 4, 4, 4]);
    }
}
