//! A wind sea and an optional swell, spread over directions: the `F(kx, kz)` a spectral ocean samples.

use std::f64::consts::TAU;
use std::sync::Arc;

use super::{Dispersion, GriddedSpectrum, Jonswap, Phillips, PiersonMoskowitz, Spreading, Swell, TableSum, Tma};

/// The wind-sea spectrum model.
#[derive(Clone, Debug, PartialEq)]
pub enum WindSea {
    /// Tessendorf's Phillips spectrum (defined in wavenumber).
    Phillips(Phillips),
    /// Fully developed sea.
    PiersonMoskowitz(PiersonMoskowitz),
    /// Fetch-limited sea.
    Jonswap(Jonswap),
    /// Fetch-limited sea in finite depth.
    Tma(Tma),
    /// Tabulated directional spectra, summed (`spectrum = "table"`): directional already, so the
    /// spreading and the wind direction do not apply.
    Table(Arc<TableSum>),
}

impl WindSea {
    /// Omnidirectional wavenumber spectrum `Φ(k) = S(w(k)) dw/dk` (m³/rad) at k (rad/m).
    pub fn density_k(&self, k: f64, dispersion: &Dispersion) -> f64 {
        if k <= 0.0 {
            return 0.0;
        }
        let w = dispersion.omega_f64(k);
        let s = match self {
            WindSea::Phillips(p) => return p.density_k(k),
            WindSea::Table(t) => {
                // Φ(k) = ∫ F(k, θ) k dθ, by the midpoint rule over 1° steps (not on a hot path).
                let n = 360;
                let dt = TAU / f64::from(n);
                return (0..n).map(|j| t.wavenumber_density(k, (f64::from(j) + 0.5) * dt, dispersion)).sum::<f64>()
                    * k
                    * dt;
            }
            WindSea::PiersonMoskowitz(p) => p.density(w),
            WindSea::Jonswap(j) => j.density(w),
            WindSea::Tma(t) => t.density(w),
        };
        s * dispersion.group_speed_f64(k)
    }

    /// Peak angular frequency (rad/s).
    pub fn peak_omega(&self, dispersion: &Dispersion) -> f64 {
        match self {
            WindSea::Phillips(p) => dispersion.omega_f64(p.peak_wavenumber()),
            WindSea::PiersonMoskowitz(p) => p.peak_omega(),
            WindSea::Jonswap(j) => j.peak_omega,
            WindSea::Tma(t) => t.peak_omega,
            // A table without an interior peak in its frequency spectrum: its middle frequency.
            WindSea::Table(t) => match t.peak_period() {
                Some(tp) => TAU / tp,
                None => {
                    let g = t.stats_grid();
                    TAU * g.freq_hz[g.freq_hz.len() / 2]
                }
            },
        }
    }
}

/// The directional wavenumber spectrum of a sea: a wind sea spread about the wind, plus a swell.
///
/// `F(kx, kz) = Φ(k) D(θ - θ_wind) / k + Φ_swell(k) D_swell(θ - θ_swell) / k` (m⁴/rad²), where
/// `θ = atan2(kz, kx)` is the direction a wave travels; `∫∫ F dkx dkz` is the height variance m0.
#[derive(Clone, Debug, PartialEq)]
pub struct DirectionalSpectrum {
    /// The wind sea.
    pub wind_sea: WindSea,
    /// Its spreading about the wind direction.
    pub spreading: Spreading,
    /// Direction the wind blows towards (rad, from +X towards +Z).
    pub wind_direction: f64,
    /// 10 m wind speed U10 (m/s), used by wind-dependent spreading.
    pub wind_speed: f64,
    /// Dispersion relation (depth).
    pub dispersion: Dispersion,
    /// Optional swell added to the wind sea.
    pub swell: Option<Swell>,
}

impl DirectionalSpectrum {
    /// F(kx, kz) in m⁴/rad² (m² per (rad/m)²) at wave vector (kx, kz) in rad/m.
    pub fn density(&self, kx: f64, kz: f64) -> f64 {
        let k = kx.hypot(kz);
        if k <= 0.0 {
            return 0.0;
        }
        let theta = kz.atan2(kx);
        let w = self.dispersion.omega_f64(k);
        let mut f = match &self.wind_sea {
            WindSea::Table(t) => t.wavenumber_density(k, theta, &self.dispersion) * k,
            sea => {
                let wp = sea.peak_omega(&self.dispersion);
                sea.density_k(k, &self.dispersion)
                    * self.spreading.density(theta - self.wind_direction, w, wp, self.wind_speed)
            }
        };
        if let Some(s) = &self.swell {
            f += s.density(w)
                * self.dispersion.group_speed_f64(k)
                * s.spreading.density(theta - s.direction, w, s.peak_omega(), self.wind_speed);
        }
        f / k
    }

    /// Peak period (s) of the stronger component at its own peak (the wind sea unless the swell's
    /// peak density is higher).
    pub fn peak_period(&self) -> f64 {
        let wp = self.wind_sea.peak_omega(&self.dispersion);
        let mut best = (self.wind_sea.density_k(self.dispersion.wavenumber_f64(wp), &self.dispersion), wp);
        if let Some(s) = &self.swell {
            let ws = s.peak_omega();
            let k = self.dispersion.wavenumber_f64(ws);
            let ds = s.density(ws) * self.dispersion.group_speed_f64(k);
            if ds > best.0 {
                best = (ds, ws);
            }
        }
        TAU / best.1
    }

    /// This spectrum sampled as wavespectra's `efth(freq, dir)` (m²/Hz/deg, directions the waves
    /// come from, nautical) at `freq_hz` and `dir_deg`: `E(f, φ) = F(k, θ) k (dk/df) (π/180)` with
    /// `dk/df = 2π / c_g` and `θ = φ + 90°` the direction of travel in swell's frame.
    pub fn gridded(&self, freq_hz: Vec<f64>, dir_deg: Vec<f64>) -> GriddedSpectrum {
        let mut g = GriddedSpectrum::zeros(freq_hz, dir_deg);
        let nd = g.dir_deg.len();
        for (i, &f) in g.freq_hz.iter().enumerate() {
            let k = self.dispersion.wavenumber_f64(TAU * f);
            let dk_df = TAU / self.dispersion.group_speed_f64(k);
            for (j, &d) in g.dir_deg.iter().enumerate() {
                let theta = (d + 90.0).to_radians();
                let (kx, kz) = (k * theta.cos(), k * theta.sin());
                g.efth[i * nd + j] = self.density(kx, kz) * k * dk_df * std::f64::consts::PI / 180.0;
            }
        }
        g
    }

    /// The grid a sea's statistics are taken on: a table's own (or the union of several), else
    /// frequencies from 0.01 to 2 Hz in steps of 2 % and directions every 5°.
    pub fn stats_grid(&self) -> GriddedSpectrum {
        match (&self.wind_sea, &self.swell) {
            (WindSea::Table(t), None) => t.stats_grid(),
            (WindSea::Table(t), Some(_)) => {
                let g = t.stats_grid();
                self.gridded(g.freq_hz, g.dir_deg)
            }
            _ => {
                let n = (200f64.ln() / 1.02f64.ln()).ceil() as i32;
                let freq = (0..=n).map(|i| 0.01 * 1.02f64.powi(i)).collect();
                let dir = (0..72).map(|j| f64::from(j) * 5.0).collect();
                self.gridded(freq, dir)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spectrum::{frequency_moment, Jonswap};

    /// `∫∫ F dkx dkz` in polar coordinates: `∫ k dk ∫ dθ F`.
    fn variance(s: &DirectionalSpectrum, k_max: f64) -> f64 {
        let (nk, nt) = (4000, 720);
        let dk = k_max / nk as f64;
        let dt = TAU / nt as f64;
        let mut sum = 0.0;
        for i in 0..nk {
            let k = (i as f64 + 0.5) * dk;
            for j in 0..nt {
                let t = (j as f64 + 0.5) * dt;
                sum += s.density(k * t.cos(), k * t.sin()) * k * dk * dt;
            }
        }
        sum
    }

    #[test]
    fn spreading_keeps_the_variance_of_the_frequency_spectrum() {
        let j = Jonswap::from_wind(10.0, 80e3, 3.3);
        let m0 = frequency_moment(|w| j.density(w), 0, 0.05, (9.81f64 * 4.0).sqrt(), 40_000);
        for spreading in crate::spectrum::SpreadingFunction::ALL.iter().map(|&f| Spreading::from(f)) {
            let s = DirectionalSpectrum {
                wind_sea: WindSea::Jonswap(j),
                spreading,
                wind_direction: 0.7,
                wind_speed: 10.0,
                dispersion: Dispersion::Deep,
                swell: None,
            };
            let v = variance(&s, 4.0);
            assert!((v / m0 - 1.0).abs() < 2e-3, "{spreading:?}: {v} vs {m0}");
        }
    }
}
