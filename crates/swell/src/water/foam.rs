//! Foam from the folding of a choppy surface, with persistence that depends on time alone.
//!
//! Where horizontal displacement squeezes the surface, the Jacobian of the horizontal map
//! `J = (1 + Dxx)(1 + Dzz) - Dxz²` falls below 1; at 0 the surface folds over (a breaking crest).
//! Tessendorf 2001 §3.5 suggests marking foam where J drops below a threshold. swell turns that into
//! a coverage in [0, 1] that rises linearly over [`FOAM_RAMP`] below the threshold (soft-edged
//! whitecaps rather than a hard mask), and optionally keeps foam after the crest has passed.
//!
//! # Foam defined by time alone
//!
//! Persistent foam remembers earlier crests, so a naive update `v = max(coverage, v e^{-dt/fade})`
//! from frame to frame makes the foam of a frame depend on which frames came before it: a still, a
//! shard of a bake or a resumed bake would each show different foam for the same time. swell
//! instead defines the foam at time `t` from a fixed **lattice** of times `k s` (`s` =
//! [`FOAM_LATTICE_STEP_S`], or the nearest step that divides the loop period of a looping sea):
//!
//! - At lattice index k the remembered foam is `L_k = max(c_k, L_{k-1} d - e)`, with `c_k` the
//!   coverage at time `k s`, `d = e^{-s/fade}` and `e = f (1 - d)`, f = [`FOAM_FADE_FLOOR`]. That is
//!   `(L + f)` fading as `e^{-s/fade}`: an exponential fade with the time constant `fade`, shifted
//!   down by f so that it reaches zero after a finite `ln(1 + 1/f) fade` (4.2 fade times) instead of
//!   never.
//! - Because every remembered value reaches zero (or is overtaken by a new crest) within
//!   [`FoamField::window`] steps `M`, `L_k` depends only on `c_{k-M+1} .. c_k`: starting from an
//!   empty field M steps back gives bit for bit the value of a recursion that ran from the start
//!   (the update is monotone, so the two runs meet as soon as the older memory is overtaken, and
//!   from then on compute the same numbers). So a still at any time warms up over M lattice steps,
//!   and a sequential animation steps the lattice forward one step at a time: both give the same
//!   bytes.
//! - The foam at a frame time `t` between lattice times `k s <= t < (k + 1) s` is
//!   `max(coverage(t), (L_k + f) e^{-(t - k s)/fade} - f)`: fresh foam exactly where the crests are
//!   at `t`, and the remembered foam faded to `t`.
//!
//! Cost: the lattice needs the Jacobian at `1 / s` = 20 extra times a second of simulated time
//! (the FFT ocean's first cascade only), and a time far from the last one asked for needs `M`
//! lattice steps (M = 169 for the default 2 s fade: about 60 ms at 256², 1.5 s at 1024²).

use rayon::prelude::*;

/// Jacobian range (dimensionless) below the threshold over which coverage goes from 0 to 1: wide
/// enough that whitecaps have soft edges on a 256² grid, narrow enough that they stay on the crests.
pub const FOAM_RAMP: f32 = 0.25;

/// Time between the foam lattice's samples, s: fine enough that a crest moving at 10 m/s leaves a
/// continuous trail on a 0.5 m grid, coarse enough that the lattice costs fewer steps than the
/// frames of a 24 frames/s animation.
pub const FOAM_LATTICE_STEP_S: f64 = 0.05;

/// How far below zero (in coverage) the exponential fade aims, so that fading foam vanishes after
/// `ln(1 + 1/f)` = 4.2 fade times: 1/64 is below what an 8-bit foam map shows by then.
pub const FOAM_FADE_FLOOR: f32 = 1.0 / 64.0;

/// Foam coverage in [0, 1] for Jacobian `jacobian` and threshold `threshold`.
#[inline]
pub fn foam_coverage(jacobian: f32, threshold: f32) -> f32 {
    ((threshold - jacobian) / FOAM_RAMP).clamp(0.0, 1.0)
}

/// One sample's foam after an update: the fresh `coverage` or the `previous` foam faded by
/// `decay` and lowered by `floor`, whichever is larger (never below 0, since coverage is not).
#[inline]
pub fn foam_update(coverage: f32, previous: f32, decay: f32, floor: f32) -> f32 {
    coverage.max(previous * decay - floor)
}

/// An update of a foam field fused into the code that computes the Jacobian (the FFT ocean's
/// row pass): each `out[i]` becomes `foam_update(coverage(J_i), source[i], decay, floor)`, with
/// `source` = `out` itself when it is `None`.
pub struct FoamUpdate<'a> {
    /// The field written, row-major `[z][x]`.
    pub out: &'a mut [f32],
    /// The previous foam, if not `out` itself.
    pub source: Option<&'a [f32]>,
    /// Factor in [0, 1] on the previous foam.
    pub decay: f32,
    /// Coverage in [0, 1] subtracted after the decay.
    pub floor: f32,
    /// Jacobian threshold below which foam appears.
    pub threshold: f32,
}

/// The lattice steps a time needs before its own frame: indices `first..=last` (empty when the
/// lattice is already there), each at [`FoamField::lattice_time`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LatticeSteps {
    /// First lattice index to step.
    pub first: i64,
    /// Last lattice index to step (the one at or just before the frame's time).
    pub last: i64,
}

impl LatticeSteps {
    /// The indices in order.
    pub fn indices(self) -> std::ops::RangeInclusive<i64> {
        self.first..=self.last
    }
}

/// A foam field on a periodic n x n grid: the foam at the last frame's time and the lattice's
/// remembered foam (see the [module documentation](self)).
#[derive(Clone, Debug)]
pub struct FoamField {
    /// Grid side.
    pub n: usize,
    /// Coverage in [0, 1] at the last frame's time, row-major `[z][x]`.
    pub values: Vec<f32>,
    /// Fade time constant (s); 0 keeps nothing from one time to the next.
    pub fade: f32,
    /// Coverage threshold on the Jacobian.
    pub threshold: f32,
    /// The lattice's remembered foam at `lattice_index` (empty without persistence).
    lattice: Vec<f32>,
    lattice_index: Option<i64>,
    /// Lattice step, s.
    step: f64,
    /// Lattice steps per loop period, for a looping sea.
    loop_steps: Option<i64>,
    /// Lattice steps after which any remembered foam has vanished.
    window: i64,
    step_decay: f32,
    step_floor: f32,
}

impl FoamField {
    /// An empty n x n field with the given threshold and fade (s). With `loop_period` (s), the
    /// lattice step is the one nearest [`FOAM_LATTICE_STEP_S`] that divides the period, so the foam
    /// loops with the sea.
    pub fn new(n: usize, threshold: f32, fade: f32, loop_period: Option<f64>) -> Self {
        let (step, loop_steps) = match loop_period {
            Some(p) => {
                let steps = (p / FOAM_LATTICE_STEP_S).round().max(1.0);
                (p / steps, Some(steps as i64))
            }
            None => (FOAM_LATTICE_STEP_S, None),
        };
        let persistent = fade > 0.0;
        let step_decay = if persistent { (-step / f64::from(fade)).exp() as f32 } else { 0.0 };
        let step_floor = FOAM_FADE_FLOOR * (1.0 - step_decay);
        Self {
            n,
            values: vec![0.0; n * n],
            fade,
            threshold,
            lattice: if persistent { vec![0.0; n * n] } else { Vec::new() },
            lattice_index: None,
            step,
            loop_steps,
            window: if persistent { fade_window(step_decay, step_floor) } else { 0 },
            step_decay,
            step_floor,
        }
    }

    /// Whether foam persists after the crest (fade > 0).
    pub fn persistent(&self) -> bool {
        self.fade > 0.0
    }

    /// Lattice steps M after which remembered foam has faded to zero: the foam at a lattice time
    /// depends on the coverage of the last M lattice times only.
    pub fn window(&self) -> i64 {
        self.window
    }

    /// The lattice step, s.
    pub fn lattice_step(&self) -> f64 {
        self.step
    }

    /// Time (s) of lattice index `k`; for a looping sea, reduced into the first period.
    pub fn lattice_time(&self, k: i64) -> f64 {
        match self.loop_steps {
            Some(p) => k.rem_euclid(p) as f64 * self.step,
            None => k as f64 * self.step,
        }
    }

    /// The lattice index at or just before time `t` (s).
    fn index_of(&self, t: f64) -> i64 {
        // The guard absorbs a time a rounding error short of a lattice time (k s computed as
        // t = k / fps), which would otherwise take the previous index and fade a step's worth.
        let k = (t / self.step).floor();
        let next = k + 1.0;
        let k = if (next * self.step - t).abs() <= 1e-9 * self.step.max(t.abs()) { next } else { k };
        k.clamp(i64::MIN as f64 / 2.0, i64::MAX as f64 / 2.0) as i64
    }

    /// Plans the update for a frame at time `t` (s): the lattice steps to run first (each with
    /// [`FoamField::lattice_update`]), then the frame with [`FoamField::frame_update`]. Empty
    /// without persistence. Records the lattice as being at the plan's last index: the caller must
    /// run every step it returns.
    pub fn plan(&mut self, t: f64) -> Option<LatticeSteps> {
        if !self.persistent() {
            return None;
        }
        let k = self.index_of(t);
        let ahead = self.lattice_index.map(|at| match self.loop_steps {
            // A looping lattice is the same after a period: step forward around the loop.
            Some(p) => (k - at).rem_euclid(p),
            None => k - at,
        });
        let steps = match ahead {
            Some(0) => None,
            Some(d) if d > 0 && d <= self.window => Some(LatticeSteps { first: k - d + 1, last: k }),
            // Backwards, far ahead or the first time: start from no foam a window back, which
            // gives the same values (see the module documentation).
            _ => {
                self.lattice.fill(0.0);
                Some(LatticeSteps { first: k - self.window + 1, last: k })
            }
        };
        self.lattice_index = Some(k);
        steps
    }

    /// The fused update for one lattice step (in place on the lattice).
    pub fn lattice_update(&mut self) -> FoamUpdate<'_> {
        FoamUpdate {
            out: &mut self.lattice,
            source: None,
            decay: self.step_decay,
            floor: self.step_floor,
            threshold: self.threshold,
        }
    }

    /// The fused update for the frame at time `t` (s), after the steps of [`FoamField::plan`]:
    /// the lattice's foam faded to `t`, or no memory without persistence.
    pub fn frame_update(&mut self, t: f64) -> FoamUpdate<'_> {
        // Only a persistent field plans lattice steps, so only it has a lattice index.
        let Some(k) = self.lattice_index else {
            return FoamUpdate {
                out: &mut self.values,
                source: None,
                decay: 0.0,
                floor: 0.0,
                threshold: self.threshold,
            };
        };
        // t is already reduced into the loop's first period; k may be the period's end (t a
        // rounding error short of it), which gives a zero interval.
        let since = (t - k as f64 * self.step).max(0.0);
        let decay = (-since / f64::from(self.fade)).exp() as f32;
        FoamUpdate {
            out: &mut self.values,
            source: Some(&self.lattice),
            decay,
            floor: FOAM_FADE_FLOOR * (1.0 - decay),
            threshold: self.threshold,
        }
    }

    /// Mean coverage over the field, in [0, 1].
    pub fn mean(&self) -> f32 {
        (self.values.iter().map(|&v| f64::from(v)).sum::<f64>() / self.values.len() as f64) as f32
    }
}

impl FoamUpdate<'_> {
    /// Applies the update from the Jacobian at each sample `(i, j)` (column, row) of an n-wide
    /// field: the plain reference of what the FFT ocean fuses into its row pass.
    pub fn apply(self, n: usize, jacobian: impl Fn(usize, usize) -> f32 + Sync) {
        let FoamUpdate { out, source, decay, floor, threshold } = self;
        let update = |(j, row): (usize, &mut [f32])| {
            for (i, v) in row.iter_mut().enumerate() {
                let previous = source.map_or(*v, |s| s[j * n + i]);
                *v = foam_update(foam_coverage(jacobian(i, j), threshold), previous, decay, floor);
            }
        };
        out.par_chunks_mut(n).enumerate().for_each(update);
    }
}

/// Lattice steps after which foam of coverage 1, fading by `decay` and `floor` a step with no new
/// crest, has reached 0: counted with the update's own f32 operations, plus one for safety.
fn fade_window(decay: f32, floor: f32) -> i64 {
    let mut v = 1.0f32;
    let mut steps = 0;
    while v > 0.0 {
        v = foam_update(0.0, v, decay, floor);
        steps += 1;
    }
    steps + 1
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn coverage_ramps_below_the_threshold() {
        assert_eq!(foam_coverage(1.0, 0.5), 0.0);
        assert_eq!(foam_coverage(0.5, 0.5), 0.0);
        assert_eq!(foam_coverage(0.5 - FOAM_RAMP, 0.5), 1.0);
    }

    #[test]
    fn remembered_foam_fades_with_the_time_constant_and_vanishes_in_the_window() {
        let mut f = FoamField::new(2, 0.5, 2.0, None);
        // The fade: (1 + f) e^{-s/fade} - f after s seconds.
        let expected = |s: f64| (1.0 + f64::from(FOAM_FADE_FLOOR)) * (-s / 2.0).exp() - f64::from(FOAM_FADE_FLOOR);
        let mut v = 1.0f32;
        for k in 1..=40 {
            v = foam_update(0.0, v, f.step_decay, f.step_floor);
            assert!((f64::from(v) - expected(k as f64 * f.step)).abs() < 1e-5, "step {k}");
        }
        // ln(1 + 64) * 2 s / 0.05 s = 167 steps, plus the safety step and a rounding step.
        assert!((167..=170).contains(&f.window()), "{}", f.window());
        // Planning: a first time warms up over a window; the next lattice time is one step; going
        // back warms up again; a time between lattice points needs no step after its lattice point.
        assert_eq!(f.plan(10.0), Some(LatticeSteps { first: 200 - f.window() + 1, last: 200 }));
        assert_eq!(f.plan(10.05), Some(LatticeSteps { first: 201, last: 201 }));
        assert_eq!(f.plan(10.07), None);
        assert_eq!(f.plan(5.0).map(|s| s.first), Some(100 - f.window() + 1));
        // A time a rounding error short of a lattice time is that lattice time.
        let mut g = FoamField::new(2, 0.5, 2.0, None);
        assert_eq!(g.plan(3.0 - 1e-13).map(|s| s.last), Some(60));
    }

    #[test]
    fn a_looping_lattice_divides_the_period_and_wraps() {
        let mut f = FoamField::new(2, 0.5, 1.0, Some(1.02));
        assert_eq!(f.lattice_step(), 1.02 / 20.0);
        assert_eq!(f.lattice_time(20), 0.0);
        assert_eq!(f.lattice_time(-1), f.lattice_time(19));
        f.plan(0.99);
        // Index 19 to index 0 (the loop's start) is one step around the loop.
        assert_eq!(f.plan(0.0), Some(LatticeSteps { first: 0, last: 0 }));
    }

    #[test]
    fn without_persistence_a_frame_is_its_own_coverage() {
        let mut f = FoamField::new(2, 0.5, 0.0, None);
        assert_eq!(f.plan(3.0), None);
        f.values.fill(0.7);
        f.frame_update(3.0).apply(2, |_, _| 1.0);
        assert!(f.values.iter().all(|&v| v == 0.0));
        f.frame_update(3.1).apply(2, |_, _| -1.0);
        assert!(f.values.iter().all(|&v| v == 1.0));
    }
}
