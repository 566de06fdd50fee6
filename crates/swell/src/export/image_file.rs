//! PNG stills and GIF animations.

use std::io::Write;
use std::path::Path;

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

/// One palette-quantised GIF frame, ready to write (see [`encode_gif_frame`]).
pub struct GifFrame(gif::Frame<'static>);

/// Quantises an RGBA8 image to a 256-colour GIF frame shown for `delay_cs` hundredths of a second.
///
/// Quantisation (NeuQuant) is the slow part of GIF writing and frames are independent, so callers
/// run this in parallel and then write the frames in order with [`write_gif`].
pub fn encode_gif_frame(width: u16, height: u16, rgba: &[u8], delay_cs: u16) -> GifFrame {
    let mut pixels = rgba.to_vec();
    // Speed 10 is gif's recommended balance; 1 is best quality and ~10x slower.
    let mut frame = gif::Frame::from_rgba_speed(width, height, &mut pixels, 10);
    frame.delay = delay_cs;
    GifFrame(frame)
}

/// Writes frames as a looping GIF animation, atomically.
pub fn write_gif(path: &Path, width: u16, height: u16, frames: &[GifFrame]) -> Result<()> {
    let gif_err = |e: gif::EncodingError| Error::Image { path: path.into(), message: e.to_string() };
    write_atomically(path, |out: &mut dyn Write| {
        let mut enc = gif::Encoder::new(out, width, height, &[]).map_err(gif_err)?;
        enc.set_repeat(gif::Repeat::Infinite).map_err(gif_err)?;
        for f in frames {
            enc.write_frame(&f.0).map_err(gif_err)?;
        }
        Ok(())
    })
}
