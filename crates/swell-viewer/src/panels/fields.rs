//! Field editors every panel uses: one labelled number, vector or colour per grid row.
//!
//! They never clamp: a value outside its range is kept in the draft and refused by validation,
//! with the reason shown at the top of the panel (see [`crate::editor::SceneEditor::apply`]).

use eframe::egui::{self, DragValue, Ui};
use glam::{Vec2, Vec3};
use swell::closed_set::ClosedSet;

/// A labelled number with a unit suffix (`" m"`, `" m/s"`, `""`); returns whether it changed.
pub fn number(ui: &mut Ui, label: &str, value: &mut f32, speed: f64, suffix: &str) -> bool {
    ui.label(label);
    let changed = ui.add(DragValue::new(value).speed(speed).suffix(suffix).max_decimals(4)).changed();
    ui.end_row();
    changed
}

/// A labelled whole number.
pub fn count(ui: &mut Ui, label: &str, value: &mut u32, speed: f64) -> bool {
    ui.label(label);
    let changed = ui.add(DragValue::new(value).speed(speed)).changed();
    ui.end_row();
    changed
}

/// A labelled whole number that drags and steps (arrow keys) in multiples of `step`, for keys
/// that take only multiples (`water.lod.ring_cells`, multiples of 4): dragging then passes only
/// through values the key accepts instead of refusing three in four. A typed value is kept as
/// typed, multiple or not, and refused by validation like any other. `speed` is in steps per
/// point of drag and per key press; each press lands on a whole step, so a speed below 1 (as
/// other counts take) would leave single presses where they were.
pub fn count_in_steps(ui: &mut Ui, label: &str, value: &mut u32, step: u32, speed: f64) -> bool {
    ui.label(label);
    let step = f64::from(step.max(1));
    let before = *value;
    // The widget edits the number of steps (whole, so drags land on multiples); the text shows
    // and reads the value itself.
    ui.add(
        DragValue::from_get_set(|set| {
            if let Some(steps) = set {
                *value = (steps * step).round().clamp(0.0, f64::from(u32::MAX)) as u32;
            }
            f64::from(*value) / step
        })
        .speed(speed)
        .max_decimals(0)
        .custom_formatter(|steps, _| format!("{}", (steps * step).round()))
        .custom_parser(|text| text.trim().parse::<f64>().ok().map(|v| v / step)),
    );
    ui.end_row();
    *value != before
}

/// Three drag values for a 3-vector, without a label or row end (for use inside tables).
pub fn vec3_inline(ui: &mut Ui, v: &mut Vec3, speed: f64) -> bool {
    vec3_parts_inline(ui, v, speed, ["x ", "y ", "z "], "")
}

/// Three drag values for a 3-vector whose parts have their own names (`yaw`, `pitch`, `roll`) and
/// a unit suffix, without a label or row end.
pub fn vec3_parts_inline(ui: &mut Ui, v: &mut Vec3, speed: f64, names: [&str; 3], suffix: &str) -> bool {
    let mut changed = false;
    for (c, name) in [&mut v.x, &mut v.y, &mut v.z].into_iter().zip(names) {
        changed |= ui.add(DragValue::new(c).speed(speed).prefix(name).suffix(suffix).max_decimals(4)).changed();
    }
    changed
}

/// A labelled 3-vector with named parts and a unit suffix ([`vec3_parts_inline`]).
pub fn vec3_parts(ui: &mut Ui, label: &str, v: &mut Vec3, speed: f64, names: [&str; 3], suffix: &str) -> bool {
    ui.label(label);
    let changed = ui.horizontal(|ui| vec3_parts_inline(ui, v, speed, names, suffix)).inner;
    ui.end_row();
    changed
}

/// A labelled 3-vector (x, y, z).
pub fn vec3(ui: &mut Ui, label: &str, v: &mut Vec3, speed: f64) -> bool {
    ui.label(label);
    let changed = ui.horizontal(|ui| vec3_inline(ui, v, speed)).inner;
    ui.end_row();
    changed
}

/// A labelled horizontal 2-vector, shown as (x, z) as scene files mean it.
pub fn vec2_xz(ui: &mut Ui, label: &str, v: &mut Vec2, speed: f64) -> bool {
    ui.label(label);
    let changed = ui
        .horizontal(|ui| {
            let a = ui.add(DragValue::new(&mut v.x).speed(speed).prefix("x ").max_decimals(4)).changed();
            let b = ui.add(DragValue::new(&mut v.y).speed(speed).prefix("z ").max_decimals(4)).changed();
            a | b
        })
        .inner;
    ui.end_row();
    changed
}

/// A labelled linear-RGB colour: a swatch with egui's (linear) picker and the three components,
/// which may exceed 1 where the scene allows it (light colours).
pub fn color(ui: &mut Ui, label: &str, c: &mut Vec3) -> bool {
    ui.label(label);
    let changed = ui
        .horizontal(|ui| {
            let mut rgb = c.to_array();
            let mut changed = false;
            // The picker works in [0, 1]; only offer it when the colour is inside that range, so
            // showing it can never rewrite a brighter colour.
            if rgb.iter().all(|v| (0.0..=1.0).contains(v))
                && egui::color_picker::color_edit_button_rgb(ui, &mut rgb).changed()
            {
                *c = Vec3::from_array(rgb);
                changed = true;
            }
            for (v, name) in [(&mut c.x, "r "), (&mut c.y, "g "), (&mut c.z, "b ")] {
                changed |= ui.add(DragValue::new(v).speed(0.005).prefix(name).max_decimals(3)).changed();
            }
            changed
        })
        .inner;
    ui.end_row();
    changed
}

/// A labelled triple of numbers per linear RGB channel that is not a colour (an absorption
/// coefficient, 1/m), with a unit suffix; no colour picker.
pub fn rgb_numbers(ui: &mut Ui, label: &str, v: &mut Vec3, speed: f64, suffix: &str) -> bool {
    ui.label(label);
    let changed = ui
        .horizontal(|ui| {
            let mut changed = false;
            for (c, name) in [(&mut v.x, "r "), (&mut v.y, "g "), (&mut v.z, "b ")] {
                changed |= ui.add(DragValue::new(c).speed(speed).prefix(name).suffix(suffix).max_decimals(4)).changed();
            }
            changed
        })
        .inner;
    ui.end_row();
    changed
}

/// A labelled optional 3-vector: a check box (`None` when off) and, when on, its components.
/// Turning it on starts from `default`.
pub fn optional_vec3(ui: &mut Ui, label: &str, value: &mut Option<Vec3>, default: Vec3, speed: f64) -> bool {
    optional_vec3_from(ui, label, value, || default, speed)
}

/// [`optional_vec3`] whose starting value is computed only when the box is ticked: a default that
/// costs something to find (a body's inertia, from its hull) is not computed every frame.
pub fn optional_vec3_from(
    ui: &mut Ui,
    label: &str,
    value: &mut Option<Vec3>,
    default: impl FnOnce() -> Vec3,
    speed: f64,
) -> bool {
    ui.label(label);
    let changed = ui
        .horizontal(|ui| {
            let mut on = value.is_some();
            let mut changed = false;
            if ui.checkbox(&mut on, "").changed() {
                *value = on.then(default);
                changed = true;
            }
            if let Some(v) = value {
                changed |= vec3_inline(ui, v, speed);
            }
            changed
        })
        .inner;
    ui.end_row();
    changed
}

/// A labelled optional text (a file name): a check box (`None` when off) and, when on, a text
/// field. Turning it on starts from `default`.
pub fn optional_text(ui: &mut Ui, label: &str, value: &mut Option<String>, default: &str) -> bool {
    ui.label(label);
    let changed = ui
        .horizontal(|ui| {
            let mut on = value.is_some();
            let mut changed = false;
            if ui.checkbox(&mut on, "").changed() {
                *value = on.then(|| default.to_owned());
                changed = true;
            }
            if let Some(text) = value {
                changed |= ui.add(egui::TextEdit::singleline(text).desired_width(180.0)).changed();
            }
            changed
        })
        .inner;
    ui.end_row();
    changed
}

/// A two-column grid for `label | editor` rows, with a unique id.
pub fn grid(id: &str) -> egui::Grid {
    egui::Grid::new(id).num_columns(2).spacing([8.0, 4.0])
}

/// A labelled optional number: a check box (`None` when off) and, when on, its value. Turning it on
/// starts from `default`.
pub fn optional_number(
    ui: &mut Ui,
    label: &str,
    value: &mut Option<f32>,
    default: f32,
    speed: f64,
    suffix: &str,
) -> bool {
    toggled_number(ui, label, value, default, speed, suffix, None)
}

/// A labelled optional number whose absence means "automatic" (`water.lod.spacing`): an *auto*
/// check box, on when the value is `None`, showing `auto_value`, what the scene then gets; turned
/// off, the number starts from `auto_value`, so the picture does not jump.
pub fn auto_number(
    ui: &mut Ui,
    label: &str,
    value: &mut Option<f32>,
    auto_value: f32,
    speed: f64,
    suffix: &str,
) -> bool {
    toggled_number(ui, label, value, auto_value, speed, suffix, Some("auto"))
}

/// The row both of the above are: a check box and, when `value` is set, its number (set to
/// `start` when the box turns it on). With `auto` the box is labelled so and checked while the
/// value is `None`, which shows `start` greyed; without, the box is checked while it is set.
fn toggled_number(
    ui: &mut Ui,
    label: &str,
    value: &mut Option<f32>,
    start: f32,
    speed: f64,
    suffix: &str,
    auto: Option<&str>,
) -> bool {
    ui.label(label);
    let changed = ui
        .horizontal(|ui| {
            let mut checked = value.is_some() != auto.is_some();
            let mut changed = false;
            if ui.checkbox(&mut checked, auto.unwrap_or("")).changed() {
                *value = (checked != auto.is_some()).then_some(start);
                changed = true;
            }
            match value {
                Some(v) => changed |= ui.add(DragValue::new(v).speed(speed).suffix(suffix).max_decimals(4)).changed(),
                // Four decimals, as the number shows once it is set.
                None if auto.is_some() => {
                    ui.weak(format!("{}{suffix}", (start * 1e4).round() / 1e4));
                }
                None => {}
            }
            changed
        })
        .inner;
    ui.end_row();
    changed
}

/// A labelled choice among `options` (value, name) in a combo box; returns whether it changed.
pub fn choice<T: PartialEq + Copy>(ui: &mut Ui, label: &str, value: &mut T, options: &[(T, &str)]) -> bool {
    ui.label(label);
    let current = options.iter().find(|(v, _)| v == value).map_or("?", |(_, n)| n);
    let mut changed = false;
    egui::ComboBox::from_id_salt(("choice", label)).selected_text(current).show_ui(ui, |ui| {
        for &(v, name) in options {
            changed |= ui.selectable_value(value, v, name).changed();
        }
    });
    ui.end_row();
    changed
}

/// A labelled choice among every member of a closed set (`swell::closed_set`), by its names; returns
/// whether it changed. The menu is the set's own list, so a new member appears without an edit here.
pub fn member<T: ClosedSet>(ui: &mut Ui, label: &str, value: &mut T) -> bool {
    choice(ui, label, value, &member_options::<T>())
}

/// The entries of [`member`]'s menu: every member of `T` with its name, in declaration order.
pub fn member_options<T: ClosedSet>() -> Vec<(T, &'static str)> {
    T::ALL.iter().map(|&m| (m, m.name())).collect()
}

/// A labelled check box.
pub fn flag(ui: &mut Ui, label: &str, value: &mut bool) -> bool {
    ui.label(label);
    let changed = ui.checkbox(value, "").changed();
    ui.end_row();
    changed
}

/// Largest seed a scene file can hold: TOML integers are signed 64-bit, so a larger `u64` seed
/// could be typed but not saved.
pub const MAX_SEED: u64 = i64::MAX as u64;

/// The seed after `seed`, wrapping to 0 past [`MAX_SEED`].
pub fn next_seed(seed: u64) -> u64 {
    if seed >= MAX_SEED {
        0
    } else {
        seed + 1
    }
}

/// A labelled 64-bit seed in [0, [`MAX_SEED`]] with a "next" button (seed + 1, wrapping); returns
/// whether it changed. Unlike the other fields this one holds its range in the widget: a seed
/// has no invalid values to explain, only ones a file cannot store.
pub fn seed(ui: &mut Ui, label: &str, value: &mut u64) -> bool {
    ui.label(label);
    let changed = ui
        .horizontal(|ui| {
            let mut changed = ui.add(DragValue::new(value).speed(1.0).range(0..=MAX_SEED)).changed();
            if ui.small_button("next").on_hover_text("seed + 1").clicked() {
                *value = next_seed(*value);
                changed = true;
            }
            changed
        })
        .inner;
    ui.end_row();
    changed
}

#[cfg(test)]
mod tests {
    use swell::scene::Shading;
    use swell::spectrum::{SpectrumKind, SpreadingFunction};
    use swell::water::Edges;

    use super::*;

    /// Issue 21: every member of every closed set the panels offer is in its menu, under the name
    /// the scene format reads.
    #[test]
    fn menus_list_every_member_of_every_closed_set_by_its_scene_name() {
        fn check<T: ClosedSet>() {
            let options = member_options::<T>();
            assert_eq!(options.iter().map(|(m, _)| *m).collect::<Vec<_>>(), T::ALL);
            for (m, name) in options {
                assert_eq!(T::parse("menu", name).unwrap(), m);
            }
        }
        check::<Shading>();
        check::<SpectrumKind>();
        check::<SpreadingFunction>();
        check::<Edges>();
        check::<swell::scene::SkyModel>();
        check::<swell::scene::GlitterModel>();
        check::<swell::math::ToneCurve>();
        check::<swell::body::BodyShape>();
    }

    /// Arrow presses (one per frame, as a held key sends them) move a count in steps by whole
    /// steps; a typed value that is not a multiple is kept as typed.
    #[test]
    fn a_count_in_steps_moves_by_whole_steps_and_keeps_typed_values() {
        fn run(ctx: &egui::Context, events: Vec<egui::Event>, value: &mut u32) -> bool {
            let mut changed = false;
            let mut out = ctx.run_ui(egui::RawInput { events, ..Default::default() }, |ui| {
                egui::CentralPanel::default().show(ui, |ui| {
                    grid("t").show(ui, |ui| changed = count_in_steps(ui, "cells", value, 4, 1.0));
                });
            });
            out.textures_delta.clear();
            changed
        }
        let key = |key| egui::Event::Key {
            key,
            physical_key: None,
            pressed: true,
            repeat: false,
            modifiers: egui::Modifiers::NONE,
        };
        let ctx = egui::Context::default();
        let mut value = 96;
        run(&ctx, vec![], &mut value);
        run(&ctx, vec![key(egui::Key::Tab)], &mut value);
        for expected in [100, 104, 108] {
            assert!(run(&ctx, vec![key(egui::Key::ArrowUp)], &mut value));
            assert_eq!(value, expected);
        }
        assert!(run(&ctx, vec![key(egui::Key::ArrowDown)], &mut value));
        assert_eq!(value, 104);
        // Typed: the text is read as the value itself, not rounded to a step.
        let ctx = egui::Context::default();
        let mut typed = 96;
        run(&ctx, vec![], &mut typed);
        run(&ctx, vec![key(egui::Key::Tab)], &mut typed);
        run(&ctx, vec![egui::Event::Text("30".into())], &mut typed);
        run(&ctx, vec![key(egui::Key::Enter)], &mut typed);
        assert_eq!(typed, 30);
    }
}
