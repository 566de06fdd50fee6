//! The procedural sky: what the background shows and what water reflects.

use glam::Vec3;
use serde::{Deserialize, Serialize};

use crate::error::{check_finite_vec, check_non_negative, check_range, Error, Result};
use crate::math::Vec3Lanes;
use crate::scene::Light;

/// A sky that blends from a horizon colour to a zenith colour with the elevation of the view ray.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Sky {
    /// Linear RGB radiance at the horizon, >= 0.
    pub horizon: Vec3,
    /// Linear RGB radiance straight up, >= 0.
    pub zenith: Vec3,
    /// Linear RGB radiance seen below the horizon where nothing is drawn (the far ground), >= 0.
    pub ground: Vec3,
    /// Direction the sunlight travels (world, any non-zero length), as for a directional light;
    /// absent: the first directional `[[light]]`'s direction (no sun disc without one).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sun_direction: Option<Vec3>,
    /// Angular diameter of the drawn sun disc in degrees, in [0, 20]; 0 hides it. Default 1.5 (the
    /// real sun is 0.53°; a larger disc stays visible at a few hundred pixels).
    pub sun_size_deg: f32,
    /// Radiance of the disc relative to white (linear), >= 0. Default 20, so that its reflection
    /// stays bright after Fresnel's 2 % at normal incidence.
    pub sun_intensity: f32,
}

/// The sun as drawn in the sky: a disc with a soft edge.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SunDisc {
    /// Unit vector towards the sun.
    pub to_sun: Vec3,
    /// Cosine of the disc's angular radius.
    pub cos_radius: f32,
    /// Linear RGB radiance at the centre of the disc.
    pub radiance: Vec3,
}

impl SunDisc {
    /// Radiance of the disc seen along unit direction `dir`: full inside the disc, falling
    /// smoothly to 0 over a rim as wide as the radius (a crude limb and glare), 0 elsewhere.
    pub fn radiance(&self, dir: Vec3) -> Vec3 {
        let c = dir.dot(self.to_sun);
        let rim = 1.0 - self.cos_radius;
        let edge = (c - (self.cos_radius - rim * 3.0)) / (rim * 3.0);
        if edge <= 0.0 {
            return Vec3::ZERO;
        }
        let k = edge.min(1.0);
        self.radiance * (k * k * (3.0 - 2.0 * k))
    }
}
impl SunDisc {
    /// [`Self::radiance`] along eight unit directions.
    #[inline(always)]
    pub fn radiance_lanes(&self, dir: Vec3Lanes) -> Vec3Lanes {
        let c = dir.dot1(self.to_sun);
        let rim = 1.0 - self.cos_radius;
        let edge = (c - (self.cos_radius - rim * 3.0)) / (rim * 3.0);
        let k = edge.min(1.0);
        let weight = edge.le(0.0).select(0.0, k * k * (3.0 - 2.0 * k));
        Vec3Lanes::splat(self.radiance).scale(weight)
    }
}

impl Default for Sky {
    fn default() -> Self {
        Self {
            horizon: Vec3::new(0.62, 0.72, 0.82),
            zenith: Vec3::new(0.12, 0.28, 0.62),
            ground: Vec3::new(0.18, 0.20, 0.22),
            sun_direction: None,
            sun_size_deg: 1.5,
            sun_intensity: 20.0,
        }
    }
}

impl Sky {
    /// Checks the colours, naming keys under `key` (normally `sky`).
    pub fn validate(&self, key: &str) -> Result<()> {
        for (name, c) in [("horizon", self.horizon), ("zenith", self.zenith), ("ground", self.ground)] {
            for (i, v) in c.to_array().into_iter().enumerate() {
                check_non_negative(&format!("{key}.{name}[{i}]"), v)?;
            }
        }
        if let Some(d) = self.sun_direction {
            check_finite_vec(&format!("{key}.sun_direction"), &d.to_array())?;
            if d.length() < 1e-6 {
                return Err(Error::invalid(format!("{key}.sun_direction"), "must be non-zero"));
            }
        }
        check_range(&format!("{key}.sun_size_deg"), self.sun_size_deg, 0.0, 20.0)?;
        check_non_negative(&format!("{key}.sun_intensity"), self.sun_intensity)
    }

    /// The sun disc, lit by the first directional light's colour (white without one), or `None`
    /// when it has no direction or no size.
    pub fn sun(&self, lights: &[Light]) -> Option<SunDisc> {
        let first = lights.iter().find_map(|l| match *l {
            Light::Directional { direction, color, .. } => Some((direction, color)),
            Light::Point { .. } => None,
        });
        let direction = self.sun_direction.or(first.map(|f| f.0))?;
        if self.sun_size_deg <= 0.0 || self.sun_intensity <= 0.0 {
            return None;
        }
        let color = first.map_or(Vec3::ONE, |f| f.1);
        Some(SunDisc {
            to_sun: -direction.normalize(),
            cos_radius: (0.5 * self.sun_size_deg).to_radians().cos(),
            radiance: color * self.sun_intensity,
        })
    }

    /// [`Self::radiance`] along eight unit directions: the same formula lane by lane.
    #[inline(always)]
    pub fn radiance_lanes(&self, dir: Vec3Lanes) -> Vec3Lanes {
        let up = Vec3Lanes::splat(self.horizon).lerp(Vec3Lanes::splat(self.zenith), dir.y.max(0.0).sqrt());
        let down = Vec3Lanes::splat(self.horizon).lerp(Vec3Lanes::splat(self.ground), (-dir.y * 8.0).min(1.0));
        dir.y.lt(0.0).select3(down, up)
    }

    /// Radiance seen along the unit world direction `dir`.
    pub fn radiance(&self, dir: Vec3) -> Vec3 {
        if dir.y >= 0.0 {
            // sqrt keeps the bright horizon band narrow, as in a clear sky.
            self.horizon.lerp(self.zenith, dir.y.sqrt())
        } else {
            self.horizon.lerp(self.ground, (-dir.y * 8.0).min(1.0))
        }
    }
}
