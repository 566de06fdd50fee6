//! The wave-set panel (`model = "wave-set"`, paper 000 §2.4): Gerstner waves drawn from a seeded
//! fan around the wind, wavelengths around a median, amplitudes at the median's ratio and speeds
//! from the dispersion relation. Every key of [`WaveSetParams`] is a widget; "next" on the seed
//! draws a new set with the same statistics.

use eframe::egui::Ui;
use swell::water::{WaveSetParams, MAX_GERSTNER_WAVES};

use super::{dispersion, fields};

/// Shows every key; returns whether `p` changed.
pub fn show(ui: &mut Ui, p: &mut WaveSetParams) -> bool {
    let mut changed = false;
    ui.label("Generated Gerstner wave set (paper 000 §2.4)");
    fields::grid("wave-set").show(ui, |ui| {
        changed |= fields::count(ui, &format!("waves [1, {MAX_GERSTNER_WAVES}]"), &mut p.count, 0.1);
        changed |= fields::number(ui, "wind direction (0 = +X, 90 = +Z)", &mut p.wind_direction_deg, 1.0, " deg");
        changed |= fields::number(ui, "spread, full fan [0, 360]", &mut p.spread_deg, 1.0, " deg");
        changed |= fields::number(ui, "median wavelength > 0", &mut p.median_wavelength, 0.1, " m");
        changed |= fields::number(ui, "median amplitude (2 pi A / L <= 1)", &mut p.median_amplitude, 0.005, " m");
        changed |= fields::number(ui, "steepness Q [0, 1]", &mut p.steepness, 0.01, "");
        changed |= dispersion::show(ui, &mut p.dispersion);
        changed |= fields::seed(ui, "seed", &mut p.seed);
    });
    changed
}
