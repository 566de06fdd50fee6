//! The sea beyond the camera-following mesh, to the horizon: every pixel the geometry left at the
//! far plane whose view ray goes down meets the mean sea plane y = 0 there, and is shaded as water
//! whose every wave is unresolved (their whole slope variance, `shading/slope_variance.rs`).
//!
//! This is a ray cast per pixel, not geometry, so the camera's far plane cannot cut the sea off
//! and no band of sky `ground` colour is left between the last triangle and the horizon, at any
//! camera height. Out there a wave of the largest amplitude spans less than a pixel (the rings
//! reach [`crate::mesh::Clipmap::reach`]), so the flat mean plane and the displaced rings meet
//! without a visible step.
//!
//! A camera under the mean surface (a wave passing over it, or a user flying down) sees the
//! surface from below as a plain surface: the pixels no geometry covered get the water's body
//! colour lit by the ambient term, never a smear of sky.

use glam::Vec3;
use rayon::prelude::*;

use super::sky_pass::{SkyRays, SkyRow};
use super::FrameContext;
use crate::raster::Framebuffer;
use crate::scene::Camera;
use crate::shading::{lambert, shade_water_run, Lobe, NoBottom, SurfaceVarying, UnresolvedSlopes, WaterLook, WaterRun};
use crate::world::WaterBody;

/// Rows per task: the far field is a band just under the horizon.
const ROWS_PER_TASK: usize = 8;

/// Depth written where the far field lands: just in front of the far plane, so the sky pass
/// (which fills depth 1) leaves these pixels alone.
pub(crate) const FAR_FIELD_DEPTH: f32 = 1.0 - f32::EPSILON;

/// Shades every pixel still at the far plane whose view ray meets the sea plane (or, from under
/// the surface, every one of them).
pub fn draw(
    fb: &mut Framebuffer,
    frame: &FrameContext,
    camera: &Camera,
    water: &WaterBody,
    slopes: &UnresolvedSlopes,
    lobe: Lobe,
) {
    let (width, height) = (fb.width(), fb.height());
    let rays = SkyRays::new(camera, width as f32 / height as f32);
    let env = &frame.env;
    let eye = env.eye;
    let material = &water.material;
    // Far out no bottom shows; the texture would alias, so the body colour stands for it.
    let look = WaterLook::new(material, &NoBottom, None, env.time)
        .with_glitter(super::water_pass::sun_glitter(water, env.sun.as_ref()));
    let variance = slopes.total();
    let below = eye.y < 0.0;
    let from_below = if below { material.color * lambert(env, eye, -Vec3::Y) } else { Vec3::ZERO };
    let w = width as usize;
    fb.color.par_chunks_mut(w).zip(fb.depth.par_chunks_mut(w)).enumerate().with_max_len(ROWS_PER_TASK).for_each_init(
        || (Vec::new(), Vec::new()),
        |(xs, shaded): &mut (Vec<usize>, Vec<Vec3>), (y, (colors, depth))| {
            let ndc_y = 1.0 - 2.0 * (y as f32 + 0.5) / height as f32;
            let row = rays.row(ndc_y);
            xs.clear();
            for (x, (c, d)) in colors.iter_mut().zip(depth.iter_mut()).enumerate() {
                if *d < 1.0 {
                    continue;
                }
                if below {
                    *c = from_below;
                    *d = FAR_FIELD_DEPTH;
                    continue;
                }
                let ndc_x = 2.0 * (x as f32 + 0.5) / width as f32 - 1.0;
                if row.direction(ndc_x).y < 0.0 {
                    xs.push(x); // else the sky's
                }
            }
            // The row's far-field pixels, shaded eight at a time.
            let run = FarRow { xs, row: &row, width: width as f32, eye, variance };
            shaded.resize(xs.len(), Vec3::ZERO);
            shade_water_run(env, &look, lobe, &run, shaded);
            for (&x, c) in xs.iter().zip(shaded.iter()) {
                colors[x] = *c;
                depth[x] = FAR_FIELD_DEPTH;
            }
        },
    );
}

/// The pixels of one row that see the mean sea plane beyond the rings, as a run of water points.
struct FarRow<'a> {
    xs: &'a [usize],
    row: &'a SkyRow,
    width: f32,
    eye: Vec3,
    /// Every wave is unresolved out there.
    variance: f32,
}

impl WaterRun for FarRow<'_> {
    fn len(&self) -> usize {
        self.xs.len()
    }
    #[inline(always)]
    fn point(&self, i: usize) -> SurfaceVarying {
        let ndc_x = 2.0 * (self.xs[i] as f32 + 0.5) / self.width - 1.0;
        let dir = self.row.direction(ndc_x);
        let position = self.eye + dir * (-self.eye.y / dir.y);
        SurfaceVarying { position, normal: Vec3::Y, foam: 0.0, unresolved: self.variance }
    }
}
