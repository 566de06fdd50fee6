//! Simulation time: play, pause, speed and single steps, apart from the wall clock.

/// Longest wall-clock interval one frame may advance the simulation, seconds: after a stall (a
/// window drag, a slow rebuild) the water resumes where it was instead of jumping ahead.
pub const MAX_FRAME_DT: f64 = 0.1;

/// Fastest playback, as a multiple of real time.
pub const MAX_SPEED: f64 = 16.0;

/// The simulation clock the viewer drives [`swell::world::World::update`] with.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Clock {
    /// Simulation time, seconds.
    pub time: f64,
    /// Whether time advances with the wall clock.
    pub playing: bool,
    /// Simulation seconds per wall-clock second, in [0, [`MAX_SPEED`]]; negative would run the
    /// stateful models backwards, which they cannot do.
    pub speed: f64,
    /// Simulation seconds one press of "step" advances, in (0, 10].
    pub step: f64,
}

impl Default for Clock {
    fn default() -> Self {
        Self { time: 0.0, playing: true, speed: 1.0, step: 1.0 / 30.0 }
    }
}

impl Clock {
    /// Advances by `wall_dt` wall-clock seconds (clamped to [0, [`MAX_FRAME_DT`]]) times the speed,
    /// if playing. Returns whether the time changed.
    pub fn tick(&mut self, wall_dt: f64) -> bool {
        let dt = if wall_dt.is_finite() { wall_dt.clamp(0.0, MAX_FRAME_DT) } else { 0.0 };
        let speed = if self.speed.is_finite() { self.speed.clamp(0.0, MAX_SPEED) } else { 0.0 };
        if !self.playing || dt * speed == 0.0 {
            return false;
        }
        self.time += dt * speed;
        true
    }

    /// Advances by one step (whether playing or not) and pauses, as the papers' step button does.
    pub fn step_once(&mut self) {
        self.playing = false;
        let step = if self.step.is_finite() { self.step.clamp(1e-6, 10.0) } else { 1.0 / 30.0 };
        self.time += step;
    }

    /// Play if paused, pause if playing (the space key).
    pub fn toggle(&mut self) {
        self.playing = !self.playing;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn play_pause_speed_and_step() {
        let mut c = Clock::default();
        assert!(c.tick(0.05));
        assert_eq!(c.time, 0.05);
        c.speed = 2.0;
        c.tick(0.05);
        assert!((c.time - 0.15).abs() < 1e-12);
        c.toggle();
        assert!(!c.tick(0.05));
        assert!((c.time - 0.15).abs() < 1e-12);
        c.step = 0.5;
        c.step_once();
        assert!((c.time - 0.65).abs() < 1e-12);
        assert!(!c.playing);
    }

    #[test]
    fn stalls_and_bad_values_do_not_jump_or_poison_time() {
        let mut c = Clock::default();
        c.tick(5.0);
        assert_eq!(c.time, MAX_FRAME_DT);
        c.tick(f64::NAN);
        c.speed = f64::INFINITY;
        c.tick(0.01);
        c.speed = -3.0;
        c.tick(0.01);
        assert_eq!(c.time, MAX_FRAME_DT);
        c.step = f64::NAN;
        c.step_once();
        assert!(c.time.is_finite() && c.time > MAX_FRAME_DT);
    }
}
