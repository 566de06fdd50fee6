//! The parameter panel: one module per scene section or water model, each a `show` function that
//! edits part of the draft scene and says whether it changed.
//!
//! The pattern every panel follows (see the crate documentation for how to add one):
//!
//! ```text
//! pub fn show(ui: &mut Ui, section: &mut Section [, form: &mut SectionForm]) -> bool
//! ```
//!
//! - `section` is the part of [`SceneEditor::draft`](crate::editor::SceneEditor::draft) it edits;
//!   widgets write into it directly and never clamp, so a bad value stays visible;
//! - `form` (optional) is what the panel remembers between frames that is not part of the scene
//!   (a "new wave" being typed, the reason an add was refused); it lives in [`PanelState`];
//! - the return value says whether the section changed; [`show_all`] then asks the editor to
//!   validate and commit the draft, and the reason for a refusal is shown at the top.
//!
//! Pure edit operations (adding a wave, switching a model) are plain functions beside the panel,
//! unit-tested without a window.

pub mod airy;
pub mod bodies;
pub mod camera;
pub mod dispersion;
pub mod fft_ocean;
pub mod fields;
pub mod files;
pub mod gerstner;
pub mod keys;
pub mod lights;
pub mod noise;
pub mod radial;
pub mod render;
pub mod river;
pub mod sines;
pub mod sky;
pub mod spectrum_tables;
pub mod springs;
pub mod steep_sines;
pub mod table_fields;
pub mod terrain;
pub mod tessendorf;
pub mod time;
pub mod water;
pub mod water_transform;
pub mod wave_list;
pub mod wave_set;

use eframe::egui::{CollapsingHeader, Ui};
use swell::scene::Scene;

use crate::clock::Clock;

/// Everything panels remember between frames that is not in the scene.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PanelState {
    /// Gerstner's "new wave" form.
    pub gerstner: gerstner::GerstnerForm,
    /// Sum of sines' "new wave" form.
    pub sines: sines::SinesForm,
    /// Tessendorf's "new wave" form.
    pub tessendorf: tessendorf::TessendorfForm,
    /// Airy's "new wave" form.
    pub airy: airy::AiryForm,
    /// Steep sines' "new wave" form.
    pub steep_sines: steep_sines::SteepSinesForm,
    /// Step sizes of the water's transform buttons.
    pub water_transform: water_transform::WaterTransformForm,
    /// Why the last model switch failed.
    pub water_message: Option<String>,
    /// File paths and the outcome of the last file operation.
    pub files: files::FilesForm,
    /// What a click on the spring mesh drops.
    pub click_drop: springs::ClickDrop,
    /// Transform steps, heightmap path and the last refusal of the terrain panel.
    pub terrain: terrain::TerrainForm,
    /// What a click on the water does, the body the keys push, the bodies' last places.
    pub bodies: bodies::BodiesForm,
    /// An edit dragged out in a scene with bodies, waiting for the drag's end to be committed
    /// ([`commit_now`]).
    pub commit_after_drag: bool,
}

/// Whether the panel's edits are committed this frame, given whether the draft `changed`, a drag
/// is under way and the scene has bodies; `held` remembers an edit waiting for the drag's end.
///
/// Committing a scene with bodies replays them from t = 0 (the world is rebuilt and every 1/120 s
/// body step moves the water model: 3.6 s at t = 10 s on the FFT sea), so a value dragged out is
/// committed once, when the drag ends, instead of every frame of the drag. Without bodies every
/// frame of a drag commits, as before.
pub fn commit_now(changed: bool, dragging: bool, has_bodies: bool, held: &mut bool) -> bool {
    // Once held, an edit waits for the drag's end whatever else happens meanwhile.
    if dragging && (has_bodies && changed || *held) {
        *held = true;
        return false;
    }
    let now = changed || *held;
    *held = false;
    now
}

/// What the panel asks of the viewer this frame.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PanelOutput {
    /// The draft scene changed: validate and commit it.
    pub scene_changed: bool,
    /// "Revert" was clicked: drop the refused draft.
    pub revert: bool,
    /// "Reset camera" was clicked.
    pub reset_camera: bool,
    /// A file operation was asked for.
    pub file: Option<files::FileRequest>,
    /// *Add crate* or *Add buoy* was clicked: drop one at the view's centre.
    pub drop: Option<crate::body_control::DropKind>,
}

/// Shows every section, in the order a user works: files, time, water, terrain, bodies, lights,
/// sky, render, camera. `error` is why the draft was last refused, shown at the top.
pub fn show_all(
    ui: &mut Ui,
    draft: &mut Scene,
    state: &mut PanelState,
    clock: &mut Clock,
    error: Option<&str>,
) -> PanelOutput {
    let mut out = PanelOutput::default();
    if let Some(e) = error {
        ui.horizontal_wrapped(|ui| {
            ui.colored_label(ui.visuals().error_fg_color, format!("Refused: {e}"));
            out.revert = ui.button("Revert").on_hover_text("Go back to the scene being shown").clicked();
        });
        ui.separator();
    }
    section(ui, "Files", true, |ui| out.file = files::show(ui, &mut state.files));
    section(ui, "Time", true, |ui| time::show(ui, clock));
    let has_terrain = draft.terrain.is_some();
    section(ui, "Water", true, |ui| out.scene_changed |= water::show(ui, &mut draft.water, state, has_terrain));
    section(ui, "Terrain", draft.terrain.is_some(), |ui| {
        let (changed, request) = terrain::show(ui, &mut draft.terrain, &mut state.terrain);
        out.scene_changed |= changed;
        out.file = out.file.take().or(request);
    });
    section(ui, "Bodies", true, |ui| {
        let (changed, drop) = bodies::show(ui, &mut draft.bodies, &mut state.bodies);
        out.scene_changed |= changed;
        out.drop = drop;
    });
    section(ui, "Lights", false, |ui| out.scene_changed |= lights::show(ui, &mut draft.lights));
    section(ui, "Sky", false, |ui| out.scene_changed |= sky::show(ui, &mut draft.sky));
    section(ui, "Render", true, |ui| {
        out.scene_changed |= render::show(ui, &mut draft.render);
    });
    section(ui, "Camera", false, |ui| {
        let (changed, request) = camera::show(ui, &mut draft.camera);
        out.scene_changed |= changed;
        out.reset_camera = request.reset;
    });
    let dragging = ui.ctx().dragged_id().is_some();
    out.scene_changed = commit_now(out.scene_changed, dragging, !draft.bodies.is_empty(), &mut state.commit_after_drag);
    out
}

fn section(ui: &mut Ui, title: &str, open: bool, body: impl FnOnce(&mut Ui)) {
    // While the key test records what the panel edits, every section is drawn.
    CollapsingHeader::new(title).default_open(open || keys::is_recording()).show(ui, body);
}

/// Runs [`show_all`] for one frame of a window-less egui context (no input), for tests.
#[cfg(test)]
pub(crate) fn show_headless(draft: &mut Scene, state: &mut PanelState, clock: &mut Clock) -> PanelOutput {
    use eframe::egui;
    let ctx = egui::Context::default();
    let mut out = PanelOutput::default();
    for _ in 0..2 {
        // Two passes: egui lays some widgets out in a first, invisible pass.
        let mut output = ctx.run_ui(egui::RawInput::default(), |ui| {
            egui::CentralPanel::default().show(ui, |ui| {
                egui::ScrollArea::vertical().show(ui, |ui| out = show_all(ui, draft, state, clock, Some("test error")));
            });
        });
        // No painter takes the font textures here; egui (debug builds) insists they are handled.
        output.textures_delta.clear();
    }
    out
}

/// What the model panels' tests share: a small scene with a given model, and committing an edit of
/// its model the way the viewer does (draft, then [`crate::editor::SceneEditor::apply`]).
#[cfg(test)]
pub(crate) mod test_support {
    use swell::scene::{preset, Scene, WaterModelSpec};

    use crate::editor::SceneEditor;

    /// The `sea` preset with its water switched to `model` (defaults) on a coarse grid.
    pub fn scene_with(model: &str) -> Scene {
        let mut scene = preset("sea").unwrap();
        let mut w = super::water::switch_model(scene.water.as_ref(), model).unwrap();
        w.surface.cells = [16, 16];
        scene.water = Some(w);
        scene
    }

    /// Applies `edit` to the model of `scene` as a panel would and commits it through the editor:
    /// the committed scene, checked to save and load back unchanged, or the refusal shown at the
    /// top of the panel (the shown scene then unchanged).
    pub fn commit(scene: &Scene, edit: impl FnOnce(&mut WaterModelSpec)) -> Result<Scene, String> {
        let mut editor = SceneEditor::new(scene.clone()).unwrap();
        edit(&mut editor.draft.water.as_mut().unwrap().model);
        match editor.apply() {
            Ok(()) => {
                let shown = editor.scene().clone();
                assert_eq!(shown, editor.draft);
                assert_eq!(Scene::from_toml(&shown.to_toml(), "t").unwrap(), shown);
                Ok(shown)
            }
            Err(e) => {
                assert_eq!(editor.scene(), scene);
                assert_eq!(editor.error(), Some(e.to_string().as_str()));
                Err(e.to_string())
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use swell::scene::{preset, PRESETS};

    use super::*;

    #[test]
    fn showing_the_panel_changes_nothing_in_any_preset() {
        for p in PRESETS {
            let scene = preset(p.name).unwrap();
            let mut draft = scene.clone();
            let mut state = PanelState::default();
            let mut clock = Clock::default();
            let out = show_headless(&mut draft, &mut state, &mut clock);
            assert_eq!(draft, scene, "preset {}", p.name);
            assert_eq!(out, PanelOutput::default());
            assert_eq!(state, PanelState::default());
            assert_eq!(clock, Clock::default());
            // And what the panel shows saves to the same file.
            assert_eq!(Scene::from_toml(&draft.to_toml(), "t").unwrap(), scene);
        }
    }

    /// Scene-file keys with no widget on purpose, and why.
    const NOT_EDITED: &[(&str, &str)] = &[("version", "the file format's version: always 1, not a parameter")];

    /// The water of the `sea` preset switched to `model`, with the keys a default leaves out
    /// (optional keys, wave lists, a dispersion with a depth) set from `extra`, a `[water]` TOML
    /// fragment.
    fn water_with(model: &str, extra: &str) -> swell::scene::WaterSpec {
        let sea = preset("sea").unwrap().water.unwrap();
        let mut t = water::switch_model(Some(&sea), model).unwrap().to_table();
        t.extend(toml::from_str::<toml::Table>(extra).unwrap());
        swell::scene::WaterSpec::from_table(t, "test").unwrap()
    }

    /// Sets `[water] extent` (unbounded where the model can be) and every `[water.lod]` key away
    /// from their defaults, at which a file leaves them out.
    fn set_extent_and_lod(w: &mut swell::scene::WaterSpec) {
        use swell::scene::WaterExtent;
        let unbounded = WaterExtent::Unbounded.validate(&w.model).is_ok();
        w.surface.extent = Some(if unbounded { WaterExtent::Unbounded } else { WaterExtent::Patch });
        w.surface.lod = swell::scene::LodSettings { levels: 6, ring_cells: 64, spacing: Some(0.5) };
    }

    /// Floating bodies that together set every `[[body]]` key: density and mass are exclusive, and
    /// only a mesh has a path (named, not read, by the panel).
    fn bodies_with_every_key() -> Vec<swell::body::BodySpec> {
        use glam::Vec3;
        use swell::body::{BodyShape, BodySpec};
        let mut a = BodySpec::new(BodyShape::Box, &[1.0, 0.5, 2.0], Vec3::new(1.0, 0.5, -2.0));
        a.name = "crate".into();
        a.density = Some(400.0);
        a.center_of_mass = Some(Vec3::new(0.0, -0.1, 0.0));
        a.inertia = Some(Vec3::new(50.0, 60.0, 20.0));
        a.rotation_deg = Vec3::new(20.0, 5.0, -5.0);
        a.velocity = Vec3::new(0.5, -1.0, 0.0);
        a.angular_velocity = Vec3::new(0.0, 0.3, 0.0);
        a.release_time = 2.5;
        a.drag = 1.5;
        a.linear_drag = 30.0;
        a.friction = 0.4;
        a.color = Vec3::new(0.7, 0.2, 0.1);
        let mut b = BodySpec::new(BodyShape::Sphere, &[0.4], Vec3::new(-3.0, 1.0, 0.0));
        b.mass = Some(40.0);
        let mut c = BodySpec::new(BodyShape::Mesh, &[], Vec3::new(4.0, 1.0, 3.0));
        c.path = Some("hull.obj".into());
        vec![a, b, c]
    }

    /// One scene per water model (two for the FFT ocean: swell's keys and Blender's) in which every
    /// key of the scene format is set: both kinds of light, the sun's own direction, a power-law
    /// gamma, a flat bottom and a texture, a terrain with size and extent, the models' optional keys.
    fn scenes_with_every_key() -> Vec<(String, Scene)> {
        let mut base = preset("sea").unwrap();
        base.lights = vec![lights::NEW_DIRECTIONAL, lights::NEW_POINT];
        base.sky.sun_direction = Some(sky::DEFAULT_SUN_DIRECTION);
        base.render.gamma = Some(render::DEFAULT_POWER_GAMMA);
        let mut t = terrain::switch_generator(None, Some("hills")).unwrap().unwrap();
        t.size = Some(65);
        t.extent = Some(swell::scene::DEFAULT_TERRAIN_EXTENT);
        t.far_land = Some(swell::terrain::FarLandParams::default());
        base.terrain = Some(t);
        base.bodies = bodies_with_every_key();
        let depth = "dispersion = { type = 'finite-depth', depth = 12.0 }\n";
        let listed = "waves = [{ amplitude = 0.2, wavelength = 20.0, direction = [1.0, 0.0], phase = 0.5 }]\n";
        let models: Vec<(&str, String)> = vec![
            ("gerstner", String::new()),
            ("sines", String::new()),
            ("tessendorf", format!("{depth}loop_period = 30.0\n{listed}")),
            ("wave-set", depth.into()),
            ("airy", format!("{depth}{listed}")),
            (
                "steep-sines",
                "waves = [{ amplitude = 0.2, frequency = 0.3, velocity = 2.0, direction = [1.0, 0.0], exponent = 2.0 }]\n"
                    .into(),
            ),
            ("radial", String::new()),
            ("noise", String::new()),
            ("springs", "drops = { interval = 4.0, radius = 1.0, depth = 0.8, seed = 3 }\n".into()),
            ("river", String::new()),
            (
                "fft",
                "depth = 20.0\nloop_period = 60.0\nswell = { height = 1.0, period = 12.0, direction_deg = 30.0, spread = 8.0 }\n"
                    .into(),
            ),
        ];
        assert_eq!(models.len(), swell::scene::WATER_MODELS.len(), "a model without a scene here");
        let mut scenes: Vec<(String, Scene)> = models
            .into_iter()
            .map(|(m, extra)| {
                let mut s = base.clone();
                let mut w = water_with(m, &extra);
                // Fresh water: written to the file only when it is not sea water.
                w.density = 1000.0;
                w.material.bottom_depth = Some(water::DEFAULT_BOTTOM_DEPTH_M);
                w.material.texture = Some("procedural".into());
                w.material.foam_texture = Some("procedural".into());
                // Left out of the file at their identity values.
                w.surface.yaw_deg = 15.0;
                w.surface.uniform_scale = 1.5;
                set_extent_and_lod(&mut w);
                s.water = Some(w);
                (m.to_string(), s)
            })
            .collect();
        let mut blender = base.clone();
        blender.water = preset("ocean-blender").unwrap().water;
        blender.water.as_mut().unwrap().surface.yaw_deg = 15.0;
        set_extent_and_lod(blender.water.as_mut().unwrap());
        scenes.push(("fft with [water.blender]".into(), blender));
        // A measured sea: every table key set (the files are named, not read, by the panel).
        let mut measured = base.clone();
        let table = "spectrum = 'table'\nspectrum_direction = 'going-to'\nspectrum_file = 'a.csv'\n\
            spectrum_table = [{ freq_hz = [0.05, 0.1, 0.2], dir_deg = [0.0, 180.0], efth = [[0.1, 0.0], [1.0, 0.5], [0.2, 0.0]] }, \
            { freq_rad_s = [0.4, 0.6, 1.0], dir_rad = [0.0, 3.0], efth = [[0.1, 0.0], [1.0, 0.5], [0.2, 0.0]] }]\n\
            ndbc = { density = 'b.data_spec', alpha1 = 'b.swdir', alpha2 = 'b.swdir2', r1 = 'b.swr1', r2 = 'b.swr2', \
            time = '2020-06-08 03:50', dir_step_deg = 5.0, estimator = 'weighted' }\n";
        let mut w = water_with("fft", table);
        set_extent_and_lod(&mut w);
        measured.water = Some(w);
        scenes.push(("fft with spectrum = \"table\"".into(), measured));
        scenes
    }

    /// The panel has a widget for every key of the scene format, for every water model, and
    /// declares no key the format does not have. A key without a widget fails here by name.
    ///
    /// The format's keys are every key of each scene, those its file leaves out at their defaults
    /// included ([`keys::format::scene_keys`], from the scene types' own serialisation): a new key
    /// fails here even while every preset leaves it at its default. A table left out whole
    /// (`water.lod` at its defaults) counts as covered by any widget inside it; the scenes below
    /// also set such tables, so that their own keys are checked one by one.
    #[test]
    fn the_panel_edits_every_key_of_the_scene_format() {
        let scenes = scenes_with_every_key();
        let not_edited = |k: &&String| !NOT_EDITED.iter().any(|(x, _)| x == k);
        let mut format = keys::format::SceneKeys::default();
        let mut all_declared = std::collections::BTreeSet::new();
        for (label, scene) in &scenes {
            let found = keys::format::scene_keys(scene);
            // The walk lays the scene out as its file does: a section it misses fails here.
            let table: toml::Table = toml::from_str(&scene.to_toml()).unwrap();
            assert_eq!(found.written, keys::key_paths(&table), "{label}: the key walk and the saved file disagree");
            let mut draft = scene.clone();
            let (_, declared) = keys::recording(|| {
                show_headless(&mut draft, &mut PanelState::default(), &mut Clock::default());
            });
            assert_eq!(&draft, scene, "{label}: showing changed the scene");
            let missing: Vec<_> = found.written.iter().filter(not_edited).filter(|k| !declared.contains(*k)).collect();
            assert!(missing.is_empty(), "{label}: no panel widget edits {missing:?}");
            let missing: Vec<_> = found
                .left_out
                .iter()
                .filter(not_edited)
                .filter(|k| !keys::format::SceneKeys::covered(&declared, k))
                .collect();
            assert!(
                missing.is_empty(),
                "{label}: no panel widget edits {missing:?} (left out of the file at their defaults)"
            );
            format.written.extend(found.written);
            format.left_out.extend(found.left_out);
            all_declared.extend(declared);
        }
        // And no declaration names a key that none of the scenes has (a typo, a renamed key): a
        // key written or left out, a key inside a table left out whole, or a table (its switch).
        let known = |d: &String| {
            let one: std::collections::BTreeSet<String> = [d.clone()].into();
            format.written.contains(d)
                || format.left_out.iter().any(|l| keys::format::SceneKeys::covered(&one, l))
                || format.written.iter().any(|w| w.starts_with(&format!("{d}.")) || w.starts_with(&format!("{d}[].")))
        };
        let unknown: Vec<_> = all_declared.iter().filter(|d| !known(d)).collect();
        assert!(unknown.is_empty(), "the panel declares keys the scene format does not have: {unknown:?}");
    }

    /// Numeric keys whose widget is a menu rather than a number (arrow keys do not step it).
    const MENU_NUMBERS: &[(&str, &str)] = &[("water.grid", "a menu of the powers of two the FFT takes")];

    /// Every leaf of a saved scene, with array-of-tables indices, and its value as text.
    fn leaf_values(scene: &Scene) -> std::collections::BTreeMap<String, String> {
        fn walk(prefix: &str, t: &toml::Table, out: &mut std::collections::BTreeMap<String, String>) {
            for (k, v) in t {
                let path = if prefix.is_empty() { k.clone() } else { format!("{prefix}.{k}") };
                match v {
                    toml::Value::Table(t) => walk(&path, t, out),
                    toml::Value::Array(items) if items.iter().all(toml::Value::is_table) && !items.is_empty() => {
                        for (i, item) in items.iter().enumerate() {
                            walk(&format!("{path}[{i}]"), item.as_table().expect("checked"), out);
                        }
                    }
                    v => {
                        out.insert(path, v.to_string());
                    }
                }
            }
        }
        let mut out = std::collections::BTreeMap::new();
        walk("", &toml::from_str(&scene.to_toml()).unwrap(), &mut out);
        out
    }

    /// `light[1].color` -> `light[].color`, the form panels declare.
    fn without_indices(path: &str) -> String {
        let mut out = String::new();
        let mut in_index = false;
        for c in path.chars() {
            match c {
                '[' => in_index = true,
                ']' => in_index = false,
                _ if in_index => continue,
                _ => {}
            }
            out.push(c);
        }
        out
    }

    /// Drives the panel with the keyboard, as a user can: Tab to each widget in turn and hold the
    /// up arrow (which steps a focused number by its drag speed per press). Returns the key paths of the
    /// scene that changed on the way.
    fn keys_the_keyboard_changes(scene: &Scene) -> std::collections::BTreeSet<String> {
        use eframe::egui;
        let ctx = egui::Context::default();
        let mut draft = scene.clone();
        let mut state = PanelState::default();
        let mut clock = Clock::default();
        let press = |key| egui::Event::Key {
            key,
            physical_key: None,
            pressed: true,
            repeat: false,
            modifiers: egui::Modifiers::NONE,
        };
        let mut frame = |events: Vec<egui::Event>, draft: &mut Scene| {
            let input = egui::RawInput { events, ..Default::default() };
            let mut output = ctx.run_ui(input, |ui| {
                egui::CentralPanel::default().show(ui, |ui| {
                    egui::ScrollArea::vertical().show(ui, |ui| show_all(ui, draft, &mut state, &mut clock, None));
                });
            });
            output.textures_delta.clear();
        };
        let mut changed = std::collections::BTreeSet::new();
        // Sections open (as while recording), so every widget can take the focus.
        keys::recording(|| {
            frame(vec![], &mut draft);
            frame(vec![], &mut draft);
            let mut visited = std::collections::HashSet::new();
            for _ in 0..5000 {
                let before = leaf_values(&draft);
                frame(vec![press(egui::Key::Tab)], &mut draft);
                let Some(id) = ctx.memory(|m| m.focused()) else { break };
                if !visited.insert(id) {
                    break; // around once
                }
                // Twenty presses (a held key): whole numbers with a drag speed below 1 (threads,
                // seeds) step by speed x presses.
                frame(vec![press(egui::Key::ArrowUp); 20], &mut draft);
                // The arrow may also move the focus upwards: put it back where Tab left it.
                ctx.memory_mut(|m| m.request_focus(id));
                frame(vec![], &mut draft);
                let after = leaf_values(&draft);
                for (k, v) in &after {
                    if before.get(k) != Some(v) {
                        changed.insert(without_indices(k));
                    }
                }
            }
        });
        changed
    }

    /// The declarations are honest for numbers: Tab to each widget and hold the up arrow, and
    /// every numeric key of the scene format changes in the draft scene (a declared key no widget
    /// really edits fails here by name). Switches, menus and texts are declared only.
    #[test]
    fn the_keyboard_reaches_every_numeric_key_through_the_panel() {
        for (label, scene) in scenes_with_every_key() {
            let table: toml::Table = toml::from_str(&scene.to_toml()).unwrap();
            let values = leaf_values(&scene);
            let numeric: std::collections::BTreeSet<String> = values
                .iter()
                .filter(|(_, v)| v.starts_with(|c: char| c.is_ascii_digit() || c == '-' || c == '['))
                .map(|(k, _)| without_indices(k))
                .filter(|k| !NOT_EDITED.iter().chain(MENU_NUMBERS).any(|(x, _)| x == k))
                .collect();
            assert!(keys::key_paths(&table).is_superset(&numeric));
            let changed = keys_the_keyboard_changes(&scene);
            let unreached: Vec<_> = numeric.difference(&changed).collect();
            assert!(unreached.is_empty(), "{label}: no widget the keyboard reaches changes {unreached:?}");
        }
    }

    #[test]
    fn with_bodies_a_dragged_edit_commits_once_when_the_drag_ends() {
        let mut held = false;
        // Bodies: frames of a drag hold the edit, the frame after it commits it once.
        assert!(!commit_now(true, true, true, &mut held));
        assert!(!commit_now(false, true, true, &mut held));
        assert!(!commit_now(true, true, true, &mut held));
        assert!(held);
        assert!(commit_now(false, false, true, &mut held));
        assert!(!held);
        assert!(!commit_now(false, false, true, &mut held), "committed twice");
        // Typed values and clicks commit at once; without bodies so does every frame of a drag.
        assert!(commit_now(true, false, true, &mut held));
        assert!(commit_now(true, true, false, &mut held));
        assert!(!commit_now(false, true, false, &mut held));
        // A drag of something else (the camera) with nothing held commits nothing.
        assert!(!commit_now(false, true, true, &mut held) && !held);
        // A held edit is kept to the drag's end even if the bodies went meanwhile.
        assert!(!commit_now(true, true, true, &mut held));
        assert!(!commit_now(false, true, false, &mut held));
        assert!(commit_now(false, false, false, &mut held));
    }

    #[test]
    fn the_panel_shows_scenes_without_water_and_with_every_model() {
        let mut scene = preset("sea").unwrap();
        scene.water = None;
        let mut draft = scene.clone();
        show_headless(&mut draft, &mut PanelState::default(), &mut Clock::default());
        assert_eq!(draft, scene);
        for &m in swell::scene::WATER_MODELS {
            scene.water = Some(water::switch_model(None, m).unwrap());
            let mut draft = scene.clone();
            show_headless(&mut draft, &mut PanelState::default(), &mut Clock::default());
            assert_eq!(draft, scene, "model {m}");
        }
    }
}
