//! Lights as seen from a surface point.

use glam::Vec3;

use super::{SkyRadiance, SunDisc};
use crate::math::Vec3Lanes;
use crate::scene::Light;

/// Everything that lights a surface: the lights, the ambient term and the sky (for reflections).
#[derive(Clone, Copy, Debug)]
pub struct Environment<'a> {
    /// Light sources.
    pub lights: &'a [Light],
    /// Ambient radiance added to every diffuse surface.
    pub ambient: Vec3,
    /// The sky, ready to look up, for reflections and the haze of distance.
    pub sky: &'a SkyRadiance,
    /// The sun disc drawn in the sky and reflected by water, if any ([`Sky::sun`](crate::scene::Sky::sun)).
    pub sun: Option<SunDisc>,
    /// Camera position, world metres.
    pub eye: Vec3,
    /// Simulation time of the frame, seconds (animates sliding textures).
    pub time: f64,
}

impl Environment<'_> {
    /// Radiance of the sky, sun disc included, along unit world direction `dir`.
    pub fn sky_radiance(&self, dir: Vec3) -> Vec3 {
        let sky = self.sky.radiance(dir);
        match &self.sun {
            Some(sun) => sky + sun.radiance(dir),
            None => sky,
        }
    }

    /// `color` of a surface at world `p` with the sky's aerial perspective applied
    /// ([`SkyRadiance::aerial_perspective`]; unchanged when `[sky] haze_distance` is 0).
    #[inline]
    pub fn haze(&self, p: Vec3, color: Vec3) -> Vec3 {
        self.sky.aerial_perspective(self.eye, p, color)
    }
}

impl Environment<'_> {
    /// [`Self::sky_radiance`] along many unit directions.
    #[inline(always)]
    pub fn sky_radiance_lanes(&self, dir: Vec3Lanes) -> Vec3Lanes {
        let sky = self.sky.radiance_lanes(dir);
        match &self.sun {
            Some(sun) => sky + sun.radiance_lanes(dir),
            None => sky,
        }
    }
}

/// Ambient plus Lambert diffuse irradiance at `p` with unit normal `n`:
/// `ambient + sum radiance * max(0, n.l)`.
pub fn lambert(env: &Environment, p: Vec3, n: Vec3) -> Vec3 {
    env.lights.iter().fold(env.ambient, |acc, light| {
        let inc = light.incident(p);
        acc + inc.radiance * n.dot(inc.to_light).max(0.0)
    })
}
