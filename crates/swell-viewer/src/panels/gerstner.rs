//! The Gerstner panel (paper 000's wave list): edit each wave, delete one, clear, add a wave given
//! its amplitude, wavelength, speed, direction and steepness, regenerate a seeded set. The list
//! itself is [`super::wave_list`], shared with the sum of sines.

use eframe::egui::Ui;
use glam::Vec2;
use swell::scene::GerstnerSpec;
use swell::water::GerstnerWave;

use super::wave_list::{self, WaveListForm};

/// What the panel remembers between frames.
pub type GerstnerForm = WaveListForm<GerstnerWave>;

impl Default for WaveListForm<GerstnerWave> {
    fn default() -> Self {
        // A 20 m deep-water wave: speed sqrt(g L / 2 pi) = 5.59 m/s, amplitude at paper 000's
        // median ratio A/L = 0.012.
        WaveListForm::new(GerstnerWave {
            amplitude: 0.24,
            wavelength: 20.0,
            speed: 5.59,
            direction: Vec2::new(1.0, 0.0),
            steepness: 0.5,
        })
    }
}

/// Shows the wave list; returns whether `spec` changed.
pub fn show(ui: &mut Ui, spec: &mut GerstnerSpec, form: &mut GerstnerForm) -> bool {
    ui.label("Gerstner waves (paper 000 §2.2); Q is the steepness");
    wave_list::show(ui, &mut spec.waves, form)
}
