//! Wave models: what the water surface looks like at time t.
//!
//! Every model implements [`WaveModel`]: it fills caller-owned position and normal buffers for a
//! [`GridSpec`](crate::math::GridSpec) and answers point queries with [`WaveModel::height_at`].
//! Analytic models (those with a closed form per point) implement [`PointWave`] and get parallel grid
//! evaluation and the height query from [`evaluate_pointwise`] and [`height_by_inversion`].

mod gerstner;
mod gerstner_tessendorf;
mod sum_of_sines;
mod trochoidal_sum;
mod wave_model;

pub use gerstner::{Gerstner, GerstnerWave, MAX_GERSTNER_WAVES};
pub use gerstner_tessendorf::{GerstnerTessendorf, TessendorfParams, TessendorfWave, MAX_TESSENDORF_WAVES};
pub use sum_of_sines::{SineWave, SumOfSines, MAX_SINE_WAVES};
pub use wave_model::{evaluate_pointwise, height_by_inversion, PointWave, SurfacePoint, WaveModel};
