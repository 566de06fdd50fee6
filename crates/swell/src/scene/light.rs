//! Light sources.

use glam::Vec3;
use serde::{Deserialize, Serialize};

use crate::error::{check_finite_vec, check_non_negative, Error, Result};

/// A light source. In a scene file: `[[light]]` with `type = "directional"` or `type = "point"`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "lowercase", deny_unknown_fields)]
pub enum Light {
    /// A light at infinity (the sun).
    Directional {
        /// Direction in which the light travels (world, any non-zero length): `[0, -1, 0]` shines
        /// straight down.
        direction: Vec3,
        /// Linear RGB colour, components >= 0. Default white.
        #[serde(default = "white")]
        color: Vec3,
        /// Irradiance scale, >= 0. Default 1.
        #[serde(default = "one")]
        intensity: f32,
    },
    /// A point light whose irradiance falls off with the square of the distance.
    Point {
        /// Position, world metres.
        position: Vec3,
        /// Linear RGB colour, components >= 0. Default white.
        #[serde(default = "white")]
        color: Vec3,
        /// Irradiance at 1 m, >= 0. Default 1.
        #[serde(default = "one")]
        intensity: f32,
    },
}

fn white() -> Vec3 {
    Vec3::ONE
}
fn one() -> f32 {
    1.0
}

/// Light arriving at a surface point: unit direction towards the light and radiance scale.
#[derive(Clone, Copy, Debug)]
pub struct Incident {
    /// Unit vector from the surface towards the light.
    pub to_light: Vec3,
    /// Colour times intensity (and falloff, for point lights).
    pub radiance: Vec3,
}

impl Light {
    /// Checks the light, naming keys under `key` (e.g. `light[0]`).
    pub fn validate(&self, key: &str) -> Result<()> {
        let (v, name, color, intensity) = match self {
            Light::Directional { direction, color, intensity } => (direction, "direction", color, intensity),
            Light::Point { position, color, intensity } => (position, "position", color, intensity),
        };
        check_finite_vec(&format!("{key}.{name}"), &v.to_array())?;
        if name == "direction" && v.length() < 1e-6 {
            return Err(Error::invalid(format!("{key}.direction"), "must be non-zero"));
        }
        for (i, c) in color.to_array().into_iter().enumerate() {
            check_non_negative(&format!("{key}.color[{i}]"), c)?;
        }
        check_non_negative(&format!("{key}.intensity"), *intensity)
    }

    /// Light arriving at world point `p`.
    pub fn incident(&self, p: Vec3) -> Incident {
        match *self {
            Light::Directional { direction, color, intensity } => {
                Incident { to_light: -direction.normalize(), radiance: color * intensity }
            }
            Light::Point { position, color, intensity } => {
                let d = position - p;
                let r2 = d.length_squared().max(1e-6);
                Incident { to_light: d / r2.sqrt(), radiance: color * (intensity / r2) }
            }
        }
    }
}
