//! The steep-sines panel (`model = "steep-sines"`, paper 003 §1.1.2's `A ((sin S + 1) / 2)^k`):
//! each wave's amplitude, spatial frequency, crest speed, direction and sharpness exponent k. The
//! list is [`super::wave_list`].

use std::f32::consts::TAU;

use eframe::egui::Ui;
use glam::Vec2;
use swell::water::{GerstnerWave, SteepSineWave, SteepSinesParams, MAX_STEEP_SINE_WAVES};
use swell::Result;

use super::wave_list::{self, cell, ListedWave, WaveListForm};

/// What the panel remembers between frames.
pub type SteepSinesForm = WaveListForm<SteepSineWave>;

/// Sharpness exponent k given to generated waves: paper 003's figures use small k; 2 narrows the
/// crests visibly without spikes.
pub const GENERATED_EXPONENT: f32 = 2.0;

impl ListedWave for SteepSineWave {
    const HEADERS: &'static [&'static str] = &["A m", "freq rad/m", "v m/s", "dir x", "dir z", "k"];
    const KEYS: &'static [&'static str] = &["amplitude", "frequency", "velocity", "direction", "exponent"];
    const MAX: usize = MAX_STEEP_SINE_WAVES;
    const ID: &'static str = "steep-sines";
    fn cells(&mut self, ui: &mut Ui) -> bool {
        cell(ui, &mut self.amplitude, 0.005)
            | cell(ui, &mut self.frequency, 0.005)
            | cell(ui, &mut self.velocity, 0.05)
            | cell(ui, &mut self.direction.x, 0.01)
            | cell(ui, &mut self.direction.y, 0.01)
            | cell(ui, &mut self.exponent, 0.05)
    }
    fn check(&self, key: &str) -> Result<()> {
        self.validate(key)
    }
    /// freq = 2 pi / L (the model's definition) and the wave's own speed.
    fn from_gerstner(w: GerstnerWave) -> Self {
        SteepSineWave {
            amplitude: w.amplitude,
            frequency: TAU / w.wavelength,
            velocity: w.speed,
            direction: w.direction,
            exponent: GENERATED_EXPONENT,
        }
    }
}

impl Default for WaveListForm<SteepSineWave> {
    fn default() -> Self {
        // A 20 m deep-water wave (freq 2 pi / 20, speed sqrt(g L / 2 pi)).
        WaveListForm::new(SteepSineWave {
            amplitude: 0.24,
            frequency: TAU / 20.0,
            velocity: 5.59,
            direction: Vec2::X,
            exponent: GENERATED_EXPONENT,
        })
    }
}

/// Shows the wave list; returns whether `p` changed.
pub fn show(ui: &mut Ui, p: &mut SteepSinesParams, form: &mut SteepSinesForm) -> bool {
    ui.label("Steep sines A ((sin S + 1) / 2)^k (paper 003 §1.1.2); freq = 2 pi / wavelength, k in [1, 64]");
    wave_list::show(ui, &mut p.waves, form)
}

#[cfg(test)]
mod tests {
    use swell::scene::WaterModelSpec;

    use super::super::test_support::{commit, scene_with};
    use super::*;

    fn params(m: &mut WaterModelSpec) -> &mut SteepSinesParams {
        match m {
            WaterModelSpec::SteepSines(p) => p,
            other => panic!("not steep sines: {other:?}"),
        }
    }

    #[test]
    fn the_wave_list_edits_save_and_load_and_bad_ones_are_refused() {
        let scene = scene_with("steep-sines");
        let mut form = SteepSinesForm::default();
        let shown = commit(&scene, |m| {
            let p = params(m);
            p.waves.clear();
            form.regenerate(&mut p.waves).unwrap();
            form.new_wave.exponent = 8.0;
            form.add_to(&mut p.waves).unwrap();
        })
        .unwrap();
        let WaterModelSpec::SteepSines(p) = &shown.water.as_ref().unwrap().model else { unreachable!() };
        assert_eq!(p.waves.len(), form.set.count as usize + 1);
        // A generated wave keeps its wavelength as freq = 2 pi / L and its speed.
        for w in &p.waves[..form.set.count as usize] {
            assert_eq!(w.exponent, GENERATED_EXPONENT);
            let l = TAU / w.frequency;
            assert!(l > 0.0 && w.velocity > 0.0);
        }
        let e = commit(&shown, |m| params(m).waves[0].exponent = 100.0).unwrap_err();
        assert_eq!(e, "water.waves[0].exponent = 100 is outside [1, 64]");
        form.new_wave.velocity = -1.0;
        let mut waves = p.waves.clone();
        assert!(form.add_to(&mut waves).is_err());
        assert!(form.message.as_deref().unwrap().contains(".velocity = -1"), "{:?}", form.message);
    }
}
