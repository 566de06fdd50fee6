//! Where a frame's rendering time goes, pass by pass: what `swell bench realtime` reports beside
//! the frame rate (issue 33: the per-stage split) and what a profiler of one preset starts from.

use std::time::{Duration, Instant};

/// Wall time of each pass of the last [`super::Renderer::render_size`]. The water pass rasterizes
/// and shades in one deferred walk per band, so its raster and shading are one figure here (the
/// split between them is a profiler's: docs/PERFORMANCE.md).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RenderStages {
    /// The terrain, the land beyond it and the terrain's mirror image for the water.
    pub terrain: Duration,
    /// The unbounded sea's footprint filter over the world's rings (image-dependent only).
    pub sea_filter: Duration,
    /// The water surface: rasterized and shaded (deferred).
    pub water: Duration,
    /// The unbounded sea from the rings' edge to the horizon.
    pub far_field: Duration,
    /// The sky behind everything (and the depth clear before it).
    pub sky: Duration,
    /// Overlays and the supersampled frame's downsampling.
    pub finish: Duration,
}

impl RenderStages {
    /// The sum of the stages.
    pub fn total(&self) -> Duration {
        self.terrain + self.sea_filter + self.water + self.far_field + self.sky + self.finish
    }
}

/// Times consecutive stages: each [`Stopwatch::lap`] adds the time since the previous one (or since
/// the start) to a stage.
pub(crate) struct Stopwatch(Instant);

impl Stopwatch {
    /// Starts timing now.
    pub(crate) fn start() -> Self {
        Self(Instant::now())
    }

    /// Adds the time since the last lap to `stage`.
    pub(crate) fn lap(&mut self, stage: &mut Duration) {
        let now = Instant::now();
        *stage += now - self.0;
        self.0 = now;
    }
}
