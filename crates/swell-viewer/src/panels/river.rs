//! The river panel (`model = "river"`, paper 004): water flowing downstream (+Z) between two
//! oscillating banks, with optional ripples. Every key of [`RiverParams`] is a widget; the banks may
//! not touch (`left_offset + left_amplitude < right_offset - right_amplitude`), which validation
//! refuses with that reason.

use eframe::egui::Ui;
use swell::water::RiverParams;

use super::{fields, keys};

/// Shows every key, and the material's `texture` (the pattern that flows); returns whether `p`
/// or `texture` changed.
pub fn show(ui: &mut Ui, p: &mut RiverParams, texture: &mut Option<String>) -> bool {
    let mut changed = false;
    ui.label("River between oscillating banks (paper 004); flows towards +Z");
    fields::grid("river").show(ui, |ui| {
        changed |= fields::optional_text(ui, "flowing texture (off: streaks)", texture, "streaks");
        changed |= fields::number(ui, "flow speed", &mut p.flow_speed, 0.05, " m/s");
        changed |= fields::number(ui, "left bank mean x", &mut p.left_offset, 0.05, " m");
        changed |= fields::number(ui, "left bank swing >= 0", &mut p.left_amplitude, 0.01, " m");
        changed |= fields::number(ui, "right bank mean x", &mut p.right_offset, 0.05, " m");
        changed |= fields::number(ui, "right bank swing >= 0", &mut p.right_amplitude, 0.01, " m");
        changed |= fields::number(ui, "right bank phase lead", &mut p.right_phase, 0.01, " rad");
        changed |= fields::number(ui, "bank rate >= 0", &mut p.bank_rate, 0.01, " rad/s");
        changed |= fields::number(ui, "bank phase at t = 0", &mut p.bank_phase, 0.01, " rad");
        changed |= fields::number(ui, "bank wavenumber q >= 0", &mut p.bank_wavenumber, 0.01, " rad/m");
        changed |= fields::number(ui, "texture repeat length > 0", &mut p.texture_length, 0.05, " m");
        changed |= fields::number(ui, "ripple amplitude >= 0", &mut p.ripple_amplitude, 0.005, " m");
        changed |= fields::number(ui, "ripple wavelength > 0", &mut p.ripple_wavelength, 0.01, " m");
        keys::edits(
            "water",
            &[
                "flow_speed",
                "left_offset",
                "left_amplitude",
                "right_offset",
                "right_amplitude",
                "right_phase",
                "bank_rate",
                "bank_phase",
                "bank_wavenumber",
                "texture_length",
                "ripple_amplitude",
                "ripple_wavelength",
            ],
        );
    });
    changed
}

#[cfg(test)]
mod tests {
    use swell::scene::WaterModelSpec;

    use super::super::test_support::{commit, scene_with};
    use super::*;

    fn params(m: &mut WaterModelSpec) -> &mut RiverParams {
        match m {
            WaterModelSpec::River(p) => p,
            other => panic!("not river: {other:?}"),
        }
    }

    #[test]
    fn every_key_edits_saves_and_loads_and_touching_banks_are_refused() {
        let scene = scene_with("river");
        let shown = commit(&scene, |m| {
            let p = params(m);
            (p.flow_speed, p.left_offset, p.left_amplitude, p.right_offset, p.right_amplitude) =
                (1.5, -3.0, 0.4, 1.0, 0.3);
            (p.right_phase, p.bank_rate, p.bank_phase, p.bank_wavenumber) = (0.2, 0.8, 0.1, 0.5);
            (p.texture_length, p.ripple_amplitude, p.ripple_wavelength) = (3.0, 0.02, 0.5);
        })
        .unwrap();
        let WaterModelSpec::River(p) = &shown.water.as_ref().unwrap().model else { unreachable!() };
        assert_eq!((p.flow_speed, p.ripple_amplitude), (1.5, 0.02));
        let e = commit(&shown, |m| params(m).right_offset = -2.5).unwrap_err();
        assert!(e.contains("water.right_offset"), "{e}");
        let e = commit(&shown, |m| params(m).texture_length = 0.0).unwrap_err();
        assert_eq!(e, "water.texture_length = 0 is outside (0, inf)");
    }
}
