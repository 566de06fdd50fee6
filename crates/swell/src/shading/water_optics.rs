//! The colour of a water surface point: light scattered from the water body plus the sky it
//! reflects, weighted by Fresnel (paper 003 §2).

use glam::Vec3;

use super::{fresnel_dielectric, lambert, Environment};
use crate::scene::WaterMaterial;

/// Radiance leaving water point `p` (world m) with unit normal `n` towards the eye.
///
/// `(1 - F) * color * (ambient + diffuse) + F * sky(reflected view ray)`, with F the exact Fresnel
/// reflectance for the material's refractive index. A reflected ray that points below the horizon
/// hits the water again; it is bent back to the horizon, whose colour is what such a ray would
/// eventually see.
pub fn shade_water(env: &Environment, material: &WaterMaterial, p: Vec3, n: Vec3) -> Vec3 {
    let to_eye = (env.eye - p).normalize_or(Vec3::Y);
    // Seen from behind (a fold, or the far side of a steep crest), shade the side facing the eye.
    let n = if n.dot(to_eye) < 0.0 { -n } else { n };
    let cos_i = n.dot(to_eye);
    let f = fresnel_dielectric(cos_i, material.refractive_index);
    let mut reflected = (2.0 * cos_i * n - to_eye).normalize_or(Vec3::Y);
    reflected.y = reflected.y.max(0.0);
    let body = material.color * lambert(env, p, n);
    body * (1.0 - f) + env.sky.radiance(reflected.normalize_or(Vec3::Y)) * f
}
