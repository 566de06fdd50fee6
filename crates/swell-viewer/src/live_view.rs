//! The central view: swell's CPU render of the world at the view's pixel size, made on the
//! [`crate::render_thread`] one frame ahead and shown by [`crate::gl_view`] (upload and blit at
//! paint).
//!
//! Each UI frame [`LiveView::collect`]s the frame asked for by the previous UI frame (waiting for
//! it if the render is slower than the paint), hands it to the screen, and [`LiveView::request`]s
//! the next one, which is then rendered while egui paints.

use std::path::Path;

use eframe::egui::{self, Rect};
use swell::scene::Scene;
use swell::{Error, Result};

use crate::body_control::{BodyDrop, LiveBody, Push};
use crate::frame::{FrameKey, StageTimes};
use crate::gl_view::{GlView, ShownFrame};
use crate::render_thread::{Disturbance, RenderThread, Request};

/// The render thread, the frame on screen and the bookkeeping between them.
pub struct LiveView {
    /// Started by the first request (it needs the egui context to wake the UI).
    thread: Option<RenderThread>,
    screen: GlView,
    /// The buffer of the frame shown before the current one, lent to the next request.
    spare: Vec<u8>,
    /// Key of the last request (rendered or in flight).
    requested: Option<FrameKey>,
    /// Scene revision the render thread has.
    sent_revision: Option<u64>,
    in_flight: bool,
    shown: bool,
    disturbances: Vec<Disturbance>,
    /// Bodies to drop with the next request.
    drops: Vec<BodyDrop>,
    /// The push to send with every request until changed.
    push: Option<Push>,
    /// The bodies of the last frame received, until taken.
    bodies: Option<Vec<LiveBody>>,
    /// What became of the drops of the frames received, until taken.
    dropped: Vec<std::result::Result<swell::body::BodySpec, String>>,
}

impl Default for LiveView {
    fn default() -> Self {
        Self::new()
    }
}

impl LiveView {
    /// An empty view; the render thread starts with the first request.
    pub fn new() -> Self {
        Self {
            thread: None,
            screen: GlView::default(),
            spare: Vec::new(),
            requested: None,
            sent_revision: None,
            in_flight: false,
            shown: false,
            disturbances: Vec::new(),
            drops: Vec::new(),
            push: None,
            bodies: None,
            dropped: Vec::new(),
        }
    }

    /// Whether a frame for `key` would differ from the last one asked for: another key, or a drop
    /// waiting to be made (a paused view renders again to show it).
    pub fn is_stale(&self, key: &FrameKey) -> bool {
        self.requested.as_ref() != Some(key) || !self.drops.is_empty()
    }

    /// Whether a frame is being rendered.
    pub fn in_flight(&self) -> bool {
        self.in_flight
    }

    /// Takes the frame in flight, waiting for it, and queues it for the next paint. None if no
    /// frame was in flight; otherwise the scene revision it was asked for, and its simulation and
    /// render times (its upload is timed when a paint shows it: [`LiveView::take_shown`]) or why
    /// it failed (a scene that does not build, an unstable model).
    pub fn collect(&mut self) -> Option<(u64, Result<StageTimes>)> {
        if !self.in_flight {
            return None;
        }
        self.in_flight = false;
        // One frame is in flight at most: the last one requested.
        let revision = self.requested.as_ref().map_or(0, |k| k.revision);
        let Some(outcome) = self.thread.as_ref().and_then(RenderThread::receive) else {
            return Some((revision, Err(Error::invalid("view", "the render thread stopped"))));
        };
        Some((
            revision,
            match outcome {
                Ok(mut frame) => {
                    self.bodies = Some(std::mem::take(&mut frame.bodies));
                    self.dropped.append(&mut frame.dropped);
                    let mut slot = self.screen.lock();
                    // The frame goes on screen; the one it replaces (uploaded at the last paint)
                    // becomes the spare buffer of the next request.
                    std::mem::swap(&mut slot.pixels, &mut frame.pixels);
                    slot.mark_new(frame.size, frame.times);
                    self.spare = frame.pixels;
                    self.shown = true;
                    Ok(frame.times)
                }
                Err((e, buffer)) => {
                    self.spare = buffer;
                    Err(e)
                }
            },
        ))
    }

    /// Asks for the frame `key` of `scene` (which has revision `key.revision`) with `threads`
    /// workers (0 = one per core); `ctx` is woken when it is ready. Call [`LiveView::collect`]
    /// first: one frame is in flight at most.
    pub fn request(&mut self, ctx: &egui::Context, scene: &Scene, key: FrameKey, threads: u32) -> Result<()> {
        debug_assert!(!self.in_flight, "collect before requesting");
        if self.thread.is_none() {
            let ctx = ctx.clone();
            self.thread = Some(RenderThread::start(move || ctx.request_repaint())?);
        }
        let thread = self.thread.as_ref().expect("started above");
        let scene = (self.sent_revision != Some(key.revision)).then(|| Box::new(scene.clone()));
        let request = Request {
            key,
            scene,
            disturbances: std::mem::take(&mut self.disturbances),
            drops: std::mem::take(&mut self.drops),
            push: self.push,
            threads,
            buffer: std::mem::take(&mut self.spare),
        };
        if !thread.send(request) {
            return Err(Error::invalid("view", "the render thread stopped"));
        }
        self.sent_revision = Some(key.revision);
        self.requested = Some(key);
        self.in_flight = true;
        Ok(())
    }

    /// Frames requested or received that no paint has shown yet: the one in flight and the one
    /// waiting for its upload (0 to 2).
    pub fn pending(&self) -> u32 {
        u32::from(self.in_flight) + u32::from(self.screen.lock().is_waiting())
    }

    /// The frames the window showed (uploaded and blitted) since the last call, oldest first,
    /// with their own stage times and when each was shown.
    pub fn take_shown(&self) -> Vec<ShownFrame> {
        self.screen.lock().take_shown()
    }

    /// Forwards a click's dent to the render thread's world (applied before the next frame).
    pub fn disturb(&mut self, d: Disturbance) {
        self.disturbances.push(d);
    }

    /// Forwards a body to drop to the render thread's world (added before the next frame); what
    /// became of it comes back through [`LiveView::take_dropped`].
    pub fn drop_body(&mut self, d: BodyDrop) {
        self.drops.push(d);
    }

    /// Sets the push every following request carries (`None`: no body pushed).
    pub fn set_push(&mut self, push: Option<Push>) {
        self.push = push;
    }

    /// The bodies of the frame received since the last call, if one was.
    pub fn take_bodies(&mut self) -> Option<Vec<LiveBody>> {
        self.bodies.take()
    }

    /// What became of the drops of the frames received since the last call, oldest first: the
    /// spec the render thread's world added, or why it refused it.
    pub fn take_dropped(&mut self) -> Vec<std::result::Result<swell::body::BodySpec, String>> {
        std::mem::take(&mut self.dropped)
    }

    /// Whether a frame has been received (and can be painted).
    pub fn has_frame(&self) -> bool {
        self.shown
    }

    /// Paints the newest frame into `rect` (points) of `painter`'s layer.
    pub fn paint(&self, painter: &egui::Painter, rect: Rect) {
        self.screen.paint(painter, rect);
    }

    /// Frees the on-screen texture (at exit).
    pub fn destroy(&self, gl: &eframe::glow::Context) {
        self.screen.destroy(gl);
    }

    /// Pixel size of the frame on screen.
    pub fn size(&self) -> [u32; 2] {
        self.screen.lock().size
    }

    /// Writes the frame on screen (the view alone, at its pixel size) as PNG.
    pub fn save_png(&self, path: &Path) -> Result<()> {
        let slot = self.screen.lock();
        if slot.pixels.is_empty() {
            return Err(Error::invalid("screenshot", "nothing has been rendered yet"));
        }
        crate::files::write_screenshot(path, slot.size[0] as usize, slot.size[1] as usize, &slot.pixels)
    }
}
