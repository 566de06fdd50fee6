//! A field editor for any parameter struct, through its scene-file keys: the struct is written as a
//! TOML table, each key gets a widget by its value type (number, whole number, switch, text, list
//! of numbers), and the edited table is read back by the same parser as a scene file.
//!
//! Used where there are many small parameter structs of the same kind (terrain generators), so a
//! new generator or key gets a panel row without viewer code. Keys and values are exactly those of
//! `docs/scene-format.md`.

use eframe::egui::{DragValue, Ui};

use super::fields;

/// Drag speed for a number currently `v`: one percent of it, so small and large values both move
/// at a usable rate.
fn speed_for(v: f64) -> f64 {
    (v.abs() * 0.01).max(0.001)
}

/// One number cell (float or integer); returns whether it changed. Other values are left alone.
fn number_cell(ui: &mut Ui, v: &mut toml::Value) -> bool {
    match v {
        toml::Value::Float(f) => {
            let s = speed_for(*f);
            ui.add(DragValue::new(f).speed(s).max_decimals(4)).changed()
        }
        toml::Value::Integer(i) => ui.add(DragValue::new(i).speed(0.2)).changed(),
        other => {
            ui.monospace(other.to_string());
            false
        }
    }
}

/// Shows one row per key of `table` (sorted, as TOML writes them); returns whether any changed.
/// Nested tables are shown read-only.
pub fn show(ui: &mut Ui, id: &str, table: &mut toml::Table) -> bool {
    let mut changed = false;
    fields::grid(id).show(ui, |ui| {
        for (key, value) in table.iter_mut() {
            ui.label(key.replace('_', " "));
            match value {
                toml::Value::Boolean(b) => changed |= ui.checkbox(b, "").changed(),
                toml::Value::String(s) => changed |= ui.text_edit_singleline(s).changed(),
                toml::Value::Array(items) => {
                    ui.horizontal(|ui| {
                        for item in items.iter_mut() {
                            changed |= number_cell(ui, item);
                        }
                    });
                }
                toml::Value::Table(t) => {
                    ui.monospace(toml::to_string(t).unwrap_or_default().replace('\n', "; "));
                }
                v => changed |= number_cell(ui, v),
            }
            ui.end_row();
        }
    });
    changed
}

/// Adds `delta` to the integer key `key` of `table` (wrapping at zero), if there is one; returns
/// whether there was. The "new seed" buttons use it.
pub fn bump_integer(table: &mut toml::Table, key: &str, delta: i64) -> bool {
    match table.get_mut(key) {
        Some(toml::Value::Integer(i)) => {
            *i = i.checked_add(delta).filter(|v| *v >= 0).unwrap_or(0);
            true
        }
        _ => false,
    }
}
