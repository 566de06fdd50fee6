//! Small mathematical building blocks shared by every stage: the regular grid and colour transfer.

mod color;
mod grid_spec;

pub use color::{linear_to_srgb, srgb_to_linear};
pub use grid_spec::{GridSpec, MAX_GRID_CELLS};
