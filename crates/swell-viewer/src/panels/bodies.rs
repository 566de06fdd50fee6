//! The bodies panel (`[[body]]`, issue 34): what a left click on the water does (dent it, drop a
//! crate, drop a buoy), *Add crate* / *Add buoy*, which body the keys push, and every key of every
//! body with where the last frame showed it.
//!
//! Drops do not edit the draft: they go to the render thread's world and come back as specs the
//! editor appends ([`crate::body_control`]), so the world is not rebuilt for them. Every other
//! edit goes through the draft like any key: validated, then committed, and the world is rebuilt
//! from the scene (the bodies replayed from t = 0, a drop at its release time).

use std::path::PathBuf;

use eframe::egui::{self, CollapsingHeader, DragValue, Ui};
use glam::{Vec3, Vec3Swizzles};
use swell::body::{BodyShape, BodySpec, DEFAULT_BODY_DENSITY, MAX_BODIES};

use super::{fields, keys};
use crate::body_control::{DropKind, LiveBody};

/// What a plain left click on the water does (Shift+click always drops a crate).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ClickMode {
    /// Dent the water where it takes dents (the spring mesh), as before bodies existed.
    #[default]
    Disturb,
    /// Drop a body of this kind where the click meets the water.
    Drop(DropKind),
}

/// Every click mode with its label, in the order the menu shows them.
pub const CLICK_MODES: [(ClickMode, &str); 3] = [
    (ClickMode::Disturb, "disturb the water"),
    (ClickMode::Drop(DropKind::Crate), "drop a crate"),
    (ClickMode::Drop(DropKind::Buoy), "drop a buoy"),
];

/// What the bodies panel remembers between frames (not part of the scene).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct BodiesForm {
    /// What a plain click on the water does.
    pub click: ClickMode,
    /// The body the keys push, by index; `None` (or an index past the list): the last body.
    pub selected: Option<usize>,
    /// Every body as the last frame showed it, in scene order.
    pub live: Vec<LiveBody>,
    /// Why the last drop was refused.
    pub message: Option<String>,
}

impl BodiesForm {
    /// The index of the body the keys push among `count` bodies: the chosen one while it exists,
    /// else the last (the one dropped last, as drops are appended); `None` without bodies.
    pub fn pushed(&self, count: usize) -> Option<usize> {
        self.selected.filter(|&i| i < count).or(count.checked_sub(1))
    }

    /// A drop was added as body `index`: the keys push it from now on.
    pub fn dropped(&mut self, index: usize) {
        self.selected = Some(index);
        self.message = None;
    }
}

/// How a body's mass is given: `density`, `mass` or neither (the default density).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MassBy {
    /// Neither key: [`DEFAULT_BODY_DENSITY`].
    DefaultDensity,
    /// `density`.
    Density,
    /// `mass`.
    Mass,
}

/// Which of `density` and `mass` `spec` gives (`Mass` when both are, which validation refuses).
pub fn mass_by(spec: &BodySpec) -> MassBy {
    match (spec.density, spec.mass) {
        (_, Some(_)) => MassBy::Mass,
        (Some(_), None) => MassBy::Density,
        (None, None) => MassBy::DefaultDensity,
    }
}

/// Volume (m³) of `spec`'s hull, from its shape, size and mesh alone; `None` while those are not
/// valid or the mesh cannot be read.
pub fn hull_volume(spec: &BodySpec) -> Option<f64> {
    let mut shape_only = BodySpec::new(spec.shape, &spec.size, Vec3::ZERO);
    shape_only.path.clone_from(&spec.path);
    shape_only.validate("body").ok()?;
    Some(shape_only.hull("body").ok()?.mass_properties().volume)
}

/// Gives `spec`'s mass as `by` says, keeping the mass it has where the hull's volume is known (a
/// 500 kg/m³ crate of 1 m³ becomes `mass = 500`, and back), so the body does not change.
pub fn set_mass_by(spec: &mut BodySpec, by: MassBy) {
    let volume = hull_volume(spec);
    let density = match (spec.density, spec.mass, volume) {
        (Some(d), _, _) => d,
        (None, Some(m), Some(v)) if v > 0.0 => (f64::from(m) / v) as f32,
        _ => DEFAULT_BODY_DENSITY,
    };
    (spec.density, spec.mass) = match by {
        MassBy::DefaultDensity => (None, None),
        MassBy::Density => (Some(density), None),
        // Without a volume (a size being typed), a cubic metre's worth.
        MassBy::Mass => (None, Some((f64::from(density) * volume.unwrap_or(1.0)) as f32)),
    };
}

/// The size a body of `shape` starts with when switched to it, m: a 1 m box, a 0.5 m ball, a
/// 2 m log of 0.25 m radius; a mesh has its file's.
pub fn default_size(shape: BodyShape) -> Vec<f32> {
    match shape {
        BodyShape::Box => vec![1.0, 1.0, 1.0],
        BodyShape::Sphere => vec![0.5],
        BodyShape::Capsule => vec![0.25, 2.0],
        BodyShape::Mesh => Vec::new(),
    }
}

/// Switches `spec` to `shape` with [`default_size`]; a mesh starts with an empty `path`, which
/// validation refuses until a file is named (the refusal says so), and the other shapes have none.
pub fn switch_shape(spec: &mut BodySpec, shape: BodyShape) {
    if spec.shape == shape {
        return;
    }
    spec.shape = shape;
    spec.size = default_size(shape);
    spec.path = (shape == BodyShape::Mesh).then(PathBuf::new);
}

/// Names of the parts of `shape`'s `size` (`len` values), as the panel labels them; plain when
/// the count is not the shape's (a value being refused).
fn size_parts(shape: BodyShape, len: usize) -> &'static [&'static str] {
    let names: &'static [&'static str] = match shape {
        BodyShape::Box => &["x ", "y ", "z "],
        BodyShape::Sphere => &["radius "],
        BodyShape::Capsule => &["radius ", "length "],
        BodyShape::Mesh => &[],
    };
    if names.len() == len {
        names
    } else {
        &["", "", "", "", "", "", "", ""]
    }
}

/// The principal moments (kg·m²) of `spec`'s solid hull about its centre of mass, what an unset
/// `inertia` gives: where ticking `inertia` starts, so the body does not change. `None` while
/// the body does not build.
pub fn solid_inertia(spec: &BodySpec) -> Option<Vec3> {
    let unset = BodySpec { inertia: None, ..spec.clone() };
    let m = unset.build(0, "body").ok()?.material.inertia;
    Some(glam::DVec3::new(m.x_axis.x, m.y_axis.y, m.z_axis.z).as_vec3())
}

/// Removes body `i` from `bodies` and from what the form knows of it; the pushed body stays the
/// same body (or goes back to the last one if it was `i`).
pub fn remove_body(bodies: &mut Vec<BodySpec>, form: &mut BodiesForm, i: usize) {
    if i >= bodies.len() {
        return;
    }
    bodies.remove(i);
    if i < form.live.len() {
        form.live.remove(i);
    }
    form.selected = match form.selected {
        Some(s) if s == i => None,
        Some(s) if s > i => Some(s - 1),
        s => s,
    };
}

/// The line under a body: where the last frame showed it.
pub fn live_line(live: &LiveBody) -> String {
    let p = live.position;
    let mut s = format!("now at ({:.2}, {:.2}, {:.2}) m", p.x, p.y, p.z);
    if let Some(h) = live.water_height {
        s.push_str(&format!(", centre {:+.2} m from the water", p.y - h));
    }
    s.push_str(&format!(
        ", {:.2} m/s ({:.2} across), {:.1} kg",
        live.velocity.length(),
        live.velocity.xz().length(),
        live.mass
    ));
    s
}

/// The name a body goes by: its `name`, or `body<i>`.
fn shown_name(spec: &BodySpec, i: usize) -> String {
    if spec.name.is_empty() {
        format!("body{i}")
    } else {
        spec.name.clone()
    }
}

/// Every key of one body (number `i`); returns whether it changed.
fn show_body(ui: &mut Ui, i: usize, spec: &mut BodySpec) -> bool {
    let mut changed = false;
    fields::grid("body").show(ui, |ui| {
        ui.label("name");
        let hint = format!("body{i}");
        changed |= ui.add(egui::TextEdit::singleline(&mut spec.name).hint_text(hint).desired_width(180.0)).changed();
        ui.end_row();
        let mut shape = spec.shape;
        if fields::member(ui, "shape", &mut shape) {
            switch_shape(spec, shape);
            changed = true;
        }
        ui.label("size");
        ui.horizontal(|ui| {
            let parts = size_parts(spec.shape, spec.size.len());
            for (v, name) in spec.size.iter_mut().zip(parts) {
                changed |= ui.add(DragValue::new(v).speed(0.01).prefix(*name).suffix(" m").max_decimals(4)).changed();
            }
            if spec.size.is_empty() {
                ui.weak("the mesh's own");
            }
        });
        ui.end_row();
        keys::edits("body[]", &["name", "shape", "size"]);
        // Only a mesh reads a file; another shape shows a path only to let a refused one be cleared.
        if spec.shape == BodyShape::Mesh || spec.path.is_some() {
            ui.label("OBJ file");
            let mut text = spec.path.as_ref().map(|p| p.display().to_string()).unwrap_or_default();
            let edit = egui::TextEdit::singleline(&mut text).hint_text("hull.obj").desired_width(220.0);
            if ui.add(edit).changed() {
                spec.path = Some(PathBuf::from(text));
                changed = true;
            }
            ui.end_row();
            keys::edits("body[]", &["path"]);
        }
        let mut by = mass_by(spec);
        let default_label = format!("default density ({DEFAULT_BODY_DENSITY} kg/m³)");
        let options =
            [(MassBy::DefaultDensity, default_label.as_str()), (MassBy::Density, "density"), (MassBy::Mass, "mass")];
        if fields::choice(ui, "mass from", &mut by, &options) {
            set_mass_by(spec, by);
            changed = true;
        }
        if let Some(d) = &mut spec.density {
            changed |= fields::number(ui, "  density", d, 1.0, " kg/m³");
        }
        if let Some(m) = &mut spec.mass {
            changed |= fields::number(ui, "  mass", m, 1.0, " kg");
        }
        keys::edits("body[]", &["density", "mass"]);
        changed |=
            fields::optional_vec3(ui, "centre of mass (off: centroid)", &mut spec.center_of_mass, Vec3::ZERO, 0.01);
        let solid = || solid_inertia(spec).unwrap_or(Vec3::ONE);
        let mut inertia = spec.inertia;
        if fields::optional_vec3_from(ui, "inertia kg·m² (off: solid)", &mut inertia, solid, 0.1) {
            spec.inertia = inertia;
            changed = true;
        }
        changed |= fields::vec3(ui, "position (m)", &mut spec.position, 0.05);
        let turn = ["yaw ", "pitch ", "roll "];
        changed |= fields::vec3_parts(ui, "rotation", &mut spec.rotation_deg, 0.5, turn, "°");
        changed |= fields::vec3(ui, "velocity (m/s)", &mut spec.velocity, 0.05);
        changed |= fields::vec3(ui, "angular velocity (rad/s)", &mut spec.angular_velocity, 0.01);
        ui.label("release time");
        let release = DragValue::new(&mut spec.release_time).speed(0.05).suffix(" s").max_decimals(4);
        changed |= ui.add(release).on_hover_text("held still until then (a drop: the time of the click)").changed();
        ui.end_row();
        changed |= fields::number(ui, "drag", &mut spec.drag, 0.01, "");
        changed |= fields::number(ui, "linear drag", &mut spec.linear_drag, 0.5, " N·s/m³");
        changed |= fields::number(ui, "friction", &mut spec.friction, 0.01, "");
        changed |= fields::color(ui, "colour", &mut spec.color);
        keys::edits(
            "body[]",
            &[
                "center_of_mass",
                "inertia",
                "position",
                "rotation_deg",
                "velocity",
                "angular_velocity",
                "release_time",
                "drag",
                "linear_drag",
                "friction",
                "color",
            ],
        );
    });
    changed
}

/// Shows the click mode, the *Add* buttons, the pushed body and every body; returns whether
/// `bodies` changed and which kind an *Add* button asked to drop (at the view's centre).
pub fn show(ui: &mut Ui, bodies: &mut Vec<BodySpec>, form: &mut BodiesForm) -> (bool, Option<DropKind>) {
    let mut changed = false;
    let mut drop = None;
    fields::grid("bodies-click").show(ui, |ui| {
        fields::choice(ui, "left click on the water", &mut form.click, &CLICK_MODES);
    });
    ui.small("Shift+click always drops a crate. A drop falls from 1 m above the surface under the pointer.");
    ui.horizontal(|ui| {
        let n = bodies.len();
        ui.label(if n == 1 { "1 body".to_string() } else { format!("{n} bodies") });
        ui.add_enabled_ui(n < MAX_BODIES, |ui| {
            for kind in DropKind::ALL {
                if ui
                    .button(format!("Add {}", kind.name()))
                    .on_hover_text("dropped at the centre of the view")
                    .clicked()
                {
                    drop = Some(kind);
                }
            }
        });
    });
    // The buttons add `[[body]]` entries (through the render thread's world).
    keys::edits("", &["body"]);
    ui.small(
        "An edit replays every body from t = 0, one water step per 1/120 s (seconds on the FFT sea late in a \
         run: Time > Restart first to edit quickly); a dragged value is committed when let go. Drops replay nothing.",
    );
    if let Some(m) = &form.message {
        ui.colored_label(ui.visuals().error_fg_color, m);
    }
    if !bodies.is_empty() {
        let names: Vec<String> = bodies.iter().enumerate().map(|(i, b)| shown_name(b, i)).collect();
        let last = format!("the last ({})", names[names.len() - 1]);
        let mut options = vec![(None, last.as_str())];
        options.extend(names.iter().enumerate().map(|(i, n)| (Some(i), n.as_str())));
        fields::grid("bodies-push").show(ui, |ui| {
            fields::choice(ui, "I J K L push", &mut form.selected, &options);
        });
        ui.small("I forward, K back, J left, L right, as the camera looks; 2 m/s² times the body's mass.");
    }
    let pushed = form.pushed(bodies.len());
    let mut delete = None;
    for (i, spec) in bodies.iter_mut().enumerate() {
        let marker = if pushed == Some(i) { "  (pushed by I J K L)" } else { "" };
        let title = format!("body[{i}] {} ({}){marker}", shown_name(spec, i), spec.shape);
        ui.push_id(("body", i), |ui| {
            CollapsingHeader::new(title).id_salt("header").default_open(keys::is_recording()).show(ui, |ui| {
                changed |= show_body(ui, i, spec);
                if let Some(live) = form.live.get(i) {
                    ui.small(live_line(live));
                }
                if ui.small_button("delete").clicked() {
                    delete = Some(i);
                }
            });
        });
    }
    if let Some(i) = delete {
        remove_body(bodies, form, i);
        changed = true;
    }
    (changed, drop)
}

#[cfg(test)]
mod tests {
    use swell::scene::preset;

    use super::*;
    use crate::editor::SceneEditor;

    fn crate_at(x: f32) -> BodySpec {
        BodySpec::new(BodyShape::Box, &[1.0, 1.0, 1.0], Vec3::new(x, 0.0, 0.0))
    }

    /// `edit` applied to the `sea` preset with two crates, committed through the editor as the
    /// panel's edits are: the committed scene (checked to save and load back unchanged) or the
    /// refusal shown at the top of the panel.
    fn commit(edit: impl FnOnce(&mut Vec<BodySpec>)) -> Result<Vec<BodySpec>, String> {
        let mut scene = preset("sea").unwrap();
        scene.bodies = vec![crate_at(0.0), crate_at(3.0)];
        let mut e = SceneEditor::new(scene.clone()).unwrap();
        edit(&mut e.draft.bodies);
        match e.apply() {
            Ok(()) => {
                let back = swell::scene::Scene::from_toml(&e.scene().to_toml(), "t").unwrap();
                assert_eq!(&back, e.scene());
                Ok(back.bodies)
            }
            Err(err) => {
                assert_eq!(e.scene(), &scene, "a refused edit changed the scene");
                Err(err.to_string())
            }
        }
    }

    #[test]
    fn every_shape_switched_to_has_a_valid_size_and_a_mesh_asks_for_its_file() {
        for &shape in BodyShape::ALL {
            let mut b = crate_at(0.0);
            switch_shape(&mut b, shape);
            assert_eq!(b.shape, shape);
            match shape {
                BodyShape::Mesh => {
                    let e = b.validate("body[0]").unwrap_err().to_string();
                    assert!(e.contains("body[0].path"), "{e}");
                    b.path = Some("hull.obj".into());
                    b.validate("body[0]").unwrap();
                }
                _ => b.validate("body[0]").unwrap(),
            }
            // Back to a box: a box again, with no path left behind.
            switch_shape(&mut b, BodyShape::Box);
            assert_eq!(b, crate_at(0.0));
        }
    }

    #[test]
    fn switching_between_density_and_mass_keeps_the_mass() {
        let mut b = crate_at(0.0);
        b.size = vec![2.0, 0.5, 1.0];
        assert_eq!(mass_by(&b), MassBy::DefaultDensity);
        set_mass_by(&mut b, MassBy::Mass);
        assert_eq!((b.density, b.mass), (None, Some(500.0)));
        b.mass = Some(250.0);
        set_mass_by(&mut b, MassBy::Density);
        assert_eq!((b.density, b.mass), (Some(250.0), None));
        set_mass_by(&mut b, MassBy::DefaultDensity);
        assert_eq!((b.density, b.mass), (None, None));
        // A sphere's volume is its hull's, not the box around it.
        let mut ball = BodySpec::new(BodyShape::Sphere, &[0.5], Vec3::ZERO);
        ball.density = Some(300.0);
        set_mass_by(&mut ball, MassBy::Mass);
        let built = ball.build(0, "body[0]").unwrap().material.mass;
        assert!((f64::from(ball.mass.unwrap()) - 300.0 * hull_volume(&ball).unwrap()).abs() < 1e-3);
        assert!((built - f64::from(ball.mass.unwrap())).abs() < 1e-3, "{built}");
        // A ball fills about half (pi / 6) of its box.
        assert!((0.45..0.55).contains(&(built / 300.0)), "{built}");
        // Without a valid size there is no volume: a cubic metre's worth, and no panic.
        let mut bad = crate_at(0.0);
        bad.size = vec![-1.0, 1.0, 1.0];
        set_mass_by(&mut bad, MassBy::Mass);
        assert_eq!(bad.mass, Some(DEFAULT_BODY_DENSITY));
    }

    #[test]
    fn ticking_inertia_starts_from_the_solid_hull_s_and_changes_nothing() {
        let b = crate_at(0.0);
        let i = solid_inertia(&b).unwrap();
        // A 500 kg unit cube: m (1 + 1) / 12 about each axis.
        assert!((i - Vec3::splat(500.0 * 2.0 / 12.0)).abs().max_element() < 1e-3, "{i}");
        let with = BodySpec { inertia: Some(i), ..b.clone() };
        let (a, c) = (b.build(0, "b").unwrap().material.inertia, with.build(0, "b").unwrap().material.inertia);
        assert!((a - c).abs_diff_eq(glam::DMat3::ZERO, 1e-3), "{a} vs {c}");
        assert_eq!(solid_inertia(&BodySpec { size: vec![0.0], ..b }), None);
    }

    #[test]
    fn edits_commit_through_the_scene_and_bad_values_are_refused_by_key() {
        let bodies = commit(|b| {
            b[1].position.y = 2.0;
            b[1].rotation_deg.x = 30.0;
            b[1].color = Vec3::new(0.9, 0.1, 0.1);
            b[0].name = "raft".into();
            switch_shape(&mut b[0], BodyShape::Capsule);
        })
        .unwrap();
        assert_eq!((bodies[0].name.as_str(), bodies[0].shape), ("raft", BodyShape::Capsule));
        assert_eq!((bodies[1].position.y, bodies[1].rotation_deg.x), (2.0, 30.0));
        for (edit, key) in [
            (
                Box::new(|b: &mut Vec<BodySpec>| b[0].size[1] = -1.0) as Box<dyn FnOnce(&mut Vec<BodySpec>)>,
                "body[0].size[1]",
            ),
            (Box::new(|b: &mut Vec<BodySpec>| b[1].friction = 5.0), "body[1].friction"),
            (Box::new(|b: &mut Vec<BodySpec>| b[1].name = "body0".into()), "body[1].name"),
            (Box::new(|b: &mut Vec<BodySpec>| (b[0].density, b[0].mass) = (Some(500.0), Some(10.0))), "body[0].mass"),
            (Box::new(|b: &mut Vec<BodySpec>| b[0].release_time = -1.0), "body[0].release_time"),
            (Box::new(|b: &mut Vec<BodySpec>| switch_shape(&mut b[1], BodyShape::Mesh)), "body[1].path"),
        ] {
            let e = commit(edit).unwrap_err();
            assert!(e.contains(key), "{key}: {e}");
        }
    }

    #[test]
    fn removing_a_body_keeps_the_pushed_one() {
        let mut bodies = vec![crate_at(0.0), crate_at(1.0), crate_at(2.0)];
        let mut form = BodiesForm { selected: Some(2), live: vec![LiveBody::default(); 3], ..Default::default() };
        assert_eq!(form.pushed(3), Some(2));
        remove_body(&mut bodies, &mut form, 0);
        assert_eq!((bodies.len(), form.live.len(), form.selected), (2, 2, Some(1)));
        remove_body(&mut bodies, &mut form, 1);
        assert_eq!(form.selected, None, "the pushed body is gone: back to the last");
        assert_eq!(form.pushed(bodies.len()), Some(0));
        remove_body(&mut bodies, &mut form, 5);
        assert_eq!(bodies.len(), 1);
        // The last body by default, a drop becomes the pushed one, and none without bodies.
        let mut form = BodiesForm::default();
        assert_eq!((form.pushed(4), form.pushed(0)), (Some(3), None));
        form.message = Some("refused".into());
        form.dropped(1);
        assert_eq!((form.pushed(4), form.message.as_deref()), (Some(1), None));
        assert_eq!(BodiesForm { selected: Some(9), ..Default::default() }.pushed(4), Some(3));
    }

    #[test]
    fn the_live_line_says_how_far_the_centre_is_from_the_water() {
        let live = LiveBody {
            position: Vec3::new(1.0, 0.25, -2.0),
            velocity: Vec3::new(3.0, 4.0, 0.0),
            water_height: Some(0.05),
            mass: 500.0,
        };
        assert_eq!(
            live_line(&live),
            "now at (1.00, 0.25, -2.00) m, centre +0.20 m from the water, 5.00 m/s (3.00 across), 500.0 kg"
        );
        assert!(!live_line(&LiveBody { water_height: None, ..live }).contains("water"));
    }
}
