//! Floating bodies: rigid bodies riding the water as drawn (issue 34).
//!
//! A body is a closed hull ([`Hull`]: a box, sphere, capsule or an OBJ mesh) with a mass and an
//! inertia, moved in six degrees of freedom by gravity, the water's pressure and drag and the
//! ground's contacts ([`FloatingBody`]). The water acts through [`BodyEnvironment`], which the
//! world answers from the wave model that is drawn, so a body never floats on a copy of the
//! waves that drifts from the picture. [`FloatingBodies`] steps a scene's bodies together at
//! [`BODY_STEP_HZ`], so poses depend only on the time asked for.
//!
//! Data flow: [`BodySpec`] (a scene's `[[body]]`) -> [`Hull`] and [`MassProperties`] ->
//! [`FloatingBody`] -> per step, [`water_forces`] and [`ground_contact`] loads -> the integrated
//! [`BodyState`] -> [`BodyPose`] for renderers and files.

pub mod body_contact;
mod body_environment;
mod body_spec;
mod floating_bodies;
pub mod ground_contact;
mod hull;
#[cfg(test)]
mod physics_tests;
mod rigid_body;
pub mod water_forces;

pub use body_environment::{BodyEnvironment, ModelWater, StillWater};
pub use body_spec::{
    validate_bodies, BodyShape, BodySpec, BODY_DENSITY_RANGE, BODY_SIZE_RANGE_M, BOX_CELL_M, DEFAULT_BODY_DENSITY,
    MAX_BODIES, MAX_BODY_POSITION_M, MAX_BODY_SPEED,
};
pub use floating_bodies::{FloatingBodies, BODY_STEP_HZ, SEA_WATER_DENSITY, WATER_DENSITY_RANGE};
pub use hull::{Hull, MassProperties, MAX_HULL_TRIANGLES};
pub use rigid_body::{BodyMaterial, BodyPose, BodyState, FloatingBody, Load, LoadReport};
