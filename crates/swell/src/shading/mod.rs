//! Shading: how much light leaves a surface point towards the eye.
//!
//! The rasterizer interpolates whatever the chosen [`Shading`] model needs; the functions here turn
//! a position, a normal and the scene's lights and sky into linear RGB.

mod fresnel;
mod lighting;
mod terrain_color;
mod water_optics;

pub use fresnel::fresnel_dielectric;
pub use lighting::{lambert, Environment};
pub use terrain_color::{shade_terrain, TerrainMaterial, TerrainShading};
pub use water_optics::shade_water;

use serde::{Deserialize, Serialize};

/// Where lighting is evaluated.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Shading {
    /// Once per triangle from its face normal (paper 001's look).
    Flat,
    /// Once per vertex from the vertex normal, colours interpolated across the triangle (paper 000).
    #[default]
    Gouraud,
}
