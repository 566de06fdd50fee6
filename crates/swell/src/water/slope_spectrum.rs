//! The slope spectrum of a wave model as the filtering needs it: the slope variance of the waves
//! shorter than a cut-off wavenumber, looked up in constant time ([`UnresolvedSlopes`]), and the
//! one formula every model with discrete waves lists its slopes by ([`push_wave_slopes`]).
//!
//! It lives with the models because it is a fact about the surface, not about light: the
//! renderer's footprint filter (`render/sea_lod.rs`) and the shading of the unresolved part
//! (`shading/slope_variance.rs`, Bruneton, Neyret and Holzschuch 2010) both read it. For one
//! wave of amplitude A and wavenumber k the slope variance, summed over both horizontal axes, is
//! `(A k)^2 / 2`; for the FFT ocean, `k^2 |h(k)|^2` per wave vector
//! ([`crate::water::WaveModel::slope_components`]).

use crate::math::{fast_log2, Lanes};

/// Appends `(wavenumber rad/m, slope variance)` for each `(amplitude m, wavelength m)` wave of a
/// sinusoidal train: `k = 2 pi / L` and `(A k)^2 / 2`, the mean of `(A k cos)^2` over a period.
/// The one definition the Gerstner, Tessendorf, sines and Airy models list their slopes with.
pub fn push_wave_slopes(waves: impl IntoIterator<Item = (f32, f32)>, out: &mut Vec<(f32, f32)>) {
    for (amplitude, wavelength) in waves {
        let k = std::f32::consts::TAU / wavelength;
        out.push((k, 0.5 * (amplitude * k).powi(2)));
    }
}

/// The sea surface's total slope variance (both axes summed, dimensionless) at wind speed `u10`
/// (m/s, 10 m up), as Cox and Munk (1954) measured it from the sun's glitter on a clean sea:
/// `0.003 + 5.12e-3 U10` (± 0.004), every wave down to the capillary ripples. The whitecaps' total
/// Jacobian variance (`water/foam.rs`); negative or NaN speeds read as calm (0.003).
pub fn cox_munk_slope_variance(u10: f32) -> f32 {
    0.003 + 5.12e-3 * u10.max(0.0)
}

/// Cox and Munk's (1954) clean-sea slope variances (upwind, crosswind; dimensionless) at wind
/// speed `u10` (m/s, 10 m up): `3.16e-3 U` and `0.003 + 1.92e-3 U` with U the wind at 12.5 m,
/// their anemometer's height, taken from U10 by the 1/7 power law (`U12.5 = 1.032 U10`). Every
/// wave down to the capillaries: the distribution the sun's glitter shows
/// ([`crate::scene::GlitterModel::CoxMunk`]). Negative or NaN speeds read as calm. Their sum is
/// not [`cox_munk_slope_variance`]: Cox and Munk fitted the total on its own (`0.003 + 5.12e-3
/// U`), and the whitecaps keep that fit.
pub fn cox_munk_axis_variances(u10: f32) -> glam::Vec2 {
    let u = u10.max(0.0) * 1.25f32.powf(1.0 / 7.0);
    glam::Vec2::new(3.16e-3 * u, 0.003 + 1.92e-3 * u)
}

/// The wind speed U10 (m/s) of a fully developed sea whose spectral peak has wavenumber
/// `k_peak` (rad/m): Pierson and Moskowitz (1964) put the peak at `ω = 0.877 g / U`, so in deep
/// water `k = 0.769 g / U²`. What a sea of discrete waves with no wind of its own is taken to be
/// blown by, its longest wave standing for the peak.
pub fn developed_sea_wind(k_peak: f32) -> f32 {
    (0.877f32 * 0.877 * crate::GRAVITY / k_peak).sqrt()
}

/// Entries of the cut-off table (log-spaced wavenumbers).
const TABLE: usize = 64;

/// The slope variance of a surface's waves shorter than a cut-off, looked up in constant time.
///
/// Built once from a model's components (wavenumber rad/m, slope variance); `above(k)` is the sum
/// over the components of their unresolved share at the cut (all of a wave an octave shorter than
/// the cut, none of one an octave longer, a smooth blend between: [`unresolved_share`]),
/// interpolated in log k between 64 log-spaced cut-offs from half the longest wave's k to twice
/// the shortest's.
#[derive(Clone, Debug, PartialEq)]
pub struct UnresolvedSlopes {
    log_k0: f32,
    inv_step: f32,
    table: [f32; TABLE],
    total: f32,
    height_variance: f32,
}

impl Default for UnresolvedSlopes {
    /// A surface with no waves to filter (a mirror stays a mirror).
    fn default() -> Self {
        Self { log_k0: 0.0, inv_step: 0.0, table: [0.0; TABLE], total: 0.0, height_variance: 0.0 }
    }
}

impl UnresolvedSlopes {
    /// From `(wavenumber rad/m, slope variance)` pairs; non-finite or non-positive ones are skipped.
    pub fn from_components(components: &[(f32, f32)]) -> Self {
        let valid: Vec<(f64, f64)> = components
            .iter()
            .filter(|(k, v)| k.is_finite() && v.is_finite() && *k > 0.0 && *v > 0.0)
            .map(|&(k, v)| (f64::from(k), f64::from(v)))
            .collect();
        if valid.is_empty() {
            return Self::default();
        }
        let k_lo = valid.iter().map(|c| c.0).fold(f64::INFINITY, f64::min) * 0.5;
        let k_hi = valid.iter().map(|c| c.0).fold(0.0, f64::max) * 2.0;
        let (l0, l1) = (k_lo.ln(), k_hi.ln());
        let step = (l1 - l0) / (TABLE - 1) as f64;
        let mut table = [0.0f32; TABLE];
        for (i, t) in table.iter_mut().enumerate() {
            let cut = (l0 + step * i as f64).exp();
            // Summed in f64 and in a fixed order: the table is the same on every run.
            *t = valid.iter().map(|c| c.1 * unresolved_share(c.0, cut)).sum::<f64>() as f32;
        }
        let total = valid.iter().map(|c| c.1).sum::<f64>() as f32;
        // A wave of amplitude A has slope variance (A k)² / 2 and height variance A² / 2.
        let height_variance = valid.iter().map(|c| c.1 / (c.0 * c.0)).sum::<f64>() as f32;
        Self { log_k0: l0 as f32, inv_step: (1.0 / step) as f32, table, total, height_variance }
    }

    /// Variance of the surface's height over all its waves, m² (`m0`; the significant wave
    /// height is `4 sqrt(m0)`), 0 without waves: the scale of its crests.
    pub fn height_variance(&self) -> f32 {
        self.height_variance
    }

    /// The longest wave's wavenumber, rad/m; `None` without waves.
    pub fn longest_wavenumber(&self) -> Option<f32> {
        // The table starts at half the smallest wavenumber (`from_components`).
        (self.total > 0.0).then(|| 2.0 * self.log_k0.exp())
    }

    /// Slope variance of every wave (both axes summed), the far field's where no geometry is left.
    pub fn total(&self) -> f32 {
        self.total
    }

    /// Slope variance (both axes summed) the cut-off `k_cut` rad/m leaves unresolved: the waves
    /// shorter than it, blended over an octave either side ([`unresolved_share`]).
    pub fn above(&self, k_cut: f32) -> f32 {
        if self.total == 0.0 {
            return 0.0;
        }
        if k_cut.is_nan() || k_cut <= 0.0 {
            return self.total;
        }
        let x = (fast_log2(k_cut) * std::f32::consts::LN_2 - self.log_k0) * self.inv_step;
        if x <= 0.0 {
            return self.table[0];
        }
        if x >= (TABLE - 1) as f32 {
            return 0.0;
        }
        let i = x as usize;
        let f = x - i as f32;
        self.table[i] * (1.0 - f) + self.table[i + 1] * f
    }

    /// Slope variance (both axes) of the waves a sample spread over `footprint` metres cannot
    /// resolve: those shorter than two footprints (Nyquist), `k > pi / footprint`.
    pub fn unresolved(&self, footprint: f32) -> f32 {
        self.above(std::f32::consts::PI / footprint.max(1e-6))
    }

    /// [`Self::unresolved`] of eight footprints: the table index computed for all lanes at once,
    /// then one table read per lane.
    #[inline(always)]
    pub fn unresolved_lanes(&self, footprint: Lanes) -> Lanes {
        if self.total == 0.0 {
            return Lanes::splat(0.0);
        }
        let k_cut = std::f32::consts::PI / footprint.max(1e-6);
        let x = (k_cut.map(fast_log2) * std::f32::consts::LN_2 - self.log_k0) * self.inv_step;
        let last = (TABLE - 1) as f32;
        Lanes::from_fn(|l| {
            let x = x.0[l];
            if x.is_nan() {
                return self.total; // read as no cut, as `above` does
            }
            if x >= last {
                return 0.0; // past the table
            }
            let x = x.max(0.0);
            // In [0, last) here: through i32, whose conversion is one instruction and a clamp
            // (to usize took a dozen per lane, a fifth of this look-up).
            let i = x as i32 as usize;
            let f = x - i as f32;
            self.table[i] * (1.0 - f) + self.table[i + 1] * f
        })
    }
}

/// The share of a wave of wavenumber `k` that a cut-off at `cut` (rad/m) leaves to the shading:
/// 0 for a wave an octave or more longer than the cut, 1 for one an octave or more shorter, and
/// a smoothstep in `log2(k / cut)` between. A pixel's box filter weakens a wave gradually as it
/// shortens towards the footprint (its response is a sinc), and a hard cut made each wave's tilt
/// leave the geometric normals at one distance: with a few analytic waves (the `sea` preset's six
/// Gerstner waves) that drew a line across the sea where the longest one went.
fn unresolved_share(k: f64, cut: f64) -> f64 {
    let x = (0.5 * ((k / cut).log2() + 1.0)).clamp(0.0, 1.0);
    x * x * (3.0 - 2.0 * x)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_variance_above_a_cut_sums_the_shorter_waves() {
        // Three waves: k = 0.1, 1, 10 rad/m with slope variances 0.001, 0.01, 0.02.
        let s = UnresolvedSlopes::from_components(&[(0.1, 0.001), (1.0, 0.01), (10.0, 0.02)]);
        assert!((s.total() - 0.031).abs() < 1e-7);
        assert!((s.above(0.01) - 0.031).abs() < 1e-6);
        // A wave an octave or more shorter than the cut is all unresolved, one an octave or more
        // longer not at all (to the table's interpolation, 1e-6 two octaves away)...
        assert!((s.above(0.25) - 0.03).abs() < 1e-6, "{}", s.above(0.25));
        assert!((s.above(2.5) - 0.02).abs() < 1e-6, "{}", s.above(2.5));
        // ...and one at the cut half: no wave leaves the geometry at a single distance.
        assert!((s.above(1.0) - 0.025).abs() < 2e-4, "{}", s.above(1.0));
        assert!(s.above(0.8) > 0.025 && s.above(1.25) < 0.025);
        assert_eq!(s.above(100.0), 0.0);
        // Monotone in the cut (to within the fast logarithm's 1e-6 in the table index).
        let mut last = f32::INFINITY;
        for i in 0..200 {
            let v = s.above(0.01 * 1.05f32.powi(i));
            assert!(v <= last + 1e-7);
            last = v;
        }
        // The batched look-up is the scalar one, lane by lane.
        let footprints = crate::math::Lanes::from_fn(|i| 0.01 * 1.3f32.powi(i as i32 % 40));
        let batch = s.unresolved_lanes(footprints);
        for i in 0..crate::math::LANES {
            assert_eq!(batch.0[i], s.unresolved(footprints.0[i]), "lane {i}");
        }
        assert_eq!(UnresolvedSlopes::default().above(1.0), 0.0);
    }

    #[test]
    fn a_wave_train_s_slope_variance_is_half_the_square_of_its_peak_slope() {
        let mut out = Vec::new();
        push_wave_slopes([(0.5, 20.0), (0.1, 2.0)], &mut out);
        let k = std::f32::consts::TAU / 20.0;
        assert_eq!(out[0], (k, 0.5 * (0.5 * k) * (0.5 * k)));
        assert_eq!(out.len(), 2);
    }
}
