//! The sum-of-sines panel (paper 000 §2.1, paper 003 §1.1.2): the same wave list as Gerstner,
//! without steepness.

use eframe::egui::{self, DragValue, RichText, Ui};
use glam::Vec2;
use swell::scene::SinesSpec;
use swell::water::{SineWave, MAX_SINE_WAVES};
use swell::{Error, Result};

/// What the panel remembers between frames: the "new wave" form and why the last add failed.
#[derive(Clone, Debug, PartialEq)]
pub struct SinesForm {
    /// The wave "Add wave" appends.
    pub new_wave: SineWave,
    /// Why the last "Add wave" was refused.
    pub message: Option<String>,
}

impl Default for SinesForm {
    fn default() -> Self {
        Self {
            new_wave: SineWave { amplitude: 0.24, wavelength: 20.0, speed: 5.59, direction: Vec2::new(1.0, 0.0) },
            message: None,
        }
    }
}

impl SinesForm {
    /// Appends the form's wave if it is valid and the list has room.
    pub fn add_to(&mut self, spec: &mut SinesSpec) -> Result<()> {
        let result = add_wave(spec, self.new_wave);
        self.message = result.as_ref().err().map(ToString::to_string);
        result
    }
}

/// Appends `wave`, refusing an invalid wave or a full list.
pub fn add_wave(spec: &mut SinesSpec, wave: SineWave) -> Result<()> {
    if spec.waves.len() >= MAX_SINE_WAVES {
        return Err(Error::out_of_range(
            "water.waves",
            format!("{} waves", spec.waves.len() + 1),
            format!("[0, {MAX_SINE_WAVES}] waves"),
        ));
    }
    wave.validate(&format!("water.waves[{}]", spec.waves.len()))?;
    spec.waves.push(wave);
    Ok(())
}

/// Shows the wave list and the add form; returns whether `spec` changed.
pub fn show(ui: &mut Ui, spec: &mut SinesSpec, form: &mut SinesForm) -> bool {
    let mut changed = false;
    ui.label(format!("{} waves (at most {MAX_SINE_WAVES}); direction is (x, z)", spec.waves.len()));
    let mut delete = None;
    egui::Grid::new("sine-waves").striped(true).spacing([4.0, 2.0]).show(ui, |ui| {
        for h in ["#", "A m", "L m", "S m/s", "dir x", "dir z", ""] {
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
    if ui.button("Clear").on_hover_text("Remove every wave (flat water)").clicked() && !spec.waves.is_empty() {
        spec.waves.clear();
        changed = true;
    }
    ui.separator();
    ui.label("New wave");
    egui::Grid::new("sine-new").spacing([4.0, 2.0]).show(ui, |ui| {
        for h in ["A m", "L m", "S m/s", "dir x", "dir z"] {
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

fn wave_row(ui: &mut Ui, w: &mut SineWave) -> bool {
    let mut changed = false;
    let mut cell = |ui: &mut Ui, v: &mut f32, speed: f64| {
        changed |= ui.add(DragValue::new(v).speed(speed).max_decimals(4)).changed();
    };
    cell(ui, &mut w.amplitude, 0.005);
    cell(ui, &mut w.wavelength, 0.1);
    cell(ui, &mut w.speed, 0.05);
    cell(ui, &mut w.direction.x, 0.01);
    cell(ui, &mut w.direction.y, 0.01);
    changed
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn add_refuses_bad_waves() {
        let mut spec = SinesSpec::default();
        let mut form = SinesForm::default();
        form.add_to(&mut spec).unwrap();
        form.new_wave.direction = Vec2::ZERO;
        assert!(form.add_to(&mut spec).is_err());
        assert!(form.message.as_deref().unwrap().starts_with("water.waves[1].direction"));
        assert_eq!(spec.waves.len(), 1);
    }
}
