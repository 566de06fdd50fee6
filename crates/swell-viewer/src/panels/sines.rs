//! The sum-of-sines panel (paper 000 §2.1, paper 003 §1.1.2): the same wave list as Gerstner
//! ([`super::wave_list`]), without steepness.

use eframe::egui::Ui;
use glam::Vec2;
use swell::scene::SinesSpec;
use swell::water::SineWave;

use super::wave_list::{self, WaveListForm};

/// What the panel remembers between frames.
pub type SinesForm = WaveListForm<SineWave>;

impl Default for WaveListForm<SineWave> {
    fn default() -> Self {
        WaveListForm::new(SineWave { amplitude: 0.24, wavelength: 20.0, speed: 5.59, direction: Vec2::new(1.0, 0.0) })
    }
}

/// Shows the wave list; returns whether `spec` changed.
pub fn show(ui: &mut Ui, spec: &mut SinesSpec, form: &mut SinesForm) -> bool {
    ui.label("Sum of sines (paper 000 §2.1)");
    wave_list::show(ui, &mut spec.waves, form)
}
