//! The rendered frame on screen: an RGBA8 texture copied to the window with one framebuffer
//! blit, inside egui's paint pass.
//!
//! Why not an egui texture: egui uploads images as sRGB textures and draws them with its general
//! shader, which per pixel decodes the texel to linear, re-encodes it with `pow(x, 1/2.4)` and
//! dithers. On Mesa's software OpenGL (llvmpipe) that shader, run over the 1280x720 view every
//! frame, cost about as much CPU as swell's own render (perf, `sea` preset: 47 % of the process
//! in llvmpipe's JIT code, see docs/PERFORMANCE.md). swell's bytes are already display-encoded,
//! so a plain RGBA8 texture blitted 1:1 shows the same pixels (egui's round trip gives them back
//! unchanged, up to its dithering) with no shading at all, and the upload is one
//! `glTexSubImage2D` straight from the render's buffer (no `ColorImage` conversion).

use std::sync::{Arc, Mutex, MutexGuard};
use std::time::{Duration, Instant};

use eframe::egui::{self, Rect};
use eframe::egui_glow;
use eframe::glow::{self, HasContext};

use crate::frame::StageTimes;

/// The newest frame and the GL objects that show it, shared with egui's paint callback.
#[derive(Default)]
pub struct FrameSlot {
    /// The newest frame, RGBA8, rows top first (alpha 255).
    pub pixels: Vec<u8>,
    /// Its size in pixels.
    pub size: [u32; 2],
    /// `pixels` changed since the last upload.
    dirty: bool,
    /// Simulation and render times of `pixels` while it waits for its upload.
    waiting: StageTimes,
    /// Frames uploaded and blitted since the last [`FrameSlot::take_shown`], oldest first: the
    /// frames the window really showed (what the status line counts).
    shown: Vec<ShownFrame>,
    /// Frames replaced before any paint showed them (never counted as shown).
    pub dropped: u64,
    gl: Option<GlObjects>,
}

/// A frame that reached the window: its stage times (upload included) and when it was shown.
#[derive(Clone, Copy, Debug)]
pub struct ShownFrame {
    /// Simulation and render (render thread) and upload (this paint) of this very frame.
    pub times: StageTimes,
    /// When its upload finished, at the paint that showed it.
    pub at: Instant,
}

/// Two textures used in turn: llvmpipe draws deferred, so writing the texture the previous
/// frame's blit reads would wait for that blit (measured: the upload took 12-18 ms instead of ~1).
struct GlObjects {
    textures: [glow::Texture; 2],
    fbos: [glow::Framebuffer; 2],
    sizes: [[u32; 2]; 2],
    /// The one holding the newest frame.
    current: usize,
}

impl FrameSlot {
    /// Marks `pixels` (of `size`, made in `times`) as a new frame to upload at the next paint. A
    /// frame still waiting for its paint is replaced unseen and counted in [`FrameSlot::dropped`].
    pub fn mark_new(&mut self, size: [u32; 2], times: StageTimes) {
        if self.dirty {
            self.dropped += 1;
        }
        self.size = size;
        self.dirty = true;
        self.waiting = times;
    }

    /// Whether a frame waits for its paint.
    pub fn is_waiting(&self) -> bool {
        self.dirty
    }

    /// The waiting frame was uploaded (taking `upload`) and is shown from `at` on.
    #[cfg(test)]
    fn uploaded(&mut self, upload: Duration, at: Instant) {
        record_upload(&mut self.dirty, &mut self.shown, self.waiting, upload, at);
    }

    /// The frames shown since the last call, oldest first.
    pub fn take_shown(&mut self) -> Vec<ShownFrame> {
        std::mem::take(&mut self.shown)
    }
}

/// Marks the waiting frame (of `waiting` times) as uploaded in `upload` and shown from `at` on.
/// Takes the slot's fields apart so that the draw can call it while holding its GL objects.
fn record_upload(dirty: &mut bool, shown: &mut Vec<ShownFrame>, waiting: StageTimes, upload: Duration, at: Instant) {
    debug_assert!(*dirty, "only a waiting frame is uploaded");
    *dirty = false;
    shown.push(ShownFrame { times: StageTimes { upload, ..waiting }, at });
}

/// A handle to the shared [`FrameSlot`]; cloning it shares the same slot.
#[derive(Clone, Default)]
pub struct GlView {
    slot: Arc<Mutex<FrameSlot>>,
}

impl GlView {
    /// Locks the slot (uncontended: the UI thread is its only user; the paint callback runs on it).
    pub fn lock(&self) -> MutexGuard<'_, FrameSlot> {
        self.slot.lock().unwrap_or_else(|poisoned| poisoned.into_inner())
    }

    /// Queues the paint of the newest frame into `rect` (points) of `painter`'s layer.
    pub fn paint(&self, painter: &egui::Painter, rect: Rect) {
        let slot = self.slot.clone();
        let callback = egui_glow::CallbackFn::new(move |info, painter| {
            let mut s = slot.lock().unwrap_or_else(|poisoned| poisoned.into_inner());
            // SAFETY: egui_glow calls this on the thread owning the current GL context, and
            // restores its own state (program, buffers, viewport) after the callback.
            unsafe { s.draw(painter.gl(), &info) };
        });
        painter.add(egui::PaintCallback { rect, callback: Arc::new(callback) });
    }

    /// Frees the GL objects (at exit, with the context still current).
    pub fn destroy(&self, gl: &glow::Context) {
        if let Some(o) = self.lock().gl.take() {
            for (fbo, texture) in o.fbos.into_iter().zip(o.textures) {
                // SAFETY: the objects were made on this context, which eframe keeps current at exit.
                unsafe {
                    gl.delete_framebuffer(fbo);
                    gl.delete_texture(texture);
                }
            }
        }
    }
}

impl FrameSlot {
    /// Uploads a new frame if there is one, then blits the texture over the callback's viewport.
    unsafe fn draw(&mut self, gl: &glow::Context, info: &egui::PaintCallbackInfo) {
        let [w, h] = self.size;
        if w == 0 || h == 0 || self.pixels.len() != (w * h * 4) as usize {
            return;
        }
        if self.gl.is_none() {
            let (Ok(t0), Ok(t1), Ok(f0), Ok(f1)) =
                (gl.create_texture(), gl.create_texture(), gl.create_framebuffer(), gl.create_framebuffer())
            else {
                return;
            };
            self.gl = Some(GlObjects { textures: [t0, t1], fbos: [f0, f1], sizes: [[0, 0]; 2], current: 1 });
        }
        let o = self.gl.as_mut().expect("made above");
        if self.dirty {
            let t0 = Instant::now();
            let i = 1 - o.current;
            let (texture, fbo) = (o.textures[i], o.fbos[i]);
            gl.bind_texture(glow::TEXTURE_2D, Some(texture));
            gl.pixel_store_i32(glow::UNPACK_ALIGNMENT, 4);
            let data = glow::PixelUnpackData::Slice(Some(&self.pixels));
            if o.sizes[i] != self.size {
                gl.tex_parameter_i32(glow::TEXTURE_2D, glow::TEXTURE_MIN_FILTER, glow::NEAREST as i32);
                gl.tex_parameter_i32(glow::TEXTURE_2D, glow::TEXTURE_MAG_FILTER, glow::NEAREST as i32);
                let (iw, ih) = (w as i32, h as i32);
                gl.tex_image_2d(
                    glow::TEXTURE_2D,
                    0,
                    glow::RGBA8 as i32,
                    iw,
                    ih,
                    0,
                    glow::RGBA,
                    glow::UNSIGNED_BYTE,
                    data,
                );
                gl.bind_framebuffer(glow::READ_FRAMEBUFFER, Some(fbo));
                gl.framebuffer_texture_2d(
                    glow::READ_FRAMEBUFFER,
                    glow::COLOR_ATTACHMENT0,
                    glow::TEXTURE_2D,
                    Some(texture),
                    0,
                );
                o.sizes[i] = self.size;
            } else {
                gl.tex_sub_image_2d(
                    glow::TEXTURE_2D,
                    0,
                    0,
                    0,
                    w as i32,
                    h as i32,
                    glow::RGBA,
                    glow::UNSIGNED_BYTE,
                    data,
                );
            }
            gl.bind_texture(glow::TEXTURE_2D, None);
            o.current = i;
            let now = Instant::now();
            record_upload(&mut self.dirty, &mut self.shown, self.waiting, now - t0, now);
        }
        let [w, h] = o.sizes[o.current];
        if w == 0 || h == 0 {
            return;
        }
        // Rows are stored top first and GL counts from the bottom: flip in the blit. A frame of
        // the previous view size (one frame after a resize) is stretched to the new viewport.
        let v = info.viewport_in_pixels();
        gl.bind_framebuffer(glow::READ_FRAMEBUFFER, Some(o.fbos[o.current]));
        gl.bind_framebuffer(glow::DRAW_FRAMEBUFFER, None);
        gl.blit_framebuffer(
            0,
            h as i32,
            w as i32,
            0,
            v.left_px,
            v.from_bottom_px,
            v.left_px + v.width_px,
            v.from_bottom_px + v.height_px,
            glow::COLOR_BUFFER_BIT,
            glow::NEAREST,
        );
        gl.bind_framebuffer(glow::FRAMEBUFFER, None);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_frames_a_paint_uploads_count_as_shown() {
        let ms = Duration::from_millis;
        let mut slot = FrameSlot::default();
        let t = |sim| StageTimes { simulate: ms(sim), render: ms(20), upload: Duration::ZERO };
        slot.mark_new([4, 4], t(1));
        slot.mark_new([4, 4], t(2)); // replaced before any paint: dropped, not shown
        assert_eq!(slot.dropped, 1);
        let at = Instant::now();
        slot.uploaded(ms(3), at);
        assert!(!slot.is_waiting());
        slot.mark_new([4, 4], t(5));
        slot.uploaded(ms(4), at + ms(30));
        let shown = slot.take_shown();
        assert_eq!(shown.len(), 2);
        assert_eq!((shown[0].times.simulate, shown[0].times.upload), (ms(2), ms(3)));
        assert_eq!((shown[1].times.simulate, shown[1].times.upload, shown[1].at - at), (ms(5), ms(4), ms(30)));
        assert!(slot.take_shown().is_empty());
    }
}
