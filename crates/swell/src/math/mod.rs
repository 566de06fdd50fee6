//! Small mathematical building blocks shared by every stage: the regular grid, colour transfer and
//! seeded gradient noise.

mod color;
mod fast_trig;
mod grid_spec;
mod perlin;
mod transform;

pub use color::{linear_to_srgb, srgb_to_linear, xyy_to_linear_srgb};
pub use fast_trig::{fast_floor, fast_sin_cos, reduce_turns, sin_cos_turns, FAST_SIN_COS_MAX_ERROR};
pub use grid_spec::{GridSpec, MAX_GRID_CELLS};
pub use perlin::Perlin;
pub use transform::{Transform, MAX_SCALE};
