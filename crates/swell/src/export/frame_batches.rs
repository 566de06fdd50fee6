//! Rendering an image sequence in order and encoding it in parallel: how the GIF and PNG-sequence
//! writers share the cores between the renderer and the encoders.

use rayon::prelude::*;

use crate::error::Result;

/// Renders `frames` in order with `render(frame, rgba)` on the calling thread, a batch of twice
/// the worker threads at a time, then encodes the batch's images in parallel with
/// `encode(frame, rgba)` and hands the results to `sink(frame, encoded)` in frame order.
///
/// Rendering stays in order because a time-stepped model moves forward from one frame to the next
/// (and the renderer is parallel inside); encoding a frame depends on that frame alone, so the
/// output does not depend on the number of threads. Memory holds one batch of images however many
/// frames there are. Stops at the first error.
pub(crate) fn render_then_encode<T: Send>(
    frames: &[u32],
    mut render: impl FnMut(u32, &mut Vec<u8>) -> Result<()>,
    encode: impl Fn(u32, &[u8]) -> Result<T> + Sync,
    mut sink: impl FnMut(u32, T) -> Result<()>,
) -> Result<()> {
    let batch = 2 * rayon::current_num_threads().max(1);
    let mut buffers: Vec<Vec<u8>> = vec![Vec::new(); batch.min(frames.len())];
    for chunk in frames.chunks(batch) {
        for (&frame, buf) in chunk.iter().zip(&mut buffers) {
            render(frame, buf)?;
        }
        let encoded: Vec<Result<T>> =
            chunk.par_iter().zip(buffers[..chunk.len()].par_iter()).map(|(&frame, rgba)| encode(frame, rgba)).collect();
        for (&frame, e) in chunk.iter().zip(encoded) {
            sink(frame, e?)?;
        }
    }
    Ok(())
}
