//! What a rendered frame is and what it cost: the vocabulary the render thread, the screen and
//! the live view share. It sits below all three, so that none of them imports another for it.

use std::time::Duration;

/// How long each stage of one frame took.
#[derive(Clone, Copy, Debug, Default)]
pub struct StageTimes {
    /// `World::update` (and, after a scene change, following it), on the render thread.
    pub simulate: Duration,
    /// Rasterizing and encoding to RGBA8, on the render thread.
    pub render: Duration,
    /// Copying into the window's texture, at the paint that shows the frame (zero until then).
    pub upload: Duration,
}

/// What a frame was rendered from; a frame with the same key would be identical.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FrameKey {
    /// [`crate::editor::SceneEditor::revision`] of the scene.
    pub revision: u64,
    /// Simulation time, seconds.
    pub time: f64,
    /// Image size in pixels.
    pub size: [u32; 2],
}
