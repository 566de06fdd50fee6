//! The sky panel: horizon, zenith and below-horizon colours (linear RGB).

use eframe::egui::Ui;
use swell::scene::Sky;

use super::fields;

/// Shows the sky colours; returns whether they changed.
pub fn show(ui: &mut Ui, sky: &mut Sky) -> bool {
    let mut changed = false;
    fields::grid("sky").show(ui, |ui| {
        changed |= fields::color(ui, "horizon", &mut sky.horizon);
        changed |= fields::color(ui, "zenith", &mut sky.zenith);
        changed |= fields::color(ui, "ground", &mut sky.ground);
    });
    changed
}
