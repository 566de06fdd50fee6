//! Frame timings for the status line: frames per second and where the time goes.
//!
//! Only frames the window really showed are recorded (the render thread made them and a paint
//! uploaded and blitted them, [`crate::gl_view::ShownFrame`]), each with its own simulation,
//! render and upload times; frames per second come from the time between two shown frames, not
//! from how often the UI repaints (egui repaints for the mouse, the panel and the screenshot too).

use std::time::Duration;

/// Weight of the newest frame in the running averages (about the last 20 frames count).
const SMOOTHING: f64 = 0.05;

/// Frames ignored by the whole-run summary: the first frames pay for allocation and warm-up.
pub const WARMUP_FRAMES: u64 = 5;

/// Running averages of one frame's parts, in seconds.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FrameTimes {
    /// Wall-clock time from one shown frame to the next (1 / fps).
    pub frame: f64,
    /// [`swell::world::World::update`]: moving the water.
    pub simulate: f64,
    /// `Renderer::render_size` and the RGBA8 encoding.
    pub render: f64,
    /// Copying the image into the window's texture.
    pub upload: f64,
}

/// Smoothed and whole-run frame timings.
#[derive(Clone, Debug, Default)]
pub struct FrameStats {
    /// Exponential running averages (what the status line shows).
    pub recent: FrameTimes,
    /// Sums over the frames after [`WARMUP_FRAMES`] (for the summary printed at exit).
    total: FrameTimes,
    /// Frames after warm-up that had a previous shown frame (the count of `total.frame`).
    intervals: u64,
    /// Shown frames recorded so far.
    pub frames: u64,
}

impl FrameStats {
    /// Records one shown frame: `interval` since the previous shown frame (None for the first),
    /// and this frame's own simulation, render and upload times.
    pub fn record(&mut self, interval: Option<Duration>, simulate: Duration, render: Duration, upload: Duration) {
        let now = FrameTimes {
            frame: interval.map_or(0.0, |d| d.as_secs_f64()),
            simulate: simulate.as_secs_f64(),
            render: render.as_secs_f64(),
            upload: upload.as_secs_f64(),
        };
        let first = self.frames == 0;
        let mix = |old: f64, new: f64, first: bool| if first { new } else { old + SMOOTHING * (new - old) };
        self.recent = FrameTimes {
            // The first interval starts the average; a frame without one leaves it alone.
            frame: match interval {
                Some(_) => mix(self.recent.frame, now.frame, self.recent.frame == 0.0),
                None => self.recent.frame,
            },
            simulate: mix(self.recent.simulate, now.simulate, first),
            render: mix(self.recent.render, now.render, first),
            upload: mix(self.recent.upload, now.upload, first),
        };
        if self.frames >= WARMUP_FRAMES {
            if interval.is_some() {
                self.total.frame += now.frame;
                self.intervals += 1;
            }
            self.total.simulate += now.simulate;
            self.total.render += now.render;
            self.total.upload += now.upload;
        }
        self.frames += 1;
    }

    /// Frames per second from the running average (0 before the first frame).
    pub fn fps(&self) -> f64 {
        if self.recent.frame > 0.0 {
            1.0 / self.recent.frame
        } else {
            0.0
        }
    }

    /// Mean timings over the frames after warm-up, if there were any.
    pub fn mean(&self) -> Option<FrameTimes> {
        let n = self.frames.checked_sub(WARMUP_FRAMES).filter(|&n| n > 0)? as f64;
        Some(FrameTimes {
            frame: if self.intervals > 0 { self.total.frame / self.intervals as f64 } else { 0.0 },
            simulate: self.total.simulate / n,
            render: self.total.render / n,
            upload: self.total.upload / n,
        })
    }
}

impl FrameTimes {
    /// One line: `31.2 fps | sim 2.1 ms | render 17.9 ms | upload 1.3 ms`.
    pub fn line(&self) -> String {
        let fps = if self.frame > 0.0 { 1.0 / self.frame } else { 0.0 };
        format!(
            "{fps:.1} fps | sim {:.1} ms | render {:.1} ms | upload {:.1} ms",
            self.simulate * 1e3,
            self.render * 1e3,
            self.upload * 1e3
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn averages_skip_warmup_and_fps_inverts_the_frame_time() {
        let ms = Duration::from_millis;
        let mut s = FrameStats::default();
        assert_eq!(s.mean(), None);
        s.record(None, ms(100), ms(300), ms(10));
        assert_eq!(s.fps(), 0.0, "one frame has no rate");
        for _ in 1..WARMUP_FRAMES {
            s.record(Some(ms(500)), ms(100), ms(300), ms(10));
        }
        assert_eq!(s.mean(), None);
        for _ in 0..10 {
            s.record(Some(ms(25)), ms(5), ms(15), ms(1));
        }
        let m = s.mean().unwrap();
        assert!((m.frame - 0.025).abs() < 1e-9 && (m.render - 0.015).abs() < 1e-9);
        assert!(m.line().starts_with("40.0 fps | sim 5.0 ms | render 15.0 ms"), "{}", m.line());
        assert!(s.fps() > 2.0 && s.fps() < 40.0);
        assert_eq!(s.frames, 10 + WARMUP_FRAMES);
    }

    /// The rate is that of shown frames, whatever the UI's repaint rate: 10 frames shown 50 ms
    /// apart are 20 fps, and the times are those of the frames themselves.
    #[test]
    fn fps_counts_shown_frames_not_repaints() {
        let ms = Duration::from_millis;
        let mut s = FrameStats::default();
        for k in 0..(WARMUP_FRAMES + 10) {
            s.record((k > 0).then(|| ms(50)), ms(10), ms(35), ms(1));
        }
        let m = s.mean().unwrap();
        assert!((1.0 / m.frame - 20.0).abs() < 1e-6, "{}", m.line());
        // A rate above 1 / (sim + render) would be impossible for one render thread.
        assert!(1.0 / m.frame <= 1.0 / (m.simulate + m.render));
        assert!((s.fps() - 20.0).abs() < 1e-6);
    }
}
