//! One query API for every water model: [`Water`], the water of a scene asked about a time `t`.
//!
//! What an engine, a simulator or a notebook needs from the water, for any `t` (s):
//!
//! - the displaced positions and unit normals of the model's grid ([`Water::displace`]), the same
//!   numbers the renderer draws, `swell export` writes and (in the patch's own frame) `swell bake`
//!   writes as `position - rest`;
//! - foam coverage on that grid, where the model has foam ([`Water::foam`]);
//! - the height and the normal of the surface above many world points at once
//!   ([`Water::heights_at`], [`Water::normals_at`]), in parallel, agreeing with
//!   [`World::water_height_at`](super::World::water_height_at).
//!
//! ## Time
//!
//! Every query takes `t` and the answer depends only on the scene and `t`, never on what was asked
//! before. The model is brought to `t` only when it is not already there, so many queries at one
//! time cost one evaluation of the model's state (for the FFT ocean, one spectral synthesis; after
//! it a point query bilinearly samples the synthesised fields, about a microsecond).
//!
//! Stateful models (the spring mesh) step from their current state forward at their own fixed time
//! step; asked for an earlier time they rebuild from t = 0 and step forward again, so the answer
//! for a given `t` is the same whatever came before (going back costs the steps from 0 to `t`).
//! The spring mesh refuses a `t` more than its step limit past its current state
//! ([`crate::water::MAX_STEPS_PER_ADVANCE`]). [`Water`] offers no `disturb`: a disturbance would make
//! answers depend on history.
//!
//! ## Frames
//!
//! Grid positions, normals and point queries are in world coordinates: the patch's
//! [`WaterPlacement`] (turn and uniform scale about its centre) is applied, as the renderer does.
//! Rows of the grid run along +Z (`rows = cells_z + 1`), columns along +X (`cols = cells_x + 1`);
//! vertex (column i, row j) is at index `j * cols + i`.
//!
//! ## Threads
//!
//! Queries take `&mut self` (they move the cached state): share one [`Water`] between threads
//! behind a lock, or give each thread its own. The work inside one call runs on rayon's current
//! pool and the results do not depend on its size.
//!
//! ```
//! use glam::Vec2;
//! use swell::Water;
//!
//! let text = "version = 1\n[camera]\neye = [0.0, 20.0, 40.0]\ntarget = [0.0, 0.0, 0.0]\n\
//!             [water]\nmodel = 'fft'\ngrid = 32\nsize = [100.0, 100.0]\ncells = [32, 32]\n";
//! let mut water = Water::from_toml(text, "example")?;
//! let (rows, cols) = (water.rows(), water.cols());
//! let mut positions = vec![glam::Vec3::ZERO; rows * cols];
//! let mut normals = vec![glam::Vec3::ZERO; rows * cols];
//! water.displace(2.0, &mut positions, &mut normals)?;
//! // A floating object's height, asked at the same time: one synthesis served both calls.
//! let mut h = [0.0f32; 2];
//! water.heights_at(2.0, &[Vec2::new(3.0, -4.0), Vec2::new(10.0, 7.5)], &mut h)?;
//! assert!(h.iter().all(|h| h.abs() < 10.0));
//! # Ok::<(), swell::Error>(())
//! ```

use glam::{DVec2, DVec3, Vec2, Vec3};
use rayon::prelude::*;

use crate::error::{Error, Result};
use crate::math::GridSpec;
use crate::scene::{Scene, WaterExtent, WaterPlacement, WaterSpec};
use crate::water::WaveModel;

/// Horizontal step (world metres) of the central differences [`Water::normals_at`] takes of the
/// height: small against every wavelength a scene allows, large against the f32 spacing of
/// coordinates within a few kilometres of the origin (0.5 mm at 4 km).
pub const NORMAL_STEP_M: f32 = 0.02;

/// Points per parallel task of the batched point queries: large enough that scheduling costs
/// nothing against the queries, small enough that two cores share a thousand points evenly.
const POINTS_PER_TASK: usize = 256;

/// Work (node updates of a stepped model) between two calls of a [`Watch`]: about 10-50 ms of a
/// spring-mesh step on one core, so a cancel is seen well within a second at any lattice size.
pub const WORK_PER_WATCH: u64 = 1 << 20;

/// Told how far a long advance has got, as the fraction done in [0, 1); returns `false` to stop
/// it, which ends the query with [`Error::Cancelled`]. See [`Water::set_watch`].
pub type Watch = Box<dyn FnMut(f64) -> bool + Send>;

/// The water of a scene, built and ready to answer queries about any time. See the module docs.
pub struct Water {
    spec: WaterSpec,
    model: Box<dyn WaveModel>,
    grid: GridSpec,
    placement: WaterPlacement,
    /// The time the model's state is at, seconds.
    time: f64,
    /// Progress and cancel of long advances, if the caller asked for them.
    watch: Option<Watch>,
    /// Whether the water covers the plane or only its patch ([`Water::has_water_at`]).
    extent: WaterExtent,
}

impl std::fmt::Debug for Water {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Water").field("grid", &self.grid).field("placement", &self.placement).finish_non_exhaustive()
    }
}

/// Checks a time: finite seconds.
fn check_time(t: f64) -> Result<()> {
    if t.is_finite() {
        Ok(())
    } else {
        Err(Error::out_of_range("t", t, "finite seconds"))
    }
}

/// A world point (x, z) as the queries take it: single ([`Vec2`]) or double ([`DVec2`]) precision.
trait QueryPoint: Copy + Sync {
    /// The coordinates, widened to f64.
    fn xz(self) -> (f64, f64);
}

impl QueryPoint for Vec2 {
    fn xz(self) -> (f64, f64) {
        (f64::from(self.x), f64::from(self.y))
    }
}

impl QueryPoint for DVec2 {
    fn xz(self) -> (f64, f64) {
        (self.x, self.y)
    }
}

/// Farthest a query point may lie from the origin along x or z, metres: a million kilometres, 25
/// times round the Earth. Past it the models' f32 arithmetic overflows (a wave's phase `k x` at
/// 10^38 m is infinite, and f64 points past 3.4 * 10^38 m have no f32 at all), so such a point
/// is refused rather than answered with NaN. Within it every model's answer is finite.
pub const MAX_QUERY_COORDINATE_M: f64 = 1.0e9;

/// Refuses the first point with a non-finite coordinate or one past [`MAX_QUERY_COORDINATE_M`],
/// naming it `points[i]` (issue 37): a NaN buoy must be told, not answered with calm water.
fn check_points<P: QueryPoint>(points: &[P]) -> Result<()> {
    let within = |c: f64| c.abs() <= MAX_QUERY_COORDINATE_M;
    match points.iter().position(|p| !(within(p.xz().0) && within(p.xz().1))) {
        None => Ok(()),
        Some(i) => {
            let (x, z) = points[i].xz();
            let range = if x.is_finite() && z.is_finite() {
                "(x, z) within 1e9 m of the origin (MAX_QUERY_COORDINATE_M)"
            } else {
                "finite (x, z) in metres"
            };
            let (x, z) = (crate::error::Human(x), crate::error::Human(z));
            Err(Error::out_of_range(format!("points[{i}]"), format!("({x}, {z})"), range))
        }
    }
}

/// `out[i] = answer(points[i])` for every point, in parallel tasks of [`POINTS_PER_TASK`].
fn each_point<P: Sync, O: Send>(points: &[P], out: &mut [O], answer: impl Fn(&P) -> O + Sync) {
    out.par_chunks_mut(POINTS_PER_TASK).zip(points.par_chunks(POINTS_PER_TASK)).for_each(|(o, p)| {
        for (o, p) in o.iter_mut().zip(p) {
            *o = answer(p);
        }
    });
}

/// Checks that a caller's buffer `name` holds exactly `expected` elements.
fn check_len(name: &str, len: usize, expected: usize, what: &str) -> Result<()> {
    if len == expected {
        Ok(())
    } else {
        Err(Error::invalid(name, format!("holds {len} elements; must hold {expected} ({what})")))
    }
}

impl Water {
    /// Builds the water of a scene's `[water]` section, validating it, at time 0 (as
    /// [`World::new`](super::World::new) does).
    pub fn new(spec: &WaterSpec) -> Result<Self> {
        spec.validate()?;
        let mut model = spec.model.build()?;
        model.advance(0.0)?;
        Ok(Self {
            spec: spec.clone(),
            model,
            grid: spec.surface.grid()?,
            placement: spec.surface.placement()?,
            time: 0.0,
            watch: None,
            extent: spec.surface.extent.unwrap_or_else(|| WaterExtent::default_for(&spec.model, false)),
        })
    }

    /// Builds the water of `scene`; an error names `water` if the scene has none.
    pub fn from_scene(scene: &Scene) -> Result<Self> {
        match &scene.water {
            Some(spec) => Self::new(spec),
            None => Err(Error::invalid("water", "the scene has no [water] section: there is no water to query")),
        }
    }

    /// Parses a scene's TOML text (see `docs/scene-format.md`) and builds its water; `source` (a
    /// path or a name) is named in parse errors. The errors are the CLI's (`swell render` prints
    /// the same text after `error: `).
    pub fn from_toml(text: &str, source: &str) -> Result<Self> {
        Self::from_scene(&Scene::from_toml(text, source)?)
    }

    /// The `[water]` section this water was built from.
    pub fn spec(&self) -> &WaterSpec {
        &self.spec
    }

    /// The model's grid, in the patch's own frame (before [`Water::placement`]).
    pub fn grid(&self) -> &GridSpec {
        &self.grid
    }

    /// Where the patch sits in the world.
    pub fn placement(&self) -> &WaterPlacement {
        &self.placement
    }

    /// Rows of the grid (vertices along +Z, `cells_z + 1`).
    pub fn rows(&self) -> usize {
        self.grid.verts_z()
    }

    /// Columns of the grid (vertices along +X, `cells_x + 1`).
    pub fn cols(&self) -> usize {
        self.grid.verts_x()
    }

    /// Vertices of the grid, `rows * cols`: the length of the buffers [`Water::displace`] and
    /// [`Water::foam`] fill.
    pub fn vertex_count(&self) -> usize {
        self.grid.vertex_count()
    }

    /// Whether there is water above world (x, z) (m): everywhere for unbounded water, inside the
    /// patch's rectangle (its placement applied, edges included) for a patch. The extent is
    /// `[water] extent`, else the model's default without terrain: the pool, the spring lattice
    /// and the river are patches, the FFT ocean and the closed forms cover the plane (a lake's
    /// terrain is not consulted: give `extent = "patch"` to bound it).
    pub fn has_water_at(&self, p: Vec2) -> bool {
        covers(self.extent, &self.grid, || self.placement.to_local_xz(p).as_dvec2())
    }

    /// The time (s) the model's state is at: the `t` of the last query (0 after building).
    pub fn time(&self) -> f64 {
        self.time
    }

    /// Brings the model to time `t` (s) unless it is already there. Every query calls it; call it
    /// yourself to pay for the state's evaluation at a moment of your choosing.
    ///
    /// A stepped model (the spring mesh) asked far ahead may take minutes: with a [`Watch`] set
    /// ([`Water::set_watch`]) it is told the progress about every [`WORK_PER_WATCH`] node updates
    /// and may stop the call, which then fails with [`Error::Cancelled`]; asking again continues
    /// from where it stopped, and the answer is the same as without a stop.
    pub fn advance_to(&mut self, t: f64) -> Result<()> {
        check_time(t)?;
        if t == self.time {
            return Ok(());
        }
        // On failure the state is unknown: rebuild it on the next query rather than trust it.
        self.time = f64::NAN;
        let Some(watch) = self.watch.as_mut() else {
            self.model.advance(t)?;
            self.time = t;
            return Ok(());
        };
        let mut total = None;
        loop {
            let left = self.model.advance_partly(t, WORK_PER_WATCH)?;
            if left == 0 {
                break;
            }
            // Measured from the end of the first part: the fraction starts at 0 and only grows.
            let first = *total.get_or_insert(left) as f64;
            if !watch((1.0 - left as f64 / first).clamp(0.0, 1.0)) {
                return Err(Error::Cancelled(format!(
                    "stopped at the caller's request on the way to t = {}, {left} steps short; asking again continues from there",
                    crate::error::Human(t)
                )));
            }
        }
        self.time = t;
        Ok(())
    }

    /// Sets (or, with `None`, removes) the [`Watch`] told the progress of long advances, which
    /// may stop them. Closed-form and spectral models never call it: they reach any time in one
    /// evaluation.
    pub fn set_watch(&mut self, watch: Option<Watch>) {
        self.watch = watch;
    }

    /// Writes the displaced world position (m) and unit normal of every grid vertex at time `t`
    /// (s), row-major (see the module docs). Both buffers must hold [`Water::vertex_count`]
    /// elements. The numbers are those [`World::update`](super::World::update) gives its mesh.
    pub fn displace(&mut self, t: f64, positions: &mut [Vec3], normals: &mut [Vec3]) -> Result<()> {
        let n = self.vertex_count();
        let what = format!("the grid's {} rows x {} columns of vertices", self.rows(), self.cols());
        check_len("positions", positions.len(), n, &what)?;
        check_len("normals", normals.len(), n, &what)?;
        self.advance_to(t)?;
        self.model.evaluate(&self.grid, t, positions, normals);
        self.placement.apply_to(positions, normals);
        let finite = |v: &Vec3| v.is_finite();
        if positions.par_iter().all(finite) && normals.par_iter().all(finite) {
            Ok(())
        } else {
            Err(Error::Unstable(format!(
                "the water model produced non-finite positions or normals at time {t} s; \
                 reduce the wave amplitudes, wavelengths or speeds in [water]"
            )))
        }
    }

    /// Writes foam coverage in [0, 1] of every grid vertex at time `t` (s) into `out` (length
    /// [`Water::vertex_count`]) and returns true, or returns false and leaves `out` untouched if
    /// the model has no foam (only the FFT ocean with `foam = true` has).
    pub fn foam(&mut self, t: f64, out: &mut [f32]) -> Result<bool> {
        let what = format!("the grid's {} rows x {} columns of vertices", self.rows(), self.cols());
        check_len("foam", out.len(), self.vertex_count(), &what)?;
        self.advance_to(t)?;
        Ok(self.model.foam(&self.grid, out))
    }

    /// Height (m above the water at rest, y = 0) of the surface above world (x, z) at time `t`
    /// (s); NaN where there is no water ([`Water::has_water_at`]). See [`Water::heights_at`].
    pub fn height_at(&mut self, x: f32, z: f32, t: f64) -> Result<f32> {
        let mut h = [0.0];
        self.heights_at(t, &[Vec2::new(x, z)], &mut h)?;
        Ok(h[0])
    }

    /// Heights (m) of the surface above the world points `points` = (x, z) (m) at time `t` (s),
    /// into `out` (same length), in parallel; each point's answer is the one
    /// [`World::water_height_at`](super::World::water_height_at) gives where there is water, and
    /// NaN where there is none ([`Water::has_water_at`]: off a finite patch), so that an object
    /// off the pool is told, not floated on the model's formula extended. A point with a
    /// non-finite coordinate is refused (naming the first), `out` left as it was. Accuracy is each
    /// model's [`WaveModel::height_at`]'s.
    pub fn heights_at(&mut self, t: f64, points: &[Vec2], out: &mut [f32]) -> Result<()> {
        check_len("heights", out.len(), points.len(), "one per point")?;
        check_points(points)?;
        self.advance_to(t)?;
        let (model, placement, extent, grid) = (self.model.as_ref(), self.placement, self.extent, &self.grid);
        each_point(points, out, |&p| {
            if covers(extent, grid, || placement.to_local_xz(p).as_dvec2()) {
                world_height(model, &placement, p, t)
            } else {
                f32::NAN
            }
        });
        Ok(())
    }

    /// Unit normals of the surface above the world points `points` = (x, z) (m) at time `t` (s),
    /// into `out` (same length), in parallel: central differences of the height over
    /// [`NORMAL_STEP_M`], so five height queries per point. They agree with the grid's analytic
    /// normals to the differences' accuracy (the slope's change over 2 cm). NaN vectors where
    /// there is no water, as [`Water::heights_at`].
    pub fn normals_at(&mut self, t: f64, points: &[Vec2], out: &mut [Vec3]) -> Result<()> {
        check_len("normals", out.len(), points.len(), "one per point")?;
        check_points(points)?;
        self.advance_to(t)?;
        let (model, placement, extent, grid) = (self.model.as_ref(), self.placement, self.extent, &self.grid);
        each_point(points, out, |&p| {
            if covers(extent, grid, || placement.to_local_xz(p).as_dvec2()) {
                world_normal(model, &placement, p, t)
            } else {
                Vec3::NAN
            }
        });
        Ok(())
    }

    /// [`Water::has_water_at`] of a world point given in double precision.
    pub fn has_water_at_f64(&self, p: DVec2) -> bool {
        covers(self.extent, &self.grid, || self.placement.to_local_xz_f64(p))
    }

    /// [`Water::heights_at`] of world points given in double precision, for engines whose
    /// coordinates run far from the origin (at 10^6 m an f32 coordinate moves in 6 cm steps).
    /// The point is carried into the patch's frame in f64 and, where the model repeats in space
    /// (the FFT ocean, [`WaveModel::spatial_period`]), whole periods are taken off in f64 before
    /// the model, which computes in f32, is asked: such water answers at 10^6 m as precisely as
    /// near the origin. Models that do not repeat (Gerstner and sine sums, noise) are asked at
    /// the local point narrowed to f32, so far out their answer has f32's spacing. NaN where
    /// there is no water, non-finite coordinates refused, as [`Water::heights_at`].
    pub fn heights_at_f64(&mut self, t: f64, points: &[DVec2], out: &mut [f64]) -> Result<()> {
        check_len("heights", out.len(), points.len(), "one per point")?;
        check_points(points)?;
        self.advance_to(t)?;
        let (model, placement, extent, grid) = (self.model.as_ref(), self.placement, self.extent, &self.grid);
        each_point(points, out, |&p| {
            if covers(extent, grid, || placement.to_local_xz_f64(p)) {
                let at = PreciseLocal::new(model, &placement, p);
                f64::from(at.world_height(model, &placement, DVec2::ZERO, t))
            } else {
                f64::NAN
            }
        });
        Ok(())
    }

    /// [`Water::normals_at`] of world points given in double precision, with the precision of
    /// [`Water::heights_at_f64`]: the central differences are taken about the point with its
    /// whole periods off, so they keep their 2 cm step at any distance.
    pub fn normals_at_f64(&mut self, t: f64, points: &[DVec2], out: &mut [DVec3]) -> Result<()> {
        check_len("normals", out.len(), points.len(), "one per point")?;
        check_points(points)?;
        self.advance_to(t)?;
        let (model, placement, extent, grid) = (self.model.as_ref(), self.placement, self.extent, &self.grid);
        each_point(points, out, |&p| {
            if !covers(extent, grid, || placement.to_local_xz_f64(p)) {
                return DVec3::NAN;
            }
            let at = PreciseLocal::new(model, &placement, p);
            let e = f64::from(NORMAL_STEP_M);
            let h = |dx: f64, dz: f64| f64::from(at.world_height(model, &placement, DVec2::new(dx, dz), t));
            let slope_x = (h(e, 0.0) - h(-e, 0.0)) / (2.0 * e);
            let slope_z = (h(0.0, e) - h(0.0, -e)) / (2.0 * e);
            DVec3::new(-slope_x, 1.0, -slope_z).normalize()
        });
        Ok(())
    }
}

/// [`Water::has_water_at`] from its parts, which the parallel queries of both precisions share:
/// everywhere for unbounded water, else whether the local point `local` gives (computed only for
/// a patch) lies in the patch's rectangle, edges included. An f32 local point widened to f64
/// compares exactly as it would in f32.
pub(super) fn covers(extent: WaterExtent, grid: &GridSpec, local: impl FnOnce() -> DVec2) -> bool {
    match extent {
        WaterExtent::Unbounded => true,
        WaterExtent::Patch => {
            let l = local();
            let (lo, hi) = (grid.origin.as_dvec2(), (grid.origin + grid.size).as_dvec2());
            l.cmpge(lo).all() && l.cmple(hi).all()
        }
    }
}

/// A world point given in f64, about which the `_f64` queries ask the model: the whole spatial
/// periods of its local point, taken off in f64 so that what is narrowed to f32 is small.
struct PreciseLocal {
    /// The world point, m.
    world: DVec2,
    /// Whole periods (m, local frame) to take off: zero for a model that does not repeat.
    shift: DVec2,
}

impl PreciseLocal {
    fn new(model: &dyn WaveModel, placement: &WaterPlacement, world: DVec2) -> Self {
        let shift = match model.spatial_period() {
            Some(period) => {
                let period = f64::from(period);
                (placement.to_local_xz_f64(world) / period).floor() * period
            }
            None => DVec2::ZERO,
        };
        Self { world, shift }
    }

    /// The world height (m) above the world point moved by `offset` (m): one shift for the
    /// point and its neighbours, so differences across a period's seam stay differences.
    fn world_height(&self, model: &dyn WaveModel, placement: &WaterPlacement, offset: DVec2, t: f64) -> f32 {
        let l = (placement.to_local_xz_f64(self.world + offset) - self.shift).as_vec2();
        placement.to_world_height(model.height_at(l.x, l.y, t))
    }
}

/// The world height above world (x, z): the model asked at the local point that lands there.
fn world_height(model: &dyn WaveModel, placement: &WaterPlacement, p: Vec2, t: f64) -> f32 {
    let l = placement.to_local_xz(p);
    placement.to_world_height(model.height_at(l.x, l.y, t))
}

/// The unit normal above world (x, z) by central differences of [`world_height`].
fn world_normal(model: &dyn WaveModel, placement: &WaterPlacement, p: Vec2, t: f64) -> Vec3 {
    let e = NORMAL_STEP_M;
    let h = |dx: f32, dz: f32| world_height(model, placement, p + Vec2::new(dx, dz), t);
    let slope_x = (h(e, 0.0) - h(-e, 0.0)) / (2.0 * e);
    let slope_z = (h(0.0, e) - h(0.0, -e)) / (2.0 * e);
    Vec3::new(-slope_x, 1.0, -slope_z).normalize()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::preset;
    use crate::world::World;

    /// A small version of preset `name`: `cells` per side (if it has water).
    fn small(name: &str, cells: u32) -> Scene {
        let mut s = preset(name).unwrap();
        if let Some(w) = &mut s.water {
            w.surface.cells = [cells, cells];
        }
        s
    }

    fn grid_of(w: &mut Water, t: f64) -> (Vec<Vec3>, Vec<Vec3>) {
        let n = w.vertex_count();
        let (mut p, mut q) = (vec![Vec3::ZERO; n], vec![Vec3::ZERO; n]);
        w.displace(t, &mut p, &mut q).unwrap();
        (p, q)
    }

    #[test]
    fn the_grid_and_heights_are_the_world_s_for_every_preset_with_water() {
        for p in crate::scene::PRESETS {
            let scene = small(p.name, 24);
            if scene.water.is_none() {
                continue;
            }
            let mut water = Water::from_scene(&scene).unwrap();
            let mut world = World::new(scene).unwrap();
            for t in [0.0, 1.25, 0.5] {
                world.update(t).unwrap();
                let (pos, nrm) = grid_of(&mut water, t);
                let mesh = world.patch_mesh().unwrap().unwrap();
                assert_eq!(pos, mesh.positions, "{} t = {t}", p.name);
                assert_eq!(nrm, mesh.normals, "{} t = {t}", p.name);
                let pts = [Vec2::new(1.5, -2.0), Vec2::new(-7.0, 3.25)];
                let mut h = [0.0; 2];
                water.heights_at(t, &pts, &mut h).unwrap();
                for (k, q) in pts.iter().enumerate() {
                    if water.has_water_at(*q) {
                        assert_eq!(Some(h[k]), world.water_height_at(q.x, q.y), "{} t = {t}", p.name);
                    } else {
                        assert!(h[k].is_nan(), "{} t = {t}: off the patch, {}", p.name, h[k]);
                    }
                }
            }
        }
    }

    #[test]
    fn answers_do_not_depend_on_the_order_or_history_of_calls() {
        for name in ["ocean", "springs", "sea", "river"] {
            let scene = small(name, 16);
            let pts: Vec<Vec2> =
                (0..50).map(|k| Vec2::new(k as f32 * 0.7 - 17.0, (k as f32 * 1.3).sin() * 9.0)).collect();
            let ask = |w: &mut Water, t: f64| {
                let mut h = vec![0.0; pts.len()];
                w.heights_at(t, &pts, &mut h).unwrap();
                let (p, n) = grid_of(w, t);
                let mut foam = vec![0.0; w.vertex_count()];
                let has = w.foam(t, &mut foam).unwrap();
                // Bits, so that the NaN of points off a finite patch compare equal.
                (h.iter().map(|h| h.to_bits()).collect::<Vec<_>>(), p, n, has.then_some(foam))
            };
            let mut fresh = Water::from_scene(&scene).unwrap();
            let expected = ask(&mut fresh, 2.0);
            let mut used = Water::from_scene(&scene).unwrap();
            for t in [3.0, 0.5, 2.0, 7.25, 2.0, 1.0] {
                ask(&mut used, t);
            }
            assert_eq!(ask(&mut used, 2.0), expected, "{name}");
            assert_eq!(used.time(), 2.0);
        }
    }

    /// A long spring-mesh advance tells its progress, stops when the watch says so, and asked
    /// again continues to the same answer as an advance that was never stopped (issue 37).
    #[test]
    fn a_watch_sees_progress_and_can_cancel_without_changing_the_answer() {
        use std::sync::{Arc, Mutex};
        // 1000 steps of 0.4 s on a 129² lattice: about 16 parts of WORK_PER_WATCH.
        let scene = small("springs", 16);
        let t = 400.0;
        let mut plain = Water::from_scene(&scene).unwrap();
        let expected = grid_of(&mut plain, t);
        let mut watched = Water::from_scene(&scene).unwrap();
        let seen = Arc::new(Mutex::new(Vec::new()));
        let log = Arc::clone(&seen);
        watched.set_watch(Some(Box::new(move |f| {
            let mut log = log.lock().unwrap();
            log.push(f);
            log.len() < 3
        })));
        let n = watched.vertex_count();
        let (mut p, mut q) = (vec![Vec3::ZERO; n], vec![Vec3::ZERO; n]);
        let e = watched.displace(t, &mut p, &mut q).unwrap_err();
        assert!(matches!(e, Error::Cancelled(_)), "{e}");
        assert!(e.to_string().starts_with("cancelled: stopped at the caller's request on the way to t = 400"), "{e}");
        let fractions = seen.lock().unwrap().clone();
        assert_eq!(fractions.len(), 3);
        assert_eq!(fractions[0], 0.0);
        assert!(fractions.windows(2).all(|w| w[1] > w[0] && w[1] < 1.0), "{fractions:?}");
        // Asked again, with the watch always saying go on: the stopped advance finishes.
        watched.set_watch(Some(Box::new(|_| true)));
        assert_eq!(grid_of(&mut watched, t), expected);
        watched.set_watch(None);
        assert_eq!(grid_of(&mut watched, t), expected);
        // Closed-form models never call the watch.
        let mut sea = Water::from_scene(&small("sea", 8)).unwrap();
        sea.set_watch(Some(Box::new(|_| panic!("a closed-form model has nothing to wait for"))));
        grid_of(&mut sea, 1.0e5);
    }

    /// Off a finite patch there is no water: NaN heights and normals, told by `has_water_at`
    /// (issue 37), where the models' formulas would answer calm or extended water.
    #[test]
    fn points_off_finite_water_answer_nan() {
        for (name, finite) in [("pool", true), ("springs", true), ("river", true), ("ocean", false), ("sea", false)] {
            let mut water = Water::from_scene(&small(name, 8)).unwrap();
            let g = *water.grid();
            let inside = water.placement().to_world(glam::Vec3::new(
                g.origin.x + 0.5 * g.size.x,
                0.0,
                g.origin.y + 0.5 * g.size.y,
            ));
            let (inside, far) = (Vec2::new(inside.x, inside.z), Vec2::new(1.0e5, -3.0e4));
            assert!(water.has_water_at(inside), "{name}");
            assert_eq!(water.has_water_at(far), !finite, "{name}");
            let (mut h, mut n) = ([0.0; 2], [Vec3::ZERO; 2]);
            water.heights_at(1.0, &[inside, far], &mut h).unwrap();
            water.normals_at(1.0, &[inside, far], &mut n).unwrap();
            assert!(h[0].is_finite() && n[0].is_finite(), "{name}");
            assert_eq!(h[1].is_nan(), finite, "{name}: {}", h[1]);
            assert_eq!(n[1].is_nan(), finite, "{name}: {}", n[1]);
        }
        // A closed-form model bounded by `extent = "patch"`.
        let mut scene = small("sea", 8);
        scene.water.as_mut().unwrap().surface.extent = Some(WaterExtent::Patch);
        let water = Water::from_scene(&scene).unwrap();
        assert!(!water.has_water_at(Vec2::new(1.0e5, 0.0)));
    }

    /// Issue 37: an engine at 10^6 m asks in f64. On periodic water (the FFT ocean) the answer
    /// there is the answer a whole number of periods nearer, to f32's precision near the origin;
    /// a placed patch's coverage is decided in f64; non-finite points are refused.
    #[test]
    fn double_precision_points_keep_their_precision_far_out() {
        let text = "[water]\nmodel = 'fft'\ngrid = 32\npatch_size = 64.0\ncascades = 1\nchoppiness = 1.0\n\
                    size = [64.0, 64.0]\ncells = [16, 16]\n";
        let mut water = Water::from_toml(text, "test").unwrap();
        let near = [DVec2::new(3.3, -7.1), DVec2::new(10.25, 40.0), DVec2::new(-0.01, 63.99)];
        // 15,625 periods of 64 m: 10^6 m out along x, 4.096 * 10^6 m along z.
        let far: Vec<DVec2> = near.iter().map(|p| *p + DVec2::new(1.0e6, 4.096e6)).collect();
        let (mut h_near, mut h_far) = ([0.0; 3], [0.0; 3]);
        water.heights_at_f64(2.5, &near, &mut h_near).unwrap();
        water.heights_at_f64(2.5, &far, &mut h_far).unwrap();
        let mut h32 = [0.0f32; 3];
        water.heights_at(2.5, &near.map(|p| p.as_vec2()), &mut h32).unwrap();
        for k in 0..3 {
            assert!(h_near[k].abs() > 1e-3, "a calm point proves nothing: {}", h_near[k]);
            assert!((h_far[k] - h_near[k]).abs() < 1e-4, "point {k}: far {} near {}", h_far[k], h_near[k]);
            assert!((h_near[k] - f64::from(h32[k])).abs() < 1e-4, "point {k}: f64 {} f32 {}", h_near[k], h32[k]);
        }
        let (mut n_near, mut n_far) = ([DVec3::ZERO; 3], [DVec3::ZERO; 3]);
        water.normals_at_f64(2.5, &near, &mut n_near).unwrap();
        water.normals_at_f64(2.5, &far, &mut n_far).unwrap();
        for k in 0..3 {
            assert!((n_far[k] - n_near[k]).length() < 1e-3, "point {k}: far {} near {}", n_far[k], n_near[k]);
            assert!((n_near[k].length() - 1.0).abs() < 1e-9);
        }
        let e = water.heights_at_f64(0.0, &[DVec2::ZERO, DVec2::new(f64::NAN, 1.0)], &mut h_near[..2]).unwrap_err();
        assert!(e.to_string().starts_with("points[1] = (NaN, 1) is outside finite"), "{e}");
        // Finite but past the models' arithmetic: refused, not answered with NaN.
        let e = water.heights_at_f64(0.0, &[DVec2::new(1.0, 2.0e196)], &mut h_near[..1]).unwrap_err();
        assert!(e.to_string().contains("within 1e9 m of the origin (MAX_QUERY_COORDINATE_M)"), "{e}");
        let mut h32 = [0.0f32];
        let e = water.heights_at(0.0, &[Vec2::new(-1.5e9, 0.0)], &mut h32).unwrap_err();
        assert_eq!(
            e.to_string(),
            "points[0] = (-1.5e9, 0) is outside (x, z) within 1e9 m of the origin (MAX_QUERY_COORDINATE_M)"
        );
        // A placed patch 10^6 m out: in and just out of it, 1 cm apart, told apart.
        let mut scene = small("pool", 8);
        let s = &mut scene.water.as_mut().unwrap().surface;
        s.center = Vec2::new(1.0e6, 0.0);
        let (half, center) = (0.5 * f64::from(s.size.x), f64::from(s.center.x));
        let mut pool = Water::from_scene(&scene).unwrap();
        let (inside, outside) = (DVec2::new(center + half - 0.005, 0.0), DVec2::new(center + half + 0.005, 0.0));
        assert!(pool.has_water_at_f64(inside) && !pool.has_water_at_f64(outside));
        let mut h = [0.0; 2];
        pool.heights_at_f64(1.0, &[inside, outside], &mut h).unwrap();
        assert!(h[0].is_finite() && h[1].is_nan(), "{h:?}");
    }

    #[test]
    fn a_placed_patch_answers_in_world_coordinates() {
        let mut scene = small("sea", 16);
        let s = &mut scene.water.as_mut().unwrap().surface;
        (s.yaw_deg, s.uniform_scale, s.center) = (30.0, 1.5, Vec2::new(4.0, -3.0));
        let mut water = Water::from_scene(&scene).unwrap();
        let mut world = World::new(scene).unwrap();
        world.update(0.75).unwrap();
        let (pos, _) = grid_of(&mut water, 0.75);
        assert_eq!(pos, world.patch_mesh().unwrap().unwrap().positions);
        let pts: Vec<Vec2> = pos.iter().step_by(37).map(|p| Vec2::new(p.x, p.z)).collect();
        let mut h = vec![0.0; pts.len()];
        water.heights_at(0.75, &pts, &mut h).unwrap();
        for (k, p) in pos.iter().step_by(37).enumerate() {
            assert!((h[k] - p.y).abs() < 1e-3, "vertex {k}: query {} vs mesh {}", h[k], p.y);
        }
    }

    #[test]
    fn point_normals_agree_with_the_grid_s_analytic_normals() {
        let mut water = Water::from_scene(&small("sea", 64)).unwrap();
        let (pos, nrm) = grid_of(&mut water, 1.0);
        let idx: Vec<usize> = (0..pos.len()).step_by(97).collect();
        let pts: Vec<Vec2> = idx.iter().map(|&k| Vec2::new(pos[k].x, pos[k].z)).collect();
        let mut n = vec![Vec3::ZERO; pts.len()];
        water.normals_at(1.0, &pts, &mut n).unwrap();
        for (q, &k) in idx.iter().enumerate() {
            assert!((n[q].length() - 1.0).abs() < 1e-5);
            assert!(n[q].dot(nrm[k]) > 0.999, "vertex {k}: {} vs {}", n[q], nrm[k]);
        }
    }

    #[test]
    fn foam_is_reported_only_by_models_that_have_it() {
        let mut ocean = Water::from_scene(&small("ocean", 16)).unwrap();
        let mut out = vec![-1.0; ocean.vertex_count()];
        assert!(ocean.foam(1.0, &mut out).unwrap());
        assert!(out.iter().all(|f| (0.0..=1.0).contains(f)));
        let mut sea = Water::from_scene(&small("sea", 16)).unwrap();
        let mut out = vec![-1.0; sea.vertex_count()];
        assert!(!sea.foam(1.0, &mut out).unwrap());
        assert!(out.iter().all(|f| *f == -1.0));
    }

    #[test]
    fn bad_input_is_an_error_naming_the_parameter() {
        let mut w = Water::from_scene(&small("sea", 4)).unwrap();
        let (mut p, mut n) = (vec![Vec3::ZERO; 24], vec![Vec3::ZERO; 25]);
        let e = w.displace(0.0, &mut p, &mut n).unwrap_err().to_string();
        assert_eq!(e, "positions: holds 24 elements; must hold 25 (the grid's 5 rows x 5 columns of vertices)");
        let e = w.heights_at(f64::NAN, &[Vec2::ZERO], &mut [0.0]).unwrap_err().to_string();
        assert_eq!(e, "t = NaN is outside finite seconds");
        let e = w.heights_at(0.0, &[Vec2::ZERO], &mut []).unwrap_err().to_string();
        assert_eq!(e, "heights: holds 0 elements; must hold 1 (one per point)");
        // A NaN or infinite point is refused, naming the first, and nothing is written.
        let mut h = [7.0; 3];
        let bad = [Vec2::ZERO, Vec2::new(1.0, f32::NAN), Vec2::new(f32::INFINITY, 0.0)];
        let e = w.heights_at(0.0, &bad, &mut h).unwrap_err().to_string();
        assert_eq!(e, "points[1] = (1, NaN) is outside finite (x, z) in metres");
        assert_eq!(h, [7.0; 3]);
        let e = w.normals_at(0.0, &bad[2..], &mut [Vec3::ZERO]).unwrap_err().to_string();
        assert_eq!(e, "points[0] = (inf, 0) is outside finite (x, z) in metres");
        assert!(w.height_at(f32::NEG_INFINITY, 0.0, 0.0).is_err());
        let e = w.foam(f64::INFINITY, &mut [0.0; 25]).unwrap_err().to_string();
        assert!(e.starts_with("t = inf"), "{e}");
        let no_water = "version = 1\n[camera]\neye = [0.0, 5.0, 10.0]\ntarget = [0.0, 0.0, 0.0]\n";
        let e = Water::from_toml(no_water, "t").unwrap_err().to_string();
        assert!(e.starts_with("water: the scene has no [water] section"), "{e}");
        let e = Water::from_toml("[water]\nmodel = 'sines'\ncells = [0, 4]\n", "t").unwrap_err();
        assert_eq!(e.to_string(), "t: water.cells[0] = 0 is outside [1, 4096]");
        // Only [water] is required.
        let w = Water::from_toml("[water]\nmodel = 'sines'\ncells = [8, 4]\n", "t").unwrap();
        assert_eq!((w.rows(), w.cols()), (5, 9));
    }
}
