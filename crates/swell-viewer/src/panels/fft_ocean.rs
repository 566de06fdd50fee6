//! The FFT ocean panel (`model = "fft"`): spectrum, wind, fetch, depth, choppiness, spreading, grid,
//! patch size, cascades, seed, foam, loop period and the optional swell.
//!
//! Every key of [`FftOceanParams`] has a widget; values are refused by the same validation as a
//! scene file (the reason is shown at the top of the panel). The grid must be a power of two, so
//! it is a menu rather than a number.

use eframe::egui::Ui;
use swell::spectrum::Spreading;
use swell::water::{BlenderOcean, FftOceanParams, SwellParams, FFT_GRID_RANGE};

use super::{fields, keys, table_fields};

/// Depth (m) the panel starts from when `depth` is switched on; TMA's shallow-water effects show
/// below about a quarter of the peak wavelength.
pub const DEFAULT_DEPTH_M: f32 = 20.0;

/// Loop period (s) the panel starts from when looping is switched on.
pub const DEFAULT_LOOP_PERIOD_S: f32 = 60.0;

/// Grid sides the menu offers: every power of two in [`FFT_GRID_RANGE`].
pub fn grid_sides() -> Vec<u32> {
    let (lo, hi) = FFT_GRID_RANGE;
    (lo.trailing_zeros()..=hi.trailing_zeros()).map(|s| 1 << s).collect()
}

/// Shows every FFT ocean parameter; returns whether `p` changed.
pub fn show(ui: &mut Ui, p: &mut FftOceanParams) -> bool {
    let mut changed = false;
    ui.label("FFT ocean (paper 003 §1.2.2, after Tessendorf 2001)");
    fields::grid("fft-ocean").show(ui, |ui| {
        changed |= fields::member(ui, "spectrum", &mut p.spectrum);
        changed |= fields::number(ui, "wind speed U10", &mut p.wind_speed, 0.05, " m/s");
        changed |= fields::number(ui, "wind direction", &mut p.wind_direction_deg, 0.5, " deg");
        changed |= fields::number(ui, "fetch", &mut p.fetch_km, 1.0, " km");
        changed |= fields::optional_number(ui, "depth (off: deep)", &mut p.depth, DEFAULT_DEPTH_M, 0.1, " m");
        changed |= fields::number(ui, "peak enhancement gamma", &mut p.gamma, 0.01, "");
        changed |= fields::number(ui, "small-wave cutoff", &mut p.small_wave_cutoff, 0.001, " m");
        changed |= fields::number(ui, "choppiness", &mut p.choppiness, 0.01, "");
        // The named functions only: the others are set up by `[water.blender]`, never chosen.
        if let Spreading::Named(mut f) = p.spreading {
            if fields::member(ui, "spreading", &mut f) {
                p.spreading = f.into();
                changed = true;
            }
        }
        let sides: Vec<(u32, String)> = grid_sides().into_iter().map(|n| (n, format!("{n} x {n}"))).collect();
        let options: Vec<(u32, &str)> = sides.iter().map(|(n, s)| (*n, s.as_str())).collect();
        changed |= fields::choice(ui, "grid", &mut p.grid, &options);
        changed |= fields::number(ui, "patch size", &mut p.patch_size, 1.0, " m");
        changed |= fields::count(ui, "cascades", &mut p.cascades, 0.05);
        changed |= fields::flag(ui, "tile cascades (bakes tile)", &mut p.tile_cascades);
        changed |= fields::count(ui, "seed", &mut p.seed, 1.0);
        changed |= fields::optional_number(ui, "loop period", &mut p.loop_period, DEFAULT_LOOP_PERIOD_S, 0.5, " s");
        changed |= fields::flag(ui, "foam", &mut p.foam);
        keys::edits(
            "water",
            &[
                "spectrum",
                "wind_speed",
                "wind_direction_deg",
                "fetch_km",
                "depth",
                "gamma",
                "small_wave_cutoff",
                "choppiness",
                "spreading",
                "grid",
                "patch_size",
                "cascades",
                "tile_cascades",
                "seed",
                "loop_period",
                "foam",
            ],
        );
        if p.foam {
            changed |= fields::number(ui, "foam threshold (Jacobian)", &mut p.foam_threshold, 0.005, "");
            changed |= fields::number(ui, "foam fade", &mut p.foam_fade_s, 0.05, " s");
            keys::edits("water", &["foam_threshold", "foam_fade_s"]);
        }
        let mut has_swell = p.swell.is_some();
        if fields::flag(ui, "swell", &mut has_swell) {
            p.swell = has_swell.then(SwellParams::default);
            changed = true;
        }
        // The switch adds or removes the whole table.
        keys::edits("water", &["swell"]);
        if let Some(s) = &mut p.swell {
            changed |= fields::number(ui, "  swell height Hs", &mut s.height, 0.01, " m");
            changed |= fields::number(ui, "  swell period", &mut s.period, 0.05, " s");
            changed |= fields::number(ui, "  swell direction", &mut s.direction_deg, 0.5, " deg");
            changed |= fields::number(ui, "  swell spread s", &mut s.spread, 0.5, "");
            keys::edits("water.swell", &["height", "period", "direction_deg", "spread"]);
        }
        let mut has_blender = p.blender.is_some();
        if fields::flag(ui, "Blender's Ocean keys", &mut has_blender) {
            set_blender(p, has_blender);
            changed = true;
        }
        keys::edits("water", &["blender"]);
    });
    changed |= super::spectrum_tables::show(ui, p);
    if let Some(b) = &mut p.blender {
        ui.label("[water.blender]: Blender's names and meaning; they replace the sea keys above");
        let mut table = toml::Table::try_from(&*b).unwrap_or_default();
        let names: Vec<&str> = table.keys().map(String::as_str).collect();
        keys::edits("water.blender", &names);
        if table_fields::show(ui, "fft-blender", &mut table) {
            // Read back by the scene file's own parser; a key of the wrong type stays unchanged.
            if let Ok(edited) = toml::Value::Table(table).try_into::<BlenderOcean>() {
                *b = edited;
                changed = true;
            }
        }
    }
    changed
}

/// Switches `[water.blender]` on (Blender's defaults, with the sea keys it replaces put back to
/// their defaults, as a scene file must leave them) or off.
pub fn set_blender(p: &mut FftOceanParams, on: bool) {
    if !on {
        p.blender = None;
        return;
    }
    let d = FftOceanParams::default();
    *p = FftOceanParams {
        grid: d.grid,
        patch_size: d.patch_size,
        spectrum: d.spectrum,
        wind_speed: d.wind_speed,
        wind_direction_deg: d.wind_direction_deg,
        fetch_km: d.fetch_km,
        depth: d.depth,
        choppiness: d.choppiness,
        spreading: d.spreading,
        gamma: d.gamma,
        small_wave_cutoff: d.small_wave_cutoff,
        seed: d.seed,
        blender: Some(BlenderOcean::default()),
        ..p.clone()
    };
}

#[cfg(test)]
mod tests {
    use swell::scene::{preset, Scene, WaterModelSpec};
    use swell::spectrum::{SpectrumKind, SpreadingFunction};

    use super::*;

    #[test]
    fn the_menus_name_what_the_scene_format_reads() {
        let sides = grid_sides();
        assert_eq!((sides[0], *sides.last().unwrap()), FFT_GRID_RANGE);
        for n in sides {
            let p = FftOceanParams { grid: n, ..Default::default() };
            p.validate("water").unwrap();
        }
    }

    #[test]
    fn panel_edits_save_and_load_back_and_bad_ones_are_refused() {
        let mut scene = preset("ocean").unwrap();
        let WaterModelSpec::Fft(p) = &mut scene.water.as_mut().unwrap().model else { panic!("ocean is not fft") };
        p.depth = Some(DEFAULT_DEPTH_M);
        p.spectrum = SpectrumKind::Tma;
        p.loop_period = Some(DEFAULT_LOOP_PERIOD_S);
        p.swell = Some(SwellParams::default());
        p.spreading = Spreading::Named(SpreadingFunction::DonelanBanner);
        scene.validate().unwrap();
        assert_eq!(Scene::from_toml(&scene.to_toml(), "t").unwrap(), scene);
        // TMA without a depth is refused with the reason.
        let WaterModelSpec::Fft(p) = &mut scene.water.as_mut().unwrap().model else { unreachable!() };
        p.depth = None;
        let e = scene.water.as_ref().unwrap().model.build().err().unwrap().to_string();
        assert!(e.contains("depth"), "{e}");
    }
}
