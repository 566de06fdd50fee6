//! The Gerstner panel (paper 000's wave list): edit each wave, delete one, clear, and add a wave
//! given its amplitude, wavelength, speed, direction and steepness.

use eframe::egui::{self, DragValue, RichText, Ui};
use glam::Vec2;
use swell::scene::GerstnerSpec;
use swell::water::{GerstnerWave, MAX_GERSTNER_WAVES};
use swell::{Error, Result};

/// What the panel remembers between frames: the "new wave" form and why the last add failed.
#[derive(Clone, Debug, PartialEq)]
pub struct GerstnerForm {
    /// The wave "Add wave" appends.
    pub new_wave: GerstnerWave,
    /// Why the last "Add wave" was refused.
    pub message: Option<String>,
}

impl Default for GerstnerForm {
    fn default() -> Self {
        // A 20 m deep-water wave: speed sqrt(g L / 2 pi) = 5.59 m/s, amplitude at paper 000's
        // median ratio A/L = 0.012.
        Self {
            new_wave: GerstnerWave {
                amplitude: 0.24,
                wavelength: 20.0,
                speed: 5.59,
                direction: Vec2::new(1.0, 0.0),
                steepness: 0.5,
            },
            message: None,
        }
    }
}

impl GerstnerForm {
    /// Appends the form's wave if it is valid and the list has room (paper 000 refuses negative
    /// amplitude, length or speed and steepness outside [0, 1]).
    pub fn add_to(&mut self, spec: &mut GerstnerSpec) -> Result<()> {
        let result = add_wave(spec, self.new_wave);
        self.message = result.as_ref().err().map(ToString::to_string);
        result
    }
}

/// Appends `wave` to the list, refusing an invalid wave or a full list.
pub fn add_wave(spec: &mut GerstnerSpec, wave: GerstnerWave) -> Result<()> {
    let key = format!("water.waves[{}]", spec.waves.len());
    if spec.waves.len() >= MAX_GERSTNER_WAVES {
        return Err(Error::out_of_range(
            "water.waves",
            format!("{} waves", spec.waves.len() + 1),
            format!("[0, {MAX_GERSTNER_WAVES}] waves"),
        ));
    }
    wave.validate(&key)?;
    spec.waves.push(wave);
    Ok(())
}

/// Shows the wave list and the add form; returns whether `spec` changed.
pub fn show(ui: &mut Ui, spec: &mut GerstnerSpec, form: &mut GerstnerForm) -> bool {
    let mut changed = false;
    ui.label(format!(
        "{} waves (at most {MAX_GERSTNER_WAVES}); direction is (x, z), Q the steepness",
        spec.waves.len()
    ));
    let mut delete = None;
    egui::Grid::new("gerstner-waves").striped(true).spacing([4.0, 2.0]).show(ui, |ui| {
        for h in ["#", "A m", "L m", "S m/s", "dir x", "dir z", "Q", ""] {
            ui.label(RichText::new(h).small());
        }
        ui.end_row();
        for (i, w) in spec.waves.iter_mut().enumerate() {
            ui.label(i.to_string());
            changed |= wave_row(ui, w);
            if ui.small_button("x").on_hover_text("Delete this wave").clicked() {
                delete = Some(i);
            }
            ui.end_row();
        }
    });
    if let Some(i) = delete {
        spec.waves.remove(i);
        changed = true;
    }
    ui.horizontal(|ui| {
        if ui.button("Clear").on_hover_text("Remove every wave (flat water)").clicked() && !spec.waves.is_empty() {
            spec.waves.clear();
            changed = true;
        }
    });
    ui.separator();
    ui.label("New wave");
    egui::Grid::new("gerstner-new").spacing([4.0, 2.0]).show(ui, |ui| {
        for h in ["A m", "L m", "S m/s", "dir x", "dir z", "Q"] {
            ui.label(RichText::new(h).small());
        }
        ui.end_row();
        wave_row(ui, &mut form.new_wave);
        ui.end_row();
    });
    if ui.button("Add wave").clicked() && form.add_to(spec).is_ok() {
        changed = true;
    }
    if let Some(m) = &form.message {
        ui.colored_label(ui.visuals().error_fg_color, m);
    }
    changed
}

/// One wave's six fields in table cells; returns whether any changed.
fn wave_row(ui: &mut Ui, w: &mut GerstnerWave) -> bool {
    let mut changed = false;
    let mut cell = |ui: &mut Ui, v: &mut f32, speed: f64| {
        changed |= ui.add(DragValue::new(v).speed(speed).max_decimals(4)).changed();
    };
    cell(ui, &mut w.amplitude, 0.005);
    cell(ui, &mut w.wavelength, 0.1);
    cell(ui, &mut w.speed, 0.05);
    cell(ui, &mut w.direction.x, 0.01);
    cell(ui, &mut w.direction.y, 0.01);
    cell(ui, &mut w.steepness, 0.01);
    changed
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn add_refuses_bad_waves_and_full_lists_with_the_reason() {
        let mut spec = GerstnerSpec::default();
        let mut form = GerstnerForm::default();
        form.add_to(&mut spec).unwrap();
        assert_eq!(spec.waves, vec![form.new_wave]);
        form.new_wave.steepness = 1.5;
        assert!(form.add_to(&mut spec).is_err());
        assert_eq!(form.message.as_deref(), Some("water.waves[1].steepness = 1.5 is outside [0, 1]"));
        assert_eq!(spec.waves.len(), 1);
        form.new_wave.steepness = 0.5;
        form.new_wave.wavelength = -1.0;
        assert!(form.add_to(&mut spec).unwrap_err().to_string().contains("wavelength = -1"));
        form.new_wave.wavelength = 10.0;
        while spec.waves.len() < MAX_GERSTNER_WAVES {
            form.add_to(&mut spec).unwrap();
        }
        assert!(form.add_to(&mut spec).unwrap_err().to_string().starts_with("water.waves = 65 waves"));
        assert_eq!(spec.waves.len(), MAX_GERSTNER_WAVES);
        form.add_to(&mut GerstnerSpec::default()).unwrap();
        assert_eq!(form.message, None);
    }
}
