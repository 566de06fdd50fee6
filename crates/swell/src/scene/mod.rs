//! Scenes: the description of a frame (camera, lights, sky, water, terrain, render settings), the
//! TOML file format that stores it, its validation and the built-in presets. A scene is parameters
//! only: [`crate::shading`] reads its materials and the sky's keys, and [`crate::world`] builds the
//! runnable world from it.

mod camera;
mod glitter_model;
mod light;
mod memory_estimate;
mod presets;
mod render_settings;
#[allow(clippy::module_inception)]
mod scene;
mod shading_model;
mod sky;
mod sky_model;
mod terrain_material;
mod terrain_spec;
mod water_extent;
mod water_material;
mod water_placement;
mod water_spec;

pub use camera::Camera;
pub use glitter_model::GlitterModel;
pub use light::{Incident, Light};
pub use presets::{preset, Preset, PRESETS};
pub use render_settings::{RenderSettings, MAX_IMAGE_SIDE, MAX_SUPERSAMPLE, MAX_THREADS};
pub use scene::{Scene, MAX_LIGHTS, SCENE_VERSION};
pub use shading_model::Shading;
pub use sky::{Sky, TURBIDITY_RANGE};
pub use sky_model::SkyModel;
pub use terrain_material::{TerrainMaterial, WET_DARKENING};
pub use terrain_spec::{
    HeightmapSpec, TerrainGenerator, TerrainSpec, DEFAULT_TERRAIN_EXTENT, DEFAULT_TERRAIN_SIZE, TERRAIN_GENERATORS,
};
pub use water_extent::{LodSettings, WaterExtent, LOD_RING_CELLS, LOD_SPACING_M, MAX_LOD_LEVELS, MAX_LOD_VERTICES};
pub use water_material::MAX_ABSORPTION;
pub use water_placement::WaterPlacement;
pub use water_spec::{GerstnerSpec, SinesSpec, WaterMaterial, WaterModelSpec, WaterSpec, WaterSurface, WATER_MODELS};
