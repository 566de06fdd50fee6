//! The FFT ocean's parameters as a user gives them (`[water]` with `model = "fft"`), and their checks.

use serde::{Deserialize, Serialize};

use super::blender::BlenderOcean;
use super::FftOcean;
use crate::error::{check_count, check_range, Error, Result};
use std::path::PathBuf;
use std::sync::Arc;

use crate::spectrum::LoopFit;
use crate::spectrum::{
    parse_spectrum_csv, DirectionAxis, DirectionConvention, DirectionalSpectrum, Dispersion, FrequencyAxis, Jonswap,
    Phillips, PiersonMoskowitz, SpectrumKind, SpectrumTable, Spreading, SpreadingFunction, Swell, TableConvention,
    TableSum, Tma, WindSea,
};
use crate::water::{ModelParams, WaveModel};

/// Smallest and largest FFT grid side.
pub const FFT_GRID_RANGE: (u32, u32) = (16, 2048);
/// Most cascades (patches of different sizes) one ocean sums.
pub const MAX_CASCADES: u32 = 4;

/// A swell added to the wind sea (`[water.swell]`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SwellParams {
    /// Significant height of the swell alone, m, in [0, 30]. Default 1.
    pub height: f32,
    /// Peak period, s, in [2, 30]. Default 11.
    pub period: f32,
    /// Direction of travel, degrees from +X towards +Z, finite. Default 30.
    pub direction_deg: f32,
    /// cos-2s spreading exponent, in [0, 200]; larger is narrower (25 short swell, 75 long). Default 40.
    pub spread: f32,
}

impl Default for SwellParams {
    fn default() -> Self {
        Self { height: 1.0, period: 11.0, direction_deg: 30.0, spread: 40.0 }
    }
}

/// A tabulated spectrum written in the scene (`[[water.spectrum_table]]`): one frequency axis and
/// one direction axis, each named by its unit, and `efth[frequency][direction]` in m² per unit of
/// each (m²/Hz/deg with `freq_hz` and `dir_deg`).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InlineSpectrumTable {
    /// Frequencies, Hz, strictly increasing in [0.001, 20].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub freq_hz: Option<Vec<f64>>,
    /// Angular frequencies, rad/s (instead of `freq_hz`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub freq_rad_s: Option<Vec<f64>>,
    /// Directions, degrees, strictly increasing and equally spaced, meaning `spectrum_direction`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dir_deg: Option<Vec<f64>>,
    /// Directions, radians (instead of `dir_deg`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dir_rad: Option<Vec<f64>>,
    /// Energy density, one row per frequency, one value per direction, >= 0.
    pub efth: Vec<Vec<f64>>,
}

impl InlineSpectrumTable {
    /// The table, with errors naming `key` (`water.spectrum_table[0].`, with the dot).
    pub fn table(&self, meaning: DirectionConvention, key: &str) -> Result<SpectrumTable> {
        fn pick<'a>(
            a: &'a Option<Vec<f64>>,
            b: &'a Option<Vec<f64>>,
            names: [&str; 2],
            key: &str,
        ) -> Result<(&'a [f64], usize)> {
            match (a, b) {
                (Some(v), None) => Ok((v, 0)),
                (None, Some(v)) => Ok((v, 1)),
                _ => Err(Error::invalid(
                    format!("{key}{}", names[0]),
                    format!("give exactly one of {} and {} (the axis is named by its unit)", names[0], names[1]),
                )),
            }
        }
        let (freq, fu) = pick(&self.freq_hz, &self.freq_rad_s, ["freq_hz", "freq_rad_s"], key)?;
        let (dir, du) = pick(&self.dir_deg, &self.dir_rad, ["dir_deg", "dir_rad"], key)?;
        if self.efth.len() != freq.len() {
            return Err(Error::invalid(
                format!("{key}efth"),
                format!("{} rows for {} frequencies: one row per frequency", self.efth.len(), freq.len()),
            ));
        }
        if let Some((i, row)) = self.efth.iter().enumerate().find(|(_, r)| r.len() != dir.len()) {
            return Err(Error::invalid(
                format!("{key}efth[{i}]"),
                format!("{} values for {} directions: one value per direction", row.len(), dir.len()),
            ));
        }
        let convention = TableConvention {
            frequency: [FrequencyAxis::Hz, FrequencyAxis::RadPerS][fu],
            direction: [DirectionAxis::Degrees, DirectionAxis::Radians][du],
            meaning,
        };
        let flat: Vec<f64> = self.efth.iter().flatten().copied().collect();
        SpectrumTable::new(freq, dir, &flat, convention, key)
    }
}

/// One path or a list of paths (`spectrum_file = "a.csv"` or `["a.csv", "b.csv"]`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum SpectrumFiles {
    /// One file.
    One(PathBuf),
    /// Several files, summed.
    Many(Vec<PathBuf>),
}

impl SpectrumFiles {
    /// The paths, in order.
    pub fn paths(&self) -> &[PathBuf] {
        match self {
            SpectrumFiles::One(p) => std::slice::from_ref(p),
            SpectrumFiles::Many(v) => v,
        }
    }

    fn paths_mut(&mut self) -> &mut [PathBuf] {
        match self {
            SpectrumFiles::One(p) => std::slice::from_mut(p),
            SpectrumFiles::Many(v) => v,
        }
    }
}

fn is_coming_from(d: &DirectionConvention) -> bool {
    *d == DirectionConvention::ComingFrom
}

/// Most bytes a spectrum file may hold.
pub const MAX_SPECTRUM_FILE_BYTES: u64 = 64 << 20;

/// Parameters of [`super::FftOcean`]. Units are SI except where the key names another (`_deg`, `_km`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct FftOceanParams {
    /// FFT grid side N: a power of two in [16, 2048]. Default 256.
    pub grid: u32,
    /// Side L of the square periodic patch, m, in [1, 100000]. Default 250.
    pub patch_size: f32,
    /// Wind-sea spectrum. Default `jonswap`.
    pub spectrum: SpectrumKind,
    /// Wind speed U10, 10 m above the sea, m/s, in [0.5, 60]. Default 10.
    pub wind_speed: f32,
    /// Direction the wind blows towards, degrees from +X towards +Z, in [-360, 360]. Default 0.
    pub wind_direction_deg: f32,
    /// Fetch (JONSWAP, TMA), km, in [0.1, 10000]. Default 100.
    pub fetch_km: f32,
    /// Water depth, m, in [0.1, 10000]; absent means deep water. Required by `tma`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub depth: Option<f32>,
    /// Horizontal displacement scale λ, in [0, 2]; 0 gives rounded crests, 1 Tessendorf's choppy
    /// sea; larger values fold crests over (foam). Default 1.
    pub choppiness: f32,
    /// Directional spreading. Default `mitsuyasu`.
    pub spreading: Spreading,
    /// JONSWAP/TMA peak enhancement γ, in [1, 10]. Default 3.3.
    pub gamma: f32,
    /// Phillips small-wave cutoff l, m, in [0, 100]. Default 0 (none).
    pub small_wave_cutoff: f32,
    /// Random seed; the same seed gives the same sea. Default 0.
    pub seed: u32,
    /// Number of patches of decreasing size summed to hide tiling, in [1, 4]. Default 1.
    pub cascades: u32,
    /// Whether the cascades' patches divide the first one (sides `L / {1, 4, 19, 83}` instead of
    /// `L / 4.36^c`), so the whole sea repeats over `patch_size` and baked maps can tile. Default
    /// false.
    pub tile_cascades: bool,
    /// Loop period T, s, in [1, 100000]: the sea repeats exactly after T. Absent: no loop.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub loop_period: Option<f32>,
    /// Whether to compute foam. Default true.
    pub foam: bool,
    /// Jacobian below which the surface foams, in [-1, 2]. Default 0.35. The active whitecap
    /// coverage is the chance that the Jacobian, resolved plus the unresolved rest of the sea's
    /// slopes, falls below it (`water/foam.rs`), so the same value holds on every grid: with the
    /// other keys at their defaults (JONSWAP, 100 km fetch, choppiness 1, 2 s fade) the steady
    /// whitecap coverage follows the coverage observed against wind speed, `3.84e-6 U10^3.41`
    /// (Monahan and O'Muircheartaigh 1980), within 0.72 to 1.13 times from 8 to 20 m/s for every
    /// patch from 128 to 1024 m and grid from 128² to 512² (tested).
    pub foam_threshold: f32,
    /// Time constant (s) over which foam fades once the crest has passed, in [0, 60]; 0 keeps no
    /// foam from one frame to the next. Default 2.
    pub foam_fade_s: f32,
    /// Optional swell.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub swell: Option<SwellParams>,
    /// Optional `[water.blender]`: the sea given by Blender's Ocean modifier keys (see
    /// [`BlenderOcean`]); it replaces the sea keys above.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub blender: Option<BlenderOcean>,
    /// With `spectrum = "table"`: CSV files of `E(f, θ)` ([`crate::spectrum::parse_spectrum_csv`]),
    /// one path or a list, relative to the scene file; summed with the other tables.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub spectrum_file: Option<SpectrumFiles>,
    /// With `spectrum = "table"`: tables written in the scene, summed with the files.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub spectrum_table: Vec<InlineSpectrumTable>,
    /// What the tables' directions mean. Default `coming-from` (nautical, as wavespectra).
    #[serde(skip_serializing_if = "is_coming_from")]
    pub spectrum_direction: DirectionConvention,
    /// With `spectrum = "table"`: a buoy's NDBC spectral files (`[water.ndbc]`), summed with the
    /// other tables.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub ndbc: Option<Box<crate::spectrum::NdbcFiles>>,
}

impl Default for FftOceanParams {
    fn default() -> Self {
        Self {
            grid: 256,
            patch_size: 250.0,
            spectrum: SpectrumKind::Jonswap,
            wind_speed: 10.0,
            wind_direction_deg: 0.0,
            fetch_km: 100.0,
            depth: None,
            choppiness: 1.0,
            spreading: Spreading::Named(SpreadingFunction::Mitsuyasu),
            gamma: 3.3,
            small_wave_cutoff: 0.0,
            seed: 0,
            cascades: 1,
            tile_cascades: false,
            loop_period: None,
            foam: true,
            foam_threshold: 0.35,
            foam_fade_s: 2.0,
            swell: None,
            blender: None,
            spectrum_file: None,
            spectrum_table: Vec::new(),
            spectrum_direction: DirectionConvention::ComingFrom,
            ndbc: None,
        }
    }
}

/// The `[water]` keys a `[water.blender]` table replaces, with the Blender key that sets each.
const REPLACED_KEYS: [(&str, &str); 12] = [
    ("grid", "resolution"),
    ("patch_size", "spatial_size"),
    ("spectrum", "spectrum"),
    ("wind_speed", "wind_velocity"),
    ("wind_direction_deg", "wave_direction_deg"),
    ("fetch_km", "fetch_jonswap"),
    ("depth", "depth"),
    ("choppiness", "choppiness"),
    ("spreading", "wave_alignment"),
    ("gamma", "sharpen_peak_jonswap"),
    ("small_wave_cutoff", "wave_scale_min"),
    ("seed", "random_seed"),
];

/// Refuses a `[water]` sea key that a `[water.blender]` table also sets (one of the two would be
/// silently ignored). `params` holds the user's keys, `key` is normally `water`.
fn check_not_both(params: &FftOceanParams, key: &str) -> Result<()> {
    let d = FftOceanParams::default();
    let given = [
        params.grid != d.grid,
        params.patch_size != d.patch_size,
        params.spectrum != d.spectrum,
        params.wind_speed != d.wind_speed,
        params.wind_direction_deg != d.wind_direction_deg,
        params.fetch_km != d.fetch_km,
        params.depth != d.depth,
        params.choppiness != d.choppiness,
        params.spreading != d.spreading,
        params.gamma != d.gamma,
        params.small_wave_cutoff != d.small_wave_cutoff,
        params.seed != d.seed,
    ];
    match REPLACED_KEYS.iter().zip(given).find(|(_, g)| *g) {
        Some(((swell_key, blender_key), _)) => Err(Error::invalid(
            format!("{key}.{swell_key}"),
            format!("set by {key}.blender.{blender_key} when [{key}.blender] is given; remove one of them"),
        )),
        None => Ok(()),
    }
}

impl FftOceanParams {
    /// Checks every field, naming keys under `key` (normally `water`).
    pub fn validate(&self, key: &str) -> Result<()> {
        let k = |name: &str| format!("{key}.{name}");
        let (lo, hi) = FFT_GRID_RANGE;
        if !(self.grid.is_power_of_two() && (lo..=hi).contains(&self.grid)) {
            return Err(Error::out_of_range(k("grid"), self.grid, format!("powers of two in [{lo}, {hi}]")));
        }
        check_range(&k("patch_size"), self.patch_size, 1.0, 100_000.0)?;
        check_range(&k("wind_speed"), self.wind_speed, 0.5, 60.0)?;
        check_range(&k("wind_direction_deg"), self.wind_direction_deg, -360.0, 360.0)?;
        check_range(&k("fetch_km"), self.fetch_km, 0.1, 10_000.0)?;
        if let Some(d) = self.depth {
            check_range(&k("depth"), d, 0.1, 10_000.0)?;
        } else if self.spectrum == SpectrumKind::Tma {
            return Err(Error::invalid(k("depth"), "spectrum = \"tma\" needs the water depth in metres (depth = ...)"));
        }
        check_range(&k("choppiness"), self.choppiness, 0.0, 2.0)?;
        if let Spreading::Cos2s(_) | Spreading::CosPower { .. } = self.spreading {
            return Err(Error::invalid(k("spreading"), format!("valid: {}", SpreadingFunction::NAMES.join(", "))));
        }
        check_range(&k("gamma"), self.gamma, 1.0, 10.0)?;
        check_range(&k("small_wave_cutoff"), self.small_wave_cutoff, 0.0, 100.0)?;
        check_count(&k("cascades"), self.cascades, 1, MAX_CASCADES)?;
        if let Some(t) = self.loop_period {
            check_range(&k("loop_period"), t, 1.0, 100_000.0)?;
        }
        check_range(&k("foam_threshold"), self.foam_threshold, -1.0, 2.0)?;
        check_range(&k("foam_fade_s"), self.foam_fade_s, 0.0, 60.0)?;
        if let Some(s) = &self.swell {
            check_range(&k("swell.height"), s.height, 0.0, 30.0)?;
            check_range(&k("swell.period"), s.period, 2.0, 30.0)?;
            check_range(&k("swell.direction_deg"), s.direction_deg, -360.0, 360.0)?;
            check_range(&k("swell.spread"), s.spread, 0.0, 200.0)?;
        }
        if let Some(b) = &self.blender {
            b.validate(&k("blender"))?;
            check_not_both(self, key)?;
        }
        self.validate_tables(key)
    }

    /// The table keys: given exactly when `spectrum = "table"`, without the keys that shape a
    /// parametric wind sea; inline tables checked in full (files are read when the sea is built).
    fn validate_tables(&self, key: &str) -> Result<()> {
        let k = |name: &str| format!("{key}.{name}");
        let has_tables = self.spectrum_file.is_some() || !self.spectrum_table.is_empty() || self.ndbc.is_some();
        if self.spectrum != SpectrumKind::Table {
            if has_tables {
                let given = if self.spectrum_file.is_some() {
                    "spectrum_file"
                } else if self.ndbc.is_some() {
                    "ndbc"
                } else {
                    "spectrum_table"
                };
                return Err(Error::invalid(
                    k(given),
                    format!("a tabulated spectrum needs spectrum = \"table\" (spectrum is \"{}\")", self.spectrum),
                ));
            }
            return Ok(());
        }
        if !has_tables {
            return Err(Error::invalid(
                k("spectrum"),
                "\"table\" needs spectrum_file, [[water.spectrum_table]] or [water.ndbc]",
            ));
        }
        let d = FftOceanParams::default();
        let shaping = [
            ("fetch_km", self.fetch_km != d.fetch_km),
            ("gamma", self.gamma != d.gamma),
            ("small_wave_cutoff", self.small_wave_cutoff != d.small_wave_cutoff),
            ("spreading", self.spreading != d.spreading),
        ];
        if let Some((name, _)) = shaping.iter().find(|(_, given)| *given) {
            return Err(Error::invalid(
                k(name),
                "shapes a parametric wind sea; with spectrum = \"table\" the tables give the whole sea (remove it)",
            ));
        }
        if let Some(files) = &self.spectrum_file {
            if files.paths().is_empty() {
                return Err(Error::invalid(k("spectrum_file"), "an empty list: name at least one file"));
            }
            if files.paths().len() > crate::limits::MAX_LIST_ITEMS {
                return Err(Error::out_of_range(
                    k("spectrum_file"),
                    format!("{} files", files.paths().len()),
                    format!("[1, {}] files", crate::limits::MAX_LIST_ITEMS),
                ));
            }
        }
        for (i, t) in self.spectrum_table.iter().enumerate() {
            t.table(self.spectrum_direction, &format!("{key}.spectrum_table[{i}]."))?;
        }
        if let Some(n) = &self.ndbc {
            n.validate(&k("ndbc"))?;
        }
        Ok(())
    }

    /// Makes the spectrum files' relative paths relative to `dir` (the scene file's directory).
    pub fn resolve_paths(&mut self, dir: &std::path::Path) {
        if let Some(files) = &mut self.spectrum_file {
            for p in files.paths_mut() {
                if p.is_relative() {
                    *p = dir.join(&*p);
                }
            }
        }
        if let Some(n) = &mut self.ndbc {
            n.resolve_paths(dir);
        }
    }

    /// The tables of `spectrum = "table"`, read and checked: the files (errors name the file and
    /// the line), the inline tables, the buoy's files.
    pub fn tables(&self) -> Result<TableSum> {
        let mut tables = Vec::new();
        for path in self.spectrum_file.iter().flat_map(|f| f.paths()) {
            let bytes = crate::io::read_input(path, MAX_SPECTRUM_FILE_BYTES)?;
            let source = path.display().to_string();
            let text = String::from_utf8(bytes).map_err(|_| Error::Parse {
                path: source.clone(),
                message: "not UTF-8 text (a spectrum CSV)".into(),
            })?;
            tables.push(parse_spectrum_csv(&text, &source, self.spectrum_direction)?);
        }
        for (i, t) in self.spectrum_table.iter().enumerate() {
            tables.push(t.table(self.spectrum_direction, &format!("water.spectrum_table[{i}]."))?);
        }
        if let Some(n) = &self.ndbc {
            tables.push(n.table("water.ndbc")?);
        }
        Ok(TableSum { tables })
    }

    /// The parameters the sea is built from: these, or with `[water.blender]` the Blender keys
    /// mapped onto swell's ([`FftOceanParams::with_blender`]). Assumes `self` is valid.
    pub fn resolved(&self) -> FftOceanParams {
        match &self.blender {
            Some(b) => self.with_blender(b),
            None => self.clone(),
        }
    }

    /// swell's own parameters for the Blender ocean `b`: the sea keys of `self` are replaced, the
    /// rest (cascades, loop period, foam) kept. Assumes both are valid.
    pub fn with_blender(&self, b: &BlenderOcean) -> FftOceanParams {
        FftOceanParams {
            grid: b.grid(),
            patch_size: b.spatial_size,
            spectrum: b.spectrum,
            wind_speed: b.wind_velocity,
            wind_direction_deg: b.wave_direction_deg,
            fetch_km: b.fetch_jonswap,
            depth: Some(b.depth),
            choppiness: b.choppiness,
            spreading: b.spreading(),
            gamma: b.gamma(),
            small_wave_cutoff: b.wave_scale_min,
            seed: b.random_seed,
            ..self.clone()
        }
    }

    /// The directional spectrum these parameters describe (km and degrees converted to SI here);
    /// with `spectrum = "table"` the tables are read here ([`FftOceanParams::tables`]).
    pub fn spectrum(&self) -> Result<DirectionalSpectrum> {
        let u10 = f64::from(self.wind_speed);
        let fetch = f64::from(self.fetch_km) * 1000.0;
        let gamma = f64::from(self.gamma);
        let depth = self.depth.map(f64::from);
        let wind_sea = match self.spectrum {
            SpectrumKind::Phillips => {
                WindSea::Phillips(Phillips { wind_speed: u10, small_wave_cutoff: f64::from(self.small_wave_cutoff) })
            }
            SpectrumKind::PiersonMoskowitz => WindSea::PiersonMoskowitz(PiersonMoskowitz::from_u10(u10)),
            SpectrumKind::Jonswap => WindSea::Jonswap(Jonswap::from_wind(u10, fetch, gamma)),
            SpectrumKind::Tma => WindSea::Tma(Tma::new(
                Jonswap::from_wind(u10, fetch, gamma),
                depth.expect("validate() requires depth for tma"),
            )),
            SpectrumKind::Table => WindSea::Table(Arc::new(self.tables()?)),
        };
        Ok(DirectionalSpectrum {
            wind_sea,
            spreading: self.spreading,
            wind_direction: f64::from(self.wind_direction_deg).to_radians(),
            wind_speed: u10,
            dispersion: Dispersion::for_depth(self.depth),
            swell: self.swell.map(|s| {
                Swell::new(
                    f64::from(s.height),
                    f64::from(s.period),
                    f64::from(s.direction_deg).to_radians(),
                    f64::from(s.spread),
                )
            }),
        })
    }
}
impl ModelParams for FftOceanParams {
    /// Everywhere: the cascades tile the plane.
    fn defined_everywhere(&self) -> bool {
        true
    }

    fn validate(&self) -> Result<()> {
        FftOceanParams::validate(self, "water")
    }

    fn build(&self) -> Result<Box<dyn WaveModel>> {
        Ok(Box::new(FftOcean::new(self)?))
    }

    fn estimate_bytes(&self) -> u64 {
        let p = self.resolved();
        crate::limits::estimate_fft_bytes(p.grid, p.cascades)
    }

    fn loop_period(&self) -> Option<f64> {
        self.loop_period.map(f64::from)
    }

    fn loop_warning(&self) -> Option<String> {
        let p = self.resolved();
        let period = f64::from(p.loop_period?);
        let spectrum = p.spectrum().ok()?;
        LoopFit::for_spectrum(period, std::f64::consts::TAU / spectrum.peak_period()).warning("water.loop_period")
    }
}
