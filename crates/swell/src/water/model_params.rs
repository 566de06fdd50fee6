//! What a wave model's parameters offer the scene: checks without building, the build itself, and
//! the facts a caller needs before building (memory, loop period, time steps).
//!
//! Each model implements [`ModelParams`] for its parameter type in its own file; the scene's table
//! of models (`scene/water_spec.rs`, one line per model) dispatches to it. So adding a model is its
//! file plus that line, and `Scene::validate` never builds a model to check it.

use super::WaveModel;
use crate::error::Result;

/// A surface that carries a sliding texture with its flow (paper 004's river): the renderer
/// slides the water's texture by `velocity t` and repeats it every `texture_length`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfaceFlow {
    /// Velocity of the surface in the model's own frame, [x, z] m/s.
    pub velocity: glam::Vec2,
    /// Length of one texture repeat in the model's own frame, metres, > 0.
    pub texture_length: f32,
}

/// A wave model's parameters as a scene holds them (`[water]` with `model = "..."`).
///
/// Keys are named under `water` in errors (`water.waves[2].speed`).
pub trait ModelParams {
    /// Checks every parameter against its range without building anything or allocating more than
    /// a few small values, so that a scene can be refused before any large allocation.
    fn validate(&self) -> Result<()>;

    /// Builds the model. Validates first, so an invalid set is refused the same way.
    fn build(&self) -> Result<Box<dyn WaveModel>>;

    /// Bytes the built model allocates for its own state (spectra, FFT buffers, lattices), beyond
    /// the surface mesh the scene counts; an estimate within a factor of 1.5. Assumes the
    /// parameters are valid. Default 0: closed-form models keep a few hundred bytes.
    fn estimate_bytes(&self) -> u64 {
        0
    }

    /// The period (s) after which the model repeats exactly, if it was given one.
    fn loop_period(&self) -> Option<f64> {
        None
    }

    /// A warning when the loop period is too short for the sea (`spectrum/loop_period.rs`), naming
    /// `water.loop_period`; `None` without a loop or when it fits. Assumes valid parameters.
    fn loop_warning(&self) -> Option<String> {
        None
    }

    /// Fixed time steps a time-stepped model takes from its start to reach time `t` (s), warm-up
    /// included; `None` for models that are functions of time.
    fn steps_to(&self, _t: f64) -> Option<f64> {
        None
    }

    /// The time (s) reached after `steps` fixed steps from the start, warm-up subtracted: the
    /// inverse of [`ModelParams::steps_to`]; `None` for models that are functions of time.
    fn time_after_steps(&self, _steps: f64) -> Option<f64> {
        None
    }

    /// Whether the model's surface is defined over the whole plane y = 0 (a closed form of (x, z),
    /// or cascades that tile), so that it can be an unbounded sea reaching the horizon
    /// (`[water] extent = "unbounded"`, the default for such models without terrain), or finite by
    /// nature (a pool, a lattice, a river between banks), which can only be a patch. Required,
    /// with no default: adding a model makes its author decide.
    fn defined_everywhere(&self) -> bool;

    /// Whether the built model keeps a state that a click or a stone can disturb
    /// ([`WaveModel::disturb`] returns true). Lets a caller decide without building the model.
    fn takes_disturbances(&self) -> bool {
        false
    }

    /// The flow that slides the water's texture, for models whose water visibly moves along the
    /// surface (the river); `None` (the default) for waves, whose water stays in place.
    fn surface_flow(&self) -> Option<SurfaceFlow> {
        None
    }
}
