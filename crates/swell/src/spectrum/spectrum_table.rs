//! A measured or modelled directional spectrum given as a table `E(f, θ)` (a buoy, WAVEWATCH III,
//! SWAN, ERA5 through wavespectra), and the continuous spectrum an FFT ocean samples from it.
//!
//! The table is stored in wavespectra's conventions ([`GriddedSpectrum`]: Hz, degrees the waves
//! come from, m²/Hz/deg) whatever convention it was written in. Between its samples the density is
//! linear in frequency and in direction (periodic when the directions close the circle); below the
//! first frequency it is zero; above the last one it continues as f⁻⁵ when the last frequency is
//! above 0.333 Hz, the tail wavespectra adds to Hs, and is zero otherwise. That continuous density
//! is scaled so that its integral is the table's own variance by wavespectra's rule
//! ([`GriddedSpectrum::variance`]): the sea keeps the table's Hs (within sampling scatter and
//! what the FFT grid cannot hold).
//!
//! An FFT ocean samples `F(kx, kz)` (m⁴/rad²); with `θ` the direction of travel in swell's frame
//! (from +X towards +Z) and `φ = θ − 90°` the nautical direction the wave comes from,
//! `F = E(f, φ) (180/π) (df/dk) / k` with `f = ω(k) / 2π` and `df/dk = c_g / 2π` from the
//! dispersion at the scene's depth.

use super::gridded_spectrum::{GriddedSpectrum, TAIL_FROM_HZ};
use super::Dispersion;
use crate::error::{Error, Result};

crate::closed_set! {
    /// What a table's directions name (`spectrum_direction`).
    #[derive(Default)]
    pub enum DirectionConvention: "a direction convention" {
        /// Nautical, where the waves come from: 0 = from north (−Z), 90 = from east (+X); the
        /// convention of wavespectra, WAVEWATCH III's output and NDBC.
        #[default]
        ComingFrom = "coming-from",
        /// Nautical, where the waves travel to: 0 = towards north (−Z), 90 = towards east (+X).
        GoingTo = "going-to",
        /// swell's own: the direction of travel from +X towards +Z, as `wind_direction_deg`.
        Swell = "swell",
    }
}

crate::closed_set! {
    /// The frequency axis of a table, named by its unit (a CSV header's first column, an inline
    /// table's key).
    pub enum FrequencyAxis: "a frequency axis" {
        /// Frequency in Hz; the density is per Hz.
        Hz = "freq_hz",
        /// Angular frequency in rad/s; the density is per rad/s.
        RadPerS = "freq_rad_s",
    }
}

crate::closed_set! {
    /// The direction axis of a table, named by its unit.
    pub enum DirectionAxis: "a direction axis" {
        /// Degrees; the density is per degree.
        Degrees = "dir_deg",
        /// Radians; the density is per radian.
        Radians = "dir_rad",
    }
}

/// Largest energy density accepted, m²/Hz/deg (a 100 m sea in one bin of 0.001 Hz x 1° holds
/// 6e5; anything above is a unit mistake).
pub const MAX_EFTH: f64 = 1.0e6;
/// Frequencies accepted, Hz: periods from 1000 s to 0.05 s.
pub const FREQ_RANGE_HZ: (f64, f64) = (1.0e-3, 20.0);

/// A tabulated directional spectrum and its continuous interpolant (see the module
/// documentation).
#[derive(Clone, Debug, PartialEq)]
pub struct SpectrumTable {
    /// The table in wavespectra's conventions, as given (unscaled).
    grid: GriddedSpectrum,
    /// Whether the directions close the circle (`n dd = 360°`): then the density is periodic.
    periodic: bool,
    /// Factor on the interpolant that makes its integral the table's variance.
    scale: f64,
}

/// How a table was written: the units its axes name and what its directions mean.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TableConvention {
    /// Unit of the frequencies (and of the density per frequency).
    pub frequency: FrequencyAxis,
    /// Unit of the directions (and of the density per direction).
    pub direction: DirectionAxis,
    /// What the directions name.
    pub meaning: DirectionConvention,
}

impl TableConvention {
    /// wavespectra's: Hz, degrees, coming from.
    pub const WAVESPECTRA: TableConvention = TableConvention {
        frequency: FrequencyAxis::Hz,
        direction: DirectionAxis::Degrees,
        meaning: DirectionConvention::ComingFrom,
    };
}

impl SpectrumTable {
    /// The table with frequencies `freq`, directions `dir` and values `efth` (row-major,
    /// `efth[i * dir.len() + j]`), written in `convention`. Errors name the field under `key`
    /// (`freq_hz[3]`, `efth[2][5]`) with the value and the valid range: frequencies strictly
    /// increasing in [`FREQ_RANGE_HZ`], at least 3; directions strictly increasing, equally
    /// spaced, spanning less than a full turn; values finite in [0, [`MAX_EFTH`]] m²/Hz/deg, not
    /// all zero.
    pub fn new(freq: &[f64], dir: &[f64], efth: &[f64], convention: TableConvention, key: &str) -> Result<Self> {
        let (fname, dname) = (convention.frequency.name(), convention.direction.name());
        let to_hz = match convention.frequency {
            FrequencyAxis::Hz => 1.0,
            FrequencyAxis::RadPerS => 1.0 / std::f64::consts::TAU,
        };
        let to_deg = match convention.direction {
            DirectionAxis::Degrees => 1.0,
            DirectionAxis::Radians => 180.0 / std::f64::consts::PI,
        };
        let (lo, hi) = FREQ_RANGE_HZ;
        for (i, &f) in freq.iter().enumerate() {
            let hz = f * to_hz;
            if !(hz.is_finite() && (lo..=hi).contains(&hz)) {
                return Err(Error::out_of_range(format!("{key}{fname}[{i}]"), f, format!("[{lo}, {hi}] Hz")));
            }
            if i > 0 && f <= freq[i - 1] {
                let what = if f == freq[i - 1] { "repeats" } else { "is below" };
                return Err(Error::invalid(
                    format!("{key}{fname}[{i}]"),
                    format!("{f} {what} {fname}[{}] = {}: frequencies must be strictly increasing", i - 1, freq[i - 1]),
                ));
            }
        }
        if freq.len() < 3 {
            return Err(Error::out_of_range(
                format!("{key}{fname}"),
                format!("{} frequencies", freq.len()),
                "[3, ...] (a peak needs two neighbours)",
            ));
        }
        if dir.is_empty() {
            return Err(Error::out_of_range(format!("{key}{dname}"), "0 directions", "[1, ...]"));
        }
        for (j, &d) in dir.iter().enumerate() {
            let deg = d * to_deg;
            if !(deg.is_finite() && (-360.0..=720.0).contains(&deg)) {
                let range = if to_deg == 1.0 { "[-360, 720] degrees" } else { "[-2π, 4π] radians" };
                return Err(Error::out_of_range(format!("{key}{dname}[{j}]"), d, range));
            }
            if j > 0 && d <= dir[j - 1] {
                let what = if d == dir[j - 1] { "repeats" } else { "is below" };
                return Err(Error::invalid(
                    format!("{key}{dname}[{j}]"),
                    format!(
                        "{d} {what} {dname}[{}] = {}: directions must be strictly increasing (sort the table)",
                        j - 1,
                        dir[j - 1]
                    ),
                ));
            }
        }
        let dd = if dir.len() > 1 { (dir[1] - dir[0]) * to_deg } else { 360.0 };
        for j in 2..dir.len() {
            let step = (dir[j] - dir[j - 1]) * to_deg;
            if (step - dd).abs() > 1e-6 * dd.max(1.0) {
                return Err(Error::invalid(
                    format!("{key}{dname}[{j}]"),
                    format!("{}: directions must be equally spaced (the first step is {})", dir[j], dir[1] - dir[0]),
                ));
            }
        }
        let span = (dir[dir.len() - 1] - dir[0]) * to_deg;
        if span + dd > 360.0 * (1.0 + 1e-9) {
            return Err(Error::invalid(
                format!("{key}{dname}"),
                format!("{} directions {} apart cover more than a full turn (a direction repeats)", dir.len(), dd),
            ));
        }
        if efth.len() != freq.len() * dir.len() {
            return Err(Error::invalid(
                format!("{key}efth"),
                format!("{} values for {} frequencies x {} directions", efth.len(), freq.len(), dir.len()),
            ));
        }
        // Density per Hz per degree: per rad/s -> per Hz multiplies by 2π; per rad -> per deg by π/180.
        let density = (1.0 / to_hz) / to_deg;
        let mut values = Vec::with_capacity(efth.len());
        for (n, &e) in efth.iter().enumerate() {
            let v = e * density;
            if !(v.is_finite() && (0.0..=MAX_EFTH).contains(&v)) {
                let (i, j) = (n / dir.len(), n % dir.len());
                return Err(Error::out_of_range(
                    format!("{key}efth[{i}][{j}]"),
                    e,
                    format!("[0, {MAX_EFTH}] m²/Hz/deg (finite energy density)"),
                ));
            }
            values.push(v);
        }
        // Directions as wavespectra's: coming from, nautical degrees in [0, 360), increasing.
        let from = |d: f64| {
            let deg = d * to_deg;
            let nautical_from = match convention.meaning {
                DirectionConvention::ComingFrom => deg,
                DirectionConvention::GoingTo => deg + 180.0,
                // Travel θ from +X towards +Z; a wave travelling along θ comes from θ − 90°.
                DirectionConvention::Swell => deg - 90.0,
            };
            nautical_from.rem_euclid(360.0)
        };
        let nd = dir.len();
        // The converted directions are a rotation of an increasing cyclic list: start at the least.
        let start = (0..nd).min_by(|&a, &b| from(dir[a]).total_cmp(&from(dir[b]))).unwrap_or(0);
        let order: Vec<usize> = (0..nd).map(|j| (start + j) % nd).collect();
        let dir_deg: Vec<f64> = order.iter().map(|&j| from(dir[j])).collect();
        let freq_hz: Vec<f64> = freq.iter().map(|f| f * to_hz).collect();
        let efth: Vec<f64> = values.chunks_exact(nd).flat_map(|row| order.iter().map(move |&j| row[j])).collect();
        let grid = GriddedSpectrum { freq_hz, dir_deg, efth };
        let periodic = nd > 1 && ((nd as f64) * dd - 360.0).abs() < 1e-6 * 360.0;
        let target = grid.variance();
        if target <= 0.0 {
            return Err(Error::invalid(format!("{key}efth"), "every value is 0: the table holds no waves"));
        }
        let mut table = SpectrumTable { grid, periodic, scale: 1.0 };
        table.scale = target / table.interpolant_variance();
        if !(table.scale.is_finite() && table.scale > 0.0 && target.is_finite()) {
            return Err(Error::invalid(
                format!("{key}efth"),
                "the table's energy cannot be interpolated (it lies only where the interpolant has no width)",
            ));
        }
        Ok(table)
    }

    /// The table in wavespectra's conventions, as given.
    pub fn grid(&self) -> &GriddedSpectrum {
        &self.grid
    }

    /// The exact integral of the unscaled interpolant over frequency and direction, m².
    fn interpolant_variance(&self) -> f64 {
        let g = &self.grid;
        let (nd, dd) = (g.dir_deg.len(), g.dd());
        // Linear in direction: periodic trapezoid over the circle, or over [first, last] (one
        // direction alone is a 1° wide line: wavespectra's dd = 1).
        let per_freq: Vec<f64> = g
            .efth
            .chunks_exact(nd)
            .map(|row| match (nd, self.periodic) {
                (1, _) => row[0],
                (_, true) => dd * row.iter().sum::<f64>(),
                (_, false) => dd * (row.iter().sum::<f64>() - 0.5 * (row[0] + row[nd - 1])),
            })
            .collect();
        let f = &g.freq_hz;
        let mut m0: f64 = (1..f.len()).map(|i| 0.5 * (per_freq[i - 1] + per_freq[i]) * (f[i] - f[i - 1])).sum();
        let last = f.len() - 1;
        if f[last] > TAIL_FROM_HZ {
            m0 += 0.25 * per_freq[last] * f[last];
        }
        m0
    }

    /// `E(f, φ)` of the scaled interpolant, m²/Hz/deg, at `f_hz` and `from_deg` (nautical,
    /// coming from, any angle).
    pub fn density(&self, f_hz: f64, from_deg: f64) -> f64 {
        let g = &self.grid;
        let f = &g.freq_hz;
        let last = f.len() - 1;
        if f_hz.is_nan() || f_hz < f[0] {
            return 0.0;
        }
        if f_hz >= f[last] {
            return if f_hz == f[last] || f[last] > TAIL_FROM_HZ {
                self.direction_density(last, from_deg) * (f[last] / f_hz).powi(5) * self.scale
            } else {
                0.0
            };
        }
        let i = f.partition_point(|&x| x <= f_hz) - 1;
        let w = (f_hz - f[i]) / (f[i + 1] - f[i]);
        let e = (1.0 - w) * self.direction_density(i, from_deg) + w * self.direction_density(i + 1, from_deg);
        e * self.scale
    }

    /// The unscaled density of frequency row `i` at `from_deg`, linear between directions.
    fn direction_density(&self, i: usize, from_deg: f64) -> f64 {
        let g = &self.grid;
        let nd = g.dir_deg.len();
        let row = &g.efth[i * nd..(i + 1) * nd];
        if nd == 1 {
            // A single direction: a line 1° wide (wavespectra's dd = 1), centred on it.
            let off = (from_deg - g.dir_deg[0] + 180.0).rem_euclid(360.0) - 180.0;
            return if off.abs() <= 0.5 { row[0] } else { 0.0 };
        }
        let dd = g.dd();
        // Angle past the first direction, in [0, 360).
        let a = (from_deg - g.dir_deg[0]).rem_euclid(360.0);
        let pos = a / dd;
        // A table of a few directions a hair apart leaves most of the circle past its last one.
        if pos.is_nan() || pos >= nd as f64 {
            return 0.0;
        }
        let j = pos.floor() as usize;
        let w = pos - j as f64;
        if j + 1 < nd {
            (1.0 - w) * row[j] + w * row[j + 1]
        } else if self.periodic && j < nd {
            (1.0 - w) * row[nd - 1] + w * row[0]
        } else if j == nd - 1 && w == 0.0 {
            row[nd - 1]
        } else {
            0.0
        }
    }

    /// `F(kx, kz)` in m⁴/rad² at wavenumber `k` (rad/m) travelling along `theta` (rad, swell's
    /// frame), for an FFT ocean in water of `dispersion`.
    pub fn wavenumber_density(&self, k: f64, theta: f64, dispersion: &Dispersion) -> f64 {
        if k <= 0.0 {
            return 0.0;
        }
        let tau = std::f64::consts::TAU;
        let f = dispersion.omega_f64(k) / tau;
        let from_deg = theta.to_degrees() - 90.0;
        let per_rad = self.density(f, from_deg) * 180.0 / std::f64::consts::PI;
        per_rad * dispersion.group_speed_f64(k) / tau / k
    }

    /// The smooth peak period of the table (wavespectra's Tp), s, if its frequency spectrum has
    /// an interior peak.
    pub fn peak_period(&self) -> Option<f64> {
        self.grid.stats().tp_s
    }
}

/// Several tables summed (a wind sea and swells, each from its own source).
#[derive(Clone, Debug, PartialEq)]
pub struct TableSum {
    /// The tables, each normalised to its own variance.
    pub tables: Vec<SpectrumTable>,
}

impl TableSum {
    /// `F(kx, kz)` of the sum, m⁴/rad² (see [`SpectrumTable::wavenumber_density`]).
    pub fn wavenumber_density(&self, k: f64, theta: f64, dispersion: &Dispersion) -> f64 {
        self.tables.iter().map(|t| t.wavenumber_density(k, theta, dispersion)).sum()
    }

    /// The grid the sum's statistics are taken on: a single table's own; for several, the
    /// sorted union of their frequencies and the finest direction step among those that divide
    /// the circle (else 5°), each table's interpolant summed there.
    pub fn stats_grid(&self) -> GriddedSpectrum {
        if let [one] = self.tables.as_slice() {
            return one.grid.clone();
        }
        let mut freq: Vec<f64> = self.tables.iter().flat_map(|t| t.grid.freq_hz.iter().copied()).collect();
        freq.sort_by(f64::total_cmp);
        freq.dedup();
        let dd = self
            .tables
            .iter()
            .map(|t| t.grid.dd())
            .filter(|dd| (360.0 / dd - (360.0 / dd).round()).abs() < 1e-9)
            .fold(f64::INFINITY, f64::min);
        let dd = if dd.is_finite() { dd } else { 5.0 };
        let nd = (360.0 / dd).round() as usize;
        let dir: Vec<f64> = (0..nd).map(|j| j as f64 * dd).collect();
        let mut g = GriddedSpectrum::zeros(freq, dir);
        let nd = g.dir_deg.len();
        for i in 0..g.freq_hz.len() {
            for j in 0..nd {
                g.efth[i * nd + j] = self.tables.iter().map(|t| t.density(g.freq_hz[i], g.dir_deg[j])).sum();
            }
        }
        g
    }

    /// Peak period of the sum (wavespectra's Tp on [`TableSum::stats_grid`]), s.
    pub fn peak_period(&self) -> Option<f64> {
        self.stats_grid().stats().tp_s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn freqs() -> Vec<f64> {
        (0..30).map(|i| 0.05 * 1.08f64.powi(i)).collect()
    }

    fn bump(f: f64, d: f64, centre: f64) -> f64 {
        let off = ((d - centre + 540.0) % 360.0 - 180.0).to_radians();
        (-((f - 0.1) / 0.03).powi(2)).exp() * off.cos().max(0.0).powi(4)
    }

    #[test]
    fn conventions_meet_in_wavespectras_frame() {
        let f = freqs();
        let from: Vec<f64> = (0..24).map(|j| f64::from(j) * 15.0).collect();
        let e: Vec<f64> = f.iter().flat_map(|&f| from.iter().map(move |&d| bump(f, d, 300.0))).collect();
        let a = SpectrumTable::new(&f, &from, &e, TableConvention::WAVESPECTRA, "").unwrap();
        // The same sea written going-to, in rad/s and radians: density per rad/s per rad.
        let w: Vec<f64> = f.iter().map(|f| f * std::f64::consts::TAU).collect();
        let to: Vec<f64> = (0..24).map(|j| (f64::from(j) * 15.0).to_radians()).collect();
        let per = (180.0 / std::f64::consts::PI) / std::f64::consts::TAU;
        let e2: Vec<f64> =
            f.iter().flat_map(|&f| to.iter().map(move |&d| bump(f, d.to_degrees() + 180.0, 300.0) * per)).collect();
        let conv = TableConvention {
            frequency: FrequencyAxis::RadPerS,
            direction: DirectionAxis::Radians,
            meaning: DirectionConvention::GoingTo,
        };
        let b = SpectrumTable::new(&w, &to, &e2, conv, "").unwrap();
        let (sa, sb) = (a.grid().stats(), b.grid().stats());
        assert!((sa.hs_m - sb.hs_m).abs() < 1e-9 * sa.hs_m, "{sa:?} {sb:?}");
        assert!((sa.dpm_deg.unwrap() - 300.0).abs() < 1e-6 && (sb.dpm_deg.unwrap() - 300.0).abs() < 1e-6);
        // Coming from 300° (west-north-west) means travelling towards 120°, i.e. θ = 30° in swell's
        // frame (+X towards +Z): the density is there, not at the opposite direction.
        let d = Dispersion::Deep;
        let k = d.wavenumber_f64(std::f64::consts::TAU * 0.1);
        assert!(a.wavenumber_density(k, 30f64.to_radians(), &d) > 0.0);
        assert_eq!(a.wavenumber_density(k, 210f64.to_radians(), &d), 0.0);
        assert!((a.wavenumber_density(k, 0.3, &d) / b.wavenumber_density(k, 0.3, &d) - 1.0).abs() < 1e-9);
    }

    #[test]
    fn the_interpolant_keeps_the_tables_variance() {
        let f = freqs();
        let from: Vec<f64> = (0..36).map(|j| f64::from(j) * 10.0).collect();
        let e: Vec<f64> = f.iter().flat_map(|&f| from.iter().map(move |&d| bump(f, d, 45.0))).collect();
        let t = SpectrumTable::new(&f, &from, &e, TableConvention::WAVESPECTRA, "").unwrap();
        // Integrate the wavenumber density numerically in polar coordinates.
        let d = Dispersion::Deep;
        let (nk, nt) = (3000, 720);
        let k_max = d.wavenumber_f64(std::f64::consts::TAU * 2.0);
        let dk = k_max / f64::from(nk);
        let dt = std::f64::consts::TAU / f64::from(nt);
        let mut v = 0.0;
        for i in 0..nk {
            let k = (f64::from(i) + 0.5) * dk;
            for j in 0..nt {
                v += t.wavenumber_density(k, (f64::from(j) + 0.5) * dt, &d) * k * dk * dt;
            }
        }
        let m0 = t.grid().variance();
        assert!((v / m0 - 1.0).abs() < 5e-3, "{v} vs {m0}");
    }

    #[test]
    fn bad_tables_are_refused_by_field_value_and_range() {
        let c = TableConvention::WAVESPECTRA;
        let e = |f: &[f64], d: &[f64], v: &[f64]| SpectrumTable::new(f, d, v, c, "t.").unwrap_err().to_string();
        let ok_e = vec![1.0; 6];
        assert_eq!(
            e(&[0.1, 0.2, 0.3], &[0.0, 180.0], &[1.0, 1.0, -1.0, 1.0, 1.0, 1.0]),
            "t.efth[1][0] = -1 is outside [0, 1000000] m²/Hz/deg (finite energy density)"
        );
        assert!(
            e(&[0.1, 0.2, 0.3], &[0.0, 180.0], &[1.0, f64::NAN, 1.0, 1.0, 1.0, 1.0]).starts_with("t.efth[0][1] = NaN")
        );
        assert!(e(&[0.1, 0.3, 0.2], &[0.0, 180.0], &ok_e).contains("t.freq_hz[2]: 0.2 is below freq_hz[1] = 0.3"));
        assert!(e(&[0.1, 0.2, 0.2], &[0.0, 180.0], &ok_e).contains("repeats"));
        assert!(e(&[0.1, 0.2, 0.3], &[180.0, 0.0], &ok_e).contains("t.dir_deg[1]: 0 is below"));
        assert!(e(&[0.1, 0.2, 0.3], &[0.0, 360.0], &ok_e).contains("more than a full turn"));
        assert!(e(&[0.1, 0.2, 0.3], &[0.0, 10.0, 30.0], &[1.0; 9]).contains("equally spaced"));
        assert!(e(&[0.1, 0.2], &[0.0], &[1.0, 1.0]).starts_with("t.freq_hz = 2 frequencies is outside [3"));
        assert!(e(&[0.1, 0.2, 0.3], &[0.0, 180.0], &[0.0; 6]).contains("holds no waves"));
        assert!(e(&[0.1, 0.2, 0.3], &[0.0, 180.0], &[1.0; 5]).contains("5 values for 3 frequencies x 2 directions"));
        assert!(e(&[0.0, 0.2, 0.3], &[0.0], &[1.0; 3]).starts_with("t.freq_hz[0] = 0 is outside [0.001, 20] Hz"));
    }
}
