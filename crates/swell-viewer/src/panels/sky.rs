//! The sky panel: the model (gradient or Preetham's physical sky), the gradient's horizon, zenith
//! and below-horizon colours (linear RGB, in the renderer's 20,000 cd/m² unit), the sun's angles,
//! the turbidity, the haze distance, whether the sun drives the first light, and the sun disc's
//! direction and angular size (its radiance follows from the sunlight).

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
        changed |= fields::member(ui, "model", &mut sky.model);
        changed |= fields::number(ui, "sun elevation [-10, 90]", &mut sky.sun_elevation_deg, 0.2, " deg");
        changed |= fields::number(ui, "sun azimuth from north (-Z) [0, 360)", &mut sky.sun_azimuth_deg, 0.5, " deg");
        changed |= fields::number(ui, "turbidity [1.7, 10]", &mut sky.turbidity, 0.05, "");
        changed |= fields::number(ui, "haze distance (0: off)", &mut sky.haze_distance, 5.0, " m");
        changed |= fields::flag(ui, "sun drives the first light", &mut sky.sun_drives_light);
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
    });
    keys::edits(
        "sky",
        &[
            "model",
            "sun_elevation_deg",
            "sun_azimuth_deg",
            "turbidity",
            "haze_distance",
            "sun_drives_light",
            "horizon",
            "zenith",
            "ground",
            "sun_direction",
            "sun_size_deg",
        ],
    );
    changed
}
