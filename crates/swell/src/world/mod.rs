//! The world: a scene made runnable. [`World::new`] validates a [`crate::scene::Scene`] once and
//! builds its models, meshes, terrain and materials once; [`World::update`] moves them to a time
//! each frame, and the renderer ([`crate::render`]) and the exporters ([`crate::export`]) read it.
//! Beside it, what else is built from a scene: [`Water`] (`swell::Water`), the water alone behind
//! one query API for embedders, and [`sea_stats`], the sea state a spectral scene realises.

mod sea_stats;
mod terrain_body;
mod terrain_far_land;
mod water_query;
#[allow(clippy::module_inception)]
mod world;
mod world_environment;

pub use sea_stats::{sea_stats, water_sea_stats, SeaStats};
pub use terrain_body::TerrainBody;
pub use terrain_far_land::FarLand;
pub use water_query::{Watch, Water, MAX_QUERY_COORDINATE_M, NORMAL_STEP_M, WORK_PER_WATCH};
pub use world::{WaterBody, World};
