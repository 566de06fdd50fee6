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

/// Entries of the cut-off table (log-spaced wavenumbers).
const TABLE: usize = 64;

/// The slope variance of a surface's waves shorter than a cut-off, looked up in constant time.
///
/// Built once from a model's components (wavenumber rad/m, slope variance); `above(k)` is the sum
/// over the components with wavenumber above `k`, interpolated in log k between 64 log-spaced
/// cut-offs from half the longest wave's k to twice the shortest's.
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
            *t = valid.iter().filter(|c| c.0 > cut).map(|c| c.1).sum::<f64>() as f32;
        }
        let total = valid.iter().map(|c| c.1).sum::<f64>() as f32;
        Self { log_k0: l0 as f32, inv_step: (1.0 / step) as f32, table, total }
    }

    /// Slope variance of every wave (both axes summed), the far field's where no geometry is left.
    pub fn total(&self) -> f32 {
        self.total
    }

    /// Slope variance (both axes summed) of the waves with wavenumber above `k_cut` rad/m.
    pub fn above(&self, k_cut: f32) -> f32 {
        if self.total == 0.0 {
            return 0.0;
        }
        if !(k_cut > 0.0) {
            return self.total;
        }
        let x = (k_cut.ln() - self.log_k0) * self.inv_step;
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
}

/// Bruneton et al.'s fit of the Fresnel reflectance of water averaged over Gaussian slopes of
/// deviation `sigma_v` along the view, for the view at `cos_v` to the mean normal; `sigma_v = 0`
/// gives Schlick's `(1 - cos)^5` without the normal-incidence term, which [`mean_fresnel`] adds.
fn bruneton_fresnel(cos_v: f32, sigma_v: f32) -> f32 {
    let c = (1.0 - cos_v.clamp(0.0, 1.0)).max(0.0);
    c.powf(5.0 * (-2.69 * sigma_v).exp()) / (1.0 + 22.7 * sigma_v.powf(1.5))
}

/// Mean Fresnel reflectance over slopes of total variance `variance` (both axes; isotropic, so
/// `sigma_v^2 = variance / 2`), for a view at `cos_v` to the mean normal and normal-incidence
/// reflectance `r0`.
pub fn mean_fresnel(cos_v: f32, variance: f32, r0: f32) -> f32 {
    let sigma_v = (0.5 * variance.max(0.0)).sqrt();
    (r0 + (1.0 - r0) * bruneton_fresnel(cos_v, sigma_v)).clamp(0.0, 1.0)
}

/// A Blinn-Phong exponent widened by unresolved slopes of total variance `variance`: its
/// equivalent Beckmann roughness `m^2 = 2 / (s + 2)` (Walter et al. 2007) grows by the variance,
/// `s' = 2 / (m^2 + variance) - 2`, and the returned weight `(s' + 2) / (s + 2)` keeps the
/// highlight's energy (the lobe's integral over the hemisphere is proportional to 1 / (s + 2)):
/// the glitter spreads and dims, it does not vanish or brighten.
pub fn widened_lobe(shininess: f32, variance: f32) -> (f32, f32) {
    let m2 = 2.0 / (shininess.max(0.0) + 2.0) + variance.max(0.0);
    let s = (2.0 / m2 - 2.0).max(0.0);
    (s, (s + 2.0) / (shininess.max(0.0) + 2.0))
}

/// Two unit normals spread about `n` by the slope deviation of total variance `variance`, tilted
/// by ±sigma towards and away from `to_eye` in the plane of incidence: where the reflected sky is
/// averaged, so a rough far sea reflects the sky above the horizon as well as the horizon itself.
/// The sky varies with elevation only, which tilts across the plane of incidence barely change,
/// so two samples stand for the four of a full cross.
pub fn spread_normals(n: Vec3, to_eye: Vec3, variance: f32) -> [Vec3; 2] {
    let sigma = (0.5 * variance.max(0.0)).sqrt();
    let t = (to_eye - n * n.dot(to_eye)).normalize_or(n.any_orthonormal_vector());
    [(n + sigma * t).normalize_or(n), (n - sigma * t).normalize_or(n)]
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
        assert!((s.above(0.5) - 0.03).abs() < 1e-6, "{}", s.above(0.5));
        assert!((s.above(5.0) - 0.02).abs() < 1e-6, "{}", s.above(5.0));
        assert_eq!(s.above(100.0), 0.0);
        // Monotone in the cut.
        let mut last = f32::INFINITY;
        for i in 0..200 {
            let v = s.above(0.01 * 1.05f32.powi(i));
            assert!(v <= last + 1e-9);
            last = v;
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
