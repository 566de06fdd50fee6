//! One floating body: its hull, mass and state, the loads on it and the step that moves it.

use glam::{DMat3, DQuat, DVec3};

use super::{BodyEnvironment, Hull};
use crate::error::{Error, Result};

/// Position, orientation and velocities of a rigid body, world frame, `f64` so that 10⁵ steps do
/// not drift.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BodyState {
    /// Centre of mass, m.
    pub position: DVec3,
    /// Rotation from the body's frame to the world, unit.
    pub orientation: DQuat,
    /// Velocity of the centre of mass, m/s.
    pub velocity: DVec3,
    /// Angular velocity, rad/s, world axes.
    pub angular_velocity: DVec3,
}

/// Where a body is at a time: what renderers, exports and `bodies.json` read.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BodyPose {
    /// Centre of mass, world m.
    pub position: DVec3,
    /// Rotation from the body's frame to the world (unit quaternion).
    pub rotation: DQuat,
}

/// Mass and how the water and the ground act on a body.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BodyMaterial {
    /// Mass, kg, > 0.
    pub mass: f64,
    /// Inertia tensor about the centre of mass in the body's frame, kg·m², positive definite.
    pub inertia: DMat3,
    /// Pressure-drag coefficient of faces pushed into the water (dimensionless).
    pub drag: f64,
    /// Skin drag, N·s/m³: force per m² of wetted hull per m/s of relative speed.
    pub linear_drag: f64,
    /// Coulomb friction coefficient against the ground.
    pub friction: f64,
}

/// Force (N) and torque about the centre of mass (N·m), world frame.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Load {
    /// Force, N.
    pub force: DVec3,
    /// Torque, N·m.
    pub torque: DVec3,
}

impl std::ops::Add for Load {
    type Output = Load;

    /// Both loads acting together.
    fn add(self, other: Load) -> Load {
        Load { force: self.force + other.force, torque: self.torque + other.torque }
    }
}

impl std::ops::AddAssign for Load {
    fn add_assign(&mut self, other: Load) {
        *self = *self + other;
    }
}

/// What the last load evaluation found, for tests and overlays.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct LoadReport {
    /// Volume under the water surface, m³ (the vertical pressure force over ρ g on still water).
    pub submerged_volume: f64,
    /// Hull vertices touching the ground.
    pub ground_contacts: u32,
}

/// A rigid body on the water: hull in its frame (centre of mass at the origin), mass, state.
#[derive(Clone, Debug)]
pub struct FloatingBody {
    /// Name, unique among the bodies of a scene.
    pub name: String,
    /// The hull, m, in the body's frame with the centre of mass at the origin.
    pub hull: Hull,
    /// Mass, inertia and drag.
    pub material: BodyMaterial,
    inverse_inertia: DMat3,
    /// State at t = 0.
    pub initial: BodyState,
    /// State at the bodies' current step.
    pub state: BodyState,
    /// Time (s) before which the body is held still at its initial state (not moved by any
    /// force): a body dropped into a running scene (`[[body]] release_time`).
    pub release_time: f64,
    /// A force (N, world) applied at the centre of mass on top of the water's, the ground's and
    /// gravity's: a user pushing the body (the viewer's keys). Not part of the scene, so not
    /// deterministic across runs; zero by default.
    pub thrust: DVec3,
    /// Loads at the current state, once evaluated.
    pub(super) load: Load,
    /// What the last evaluation found.
    pub report: LoadReport,
    /// Per-vertex scratch reused every step (no allocation after the first).
    pub(super) corners: Vec<super::water_forces::Corner>,
    /// Per hull vertex, the ground height under it at the last step (`None` off the terrain), as
    /// the water's load sampled it for the ground's.
    pub(super) grounds: Vec<Option<f32>>,
    /// Largest distance (m) of a hull vertex from the centre of mass: the bounding sphere that
    /// finds contacts between bodies.
    pub(super) radius: f32,
    /// Half the diagonal (m) of the hull's box: the lever the drag's torque limit allows.
    pub(super) reach: f64,
    /// Per hull vertex, the rest point (water model's frame) of the water above it at the last
    /// step: where the next step's height query starts. NaN before the first step and after a
    /// reset, so a run from t = 0 repeats exactly.
    pub(super) rests: Vec<glam::Vec2>,
    /// The hull's face planes, for contacts with other bodies.
    pub(super) planes: super::body_contact::FacePlanes,
}

impl FloatingBody {
    /// A body from its parts; `key` names it in errors. Refuses a singular or non-finite inertia
    /// and a non-positive mass.
    pub fn new(name: String, hull: Hull, material: BodyMaterial, initial: BodyState, key: &str) -> Result<Self> {
        if !(material.mass > 0.0 && material.mass.is_finite()) {
            return Err(Error::out_of_range(format!("{key}.mass"), material.mass, "(0, inf) kg"));
        }
        let inverse_inertia = material.inertia.inverse();
        let det = material.inertia.determinant();
        if !(det > 0.0 && inverse_inertia.is_finite()) {
            return Err(Error::invalid(
                format!("{key}.inertia"),
                format!("{:?} is not positive definite", material.inertia),
            ));
        }
        Ok(Self {
            name,
            corners: Vec::with_capacity(hull.positions.len()),
            planes: super::body_contact::FacePlanes::of(&hull),
            rests: Vec::new(),
            grounds: Vec::with_capacity(hull.positions.len()),
            radius: hull.radius(),
            reach: {
                let (lo, hi) = hull.bounds();
                f64::from((hi - lo).length()) * 0.5
            },
            hull,
            material,
            inverse_inertia,
            initial,
            state: initial,
            release_time: 0.0,
            thrust: DVec3::ZERO,
            load: Load::default(),
            report: LoadReport::default(),
        })
    }

    /// The body's pose now (at its current step).
    pub fn pose(&self) -> BodyPose {
        BodyPose { position: self.state.position, rotation: self.state.orientation }
    }

    /// Evaluates the loads at the current state: gravity, the water's pressure and drag, the
    /// ground's contacts, with the environment at time `t` (s); `water_density` kg/m³, `dt` the
    /// step the loads will act over (s).
    pub(super) fn evaluate<E: BodyEnvironment + ?Sized>(&mut self, env: &E, t: f64, water_density: f64, dt: f64) {
        if self.held_at(t) {
            self.load = Load::default();
            self.report = LoadReport::default();
            return;
        }
        let gravity = DVec3::new(0.0, -f64::from(crate::GRAVITY) * self.material.mass, 0.0);
        // The water's first: it samples the hull's vertices and the ground under them.
        let water = super::water_forces::water_load(self, env, t, water_density, dt);
        let ground = super::ground_contact::ground_load(self, env, dt);
        self.report = LoadReport { submerged_volume: water.1, ground_contacts: ground.1 };
        self.load = Load {
            force: gravity + (water.0.force + ground.0.force + self.thrust),
            torque: water.0.torque + ground.0.torque,
        };
    }

    /// Adds `extra` to the load of the current state (another body's contact).
    pub(super) fn add_load(&mut self, extra: Load) {
        self.load += extra;
    }

    /// Whether the body is still held at time `t` (s): before its release time.
    pub fn held_at(&self, t: f64) -> bool {
        t < self.release_time
    }

    /// The inverse inertia tensor in world axes for `orientation`.
    pub(super) fn world_inverse_inertia(&self, orientation: DQuat) -> DMat3 {
        let r = DMat3::from_quat(orientation);
        r * self.inverse_inertia * r.transpose()
    }

    /// The inertia tensor in world axes for `orientation`.
    pub(super) fn world_inertia(&self, orientation: DQuat) -> DMat3 {
        let r = DMat3::from_quat(orientation);
        r * self.material.inertia * r.transpose()
    }

    /// The state `dt` seconds on under the current load: semi-implicit (symplectic) Euler, the
    /// velocities first and then the pose from the new velocities, with the rotation applied
    /// exactly for the new angular velocity (so the quaternion stays unit) and the gyroscopic
    /// term `ω × Iω` from the current state.
    pub(super) fn integrated(&self, dt: f64) -> BodyState {
        let s = &self.state;
        let velocity = s.velocity + self.load.force / self.material.mass * dt;
        let inertia = self.world_inertia(s.orientation);
        let gyro = s.angular_velocity.cross(inertia * s.angular_velocity);
        let angular_velocity =
            s.angular_velocity + self.world_inverse_inertia(s.orientation) * (self.load.torque - gyro) * dt;
        let orientation = (DQuat::from_scaled_axis(angular_velocity * dt) * s.orientation).normalize();
        BodyState { position: s.position + velocity * dt, orientation, velocity, angular_velocity }
    }

    /// Kinetic energy (J) at the current state: translation and rotation.
    pub fn kinetic_energy(&self) -> f64 {
        let s = &self.state;
        0.5 * self.material.mass * s.velocity.length_squared()
            + 0.5 * s.angular_velocity.dot(self.world_inertia(s.orientation) * s.angular_velocity)
    }
}
