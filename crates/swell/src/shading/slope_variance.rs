//! Far water shaded statistically: the slope variance of the waves a pixel (or the mesh) cannot
//! resolve widens the sun's glitter and softens the Fresnel reflection, instead of those waves
//! being point-sampled into shimmer.
//!
//! Source: Bruneton, Neyret and Holzschuch 2010, "Real-time realistic ocean lighting using
//! seamless transitions from geometry to BRDF" (Computer Graphics Forum 29(2)). The waves split at
//! a cut-off wavenumber: longer ones are geometry, shorter ones only a distribution of slopes,
//! Gaussian with variance `sigma^2 = sum over the short waves of k^2 |h(k)|^2` (for one wave of
//! amplitude A and wavenumber k, `(A k)^2 / 2`). Their BRDF then uses that variance: the highlight
//! is a Beckmann lobe of roughness `m^2 = sigma^2`, and the mean Fresnel factor over the slopes is
//! their fit `F = (1 - cos v)^(5 exp(-2.69 sigma_v)) / (1 + 22.7 sigma_v^1.5)` (their eq. 13
//! appendix), `sigma_v` the slope deviation seen along the view. The per-wave form (issue 17 for
//! the analytic models) is the same sum taken over each model's own waves
//! ([`crate::water::WaveModel::slope_components`]).

use glam::Vec3;

use crate::math::{fast_exp2, fast_log2, fast_pow, Lanes, Vec3Lanes};

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
}

impl Default for UnresolvedSlopes {
    /// A surface with no waves to filter (a mirror stays a mirror).
    fn default() -> Self {
        Self { log_k0: 0.0, inv_step: 0.0, table: [0.0; TABLE], total: 0.0 }
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
        Self { log_k0: l0 as f32, inv_step: (1.0 / step) as f32, table, total }
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

/// Mean Fresnel reflectance over slopes of total variance `variance` (both axes; isotropic, so
/// `sigma_v^2 = variance / 2`), for a view at `cos_v` to the mean normal and normal-incidence
/// reflectance `r0`: Bruneton et al.'s fit `(1 - cos_v)^(5 e^(-2.69 sigma_v)) / (1 + 22.7
/// sigma_v^1.5)` of the reflectance averaged over Gaussian slopes, plus the normal-incidence
/// term; `variance = 0` gives Schlick's approximation. One lane of [`mean_fresnel_lanes`].
pub fn mean_fresnel(cos_v: f32, variance: f32, r0: f32) -> f32 {
    mean_fresnel_lanes(Lanes::splat(cos_v), Lanes::splat(variance), r0).0[0]
}

/// [`mean_fresnel`] per lane, the powers by [`fast_exp2`] and [`fast_pow`] (relative error
/// below 1e-4).
#[inline(always)]
pub fn mean_fresnel_lanes(cos_v: Lanes, variance: Lanes, r0: f32) -> Lanes {
    let sigma_v = (0.5 * variance.max(0.0)).sqrt();
    let c = (1.0 - cos_v.max(0.0).min(1.0)).max(0.0);
    let exponent = 5.0 * (-2.69 * std::f32::consts::LOG2_E * sigma_v).map(fast_exp2);
    let powered = Lanes::from_fn(|i| fast_pow(c.0[i], exponent.0[i]));
    let mean = powered / (1.0 + 22.7 * sigma_v * sigma_v.sqrt());
    (r0 + (1.0 - r0) * mean).max(0.0).min(1.0)
}

/// A Blinn-Phong exponent widened by unresolved slopes of total variance `variance`: its
/// equivalent Beckmann roughness `m^2 = 2 / (s + 2)` (Walter et al. 2007) grows by the variance,
/// `s' = 2 / (m^2 + variance) - 2`, and the returned weight `(s' + 2) / (s + 2)` keeps the
/// highlight's energy (the lobe's integral over the hemisphere is proportional to 1 / (s + 2)):
/// the glitter spreads and dims, it does not vanish or brighten. No variance leaves the lobe as it
/// is. One lane of [`widened_lobe_lanes`].
pub fn widened_lobe(shininess: f32, variance: f32) -> (f32, f32) {
    let (s, w) = widened_lobe_lanes(shininess, Lanes::splat(variance));
    (s.0[0], w.0[0])
}

/// [`widened_lobe`] per lane: (exponents, weights).
#[inline(always)]
pub fn widened_lobe_lanes(shininess: f32, variance: Lanes) -> (Lanes, Lanes) {
    let s0 = shininess.max(0.0);
    let variance = variance.max(0.0);
    let m2 = 2.0 / (s0 + 2.0) + variance;
    let some = variance.gt(0.0);
    let s = some.select((2.0 / m2 - 2.0).max(0.0), s0);
    (s, some.select((s + 2.0) / (s0 + 2.0), 1.0))
}

/// Two unit normals per lane spread about `n` by the slope deviation of total variance
/// `variance`, tilted by ±sigma towards and away from `to_eye` in the plane of incidence: where
/// the reflected sky is averaged, so a rough far sea reflects the sky above the horizon as well as
/// the horizon itself. The sky varies with elevation mostly, which tilts across the plane of
/// incidence barely change, so two samples stand for the four of a full cross. Where `to_eye` is
/// along `n` any tangent serves (glam's `any_orthonormal_vector`); the first `live` lanes count.
#[inline(always)]
pub fn spread_normals_lanes(n: Vec3Lanes, to_eye: Vec3Lanes, variance: Lanes, live: usize) -> [Vec3Lanes; 2] {
    let sigma = (0.5 * variance.max(0.0)).sqrt();
    let mut t = (to_eye - n.scale(n.dot(to_eye))).normalize_or(Vec3::ZERO);
    for i in 0..live {
        if t.lane(i) == Vec3::ZERO {
            t.set_lane(i, n.lane(i).any_orthonormal_vector());
        }
    }
    let tilt = t.scale(sigma);
    [unit_or(n + tilt, n), unit_or(n - tilt, n)]
}

/// `s` made unit per lane, or `fallback` where it has no direction. A function, not a closure:
/// a closure is compiled apart from the AVX2 kernel that inlines this (without its target
/// features), which made this step a fifth of the water's shading.
#[inline(always)]
fn unit_or(s: Vec3Lanes, fallback: Vec3Lanes) -> Vec3Lanes {
    let rcp = 1.0 / s.length();
    rcp.abs().lt(f32::INFINITY).and(rcp.abs().gt(0.0)).select3(s.scale(rcp), fallback)
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
    fn the_mean_fresnel_falls_with_roughness_at_grazing_views_and_matches_schlick_when_smooth() {
        let r0 = 0.02;
        for cos in [0.05f32, 0.2, 0.5, 0.9] {
            let schlick = r0 + (1.0 - r0) * (1.0 - cos).powi(5);
            assert!((mean_fresnel(cos, 0.0, r0) - schlick).abs() < 1e-5);
        }
        // Near the horizon a rough sea is no mirror (Bruneton et al.'s point).
        assert!(mean_fresnel(0.02, 0.04, r0) < 0.8 * mean_fresnel(0.02, 0.0, r0));
    }

    #[test]
    fn a_widened_lobe_keeps_its_energy() {
        let (s, w) = widened_lobe(200.0, 0.0);
        assert!((s - 200.0).abs() < 1e-2 && (w - 1.0).abs() < 1e-4);
        let (s, w) = widened_lobe(200.0, 0.02);
        assert!(s < 100.0 && w < 0.5, "{s} {w}");
        // Energy ~ peak / (s + 2): the same before and after.
        assert!((w / (s + 2.0) - 1.0 / 202.0).abs() < 1e-6);
    }
}
