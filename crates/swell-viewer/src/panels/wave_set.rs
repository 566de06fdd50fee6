//! The wave-set panel (`model = "wave-set"`, paper 000 §2.4): Gerstner waves drawn from a seeded
//! fan around the wind, wavelengths around a median, amplitudes at the median's ratio and speeds
//! from the dispersion relation. Every key of [`WaveSetParams`] is a widget; "next" on the seed
//! draws a new set with the same statistics.

use eframe::egui::Ui;
use swell::water::{WaveSetParams, MAX_GERSTNER_WAVES};

use super::{dispersion, fields, keys};

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
        keys::edits(
            "water",
            &[
                "count",
                "wind_direction_deg",
                "spread_deg",
                "median_wavelength",
                "median_amplitude",
                "steepness",
                "seed",
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

    fn params(m: &mut WaterModelSpec) -> &mut WaveSetParams {
        match m {
            WaterModelSpec::WaveSet(p) => p,
            other => panic!("not a wave set: {other:?}"),
        }
    }

    #[test]
    fn every_key_edits_saves_and_loads_and_bad_ones_are_refused() {
        let scene = scene_with("wave-set");
        let shown = commit(&scene, |m| {
            let p = params(m);
            (p.count, p.wind_direction_deg, p.spread_deg) = (20, 135.0, 90.0);
            (p.median_wavelength, p.median_amplitude, p.steepness, p.seed) = (35.0, 0.3, 0.4, 99);
            p.dispersion = dispersion::switch_dispersion(p.dispersion, "finite-depth");
        })
        .unwrap();
        let WaterModelSpec::WaveSet(p) = &shown.water.as_ref().unwrap().model else { unreachable!() };
        assert_eq!((p.count, p.seed), (20, 99));
        let e = commit(&shown, |m| params(m).count = 0).unwrap_err();
        assert_eq!(e, format!("water.count = 0 is outside [1, {MAX_GERSTNER_WAVES}]"));
        let e = commit(&shown, |m| params(m).spread_deg = 400.0).unwrap_err();
        assert_eq!(e, "water.spread_deg = 400 is outside [0, 360]");
    }
}
