//! Scenes: the description of a frame (camera, lights, sky, water, render settings), the TOML file
//! format that stores it, the built-in presets, and the runnable [`World`] built from it.

mod camera;
mod foam_pattern;
mod light;
mod memory_estimate;
mod preetham;
mod presets;
mod render_settings;
#[allow(clippy::module_inception)]
mod scene;
mod sea_stats;
mod shading_model;
mod sky;
mod sky_model;
mod sky_radiance;
mod terrain_body;
mod terrain_far_land;
mod terrain_material;
mod terrain_spec;
mod texture;
mod water_extent;
mod water_material;
mod water_placement;
mod water_query;
mod water_spec;
mod world;

pub use camera::Camera;
pub use foam_pattern::{FoamPattern, FOAM_PATTERN_SIDE};
pub use light::{Incident, Light};
pub use preetham::{sun_transmittance, zenith_chromaticity, zenith_luminance, Perez, PreethamSky, TURBIDITY_RANGE};
pub use presets::{preset, Preset, PRESETS};
pub use render_settings::{RenderSettings, MAX_IMAGE_SIDE, MAX_SUPERSAMPLE, MAX_THREADS};
pub use scene::{Scene, MAX_LIGHTS, SCENE_VERSION};
pub use sea_stats::{sea_stats, SeaStats};
pub use shading_model::Shading;
pub use sky::{Sky, SunDisc, SunProfile};
pub use sky_model::SkyModel;
pub use sky_radiance::{SkyRadiance, TABLE_SIDE};
pub use terrain_body::TerrainBody;
pub use terrain_far_land::FarLand;
pub use terrain_material::TerrainMaterial;
pub use terrain_spec::{
    HeightmapSpec, TerrainGenerator, TerrainSpec, DEFAULT_TERRAIN_EXTENT, DEFAULT_TERRAIN_SIZE, TERRAIN_GENERATORS,
};
pub use texture::{Texture, MAX_TEXTURE_SIDE};
pub use water_extent::{LodSettings, WaterExtent, LOD_RING_CELLS, LOD_SPACING_M, MAX_LOD_LEVELS, MAX_LOD_VERTICES};
pub use water_material::MAX_ABSORPTION;
pub use water_placement::WaterPlacement;
pub use water_query::{Water, NORMAL_STEP_M};
pub use water_spec::{GerstnerSpec, SinesSpec, WaterMaterial, WaterModelSpec, WaterSpec, WaterSurface, WATER_MODELS};
pub use world::{WaterBody, World};
