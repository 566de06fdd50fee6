//! Frame timings for the status line: frames per second and where the time goes.

use std::time::Duration;

/// Weight of the newest frame in the running averages (about the last 20 frames count).
const SMOOTHING: f64 = 0.05;

/// Frames ignored by the whole-run summary: the first frames pay for allocation and warm-up.
pub const WARMUP_FRAMES: u64 = 5;

/// Running averages of one frame's parts, in seconds.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FrameTimes {
    /// Wall-clock time between frames (1 / fps).
    pub frame: f64,
    /// [`swell::scene::World::update`]: moving the water.
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
    /// Frames recorded so far.
    pub frames: u64,
}

impl FrameStats {
    /// Records one rendered frame.
    pub fn record(&mut self, frame: Duration, simulate: Duration, render: Duration, upload: Duration) {
        let now = FrameTimes {
            frame: frame.as_secs_f64(),
            simulate: simulate.as_secs_f64(),
            render: render.as_secs_f64(),
            upload: upload.as_secs_f64(),
        };
        let a = if self.frames == 0 { 1.0 } else { SMOOTHING };
        let mix = |old: f64, new: f64| old + a * (new - old);
        self.recent = FrameTimes {
            frame: mix(self.recent.frame, now.frame),
            simulate: mix(self.recent.simulate, now.simulate),
            render: mix(self.recent.render, now.render),
            upload: mix(self.recent.upload, now.upload),
        };
        if self.frames >= WARMUP_FRAMES {
            self.total.frame += now.frame;
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
            frame: self.total.frame / n,
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
        for _ in 0..WARMUP_FRAMES {
            s.record(ms(500), ms(100), ms(300), ms(10));
        }
        assert_eq!(s.mean(), None);
        for _ in 0..10 {
            s.record(ms(25), ms(5), ms(15), ms(1));
        }
        let m = s.mean().unwrap();
        assert!((m.frame - 0.025).abs() < 1e-9 && (m.render - 0.015).abs() < 1e-9);
        assert!(m.line().starts_with("40.0 fps | sim 5.0 ms | render 15.0 ms"), "{}", m.line());
        assert!(s.fps() > 2.0 && s.fps() < 40.0);
    }
}
