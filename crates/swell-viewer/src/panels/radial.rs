//! The radial wave panel (`model = "radial"`, paper 002): circular waves `a sin(k r - w t)` around
//! a centre. Every key of [`RadialWaveParams`] is a widget.

use eframe::egui::Ui;
use swell::water::RadialWaveParams;

use super::fields;

/// Shows every key; returns whether `p` changed.
pub fn show(ui: &mut Ui, p: &mut RadialWaveParams) -> bool {
    let mut changed = false;
    ui.label("Radial wave (paper 002); crests move outwards at w / k");
    fields::grid("radial").show(ui, |ui| {
        changed |= fields::vec2_xz(ui, "wave centre (m)", &mut p.center, 0.1);
        changed |= fields::number(ui, "amplitude a >= 0", &mut p.amplitude, 0.001, " m");
        changed |= fields::number(ui, "wavenumber k > 0", &mut p.wavenumber, 0.1, " rad/m");
        changed |= fields::number(ui, "angular frequency w >= 0", &mut p.angular_frequency, 0.05, " rad/s");
    });
    changed
}
