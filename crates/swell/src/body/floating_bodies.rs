//! The bodies of a scene stepped together at a fixed rate, whatever the frame rate.

use rayon::prelude::*;

use super::{BodyEnvironment, BodyPose, BodySpec, FloatingBody};
use crate::error::{Error, Result};

/// Body steps per second: the forces are evaluated at multiples of 1/120 s, so poses depend only
/// on the time asked for, never on the frame rate (60 fps takes two steps a frame, 24 fps five).
pub const BODY_STEP_HZ: u32 = 120;

/// Sea water's density, kg/m³: `[water] density` when a scene does not give it.
pub const SEA_WATER_DENSITY: f32 = 1025.0;

/// Range of `[water] density`, kg/m³: from fresh water at 100 °C to the Dead Sea, widened.
pub const WATER_DENSITY_RANGE: (f32, f32) = (900.0, 1300.0);

/// Largest heave frequency times the step a body may have, `ω Δt`: semi-implicit Euler on the
/// hydrostatic spring is stable below 2 and follows the period within 4 % below 1.
const MAX_HEAVE_OMEGA_DT: f64 = 1.0;

/// The bodies of a scene and the water's density, at step [`FloatingBodies::steps`].
///
/// A step from step n to n + 1 evaluates every body's loads at step n's state with the water at
/// n / [`BODY_STEP_HZ`] s, then integrates; bodies are independent within a step, so they are
/// stepped in parallel and the result does not depend on the thread count. A pose between steps
/// ([`FloatingBodies::poses_at`]) is integrated from the last step under its loads, without
/// changing the state, so asking for a time never changes what a later time gives.
#[derive(Clone, Debug)]
pub struct FloatingBodies {
    bodies: Vec<FloatingBody>,
    water_density: f64,
    steps: u64,
    /// Whether every body's load is that of the current state.
    loaded: bool,
}

impl FloatingBodies {
    /// The bodies of `specs` (validated, meshes read) on water of `water_density` kg/m³.
    pub fn from_specs(specs: &[BodySpec], water_density: f32) -> Result<Self> {
        super::validate_bodies(specs)?;
        let bodies =
            specs.iter().enumerate().map(|(i, s)| s.build(i, &format!("body[{i}]"))).collect::<Result<Vec<_>>>()?;
        Self::new(bodies, water_density)
    }

    /// `bodies` on water of `water_density` kg/m³ (in [`WATER_DENSITY_RANGE`]). Refuses a body so
    /// light for its size that it would bob faster than the 120 Hz step can follow.
    pub fn new(bodies: Vec<FloatingBody>, water_density: f32) -> Result<Self> {
        let (lo, hi) = WATER_DENSITY_RANGE;
        crate::error::check_range("water.density", water_density, lo, hi)?;
        let rho = f64::from(water_density);
        for (i, b) in bodies.iter().enumerate() {
            check_steppable(b, i, rho)?;
        }
        Ok(Self { bodies, water_density: rho, steps: 0, loaded: false })
    }

    /// The bodies, in scene order, at step [`FloatingBodies::steps`].
    pub fn bodies(&self) -> &[FloatingBody] {
        &self.bodies
    }

    /// How many bodies there are.
    pub fn len(&self) -> usize {
        self.bodies.len()
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.bodies.is_empty()
    }

    /// Water density, kg/m³.
    pub fn water_density(&self) -> f64 {
        self.water_density
    }

    /// Steps taken since t = 0.
    pub fn steps(&self) -> u64 {
        self.steps
    }

    /// The time (s) of step `n`.
    pub fn step_time(n: u64) -> f64 {
        n as f64 / f64::from(BODY_STEP_HZ)
    }

    /// The last step at or before time `t` (s, >= 0); a time within a nanosecond below a step
    /// counts as that step, so that `k / 60` s is step `2k` despite rounding.
    pub fn step_at(t: f64) -> u64 {
        (t * f64::from(BODY_STEP_HZ) + 1e-7).floor().max(0.0) as u64
    }

    /// The bodies, mutable: for a push ([`FloatingBody::thrust`]); a change to a body's state or
    /// mass is the caller's to make consistent.
    pub fn bodies_mut(&mut self) -> &mut [FloatingBody] {
        &mut self.bodies
    }

    /// Adds `body` (checked like [`FloatingBodies::new`]'s, named `body[k]`, k its index) after the others; it
    /// joins at the next step. Give it a release time after the current step's time
    /// ([`FloatingBody::release_time`]) for a run from t = 0 to move it exactly as this one will.
    pub fn push(&mut self, mut body: FloatingBody) -> Result<()> {
        check_steppable(&body, self.bodies.len(), self.water_density)?;
        // Held until the next step: the current step's loads are evaluated already.
        body.release_time = body.release_time.max(Self::step_time(self.steps + 1));
        self.bodies.push(body);
        Ok(())
    }

    /// Back to t = 0: every body at its initial state.
    pub fn reset(&mut self) {
        for b in &mut self.bodies {
            b.state = b.initial;
            b.rests.clear();
        }
        self.steps = 0;
        self.loaded = false;
    }

    /// Steps to the last step at or before `t` (s, finite, >= 0), going back to t = 0 first if
    /// `t` is before the current step, and leaves the loads at that step evaluated, ready for
    /// [`FloatingBodies::poses_at`]. `env` is prepared at each step's time in increasing order.
    /// Fails, leaving the bodies at t = 0, if a body's state became non-finite.
    pub fn advance<E: BodyEnvironment>(&mut self, t: f64, env: &mut E) -> Result<()> {
        crate::limits::check_time("t", t)?;
        let target = Self::step_at(t.max(0.0));
        if self.bodies.is_empty() {
            // Nothing to step: the environment is left alone (no model advanced to step times).
            self.steps = target;
            self.loaded = true;
            return Ok(());
        }
        if target < self.steps {
            self.reset();
        }
        let dt = 1.0 / f64::from(BODY_STEP_HZ);
        loop {
            if !self.loaded {
                let ts = Self::step_time(self.steps);
                env.prepare(ts)?;
                let env = &*env;
                let rho = self.water_density;
                self.bodies.par_iter_mut().for_each(|b| b.evaluate(env, ts, rho, dt));
                let contacts = super::body_contact::contact_loads(&self.bodies, dt);
                for (b, c) in self.bodies.iter_mut().zip(contacts) {
                    if !b.held_at(ts) {
                        b.add_load(c);
                    }
                }
                self.loaded = true;
            }
            if self.steps >= target {
                return Ok(());
            }
            let now = Self::step_time(self.steps);
            let next =
                self.bodies.iter().map(|b| if b.held_at(now) { b.state } else { b.integrated(dt) }).collect::<Vec<_>>();
            if let Some((b, _)) = self.bodies.iter().zip(&next).find(|(_, s)| !state_is_finite(s)) {
                let name = b.name.clone();
                self.reset();
                return Err(Error::Unstable(format!(
                    "body \"{name}\" left the finite numbers at step {} ({:.4} s); check its mass, size and speed",
                    self.steps,
                    Self::step_time(self.steps)
                )));
            }
            for (b, s) in self.bodies.iter_mut().zip(next) {
                b.state = s;
            }
            self.steps += 1;
            self.loaded = false;
        }
    }

    /// Every body's pose at time `t` (s), which must lie in the step [`FloatingBodies::advance`]
    /// reached (from its time to the next step's): the last step's state moved on by the
    /// remainder under that step's loads. `None` if `t` is outside that step or the loads are not
    /// evaluated.
    pub fn poses_at(&self, t: f64) -> Option<Vec<BodyPose>> {
        let dt = t - Self::step_time(self.steps);
        if !self.loaded || !(-1e-6..1.0 / f64::from(BODY_STEP_HZ) + 1e-6).contains(&dt) {
            return None;
        }
        let now = Self::step_time(self.steps);
        Some(
            self.bodies
                .iter()
                .map(|b| {
                    let s = if dt > 0.0 && !b.held_at(now) { b.integrated(dt) } else { b.state };
                    BodyPose { position: s.position, rotation: s.orientation }
                })
                .collect(),
        )
    }
}

/// Refuses body `i` if it is so light for its size that, on water of density `rho` (kg/m³), it
/// would bob faster than the 120 Hz step can follow, naming `body[i].mass` and the least mass.
fn check_steppable(b: &FloatingBody, i: usize, rho: f64) -> Result<()> {
    let dt = 1.0 / f64::from(BODY_STEP_HZ);
    // The stiffest the water can be: its largest cross-section at the water line.
    let (lo, hi) = b.hull.bounds();
    let e = (hi - lo).as_dvec3();
    let area = (e.x * e.y).max(e.y * e.z).max(e.x * e.z);
    let omega = (rho * f64::from(crate::GRAVITY) * area / b.material.mass).sqrt();
    if omega * dt <= MAX_HEAVE_OMEGA_DT {
        return Ok(());
    }
    let least = rho * f64::from(crate::GRAVITY) * area * (dt / MAX_HEAVE_OMEGA_DT).powi(2);
    Err(Error::out_of_range(
        format!("body[{i}].mass"),
        format!("{:.4} kg", b.material.mass),
        format!(
            "[{least:.4}, inf) kg: lighter, \"{}\" would bob faster than the {BODY_STEP_HZ} Hz step follows (make it denser or larger)",
            b.name
        ),
    ))
}

fn state_is_finite(s: &super::BodyState) -> bool {
    s.position.is_finite() && s.orientation.is_finite() && s.velocity.is_finite() && s.angular_velocity.is_finite()
}
