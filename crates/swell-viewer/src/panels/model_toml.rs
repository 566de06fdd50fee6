//! The panel of every water model without a dedicated one (radial pool
//! wave, noise, river, Tessendorf, wave sets, Airy, steep sines): the model's own `[water]` keys as
//! editable TOML, applied through the same parser and validation as a scene file, so every
//! parameter of every model can be changed live and a bad value is refused with the scene-file
//! message (`water.fetch_km = -3 is outside ...`).

use eframe::egui::{self, Ui};
use swell::scene::{WaterModelSpec, WaterSpec};

use super::water::model_name;

/// The text being edited and the outcome of the last apply.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ModelTomlForm {
    /// The model's keys as TOML, as the user is editing them.
    pub text: String,
    /// The model the text was made from, to refresh the text when the model changes elsewhere.
    pub source: String,
    /// Why the last apply was refused.
    pub error: Option<String>,
}

/// The model's keys (without `model`) as TOML text.
pub fn model_keys(model: &WaterModelSpec) -> String {
    let mut table = toml::Table::try_from(model).unwrap_or_default();
    table.remove("model");
    toml::to_string_pretty(&table).unwrap_or_default()
}

/// Parses `text` as the keys of model `name` and validates them by building the model.
pub fn parse_model(name: &str, text: &str) -> swell::Result<WaterModelSpec> {
    let mut table: toml::Table = toml::from_str(text)
        .map_err(|e| swell::Error::Parse { path: "panel".into(), message: e.to_string().trim_end().into() })?;
    table.insert("model".into(), toml::Value::String(name.into()));
    let spec = WaterSpec::from_table(table, "panel")?;
    spec.model.build()?;
    Ok(spec.model)
}

/// Shows the editor; returns true when a valid edit replaced `model`.
pub fn show(ui: &mut Ui, model: &mut WaterModelSpec, form: &mut ModelTomlForm) -> bool {
    let current = model_keys(model);
    if form.source != current {
        form.text = current.clone();
        form.source = current;
        form.error = None;
    }
    let name = model_name(model);
    ui.label(format!("{name}: parameters (the model's [water] keys, see docs/scene-format.md)"));
    ui.add(egui::TextEdit::multiline(&mut form.text).code_editor().desired_rows(14).desired_width(f32::INFINITY));
    let mut changed = false;
    ui.horizontal(|ui| {
        if ui.button("apply").clicked() {
            match parse_model(&name, &form.text) {
                Ok(m) => {
                    *model = m;
                    form.error = None;
                    changed = true;
                }
                Err(e) => form.error = Some(e.to_string()),
            }
        }
        if ui.button("revert").clicked() {
            form.text = form.source.clone();
            form.error = None;
        }
    });
    if let Some(e) = &form.error {
        ui.colored_label(egui::Color32::from_rgb(220, 80, 60), e);
    }
    changed
}

#[cfg(test)]
mod tests {
    use super::*;
    use swell::scene::PRESETS;

    #[test]
    fn every_preset_model_round_trips_through_the_text_and_bad_values_are_refused() {
        for p in PRESETS {
            let Some(w) = swell::scene::preset(p.name).unwrap().water else { continue };
            let name = model_name(&w.model);
            let back = parse_model(&name, &model_keys(&w.model)).unwrap();
            assert_eq!(back, w.model, "preset {}", p.name);
        }
        let e = parse_model("springs", "mass = -4.0\n").unwrap_err().to_string();
        assert!(e.contains("mass"), "{e}");
        assert!(parse_model("noise", "no_such_key = 1\n").is_err());
    }
}
