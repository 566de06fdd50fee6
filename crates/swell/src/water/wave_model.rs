//! The contract every water surface model fulfils, and the machinery shared by analytic models.

use glam::{Mat2, Vec2, Vec3};
use rayon::prelude::*;

use crate::error::Result;
use crate::math::GridSpec;

/// A water surface model: displaced positions and normals of a grid at time `t`.
///
/// Contract:
/// - positions are world metres with +Y up; the surface at rest is y = 0;
/// - normals are unit length with a positive y component wherever the surface does not fold over;
/// - `evaluate` writes every vertex of `grid` (row-major, see [`GridSpec`]) and allocates nothing;
/// - output depends only on the model, `grid` and `t`: it is bit-identical on any thread count.
pub trait WaveModel: Send + Sync {
    /// Writes the displaced position and unit normal of each vertex of `grid` at time `t` (s).
    ///
    /// `positions` and `normals` must both have `grid.vertex_count()` elements.
    fn evaluate(&self, grid: &GridSpec, t: f64, positions: &mut [Vec3], normals: &mut [Vec3]);

    /// Height (m) of the displaced surface above the world point (x, z) at time `t` (s).
    ///
    /// Models that move water horizontally invert that motion; each model documents its accuracy.
    fn height_at(&self, x: f32, z: f32, t: f64) -> f32;

    /// Velocity (m/s, the model's frame) of the water at the surface above the point (x, z) at
    /// time `t` (s): what carries and drags a floating body ([`crate::body`]).
    ///
    /// Wave models built of discrete waves give each wave's linear orbital velocity at the
    /// surface (`a ω` along the wave at the crest, `∂η/∂t` vertically); the river gives its flow;
    /// other closed-form models the time derivative of their displacement; the default, for models
    /// that do not say (the FFT ocean, the spring mesh), is still water, `Vec3::ZERO`, so a body
    /// on them feels their heights and slopes but no current.
    fn surface_velocity(&self, _x: f32, _z: f32, _t: f64) -> Vec3 {
        Vec3::ZERO
    }

    /// [`WaveModel::height_at`] given `rest`, a guess of the rest point whose displaced position
    /// lands on (x, z) (a floating body's vertex keeps its answer of the step before), which a
    /// model that inverts its horizontal motion starts from and leaves at the point it found:
    /// the same height to the inversion's tolerance, in fewer iterations. The default ignores the
    /// guess and leaves it alone.
    fn height_near(&self, x: f32, z: f32, t: f64, _rest: &mut Vec2) -> f32 {
        self.height_at(x, z, t)
    }

    /// Moves internal state to time `t` (s) before [`WaveModel::evaluate`] is called for `t`.
    ///
    /// Stateless (closed-form) models ignore it, which is the default. Time-stepped models (spring
    /// mesh) step at their own fixed time step up to `t`; spectral models (FFT ocean) synthesise their
    /// fields for `t`. An error means the state became unusable (e.g. a blow-up) and nothing was drawn.
    fn advance(&mut self, _t: f64) -> Result<()> {
        Ok(())
    }

    /// [`WaveModel::advance`] in parts, for callers that must report progress or stop on request
    /// ([`crate::Water::set_watch`]): moves towards `t` (s) doing about `work` units of work (one
    /// unit is one node of one time step) and at least one step, and returns the steps still to go,
    /// 0 once the state is at `t`. Calling it until it returns 0 leaves exactly the state one
    /// `advance(t)` leaves, so an interrupted advance costs nothing when it is asked again.
    ///
    /// Models that do not step reach `t` at once: the default calls `advance` and returns 0.
    fn advance_partly(&mut self, t: f64, _work: u64) -> Result<u64> {
        self.advance(t)?;
        Ok(0)
    }

    /// Writes foam coverage in [0, 1] for each vertex of `grid` at the time of the last
    /// [`WaveModel::advance`] and returns true, or returns false (the default) if the model has no
    /// foam, leaving `out` untouched.
    fn foam(&self, _grid: &GridSpec, _out: &mut [f32]) -> bool {
        false
    }

    /// Side (m) of the square over which the surface repeats exactly along X and along Z, if it
    /// does: maps baked over a whole number of periods tile seamlessly. `None` (the default) for a
    /// surface that does not repeat in space (Gerstner and sine sums, whose wave vectors share no
    /// common period, noise, the finite pool, springs and river).
    fn spatial_period(&self) -> Option<f32> {
        None
    }

    /// Unit direction (x, z) in the model's frame that the wind blowing the waves travels towards,
    /// for models driven by one: foam is drawn out into streaks along it
    /// ([`crate::scene::WaterMaterial::foam_streak`]). `None` (the default) for the rest.
    fn wind_direction(&self) -> Option<glam::Vec2> {
        None
    }

    /// Speed of that wind 10 m above the water, m/s, for models driven by one (the FFT ocean's
    /// `wind_speed`): it sets the micro-roughness of the sun glitter
    /// ([`crate::scene::GlitterModel::CoxMunk`]). `None` (the default) for the rest.
    fn wind_speed(&self) -> Option<f32> {
        None
    }

    /// Appends the model's slope spectrum to `out` as `(wavenumber rad/m, slope variance)` pairs,
    /// slope variance summed over both horizontal axes (`(A k)^2 / 2` for a wave of amplitude A):
    /// what the renderer filters statistically where the waves are shorter than a pixel or a
    /// mesh cell ([`crate::water::UnresolvedSlopes`], Bruneton et al. 2010). Required, with no
    /// default, so that a new model says what its slopes are: one made of discrete waves lists
    /// them ([`crate::water::push_wave_slopes`]); one with no spectrum to filter (noise, a
    /// simulated lattice, a finite pool) appends nothing and says why, and is then shaded as
    /// sampled.
    fn slope_components(&self, out: &mut Vec<(f32, f32)>);

    /// Disturbs the surface at world (x, z) (m): a dent `amount` metres deep at the centre easing
    /// to 0 at `radius` m (the viewer's click on the water). Returns true if the model has state to
    /// disturb; closed-form models cannot be disturbed and return false (the default). The
    /// disturbance lasts until the model is rebuilt or stepped back in time.
    fn disturb(&mut self, _x: f32, _z: f32, _amount: f32, _radius: f32) -> Result<bool> {
        Ok(false)
    }
}

/// Displacement and normal of the surface point that rests at a given (x, z).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfacePoint {
    /// World displacement (m) from the rest position (x, 0, z).
    pub offset: Vec3,
    /// Unit surface normal at the displaced point.
    pub normal: Vec3,
}

/// A model with a closed form per point: the displaced surface is `rest + offset(rest, t)`.
pub trait PointWave: Send + Sync {
    /// Per-frame constants (e.g. each wave's phase at `t`), computed once per frame in `f64` so that
    /// phases stay exact for large `t`, then used by every vertex. Must not allocate.
    type Frame: Send + Sync;

    /// Computes the per-frame constants for time `t` (s).
    fn frame(&self, t: f64) -> Self::Frame;

    /// Displacement and normal of the point resting at `rest` = (x, z) in metres.
    fn sample(&self, frame: &Self::Frame, rest: Vec2) -> SurfacePoint;
}

/// Evaluates a [`PointWave`] over `grid`, rows in parallel.
///
/// Each vertex depends only on its rest position, so the split over threads cannot change the output.
pub fn evaluate_pointwise<W: PointWave>(
    wave: &W,
    grid: &GridSpec,
    t: f64,
    positions: &mut [Vec3],
    normals: &mut [Vec3],
) {
    let n = grid.vertex_count();
    assert!(positions.len() == n && normals.len() == n, "buffers must hold grid.vertex_count() = {n} vertices");
    let frame = wave.frame(t);
    let row = grid.verts_x();
    positions.par_chunks_mut(row).zip(normals.par_chunks_mut(row)).enumerate().for_each(|(j, (prow, nrow))| {
        for (i, (p, nrm)) in prow.iter_mut().zip(nrow.iter_mut()).enumerate() {
            let rest = grid.rest_position(i, j);
            let s = wave.sample(&frame, rest);
            *p = Vec3::new(rest.x, 0.0, rest.y) + s.offset;
            *nrm = s.normal;
        }
    });
}

/// Half the time step (s) of [`velocity_by_difference`]'s central difference: short against any
/// wave period (the shortest waves swell draws have periods above 0.1 s), long enough that `f32`
/// offsets differ by many ulps.
const VELOCITY_STEP_S: f64 = 1e-3;

/// Velocity (m/s) of the surface point resting at (x, z) at time `t`: the central difference of
/// its displacement over ±[`VELOCITY_STEP_S`], for closed-form models without an analytic
/// velocity. The point rests at (x, z) rather than being displaced there, an error of the order of
/// the wave steepness for models that move water sideways.
pub fn velocity_by_difference<W: PointWave>(wave: &W, x: f32, z: f32, t: f64) -> Vec3 {
    let rest = Vec2::new(x, z);
    let ahead = wave.sample(&wave.frame(t + VELOCITY_STEP_S), rest).offset;
    let behind = wave.sample(&wave.frame(t - VELOCITY_STEP_S), rest).offset;
    (ahead - behind) / (2.0 * VELOCITY_STEP_S) as f32
}

/// Most fixed-point iterations [`height_by_inversion`] takes.
pub const INVERSION_MAX_ITERATIONS: usize = 32;

/// Horizontal residual (m) at which [`height_by_inversion`] stops.
pub const INVERSION_TOLERANCE: f32 = 1e-5;

/// Step factor of the damped fixed-point iteration [`height_by_inversion`] starts from and falls
/// back to: plain iteration (1) oscillates near sharp crests, where the map's contraction factor
/// approaches 1; 0.75 keeps it convergent there.
const INVERSION_DAMPING: f32 = 0.75;

/// Height above world (x, z) of a surface that also moves water horizontally.
///
/// Finds the rest point `r` whose displaced position lands on (x, z), i.e. the root of
/// `F(r) = r + horizontal_offset(r) - (x, z)`, then returns that point's height. The first step is
/// the damped fixed-point step `r <- r - 0.75 F(r)`; later steps use Broyden's secant estimate of
/// the inverse Jacobian of F, built from the steps taken (2 x 2, no derivative of the model
/// needed), which converges in a few steps where the fixed-point iteration needs tens near steep
/// crests (issue 19: a million queries in under 2 s). A step that does not reduce the residual
/// resets the estimate to the damped step, so the iteration is never worse than the damped one:
/// the map is a contraction when the horizontal displacement's slope is below 1, which is exactly
/// the no-loop condition every model enforces (Gerstner steepness <= 1). It stops after
/// [`INVERSION_MAX_ITERATIONS`] or when the residual falls below [`INVERSION_TOLERANCE`] metres and
/// returns the height of the best point seen. The height error is the residual times the local
/// slope.
pub fn height_by_inversion<W: PointWave>(wave: &W, x: f32, z: f32, t: f64) -> f32 {
    let frame = wave.frame(t);
    let target = Vec2::new(x, z);
    let damped = Mat2::from_diagonal(Vec2::splat(INVERSION_DAMPING));
    let mut rest = target;
    let mut best = (f32::INFINITY, 0.0);
    // Inverse-Jacobian estimate, and the previous point and residual vector.
    let mut inverse = damped;
    let mut previous: Option<(Vec2, Vec2, f32)> = None;
    for _ in 0..INVERSION_MAX_ITERATIONS {
        let s = wave.sample(&frame, rest);
        let f = rest + Vec2::new(s.offset.x, s.offset.z) - target;
        let residual = f.length();
        if residual < best.0 {
            best = (residual, s.offset.y);
        }
        if residual < INVERSION_TOLERANCE {
            break;
        }
        if let Some((r0, f0, residual0)) = previous {
            if residual < residual0 {
                // "Good" Broyden update: H += (dr - H df) (dr^T H) / (dr^T H df).
                let (dr, df) = (rest - r0, f - f0);
                let h_df = inverse * df;
                let denominator = dr.dot(h_df);
                if denominator.abs() > 1e-12 * dr.length_squared() {
                    let row = inverse.transpose() * dr;
                    let d = (dr - h_df) / denominator;
                    inverse += Mat2::from_cols(d * row.x, d * row.y);
                }
            } else {
                inverse = damped;
            }
        }
        previous = Some((rest, f, residual));
        rest -= inverse * f;
    }
    best.1
}
