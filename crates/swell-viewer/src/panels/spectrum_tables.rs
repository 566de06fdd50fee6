//! The measured-sea keys of the FFT ocean panel (`spectrum = "table"`): the CSV files, the
//! direction convention, the tables written in the scene and a buoy's NDBC files.
//!
//! A table of a few thousand numbers is no panel's business to type in: each inline table shows
//! its size and wavespectra's Hs, Tp and Dpm, and is edited as a whole the way a user reshapes a
//! measured sea: its energy scaled (Hs scales by the square root), its directions turned, its
//! periods stretched (frequencies divided), or the table removed. The files are edited by path.

use eframe::egui::{self, Ui};
use swell::spectrum::{NdbcFiles, SpectrumKind};
use swell::water::{FftOceanParams, SpectrumFiles};

use super::{fields, keys, table_fields};

/// Shows the table keys (they take effect with `spectrum = "table"`; given with another
/// spectrum they are refused with that reason at the top of the panel); returns whether `p`
/// changed.
pub fn show(ui: &mut Ui, p: &mut FftOceanParams) -> bool {
    let mut changed = false;
    if p.spectrum != SpectrumKind::Table {
        ui.label("measured sea: choose spectrum \"table\" to use these");
    }
    fields::grid("fft-tables").show(ui, |ui| {
        changed |= fields::member(ui, "directions mean", &mut p.spectrum_direction);
        changed |= files(ui, p);
        keys::edits("water", &["spectrum_direction", "spectrum_file"]);
        let mut has_ndbc = p.ndbc.is_some();
        if fields::flag(ui, "NDBC buoy files", &mut has_ndbc) {
            p.ndbc = has_ndbc.then(Box::default);
            changed = true;
        }
        keys::edits("water", &["ndbc"]);
    });
    changed |= inline_tables(ui, p);
    if let Some(n) = &mut p.ndbc {
        ui.label("[water.ndbc]: the buoy's five files, the record's time, the estimator");
        let mut table = toml::Table::try_from(&**n).unwrap_or_default();
        // The optional time shows once set; it is typed in the scene file as "YYYY-MM-DD hh:mm".
        let names: Vec<&str> = table.keys().map(String::as_str).collect();
        keys::edits("water.ndbc", &names);
        keys::edits("water.ndbc", &["time"]);
        if table_fields::show(ui, "fft-ndbc", &mut table) {
            if let Ok(edited) = toml::Value::Table(table).try_into::<NdbcFiles>() {
                **n = edited;
                changed = true;
            }
        }
        let mut time = n.time.clone();
        fields::grid("fft-ndbc-time").show(ui, |ui| {
            if fields::optional_text(ui, "record time (off: the first)", &mut time, "2020-01-01 00:00") {
                n.time = time;
                changed = true;
            }
        });
    }
    changed
}

/// `spectrum_file` as one line of comma-separated paths (empty: none).
fn files(ui: &mut Ui, p: &mut FftOceanParams) -> bool {
    ui.label("CSV files (comma-separated)");
    let paths: Vec<String> = p.spectrum_file.iter().flat_map(|f| f.paths()).map(|p| p.display().to_string()).collect();
    let mut text = paths.join(", ");
    let changed = ui.add(egui::TextEdit::singleline(&mut text).desired_width(220.0)).changed();
    ui.end_row();
    if changed {
        let list: Vec<std::path::PathBuf> =
            text.split(',').map(str::trim).filter(|s| !s.is_empty()).map(Into::into).collect();
        p.spectrum_file = match list.len() {
            0 => None,
            1 => Some(SpectrumFiles::One(list.into_iter().next().expect("one path"))),
            _ => Some(SpectrumFiles::Many(list)),
        };
    }
    changed
}

/// Each `[[water.spectrum_table]]`: its size and statistics, and whole-table edits.
fn inline_tables(ui: &mut Ui, p: &mut FftOceanParams) -> bool {
    let mut changed = false;
    let mut remove = None;
    let meaning = p.spectrum_direction;
    for (i, t) in p.spectrum_table.iter_mut().enumerate() {
        let summary = match t.table(meaning, "") {
            Ok(table) => {
                let s = table.grid().stats();
                let opt = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.1}"));
                format!(
                    "table {i}: {} x {}, Hs {:.2} m, Tp {} s, Dpm {} deg",
                    table.grid().freq_hz.len(),
                    table.grid().dir_deg.len(),
                    s.hs_m,
                    opt(s.tp_s),
                    opt(s.dpm_deg)
                )
            }
            Err(e) => format!("table {i}: {e}"),
        };
        ui.label(summary);
        fields::grid(&format!("fft-table-{i}")).show(ui, |ui| {
            let mut energy = 1.0f32;
            if fields::number(ui, "  scale energy x", &mut energy, 0.005, "") && energy.is_finite() && energy > 0.0 {
                t.efth.iter_mut().flatten().for_each(|e| *e *= f64::from(energy));
                changed = true;
            }
            let mut turn = 0.0f32;
            if fields::number(ui, "  turn directions by", &mut turn, 0.5, " deg") && turn.is_finite() {
                let (deg, rad) = (f64::from(turn), f64::from(turn).to_radians());
                t.dir_deg.iter_mut().flatten().for_each(|d| *d += deg);
                t.dir_rad.iter_mut().flatten().for_each(|d| *d += rad);
                changed = true;
            }
            let mut stretch = 1.0f32;
            if fields::number(ui, "  stretch periods x", &mut stretch, 0.002, "")
                && stretch.is_finite()
                && stretch > 0.0
            {
                let s = f64::from(stretch);
                t.freq_hz.iter_mut().flatten().for_each(|f| *f /= s);
                t.freq_rad_s.iter_mut().flatten().for_each(|f| *f /= s);
                changed = true;
            }
        });
        if ui.button(format!("remove table {i}")).clicked() {
            remove = Some(i);
        }
    }
    keys::edits("water.spectrum_table[]", &["efth", "dir_deg", "dir_rad", "freq_hz", "freq_rad_s"]);
    if let Some(i) = remove {
        p.spectrum_table.remove(i);
        changed = true;
    }
    changed
}
