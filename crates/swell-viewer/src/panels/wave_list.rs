//! Paper 000's wave list, shared by every model made of a list of waves (Gerstner, sines,
//! Tessendorf, Airy, steep sines): edit each wave, delete
//! one, clear, add a wave from a form, and regenerate a whole seeded random set within ranges.
//!
//! "Regenerate a set" draws the set with the library's [`wave_set`] (a fan of directions around
//! the wind, wavelengths around a median, amplitudes at the median's ratio, speeds from the
//! dispersion relation; seeded, so the same form gives the same set).

use eframe::egui::{self, DragValue, RichText, Ui};
use swell::water::{wave_set, GerstnerWave, SineWave, WaveSetParams};
use swell::{Error, Result};

use super::{fields, keys};

/// A wave the list can show: its table cells, its check and how a generated wave becomes one.
pub trait ListedWave: Copy + PartialEq {
    /// Column headers of the cells, with units.
    const HEADERS: &'static [&'static str];
    /// The scene-file keys of one wave (`water.waves[]`) the cells edit.
    const KEYS: &'static [&'static str];
    /// Most waves the model takes.
    const MAX: usize;
    /// Grid id prefix (unique per model).
    const ID: &'static str;
    /// Whether "Regenerate a set" offers the shared steepness Q (only models that have one).
    const REGEN_STEEPNESS: bool = false;
    /// One wave's cells; returns whether any changed.
    fn cells(&mut self, ui: &mut Ui) -> bool;
    /// The model's own check of one wave, naming keys under `key`.
    fn check(&self, key: &str) -> Result<()>;
    /// A generated (Gerstner) wave as this kind.
    fn from_gerstner(w: GerstnerWave) -> Self;
}

/// One number cell of a wave row; returns whether it changed.
pub fn cell(ui: &mut Ui, v: &mut f32, speed: f64) -> bool {
    ui.add(DragValue::new(v).speed(speed).max_decimals(4)).changed()
}

impl ListedWave for GerstnerWave {
    const HEADERS: &'static [&'static str] = &["A m", "L m", "S m/s", "dir x", "dir z", "Q"];
    const KEYS: &'static [&'static str] = &["amplitude", "wavelength", "speed", "direction", "steepness"];
    const MAX: usize = swell::water::MAX_GERSTNER_WAVES;
    const ID: &'static str = "gerstner";
    const REGEN_STEEPNESS: bool = true;
    fn cells(&mut self, ui: &mut Ui) -> bool {
        cell(ui, &mut self.amplitude, 0.005)
            | cell(ui, &mut self.wavelength, 0.1)
            | cell(ui, &mut self.speed, 0.05)
            | cell(ui, &mut self.direction.x, 0.01)
            | cell(ui, &mut self.direction.y, 0.01)
            | cell(ui, &mut self.steepness, 0.01)
    }
    fn check(&self, key: &str) -> Result<()> {
        self.validate(key)
    }
    fn from_gerstner(w: GerstnerWave) -> Self {
        w
    }
}

impl ListedWave for SineWave {
    const HEADERS: &'static [&'static str] = &["A m", "L m", "S m/s", "dir x", "dir z"];
    const KEYS: &'static [&'static str] = &["amplitude", "wavelength", "speed", "direction"];
    const MAX: usize = swell::water::MAX_SINE_WAVES;
    const ID: &'static str = "sines";
    fn cells(&mut self, ui: &mut Ui) -> bool {
        cell(ui, &mut self.amplitude, 0.005)
            | cell(ui, &mut self.wavelength, 0.1)
            | cell(ui, &mut self.speed, 0.05)
            | cell(ui, &mut self.direction.x, 0.01)
            | cell(ui, &mut self.direction.y, 0.01)
    }
    fn check(&self, key: &str) -> Result<()> {
        self.validate(key)
    }
    fn from_gerstner(w: GerstnerWave) -> Self {
        SineWave { amplitude: w.amplitude, wavelength: w.wavelength, speed: w.speed, direction: w.direction }
    }
}

/// What the list remembers between frames: the "new wave" form, the "regenerate" ranges and why
/// the last add or regenerate was refused.
#[derive(Clone, Debug, PartialEq)]
pub struct WaveListForm<W> {
    /// The wave "Add wave" appends.
    pub new_wave: W,
    /// Ranges, count and seed of "Regenerate set".
    pub set: WaveSetParams,
    /// Why the last add or regenerate was refused.
    pub message: Option<String>,
}

impl<W: ListedWave> WaveListForm<W> {
    /// A form that adds `new_wave` and regenerates the library's default set.
    pub fn new(new_wave: W) -> Self {
        Self { new_wave, set: WaveSetParams::default(), message: None }
    }

    /// Appends the form's wave if it is valid and the list has room.
    pub fn add_to(&mut self, waves: &mut Vec<W>) -> Result<()> {
        let result = add_wave(waves, self.new_wave);
        self.message = result.as_ref().err().map(ToString::to_string);
        result
    }

    /// Replaces the list by a new seeded set drawn from the form's ranges; refused (list unchanged)
    /// if a range is invalid.
    pub fn regenerate(&mut self, waves: &mut Vec<W>) -> Result<()> {
        let result = regenerate(&self.set);
        self.message = result.as_ref().err().map(ToString::to_string);
        *waves = result?;
        Ok(())
    }
}

/// Appends `wave`, refusing an invalid wave or a full list.
pub fn add_wave<W: ListedWave>(waves: &mut Vec<W>, wave: W) -> Result<()> {
    if waves.len() >= W::MAX {
        return Err(Error::out_of_range(
            "water.waves",
            format!("{} waves", waves.len() + 1),
            format!("[0, {}] waves", W::MAX),
        ));
    }
    wave.check(&format!("water.waves[{}]", waves.len()))?;
    waves.push(wave);
    Ok(())
}

/// A seeded random set of waves within the ranges of `set` (keys named as in a `wave-set` scene).
pub fn regenerate<W: ListedWave>(set: &WaveSetParams) -> Result<Vec<W>> {
    if set.count as usize > W::MAX {
        return Err(Error::out_of_range("regenerate.count", set.count, format!("[1, {}]", W::MAX)));
    }
    Ok(wave_set(set).map_err(relabel)?.into_iter().map(W::from_gerstner).collect())
}

/// The wave-set check names keys under "regenerate", as the panel labels them.
fn relabel(e: Error) -> Error {
    Error::invalid("regenerate", e.to_string())
}

/// Shows the list, the add form and the regenerate form; returns whether `waves` changed.
pub fn show<W: ListedWave>(ui: &mut Ui, waves: &mut Vec<W>, form: &mut WaveListForm<W>) -> bool {
    let mut changed = false;
    ui.label(format!("{} waves (at most {}); direction is (x, z)", waves.len(), W::MAX));
    let mut delete = None;
    egui::Grid::new((W::ID, "waves")).striped(true).spacing([4.0, 2.0]).show(ui, |ui| {
        ui.label(RichText::new("#").small());
        for h in W::HEADERS {
            ui.label(RichText::new(*h).small());
        }
        ui.end_row();
        for (i, w) in waves.iter_mut().enumerate() {
            ui.label(i.to_string());
            changed |= w.cells(ui);
            if ui.small_button("x").on_hover_text("Delete this wave").clicked() {
                delete = Some(i);
            }
            ui.end_row();
        }
    });
    if !waves.is_empty() {
        keys::edits("water.waves[]", W::KEYS);
    }
    if let Some(i) = delete {
        waves.remove(i);
        changed = true;
    }
    if ui.button("Clear").on_hover_text("Remove every wave (flat water)").clicked() && !waves.is_empty() {
        waves.clear();
        changed = true;
    }
    ui.separator();
    ui.label("New wave");
    egui::Grid::new((W::ID, "new")).spacing([4.0, 2.0]).show(ui, |ui| {
        for h in W::HEADERS {
            ui.label(RichText::new(*h).small());
        }
        ui.end_row();
        form.new_wave.cells(ui);
        ui.end_row();
    });
    if ui.button("Add wave").clicked() && form.add_to(waves).is_ok() {
        changed = true;
    }
    ui.separator();
    egui::CollapsingHeader::new("Regenerate a set").id_salt((W::ID, "regen")).show(ui, |ui| {
        let s = &mut form.set;
        fields::grid(&format!("{}-regen", W::ID)).show(ui, |ui| {
            fields::count(ui, "waves", &mut s.count, 0.1);
            fields::number(ui, "wind direction", &mut s.wind_direction_deg, 1.0, " deg");
            fields::number(ui, "spread (full fan)", &mut s.spread_deg, 1.0, " deg");
            fields::number(ui, "median wavelength", &mut s.median_wavelength, 0.1, " m");
            fields::number(ui, "median amplitude", &mut s.median_amplitude, 0.005, " m");
            if W::REGEN_STEEPNESS {
                fields::number(ui, "steepness Q", &mut s.steepness, 0.01, "");
            }
            ui.label("seed");
            ui.add(DragValue::new(&mut s.seed).range(0..=fields::MAX_SEED));
            ui.end_row();
        });
        ui.horizontal(|ui| {
            if ui.button("Regenerate").clicked() && form.regenerate(waves).is_ok() {
                changed = true;
            }
            if ui.button("Next seed").on_hover_text("Regenerate with seed + 1").clicked() {
                form.set.seed = fields::next_seed(form.set.seed);
                if form.regenerate(waves).is_ok() {
                    changed = true;
                }
            }
        });
    });
    if let Some(m) = &form.message {
        ui.colored_label(ui.visuals().error_fg_color, m);
    }
    changed
}

#[cfg(test)]
mod tests {
    use super::*;

    fn form() -> WaveListForm<GerstnerWave> {
        WaveListForm::new(GerstnerWave {
            amplitude: 0.2,
            wavelength: 20.0,
            speed: 5.0,
            direction: glam::Vec2::X,
            steepness: 0.5,
        })
    }

    #[test]
    fn add_refuses_bad_waves_and_full_lists_with_the_reason() {
        let mut waves = Vec::new();
        let mut f = form();
        f.add_to(&mut waves).unwrap();
        assert_eq!(waves, vec![f.new_wave]);
        f.new_wave.steepness = 1.5;
        assert!(f.add_to(&mut waves).is_err());
        assert_eq!(f.message.as_deref(), Some("water.waves[1].steepness = 1.5 is outside [0, 1]"));
        f.new_wave.steepness = 0.5;
        while waves.len() < GerstnerWave::MAX {
            f.add_to(&mut waves).unwrap();
        }
        assert!(f.add_to(&mut waves).unwrap_err().to_string().starts_with("water.waves = 65 waves"));
        assert_eq!(waves.len(), GerstnerWave::MAX);
        let mut sines: Vec<SineWave> = Vec::new();
        let mut sf = WaveListForm::new(SineWave::from_gerstner(f.new_wave));
        sf.new_wave.direction = glam::Vec2::ZERO;
        assert!(sf.add_to(&mut sines).is_err());
        assert!(sf.message.as_deref().unwrap().starts_with("water.waves[0].direction"));
    }

    #[test]
    fn regenerate_is_seeded_within_the_ranges_and_refuses_bad_ranges() {
        let mut f = form();
        let mut a = Vec::new();
        f.set.count = 12;
        f.set.seed = 7;
        f.regenerate(&mut a).unwrap();
        assert_eq!(a.len(), 12);
        let mut b = Vec::new();
        f.regenerate(&mut b).unwrap();
        assert_eq!(a, b, "same seed, same set");
        f.set.seed = 8;
        f.regenerate(&mut b).unwrap();
        assert_ne!(a, b);
        // Every wave travels within the fan around the wind and is valid for the model.
        let half = (f.set.spread_deg / 2.0).to_radians() + 1e-4;
        for (i, w) in a.iter().enumerate() {
            w.validate(&format!("w[{i}]")).unwrap();
            assert!(w.direction.y.atan2(w.direction.x).abs() <= half, "{w:?}");
            assert_eq!(w.steepness, f.set.steepness);
        }
        let sines: Vec<SineWave> = regenerate(&f.set).unwrap();
        assert_eq!(sines.len(), 12);
        f.set.median_wavelength = -1.0;
        let before = b.clone();
        assert!(f.regenerate(&mut b).is_err());
        assert!(f.message.as_deref().unwrap().contains("median_wavelength"), "{:?}", f.message);
        assert_eq!(b, before);
    }
}
