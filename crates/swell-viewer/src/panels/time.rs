//! The time panel: play, pause, speed, single steps and the current simulation time.

use eframe::egui::{DragValue, Ui};

use super::fields;
use crate::clock::{Clock, MAX_SPEED};

/// Shows the clock controls; edits `clock` directly (time is not part of the scene file).
pub fn show(ui: &mut Ui, clock: &mut Clock) {
    ui.horizontal(|ui| {
        if ui.button(if clock.playing { "Pause (space)" } else { "Play (space)" }).clicked() {
            clock.toggle();
        }
        if ui.button("Step").on_hover_text("Advance by one step and pause").clicked() {
            clock.step_once();
        }
        if ui.button("Restart").on_hover_text("Back to t = 0").clicked() {
            clock.time = 0.0;
        }
    });
    fields::grid("time").show(ui, |ui| {
        ui.label("time");
        ui.label(format!("{:.2} s", clock.time));
        ui.end_row();
        ui.label("speed");
        ui.add(DragValue::new(&mut clock.speed).speed(0.01).range(0.0..=MAX_SPEED).suffix(" x"));
        ui.end_row();
        ui.label("step");
        ui.add(DragValue::new(&mut clock.step).speed(0.001).range(0.001..=10.0).suffix(" s"));
        ui.end_row();
    });
}
