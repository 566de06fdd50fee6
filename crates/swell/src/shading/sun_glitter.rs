//! The sun on a rough sea: each light's irradiance reflected through the surface's slope
//! distribution, in the light's own units (`[water.material] glitter = "cox-munk"`).
//!
//! A facet mirrors a light towards the eye when its normal is the half vector `h` between the
//! two. With the facets' slopes `ζ` spread with density `p(ζ)` about the normal the renderer
//! knows, the radiance seen is (Cox and Munk 1954, "Measurement of the roughness of the sea
//! surface from photographs of the sun's glitter", JOSA 44(11), their eq. for the glitter's
//! radiance; Bruneton, Neyret and Holzschuch 2010, §4, who add the shadowing)
//!
//! `L = E · F(v·h) · p(ζ_h) / (4 cos θv cos⁴β (1 + Λ(v) + Λ(l)))`
//!
//! with `E` the light's irradiance on a surface facing it, `F` Fresnel's reflectance at the facet,
//! `β` the facet's tilt from the normal, `θv` the view's, and `Λ` Smith's masking-shadowing for
//! Gaussian slopes (Walter, Marschner, Li and Torrance 2007, eq. 27, their rational fit), which
//! keeps a grazing view or a low sun from brightening without bound. `p` is a Gaussian whose
//! variances are those of the slopes the normal does not carry: the waves the mesh or the pixel
//! cannot resolve (issue 17's filter, isotropic), a micro-roughness along and across the wind that
//! brings the sea's total to Cox and Munk's measured one, and the sun disc's own spread (a mirror
//! shows the disc, not a point).
//!
//! Units: the renderer's radiance unit is the one in which a white Lambertian surface facing a
//! light of colour × intensity `I` has radiance `I` (the diffuse term, `shading::lambert`), so the
//! light's irradiance is `E = π I`: the glitter is in the same units as everything else.

use glam::{Vec2, Vec3};

use super::water_optics::{fresnel_dielectric_lanes, incident_lanes};
use super::{Environment, SunDisc};
use crate::math::{fast_exp2, Lanes, Vec3Lanes};
use crate::water::cox_munk_axis_variances;

/// The slope distribution the lights' reflection goes through, beside the per-point unresolved
/// variance: a micro-roughness along and across the wind and the sun disc's spread.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SunGlitter {
    /// Unit world direction (x, 0, z) the wind blows towards: the micro-roughness's first axis.
    pub wind: Vec3,
    /// Slope variance of the micro-roughness along the wind and across it (dimensionless, >= 0).
    pub micro: Vec2,
    /// Slope variance per axis of the sun disc's extent (dimensionless, > 0): a facet turned by
    /// `δ` moves the reflection by `2δ`, so a disc of angular radius `r` (radians) is a uniform
    /// disc of slopes of radius `r / 2`, whose variance per axis is `r² / 16`.
    pub disc: f32,
}

/// Angular radius of the real sun, radians (0.267°): the disc's spread where no sun is drawn.
const SUN_RADIUS: f32 = 4.65e-3;

impl SunGlitter {
    /// The distribution of a sea blown by a wind of `u10` m/s (10 m up) towards `wind` (world x, z;
    /// isotropic when `None` or zero) whose own waves have total slope variance `waves` (both axes
    /// summed: resolved and unresolved, [`crate::water::UnresolvedSlopes::total`]): the
    /// micro-roughness is, on each axis, what Cox and Munk's variance for the wind
    /// ([`cox_munk_axis_variances`]) has beyond half of `waves` (the model's slopes taken as
    /// isotropic; the FFT sea's glitter then has Cox and Munk's width across the wind within 5 %,
    /// `tests/glitter_cox_munk.rs`); none on an axis the waves already fill. Without a direction
    /// the two axes share the total evenly.
    /// `sun` is the drawn disc, whose size spreads the reflection (the real sun's without one).
    pub fn cox_munk(u10: f32, waves: f32, wind: Option<Vec2>, sun: Option<&SunDisc>) -> Self {
        let cm = cox_munk_axis_variances(u10);
        let dir = wind.and_then(|w| w.try_normalize());
        let micro = match dir {
            Some(_) => (cm - Vec2::splat(0.5 * waves.max(0.0))).max(Vec2::ZERO),
            None => Vec2::splat((0.5 * (cm.x + cm.y - waves.max(0.0))).max(0.0)),
        };
        let d = dir.unwrap_or(Vec2::X);
        Self { wind: Vec3::new(d.x, 0.0, d.y), micro, disc: disc_variance(sun) }
    }

    /// No micro-roughness: the reflection spreads only by the unresolved slopes and the disc.
    pub fn smooth(sun: Option<&SunDisc>) -> Self {
        Self { wind: Vec3::X, micro: Vec2::ZERO, disc: disc_variance(sun) }
    }

    /// Total slope variance of the micro-roughness (both axes summed).
    pub fn micro_total(&self) -> f32 {
        self.micro.x + self.micro.y
    }

    /// Radiance each lane's point reflects towards the eye from every light (module docs), for
    /// unit normals `n` facing the eye along `to_eye`, the unresolved slope variance `unresolved`
    /// (both axes summed) and water of refractive index `ior`. Lights below the horizon reflect
    /// nothing.
    #[inline(always)]
    pub fn radiance_lanes(
        &self,
        env: &Environment,
        p: Vec3Lanes,
        n: Vec3Lanes,
        to_eye: Vec3Lanes,
        unresolved: Lanes,
        ior: f32,
    ) -> Vec3Lanes {
        let half = unresolved.max(0.0) * 0.5 + self.disc;
        let var_x = half + self.micro.x;
        let var_y = half + self.micro.y;
        // A facet tilted by β has |ζ|² = tan²β, and the Gaussian's exponent is at least
        // tan²β / (largest variance): past CUT of that the glitter is below e^(−CUT/2) of its peak
        // and taken as 0. Most batches look nowhere near a light's reflection; they stop here,
        // before the tangent frame, Fresnel and the shadowing are computed.
        const CUT: f32 = 60.0;
        let reach = var_x.max(var_y) * CUT;
        // Smith's masking reads the variance in each direction's own plane; the mean of the two
        // axes stands for it (the micro-roughness's axes differ by less than 1.5 times, and the
        // masking only matters at grazing angles, where it is a small correction either way).
        let var_mean = (var_x + var_y) * 0.5;
        let mut frame = None;
        let mut acc = Vec3Lanes::splat(Vec3::ZERO);
        for light in env.lights {
            let (l, radiance) = incident_lanes(light, p);
            let h = (l + to_eye).normalize_or(Vec3::Y);
            let nh = n.dot(h).max(1e-3);
            let nh2 = nh * nh;
            let tan2 = (1.0 - nh2).max(0.0) / nh2;
            let live = l.y.gt(0.0).and(tan2.lt(reach));
            if !live.any() {
                continue;
            }
            // The tangent frame (the wind projected onto the surface, and across it), the
            // Gaussian's normalisation and the view's masking: once per batch, if a light needs them.
            // Not `get_or_insert_with`: a closure is compiled apart from the vector kernel that
            // inlines this (without its target features), which made it a twentieth of a frame.
            let (tx, ty, norm, nv, lambda_v) = match frame {
                Some(f) => f,
                None => *frame.insert(self.frame_lanes(n, to_eye, var_x, var_y, var_mean)),
            };
            let inv_nh = 1.0 / nh;
            let zx = h.dot(tx) * inv_nh;
            let zy = h.dot(ty) * inv_nh;
            let q = zx * zx / var_x + zy * zy / var_y;
            // exp(-q/2) = 2^(-q log2(e) / 2).
            let density = Lanes::from_fn(|i| fast_exp2(-0.5 * std::f32::consts::LOG2_E * q.0[i].min(CUT))) * norm;
            let fresnel = fresnel_dielectric_lanes(to_eye.dot(h), ior);
            let nl = n.dot(l).max(1e-3);
            let lambda_l = smith_lambda(nl, var_mean);
            let weight = fresnel * density / (4.0 * nv * nh2 * nh2 * (1.0 + lambda_v + lambda_l));
            acc = acc + radiance.scale(live.select(weight * std::f32::consts::PI, 0.0));
        }
        acc
    }

    /// Per lane: the tangent frame (the wind projected onto the surface of normal `n`, and across
    /// it), the slope Gaussian's normalisation, the cosine of the view and its masking Λ.
    #[inline(always)]
    fn frame_lanes(
        &self,
        n: Vec3Lanes,
        to_eye: Vec3Lanes,
        var_x: Lanes,
        var_y: Lanes,
        var_mean: Lanes,
    ) -> (Vec3Lanes, Vec3Lanes, Lanes, Lanes, Lanes) {
        let w = Vec3Lanes::splat(self.wind);
        let tx = (w - n.scale(n.dot(w))).normalize_or(Vec3::X);
        let ty = n.cross(tx);
        let norm = 1.0 / (std::f32::consts::TAU * (var_x * var_y).sqrt());
        let nv = n.dot(to_eye).max(1e-3);
        (tx, ty, norm, nv, smith_lambda(nv, var_mean))
    }
}

/// The disc's slope variance per axis ([`SunGlitter::disc`]).
fn disc_variance(sun: Option<&SunDisc>) -> f32 {
    // 1 − cos r = r² / 2 for small r.
    let r2 = sun.map_or(SUN_RADIUS * SUN_RADIUS, |s| 2.0 * (1.0 - s.cos_radius).max(0.0));
    (r2 / 16.0).max(1e-7)
}

/// Smith's Λ for Gaussian (Beckmann) slopes of variance `var` per axis seen at `cos` from the
/// normal: Walter et al.'s (2007) fit in `a = cot θ / sqrt(2 var)` (within 3e-3 + 1 % of the exact
/// `(e^(-a²) / (a sqrt π) − erfc a) / 2`, against the 1 it is added to), 0 from a = 1.6 on.
#[inline(always)]
fn smith_lambda(cos: Lanes, var: Lanes) -> Lanes {
    let sin = (1.0 - cos * cos).max(0.0).sqrt();
    let a = cos / (sin * (2.0 * var).sqrt()).max(1e-12);
    let lambda = (1.0 - 1.259 * a + 0.396 * a * a) / (3.535 * a + 2.181 * a * a);
    a.lt(1.6).select(lambda, 0.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Light, Sky};
    use crate::shading::{fresnel_dielectric, SkyRadiance};

    fn env_with(lights: &[Light]) -> Environment<'static> {
        let lights: &'static [Light] = Box::leak(lights.to_vec().into_boxed_slice());
        let sky: &'static SkyRadiance = Box::leak(Box::new(SkyRadiance::new(&Sky::default())));
        Environment { lights, ambient: Vec3::ZERO, sky, sun: None, eye: Vec3::ZERO, time: 0.0 }
    }

    /// Radiance of a flat sea (mean normal +Y) seen along `to_eye` under `g` and `env`'s lights.
    fn seen(g: &SunGlitter, env: &Environment, to_eye: Vec3) -> f32 {
        let ones = Vec3Lanes::splat(Vec3::Y);
        g.radiance_lanes(env, Vec3Lanes::splat(Vec3::ZERO), ones, Vec3Lanes::splat(to_eye), Lanes::splat(0.0), 1.333)
            .lane(0)
            .x
    }

    fn sun_at(elevation_deg: f32) -> (Vec3, Environment<'static>) {
        let e = elevation_deg.to_radians();
        let to_sun = Vec3::new(0.0, e.sin(), -e.cos());
        let env = env_with(&[Light::Directional { direction: -to_sun, color: Vec3::ONE, intensity: 1.0 }]);
        (to_sun, env)
    }

    #[test]
    fn the_reflected_flux_is_the_suns_times_fresnel() {
        // A flat sea of isotropic slopes, sun 40° up: the radiant exitance of the glitter,
        // ∫ L cos θv dω over the sky, is the irradiance E cos θl times the reflectance (masking
        // takes a little at the edges of the lobe).
        let (to_sun, env) = sun_at(40.0);
        let g = SunGlitter { wind: Vec3::X, micro: Vec2::splat(0.01), disc: 1e-7 };
        let steps = 600;
        let mut flux = 0.0f64;
        for i in 0..steps {
            let theta = (i as f64 + 0.5) / steps as f64 * std::f64::consts::FRAC_PI_2;
            for j in 0..steps {
                let phi = (j as f64 + 0.5) / steps as f64 * std::f64::consts::TAU;
                let v =
                    Vec3::new((theta.sin() * phi.cos()) as f32, theta.cos() as f32, (theta.sin() * phi.sin()) as f32);
                let d_omega =
                    theta.sin() * (std::f64::consts::FRAC_PI_2 / steps as f64) * (std::f64::consts::TAU / steps as f64);
                flux += f64::from(seen(&g, &env, v)) * theta.cos() * d_omega;
            }
        }
        let irradiance = std::f64::consts::PI * f64::from(to_sun.y);
        let f = f64::from(fresnel_dielectric(to_sun.y, 1.333));
        let ratio = flux / (irradiance * f);
        assert!((0.85..1.1).contains(&ratio), "exitance / (E cos θ F) = {ratio}");
    }

    #[test]
    fn at_the_specular_point_a_facet_facing_the_sun_shows_cox_and_munks_radiance() {
        let (to_sun, env) = sun_at(30.0);
        let g = SunGlitter { wind: Vec3::X, micro: Vec2::new(0.02, 0.01), disc: 1e-7 };
        let mirror = Vec3::new(-to_sun.x, to_sun.y, -to_sun.z);
        let l = seen(&g, &env, mirror);
        let cos_v = to_sun.y;
        let f = fresnel_dielectric(cos_v, 1.333);
        let expected = std::f32::consts::PI * f / (std::f32::consts::TAU * (0.02f32 * 0.01).sqrt()) / (4.0 * cos_v);
        // Below it only by Smith's masking at 60° from the normal (about 1 %).
        assert!(l < expected && l > 0.97 * expected, "{l} vs {expected}");
    }

    #[test]
    fn the_glitter_spreads_further_along_the_wind_and_wider_with_more_wind() {
        let (to_sun, env) = sun_at(30.0);
        let mirror = Vec3::new(-to_sun.x, to_sun.y, -to_sun.z);
        // 25° to the side of the mirror direction, once across the wind (wind along x), once along.
        let a = 25f32.to_radians();
        let side = Vec3::new(a.sin(), mirror.y, mirror.z * a.cos()).normalize();
        let wind_x = SunGlitter::cox_munk(10.0, 0.0, Some(Vec2::X), None);
        let wind_z = SunGlitter::cox_munk(10.0, 0.0, Some(Vec2::Y), None);
        assert!(seen(&wind_x, &env, side) > 1.2 * seen(&wind_z, &env, side));
        let calm = SunGlitter::cox_munk(3.0, 0.0, Some(Vec2::X), None);
        assert!(seen(&calm, &env, side) < seen(&wind_x, &env, side));
        assert!(seen(&calm, &env, mirror) > seen(&wind_x, &env, mirror));
        // The waves' own slopes take their share of the budget.
        let cm = cox_munk_axis_variances(10.0);
        let rough = SunGlitter::cox_munk(10.0, 0.5 * (cm.x + cm.y), Some(Vec2::X), None);
        assert!((rough.micro_total() - 0.5 * (cm.x + cm.y)).abs() < 1e-6);
        assert_eq!(SunGlitter::cox_munk(10.0, 1.0, None, None).micro_total(), 0.0);
    }

    #[test]
    fn a_sun_below_the_horizon_reflects_nothing_and_nothing_is_nan() {
        let (_, env) = sun_at(-5.0);
        let g = SunGlitter::cox_munk(8.0, 0.0, None, None);
        assert_eq!(seen(&g, &env, Vec3::new(0.0, 0.1, 0.995).normalize()), 0.0);
        let (_, env) = sun_at(0.5);
        let smooth = SunGlitter::smooth(None);
        for v in [Vec3::Y, Vec3::new(0.0, 1e-4, 1.0).normalize(), Vec3::new(0.0, 0.0087, -1.0).normalize()] {
            let l = seen(&smooth, &env, v);
            assert!(l.is_finite() && l >= 0.0, "{v}: {l}");
        }
    }

    #[test]
    fn smiths_lambda_matches_the_exact_form() {
        for var in [0.005f32, 0.02, 0.08] {
            for cos in [0.02f32, 0.1, 0.3, 0.6] {
                let a = f64::from(cos) / (f64::from((1.0 - cos * cos).sqrt()) * f64::from(2.0 * var).sqrt());
                let exact = 0.5 * ((-a * a).exp() / (a * std::f64::consts::PI.sqrt()) - erfc(a));
                let fit = f64::from(smith_lambda(Lanes::splat(cos), Lanes::splat(var)).0[0]);
                // Λ is added to 1 (and the other direction's Λ): an absolute error is what counts.
                assert!((fit - exact).abs() < 3e-3 + 0.01 * exact, "var {var} cos {cos}: {fit} vs {exact}");
            }
        }
    }

    /// erfc(x) = 2/sqrt(π) ∫_x^∞ e^(−t²) dt by a fine midpoint rule (Abramowitz and Stegun's
    /// 7.1.26 is too coarse for the tolerance here); the integrand is below e^-100 ten past x.
    fn erfc(x: f64) -> f64 {
        let n = 200_000;
        let top = x + 10.0;
        let h = (top - x) / n as f64;
        (0..n).map(|i| (-(x + (i as f64 + 0.5) * h).powi(2)).exp()).sum::<f64>() * h * 2.0 / std::f64::consts::PI.sqrt()
    }
}
