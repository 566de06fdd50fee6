//! Writing results to files: images and animations, always atomically.

mod atomic;
mod image_file;

pub use atomic::write_atomically;
pub use image_file::{write_gif, write_png};
