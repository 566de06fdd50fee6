//! A buoy's directional spectrum from the US National Data Buoy Center's spectral files: the
//! spectral density `C11(f)` and the four directional parameters `α1, α2, r1, r2` per band, turned
//! into `E(f, θ)` by the Longuet-Higgins (1963) Fourier series as NDBC documents it
//! (<https://www.ndbc.noaa.gov/measdes.shtml>, "Spectral wave data"):
//!
//! ```text
//! E(f, A) = C11(f) D(f, A),   D(f, A) = (1/π) (0.5 + r1 cos(A − α1) + r2 cos(2 (A − α2)))   (1/rad)
//! ```
//!
//! with `A` the nautical direction the waves come from. The truncated series can dip below zero
//! (NDBC's note, after Earle, Steele and Wang 1999); an FFT ocean needs a density, so negative
//! lobes are cut at zero and each band's `D` is scaled back to unit integral, keeping `C11`.
//! [`NdbcEstimator::Weighted`] is the positive series with weights 2/3 and 1/6 on the harmonics
//! (Longuet-Higgins, Cartwright and Smith 1963), smoother and never negative.
//!
//! Both of NDBC's text layouts are read: the realtime files (`41010.data_spec`, `.swdir`,
//! `.swdir2`, `.swr1`, `.swr2`: one line per time, newest first, each value followed by its
//! frequency in brackets) and the historical yearly files (`41010w2019.txt`, `d`, `i`, `j`, `k`:
//! a header line of frequencies, oldest first, r1 and r2 in hundredths as NDBC's note says). A
//! band whose directional values are missing (999) is spread evenly over the directions; a missing
//! density (999) is no energy.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use super::spectrum_table::{SpectrumTable, TableConvention};
use crate::error::{Error, Result};

crate::closed_set! {
    /// How the directional distribution is estimated from NDBC's four parameters.
    #[derive(Default)]
    pub enum NdbcEstimator: "an estimator" {
        /// NDBC's own series `0.5 + r1 cos + r2 cos 2`, negative lobes cut (the module docs).
        #[default]
        LonguetHiggins = "longuet-higgins",
        /// The positive weighted series `0.5 + (2/3) r1 cos + (1/6) r2 cos 2`.
        Weighted = "weighted",
    }
}

/// A buoy's five spectral files (`[water.ndbc]`), paths relative to the scene file.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NdbcFiles {
    /// Spectral density C11, m²/Hz (`.data_spec`, or the historical `w` file).
    pub density: PathBuf,
    /// Mean direction α1 per band, degrees true, coming from (`.swdir`, historical `d`).
    pub alpha1: PathBuf,
    /// Principal direction α2 per band, degrees (`.swdir2`, historical `i`).
    pub alpha2: PathBuf,
    /// First normalised polar Fourier coefficient r1 per band, in [0, 1] (`.swr1`, historical `j`
    /// in hundredths).
    pub r1: PathBuf,
    /// Second coefficient r2 per band, in [0, 1] (`.swr2`, historical `k` in hundredths).
    pub r2: PathBuf,
    /// The record to use, `"YYYY-MM-DD hh:mm"` (UTC, as the files); absent: the density file's
    /// first record (the newest in a realtime file, the oldest in a historical one).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub time: Option<String>,
    /// Direction step of the table built, degrees, dividing 360, in [1, 45]. Default 10.
    #[serde(default = "default_step")]
    pub dir_step_deg: f64,
    /// The estimator. Default `longuet-higgins`.
    #[serde(default)]
    pub estimator: NdbcEstimator,
}

fn default_step() -> f64 {
    10.0
}

impl Default for NdbcFiles {
    /// A station's realtime files in the scene's directory (`buoy.data_spec`, `buoy.swdir`, ...).
    fn default() -> Self {
        Self {
            density: "buoy.data_spec".into(),
            alpha1: "buoy.swdir".into(),
            alpha2: "buoy.swdir2".into(),
            r1: "buoy.swr1".into(),
            r2: "buoy.swr2".into(),
            time: None,
            dir_step_deg: default_step(),
            estimator: NdbcEstimator::default(),
        }
    }
}

/// Most bytes one NDBC file may hold (a year of half-hourly records is about 4 MB).
pub const MAX_NDBC_FILE_BYTES: u64 = 64 << 20;

/// One record of one file: its time and its (frequency, value) bands.
#[derive(Clone, Debug, PartialEq)]
pub struct NdbcRecord {
    /// `YYYY-MM-DD hh:mm`.
    pub time: String,
    /// (frequency Hz, value) per band, in the file's order.
    pub bands: Vec<(f64, f64)>,
}

/// Whether a file is in NDBC's realtime layout (values in hundredths only in historical files).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NdbcLayout {
    /// Realtime: `value (freq)` pairs on every line.
    Realtime,
    /// Historical: a header line of frequencies.
    Historical,
}

/// Parses one NDBC spectral text file (either layout); errors name `source` and the line.
pub fn parse_ndbc(text: &str, source: &str) -> Result<(NdbcLayout, Vec<NdbcRecord>)> {
    let err =
        |line: usize, message: String| Error::Parse { path: source.into(), message: format!("line {line}: {message}") };
    let mut lines = text.lines().enumerate().map(|(n, l)| (n + 1, l.trim())).filter(|(_, l)| !l.is_empty());
    let Some((first_n, first)) = lines.next() else {
        return Err(Error::Parse {
            path: source.into(),
            message: "empty: an NDBC spectral file starts with its #YY header".into(),
        });
    };
    let realtime = first.ends_with('>') || first.contains("(freq");
    let mut header_freqs: Vec<f64> = Vec::new();
    let mut time_fields = 5;
    if !realtime {
        let cells: Vec<&str> = first.trim_start_matches('#').split_whitespace().collect();
        time_fields = cells.iter().take_while(|c| c.chars().all(|ch| ch.is_ascii_alphabetic())).count();
        if !(4..=5).contains(&time_fields) {
            return Err(err(first_n, "expected a header `#YY MM DD hh mm` followed by the band frequencies".into()));
        }
        for c in &cells[time_fields..] {
            let f: f64 = c.parse().map_err(|_| err(first_n, format!("frequency `{c}` is not a number")))?;
            header_freqs.push(f);
        }
    }
    let mut records = Vec::new();
    for (n, line) in lines {
        if line.starts_with('#') {
            continue;
        }
        let cells: Vec<&str> = line.split_whitespace().collect();
        if cells.len() < time_fields {
            return Err(err(n, format!("{} fields; a record starts with {time_fields} time fields", cells.len())));
        }
        let num = |c: &str, what: &str| -> Result<f64> {
            let v: f64 = c
                .trim_matches(|ch| ch == '(' || ch == ')')
                .parse()
                .map_err(|_| err(n, format!("{what} `{c}` is not a number")))?;
            if v.is_finite() {
                Ok(v)
            } else {
                Err(err(n, format!("{what} = {c} is outside the finite numbers")))
            }
        };
        let t: Vec<u32> = cells[..time_fields]
            .iter()
            .map(|c| c.parse::<u32>().map_err(|_| err(n, format!("time field `{c}` is not a whole number"))))
            .collect::<Result<_>>()?;
        let year = if t[0] < 100 { t[0] + if t[0] < 50 { 2000 } else { 1900 } } else { t[0] };
        let minute = if time_fields == 5 { t[4] } else { 0 };
        let time = format!("{year:04}-{:02}-{:02} {:02}:{minute:02}", t[1], t[2], t[3]);
        let rest = &cells[time_fields..];
        let mut bands = Vec::new();
        if realtime {
            // data_spec has the separation frequency first: an odd count of cells.
            let pairs = if rest.len() % 2 == 1 { &rest[1..] } else { rest };
            for pair in pairs.chunks_exact(2) {
                if !pair[1].starts_with('(') {
                    return Err(err(
                        n,
                        format!("expected a bracketed frequency after `{}`, found `{}`", pair[0], pair[1]),
                    ));
                }
                bands.push((num(pair[1], "frequency")?, num(pair[0], "value")?));
            }
        } else {
            if rest.len() != header_freqs.len() {
                return Err(err(
                    n,
                    format!("{} values for the header's {} frequencies (cut short?)", rest.len(), header_freqs.len()),
                ));
            }
            for (c, &f) in rest.iter().zip(&header_freqs) {
                bands.push((f, num(c, "value")?));
            }
        }
        if bands.is_empty() {
            return Err(err(n, "no bands".into()));
        }
        records.push(NdbcRecord { time, bands });
    }
    if records.is_empty() {
        return Err(Error::Parse {
            path: source.into(),
            message: "no records after the header: the file is cut short".into(),
        });
    }
    Ok((if realtime { NdbcLayout::Realtime } else { NdbcLayout::Historical }, records))
}

/// NDBC's missing value in spectral files (999, 999.0, 999.00).
fn missing(v: f64) -> bool {
    v >= 999.0
}

impl NdbcFiles {
    /// Checks the keys that need no file, naming them under `key` (`water.ndbc`).
    pub fn validate(&self, key: &str) -> Result<()> {
        let step = self.dir_step_deg;
        if !(step.is_finite() && (1.0..=45.0).contains(&step) && (360.0 / step - (360.0 / step).round()).abs() < 1e-9) {
            return Err(Error::out_of_range(format!("{key}.dir_step_deg"), step, "[1, 45] degrees, dividing 360"));
        }
        if let Some(t) = &self.time {
            let ok = t.len() == 16
                && t.chars().enumerate().all(|(i, c)| match i {
                    4 | 7 => c == '-',
                    10 => c == ' ',
                    13 => c == ':',
                    _ => c.is_ascii_digit(),
                });
            if !ok {
                return Err(Error::invalid(format!("{key}.time"), format!("`{t}` is not a time \"YYYY-MM-DD hh:mm\"")));
            }
        }
        Ok(())
    }

    /// Makes relative paths relative to `dir`.
    pub fn resolve_paths(&mut self, dir: &Path) {
        for p in [&mut self.density, &mut self.alpha1, &mut self.alpha2, &mut self.r1, &mut self.r2] {
            if p.is_relative() {
                *p = dir.join(&*p);
            }
        }
    }

    /// Reads the five files and builds the table of the chosen record (errors name the file,
    /// the line or the key under `key`).
    pub fn table(&self, key: &str) -> Result<SpectrumTable> {
        self.validate(key)?;
        let density = read_record(&self.density, self.time.as_deref(), key)?;
        let time = Some(density.2.time.as_str());
        let alpha1 = read_record(&self.alpha1, time, key)?;
        let alpha2 = read_record(&self.alpha2, time, key)?;
        // r1 and r2 in historical files are hundredths (NDBC's note).
        let hundredths = |mut r: (String, NdbcLayout, NdbcRecord)| {
            if r.1 == NdbcLayout::Historical {
                r.2.bands.iter_mut().filter(|b| !missing(b.1)).for_each(|b| b.1 *= 0.01);
            }
            r
        };
        let r1 = hundredths(read_record(&self.r1, time, key)?);
        let r2 = hundredths(read_record(&self.r2, time, key)?);
        let freqs: Vec<f64> = density.2.bands.iter().map(|b| b.0).collect();
        for (source, _, rec) in [&alpha1, &alpha2, &r1, &r2] {
            let same = rec.bands.len() == freqs.len()
                && rec.bands.iter().zip(&freqs).all(|(b, f)| (b.0 - f).abs() <= 1e-6 * f.abs().max(1.0));
            if !same {
                return Err(Error::Parse {
                    path: source.clone(),
                    message: format!(
                        "its {} bands at {} are not the density file's {} bands",
                        rec.bands.len(),
                        rec.time,
                        freqs.len()
                    ),
                });
            }
        }
        for (name, (source, _, rec), lo, hi) in [
            ("r1", &r1, 0.0, 1.0),
            ("r2", &r2, 0.0, 1.0),
            ("alpha1", &alpha1, -360.0, 360.0),
            ("alpha2", &alpha2, -360.0, 360.0),
        ] {
            if let Some((i, b)) = rec.bands.iter().enumerate().find(|(_, b)| !missing(b.1) && !(lo..=hi).contains(&b.1))
            {
                return Err(Error::out_of_range(
                    format!("{source}: {name}[{i}] at {} Hz", b.0),
                    b.1,
                    format!("[{lo}, {hi}] (or 999, missing)"),
                ));
            }
        }
        let nd = (360.0 / self.dir_step_deg).round() as usize;
        let dirs: Vec<f64> = (0..nd).map(|j| j as f64 * self.dir_step_deg).collect();
        let (w1, w2) = match self.estimator {
            NdbcEstimator::LonguetHiggins => (1.0, 1.0),
            NdbcEstimator::Weighted => (2.0 / 3.0, 1.0 / 6.0),
        };
        let mut efth = Vec::with_capacity(freqs.len() * nd);
        for (i, &(f, c11)) in density.2.bands.iter().enumerate() {
            if c11 < 0.0 && !missing(c11) {
                return Err(Error::out_of_range(
                    format!("{}: density[{i}] at {f} Hz", density.0),
                    c11,
                    "[0, ...) m²/Hz (or 999, missing)",
                ));
            }
            let c11 = if missing(c11) { 0.0 } else { c11 };
            let (a1, a2, r1v, r2v) = (alpha1.2.bands[i].1, alpha2.2.bands[i].1, r1.2.bands[i].1, r2.2.bands[i].1);
            let directional = ![a1, a2, r1v, r2v].into_iter().any(missing);
            let d: Vec<f64> = dirs
                .iter()
                .map(|&a| {
                    if directional {
                        let (x1, x2) = ((a - a1).to_radians(), (a - a2).to_radians());
                        (0.5 + w1 * r1v * x1.cos() + w2 * r2v * (2.0 * x2).cos()).max(0.0)
                    } else {
                        0.5
                    }
                })
                .collect();
            // Each band's distribution back to unit integral over the circle (per degree).
            let total: f64 = d.iter().sum::<f64>() * self.dir_step_deg;
            efth.extend(d.iter().map(|x| if total > 0.0 { c11 * x / total } else { 0.0 }));
        }
        SpectrumTable::new(&freqs, &dirs, &efth, TableConvention::WAVESPECTRA, &format!("{key}."))
            .map_err(|e| e.in_source(&density.0))
    }
}

/// The record at `time` (the first if `None`) of the NDBC file `p`, with its source name and
/// layout; a missing time is named under `key`.
fn read_record(p: &Path, time: Option<&str>, key: &str) -> Result<(String, NdbcLayout, NdbcRecord)> {
    let bytes = crate::io::read_input(p, MAX_NDBC_FILE_BYTES)?;
    let source = p.display().to_string();
    let text = String::from_utf8(bytes)
        .map_err(|_| Error::Parse { path: source.clone(), message: "not UTF-8 text (an NDBC file)".into() })?;
    let (layout, records) = parse_ndbc(&text, &source)?;
    let wanted = time.map_or_else(|| records[0].time.clone(), str::to_string);
    let record = records
        .into_iter()
        .find(|r| r.time == wanted)
        .ok_or_else(|| Error::invalid(format!("{key}.time"), format!("no record at {wanted} in {source}")))?;
    Ok((source, layout, record))
}
