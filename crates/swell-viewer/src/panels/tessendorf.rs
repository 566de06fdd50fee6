//! The Tessendorf panel (`model = "tessendorf"`, paper 003 §1.2.1): Gerstner waves in Tessendorf's
//! form, each with amplitude, wavelength, direction and phase (speeds follow from the dispersion
//! relation), the dispersion relation and the optional loop period. The list is
//! [`super::wave_list`], shared with Gerstner and sines.

use std::f32::consts::TAU;

use eframe::egui::Ui;
use glam::Vec2;
use swell::water::{GerstnerWave, TessendorfParams, TessendorfWave, MAX_TESSENDORF_WAVES};
use swell::Result;

use super::wave_list::{self, cell, ListedWave, WaveListForm};
use super::{dispersion, fields, keys};

/// What the panel remembers between frames.
pub type TessendorfForm = WaveListForm<TessendorfWave>;

/// Loop period (s) the panel starts from when looping is switched on.
pub const DEFAULT_LOOP_PERIOD_S: f32 = 30.0;

impl ListedWave for TessendorfWave {
    const HEADERS: &'static [&'static str] = &["A m", "L m", "dir x", "dir z", "phase rad"];
    const KEYS: &'static [&'static str] = &["amplitude", "wavelength", "direction", "phase"];
    const MAX: usize = MAX_TESSENDORF_WAVES;
    const ID: &'static str = "tessendorf";
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
        TessendorfWave { amplitude: w.amplitude, wavelength: w.wavelength, direction: w.direction, phase: 0.0 }
    }
}

impl Default for WaveListForm<TessendorfWave> {
    fn default() -> Self {
        // A 20 m wave at paper 000's median ratio A/L = 0.012 (k A = 0.075).
        WaveListForm::new(TessendorfWave { amplitude: 0.24, wavelength: 20.0, direction: Vec2::X, phase: 0.0 })
    }
}

/// `sum k A` of the list, the quantity [`TessendorfParams::validate`] keeps at or below 1.
pub fn sum_ka(waves: &[TessendorfWave]) -> f32 {
    waves.iter().map(|w| TAU / w.wavelength * w.amplitude).sum()
}

/// Shows the model's keys and its wave list; returns whether `p` changed.
pub fn show(ui: &mut Ui, p: &mut TessendorfParams, form: &mut TessendorfForm) -> bool {
    let mut changed = false;
    ui.label("Tessendorf's Gerstner waves (paper 003 §1.2.1); speeds follow from the dispersion relation");
    fields::grid("tessendorf").show(ui, |ui| {
        changed |= dispersion::show(ui, &mut p.dispersion);
        changed |= fields::optional_number(
            ui,
            "loop period (off: none)",
            &mut p.loop_period,
            DEFAULT_LOOP_PERIOD_S,
            0.5,
            " s",
        );
    });
    keys::edits("water", &["loop_period"]);
    ui.label(format!("sum of k A = {:.3} (at most 1, or the surface folds)", sum_ka(&p.waves)));
    changed | wave_list::show(ui, &mut p.waves, form)
}

#[cfg(test)]
mod tests {
    use swell::scene::WaterModelSpec;
    use swell::spectrum::Dispersion;

    use super::super::test_support::{commit, scene_with};
    use super::*;

    fn params(m: &mut WaterModelSpec) -> &mut TessendorfParams {
        match m {
            WaterModelSpec::Tessendorf(p) => p,
            other => panic!("not tessendorf: {other:?}"),
        }
    }

    #[test]
    fn the_wave_list_and_keys_edit_save_and_load_and_bad_ones_are_refused() {
        let scene = scene_with("tessendorf");
        let mut form = TessendorfForm::default();
        let shown = commit(&scene, |m| {
            let p = params(m);
            form.add_to(&mut p.waves).unwrap();
            form.new_wave.direction = Vec2::new(0.3, 1.0);
            form.new_wave.phase = 1.2;
            form.add_to(&mut p.waves).unwrap();
            p.dispersion = dispersion::switch_dispersion(p.dispersion, "finite-depth");
            p.loop_period = Some(DEFAULT_LOOP_PERIOD_S);
        })
        .unwrap();
        let WaterModelSpec::Tessendorf(p) = &shown.water.as_ref().unwrap().model else { unreachable!() };
        assert_eq!((p.waves.len(), p.waves[1].phase), (2, 1.2));
        assert_eq!(p.dispersion, Dispersion::FiniteDepth { depth: dispersion::DEFAULT_DEPTH_M });
        // A regenerated set is a valid Tessendorf list (speeds come from the dispersion relation).
        commit(&shown, |m| form.regenerate(&mut params(m).waves).unwrap()).unwrap();
        // One wave that loops is refused when added, naming its key ...
        form.new_wave.amplitude = 5.0;
        let mut waves = p.waves.clone();
        assert!(form.add_to(&mut waves).is_err());
        assert!(form.message.as_deref().unwrap().starts_with("water.waves[2].amplitude = 5 is outside"));
        // ... and a list that folds as a whole is refused on commit, naming the list.
        let e = commit(&shown, |m| {
            let w = &mut params(m).waves;
            for x in w.iter_mut() {
                x.amplitude = 0.9 * x.wavelength / TAU;
            }
        })
        .unwrap_err();
        assert!(e.starts_with("water.waves = sum of k A"), "{e}");
        let e = commit(&shown, |m| params(m).loop_period = Some(-1.0)).unwrap_err();
        assert_eq!(e, "water.loop_period = -1 is outside (0, inf)");
    }
}
