//! The water panel: which model (or none), the patch and its grid resolution, the material, and
//! the patch's transform ([`super::water_transform`]) and the active model's own panel.
//!
//! Adding a model's panel: write `panels/<model>.rs` with `show(ui, &mut <Model>Spec, &mut
//! <Model>Form) -> bool`, add its form to [`super::PanelState`] and one arm to the `match` in
//! [`show`]; the compiler points at the match when a new `WaterModelSpec` variant arrives.

use eframe::egui::{self, Ui};
use swell::scene::{
    GerstnerSpec, SinesSpec, WaterExtent, WaterMaterial, WaterModelSpec, WaterSpec, WaterSurface, LOD_RING_CELLS,
    LOD_SPACING_M, MAX_LOD_LEVELS, WATER_MODELS,
};
use swell::water::{GerstnerWave, SineWave};
use swell::{Error, Result};

use super::{airy, fft_ocean, fields, gerstner, noise, radial, river, sines, springs, steep_sines, tessendorf};
use super::{keys, water_transform, wave_set, PanelState};

/// The water with its model switched to `name` (one of [`WATER_MODELS`]), keeping the patch and
/// material. Between Gerstner and sines the wave list carries over (a sine wave is a Gerstner wave
/// of steepness 0, so that direction changes nothing on screen); any other model starts from its
/// defaults.
pub fn switch_model(water: Option<&WaterSpec>, name: &str) -> Result<WaterSpec> {
    let (surface, material, density) = match water {
        Some(w) => (w.surface, w.material.clone(), w.density),
        None => (WaterSurface::default(), WaterMaterial::default(), swell::body::SEA_WATER_DENSITY),
    };
    if let Some(w) = water {
        if w.model.name() == name {
            return Ok(w.clone());
        }
        match (&w.model, name) {
            (WaterModelSpec::Gerstner(g), "sines") => {
                let waves = g
                    .waves
                    .iter()
                    .map(|w| SineWave {
                        amplitude: w.amplitude,
                        wavelength: w.wavelength,
                        speed: w.speed,
                        direction: w.direction,
                    })
                    .collect();
                return Ok(WaterSpec { surface, material, model: WaterModelSpec::Sines(SinesSpec { waves }), density });
            }
            (WaterModelSpec::Sines(s), "gerstner") => {
                let waves = s
                    .waves
                    .iter()
                    .map(|w| GerstnerWave {
                        amplitude: w.amplitude,
                        wavelength: w.wavelength,
                        speed: w.speed,
                        direction: w.direction,
                        steepness: 0.0,
                    })
                    .collect();
                return Ok(WaterSpec {
                    surface,
                    material,
                    model: WaterModelSpec::Gerstner(GerstnerSpec { waves }),
                    density,
                });
            }
            _ => {}
        }
    }
    if !WATER_MODELS.contains(&name) {
        return Err(Error::invalid(
            "water.model",
            format!("\"{name}\" is not a model; valid: {}", WATER_MODELS.join(", ")),
        ));
    }
    // Any other model: its defaults, read through the scene-file parser like a `[water]` table
    // that names only the model, the patch and the material.
    let base = WaterSpec { surface, material, model: WaterModelSpec::Gerstner(Default::default()), density };
    let mut table = toml::Table::new();
    for (k, v) in base.to_table() {
        if matches!(k.as_str(), "size" | "cells" | "center" | "material") {
            table.insert(k, v);
        }
    }
    table.insert("model".into(), toml::Value::String(name.into()));
    let mut w = WaterSpec::from_table(table, "viewer")?;
    // The whole patch carries over, whatever keys it has (placement included), except an extent
    // the new model cannot have (an unbounded sea switched to the finite spring lattice): it goes
    // back to automatic rather than refusing the switch.
    w.surface = surface;
    w.density = density;
    if w.surface.extent.is_some_and(|e| e.validate(&w.model).is_err()) {
        w.surface.extent = None;
    }
    Ok(w)
}

/// Bottom depth (m) the panel starts from when the flat bottom is switched on.
pub const DEFAULT_BOTTOM_DEPTH_M: f32 = 5.0;

/// Wind speed (m/s) the panel starts from when the glitter's own wind is switched on.
pub const DEFAULT_GLITTER_WIND_MS: f32 = 7.0;

/// Shows every `[water.material]` key; returns whether `m` changed.
pub fn show_material(ui: &mut Ui, m: &mut WaterMaterial) -> bool {
    let mut changed = false;
    fields::grid("water-material").show(ui, |ui| {
        changed |= fields::color(ui, "colour", &mut m.color);
        changed |= fields::member(ui, "shading", &mut m.shading);
        changed |= fields::number(ui, "refractive index", &mut m.refractive_index, 0.001, "");
        changed |= fields::member(ui, "glitter", &mut m.glitter);
        changed |= fields::number(ui, "specular", &mut m.specular, 0.01, "");
        changed |= fields::number(ui, "shininess (lobe)", &mut m.shininess, 1.0, "");
        changed |= fields::optional_number(
            ui,
            "wind speed (off: the model's)",
            &mut m.wind_speed,
            DEFAULT_GLITTER_WIND_MS,
            0.05,
            " m/s",
        );
        changed |= fields::rgb_numbers(ui, "absorption", &mut m.absorption, 0.001, " /m");
        changed |= fields::optional_number(
            ui,
            "bottom depth (off: deep)",
            &mut m.bottom_depth,
            DEFAULT_BOTTOM_DEPTH_M,
            0.05,
            " m",
        );
        changed |= fields::color(ui, "bottom colour", &mut m.bottom_color);
        changed |= fields::color(ui, "foam colour", &mut m.foam_color);
        changed |= fields::optional_text(ui, "foam texture (procedural or a file)", &mut m.foam_texture, "procedural");
        changed |= fields::number(ui, "foam scale", &mut m.foam_scale, 0.05, " m");
        changed |= fields::number(ui, "foam feather", &mut m.foam_feather, 0.005, "");
        changed |= fields::number(ui, "foam streaks (along the wind)", &mut m.foam_streak, 0.05, "");
        changed |= fields::color(ui, "scatter colour", &mut m.scatter_color);
        changed |= fields::number(ui, "scatter strength", &mut m.scatter_strength, 0.01, "");
        changed |= fields::number(ui, "scatter height", &mut m.scatter_height, 0.05, " m");
        changed |= fields::optional_text(ui, "texture (procedural or a file)", &mut m.texture, "procedural");
        changed |= fields::number(ui, "texture scale", &mut m.texture_scale, 0.05, " m");
        changed |= fields::number(ui, "texture mix", &mut m.texture_mix, 0.01, "");
        changed |= fields::vec2_xz(ui, "flow velocity (m/s)", &mut m.flow_velocity, 0.01);
        changed |= fields::number(ui, "shore foam", &mut m.shore_foam, 0.01, "");
    });
    keys::edits(
        "water.material",
        &[
            "color",
            "shading",
            "refractive_index",
            "glitter",
            "specular",
            "shininess",
            "wind_speed",
            "absorption",
            "bottom_depth",
            "bottom_color",
            "foam_color",
            "foam_texture",
            "foam_scale",
            "foam_feather",
            "foam_streak",
            "scatter_color",
            "scatter_strength",
            "scatter_height",
            "texture",
            "texture_scale",
            "texture_mix",
            "flow_velocity",
            "shore_foam",
        ],
    );
    changed
}

/// Every `water.extent` value with its scene-file name, read through the scene format's own
/// names ([`WaterExtent::NAMES`]), so that a new extent appears in the menu without an edit here.
pub fn extent_options() -> Vec<(WaterExtent, &'static str)> {
    WaterExtent::NAMES
        .iter()
        .map(|&name| {
            let e = toml::Value::String(name.into()).try_into().expect("WaterExtent::NAMES are the names it reads");
            (e, name)
        })
        .collect()
}

/// The finest ring spacing (m) an unset `water.lod.spacing` gets, as the library resolves it
/// (`LodSettings::resolved_spacing`: the patch's smaller `size / cells`). `None` while the patch
/// itself is invalid.
pub fn auto_lod_spacing(s: &WaterSurface) -> Option<f32> {
    let auto = swell::scene::LodSettings { spacing: None, ..s.lod };
    Some(auto.resolved_spacing(&s.grid().ok()?))
}

/// Shows `[water] extent` and the `[water.lod]` keys; returns whether `s` changed. `auto` is the
/// extent the scene gets while `extent` is unset (it depends on the model and on the scene's
/// terrain, which the surface alone does not know); `None` when the terrain's border decides it
/// (`WaterExtent::default_for`: unbounded around an island, a patch in a lake).
pub fn show_extent(ui: &mut Ui, s: &mut WaterSurface, auto: Option<WaterExtent>) -> bool {
    let mut changed = false;
    let options = extent_options();
    let auto_name = match auto {
        Some(auto) => options.iter().find(|(e, _)| *e == auto).map_or("?", |(_, n)| n),
        None => "by the terrain's border",
    };
    let auto_label = format!("auto ({auto_name})");
    let mut menu: Vec<(Option<WaterExtent>, &str)> = vec![(None, auto_label.as_str())];
    menu.extend(options.iter().map(|&(e, n)| (Some(e), n)));
    fields::grid("water-extent").show(ui, |ui| {
        changed |= fields::choice(ui, "extent", &mut s.extent, &menu);
    });
    keys::edits("water", &["extent"]);
    // Shown whatever the extent, so that a scene's keys stay editable before it is switched to
    // unbounded (validation checks them either way).
    ui.label("Level of detail (unbounded water's camera rings)");
    let (lo, hi) = LOD_RING_CELLS;
    let (spacing_lo, spacing_hi) = LOD_SPACING_M;
    let auto_spacing = auto_lod_spacing(s).unwrap_or(1.0);
    fields::grid("water-lod").show(ui, |ui| {
        changed |= fields::count(ui, &format!("rings [1, {MAX_LOD_LEVELS}]"), &mut s.lod.levels, 0.05);
        changed |= fields::count_in_steps(ui, &format!("ring cells [{lo}, {hi}], by 4"), &mut s.lod.ring_cells, 4, 1.0);
        changed |= fields::auto_number(
            ui,
            &format!("finest spacing [{spacing_lo}, {spacing_hi}]"),
            &mut s.lod.spacing,
            auto_spacing,
            0.005,
            " m",
        );
    });
    keys::edits("water.lod", &["levels", "ring_cells", "spacing"]);
    changed
}

/// The model menu (`none` or any of [`WATER_MODELS`]) and why the last switch was refused;
/// returns whether `water` changed.
fn show_model_menu(ui: &mut Ui, water: &mut Option<WaterSpec>, forms: &mut PanelState) -> bool {
    let mut changed = false;
    let current = water.as_ref().map(|w| w.model.name().to_string());
    let mut chosen = current.clone();
    fields::grid("water-model").show(ui, |ui| {
        ui.label("model");
        egui::ComboBox::from_id_salt("water-model-combo").selected_text(current.as_deref().unwrap_or("none")).show_ui(
            ui,
            |ui| {
                ui.selectable_value(&mut chosen, None, "none");
                for &m in WATER_MODELS {
                    ui.selectable_value(&mut chosen, Some(m.to_string()), m);
                }
            },
        );
        ui.end_row();
    });
    keys::edits("water", &["model"]);
    if chosen != current {
        match chosen {
            None => {
                *water = None;
                changed = true;
            }
            Some(name) => match switch_model(water.as_ref(), &name) {
                Ok(w) => {
                    *water = Some(w);
                    changed = true;
                }
                Err(e) => forms.water_message = Some(e.to_string()),
            },
        }
    }
    if let Some(m) = &forms.water_message {
        ui.colored_label(ui.visuals().error_fg_color, m);
    }
    changed
}

/// The patch: its size, grid cells (the grid resolution) and centre; returns whether it changed.
fn show_patch(ui: &mut Ui, s: &mut WaterSurface) -> bool {
    let mut changed = false;
    fields::grid("water-surface").show(ui, |ui| {
        changed |= fields::vec2_xz(ui, "size (m)", &mut s.size, 1.0);
        ui.label("grid cells");
        ui.horizontal(|ui| {
            let [cx, cz] = &mut s.cells;
            for (c, name) in [(cx, "x "), (cz, "z ")] {
                changed |= ui.add(egui::DragValue::new(c).speed(2.0).prefix(name)).changed();
            }
        });
        ui.end_row();
        changed |= fields::vec2_xz(ui, "center (m)", &mut s.center, 1.0);
    });
    keys::edits("water", &["size", "cells", "center"]);
    changed
}

/// Shows the water section; returns whether `water` changed. `has_terrain` says whether the scene
/// has terrain, whose border then decides the water's automatic extent.
pub fn show(ui: &mut Ui, water: &mut Option<WaterSpec>, forms: &mut PanelState, has_terrain: bool) -> bool {
    let mut changed = show_model_menu(ui, water, forms);
    let Some(w) = water else { return changed };
    changed |= show_patch(ui, &mut w.surface);
    fields::grid("water-density").show(ui, |ui| {
        let (lo, hi) = swell::body::WATER_DENSITY_RANGE;
        let label = format!("density [{lo}, {hi}] (floats bodies)");
        changed |= fields::number(ui, &label, &mut w.density, 1.0, " kg/m³");
    });
    keys::edits("water", &["density"]);
    // With terrain, a model defined everywhere is unbounded or a patch by the terrain's border.
    let auto = WaterExtent::default_for(&w.model, false);
    let auto = (!has_terrain || auto == WaterExtent::Patch).then_some(auto);
    changed |= show_extent(ui, &mut w.surface, auto);
    ui.label("Material");
    changed |= show_material(ui, &mut w.material);
    changed |= water_transform::show(ui, &mut w.surface, &mut forms.water_transform);
    ui.separator();
    changed |= match &mut w.model {
        WaterModelSpec::Gerstner(spec) => gerstner::show(ui, spec, &mut forms.gerstner),
        WaterModelSpec::Sines(spec) => sines::show(ui, spec, &mut forms.sines),
        WaterModelSpec::Fft(p) => fft_ocean::show(ui, p),
        WaterModelSpec::Springs(p) => springs::show(ui, p, &mut forms.click_drop),
        WaterModelSpec::Tessendorf(p) => tessendorf::show(ui, p, &mut forms.tessendorf),
        WaterModelSpec::WaveSet(p) => wave_set::show(ui, p),
        WaterModelSpec::Airy(p) => airy::show(ui, p, &mut forms.airy),
        WaterModelSpec::SteepSines(p) => steep_sines::show(ui, p, &mut forms.steep_sines),
        WaterModelSpec::Radial(p) => radial::show(ui, p),
        WaterModelSpec::Noise(p) => noise::show(ui, p),
        WaterModelSpec::River(p) => river::show(ui, p, &mut w.material.texture),
    };
    changed
}

#[cfg(test)]
mod tests {
    use swell::scene::preset;

    use super::*;
    use swell::scene::Shading;

    #[test]
    fn names_come_from_the_scene_format() {
        let sea = preset("sea").unwrap().water.unwrap();
        assert_eq!(sea.model.name(), "gerstner");
        for (s, name) in fields::member_options::<Shading>() {
            let text = format!("model = 'sines'\n[material]\nshading = '{name}'\n");
            let w = WaterSpec::from_table(toml::from_str(&text).unwrap(), "t").unwrap();
            assert_eq!(w.material.shading, s);
        }
    }

    #[test]
    fn switching_models_keeps_the_patch_and_carries_the_waves() {
        let sea = preset("sea").unwrap().water.unwrap();
        let sines = switch_model(Some(&sea), "sines").unwrap();
        assert_eq!((&sines.surface, &sines.material), (&sea.surface, &sea.material));
        let WaterModelSpec::Sines(s) = &sines.model else { panic!("{sines:?}") };
        assert_eq!(s.waves.len(), 10);
        let back = switch_model(Some(&sines), "gerstner").unwrap();
        let WaterModelSpec::Gerstner(g) = &back.model else { panic!("{back:?}") };
        assert!(g.waves.iter().all(|w| w.steepness == 0.0));
        // Every model listed can be chosen from nothing and builds.
        for &m in WATER_MODELS {
            let w = switch_model(None, m).unwrap();
            assert_eq!(w.model.name(), m);
            w.model.build().unwrap();
        }
        assert!(switch_model(Some(&sea), "lava").is_err());
        assert_eq!(switch_model(Some(&sea), "gerstner").unwrap(), sea);
    }

    #[test]
    fn an_extent_the_new_model_cannot_have_goes_back_to_automatic() {
        let mut sea = preset("sea").unwrap().water.unwrap();
        sea.surface.extent = Some(WaterExtent::Unbounded);
        sea.surface.lod.levels = 5;
        let springs = switch_model(Some(&sea), "springs").unwrap();
        assert_eq!(springs.surface.extent, None);
        assert_eq!(springs.surface.lod, sea.surface.lod, "the rest of the patch carries over");
        let fft = switch_model(Some(&sea), "fft").unwrap();
        assert_eq!(fft.surface.extent, Some(WaterExtent::Unbounded));
        sea.surface.extent = Some(WaterExtent::Patch);
        assert_eq!(switch_model(Some(&sea), "river").unwrap().surface.extent, Some(WaterExtent::Patch));
    }

    #[test]
    fn the_extent_menu_lists_every_extent_and_auto_spacing_is_the_patch_s() {
        let options = extent_options();
        assert_eq!(options.iter().map(|(_, n)| *n).collect::<Vec<_>>(), WaterExtent::NAMES);
        for (e, name) in options {
            let text = format!("model = 'sines'\nextent = '{name}'\n");
            let w = WaterSpec::from_table(toml::from_str(&text).unwrap(), "t").unwrap();
            assert_eq!(w.surface.extent, Some(e));
        }
        let mut s = WaterSurface { size: glam::Vec2::new(100.0, 50.0), cells: [200, 200], ..Default::default() };
        assert_eq!(auto_lod_spacing(&s), Some(0.25));
        s.cells = [0, 200];
        assert_eq!(auto_lod_spacing(&s), None);
    }
}
