//! Shading: how much light leaves a surface point towards the eye.
//!
//! The rasterizer interpolates whatever the chosen [`Shading`] model needs; the functions here turn
//! a position, a normal and the scene's lights and sky into linear RGB.

mod fresnel;
mod lighting;
mod reflection_map;
mod slope_variance;
mod specular;
mod surface_varying;
mod terrain_color;
mod texture;
mod water_optics;

pub use fresnel::fresnel_dielectric;
pub use lighting::{lambert, Environment};
pub use reflection_map::ReflectionMap;
pub use slope_variance::{mean_fresnel, spread_normals, widened_lobe, UnresolvedSlopes};
pub use specular::{shade_opaque, specular, Lobe, OpaqueLook};
pub use surface_varying::SurfaceVarying;
pub use terrain_color::{shade_terrain, TerrainMaterial, TerrainShading};
pub use texture::Texture;
pub use water_optics::{refract, shade_water, shade_water_filtered, FlatBottom, NoBottom, Seabed, WaterLook};

use serde::{Deserialize, Serialize};

/// Where lighting is evaluated, and with which specular lobe.
///
/// Every model computes ambient + diffuse (Lambert) + specular; they differ in how often and in the
/// shape of the highlight. Flat and Gouraud use the Blinn-Phong lobe at their evaluation points.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Shading {
    /// Once per triangle from its face normal (paper 001's look).
    Flat,
    /// Once per vertex from the vertex normal, colours interpolated across the triangle (paper 000).
    #[default]
    Gouraud,
    /// Per pixel from the interpolated normal and world position, with Phong's reflection lobe
    /// `(r.v)^s` (Phong 1975).
    Phong,
    /// Per pixel like Phong, with Blinn's half-vector lobe `(n.h)^s` (Blinn 1977; paper 003 §2).
    BlinnPhong,
}

impl Shading {
    /// The names the scene file and CLI accept.
    pub const NAMES: &'static [&'static str] = &["flat", "gouraud", "phong", "blinn-phong"];

    /// The specular lobe this model uses.
    pub fn lobe(self) -> Lobe {
        match self {
            Shading::Phong => Lobe::Phong,
            _ => Lobe::BlinnPhong,
        }
    }

    /// Parses a name from [`Shading::NAMES`]; `key` is named in the error.
    pub fn parse(name: &str, key: &str) -> crate::Result<Self> {
        Ok(match name {
            "flat" => Shading::Flat,
            "gouraud" => Shading::Gouraud,
            "phong" => Shading::Phong,
            "blinn-phong" => Shading::BlinnPhong,
            other => {
                return Err(crate::Error::invalid(
                    key,
                    format!("`{other}` is not a shading model; valid: {}", Self::NAMES.join(", ")),
                ))
            }
        })
    }
}
