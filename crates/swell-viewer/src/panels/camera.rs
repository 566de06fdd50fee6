//! The camera panel: eye, target, up, field of view and clip distances, and a reset to the scene's
//! own camera (`r`).

use eframe::egui::Ui;
use swell::scene::Camera;

use super::{fields, keys};

/// What the camera panel asks of the viewer beyond editing the draft.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct CameraRequest {
    /// "Reset" was clicked: return to the scene's camera.
    pub reset: bool,
}

/// Shows the camera; returns whether it changed and what else was asked.
pub fn show(ui: &mut Ui, camera: &mut Camera) -> (bool, CameraRequest) {
    let mut changed = false;
    fields::grid("camera").show(ui, |ui| {
        changed |= fields::vec3(ui, "eye (m)", &mut camera.eye, 0.1);
        changed |= fields::vec3(ui, "target (m)", &mut camera.target, 0.1);
        changed |= fields::vec3(ui, "up", &mut camera.up, 0.01);
        changed |= fields::number(ui, "vertical fov", &mut camera.fov_y_deg, 0.1, " deg");
        changed |= fields::number(ui, "near", &mut camera.near, 0.01, " m");
        changed |= fields::number(ui, "far", &mut camera.far, 1.0, " m");
    });
    keys::edits("camera", &["eye", "target", "up", "fov_y_deg", "near", "far"]);
    let reset = ui.button("Reset camera (r)").clicked();
    ui.small("Left drag orbits, right drag or wheel zooms, middle drag pans.");
    (changed, CameraRequest { reset })
}
