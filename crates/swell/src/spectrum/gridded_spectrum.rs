//! A directional spectrum on a grid of frequencies and directions, in the units and conventions of
//! the `wavespectra` Python package, and the sea-state parameters it defines.
//!
//! `efth(freq, dir)` is in m²/Hz/deg, `freq` in Hz, `dir` in degrees the waves come from, nautical
//! (0 = from north, 90 = from east; in swell's frame north is −Z and east +X, as for
//! `sun_azimuth_deg`). The parameters follow wavespectra 4.9 (`wavespectra/specarray.py`,
//! `core/npstats.py`, `core/xrstats.py`) term by term, so that `swell stats` and
//! `swell.Water.stats()` can be compared with what oceanographers compute from the same table:
//!
//! - `df` is `numpy.gradient(freq)` (one-sided at the ends, `(f[i+1] − f[i−1]) / 2` inside) and
//!   `dd = |dir[1] − dir[0]|`;
//! - the frequency spectrum is `S(f) = dd Σ_θ E(f, θ)`;
//! - `Hs = 4 sqrt(Σ S df + tail)`, where the tail `S(f_n) f_n / 4` (an f⁻⁵ tail past the last
//!   frequency) is added when `f_n > 0.333` Hz (`SpecArray.hs(tail=True)`);
//! - the peak is the largest strict local maximum of S (`SpecArray._peak`: neither end can be one);
//!   `Tp = 1 / fp` with `fp` the vertex of the parabola through the peak and its two neighbours
//!   (`npstats.tps`, wavespectra's default `smooth=True`);
//! - the first directional moments are `msin(f) = dd Σ E sin(270° − θ)` and
//!   `mcos(f) = dd Σ E cos(270° − θ)` (`SpecArray.momd`), so `(270° − atan2(msin, mcos)) mod 360`
//!   is the circular mean of the directions the waves come from: `Dpm` takes the moments at the
//!   peak frequency alone, `Dm` their integrals over frequency;
//! - `Dspr = sqrt(2 (1 − sqrt(a² + b²) / m0))` in degrees, with `a = Σ msin df`, `b = Σ mcos df`,
//!   `m0 = Σ S df` (no tail), the one-sided directional width (`SpecArray.dspr`).

use crate::error::{Error, Result};

/// `wavespectra` adds an f⁻⁵ tail to `Hs` when the last frequency is above this (Hz).
pub const TAIL_FROM_HZ: f64 = 0.333;

/// A directional spectrum `E(f, θ)` sampled on a grid, in wavespectra's units and conventions
/// (see the module documentation). Directions are equally spaced.
#[derive(Clone, Debug, PartialEq)]
pub struct GriddedSpectrum {
    /// Frequencies, Hz, strictly increasing, all > 0.
    pub freq_hz: Vec<f64>,
    /// Directions the waves come from, nautical degrees in [0, 360), strictly increasing and
    /// equally spaced.
    pub dir_deg: Vec<f64>,
    /// `E(f, θ)` in m²/Hz/deg, row-major: `efth[i * dir_deg.len() + j]` is at `freq_hz[i]`,
    /// `dir_deg[j]`; finite and >= 0.
    pub efth: Vec<f64>,
}

/// The sea-state parameters of a [`GriddedSpectrum`], as wavespectra defines them (the module
/// documentation gives each formula). `None` where wavespectra answers NaN: no interior peak in
/// the frequency spectrum, or no energy.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpectrumStats {
    /// Significant wave height Hm0, m.
    pub hs_m: f64,
    /// Smooth peak period, s.
    pub tp_s: Option<f64>,
    /// Mean direction at the peak frequency, degrees the waves come from, nautical, [0, 360).
    pub dpm_deg: Option<f64>,
    /// Mean direction over the whole spectrum, degrees the waves come from, nautical, [0, 360).
    pub dm_deg: Option<f64>,
    /// Directional spread, degrees, in [0, 81] (81° is the spread of energy equal in every
    /// direction).
    pub dspr_deg: Option<f64>,
}

impl GriddedSpectrum {
    /// A spectrum of zeros on the given axes (checked as [`GriddedSpectrum::check`] does).
    pub fn zeros(freq_hz: Vec<f64>, dir_deg: Vec<f64>) -> Self {
        let efth = vec![0.0; freq_hz.len() * dir_deg.len()];
        Self { freq_hz, dir_deg, efth }
    }

    /// Direction spacing `dd`, degrees (1 with a single direction, as wavespectra).
    pub fn dd(&self) -> f64 {
        match self.dir_deg.as_slice() {
            [a, b, ..] => (b - a).abs(),
            _ => 1.0,
        }
    }

    /// `numpy.gradient(freq)`: the frequency weights wavespectra integrates with, Hz.
    pub fn df(&self) -> Vec<f64> {
        let f = &self.freq_hz;
        let n = f.len();
        (0..n)
            .map(|i| match n {
                0 | 1 => 1.0,
                _ if i == 0 => f[1] - f[0],
                _ if i == n - 1 => f[n - 1] - f[n - 2],
                _ => (f[i + 1] - f[i - 1]) / 2.0,
            })
            .collect()
    }

    /// The frequency spectrum `S(f) = dd Σ_θ E(f, θ)`, m²/Hz.
    pub fn oned(&self) -> Vec<f64> {
        let (nd, dd) = (self.dir_deg.len(), self.dd());
        self.efth.chunks_exact(nd.max(1)).map(|row| dd * row.iter().sum::<f64>()).collect()
    }

    /// The variance `m0 = Σ S df` with wavespectra's tail when the last frequency is above
    /// [`TAIL_FROM_HZ`], m².
    pub fn variance(&self) -> f64 {
        let s = self.oned();
        let mut m0: f64 = s.iter().zip(self.df()).map(|(s, df)| s * df).sum();
        if let (Some(&sn), Some(&fn_)) = (s.last(), self.freq_hz.last()) {
            if fn_ > TAIL_FROM_HZ {
                m0 += 0.25 * sn * fn_;
            }
        }
        m0
    }

    /// The sea-state parameters wavespectra computes from this grid.
    pub fn stats(&self) -> SpectrumStats {
        let s = self.oned();
        let df = self.df();
        let (nd, dd) = (self.dir_deg.len(), self.dd());
        let hs_m = 4.0 * self.variance().max(0.0).sqrt();
        // First directional moments per frequency (SpecArray.momd with theta = 90).
        let (sin_w, cos_w): (Vec<f64>, Vec<f64>) =
            self.dir_deg.iter().map(|d| (270.0 - d).to_radians().sin_cos()).unzip();
        let moments: Vec<(f64, f64)> = self
            .efth
            .chunks_exact(nd.max(1))
            .map(|row| {
                let ms: f64 = row.iter().zip(&sin_w).map(|(e, s)| e * s).sum();
                let mc: f64 = row.iter().zip(&cos_w).map(|(e, c)| e * c).sum();
                (dd * ms, dd * mc)
            })
            .collect();
        let direction = |ms: f64, mc: f64| (270.0 - ms.atan2(mc).to_degrees()).rem_euclid(360.0);
        let peak = peak_index(&s);
        let tp_s = peak.map(|i| {
            let (f1, f2, f3) = (self.freq_hz[i - 1], self.freq_hz[i], self.freq_hz[i + 1]);
            let (e1, e2, e3) = (s[i - 1], s[i], s[i + 1]);
            let q12 = (e1 - e2) / (f1 - f2);
            let q13 = (e1 - e3) / (f1 - f3);
            let qa = (q13 - q12) / (f3 - f2);
            1.0 / ((f1 + f2 - q12 / qa) / 2.0)
        });
        let dpm_deg = peak.map(|i| direction(moments[i].0, moments[i].1));
        let a: f64 = moments.iter().zip(&df).map(|(m, df)| m.0 * df).sum();
        let b: f64 = moments.iter().zip(&df).map(|(m, df)| m.1 * df).sum();
        let e: f64 = s.iter().zip(&df).map(|(s, df)| s * df).sum();
        let energetic = e > 0.0 && nd > 0;
        let dm_deg = energetic.then(|| direction(a, b));
        let dspr_deg = energetic.then(|| (2.0 * (1.0 - (a.hypot(b) / e).min(1.0))).max(0.0).sqrt().to_degrees());
        SpectrumStats { hs_m, tp_s: tp_s.filter(|t| t.is_finite() && *t > 0.0), dpm_deg, dm_deg, dspr_deg }
    }

    /// Checks the axes and values, naming fields under `key` (`freq_hz[3]`, `efth[2][5]`).
    pub fn check(&self, key: &str) -> Result<()> {
        let nf = self.freq_hz.len();
        let nd = self.dir_deg.len();
        if nf < 3 {
            return Err(Error::out_of_range(
                format!("{key}freq_hz"),
                format!("{nf} frequencies"),
                "[3, ...] (a peak needs two neighbours)",
            ));
        }
        if nd == 0 {
            return Err(Error::out_of_range(format!("{key}dir_deg"), "0 directions", "[1, ...]"));
        }
        if self.efth.len() != nf * nd {
            return Err(Error::invalid(
                format!("{key}efth"),
                format!("{} values for {nf} frequencies x {nd} directions", self.efth.len()),
            ));
        }
        Ok(())
    }
}

/// Index of the largest strict local maximum of `s` (wavespectra's `_peak`), if any.
fn peak_index(s: &[f64]) -> Option<usize> {
    let mut best: Option<usize> = None;
    for i in 1..s.len().saturating_sub(1) {
        if s[i] > s[i - 1] && s[i] > s[i + 1] && best.is_none_or(|b| s[i] > s[b]) {
            best = Some(i);
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A cos² sea from 250° (coming from west-south-west) with a Gaussian frequency peak.
    fn sea() -> GriddedSpectrum {
        let freq: Vec<f64> = (0..40).map(|i| 0.04 * 1.07f64.powi(i)).collect();
        let dir: Vec<f64> = (0..36).map(|j| f64::from(j) * 10.0).collect();
        let mut g = GriddedSpectrum::zeros(freq.clone(), dir.clone());
        for (i, f) in freq.iter().enumerate() {
            for (j, d) in dir.iter().enumerate() {
                let off = ((d - 250.0 + 540.0) % 360.0 - 180.0).to_radians();
                let spread = if off.abs() < std::f64::consts::FRAC_PI_2 { off.cos().powi(2) } else { 0.0 };
                g.efth[i * 36 + j] = (-((f - 0.1) / 0.02).powi(2)).exp() * spread / 90.0;
            }
        }
        g
    }

    #[test]
    fn stats_follow_wavespectras_definitions() {
        let g = sea();
        let st = g.stats();
        // Tp: the parabola's vertex lies near the Gaussian's centre at 0.1 Hz.
        assert!((st.tp_s.unwrap() - 10.0).abs() < 0.2, "{st:?}");
        assert!((st.dpm_deg.unwrap() - 250.0).abs() < 1e-6, "{st:?}");
        assert!((st.dm_deg.unwrap() - 250.0).abs() < 1e-6, "{st:?}");
        // cos² over a half circle: mean resultant length 8 / (3π), spread sqrt(2 (1 − r)).
        let r = 8.0 / (3.0 * std::f64::consts::PI);
        let expected = (2.0 * (1.0 - r)).sqrt().to_degrees();
        assert!((st.dspr_deg.unwrap() - expected).abs() < 0.5, "{} vs {expected}", st.dspr_deg.unwrap());
        // Hs from m0: ∫ exp(−((f − fp)/σ)²) df = σ √π, and the spread integrates to 1 per degree sum.
        let m0 = 0.02 * std::f64::consts::PI.sqrt();
        assert!((st.hs_m / (4.0 * m0.sqrt()) - 1.0).abs() < 0.02, "{}", st.hs_m);
    }

    #[test]
    fn a_flat_spectrum_has_no_peak_and_an_isotropic_one_the_widest_spread() {
        let mut g = GriddedSpectrum::zeros(vec![0.1, 0.2, 0.3], (0..36).map(|j| f64::from(j) * 10.0).collect());
        g.efth.iter_mut().for_each(|e| *e = 1.0);
        let st = g.stats();
        assert_eq!(st.tp_s, None);
        assert!((st.dspr_deg.unwrap() - 2f64.sqrt().to_degrees()).abs() < 1e-9, "{st:?}");
        assert_eq!(GriddedSpectrum::zeros(vec![0.1, 0.2, 0.3], vec![0.0]).stats().dspr_deg, None);
    }
}
