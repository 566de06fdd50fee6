//! The lights panel: each light's kind, direction or position, colour and intensity; add and
//! delete lights.

use eframe::egui::Ui;
use glam::Vec3;
use swell::scene::{Light, MAX_LIGHTS};

use super::{fields, keys};

/// A new directional light: the sun from behind the default camera's left shoulder.
pub const NEW_DIRECTIONAL: Light =
    Light::Directional { direction: Vec3::new(0.4, -0.6, 0.5), color: Vec3::ONE, intensity: 1.0 };

/// A new point light 20 m above the origin.
pub const NEW_POINT: Light = Light::Point { position: Vec3::new(0.0, 20.0, 0.0), color: Vec3::ONE, intensity: 400.0 };

/// The same light as the other kind, keeping colour and intensity (a point light becomes a sun
/// shining from its position towards the origin, and back).
pub fn switch_kind(light: &Light) -> Light {
    match *light {
        Light::Directional { direction, color, intensity } => {
            Light::Point { position: -direction.normalize_or(Vec3::NEG_Y) * 20.0, color, intensity }
        }
        Light::Point { position, color, intensity } => {
            Light::Directional { direction: -position.normalize_or(Vec3::Y), color, intensity }
        }
    }
}

/// Shows the light list; returns whether it changed.
pub fn show(ui: &mut Ui, lights: &mut Vec<Light>) -> bool {
    let mut changed = false;
    let mut delete = None;
    for (i, light) in lights.iter_mut().enumerate() {
        ui.push_id(i, |ui| {
            ui.horizontal(|ui| {
                ui.strong(format!("light[{i}]"));
                let directional = matches!(light, Light::Directional { .. });
                if ui.selectable_label(directional, "directional").clicked() && !directional
                    || ui.selectable_label(!directional, "point").clicked() && directional
                {
                    *light = switch_kind(light);
                    changed = true;
                }
                if ui.small_button("delete").clicked() {
                    delete = Some(i);
                }
            });
            fields::grid("light").show(ui, |ui| {
                let (v, label, color, intensity) = match light {
                    Light::Directional { direction, color, intensity } => (direction, "direction", color, intensity),
                    Light::Point { position, color, intensity } => (position, "position (m)", color, intensity),
                };
                changed |= fields::vec3(ui, label, v, 0.01);
                changed |= fields::color(ui, "colour", color);
                changed |= fields::number(ui, "intensity", intensity, 0.01, "");
            });
            // The kind buttons edit `type`; the vector is the direction or the position.
            let vector = if matches!(light, Light::Directional { .. }) { "direction" } else { "position" };
            keys::edits("light[]", &["type", vector, "color", "intensity"]);
        });
    }
    if let Some(i) = delete {
        lights.remove(i);
        changed = true;
    }
    ui.horizontal(|ui| {
        ui.add_enabled_ui(lights.len() < MAX_LIGHTS, |ui| {
            if ui.button("Add sun").clicked() {
                lights.push(NEW_DIRECTIONAL);
                changed = true;
            }
            if ui.button("Add point light").clicked() {
                lights.push(NEW_POINT);
                changed = true;
            }
        });
    });
    changed
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn new_lights_are_valid_and_switching_kind_keeps_colour_and_aim() {
        for l in [NEW_DIRECTIONAL, NEW_POINT] {
            l.validate("light[0]").unwrap();
            let s = switch_kind(&l);
            s.validate("light[0]").unwrap();
            // The switched light lights the origin from the same side.
            let (a, b) = (l.incident(Vec3::ZERO).to_light, s.incident(Vec3::ZERO).to_light);
            assert!(a.dot(b) > 0.999, "{a:?} {b:?}");
        }
    }
}
