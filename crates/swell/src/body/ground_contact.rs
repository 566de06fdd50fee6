//! A body meeting the ground: hull vertices below the terrain are pushed out by a stiff, damped
//! spring along the ground's normal, with Coulomb friction, so that a body runs aground on the
//! bed and rests on land instead of falling through.
//!
//! A penalty contact rather than an exact one: the spring is as stiff as a 120 Hz explicit step
//! allows (its frequency [`CONTACT_HZ`], critically damped), so a resting body sinks into the
//! ground by g / ω² (about 1 cm) and never bounces off it.

use glam::DVec3;

use super::rigid_body::Load;
use super::{BodyEnvironment, FloatingBody};

/// Natural frequency (Hz) of a body on its contact springs: well below the step's Nyquist rate
/// (60 Hz at 120 steps a second) so that the explicit step stays stable, high enough that a body
/// resting on the ground sinks only g / (2π · 5)² ≈ 1 cm into it.
pub const CONTACT_HZ: f64 = 5.0;

/// Horizontal distance (m) over which the ground's slope is measured for its normal.
const NORMAL_STEP_M: f32 = 0.1;

/// The ground's load on `body` at its current state over a step of `dt` seconds, and how many
/// hull vertices touch it. The hull's world vertices and the ground under each are those the
/// water's load of the same step sampled ([`super::water_forces::water_load`], evaluated first).
pub(super) fn ground_load<E: BodyEnvironment + ?Sized>(body: &FloatingBody, env: &E, dt: f64) -> (Load, u32) {
    let s = body.state;
    let mut load = Load::default();
    // First the touching vertices, so that the body's stiffness is shared among them.
    let touching: Vec<(DVec3, f64, DVec3)> = body
        .corners
        .iter()
        .zip(&body.grounds)
        .filter_map(|(corner, ground)| {
            let world = corner.position;
            let (x, z) = (world.x as f32, world.z as f32);
            let g = (*ground)?;
            let depth = f64::from(g) - world.y;
            (depth > 0.0).then(|| {
                let h = NORMAL_STEP_M;
                let slope = |a: Option<f32>, b: Option<f32>| match (a, b) {
                    (Some(a), Some(b)) => f64::from(a - b) / f64::from(2.0 * h),
                    _ => 0.0,
                };
                let dx = slope(env.ground_height(x + h, z), env.ground_height(x - h, z));
                let dz = slope(env.ground_height(x, z + h), env.ground_height(x, z - h));
                (world, depth, DVec3::new(-dx, 1.0, -dz).normalize())
            })
        })
        .collect();
    if touching.is_empty() {
        return (load, 0);
    }
    let n = touching.len() as f64;
    let m = body.material.mass;
    let spring = ContactSpring { mass: m, points: n, friction: body.material.friction, dt };
    for (point, depth, normal) in touching {
        let r = point - s.position;
        let v = s.velocity + s.angular_velocity.cross(r);
        // The vertical penetration, measured along the ground's normal.
        let f = spring.force(v, normal, depth * normal.y);
        load.force += f;
        load.torque += r.cross(f);
    }
    (load, n as u32)
}

/// A stiff, critically damped contact spring with Coulomb friction, its stiffness set by a mass
/// (kg, a body's or a pair's reduced mass) at [`CONTACT_HZ`] and shared among the `points`
/// touching at once; what the ground and body contacts both push with.
pub(super) struct ContactSpring {
    /// The mass the springs hold, kg.
    pub mass: f64,
    /// How many points touch (>= 1): each takes its share of the stiffness.
    pub points: f64,
    /// Coulomb friction coefficient.
    pub friction: f64,
    /// The step the force acts over, s.
    pub dt: f64,
}

impl ContactSpring {
    /// The force (N) on a point moving at `v` (m/s, relative to what it touches) that lies
    /// `depth` m inside it across the unit `normal` (pointing out): the spring and its damping
    /// along the normal, never pulling, and friction opposing the sliding, at most μ times the
    /// push and never more than stops the point's share of the mass within the step.
    pub fn force(&self, v: DVec3, normal: DVec3, depth: f64) -> DVec3 {
        let omega = std::f64::consts::TAU * CONTACT_HZ;
        let (k, c) = (self.mass * omega * omega / self.points, 2.0 * self.mass * omega / self.points);
        let vn = v.dot(normal);
        let push = (k * depth - c * vn).max(0.0);
        let mut f = normal * push;
        let slide = v - normal * vn;
        let speed = slide.length();
        if speed > 0.0 {
            f -= slide / speed * (self.friction * push).min(self.mass * speed / (self.points * self.dt));
        }
        f
    }
}
