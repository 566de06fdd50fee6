//! The noise panel (`model = "noise"`, paper 003 §1.1.1): drifting, evolving Perlin fBm. Every key
//! of [`NoiseParams`] is a widget.

use eframe::egui::Ui;
use swell::water::{NoiseParams, MAX_NOISE_OCTAVES};

use super::fields;

/// Shows every key; returns whether `p` changed.
pub fn show(ui: &mut Ui, p: &mut NoiseParams) -> bool {
    let mut changed = false;
    ui.label("Perlin noise waves (paper 003 §1.1.1)");
    fields::grid("noise").show(ui, |ui| {
        changed |= fields::number(ui, "amplitude A >= 0", &mut p.amplitude, 0.005, " m");
        changed |= fields::number(ui, "feature size s > 0", &mut p.scale, 0.1, " m");
        changed |= fields::count(ui, &format!("octaves [1, {MAX_NOISE_OCTAVES}]"), &mut p.octaves, 0.05);
        changed |= fields::number(ui, "persistence (0, 1]", &mut p.persistence, 0.01, "");
        changed |= fields::number(ui, "lacunarity [1, 4]", &mut p.lacunarity, 0.01, "");
        changed |= fields::vec2_xz(ui, "drift (m/s)", &mut p.drift, 0.05);
        changed |= fields::number(ui, "evolution >= 0", &mut p.evolution, 0.01, " cells/s");
        changed |= fields::seed(ui, "seed", &mut p.seed);
    });
    changed
}
