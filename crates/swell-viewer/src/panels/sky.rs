//! The sky panel: horizon, zenith and below-horizon colours (linear RGB), and the sun disc's
//! direction, angular size and intensity.

use eframe::egui::Ui;
use glam::Vec3;
use swell::scene::Sky;

use super::{fields, keys};

/// The sun direction the panel starts from when its own direction is switched on (the direction
/// the sunlight travels: from high behind the default camera's left shoulder).
pub const DEFAULT_SUN_DIRECTION: Vec3 = Vec3::new(0.4, -0.6, 0.5);

/// Shows every `[sky]` key; returns whether `sky` changed.
pub fn show(ui: &mut Ui, sky: &mut Sky) -> bool {
    let mut changed = false;
    fields::grid("sky").show(ui, |ui| {
        changed |= fields::color(ui, "horizon", &mut sky.horizon);
        changed |= fields::color(ui, "zenith", &mut sky.zenith);
        changed |= fields::color(ui, "ground", &mut sky.ground);
        changed |= fields::optional_vec3(
            ui,
            "sun direction (off: first sun light)",
            &mut sky.sun_direction,
            DEFAULT_SUN_DIRECTION,
            0.01,
        );
        changed |= fields::number(ui, "sun size", &mut sky.sun_size_deg, 0.01, " deg");
        changed |= fields::number(ui, "sun intensity", &mut sky.sun_intensity, 0.1, "");
    });
    keys::edits("sky", &["horizon", "zenith", "ground", "sun_direction", "sun_size_deg", "sun_intensity"]);
    changed
}
