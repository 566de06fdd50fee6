//! The unbounded sea's view-dependent state: the camera-following mesh ([`Clipmap`]), displaced
//! each frame by world position from the wave model, and the footprint filter that tells the
//! per-pixel shading how much of the slope spectrum a pixel cannot resolve.
//!
//! Filtering (Bruneton, Neyret and Holzschuch 2010): a ring of spacing `s` carries the waves
//! longer than `2 s`; the shorter ones are point-sampled at its vertices, which is where far water
//! shimmers. Their share of the slope variance is moved from the geometry to the BRDF: each ring's
//! vertex normals keep only the resolved share of their tilt (the slope is scaled by
//! `sqrt(1 - u)`, `u` the unresolved fraction, so the geometric normals have the resolved
//! variance), and each pixel adds back, as roughness, the variance of the waves shorter than the
//! larger of its footprint and the ring's spacing ([`FootprintFilter::variance`]). The flat far
//! field beyond the rings takes the whole variance (`far_field_pass.rs`).

use glam::{Vec2, Vec3};
use rayon::prelude::*;

use crate::mesh::Clipmap;
use crate::scene::{Camera, WaterBody};
use crate::shading::UnresolvedSlopes;

/// The renderer's unbounded-sea mesh, kept between frames (rebuilt when the LOD settings change).
#[derive(Default)]
pub struct SeaLod {
    /// The rings and the (levels, ring cells, spacing) they were built with.
    clipmap: Option<((u32, u32, u32), Clipmap)>,
}

impl SeaLod {
    /// Moves the rings under `camera`, displaces them with `water`'s model at time `t` (s) and
    /// places them in the world; returns them, or `None` when the settings cannot make a mesh
    /// (validation refuses those first, so the caller then draws the patch).
    pub fn update(&mut self, water: &WaterBody, camera: &Camera, t: f64) -> Option<&Clipmap> {
        let lod = water.lod;
        let spacing = lod.spacing.unwrap_or_else(|| {
            let s = water.mesh.grid.spacing();
            s.x.min(s.y)
        });
        let key = (lod.levels, lod.ring_cells, spacing.to_bits());
        if self.clipmap.as_ref().map(|(k, _)| *k) != Some(key) {
            self.clipmap = Some((key, Clipmap::new(lod.levels, lod.ring_cells, spacing).ok()?));
        }
        let (_, clipmap) = self.clipmap.as_mut()?;
        let eye = water.placement.to_local_xz(Vec2::new(camera.eye.x, camera.eye.z));
        clipmap.follow(eye);
        clipmap.displace(water.model.as_ref(), t);
        flatten_unresolved(clipmap, &water.slopes);
        water.placement.apply_to(&mut clipmap.positions, &mut clipmap.normals);
        Some(clipmap)
    }
}

/// Scales each ring's normal tilt to the share of the slope variance its spacing resolves.
fn flatten_unresolved(clipmap: &mut Clipmap, slopes: &UnresolvedSlopes) {
    let total = slopes.total();
    if total <= 0.0 {
        return;
    }
    let mut start = 0;
    for (k, grid) in clipmap.grids().to_vec().iter().enumerate() {
        let count = grid.vertex_count();
        let unresolved = slopes.unresolved(clipmap.level_spacing(k as u32)) / total;
        let keep = (1.0 - unresolved).max(0.0).sqrt();
        if keep < 1.0 {
            clipmap.normals[start..start + count].par_iter_mut().for_each(|n| {
                // Slope (dh/dx, dh/dz) = -(n.x, n.z) / n.y, scaled, and back to a unit normal.
                let y = n.y.abs().max(1e-3);
                *n = Vec3::new(n.x * keep, y, n.z * keep).normalize_or(Vec3::Y);
            });
        }
        start += count;
    }
}

/// How much slope variance each pixel of the unbounded sea leaves unresolved.
#[derive(Clone, Copy, Debug)]
pub struct FootprintFilter<'a> {
    slopes: &'a UnresolvedSlopes,
    eye: Vec3,
    /// Angle (rad) one pixel spans, vertically.
    pixel_angle: f32,
    /// World (x, z) the rings are centred on.
    center: Vec2,
    /// Finest ring spacing (m) and ring side in cells.
    spacing: f32,
    ring_cells: f32,
}

impl<'a> FootprintFilter<'a> {
    /// For `camera` drawing `height` pixel rows (the supersampled height when supersampling) over
    /// `clipmap`'s rings (world placement `world_scale`).
    pub fn new(
        slopes: &'a UnresolvedSlopes,
        camera: &Camera,
        height: u32,
        clipmap: &Clipmap,
        world_scale: f32,
    ) -> Self {
        let pixel_angle = 2.0 * (0.5 * camera.fov_y_deg.to_radians()).tan() / height.max(1) as f32;
        Self {
            slopes,
            eye: camera.eye,
            pixel_angle,
            center: Vec2::new(camera.eye.x, camera.eye.z),
            spacing: clipmap.level_spacing(0) * world_scale,
            ring_cells: clipmap.grids()[0].cells_x as f32,
        }
    }

    /// Slope variance (both axes) the pixel showing world point `p` with mean normal `n` cannot
    /// resolve: the waves shorter than twice the larger of its footprint (its width at that
    /// distance, stretched by the grazing angle) and the ring's vertex spacing there.
    #[inline]
    pub fn variance(&self, p: Vec3, n: Vec3) -> f32 {
        let to_eye = self.eye - p;
        let distance = to_eye.length();
        let cos = (n.dot(to_eye) / distance.max(1e-6)).abs().max(0.05);
        let footprint = distance * self.pixel_angle / cos.sqrt();
        // Ring k covers Chebyshev radii [N/4, N/2] s_k about the centre: s_k <= 4 r / N.
        let r = (Vec2::new(p.x, p.z) - self.center).abs().max_element();
        let mesh = (4.0 * r / self.ring_cells).max(self.spacing);
        self.slopes.unresolved(footprint.max(mesh))
    }
}
