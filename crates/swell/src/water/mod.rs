//! Wave models: what the water surface looks like at time t.
//!
//! Every model implements [`WaveModel`]: it fills caller-owned position and normal buffers for a
//! [`GridSpec`](crate::math::GridSpec) and answers point queries with [`WaveModel::height_at`].
//! Analytic models (those with a closed form per point) implement [`PointWave`] and get parallel grid
//! evaluation and the height query from [`evaluate_pointwise`] and [`height_by_inversion`].

mod airy;
mod fft_ocean;
mod foam;
mod gerstner;
mod gerstner_tessendorf;
mod model_params;
mod noise_waves;
mod radial_wave;
mod river;
mod slope_spectrum;
mod spring_mesh;
mod steep_sines;
mod sum_of_sines;
mod trochoidal_sum;
mod wave_model;
mod wave_set;

pub use airy::{Airy, AiryParams, AiryWave, MAX_AIRY_WAVES};
pub use fft_ocean::{BlenderOcean, BLENDER_RESOLUTION_RANGE};
pub use fft_ocean::{
    FftOcean, FftOceanParams, InlineSpectrumTable, SeaState, SpectrumFiles, StageTimes, SwellParams, CASCADE_SCALE,
    FFT_GRID_RANGE, MAX_CASCADES, MAX_SPECTRUM_FILE_BYTES,
};
pub use foam::{
    foam_coverage, FoamField, FoamUpdate, FoamWeights, LatticeSteps, FOAM_ACTIVE_TIME_S, FOAM_LATTICE_STEP_S,
    FOAM_MEMORY_CUT, FOAM_MIN_SPREAD,
};
pub use gerstner::{Gerstner, GerstnerSpec, GerstnerWave, MAX_GERSTNER_WAVES};
pub use gerstner_tessendorf::{GerstnerTessendorf, TessendorfParams, TessendorfWave, MAX_TESSENDORF_WAVES};
pub use model_params::{ModelParams, SurfaceFlow};
pub use noise_waves::{NoiseFrame, NoiseParams, NoiseWaves, MAX_NOISE_OCTAVES};
pub use radial_wave::{RadialWave, RadialWaveParams};
pub use river::{River, RiverParams};
pub use slope_spectrum::{
    cox_munk_axis_variances, cox_munk_slope_variance, developed_sea_wind, push_wave_slopes, UnresolvedSlopes,
};
pub use spring_mesh::{DropSchedule, Edges, SpringMesh, SpringMeshParams, MAX_SPRING_CELLS, MAX_STEPS_PER_ADVANCE};
pub use steep_sines::{SteepSineWave, SteepSines, SteepSinesParams, MAX_STEEP_SINE_EXPONENT, MAX_STEEP_SINE_WAVES};
pub use sum_of_sines::{SineWave, SinesSpec, SumOfSines, MAX_SINE_WAVES};
pub use wave_model::{
    evaluate_pointwise, height_by_inversion, velocity_by_difference, PointWave, SurfacePoint, WaveModel,
};
pub use wave_set::{wave_set, WaveSetParams};
