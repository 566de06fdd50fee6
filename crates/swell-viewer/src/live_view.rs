//! The central view: swell's CPU render of the world at the view's pixel size, handed to
//! [`crate::gl_view`] which uploads and blits it at the next paint.
//!
//! Rendering runs on the UI thread inside the scene's rayon pool (`render.threads`).

use std::path::Path;
use std::time::{Duration, Instant};

use eframe::egui::{self, Rect};
use swell::render::Renderer;
use swell::scene::{World, MAX_IMAGE_SIDE};
use swell::{Error, Result};

use crate::gl_view::GlView;

/// How long each stage of one frame took.
#[derive(Clone, Copy, Debug, Default)]
pub struct StageTimes {
    /// `World::update`.
    pub simulate: Duration,
    /// Rasterizing and encoding to RGBA8.
    pub render: Duration,
    /// Copying into the window's texture (the upload of the previous frame: it happens at paint).
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

/// Renderer, pixel buffers, on-screen texture and thread pool of the central view.
pub struct LiveView {
    renderer: Renderer,
    /// The buffer the next frame is encoded into; swapped with the shown one after each frame.
    rgba: Vec<u8>,
    size: [u32; 2],
    screen: GlView,
    pool: Option<(u32, rayon::ThreadPool)>,
    last: Option<FrameKey>,
}

impl Default for LiveView {
    fn default() -> Self {
        Self::new()
    }
}

impl LiveView {
    /// An empty view; buffers are allocated by the first frame.
    pub fn new() -> Self {
        Self {
            renderer: Renderer::new(),
            rgba: Vec::new(),
            size: [0, 0],
            screen: GlView::default(),
            pool: None,
            last: None,
        }
    }

    /// Whether a frame for `key` would differ from the one shown.
    pub fn is_stale(&self, key: &FrameKey) -> bool {
        self.last.as_ref() != Some(key)
    }

    /// Moves `world` to `key.time`, renders it at `key.size` (each side clamped to
    /// [1, `MAX_IMAGE_SIDE`]) with `threads` workers (0 = one per core), and queues the image for
    /// upload at the next paint.
    pub fn render(&mut self, world: &mut World, key: FrameKey, threads: u32) -> Result<StageTimes> {
        let [w, h] = key.size.map(|s| s.clamp(1, MAX_IMAGE_SIDE));
        self.ensure_pool(threads)?;
        let pool = &self.pool.as_ref().expect("ensure_pool built it").1;
        let (exposure, gamma) = (world.scene.render.exposure, world.scene.render.gamma);
        let (renderer, rgba) = (&mut self.renderer, &mut self.rgba);
        let mut times = StageTimes::default();
        pool.install(|| -> Result<()> {
            let t0 = Instant::now();
            world.update(key.time)?;
            let t1 = Instant::now();
            renderer.render_size(world, w, h).encode_rgba8(exposure, gamma, rgba);
            times.simulate = t1 - t0;
            times.render = t1.elapsed();
            Ok(())
        })?;
        let mut slot = self.screen.lock();
        std::mem::swap(&mut slot.pixels, &mut self.rgba);
        slot.mark_new([w, h]);
        times.upload = slot.last_upload;
        drop(slot);
        self.size = [w, h];
        self.last = Some(key);
        Ok(times)
    }

    /// Whether a frame has been rendered (and can be painted).
    pub fn has_frame(&self) -> bool {
        self.last.is_some()
    }

    /// Paints the newest frame into `rect` (points) of `painter`'s layer.
    pub fn paint(&self, painter: &egui::Painter, rect: Rect) {
        self.screen.paint(painter, rect);
    }

    /// Frees the on-screen texture (at exit).
    pub fn destroy(&self, gl: &eframe::glow::Context) {
        self.screen.destroy(gl);
    }

    /// Pixel size of the last frame.
    pub fn size(&self) -> [u32; 2] {
        self.size
    }

    /// Writes the last rendered frame (the view alone, at its pixel size) as PNG.
    pub fn save_png(&self, path: &Path) -> Result<()> {
        let slot = self.screen.lock();
        if slot.pixels.is_empty() {
            return Err(Error::invalid("screenshot", "nothing has been rendered yet"));
        }
        crate::files::write_screenshot(path, slot.size[0] as usize, slot.size[1] as usize, &slot.pixels)
    }

    /// Builds the pool for `threads` workers, only when the count changes.
    fn ensure_pool(&mut self, threads: u32) -> Result<()> {
        if self.pool.as_ref().map(|(n, _)| *n) != Some(threads) {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads as usize)
                .build()
                .map_err(|e| Error::invalid("render.threads", format!("cannot start {threads} threads: {e}")))?;
            self.pool = Some((threads, pool));
        }
        Ok(())
    }
}
