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

use crate::math::{fast_exp2, fast_pow, Lanes, Vec3Lanes};
pub use crate::water::UnresolvedSlopes;

/// Width (m) of the patch of surface one pixel sees, per lane: `distance` (m) times the pixel's
/// angle `pixel_angle` (radians), stretched by the grazing angle as `1 / sqrt(cos)`, `cos` the
/// cosine between the surface normal and the view (taken at least 0.05, so a grazing view
/// stretches it at most 4.5 times). The one footprint the slope filter (`render/sea_lod.rs`) and
/// the foam's levels of detail (`water_optics.rs`) both use.
#[inline(always)]
pub fn pixel_footprint_lanes(distance: Lanes, pixel_angle: f32, cos: Lanes) -> Lanes {
    distance * pixel_angle / cos.max(0.05).sqrt()
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
