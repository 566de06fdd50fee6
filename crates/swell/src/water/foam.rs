//! Foam from the folding of a choppy surface: whitecaps whose coverage follows the wind rather
//! than the grid, and foam that stays behind them, defined by time alone.
//!
//! Where horizontal displacement squeezes the surface, the Jacobian of the horizontal map
//! `J = (1 + Dxx)(1 + Dzz) - Dxz²` falls below 1; at 0 the surface folds over (a breaking crest).
//! Tessendorf 2001 §3.5 suggests marking foam where J drops below a threshold.
//!
//! # Whitecaps that follow the wind, not the grid
//!
//! A grid resolves only its own waves, and the Jacobian of the waves it cannot hold is what
//! breaks first: thresholding the resolved J alone gave a steady coverage that fell a hundredfold
//! from a 128 m to a 1024 m patch at the same wind (issue 38). swell follows Dupuy and Bruneton
//! (2012, "Real-time animation and rendering of ocean whitecaps", SIGGRAPH Asia technical briefs):
//! the Jacobian at a sample is the resolved `J` plus an unresolved part, a Gaussian of zero mean,
//! and the sample's **active whitecap** coverage is the probability that the sum is below the
//! threshold,
//!
//! `c = Φ((threshold - J) / σ)`, with `σ² = λ² (s_total - s_resolved) + σ0²`.
//!
//! To first order `J - 1 = Dxx + Dzz = λ Σ k ĥ(k)`, whose variance is `λ²` times the slope variance
//! `Σ k² |ĥ|²`. `s_resolved` is what the first cascade (where foam lives) realises; `s_total` is the
//! sea's whole slope variance as Cox and Munk (1954) measured it against the wind
//! ([`crate::water::cox_munk_slope_variance`]): a spectrum's short-wave tail is a fit to the
//! energetic waves, not a measurement of the slopes, and in JONSWAP's equilibrium range the slope
//! variance hardly grows with the wind, where the breaking does. So resolved and unresolved
//! variances add up to the same total on every grid (the mean active coverage of a 0.25 m and an
//! 8 m grid agree within 6 %), and the total grows with the wind. [`FOAM_MIN_SPREAD`] (σ0) keeps
//! soft edges however fine the grid.
//!
//! # Foam that stays, defined by time alone
//!
//! A whitecap leaves foam behind that fades over `fade` seconds. Kept as a running maximum (a
//! crest's foam fading until a new crest overtakes it, swell's rule before issue 38) the amount
//! kept depends on how fast the coverage flickers, so on the grid again: a fine grid's short waves
//! break and re-break within a fade time and its steady foam came out 2.6 times a coarse grid's.
//! swell instead **integrates**: each active whitecap produces foam at the rate `c / τb`
//! ([`FOAM_ACTIVE_TIME_S`], how long a breaking crest stays active) and foam decays with `fade`,
//!
//! `R(t) = ∫ c(t') / τb · e^{-(t - t')/fade} dt'`, whose mean is `mean(c) fade / τb`,
//!
//! a linear function of the coverage's history, so its mean depends on the mean coverage alone (and
//! so on the wind alone). The foam shown is `min(1, max(c, R))`: fresh foam on the crests, streaks
//! where they have passed.
//!
//! A naive update from frame to frame would make a frame's foam depend on which frames came before
//! it (a still, a shard or a resumed bake would differ). swell defines `R` on a fixed **lattice**
//! of times `k s` (`s` = [`FOAM_LATTICE_STEP_S`], or the nearest step that divides a loop period),
//! `R_k = d R_{k-1} + g c_k` with `d = e^{-s/fade}` and `g = (1 - d) fade / τb`, cut into
//! **blocks** of at least `B` steps, `d^B <= ` [`FOAM_MEMORY_CUT`], aligned on absolute lattice
//! indices:
//!
//! - `R_k = cur_k + d^{k - start + 1} prev`, where `cur_k` is the recursion run from zero at the start
//!   of k's block and `prev` the full recursion over the block before it (run from zero at its own
//!   start). Each is a fixed sum over fixed lattice times, computed with the same f32 operations
//!   whichever way one gets there: stepping one lattice time after another (an animation), or
//!   warming up from the previous block's start (a still: between B and 2B steps). Both give the
//!   same bytes.
//! - What is dropped is foam older than the previous block, weighted by at most `d^B`: R jumps by
//!   at most 1/64 of its value at a block boundary, once every `B s` (8.3 s for the default 2 s fade).
//! - A looping sea cuts its period into blocks (the last one longer, up to 2B), so the blocks loop
//!   with it; a period shorter than 2B is one block, and `prev` then stands for every earlier period:
//!   `d^{k - start + 1} prev / (1 - d^P)`, the exact periodic sum.
//! - The foam at a frame time `t` between lattice times `k s <= t < (k + 1) s` is
//!   `min(1, max(c(t), R_k e^{-(t - k s)/fade}))`.
//!
//! Cost: the lattice needs the Jacobian at `1 / s` = 20 extra times a second of simulated time
//! (the FFT ocean's first cascade only), and a time far from the last one asked for needs up to 2B
//! lattice steps (B = 167 for the default 2 s fade: about 60 to 120 ms at 256²).

use rayon::prelude::*;

use crate::math::normal_cdf;

/// The smallest spread σ0 of the Jacobian below the resolved one (dimensionless): the width of a
/// whitecap's soft edge where the grid leaves little unresolved (the ramp of 0.25 that foam had
/// before issue 38 has this standard deviation, `0.25 / sqrt(12)`).
pub const FOAM_MIN_SPREAD: f32 = 0.072;

/// How long a breaking crest stays an active whitecap, s: the foam it leaves is produced at the
/// rate `coverage / τb`. Active whitecaps (Monahan's stage A) last a fraction of the breaking
/// wave's period; with the default 2 s fade this gives residual foam about four times the active
/// coverage, the ratio Monahan and Lu (1990) report between stage B and stage A whitecaps, and
/// with the default threshold the total coverage that Monahan and O'Muircheartaigh (1980) fitted
/// against the wind.
pub const FOAM_ACTIVE_TIME_S: f64 = 0.5;

/// Time between the foam lattice's samples, s: fine enough that a crest moving at 10 m/s leaves a
/// continuous trail on a 0.5 m grid, coarse enough that the lattice costs fewer steps than the
/// frames of a 24 frames/s animation.
pub const FOAM_LATTICE_STEP_S: f64 = 0.05;

/// The weight below which old foam is forgotten: a block of the foam's memory is at least long
/// enough that the fade brings foam down to this fraction across it (4.2 fade times), below what
/// an 8-bit foam map shows.
pub const FOAM_MEMORY_CUT: f64 = 1.0 / 64.0;

/// Foam coverage in [0, 1] for the resolved Jacobian `jacobian`, threshold `threshold` and the
/// inverse `1 / σ` of the unresolved Jacobian's spread: the chance that the two together are
/// below the threshold, `Φ((threshold - J) / σ)` (see the [module documentation](self)).
#[inline]
pub fn foam_coverage(jacobian: f32, threshold: f32, inv_spread: f32) -> f32 {
    normal_cdf((threshold - jacobian) * inv_spread)
}

/// The constants of one foam update ([`FoamUpdate`]): every sample becomes
/// `min(ceiling, max(fresh c, first a + second b + gain c))` with `c` its coverage
/// ([`foam_coverage`]) and `a`, `b` the sample's values in the two source fields.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FoamWeights {
    /// Jacobian threshold below which foam appears.
    pub threshold: f32,
    /// `1 / σ` of the unresolved Jacobian ([`foam_coverage`]).
    pub inv_spread: f32,
    /// Factor on the first source.
    pub first: f32,
    /// Factor on the second source.
    pub second: f32,
    /// Factor on the coverage added to the sources.
    pub gain: f32,
    /// Factor (0 or 1) on the coverage that the result is at least.
    pub fresh: f32,
    /// Upper bound of the result (infinite for the lattice's memory).
    pub ceiling: f32,
}

impl FoamWeights {
    /// One sample's update from its coverage `c` and its two source values: the one formula the
    /// scalar and the AVX2 code both compute, operation for operation.
    #[inline]
    pub fn apply(&self, c: f32, first: f32, second: f32) -> f32 {
        let kept = self.first * first + self.second * second + self.gain * c;
        (self.fresh * c).max(kept).min(self.ceiling)
    }
}

/// An update of a foam field fused into the code that computes the Jacobian (the FFT ocean's
/// row pass): each `out[i]` becomes `weights.apply(coverage(J_i), first[i], second[i])`, with
/// `first` = `out` itself when it is `None` and `second` = 0 when it is `None`.
pub struct FoamUpdate<'a> {
    /// The field written, row-major `[z][x]`.
    pub out: &'a mut [f32],
    /// The first source, if not `out` itself.
    pub first: Option<&'a [f32]>,
    /// The second source, if any.
    pub second: Option<&'a [f32]>,
    /// The constants.
    pub weights: FoamWeights,
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
/// memory of earlier whitecaps (see the [module documentation](self)).
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
    /// Spread σ of the unresolved Jacobian, at least [`FOAM_MIN_SPREAD`].
    spread: f32,
    /// The memory of the current block (`cur`) and of the one before it (`prev`); empty without
    /// persistence.
    cur: Vec<f32>,
    prev: Vec<f32>,
    /// Start (lattice index) of `cur`'s block, once one has been entered.
    cur_start: Option<i64>,
    /// The last lattice index integrated into `cur` (unreduced: it keeps growing around a loop).
    at: Option<i64>,
    /// Lattice step, s.
    step: f64,
    /// Lattice steps per loop period, for a looping sea.
    loop_steps: Option<i64>,
    /// Shortest block, steps.
    block: i64,
    step_decay: f32,
    gain: f32,
}

impl FoamField {
    /// An empty n x n field with the given threshold, spread σ of the unresolved Jacobian (raised
    /// to [`FOAM_MIN_SPREAD`]) and fade (s). With `loop_period` (s), the lattice step is the one
    /// nearest [`FOAM_LATTICE_STEP_S`] that divides the period, so the foam loops with the sea.
    pub fn new(n: usize, threshold: f32, spread: f32, fade: f32, loop_period: Option<f64>) -> Self {
        let (step, loop_steps) = match loop_period {
            Some(p) => {
                let steps = (p / FOAM_LATTICE_STEP_S).round().max(1.0);
                (p / steps, Some(steps as i64))
            }
            None => (FOAM_LATTICE_STEP_S, None),
        };
        let persistent = fade > 0.0;
        let fade64 = f64::from(fade);
        let (step_decay, gain, block) = if persistent {
            let d = (-step / fade64).exp();
            let block = (FOAM_MEMORY_CUT.ln() / d.ln()).ceil().max(1.0) as i64;
            (d as f32, ((1.0 - d) * fade64 / FOAM_ACTIVE_TIME_S) as f32, block)
        } else {
            (0.0, 0.0, 1)
        };
        let memory = if persistent { vec![0.0; n * n] } else { Vec::new() };
        Self {
            n,
            values: vec![0.0; n * n],
            fade,
            threshold,
            spread: spread.max(FOAM_MIN_SPREAD),
            cur: memory.clone(),
            prev: memory,
            cur_start: None,
            at: None,
            step,
            loop_steps,
            block,
            step_decay,
            gain,
        }
    }

    /// Spread σ of the unresolved Jacobian (dimensionless, at least [`FOAM_MIN_SPREAD`]).
    pub fn spread(&self) -> f32 {
        self.spread
    }

    /// Sets the spread σ of the unresolved Jacobian, raised to [`FOAM_MIN_SPREAD`] (a NaN reads
    /// as it): for a model that learns it after building its field.
    pub fn set_spread(&mut self, spread: f32) {
        self.spread = spread.max(FOAM_MIN_SPREAD);
    }

    /// Whether foam persists after the crest (fade > 0).
    pub fn persistent(&self) -> bool {
        self.fade > 0.0
    }

    /// The shortest block of the memory, lattice steps: a still warms up over between one and two
    /// blocks.
    pub fn block(&self) -> i64 {
        self.block
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

    /// Blocks in a loop's period (the last one takes the remainder), at least 1.
    fn loop_blocks(&self, period: i64) -> i64 {
        (period / self.block).max(1)
    }

    /// Start of the block holding lattice index `k`.
    fn block_start(&self, k: i64) -> i64 {
        match self.loop_steps {
            None => k.div_euclid(self.block) * self.block,
            Some(p) => {
                let r = k.rem_euclid(p);
                (k - r) + (r / self.block).min(self.loop_blocks(p) - 1) * self.block
            }
        }
    }

    /// Start of the block before the one starting at `start`.
    fn previous_block_start(&self, start: i64) -> i64 {
        match self.loop_steps {
            None => start - self.block,
            Some(p) => {
                let offset = start.rem_euclid(p);
                if offset > 0 {
                    start - self.block
                } else {
                    start - p + (self.loop_blocks(p) - 1) * self.block
                }
            }
        }
    }

    /// Plans the update for a frame at time `t` (s): the lattice steps to run first (each with
    /// [`FoamField::lattice_update`]), then the frame with [`FoamField::frame_update`]. Empty
    /// without persistence. The caller must run every step it returns.
    pub fn plan(&mut self, t: f64) -> Option<LatticeSteps> {
        if !self.persistent() {
            return None;
        }
        let k = self.index_of(t);
        // Forward from where the memory is (around a loop: the same index one period on).
        let target = match (self.at, self.loop_steps) {
            (Some(at), Some(p)) => at + (k - at).rem_euclid(p),
            _ => k,
        };
        let fresh_first = self.previous_block_start(self.block_start(target));
        match self.at {
            Some(at) if at == target => None,
            // Stepping on is cheaper than warming up: it rolls the blocks as it crosses them,
            // which gives the same sums.
            Some(at) if at < target && target - at <= target - fresh_first + 1 => {
                Some(LatticeSteps { first: at + 1, last: target })
            }
            // Backwards, far ahead or the first time: from zero at the previous block's start.
            _ => {
                self.cur_start = None;
                Some(LatticeSteps { first: fresh_first, last: target })
            }
        }
    }

    /// The fused update for lattice step `k` (in place on the current block's memory); the steps
    /// must come in the order [`FoamField::plan`] gave them.
    pub fn lattice_update(&mut self, k: i64) -> FoamUpdate<'_> {
        if self.block_start(k) == k {
            // A new block: the one just finished becomes the previous one (a warm-up's first
            // step has nothing finished yet) and the current one starts from no foam.
            if self.cur_start.is_some() {
                std::mem::swap(&mut self.cur, &mut self.prev);
            }
            self.cur.fill(0.0);
            self.cur_start = Some(k);
        }
        self.at = Some(k);
        FoamUpdate {
            out: &mut self.cur,
            first: None,
            second: None,
            weights: FoamWeights {
                threshold: self.threshold,
                inv_spread: 1.0 / self.spread,
                first: self.step_decay,
                second: 0.0,
                gain: self.gain,
                fresh: 0.0,
                ceiling: f32::INFINITY,
            },
        }
    }

    /// The fused update for the frame at time `t` (s), after the steps of [`FoamField::plan`]:
    /// the lattice's memory faded to `t`, or no memory without persistence.
    pub fn frame_update(&mut self, t: f64) -> FoamUpdate<'_> {
        let (threshold, inv_spread) = (self.threshold, 1.0 / self.spread);
        let (Some(at), Some(start)) = (self.at, self.cur_start) else {
            let weights =
                FoamWeights { threshold, inv_spread, first: 0.0, second: 0.0, gain: 0.0, fresh: 1.0, ceiling: 1.0 };
            return FoamUpdate { out: &mut self.values, first: None, second: None, weights };
        };
        let d = f64::from(self.step_decay);
        // The previous block seen from lattice index `at`; for a loop of one block it stands for
        // every earlier period.
        let mut old = d.powi((at - start + 1) as i32);
        if let Some(p) = self.loop_steps {
            if self.loop_blocks(p) == 1 {
                old /= 1.0 - d.powi(p as i32);
            }
        }
        // t is reduced into a loop's first period; its own lattice index may be the period's end
        // (t a rounding error short of it), which gives a zero interval.
        let since = (t - self.index_of(t) as f64 * self.step).max(0.0);
        let fade = (-since / f64::from(self.fade)).exp();
        FoamUpdate {
            out: &mut self.values,
            first: Some(&self.cur),
            second: Some(&self.prev),
            weights: FoamWeights {
                threshold,
                inv_spread,
                first: fade as f32,
                second: (old * fade) as f32,
                gain: 0.0,
                fresh: 1.0,
                ceiling: 1.0,
            },
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
        let FoamUpdate { out, first, second, weights: w } = self;
        let update = |(j, row): (usize, &mut [f32])| {
            for (i, v) in row.iter_mut().enumerate() {
                let a = first.map_or(*v, |s| s[j * n + i]);
                let b = second.map_or(0.0, |s| s[j * n + i]);
                *v = w.apply(foam_coverage(jacobian(i, j), w.threshold, w.inv_spread), a, b);
            }
        };
        out.par_chunks_mut(n).enumerate().for_each(update);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn coverage_is_the_chance_that_the_whole_jacobian_is_below_the_threshold() {
        // Half at the threshold; one spread below it Φ(1), far above nothing, far below all.
        assert_eq!(foam_coverage(0.5, 0.5, 10.0), 0.5);
        assert!((foam_coverage(0.4, 0.5, 10.0) - 0.841_344_7).abs() < 1e-5);
        assert!((foam_coverage(0.6, 0.5, 10.0) - 0.158_655_3).abs() < 1e-5);
        assert_eq!(foam_coverage(2.0, 0.5, 10.0), 0.0);
        assert_eq!(foam_coverage(-1.0, 0.5, 10.0), 1.0);
        // The spread is never below the soft edge's.
        assert_eq!(FoamField::new(2, 0.5, 0.0, 0.0, None).spread(), FOAM_MIN_SPREAD);
        assert_eq!(FoamField::new(2, 0.5, 0.3, 0.0, None).spread(), 0.3);
    }

    /// Runs a field's plan for `t` and its frame with a coverage history `c(k)` (a uniform field
    /// whose active coverage at lattice index k is `c(k)`, at the frame too): the foam value.
    fn foam_at(f: &mut FoamField, t: f64, c: impl Fn(i64) -> f32) -> f32 {
        // Φ((threshold - J) σ⁻¹) = c for J = threshold - σ Φ⁻¹(c): find J by bisection.
        let jacobian_for = |f: &FoamField, c: f32| {
            let (mut lo, mut hi) = (-10.0f32, 10.0f32);
            for _ in 0..60 {
                let mid = 0.5 * (lo + hi);
                if foam_coverage(mid, f.threshold, 1.0 / f.spread) > c {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            hi
        };
        for k in f.plan(t).map(|s| s.indices()).into_iter().flatten() {
            let j = jacobian_for(f, c(k));
            f.lattice_update(k).apply(2, |_, _| j);
        }
        let j = jacobian_for(f, c(f.index_of(t)));
        f.frame_update(t).apply(2, |_, _| j);
        f.values[0]
    }

    #[test]
    fn residual_foam_is_the_coverage_integrated_and_faded() {
        // Steady active coverage c gives residual foam c fade / τb (to the memory's cut).
        let mut f = FoamField::new(2, 0.5, 0.1, 2.0, None);
        let steady = foam_at(&mut f, 100.0, |_| 0.01);
        let want = 0.01 * 2.0 / FOAM_ACTIVE_TIME_S;
        assert!((f64::from(steady) / want - 1.0).abs() < 2.0 * FOAM_MEMORY_CUT, "{steady} vs {want}");
        // A burst of full coverage for 0.5 s, then none: the foam fades as e^{-t/fade}.
        let burst = |k: i64| if (1000..1010).contains(&k) { 1.0 } else { 0.0 };
        let mut g = FoamField::new(2, 0.5, 0.1, 2.0, None);
        let a = foam_at(&mut g, 51.0, burst);
        let b = foam_at(&mut g, 53.0, burst);
        assert!(a > 0.5 && a <= 1.0, "{a}");
        assert!((f64::from(b / a) - (-1.0f64).exp()).abs() < 1e-4, "{a} -> {b}");
        // The block: the fade's weight across it is at most the cut.
        let d = (-f.lattice_step() / 2.0).exp();
        assert!(d.powi(f.block() as i32) <= FOAM_MEMORY_CUT && d.powi(f.block() as i32 - 1) > FOAM_MEMORY_CUT);
    }

    #[test]
    fn a_still_and_an_animation_give_the_same_bytes() {
        // A history with structure at every scale; frames stepped one after another, from far
        // back, across block boundaries, and stills taken cold, must agree bit for bit.
        for loop_period in [None, Some(3.0), Some(30.0)] {
            // A loop's coverage repeats with it (the sea is synthesised at the reduced time).
            let period = loop_period.map(|p: f64| (p / FOAM_LATTICE_STEP_S).round() as i64);
            let c = move |k: i64| {
                let k = period.map_or(k, |p| k.rem_euclid(p)) as f32;
                ((k * 0.37).sin() * 0.5 + 0.5) * ((k * 0.011).cos() * 0.5 + 0.5)
            };
            let mut animation = FoamField::new(2, 0.5, 0.1, 2.0, loop_period);
            for frame in 0..1200 {
                let t = f64::from(frame) / 24.0;
                let local = loop_period.map_or(t, |p| t.rem_euclid(p));
                let stepped = foam_at(&mut animation, local, c);
                if frame % 97 == 0 || frame % 200 == 199 {
                    let mut still = FoamField::new(2, 0.5, 0.1, 2.0, loop_period);
                    assert_eq!(stepped, foam_at(&mut still, local, c), "frame {frame}, loop {loop_period:?}");
                }
            }
        }
    }

    #[test]
    fn a_loop_s_foam_loops() {
        for period in [1.02, 3.0, 30.0] {
            let steps = (period / FOAM_LATTICE_STEP_S).round() as i64;
            // A history that loops with the sea.
            let c = move |k: i64| ((k.rem_euclid(steps) as f32) * 0.7).sin().abs() * 0.3;
            let mut f = FoamField::new(2, 0.5, 0.1, 2.0, Some(period));
            assert_eq!(f.lattice_step(), period / steps as f64);
            assert_eq!(f.lattice_time(steps), 0.0);
            let mut first = Vec::new();
            for round in 0..3 {
                for i in 0..steps {
                    let t = i as f64 * f.lattice_step() + 0.01;
                    let v = foam_at(&mut f, t, c);
                    if round == 0 {
                        first.push(v);
                    } else {
                        // A one-block period holds every earlier period exactly; longer periods
                        // forget what is older than the previous block.
                        assert_eq!(v, first[i as usize], "period {period}, round {round}, step {i}");
                    }
                }
            }
        }
    }

    #[test]
    fn without_persistence_a_frame_is_its_own_coverage() {
        let mut f = FoamField::new(2, 0.5, 0.1, 0.0, None);
        assert_eq!(f.plan(3.0), None);
        f.values.fill(0.7);
        f.frame_update(3.0).apply(2, |_, _| 2.0);
        assert!(f.values.iter().all(|&v| v == 0.0));
        f.frame_update(3.1).apply(2, |_, _| -1.0);
        assert!(f.values.iter().all(|&v| v == 1.0));
    }
}
