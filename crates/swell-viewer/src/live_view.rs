//! The central view: swell's CPU render of the world at the view's pixel size, uploaded as an egui
//! texture.
//!
//! Rendering runs on the UI thread inside the scene's rayon pool (`render.threads`): a 1280x720
//! sea takes 10-30 ms on two cores, so a worker thread would add latency and copies for little.

use std::path::Path;
use std::time::{Duration, Instant};

use eframe::egui::{self, ColorImage, TextureHandle, TextureOptions};
use swell::render::Renderer;
use swell::scene::{World, MAX_IMAGE_SIDE};
use swell::{Error, Result};

/// How long each stage of one frame took.
#[derive(Clone, Copy, Debug, Default)]
pub struct StageTimes {
    /// `World::update`.
    pub simulate: Duration,
    /// Rasterizing and encoding to RGBA8.
    pub render: Duration,
    /// Copying into the window's texture.
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

/// Renderer, pixel buffer, texture and thread pool of the central view.
pub struct LiveView {
    renderer: Renderer,
    rgba: Vec<u8>,
    size: [u32; 2],
    texture: Option<TextureHandle>,
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
        Self { renderer: Renderer::new(), rgba: Vec::new(), size: [0, 0], texture: None, pool: None, last: None }
    }

    /// Whether a frame for `key` would differ from the one shown.
    pub fn is_stale(&self, key: &FrameKey) -> bool {
        self.last.as_ref() != Some(key)
    }

    /// Moves `world` to `key.time`, renders it at `key.size` (each side clamped to
    /// [1, `MAX_IMAGE_SIDE`]) with `threads` workers (0 = one per core), and uploads the image.
    pub fn render(
        &mut self,
        ctx: &egui::Context,
        world: &mut World,
        key: FrameKey,
        threads: u32,
    ) -> Result<StageTimes> {
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
        let t2 = Instant::now();
        // Alpha is 255 everywhere, so premultiplied and straight alpha are the same bytes.
        let image = ColorImage::from_rgba_premultiplied([w as usize, h as usize], &self.rgba);
        match &mut self.texture {
            Some(t) => t.set(image, TextureOptions::NEAREST),
            None => self.texture = Some(ctx.load_texture("swell-view", image, TextureOptions::NEAREST)),
        }
        times.upload = t2.elapsed();
        self.size = [w, h];
        self.last = Some(key);
        Ok(times)
    }

    /// The texture of the last frame, if any.
    pub fn texture(&self) -> Option<&TextureHandle> {
        self.texture.as_ref()
    }

    /// Pixel size of the last frame.
    pub fn size(&self) -> [u32; 2] {
        self.size
    }

    /// Writes the last rendered frame (the view alone, at its pixel size) as PNG.
    pub fn save_png(&self, path: &Path) -> Result<()> {
        if self.rgba.is_empty() {
            return Err(Error::invalid("screenshot", "nothing has been rendered yet"));
        }
        crate::files::write_screenshot(path, self.size[0] as usize, self.size[1] as usize, &self.rgba)
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
