//! File plumbing beneath every layer that reads or writes: an input is opened so that a FIFO
//! without a writer cannot hang a run, and a file appears under its name complete or not at all.
//! Below `limits`, `terrain`, `scene`, `shading` and `export` alike, so none imports another to
//! read or write a file.

#[cfg(feature = "render")]
mod atomic;
mod open_input;

#[cfg(feature = "render")]
pub use atomic::write_atomically;
pub use open_input::{open_input, open_seekable, read_input, SeekableInput, MAX_PIPED_BYTES};
