//! Specular highlights (Phong and Blinn-Phong lobes) and the full ambient + diffuse + specular
//! model for opaque surfaces.

use glam::Vec3;

use super::{lambert, Environment};
use crate::scene::Shading;

/// Shape of the specular highlight.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Lobe {
    /// `max(0, r.v)^s` with r the light direction mirrored about the normal (Phong 1975).
    Phong,
    /// `max(0, n.h)^s` with h the unit half vector between light and eye (Blinn 1977).
    BlinnPhong,
}

impl Lobe {
    /// The lobe a shading model uses: Phong's for [`Shading::Phong`], Blinn's for the others
    /// (flat and Gouraud evaluate the Blinn-Phong lobe at their evaluation points).
    pub fn of(shading: Shading) -> Lobe {
        match shading {
            Shading::Phong => Lobe::Phong,
            _ => Lobe::BlinnPhong,
        }
    }
}

/// Specular radiance at `p` (unit normal `n`, unit `to_eye`) from every light:
/// `sum radiance * lobe^shininess`, only where the light is above the surface.
pub fn specular(env: &Environment, p: Vec3, n: Vec3, to_eye: Vec3, lobe: Lobe, shininess: f32) -> Vec3 {
    env.lights.iter().fold(Vec3::ZERO, |acc, light| {
        let inc = light.incident(p);
        let n_dot_l = n.dot(inc.to_light);
        if n_dot_l <= 0.0 {
            return acc;
        }
        let c = match lobe {
            Lobe::Phong => (2.0 * n_dot_l * n - inc.to_light).dot(to_eye),
            Lobe::BlinnPhong => n.dot((inc.to_light + to_eye).normalize_or_zero()),
        };
        if c <= 0.0 {
            return acc;
        }
        acc + inc.radiance * c.powf(shininess)
    })
}

/// An opaque surface's reflectance: diffuse albedo and specular strength and exponent.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OpaqueLook {
    /// Linear RGB diffuse albedo, [0, 1].
    pub albedo: Vec3,
    /// Specular strength, >= 0.
    pub specular: f32,
    /// Specular exponent, >= 1.
    pub shininess: f32,
    /// Highlight shape.
    pub lobe: Lobe,
}

/// `albedo * (ambient + sum radiance max(0, n.l)) + specular * sum radiance lobe^shininess`: the
/// Phong reflection model (Phong 1975) or Blinn's variant (paper 003 §2), for unit normal `n`.
pub fn shade_opaque(env: &Environment, look: &OpaqueLook, p: Vec3, n: Vec3) -> Vec3 {
    let to_eye = (env.eye - p).normalize_or(Vec3::Y);
    let diffuse = look.albedo * lambert(env, p, n);
    if look.specular <= 0.0 {
        return diffuse;
    }
    diffuse + look.specular * specular(env, p, n, to_eye, look.lobe, look.shininess)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Light, Sky};

    fn env_with(lights: &[Light], sky: &Sky) -> Environment<'static> {
        let lights: &'static [Light] = Box::leak(lights.to_vec().into_boxed_slice());
        let sky: &'static crate::shading::SkyRadiance = Box::leak(Box::new(crate::shading::SkyRadiance::new(sky)));
        Environment { lights, ambient: Vec3::ZERO, sky, sun: None, eye: Vec3::ZERO, time: 0.0 }
    }

    #[test]
    fn both_lobes_peak_at_the_mirror_direction_and_phong_is_narrower() {
        // Light from 30° off the normal on one side.
        let l = Vec3::new(-0.5, 3f32.sqrt() / 2.0, 0.0);
        let env = env_with(&[Light::Directional { direction: -l, color: Vec3::ONE, intensity: 1.0 }], &Sky::default());
        let n = Vec3::Y;
        let at = |deg: f32, lobe| {
            let a = deg.to_radians();
            specular(&env, Vec3::ZERO, n, Vec3::new(a.sin(), a.cos(), 0.0), lobe, 50.0).x
        };
        for lobe in [Lobe::Phong, Lobe::BlinnPhong] {
            assert!((at(30.0, lobe) - 1.0).abs() < 1e-5, "{lobe:?} peaks at the mirror direction");
            assert!(at(20.0, lobe) < 1.0 && at(40.0, lobe) < 1.0);
        }
        // The half vector moves half as fast as the mirror vector: Blinn's lobe is wider.
        assert!(at(40.0, Lobe::Phong) < at(40.0, Lobe::BlinnPhong));
        // No highlight from a light below the surface.
        let below =
            env_with(&[Light::Directional { direction: Vec3::Y, color: Vec3::ONE, intensity: 1.0 }], &Sky::default());
        assert_eq!(specular(&below, Vec3::ZERO, n, Vec3::Y, Lobe::BlinnPhong, 10.0), Vec3::ZERO);
    }

    #[test]
    fn opaque_shading_is_ambient_plus_lambert_plus_specular() {
        let env = env_with(
            &[Light::Directional { direction: Vec3::new(0.0, -1.0, 0.0), color: Vec3::ONE, intensity: 2.0 }],
            &Sky::default(),
        );
        let mut env = env;
        env.ambient = Vec3::splat(0.1);
        env.eye = Vec3::new(0.0, 5.0, 0.0);
        let look = OpaqueLook { albedo: Vec3::splat(0.5), specular: 0.0, shininess: 10.0, lobe: Lobe::Phong };
        let c = shade_opaque(&env, &look, Vec3::ZERO, Vec3::Y);
        assert!((c - Vec3::splat(0.5 * (0.1 + 2.0))).length() < 1e-6);
        let shiny = OpaqueLook { specular: 0.25, ..look };
        let c2 = shade_opaque(&env, &shiny, Vec3::ZERO, Vec3::Y);
        assert!((c2 - c - Vec3::splat(0.25 * 2.0)).length() < 1e-5);
    }
}
