//! The sky seen along each pixel's view ray. The depth is cleared before the geometry passes
//! ([`clear_depth`]) and the sky drawn after them ([`draw`]), only where no geometry landed, so a
//! frame full of water does not pay for a sky it hides.

use glam::Vec3;
use rayon::prelude::*;

use crate::math::{Isa, Lanes, Vec3Lanes, LANES};
use crate::raster::Framebuffer;
use crate::scene::Camera;
use crate::shading::{SkyRadiance, SunDisc};

/// Clears depth to the far plane (colour is left for [`draw`]).
pub fn clear_depth(fb: &mut Framebuffer) {
    // Blocks filled as slices (a vectorised store loop): rayon's split down to single elements
    // cost the clear about 1.5 % of a `noon` frame in `perf`.
    fb.depth.par_chunks_mut(DEPTH_CLEAR_BLOCK).for_each(|block| block.fill(1.0));
}

/// Depth values per task of [`clear_depth`]: 64 KiB.
const DEPTH_CLEAR_BLOCK: usize = 16 * 1024;

/// Pixels between the sky samples of a tabulated sky along a row ([`draw`]).
const SPAN: usize = 8;
const _: () = assert!(LANES.is_multiple_of(SPAN), "a batch of the sky pass holds whole spans");

/// Fills every pixel still at the far plane with `sky` seen by `camera` (and its sun disc, if any).
///
/// A tabulated sky ([`SkyRadiance::is_tabulated`], Preetham's) varies over degrees while a pixel
/// is a few hundredths of one, so it is looked up every [`SPAN`] pixels of a row and blended
/// linearly between them (the sun disc, which is sharp, stays per pixel); the gradient sky is
/// evaluated at every pixel, many at a time.
pub fn draw(fb: &mut Framebuffer, camera: &Camera, sky: &SkyRadiance, sun: Option<&SunDisc>) {
    let (width, height) = (fb.width(), fb.height());
    let rays = SkyRays::new(camera, width as f32 / height as f32);
    // Both skies (and the sun) [`LANES`] pixels at a time: the lane formulas are the scalar
    // ones, lane by lane; a call per pixel cost the sky pass most of its time (for the tabulated
    // sky, the sun disc's direction and distance per pixel were half of the pass at `noon`).
    fb.fill_background_rows(|y, colors, depth| {
        let row = SkyRowFill { rays: rays.row(1.0 - 2.0 * (y as f32 + 0.5) / height as f32), width, sky, sun };
        row.fill(colors, depth);
    });
}

/// One image row of the sky (and sun): its rays, the image width and what it shows.
struct SkyRowFill<'a> {
    rays: SkyRow,
    width: u32,
    sky: &'a SkyRadiance,
    sun: Option<&'a SunDisc>,
}

impl SkyRowFill<'_> {
    /// Writes the row's pixels left at the far plane (`depth` 1), compiled for the widest vector
    /// instructions the CPU has ([`Isa`]): the same IEEE operations lane by lane whichever, so the
    /// image does not depend on the CPU.
    fn fill(&self, colors: &mut [Vec3], depth: &[f32]) {
        self.fill_with(Isa::widest(), colors, depth);
    }

    /// [`Self::fill`] compiled for `isa`.
    fn fill_with(&self, isa: Isa, colors: &mut [Vec3], depth: &[f32]) {
        isa.run(
            #[inline(always)]
            || self.fill_lanes(colors, depth),
        );
    }

    #[inline(always)]
    fn fill_lanes(&self, colors: &mut [Vec3], depth: &[f32]) {
        let Self { rays, width, sky, sun } = self;
        let ndc = |x: usize| 2.0 * (x as f32 + 0.5) / *width as f32 - 1.0;
        // A tabulated sky varies over degrees while a pixel is a few hundredths of one: it is
        // looked up every `SPAN` pixels (sample j at pixel min(j SPAN, last)), many at a time,
        // and blended linearly between (the sharp sun disc stays per pixel).
        let last = colors.len().saturating_sub(1);
        let samples: Vec<Vec3> = if sky.is_tabulated() && depth.iter().any(|&d| d >= 1.0) {
            let count = last / SPAN + 2;
            (0..count.div_ceil(LANES))
                .flat_map(|b| {
                    let at = Lanes::from_fn(|i| ndc(((b * LANES + i) * SPAN).min(last)));
                    let c = sky.radiance_lanes(rays.directions(at));
                    (0..LANES).map(move |i| c.lane(i))
                })
                .take(count)
                .collect()
        } else {
            Vec::new()
        };
        for x0 in (0..colors.len()).step_by(LANES) {
            let n = LANES.min(colors.len() - x0);
            if depth[x0..x0 + n].iter().all(|&d| d < 1.0) {
                continue;
            }
            let dir = rays.directions(Lanes::from_fn(|i| ndc(x0 + i)));
            let sun = match sun {
                Some(s) => s.radiance_lanes(dir),
                None => Vec3Lanes::splat(Vec3::ZERO),
            };
            if !sky.is_tabulated() {
                let c = sky.radiance_lanes(dir) + sun;
                for (i, (color, &d)) in colors[x0..x0 + n].iter_mut().zip(&depth[x0..x0 + n]).enumerate() {
                    if d >= 1.0 {
                        *color = c.lane(i);
                    }
                }
                continue;
            }
            // Span by span (a block holds whole spans: `LANES` is a multiple of `SPAN`), the
            // blend's ends and step once per span.
            for s0 in (x0..x0 + n).step_by(SPAN) {
                let (a, b) = (samples[s0 / SPAN], samples[s0 / SPAN + 1]);
                let step = 1.0 / ((s0 + SPAN).min(last) - s0).max(1) as f32;
                for x in s0..(s0 + SPAN).min(x0 + n) {
                    if depth[x] >= 1.0 {
                        colors[x] = a.lerp(b, (x - s0) as f32 * step) + sun.lane(x - x0);
                    }
                }
            }
        }
    }
}

/// World-space view-ray directions for NDC coordinates: a ray through NDC (x, y) is linear in x
/// and y before normalisation, so three vectors replace an inverse projection per pixel.
pub(crate) struct SkyRays {
    forward: Vec3,
    right: Vec3,
    up: Vec3,
}

impl SkyRays {
    /// Rays of `camera` for an image of `aspect` = width / height.
    pub fn new(camera: &Camera, aspect: f32) -> Self {
        let forward = (camera.target - camera.eye).normalize();
        let right = forward.cross(camera.up).normalize();
        let up = right.cross(forward);
        let tan_half = (0.5 * camera.fov_y_deg.to_radians()).tan();
        Self { forward, right: right * tan_half * aspect, up: up * tan_half }
    }

    /// The rays of the image row at `ndc_y` in [-1, 1].
    pub fn row(&self, ndc_y: f32) -> SkyRow {
        SkyRow { forward: self.forward, right: self.right, up_y: self.up * ndc_y }
    }
}

/// The view rays of one image row: [`SkyRays`] with the row's share computed once.
pub(crate) struct SkyRow {
    forward: Vec3,
    right: Vec3,
    /// The up vector scaled to the row.
    up_y: Vec3,
}

impl SkyRow {
    /// Unit world direction of the ray through NDC x `ndc_x` in [-1, 1] on this row.
    #[inline]
    pub fn direction(&self, ndc_x: f32) -> Vec3 {
        // The same sum, in the same order, as computed per pixel before the row was factored out.
        (self.forward + self.right * ndc_x + self.up_y).normalize()
    }

    /// [`Self::direction`] for many `ndc_x` at once (the same operations lane by lane).
    #[inline(always)]
    pub fn directions(&self, ndc_x: Lanes) -> Vec3Lanes {
        let splat = Vec3Lanes::splat;
        (splat(self.forward) + splat(self.right).scale(ndc_x) + splat(self.up_y)).normalize_or(Vec3::Y)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Sky, SkyModel};

    /// The sparse sampling of a tabulated sky is within 0.5 % of looking up every pixel at
    /// 1280x720 (a span is then 0.5° wide), the sun
    /// disc included, and fills only the pixels left at the far plane.
    #[test]
    fn a_tabulated_sky_sampled_per_span_matches_the_per_pixel_sky() {
        let camera = Camera { eye: Vec3::new(0.0, 2.0, 0.0), target: Vec3::new(0.0, 4.0, -10.0), ..Camera::default() };
        let sky = Sky { model: SkyModel::Preetham, sun_elevation_deg: 12.0, sun_azimuth_deg: 5.0, ..Sky::default() };
        let (w, h) = (1280, 720);
        let table = SkyRadiance::new(&sky);
        let sun = sky.sun(&[]);
        assert!(sun.is_some());
        let mut fb = Framebuffer::new(w, h);
        clear_depth(&mut fb);
        // A block of "geometry" the sky must not overwrite.
        for y in 100..200 {
            for x in 300..500 {
                fb.depth[(y * w + x) as usize] = 0.5;
                fb.color[(y * w + x) as usize] = Vec3::new(7.0, 8.0, 9.0);
            }
        }
        draw(&mut fb, &camera, &table, sun.as_ref());
        let rays = SkyRays::new(&camera, w as f32 / h as f32);
        let mut lit = 0;
        for y in (0..h).step_by(7) {
            let row = rays.row(1.0 - 2.0 * (y as f32 + 0.5) / h as f32);
            for x in 0..w {
                let c = fb.color[(y * w + x) as usize];
                if (300..500).contains(&x) && (100..200).contains(&y) {
                    assert_eq!(c, Vec3::new(7.0, 8.0, 9.0));
                    continue;
                }
                let dir = row.direction(2.0 * (x as f32 + 0.5) / w as f32 - 1.0);
                let sun_part = sun.as_ref().unwrap().radiance(dir);
                lit += usize::from(sun_part.max_element() > 0.0);
                let exact = table.radiance(dir) + sun_part;
                let err = (c - exact).abs().max_element() / exact.max_element();
                assert!(err < 5e-3, "({x}, {y}): {c} vs {exact}");
            }
        }
        assert!(lit > 0, "the sun (or its glow) is in view");
    }

    /// Both skies' rows give the same bits whichever vector instructions fill them.
    #[test]
    fn isa_builds_agree() {
        let camera = Camera { eye: Vec3::new(0.0, 2.0, 0.0), target: Vec3::new(0.3, 1.0, -10.0), ..Camera::default() };
        for model in [SkyModel::Gradient, SkyModel::Preetham] {
            isa_builds_agree_for(&camera, &Sky { model, sun_elevation_deg: 8.0, ..Sky::default() });
        }
    }

    fn isa_builds_agree_for(camera: &Camera, sky: &Sky) {
        let table = SkyRadiance::new(sky);
        assert_eq!(table.is_tabulated(), sky.model == SkyModel::Preetham);
        let sun = sky.sun(&[]);
        let rays = SkyRays::new(camera, 16.0 / 9.0);
        // 1000 columns: whole batches and a partial one; every third pixel covered by geometry.
        let depth: Vec<f32> = (0..1000).map(|x| if x % 3 == 0 { 0.5 } else { 1.0 }).collect();
        for ndc_y in [-0.9, -0.1, 0.0, 0.05, 0.7] {
            let row = SkyRowFill { rays: rays.row(ndc_y), width: 1000, sky: &table, sun: sun.as_ref() };
            let fill = |isa: Isa| {
                let mut colors = vec![Vec3::splat(-1.0); 1000];
                row.fill_with(isa, &mut colors, &depth);
                colors
            };
            let portable = fill(Isa::Portable);
            assert!(portable.iter().zip(&depth).all(|(c, &d)| (d < 1.0) == (*c == Vec3::splat(-1.0))));
            for isa in Isa::ALL.into_iter().filter(|isa| isa.is_available()) {
                let bits = |v: &[Vec3]| v.iter().flat_map(|c| c.to_array().map(f32::to_bits)).collect::<Vec<_>>();
                assert_eq!(bits(&fill(isa)), bits(&portable), "{isa:?} at ndc y {ndc_y}");
            }
        }
    }
}
