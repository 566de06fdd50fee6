//! The noise panel (`model = "noise"`, paper 003 §1.1.1): drifting, evolving Perlin fBm. Every key
//! of [`NoiseParams`] is a widget.

use eframe::egui::Ui;
use swell::water::{NoiseParams, MAX_NOISE_OCTAVES};

use super::{fields, keys};

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
        keys::edits(
            "water",
            &["amplitude", "scale", "octaves", "persistence", "lacunarity", "drift", "evolution", "seed"],
        );
    });
    changed
}

#[cfg(test)]
mod tests {
    use glam::Vec2;
    use swell::scene::WaterModelSpec;

    use super::super::fields::MAX_SEED;
    use super::super::test_support::{commit, scene_with};
    use super::*;

    fn params(m: &mut WaterModelSpec) -> &mut NoiseParams {
        match m {
            WaterModelSpec::Noise(p) => p,
            other => panic!("not noise: {other:?}"),
        }
    }

    #[test]
    fn every_key_edits_saves_and_loads_and_bad_ones_are_refused() {
        let scene = scene_with("noise");
        let shown = commit(&scene, |m| {
            let p = params(m);
            (p.amplitude, p.scale, p.octaves, p.persistence, p.lacunarity) = (0.5, 12.0, 7, 0.6, 2.5);
            (p.drift, p.evolution, p.seed) = (Vec2::new(-0.5, 2.0), 0.4, MAX_SEED);
        })
        .unwrap();
        let WaterModelSpec::Noise(p) = &shown.water.as_ref().unwrap().model else { unreachable!() };
        assert_eq!((p.octaves, p.seed), (7, MAX_SEED));
        let e = commit(&shown, |m| params(m).octaves = 13).unwrap_err();
        assert_eq!(e, format!("water.octaves = 13 is outside [1, {MAX_NOISE_OCTAVES}]"));
        let e = commit(&shown, |m| params(m).lacunarity = 5.0).unwrap_err();
        assert_eq!(e, "water.lacunarity = 5 is outside [1, 4]");
    }
}
