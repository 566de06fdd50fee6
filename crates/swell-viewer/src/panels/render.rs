//! The render panel: exposure (a factor, a camera's EV100 or metered per frame), the tone curve,
//! display gamma, ambient light, worker threads, supersampling, the overlays and the image size
//! `swell render` uses for this scene.

use eframe::egui::{DragValue, Ui};
use swell::math::ev100_of_exposure;
use swell::scene::RenderSettings;

use super::{fields, keys};

/// The display gamma offered when switching from the sRGB curve to a power law.
pub const DEFAULT_POWER_GAMMA: f32 = 2.2;

/// Shows the render settings; returns whether `render` changed.
pub fn show(ui: &mut Ui, render: &mut RenderSettings) -> bool {
    let mut changed = false;
    fields::grid("render").show(ui, |ui| {
        changed |= fields::number(ui, "exposure (x EV100 or auto)", &mut render.exposure, 0.01, "");
        // Switched on, EV100 starts where exposure alone was, so the picture does not jump.
        let unit_ev = ev100_of_exposure(1.0);
        let mut ev_changed = fields::optional_number(ui, "EV100 [-6, 24]", &mut render.ev100, unit_ev, 0.02, " EV");
        if ev_changed && render.ev100.is_some() {
            // EV100 and metering exclude each other (validation refuses both).
            render.auto_exposure = false;
        }
        if fields::flag(ui, "auto exposure (metered)", &mut render.auto_exposure) {
            if render.auto_exposure {
                render.ev100 = None;
            }
            ev_changed = true;
        }
        changed |= ev_changed;
        changed |= fields::member(ui, "tone curve", &mut render.tone_curve);
        ui.label("encoding");
        ui.horizontal(|ui| {
            let mut power = render.gamma.is_some();
            if ui.checkbox(&mut power, "power-law gamma").changed() {
                render.gamma = power.then_some(DEFAULT_POWER_GAMMA);
                changed = true;
            }
            match &mut render.gamma {
                Some(g) => changed |= ui.add(DragValue::new(g).speed(0.01).max_decimals(3)).changed(),
                None => {
                    ui.label("sRGB curve");
                }
            }
        });
        ui.end_row();
        changed |= fields::color(ui, "ambient", &mut render.ambient);
        changed |= fields::count(ui, "threads (0 = all cores)", &mut render.threads, 0.05);
        changed |= fields::count(ui, "supersample (N x N per pixel)", &mut render.supersample, 0.05);
        ui.label("saved image size");
        ui.horizontal(|ui| {
            changed |= ui.add(DragValue::new(&mut render.width).speed(4.0).suffix(" px")).changed();
            ui.label("x");
            changed |= ui.add(DragValue::new(&mut render.height).speed(4.0).suffix(" px")).changed();
        });
        ui.end_row();
        ui.label("overlays");
        ui.horizontal(|ui| {
            changed |= ui.checkbox(&mut render.wireframe, "wireframe (t)").changed();
            changed |= ui.checkbox(&mut render.normals, "normals (n)").changed();
        });
        ui.end_row();
    });
    keys::edits(
        "render",
        &[
            "exposure",
            "ev100",
            "auto_exposure",
            "tone_curve",
            "gamma",
            "ambient",
            "threads",
            "supersample",
            "width",
            "height",
            "wireframe",
            "normals",
        ],
    );
    ui.small("The view renders at the window's size; the saved size is what `swell render` uses.");
    changed
}
