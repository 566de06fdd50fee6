//! Specular highlights (Phong and Blinn-Phong lobes) and the full ambient + diffuse + specular
//! model for opaque surfaces.

use glam::Vec3;

use super::{lambert, Environment};

/// Shape of the specular highlight.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Lobe {
    /// `max(0, r.v)^s` with r the light direction mirrored about the normal (Phong 1975).
    Phong,
    /// `max(0, n.h)^s` with h the unit half vector between light and eye (Blinn 1977).
    BlinnPhong,
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
