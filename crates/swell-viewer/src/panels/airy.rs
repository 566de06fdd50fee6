//! The Airy panel (`model = "airy"`, paper 000 eqs. 2-3): linear waves, each with amplitude,
//! wavelength, direction and phase (speeds follow from the dispersion relation), and the
//! dispersion relation. The list is [`super::wave_list`].

use eframe::egui::Ui;
use glam::Vec2;
use swell::water::{AiryParams, AiryWave, GerstnerWave, MAX_AIRY_WAVES};
use swell::Result;

use super::wave_list::{self, cell, ListedWave, WaveListForm};
use super::{dispersion, fields};

/// What the panel remembers between frames.
pub type AiryForm = WaveListForm<AiryWave>;

impl ListedWave for AiryWave {
    const HEADERS: &'static [&'static str] = &["A m", "L m", "dir x", "dir z", "phase rad"];
    const KEYS: &'static [&'static str] = &["amplitude", "wavelength", "direction", "phase"];
    const MAX: usize = MAX_AIRY_WAVES;
    const ID: &'static str = "airy";
    fn cells(&mut self, ui: &mut Ui) -> bool {
        cell(ui, &mut self.amplitude, 0.005)
            | cell(ui, &mut self.wavelength, 0.1)
            | cell(ui, &mut self.direction.x, 0.01)
            | cell(ui, &mut self.direction.y, 0.01)
            | cell(ui, &mut self.phase, 0.01)
    }
    fn check(&self, key: &str) -> Result<()> {
        self.validate(key)
    }
    fn from_gerstner(w: GerstnerWave) -> Self {
        AiryWave { amplitude: w.amplitude, wavelength: w.wavelength, direction: w.direction, phase: 0.0 }
    }
}

impl Default for WaveListForm<AiryWave> {
    fn default() -> Self {
        WaveListForm::new(AiryWave { amplitude: 0.24, wavelength: 20.0, direction: Vec2::X, phase: 0.0 })
    }
}

/// Shows the model's keys and its wave list; returns whether `p` changed.
pub fn show(ui: &mut Ui, p: &mut AiryParams, form: &mut AiryForm) -> bool {
    let mut changed = false;
    ui.label("Airy waves (paper 000 eqs. 2-3); speeds follow from the dispersion relation");
    fields::grid("airy").show(ui, |ui| changed |= dispersion::show(ui, &mut p.dispersion));
    changed | wave_list::show(ui, &mut p.waves, form)
}

#[cfg(test)]
mod tests {
    use swell::scene::WaterModelSpec;
    use swell::spectrum::Dispersion;

    use super::super::test_support::{commit, scene_with};
    use super::*;

    fn params(m: &mut WaterModelSpec) -> &mut AiryParams {
        match m {
            WaterModelSpec::Airy(p) => p,
            other => panic!("not airy: {other:?}"),
        }
    }

    #[test]
    fn the_wave_list_and_dispersion_edit_save_and_load_and_bad_ones_are_refused() {
        let scene = scene_with("airy");
        let mut form = AiryForm::default();
        let shown = commit(&scene, |m| {
            let p = params(m);
            form.set.count = 6;
            form.regenerate(&mut p.waves).unwrap();
            p.waves[0].phase = -0.5;
            p.dispersion = dispersion::switch_dispersion(p.dispersion, "capillary");
        })
        .unwrap();
        let WaterModelSpec::Airy(p) = &shown.water.as_ref().unwrap().model else { unreachable!() };
        assert_eq!((p.waves.len(), p.waves[0].phase), (6, -0.5));
        assert!(matches!(p.dispersion, Dispersion::Capillary { .. }));
        let e = commit(&shown, |m| params(m).waves[3].wavelength = 0.0).unwrap_err();
        assert_eq!(e, "water.waves[3].wavelength = 0 is outside (0, inf)");
        let e = commit(&shown, |m| params(m).dispersion = Dispersion::FiniteDepth { depth: -2.0 }).unwrap_err();
        assert_eq!(e, "water.dispersion.depth = -2 is outside (0, inf)");
        form.new_wave.direction = Vec2::ZERO;
        assert!(form.add_to(&mut params(&mut shown.water.clone().unwrap().model).waves).is_err());
        assert!(form.message.as_deref().unwrap().starts_with("water.waves[6].direction"));
    }
}
