//! The unbounded sea's view-dependent state: the camera-following mesh ([`Clipmap`]), displaced
//! each frame by world position from the wave model, and the footprint filter that tells the
//! per-pixel shading how much of the slope spectrum a pixel cannot resolve.
//!
//! Filtering (Bruneton, Neyret and Holzschuch 2010): a ring of spacing `s` carries the waves
//! longer than `2 s`; the shorter ones are point-sampled at its vertices, which is where far water
//! shimmers. Their share of the slope variance is moved from the geometry to the BRDF: each
//! vertex normal keeps only the resolved share of its tilt (the slope is scaled by
//! `sqrt(1 - u)`, `u` the fraction of the variance unresolved at that vertex, so the geometric
//! normals carry the resolved variance), and each pixel adds back, as roughness, the variance of
//! the waves shorter than twice the larger of its footprint and the ring's spacing
//! ([`FootprintFilter::variance_lanes`], computed at the vertices and interpolated like the normals:
//! it varies smoothly with distance, and per pixel it was a quarter of the `sea`'s water
//! shading). The scaling treats all waves alike (a long swell far out loses tilt with the short
//! waves); per-wave removal from the geometry is left for later. The flat far field beyond the
//! rings takes the whole variance (`far_field_pass.rs`).

use glam::{Vec2, Vec3};
use rayon::prelude::*;

use crate::math::{Isa, Lanes, Vec3Lanes, LANES};
use crate::mesh::Clipmap;
use crate::scene::Camera;
use crate::shading::pixel_footprint_lanes;
use crate::water::UnresolvedSlopes;

/// The renderer's per-image state of the unbounded sea: the rings' normals with the unresolved
/// slopes moved out of them, and those slopes per vertex, kept between frames so that steady
/// frames do not allocate. The rings themselves are the world's
/// ([`crate::world::WaterBody::surface`]): only what depends on the image lives here.
#[derive(Default)]
pub struct SeaLod {
    /// The rings' normals keeping only the resolved share of their tilt.
    normals: Vec<Vec3>,
    /// Slope variance each vertex's pixel leaves unresolved ([`FootprintFilter::variance_lanes`]).
    unresolved: Vec<f32>,
}

/// What the unbounded sea's rings get for one image: normals filtered for it, and each vertex's
/// unresolved slope variance for the shading to interpolate (positions and triangles stay the
/// world's).
#[derive(Clone, Copy)]
pub struct SeaMesh<'a> {
    /// Unit normals keeping the resolved share of each vertex's tilt.
    pub normals: &'a [Vec3],
    /// Slope variance (both axes, >= 0) the pixel at each vertex leaves unresolved.
    pub unresolved: &'a [f32],
}

impl SeaLod {
    /// Moves the slopes that no pixel of a `rows`-row image seen by `camera` resolves from the
    /// normals of `rings` (the world's, displaced and placed; `world_scale` the patch's uniform
    /// scale) to the shading (each vertex's share in [`SeaMesh::unresolved`]), for a sea whose
    /// slope spectrum is `slopes` (world units).
    pub fn filter<'a>(
        &'a mut self,
        rings: &'a Clipmap,
        slopes: &UnresolvedSlopes,
        world_scale: f32,
        camera: &Camera,
        rows: u32,
    ) -> SeaMesh<'a> {
        let count = rings.positions.len();
        self.unresolved.clear();
        self.unresolved.resize(count, 0.0);
        let total = slopes.total();
        if total <= 0.0 {
            return SeaMesh { normals: &rings.normals, unresolved: &self.unresolved };
        }
        self.normals.resize(count, Vec3::Y);
        let filter = FootprintFilter::new(slopes, camera, rows, rings, world_scale);
        let tasks = self.normals.par_chunks_mut(VERTEX_TASK).zip(self.unresolved.par_chunks_mut(VERTEX_TASK));
        let inputs = rings.positions.par_chunks(VERTEX_TASK).zip(rings.normals.par_chunks(VERTEX_TASK));
        tasks.zip(inputs).for_each(|((n, u), (p, src))| {
            Isa::run_widest(
                #[inline(always)]
                || filter.move_to_shading(p, src, n, u, total),
            )
        });
        SeaMesh { normals: &self.normals, unresolved: &self.unresolved }
    }
}

/// A pixel averages over its footprint (a box), which weakens waves a few footprints long and
/// removes one exactly a footprint long, while a single sample per pixel catches them at full
/// strength: waves shorter than twice this many footprints count as unresolved. Fitted against
/// the 4 x 4 supersampled reference of `tests/unbounded_sea.rs` (far-band RMS, ocean: 8.9 grey
/// levels at 1 (Nyquist), 6.3 at 2, 4.9 at 3; sea: 7.7, 4.2, 2.3, with a hard cut per wave).
/// Since each wave leaves the geometry over two octaves about the cut (half of it still drawn at
/// the cut itself), and with the light entering the water, 3 gave 6.07 for the ocean and 3.5
/// gives 5.70 (sea 2.06).
const FOOTPRINT_WIDTH: f32 = 3.5;

/// Vertices per parallel task of the footprint filter.
const VERTEX_TASK: usize = 4096;

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
        Self {
            slopes,
            eye: camera.eye,
            pixel_angle: camera.pixel_angle(height),
            center: Vec2::new(camera.eye.x, camera.eye.z),
            spacing: clipmap.level_spacing(0) * world_scale,
            ring_cells: clipmap.grids()[0].cells_x as f32,
        }
    }

    /// [`Self::variance_lanes`] of one point.
    #[cfg(test)]
    pub fn variance(&self, p: Vec3, n: Vec3) -> f32 {
        self.variance_lanes(Vec3Lanes::splat(p), Vec3Lanes::splat(n)).0[0]
    }

    /// Slope variance (both axes) the pixel showing world point `p` with mean normal `n` cannot
    /// resolve, for [`LANES`] points at once: the waves shorter than twice the larger of its
    /// footprint (its width at that distance, stretched by the grazing angle) and the ring's
    /// vertex spacing there.
    #[inline(always)]
    fn variance_lanes(&self, p: Vec3Lanes, n: Vec3Lanes) -> Lanes {
        let to_eye = Vec3Lanes::splat(self.eye) - p;
        let distance = to_eye.length();
        let cos = (n.dot(to_eye) / distance.max(1e-6)).abs();
        let footprint = pixel_footprint_lanes(distance, self.pixel_angle, cos);
        // Ring k covers Chebyshev radii [N/4, N/2] s_k about the centre: s_k <= 4 r / N.
        let r = (p.x - self.center.x).abs().max((p.z - self.center.y).abs());
        let mesh = (4.0 * r / self.ring_cells).max(self.spacing);
        self.slopes.unresolved_lanes(footprint.max(mesh) * FOOTPRINT_WIDTH)
    }

    /// Moves the unresolved slopes of the vertices at `positions` from their normals `src` to
    /// the shading: `unresolved[i]` gets [`Self::variance_lanes`] and `normals[i]` the normal
    /// keeping the resolved share of the tilt, its slope (dh/dx, dh/dz) = -(n.x, n.z) / n.y
    /// scaled by the square root of that share (of `total`, the whole spectrum's variance).
    /// [`LANES`] vertices at a time.
    #[inline(always)]
    fn move_to_shading(
        &self,
        positions: &[Vec3],
        src: &[Vec3],
        normals: &mut [Vec3],
        unresolved: &mut [f32],
        total: f32,
    ) {
        let blocks = positions.chunks(LANES).zip(src.chunks(LANES));
        for (((p, s), n), u) in blocks.zip(normals.chunks_mut(LANES)).zip(unresolved.chunks_mut(LANES)) {
            // Lanes past the block repeat its first vertex and are dropped.
            let at = |i: usize| if i < p.len() { i } else { 0 };
            let normal = Vec3Lanes::from_fn(|i| s[at(i)]);
            let variance = self.variance_lanes(Vec3Lanes::from_fn(|i| p[at(i)]), normal);
            let keep = (1.0 - variance / total).max(0.0).sqrt();
            let tilted = Vec3Lanes { x: normal.x * keep, y: normal.y.abs().max(1e-3), z: normal.z * keep };
            let normal = keep.lt(1.0).select3(tilted.normalize_or(Vec3::Y), normal);
            for (i, (n, u)) in n.iter_mut().zip(u.iter_mut()).enumerate() {
                (*n, *u) = (normal.lane(i), variance.0[i]);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::preset;
    use crate::world::World;

    /// `height_at` answers on the surface as drawn: at the vertices of the rings (every level),
    /// the world's height query gives the vertex's height, for a Gerstner sea (which moves water
    /// sideways, so the query inverts that motion) and the FFT ocean (whose cascades tile).
    #[test]
    fn height_queries_agree_with_the_drawn_rings() {
        for name in ["sea", "ocean"] {
            let mut world = World::new(preset(name).unwrap()).unwrap();
            world.update(2.5).unwrap();
            let clipmap = world.water.as_ref().unwrap().surface.rings().expect("an unbounded sea");
            let mut worst = 0.0f32;
            for (i, p) in clipmap.positions.iter().enumerate().step_by(97) {
                let h = world.water_height_at(p.x, p.z).unwrap();
                worst = worst.max((h - p.y).abs());
                assert!((h - p.y).abs() < 2e-3, "{name}: vertex {i} at {p}: query {h}");
            }
            assert!(worst.is_finite());
        }
    }

    #[test]
    fn far_pixels_leave_more_slopes_unresolved_than_near_ones() {
        let world = World::new(preset("ocean").unwrap()).unwrap();
        let water = world.water.as_ref().unwrap();
        let camera = world.scene.camera;
        let clipmap = water.surface.rings().expect("an unbounded sea");
        let f = FootprintFilter::new(&water.slopes, &camera, 720, clipmap, 1.0);
        let at = |d: f32| f.variance(camera.eye + Vec3::new(0.0, -camera.eye.y, -d), Vec3::Y);
        let (near, mid, far) = (at(5.0), at(200.0), at(3000.0));
        assert!(near < mid && mid < far && far <= water.slopes.total() + 1e-6, "{near} {mid} {far}");
        assert!(water.slopes.total() > 0.0);
    }

    /// The footprint filter gives the same normals and variances whichever vector instructions
    /// run it, over a block that ends mid-batch.
    #[test]
    fn isa_builds_agree() {
        let world = World::new(preset("ocean").unwrap()).unwrap();
        let water = world.water.as_ref().unwrap();
        let camera = world.scene.camera;
        let clipmap = water.surface.rings().expect("an unbounded sea");
        let f = FootprintFilter::new(&water.slopes, &camera, 720, clipmap, 1.0);
        let total = water.slopes.total();
        // 1000 vertices from every ring (a block that ends mid-batch), near and far.
        let step = clipmap.positions.len() / 1000;
        let positions: Vec<Vec3> = clipmap.positions.iter().step_by(step).take(1000).copied().collect();
        let start: Vec<Vec3> = clipmap.normals.iter().step_by(step).take(1000).copied().collect();
        let run = |isa: Isa| {
            let (mut normals, mut unresolved) = (vec![Vec3::ZERO; positions.len()], vec![0.0f32; positions.len()]);
            isa.run(
                #[inline(always)]
                || f.move_to_shading(&positions, &start, &mut normals, &mut unresolved, total),
            );
            (normals, unresolved)
        };
        let bits = |(n, u): &(Vec<Vec3>, Vec<f32>)| {
            let normals = n.iter().flat_map(|v| v.to_array().map(f32::to_bits));
            normals.chain(u.iter().map(|u| u.to_bits())).collect::<Vec<_>>()
        };
        let (normals, unresolved) = run(Isa::Portable);
        // The filter does work here: many normals lose some of their tilt.
        let flattened = normals.iter().zip(&start).filter(|(a, b)| a != b).count();
        assert!(flattened > 100, "{flattened} of 1000 normals flattened");
        assert!(unresolved.iter().all(|&u| u > 0.0 && u <= total));
        let portable = bits(&(normals, unresolved));
        for isa in Isa::ALL.into_iter().filter(|isa| isa.is_available()) {
            assert_eq!(bits(&run(isa)), portable, "{isa:?}");
        }
    }
}
