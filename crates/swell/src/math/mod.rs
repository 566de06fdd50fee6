//! Small mathematical building blocks shared by every stage: the regular grid, colour transfer,
//! seeded gradient noise and the normal distribution function; the radiometric unit and the
//! display encoding (exposure, tone curve).

mod color;
mod display_encoding;
mod fast_exp;
mod fast_trig;
mod grid_spec;
mod isa;
mod lanes;
mod normal_cdf;
mod perlin;
mod tone_curve;
mod transform;

pub use color::{linear_to_srgb, srgb_to_linear, xyy_to_linear_srgb};
pub use display_encoding::{
    ev100_exposure, ev100_of_exposure, metered_ev100, DisplayEncoding, EV100_RANGE, RADIANCE_UNIT_NITS,
};
pub use fast_exp::{fast_exp2, fast_log2, fast_pow, FAST_EXP2_MAX_REL_ERROR, FAST_LOG2_MAX_ABS_ERROR};
pub use fast_trig::{fast_floor, fast_sin_cos, reduce_turns, sin_cos_turns, FAST_SIN_COS_MAX_ERROR};
pub use grid_spec::{GridSpec, MAX_GRID_CELLS};
pub use isa::Isa;
pub use lanes::{Lanes, Mask, Vec3Lanes, LANES};
pub use normal_cdf::{normal_cdf, normal_cdf_table, NORMAL_CDF_LAST, NORMAL_CDF_RANGE, NORMAL_CDF_STEPS_PER_UNIT};
pub use perlin::Perlin;
pub use tone_curve::{ToneCurve, ACES_WHITE};
pub use transform::{Transform, MAX_SCALE};
