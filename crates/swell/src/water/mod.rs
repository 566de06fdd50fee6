//! Wave models: what the water surface looks like at time t.
//!
//! Every model implements [`WaveModel`]: it fills caller-owned position and normal buffers for a
//! [`GridSpec`](crate::math::GridSpec) and answers point queries with [`WaveModel::height_at`].
//! Analytic models (those with a closed form per point) implement [`PointWave`] and get parallel grid
//! evaluation and the height query from [`evaluate_pointwise`] and [`height_by_inversion`].

mod fft_ocean;
mod foam;
mod gerstner;
mod sum_of_sines;
mod wave_model;

pub use fft_ocean::{
    FftOcean, FftOceanParams, SeaState, SpectrumKind, StageTimes, SwellParams, CASCADE_SCALE, FFT_GRID_RANGE,
    MAX_CASCADES,
};
pub use foam::{foam_coverage, FoamField, FOAM_RAMP};
pub use gerstner::{Gerstner, GerstnerWave, MAX_GERSTNER_WAVES};
pub use sum_of_sines::{SineWave, SumOfSines, MAX_SINE_WAVES};
pub use wave_model::{evaluate_pointwise, height_by_inversion, PointWave, SurfacePoint, WaveModel};
