//! The spring mesh panel (`model = "springs"`, paper 003 §1.1.3): mass m, spring constant c,
//! damping gamma and time step dt with the stability bound shown beside dt, the lattice, the
//! scheduled drops, and the size of the disturbance a click on the water drops.
//!
//! A time step at or above the bound is refused (by the model's own validation, with the bound in
//! the message) and the panel says so in red before the user even lets go of the value.

use eframe::egui::{self, Ui};
use swell::error::{check_non_negative, check_positive};
use swell::water::{DropSchedule, SpringMeshParams};
use swell::Result;

use super::{fields, keys};

/// What a click on the water drops, remembered between frames (not part of the scene).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ClickDrop {
    /// Depth of the dent at its centre, m, >= 0.
    pub depth: f32,
    /// Radius of the dent, m, > 0.
    pub radius: f32,
}

impl Default for ClickDrop {
    /// The springs preset's own drops (0.8 m deep, 1 m wide), a little shallower so clicks can be
    /// repeated without the lattice folding.
    fn default() -> Self {
        Self { depth: 0.5, radius: 1.0 }
    }
}

impl ClickDrop {
    /// Checks depth and radius, naming them as the panel shows them.
    pub fn validate(&self) -> Result<()> {
        check_non_negative("click drop depth", self.depth)?;
        check_positive("click drop radius", self.radius)
    }
}

/// The stability line shown under dt: `8 c dt^2 / m + 2 gamma dt / m` against its limit 4 (see
/// `swell::water::spring_mesh`), and whether dt is inside the bound.
pub fn stability(p: &SpringMeshParams) -> (String, bool) {
    let (m, c, g, dt) = (p.mass, p.stiffness, p.damping, p.time_step);
    let lhs = 8.0 * c * dt * dt / m + 2.0 * g * dt / m;
    let max = p.max_stable_time_step();
    let ok = m > 0.0 && c > 0.0 && dt > 0.0 && dt < max;
    let text = if m > 0.0 && c > 0.0 && g >= 0.0 {
        format!("8 c dt²/m + 2 γ dt/m = {lhs:.3} (stable below 4): dt < {max:.4} s")
    } else {
        "m and c must be > 0 and gamma >= 0".to_string()
    };
    (text, ok)
}

/// Shows every spring mesh parameter and the click-drop size; returns whether `p` changed.
pub fn show(ui: &mut Ui, p: &mut SpringMeshParams, click: &mut ClickDrop) -> bool {
    let mut changed = false;
    ui.label("Spring mesh (paper 003 §1.1.3)");
    fields::grid("springs").show(ui, |ui| {
        changed |= fields::number(ui, "mass m", &mut p.mass, 0.01, " kg");
        changed |= fields::number(ui, "spring constant c", &mut p.stiffness, 0.01, " N/m");
        changed |= fields::number(ui, "damping gamma", &mut p.damping, 0.001, " kg/s");
        changed |= fields::number(ui, "time step dt", &mut p.time_step, 0.001, " s");
        keys::edits("water", &["mass", "stiffness", "damping", "time_step"]);
    });
    let (text, ok) = stability(p);
    if ok {
        ui.small(text);
    } else {
        ui.colored_label(ui.visuals().error_fg_color, format!("unstable, refused: {text}"));
    }
    fields::grid("springs-lattice").show(ui, |ui| {
        ui.label("lattice cells");
        ui.horizontal(|ui| {
            for (c, name) in p.lattice.iter_mut().zip(["x ", "z "]) {
                changed |= ui.add(egui::DragValue::new(c).speed(1.0).prefix(name)).changed();
            }
        });
        ui.end_row();
        changed |= fields::number(ui, "spacing", &mut p.spacing, 0.005, " m");
        changed |= fields::number(ui, "rest length ratio", &mut p.rest_length_ratio, 0.005, "");
        changed |= fields::member(ui, "edges", &mut p.edges);
        changed |= fields::flag(ui, "vertical only", &mut p.vertical_only);
        changed |= fields::number(ui, "warm-up", &mut p.warm_up, 0.5, " s");
        keys::edits("water", &["lattice", "spacing", "rest_length_ratio", "edges", "vertical_only", "warm_up"]);
        let mut has_drops = p.drops.is_some();
        if fields::flag(ui, "scheduled drops", &mut has_drops) {
            p.drops = has_drops.then_some(DropSchedule { interval: 4.0, radius: 1.0, depth: 0.8, seed: 1 });
            changed = true;
        }
        // The switch adds or removes the whole table.
        keys::edits("water", &["drops"]);
        if let Some(d) = &mut p.drops {
            changed |= fields::number(ui, "  every", &mut d.interval, 0.05, " s");
            changed |= fields::number(ui, "  radius", &mut d.radius, 0.01, " m");
            changed |= fields::number(ui, "  depth", &mut d.depth, 0.01, " m");
            ui.label("  seed");
            changed |= ui.add(egui::DragValue::new(&mut d.seed)).changed();
            ui.end_row();
            keys::edits("water.drops", &["interval", "radius", "depth", "seed"]);
        }
    });
    ui.separator();
    ui.label("Click on the water to drop a disturbance:");
    fields::grid("springs-click").show(ui, |ui| {
        fields::number(ui, "depth", &mut click.depth, 0.01, " m");
        fields::number(ui, "radius", &mut click.radius, 0.01, " m");
    });
    if let Err(e) = click.validate() {
        ui.colored_label(ui.visuals().error_fg_color, e.to_string());
    }
    changed
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_stability_line_agrees_with_the_model_validation() {
        // Paper 003's table: m = 4, c = 7, gamma = 0.05, dt = 0.4 gives 2.25 < 4.
        let p = SpringMeshParams::default();
        let (text, ok) = stability(&p);
        assert!(ok && text.contains("2.250"), "{text}");
        p.validate("water").unwrap();
        for dt in [0.5, 0.6, 0.7, 0.75, 0.8, 1.0] {
            let q = SpringMeshParams { time_step: dt, ..p };
            assert_eq!(stability(&q).1, q.validate("water").is_ok(), "dt = {dt}");
        }
        let bad = SpringMeshParams { time_step: 1.0, ..p };
        let e = bad.validate("water").unwrap_err().to_string();
        assert!(e.starts_with("water.time_step = 1 is outside"), "{e}");
        assert!(!stability(&SpringMeshParams { mass: 0.0, ..p }).1);
    }

    #[test]
    fn click_drops_refuse_bad_sizes() {
        ClickDrop::default().validate().unwrap();
        assert!(ClickDrop { depth: -0.1, radius: 1.0 }.validate().unwrap_err().to_string().contains("depth"));
        assert!(ClickDrop { depth: 0.1, radius: 0.0 }.validate().unwrap_err().to_string().contains("radius"));
    }
}
