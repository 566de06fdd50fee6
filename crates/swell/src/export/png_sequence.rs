//! An animation as one PNG per frame, named by a [`FramePattern`]: the input video tools take
//! (`ffmpeg -framerate 24 -start_number 48 -i frames/sea_%04d.png`), lossless, and resumable
//! like a bake because every frame is a file of its own, written atomically.

use std::io::Cursor;
use std::path::Path;

use rayon::prelude::*;

use super::frame_batches::render_then_encode;
use super::frame_pattern::FramePattern;
use super::frame_range::FrameRange;
use super::image_file::write_png;
use crate::error::Result;

/// The frames of `range` still to write: all of them, or with `resume` those whose file is not
/// already a complete PNG of `width` x `height` pixels ([`is_complete_png`]; a missing,
/// truncated, corrupt or differently sized file is written again). In increasing order.
pub fn pending_frames(pattern: &FramePattern, range: FrameRange, width: u32, height: u32, resume: bool) -> Vec<u32> {
    let frames: Vec<u32> = range.iter().collect();
    if !resume {
        return frames;
    }
    // Decoding is most of the check: in parallel, and the list's order is the range's.
    frames.into_par_iter().filter(|&k| !is_complete_png(&pattern.path(k), width, height)).collect()
}

/// Whether `path` is a PNG of `width` x `height` pixels that decodes to the end (every row, the
/// checksums): what a frame written by [`write_png_sequence`] is, and what a killed run's file,
/// or another program's, may not be.
pub fn is_complete_png(path: &Path, width: u32, height: u32) -> bool {
    let Ok(bytes) = std::fs::read(path) else { return false };
    // A PNG ends with its IEND chunk; a decoder may stop reading before it, so check it here.
    if !bytes.ends_with(&PNG_END) {
        return false;
    }
    let Ok(decoder) = image::codecs::png::PngDecoder::new(Cursor::new(&bytes)) else { return false };
    if image::ImageDecoder::dimensions(&decoder) != (width, height) {
        return false;
    }
    let mut pixels = vec![0; image::ImageDecoder::total_bytes(&decoder) as usize];
    image::ImageDecoder::read_image(decoder, &mut pixels).is_ok()
}

/// The last 12 bytes of every PNG: the empty IEND chunk (length 0, type, CRC).
const PNG_END: [u8; 12] = [0, 0, 0, 0, b'I', b'E', b'N', b'D', 0xAE, 0x42, 0x60, 0x82];

/// Writes `frames` (absolute frame numbers, e.g. from [`pending_frames`]) as RGBA8 PNGs of
/// `width` x `height` pixels to `pattern`'s files, each atomically (a killed run leaves whole
/// frames and no partial one). `render(k, rgba)` fills `rgba` with frame k (top row first), in
/// increasing order; the PNGs are encoded and written in parallel a batch at a time, so the files
/// do not depend on the number of threads. `progress()` is called after each frame is written.
pub fn write_png_sequence(
    pattern: &FramePattern,
    frames: &[u32],
    width: u32,
    height: u32,
    render: impl FnMut(u32, &mut Vec<u8>) -> Result<()>,
    mut progress: impl FnMut(),
) -> Result<()> {
    render_then_encode(
        frames,
        render,
        |k, rgba| write_png(&pattern.path(k), width, height, rgba),
        |_, ()| {
            progress();
            Ok(())
        },
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn resume_skips_complete_frames_and_redoes_the_rest() {
        let dir = tempfile::tempdir().unwrap();
        let pattern = FramePattern::parse("--out", &dir.path().join("f_%03d.png")).unwrap();
        let range = FrameRange::new("--frames", 3, 7).unwrap();
        let image = |k: u32| vec![k as u8; 4 * 4 * 2];
        let mut rendered = Vec::new();
        let render = |k: u32, rgba: &mut Vec<u8>| {
            rendered.push(k);
            *rgba = image(k);
            Ok(())
        };
        write_png_sequence(&pattern, &pending_frames(&pattern, range, 4, 2, false), 4, 2, render, || {}).unwrap();
        assert_eq!(rendered, [3, 4, 5, 6, 7]);
        assert!(dir.path().join("f_003.png").is_file() && dir.path().join("f_007.png").is_file());
        assert!(pending_frames(&pattern, range, 4, 2, true).is_empty());
        // Frame 4 cut short (its end chunk missing), frame 6 gone, frame 5 of another size: those three are redone.
        let f4 = pattern.path(4);
        let bytes = std::fs::read(&f4).unwrap();
        std::fs::write(&f4, &bytes[..bytes.len() - 12]).unwrap();
        std::fs::remove_file(pattern.path(6)).unwrap();
        write_png(&pattern.path(5), 2, 2, &[0; 16]).unwrap();
        assert_eq!(pending_frames(&pattern, range, 4, 2, true), [4, 5, 6]);
        assert_eq!(pending_frames(&pattern, range, 4, 2, false), [3, 4, 5, 6, 7]);
        assert!(!is_complete_png(&dir.path().join("nothing.png"), 4, 2));
    }
}
