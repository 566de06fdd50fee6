//! Shading: how much light leaves a surface point towards the eye.
//!
//! The rasterizer interpolates whatever the chosen [`crate::scene::Shading`] model needs
//! (`render/shaded_draw.rs`); the functions here turn a position, a normal and the scene's lights,
//! sky and materials into linear RGB. Materials are parameters and live in [`crate::scene`];
//! this module reads them and is never read by it.

mod fresnel;
mod lighting;
mod reflection_map;
mod slope_variance;
mod specular;
mod surface_varying;
mod terrain_color;
mod water_optics;

pub use fresnel::fresnel_dielectric;
pub use lighting::{lambert, Environment};
pub use reflection_map::ReflectionMap;
pub use slope_variance::{mean_fresnel, widened_lobe, UnresolvedSlopes};
pub use specular::{shade_opaque, specular, Lobe, OpaqueLook};
pub use surface_varying::SurfaceVarying;
pub use terrain_color::shade_terrain;
pub use water_optics::{
    refract, shade_water, shade_water_filtered, shade_water_lanes, shade_water_run, FlatBottom, NoBottom, Seabed,
    WaterLook, WaterPoints, WaterRun,
};
