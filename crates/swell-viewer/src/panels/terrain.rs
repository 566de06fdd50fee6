//! The terrain panel (paper 001's generator program and paper 000's transforms): generator and its
//! parameters, size and extent, a new seed ("Regenerate"), loading and saving a 16-bit heightmap
//! PNG, and the object transform (translate, rotate about each axis, scale) with step buttons.
//!
//! Step sizes are paper 000's defaults (its `HandlerTransform`: 5 units per move, 5 degrees per
//! rotation, both editable in its dialogs); paper 000 has no scale step, so swell's is a factor
//! of 1.1 per press (ten presses about 2.6x), also editable.

use std::path::PathBuf;

use eframe::egui::{self, TextEdit, Ui};
use swell::math::Transform;
use swell::scene::TerrainMaterial;
use swell::scene::{HeightmapSpec, TerrainGenerator, TerrainSpec, DEFAULT_TERRAIN_EXTENT, TERRAIN_GENERATORS};
use swell::terrain::FarLandParams;
use swell::{Error, Result};

use super::files::{FileMessage, FileRequest};
use super::{fields, keys as key_paths, table_fields};

/// Paper 000's move step, metres per press.
pub const PAPER_MOVE_STEP_M: f32 = 5.0;
/// Paper 000's rotation step, degrees per press.
pub const PAPER_ROTATE_STEP_DEG: f32 = 5.0;
/// swell's scale step, factor per press (paper 000 has none).
pub const SCALE_STEP: f32 = 1.1;

/// What the terrain panel remembers between frames.
#[derive(Clone, Debug, PartialEq)]
pub struct TerrainForm {
    /// Move step, metres.
    pub move_step: f32,
    /// Rotation step, degrees.
    pub rotate_step: f32,
    /// Scale step, factor > 1.
    pub scale_step: f32,
    /// Heightmap PNG to load or save.
    pub heightmap_path: String,
    /// Why the last generator switch or parameter edit was refused.
    pub message: Option<String>,
    /// The outcome of the last heightmap load or save (path and size, or the error).
    pub file_message: Option<FileMessage>,
}

impl Default for TerrainForm {
    fn default() -> Self {
        Self {
            move_step: PAPER_MOVE_STEP_M,
            rotate_step: PAPER_ROTATE_STEP_DEG,
            scale_step: SCALE_STEP,
            heightmap_path: "terrain.png".into(),
            message: None,
            file_message: None,
        }
    }
}

/// The generator "Back to a generator" switches a loaded heightmap to (the paper 001 classic).
pub const DEFAULT_GENERATOR: &str = "diamond-square";

/// The `terrain.generator` name of a generator.
pub fn generator_name(g: &TerrainGenerator) -> String {
    generator_keys(g).0
}

/// The generator's name and its own keys (without `generator`), as in a scene file.
pub fn generator_keys(g: &TerrainGenerator) -> (String, toml::Table) {
    let mut t = toml::Table::try_from(g).unwrap_or_default();
    let name = match t.remove("generator") {
        Some(toml::Value::String(s)) => s,
        _ => "?".into(),
    };
    (name, t)
}

/// The terrain with its generator switched to `name` (its defaults), keeping the placement and
/// look; `None` removes the terrain. A size the new generator cannot take is dropped (default
/// size). Heightmaps are chosen by loading one ([`use_heightmap`]), not here.
pub fn switch_generator(terrain: Option<&TerrainSpec>, name: Option<&str>) -> Result<Option<TerrainSpec>> {
    let Some(name) = name else { return Ok(None) };
    if name == "heightmap" {
        return Err(Error::invalid("terrain.generator", "load a heightmap PNG to use one"));
    }
    if let Some(t) = terrain {
        if generator_name(&t.generator) == name {
            return Ok(Some(t.clone()));
        }
    }
    let generator = TerrainGenerator::from_table(name, toml::Table::new(), "viewer")?;
    let mut spec = match terrain {
        Some(t) => TerrainSpec { generator, ..t.clone() },
        None => TerrainSpec {
            size: None,
            extent: None,
            transform: Transform::IDENTITY,
            material: TerrainMaterial::default(),
            far_land: None,
            generator,
        },
    };
    if spec.validate().is_err() {
        spec.size = None;
    }
    Ok(Some(spec))
}

/// Reads edited generator keys back; refused (with the scene-file message) if a key is unknown or
/// of the wrong type. Ranges are checked when the draft is applied.
pub fn set_generator_keys(name: &str, keys: toml::Table) -> Result<TerrainGenerator> {
    TerrainGenerator::from_table(name, keys, "panel")
}

/// "Regenerate": the same generator with the next seed. Returns false for generators without a
/// seed (flat, slope, channel, heightmap), leaving the terrain as it is.
pub fn regenerate(spec: &mut TerrainSpec) -> bool {
    let (name, mut keys) = generator_keys(&spec.generator);
    if !table_fields::bump_integer(&mut keys, "seed", 1) {
        return false;
    }
    match set_generator_keys(&name, keys) {
        Ok(g) => {
            spec.generator = g;
            true
        }
        Err(_) => false,
    }
}

/// The terrain read from heightmap `path` (its sidecar gives scale, offset and extent); placement,
/// look and far land are kept. The file is read when the draft is applied, so a bad file is refused
/// there.
pub fn use_heightmap(spec: Option<&TerrainSpec>, path: PathBuf) -> TerrainSpec {
    let (transform, material) =
        spec.map_or((Transform::IDENTITY, TerrainMaterial::default()), |s| (s.transform, s.material));
    // The far land is part of the place too: kept.
    TerrainSpec {
        size: None,
        extent: None,
        transform,
        material,
        generator: TerrainGenerator::Heightmap(HeightmapSpec { path, height_scale: None, height_offset: None }),
        far_land: spec.and_then(|s| s.far_land.clone()),
    }
}

/// Whether the generator has a seed, so that "Regenerate (new seed)" means something.
pub fn has_seed(g: &TerrainGenerator) -> bool {
    generator_keys(g).1.contains_key("seed")
}

/// Shows every `[terrain.material]` key; returns whether `m` changed.
pub fn show_material(ui: &mut Ui, m: &mut TerrainMaterial) -> bool {
    let mut changed = false;
    fields::grid("terrain-material").show(ui, |ui| {
        changed |= fields::member(ui, "shading", &mut m.shading);
        changed |= fields::color(ui, "sand", &mut m.sand);
        changed |= fields::color(ui, "grass", &mut m.grass);
        changed |= fields::color(ui, "rock", &mut m.rock);
        changed |= fields::color(ui, "snow", &mut m.snow);
        changed |= fields::number(ui, "sand height", &mut m.sand_height, 0.1, " m");
        changed |= fields::number(ui, "snow height", &mut m.snow_height, 0.1, " m");
        changed |= fields::number(ui, "rock slope", &mut m.rock_slope_deg, 0.5, " deg");
        changed |= fields::number(ui, "band transition", &mut m.transition, 0.05, " m");
        changed |= fields::number(ui, "wet up to", &mut m.wet_height, 0.05, " m");
    });
    key_paths::edits(
        "terrain.material",
        &[
            "shading",
            "sand",
            "grass",
            "rock",
            "snow",
            "sand_height",
            "snow_height",
            "rock_slope_deg",
            "transition",
            "wet_height",
        ],
    );
    changed
}

/// Shows the `[terrain.far_land]` switch and, when on, its keys; returns whether it changed.
pub fn show_far_land(ui: &mut Ui, far: &mut Option<FarLandParams>) -> bool {
    let mut changed = false;
    let mut on = far.is_some();
    if ui.checkbox(&mut on, "Land to the horizon (far land)").changed() {
        *far = on.then(FarLandParams::default);
        changed = true;
    }
    // The switch adds or removes the whole table.
    key_paths::edits("terrain", &["far_land"]);
    if let Some(p) = far {
        fields::grid("terrain-far-land").show(ui, |ui| {
            changed |= fields::number(ui, "reach", &mut p.reach, 10.0, " m");
            changed |= fields::number(ui, "relief", &mut p.relief, 0.5, " m");
            changed |= fields::number(ui, "feature size", &mut p.feature_size, 5.0, " m");
            changed |= fields::seed(ui, "seed", &mut p.seed);
        });
        key_paths::edits("terrain.far_land", &["reach", "relief", "feature_size", "seed"]);
    }
    changed
}

/// One press of a transform step button.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Step {
    /// Move along axis 0..3 (x, y, z) by `sign` steps.
    Move(usize, f32),
    /// Rotate about axis 0..3 by `sign` steps.
    Rotate(usize, f32),
    /// Scale uniformly up (`1.0`) or down (`-1.0`) one step.
    Scale(f32),
}

/// Applies one step press to `t`. Rotations wrap into [-360, 360] so repeated presses stay valid.
pub fn apply_step(t: &mut Transform, step: Step, form: &TerrainForm) {
    match step {
        Step::Move(axis, sign) => t.translate[axis] += sign * form.move_step,
        Step::Rotate(axis, sign) => {
            let a = t.rotate_deg[axis] + sign * form.rotate_step;
            t.rotate_deg[axis] = if a.abs() > 360.0 { a % 360.0 } else { a };
        }
        Step::Scale(sign) => t.scale *= form.scale_step.powf(sign),
    }
}

/// Shows the terrain section; returns whether the terrain changed and a heightmap file request.
pub fn show(ui: &mut Ui, terrain: &mut Option<TerrainSpec>, form: &mut TerrainForm) -> (bool, Option<FileRequest>) {
    let mut changed = show_generator_menu(ui, terrain, form);
    let request = show_heightmap_files(ui, terrain.is_some(), form);
    if let Some(m) = &form.message {
        ui.colored_label(ui.visuals().error_fg_color, m);
    }
    let Some(t) = terrain else { return (changed, request) };
    key_paths::edits("terrain", &["generator"]);
    if let Some(switched) = show_heightmap_source(ui, t, form) {
        // The terrain was just replaced: the rest of the section shows it from the next frame.
        return (changed | switched, request);
    }
    changed |= show_generator_keys(ui, t, form);
    changed |= show_size_and_extent(ui, t);
    ui.label("Material");
    changed |= show_material(ui, &mut t.material);
    changed |= show_far_land(ui, &mut t.far_land);
    changed |= show_transform(ui, &mut t.transform, form);
    (changed, request)
}

/// The generator menu (`none` or any generator but a heightmap, which is loaded from a file);
/// returns whether the terrain changed. A refused switch leaves it and says why in `form`.
fn show_generator_menu(ui: &mut Ui, terrain: &mut Option<TerrainSpec>, form: &mut TerrainForm) -> bool {
    let current = terrain.as_ref().map(|t| generator_name(&t.generator));
    let mut chosen = current.clone();
    fields::grid("terrain-generator").show(ui, |ui| {
        ui.label("generator");
        egui::ComboBox::from_id_salt("terrain-generator-combo")
            .selected_text(current.as_deref().unwrap_or("none"))
            .show_ui(ui, |ui| {
                ui.selectable_value(&mut chosen, None, "none");
                for &g in TERRAIN_GENERATORS.iter().filter(|g| **g != "heightmap") {
                    ui.selectable_value(&mut chosen, Some(g.to_string()), g);
                }
            });
        ui.end_row();
    });
    if chosen == current {
        return false;
    }
    match switch_generator(terrain.as_ref(), chosen.as_deref()) {
        Ok(t) => {
            *terrain = t;
            form.message = None;
            true
        }
        Err(e) => {
            form.message = Some(e.to_string());
            false
        }
    }
}

/// The heightmap path with *Load* and (with a terrain to write) *Save*, and the outcome of the
/// last of them; returns the file operation asked for. The viewer does it at once, so that its
/// outcome shows under the buttons.
fn show_heightmap_files(ui: &mut Ui, has_terrain: bool, form: &mut TerrainForm) -> Option<FileRequest> {
    let mut request = None;
    ui.horizontal(|ui| {
        ui.label("heightmap PNG");
        ui.add(TextEdit::singleline(&mut form.heightmap_path).desired_width(160.0));
        if ui.button("Load").on_hover_text("Use this 8- or 16-bit grey PNG (and its .toml sidecar)").clicked() {
            request = Some(FileRequest::LoadHeightmap(PathBuf::from(&form.heightmap_path)));
        }
        if has_terrain && ui.button("Save").on_hover_text("Write the terrain as a 16-bit PNG + sidecar").clicked() {
            request = Some(FileRequest::SaveHeightmap(PathBuf::from(&form.heightmap_path)));
        }
    });
    match &form.file_message {
        Some(FileMessage::Done(m)) => {
            ui.label(m);
        }
        Some(FileMessage::Failed(m)) => {
            ui.colored_label(ui.visuals().error_fg_color, m);
        }
        None => {}
    }
    request
}

/// For a terrain read from a heightmap: says which file, with a button back to a generator (a
/// file has nothing to regenerate). `Some(changed)` when that button was pressed (the terrain is
/// then replaced, or the refusal is in `form`), `None` otherwise and for generators.
fn show_heightmap_source(ui: &mut Ui, t: &mut TerrainSpec, form: &mut TerrainForm) -> Option<bool> {
    let TerrainGenerator::Heightmap(h) = &t.generator else { return None };
    ui.label(format!("Heights come from the file {} (edit its keys below).", h.path.display()));
    if !ui.button(format!("Back to a generator ({DEFAULT_GENERATOR})")).clicked() {
        return None;
    }
    match switch_generator(Some(t), Some(DEFAULT_GENERATOR)) {
        Ok(Some(g)) => {
            *t = g;
            form.message = None;
            Some(true)
        }
        Ok(None) => Some(false),
        Err(e) => {
            form.message = Some(e.to_string());
            Some(false)
        }
    }
}

/// One row per key of the generator (or heightmap), read back through the scene-file parser, and
/// *Regenerate (new seed)* for generators with a seed; returns whether the generator changed.
fn show_generator_keys(ui: &mut Ui, t: &mut TerrainSpec, form: &mut TerrainForm) -> bool {
    let mut changed = false;
    let (name, mut keys) = generator_keys(&t.generator);
    let names: Vec<&str> = keys.keys().map(String::as_str).collect();
    key_paths::edits("terrain", &names);
    if table_fields::show(ui, "terrain-keys", &mut keys) {
        match set_generator_keys(&name, keys) {
            Ok(g) => {
                t.generator = g;
                form.message = None;
                changed = true;
            }
            Err(e) => form.message = Some(e.to_string()),
        }
    }
    if has_seed(&t.generator) && ui.button("Regenerate (new seed)").clicked() {
        changed |= regenerate(t);
    }
    changed
}

/// `size` (vertices per side; a heightmap's is its file's) and `extent` (m), each optional;
/// returns whether either changed.
fn show_size_and_extent(ui: &mut Ui, t: &mut TerrainSpec) -> bool {
    let mut changed = false;
    let from_file = matches!(t.generator, TerrainGenerator::Heightmap(_));
    fields::grid("terrain-size").show(ui, |ui| {
        if !from_file {
            let mut size = t.size.map(|s| s as f32);
            let default = swell::scene::DEFAULT_TERRAIN_SIZE as f32;
            if fields::optional_number(ui, "size (vertices)", &mut size, default, 1.0, "") {
                t.size = size.map(|s| s.round().max(0.0) as u32);
                changed = true;
            }
        }
        ui.label("extent (m)");
        ui.horizontal(|ui| {
            let mut on = t.extent.is_some();
            if ui.checkbox(&mut on, "").changed() {
                t.extent = on.then_some(DEFAULT_TERRAIN_EXTENT);
                changed = true;
            }
            if let Some(e) = &mut t.extent {
                changed |= ui.add(egui::DragValue::new(&mut e.x).speed(1.0).prefix("x ")).changed();
                changed |= ui.add(egui::DragValue::new(&mut e.y).speed(1.0).prefix("z ")).changed();
            }
        });
        ui.end_row();
    });
    if !from_file {
        key_paths::edits("terrain", &["size"]);
    }
    key_paths::edits("terrain", &["extent"]);
    changed
}

/// The object transform: translate, rotate and scale typed directly, the step sizes (the
/// panel's, not the scene's) and a row of step buttons per axis; returns whether it changed.
fn show_transform(ui: &mut Ui, transform: &mut Transform, form: &mut TerrainForm) -> bool {
    let mut changed = false;
    ui.label("Transform");
    fields::grid("terrain-transform").show(ui, |ui| {
        changed |= fields::vec3(ui, "translate (m)", &mut transform.translate, 0.1);
        changed |= fields::vec3(ui, "rotate (deg)", &mut transform.rotate_deg, 0.5);
        changed |= fields::vec3(ui, "scale", &mut transform.scale, 0.01);
        fields::number(ui, "move step", &mut form.move_step, 0.1, " m");
        fields::number(ui, "rotate step", &mut form.rotate_step, 0.1, " deg");
        fields::number(ui, "scale step", &mut form.scale_step, 0.01, " x");
    });
    key_paths::edits("terrain.transform", &["translate", "rotate_deg", "scale"]);
    let mut step = None;
    for (axis, name) in ["x", "y", "z"].into_iter().enumerate() {
        ui.horizontal(|ui| {
            ui.label(name);
            for (label, s) in [("move -", Step::Move(axis, -1.0)), ("move +", Step::Move(axis, 1.0))]
                .into_iter()
                .chain([("rot -", Step::Rotate(axis, -1.0)), ("rot +", Step::Rotate(axis, 1.0))])
            {
                if ui.small_button(label).clicked() {
                    step = Some(s);
                }
            }
        });
    }
    ui.horizontal(|ui| {
        if ui.small_button("scale /").clicked() {
            step = Some(Step::Scale(-1.0));
        }
        if ui.small_button("scale x").clicked() {
            step = Some(Step::Scale(1.0));
        }
        if ui.small_button("identity").clicked() && *transform != Transform::IDENTITY {
            *transform = Transform::IDENTITY;
            changed = true;
        }
    });
    if let Some(s) = step {
        apply_step(transform, s, form);
        changed = true;
    }
    changed
}

#[cfg(test)]
mod tests {
    use glam::Vec3;
    use swell::scene::{preset, Scene};

    use super::*;

    fn terrain_scene() -> Scene {
        preset("terrain").unwrap()
    }

    #[test]
    fn every_generator_can_be_chosen_edited_and_saved() {
        let scene = terrain_scene();
        for &g in TERRAIN_GENERATORS.iter().filter(|g| **g != "heightmap") {
            let mut s = scene.clone();
            s.terrain = switch_generator(s.terrain.as_ref(), Some(g)).unwrap();
            let t = s.terrain.as_ref().unwrap();
            assert_eq!(generator_name(&t.generator), g);
            assert_eq!(t.transform, scene.terrain.as_ref().unwrap().transform);
            t.build().unwrap();
            // The keys the panel shows read back to the same generator.
            let (name, keys) = generator_keys(&t.generator);
            assert_eq!(set_generator_keys(&name, keys).unwrap(), t.generator);
            assert_eq!(Scene::from_toml(&s.to_toml(), "t").unwrap(), s, "generator {g}");
        }
        assert_eq!(switch_generator(scene.terrain.as_ref(), None).unwrap(), None);
        assert!(switch_generator(None, Some("heightmap")).is_err());
        assert!(switch_generator(None, Some("lava")).is_err());
        let mut bad = toml::Table::new();
        bad.insert("no_such_key".into(), toml::Value::Integer(1));
        assert!(set_generator_keys("hills", bad).is_err());
    }

    #[test]
    fn a_heightmap_has_no_seed_and_goes_back_to_a_generator_in_place() {
        let mut spec = switch_generator(None, Some("hills")).unwrap().unwrap();
        spec.transform.translate.y = -2.0;
        assert!(has_seed(&spec.generator));
        let file = use_heightmap(Some(&spec), PathBuf::from("h.png"));
        assert!(!has_seed(&file.generator));
        assert!(!has_seed(&switch_generator(None, Some("flat")).unwrap().unwrap().generator));
        let back = switch_generator(Some(&file), Some(DEFAULT_GENERATOR)).unwrap().unwrap();
        assert_eq!(generator_name(&back.generator), DEFAULT_GENERATOR);
        assert_eq!(back.transform, spec.transform, "the placement stays");
        back.build().unwrap();
    }

    #[test]
    fn regenerate_changes_the_seed_and_the_heights() {
        let mut t = switch_generator(None, Some("diamond-square")).unwrap().unwrap();
        t.size = Some(33);
        let before = t.build().unwrap();
        assert!(regenerate(&mut t));
        let after = t.build().unwrap();
        assert_ne!(before.heights(), after.heights());
        let mut flat = switch_generator(None, Some("flat")).unwrap().unwrap();
        let f0 = flat.clone();
        assert!(!regenerate(&mut flat));
        assert_eq!(flat, f0);
    }

    #[test]
    fn step_buttons_move_by_paper_000_steps_and_stay_valid() {
        let form = TerrainForm::default();
        let mut t = Transform::IDENTITY;
        apply_step(&mut t, Step::Move(0, 1.0), &form);
        apply_step(&mut t, Step::Move(2, -1.0), &form);
        assert_eq!(t.translate, Vec3::new(5.0, 0.0, -5.0));
        for _ in 0..80 {
            apply_step(&mut t, Step::Rotate(1, 1.0), &form);
        }
        // 80 presses of 5 degrees = 400 degrees, wrapped back into the valid range.
        assert!((t.rotate_deg.y - 40.0).abs() < 1e-3, "{}", t.rotate_deg.y);
        apply_step(&mut t, Step::Scale(1.0), &form);
        apply_step(&mut t, Step::Scale(1.0), &form);
        apply_step(&mut t, Step::Scale(-1.0), &form);
        assert!((t.scale - Vec3::splat(1.1)).abs().max_element() < 1e-5);
        t.validate("terrain.transform").unwrap();
    }

    #[test]
    fn a_saved_heightmap_loads_back_as_the_same_terrain() {
        let dir = tempfile::tempdir().unwrap();
        let png = dir.path().join("t.png");
        let mut spec = switch_generator(None, Some("hills")).unwrap().unwrap();
        spec.size = Some(65);
        spec.transform.translate.y = -3.0;
        let field = spec.build().unwrap();
        swell::terrain::write_heightmap(&png, &field).unwrap();
        let loaded = use_heightmap(Some(&spec), png);
        assert_eq!(loaded.transform, spec.transform);
        let back = loaded.build().unwrap();
        assert_eq!((back.cols(), back.rows()), (field.cols(), field.rows()));
        let (lo, hi) = field.min_max();
        let tol = (hi - lo) / 65535.0 + 1e-4;
        for (a, b) in back.heights().iter().zip(field.heights()) {
            assert!((a - b).abs() <= tol, "{a} vs {b}");
        }
        // A missing file is refused when the draft is applied.
        let missing = use_heightmap(None, dir.path().join("missing.png"));
        assert!(missing.build().is_err());
    }
}
