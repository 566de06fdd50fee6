//! The radial wave panel (`model = "radial"`, paper 002): circular waves `a sin(k r - w t)` around
//! a centre. Every key of [`RadialWaveParams`] is a widget.

use eframe::egui::Ui;
use swell::water::RadialWaveParams;

use super::{fields, keys};

/// Shows every key; returns whether `p` changed.
pub fn show(ui: &mut Ui, p: &mut RadialWaveParams) -> bool {
    let mut changed = false;
    ui.label("Radial wave (paper 002); crests move outwards at w / k");
    fields::grid("radial").show(ui, |ui| {
        changed |= fields::vec2_xz(ui, "wave centre (m)", &mut p.center, 0.1);
        changed |= fields::number(ui, "amplitude a >= 0", &mut p.amplitude, 0.001, " m");
        changed |= fields::number(ui, "wavenumber k > 0", &mut p.wavenumber, 0.1, " rad/m");
        changed |= fields::number(ui, "angular frequency w >= 0", &mut p.angular_frequency, 0.05, " rad/s");
        keys::edits("water", &["wave_center", "amplitude", "wavenumber", "angular_frequency"]);
    });
    changed
}

#[cfg(test)]
mod tests {
    use glam::Vec2;
    use swell::scene::WaterModelSpec;

    use super::super::test_support::{commit, scene_with};
    use super::*;

    fn params(m: &mut WaterModelSpec) -> &mut RadialWaveParams {
        match m {
            WaterModelSpec::Radial(p) => p,
            other => panic!("not radial: {other:?}"),
        }
    }

    #[test]
    fn every_key_edits_saves_and_loads_and_bad_ones_are_refused() {
        let scene = scene_with("radial");
        let shown = commit(&scene, |m| {
            let p = params(m);
            (p.center, p.amplitude, p.wavenumber, p.angular_frequency) = (Vec2::new(-2.0, 5.0), 0.3, 0.5, 1.5);
        })
        .unwrap();
        let WaterModelSpec::Radial(p) = &shown.water.as_ref().unwrap().model else { unreachable!() };
        assert_eq!(p.center, Vec2::new(-2.0, 5.0));
        assert!(shown.to_toml().contains("wave_center"));
        let e = commit(&shown, |m| params(m).wavenumber = 0.0).unwrap_err();
        assert_eq!(e, "water.wavenumber = 0 is outside (0, inf)");
        let e = commit(&shown, |m| params(m).amplitude = -0.1).unwrap_err();
        assert!(e.starts_with("water.amplitude = -0.1 is outside [0"), "{e}");
    }
}
