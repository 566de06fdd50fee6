//! The CSV form of a tabulated spectrum: the long form of wavespectra's `efth(freq, dir)`
//! (`efth.to_dataframe().to_csv()` with the columns renamed by unit).
//!
//! ```text
//! freq_hz,dir_deg,efth
//! 0.05,0,0.0
//! 0.05,10,0.0012
//! ...
//! ```
//!
//! The header names the units: the first column `freq_hz` or `freq_rad_s`, the second `dir_deg` or
//! `dir_rad`, the third `efth` (per the first two columns' units: m²/Hz/deg for the defaults). One
//! row per (frequency, direction) pair, in any order; every pair of the grid exactly once. Blank
//! lines and lines starting with `#` are skipped; a UTF-8 byte-order mark is allowed.

use super::spectrum_table::{DirectionAxis, FrequencyAxis, SpectrumTable, TableConvention};
use super::DirectionConvention;
use crate::closed_set::ClosedSet;
use crate::error::{Error, Result};

/// Most rows a spectrum CSV may hold (a 200-frequency x 360-direction table has 72,000).
pub const MAX_CSV_ROWS: usize = 1_000_000;

/// Parses `text`, read from `source` (named in errors with the line: `buoy.csv: line 7: efth`),
/// as a spectrum whose directions mean `meaning`.
pub fn parse_spectrum_csv(text: &str, source: &str, meaning: DirectionConvention) -> Result<SpectrumTable> {
    let parse_err = |message: String| Error::Parse { path: source.into(), message };
    let mut lines = text
        .strip_prefix('\u{feff}')
        .unwrap_or(text)
        .lines()
        .enumerate()
        .map(|(n, l)| (n + 1, l.trim()))
        .filter(|(_, l)| !l.is_empty() && !l.starts_with('#'));
    let (header_line, header) = lines
        .next()
        .ok_or_else(|| parse_err("empty: a spectrum CSV starts with the header freq_hz,dir_deg,efth".into()))?;
    let names: Vec<&str> = header.split(',').map(|c| c.trim().trim_matches('"')).collect();
    let [fname, dname, ename] = names[..] else {
        return Err(parse_err(format!(
            "line {header_line}: the header has {} columns; expected 3: freq_hz,dir_deg,efth",
            names.len()
        )));
    };
    let frequency = FrequencyAxis::from_name(fname).ok_or_else(|| {
        parse_err(format!(
            "line {header_line}: the first column `{fname}` names no unit; valid: {} (missing units)",
            FrequencyAxis::NAMES.join(", ")
        ))
    })?;
    let direction = DirectionAxis::from_name(dname).ok_or_else(|| {
        parse_err(format!(
            "line {header_line}: the second column `{dname}` names no unit; valid: {} (missing units)",
            DirectionAxis::NAMES.join(", ")
        ))
    })?;
    if ename != "efth" {
        return Err(parse_err(format!("line {header_line}: the third column is `{ename}`; expected efth")));
    }
    let mut rows: Vec<(f64, f64, f64, usize)> = Vec::new();
    for (n, line) in lines {
        if rows.len() == MAX_CSV_ROWS {
            return Err(parse_err(format!("line {n}: more than {MAX_CSV_ROWS} rows (MAX_CSV_ROWS)")));
        }
        let cells: Vec<&str> = line.split(',').map(str::trim).collect();
        if cells.len() != 3 {
            return Err(parse_err(format!("line {n}: {} values; expected 3 ({fname},{dname},efth)", cells.len())));
        }
        let mut v = [0.0; 3];
        for (k, (cell, name)) in cells.iter().zip([fname, dname, "efth"]).enumerate() {
            v[k] =
                cell.parse::<f64>().map_err(|_| parse_err(format!("line {n}: {name} = `{cell}` is not a number")))?;
            if !v[k].is_finite() {
                return Err(parse_err(format!("line {n}: {name} = {cell} is outside the finite numbers")));
            }
        }
        rows.push((v[0], v[1], v[2], n));
    }
    if rows.is_empty() {
        return Err(parse_err(format!("no rows after the header (line {header_line}): the file is cut short")));
    }
    let axis = |pick: fn(&(f64, f64, f64, usize)) -> f64| {
        let mut a: Vec<f64> = rows.iter().map(pick).collect();
        a.sort_by(f64::total_cmp);
        a.dedup();
        a
    };
    let freq = axis(|r| r.0);
    let dir = axis(|r| r.1);
    let nd = dir.len();
    let mut efth = vec![f64::NAN; freq.len() * nd];
    for &(f, d, e, n) in &rows {
        let i = freq.partition_point(|&x| x < f);
        let j = dir.partition_point(|&x| x < d);
        let slot = &mut efth[i * nd + j];
        if !slot.is_nan() {
            return Err(parse_err(format!("line {n}: ({fname} = {f}, {dname} = {d}) is repeated")));
        }
        *slot = e;
    }
    if let Some(missing) = efth.iter().position(|e| e.is_nan()) {
        let (i, j) = (missing / nd, missing % nd);
        return Err(parse_err(format!(
            "no row for ({fname} = {}, {dname} = {}): {} rows for {} frequencies x {nd} directions (cut short?)",
            freq[i],
            dir[j],
            rows.len(),
            freq.len()
        )));
    }
    let convention = TableConvention { frequency, direction, meaning };
    SpectrumTable::new(&freq, &dir, &efth, convention, "").map_err(|e| e.in_source(source))
}

/// Writes `table`'s grid as the CSV [`parse_spectrum_csv`] reads (wavespectra's conventions).
pub fn spectrum_csv(grid: &super::GriddedSpectrum) -> String {
    let mut out = String::from("freq_hz,dir_deg,efth\n");
    let nd = grid.dir_deg.len();
    for (i, f) in grid.freq_hz.iter().enumerate() {
        for (j, d) in grid.dir_deg.iter().enumerate() {
            out.push_str(&format!("{f},{d},{}\n", grid.efth[i * nd + j]));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    const SMALL: &str = "freq_hz,dir_deg,efth\n0.1,0,1\n0.1,180,0\n0.2,0,2\n0.2,180,0.5\n0.3,0,1\n0.3,180,0\n";

    #[test]
    fn a_small_table_reads_in_any_row_order_and_writes_back() {
        let t = parse_spectrum_csv(SMALL, "s.csv", DirectionConvention::ComingFrom).unwrap();
        assert_eq!(t.grid().efth, vec![1.0, 0.0, 2.0, 0.5, 1.0, 0.0]);
        let mut rows: Vec<&str> = SMALL.lines().skip(1).collect();
        rows.reverse();
        let shuffled = format!("\u{feff}# a comment\nfreq_hz, dir_deg, efth\n{}\n", rows.join("\n"));
        let u = parse_spectrum_csv(&shuffled, "s.csv", DirectionConvention::ComingFrom).unwrap();
        assert_eq!(t, u);
        let back = parse_spectrum_csv(&spectrum_csv(t.grid()), "b", DirectionConvention::ComingFrom).unwrap();
        assert_eq!(t, back);
    }

    #[test]
    fn bad_files_name_the_file_line_field_and_range() {
        let e =
            |text: &str| parse_spectrum_csv(text, "b.csv", DirectionConvention::ComingFrom).unwrap_err().to_string();
        assert!(e("").starts_with("b.csv: empty"), "{}", e(""));
        assert!(
            e("freq,dir,efth\n0.1,0,1\n").contains("`freq` names no unit; valid: freq_hz, freq_rad_s (missing units)")
        );
        assert!(e("freq_hz,dir,efth\n").contains("`dir` names no unit"));
        assert!(e("freq_hz,dir_deg,efth\n").contains("cut short"));
        assert!(e("freq_hz,dir_deg,efth\n0.1,0\n").contains("line 2: 2 values; expected 3"));
        assert!(e("freq_hz,dir_deg,efth\n0.1,0,x\n").contains("line 2: efth = `x` is not a number"));
        assert!(e("freq_hz,dir_deg,efth\n0.1,0,nan\n").contains("line 2: efth = nan is outside the finite numbers"));
        let repeated = format!("{SMALL}0.2,0,2\n");
        assert!(e(&repeated).contains("line 8: (freq_hz = 0.2, dir_deg = 0) is repeated"), "{}", e(&repeated));
        let cut = SMALL.lines().take(6).collect::<Vec<_>>().join("\n");
        assert!(e(&cut).contains("no row for (freq_hz = 0.3, dir_deg = 180)"), "{}", e(&cut));
        let negative = SMALL.replace("0.2,180,0.5", "0.2,180,-0.5");
        assert_eq!(e(&negative), "b.csv: efth[1][1] = -0.5 is outside [0, 1000000] m²/Hz/deg (finite energy density)");
    }
}
