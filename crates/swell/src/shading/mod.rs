//! Shading: how much light leaves a surface point towards the eye, and the inputs it reads.
//!
//! The rasterizer interpolates whatever the chosen [`crate::scene::Shading`] model needs
//! (`render/shaded_draw.rs`); the functions here turn a position, a normal and the scene's lights,
//! sky and materials into linear RGB. Materials and the sky's keys are parameters and live in
//! [`crate::scene`]; this module reads them and is never read by it. Beside the shading that uses
//! them live its inputs built from those parameters: the sky's physics (the sun disc and colour,
//! Preetham et al.'s model, [`SkyRadiance`] to look the sky up), the foam pattern and textures.

mod foam_pattern;
mod fresnel;
mod lighting;
mod preetham;
mod reflection_map;
mod sky_light;
mod sky_radiance;
mod slope_variance;
mod specular;
mod sun_glitter;
mod surface_varying;
mod terrain_color;
mod texture;
mod water_optics;

pub use foam_pattern::{FoamPattern, FOAM_PATTERN_LEVELS, FOAM_PATTERN_SIDE};
pub use fresnel::fresnel_dielectric;
pub use lighting::{lambert, Environment};
pub use preetham::{sun_transmittance, zenith_chromaticity, zenith_luminance, Perez, PreethamSky};
pub use reflection_map::ReflectionMap;
pub use sky_light::{SunDisc, SunProfile};
pub use sky_radiance::{SkyRadiance, TABLE_SIDE};
pub use slope_variance::{mean_fresnel, pixel_footprint_lanes, widened_lobe, UnresolvedSlopes};
pub use specular::{shade_opaque, specular, Lobe, OpaqueLook};
pub use sun_glitter::SunGlitter;
pub use surface_varying::SurfaceVarying;
pub use terrain_color::shade_terrain;
pub use texture::{Texture, MAX_TEXTURE_SIDE};
pub use water_optics::{
    refract, shade_water, shade_water_filtered, shade_water_lanes, shade_water_run, FlatBottom, NoBottom, Seabed,
    WaterLook, WaterPoints, WaterRun,
};
