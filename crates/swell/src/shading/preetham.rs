//! The clear-sky model of Preetham, Shirley and Smits, "A Practical Analytic Model for Daylight"
//! (SIGGRAPH 1999): sky luminance and chromaticity from the Perez et al. (1993) all-weather
//! formula with the paper's turbidity-dependent coefficients (its Appendix A.2), and the sun's
//! transmittance through the atmosphere (its Appendix A.1, after Iqbal 1983).
//!
//! Everything here is the paper's closed form evaluated directly, in f64 where it is built once
//! (coefficients, zenith values); the renderer never calls it per pixel: `SkyRadiance`
//! (`shading/sky_radiance.rs`) tabulates it once per sky.
//!
//! Angles: θ is a view direction's angle from the zenith, γ its angle from the sun, θs the sun's
//! angle from the zenith, all radians.

use glam::{DVec3, Vec3};

use crate::math::{xyy_to_linear_srgb, RADIANCE_UNIT_NITS};

/// The renderer's radiance per kcd/m² of the model's luminance: 1000 / 20,000 cd/m².
pub const SKY_LUMINANCE_TO_RADIANCE: f32 = 1000.0 / RADIANCE_UNIT_NITS;

/// The luminous solar constant, klux: the sun's illuminance on a surface facing it outside the
/// atmosphere at the mean distance (IES Lighting Handbook, 10th ed.; the value of the IES
/// daylight formulas, `E = 127.5 exp(−c / sin α)`).
pub const SOLAR_ILLUMINANCE_KLUX: f32 = 127.5;

/// The five Perez coefficients A..E of one quantity (Y, x or y).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Perez {
    /// Darkening or brightening towards the horizon.
    pub a: f64,
    /// Gradient of that luminance near the horizon.
    pub b: f64,
    /// Strength of the circumsolar region.
    pub c: f64,
    /// Width of the circumsolar region.
    pub d: f64,
    /// Backscattered light.
    pub e: f64,
}

impl Perez {
    /// `F(θ, γ) = (1 + A e^(B / cos θ)) (1 + C e^(D γ) + E cos² γ)` (Perez et al. 1993, the
    /// paper's eq. 3), with `cos_theta` clamped away from 0 so that the horizon stays finite.
    pub fn f(&self, cos_theta: f64, gamma: f64) -> f64 {
        let cos_gamma = gamma.cos();
        (1.0 + self.a * (self.b / cos_theta.max(1e-3)).exp())
            * (1.0 + self.c * (self.d * gamma).exp() + self.e * cos_gamma * cos_gamma)
    }

    /// The paper's coefficients for luminance Y, and chromaticities x and y, at turbidity `t`
    /// (Appendix A.2).
    pub fn coefficients(t: f64) -> [Perez; 3] {
        let p = |a: f64, b: f64, c: f64, d: f64, e: f64| Perez { a, b, c, d, e };
        [
            p(
                0.1787 * t - 1.4630,
                -0.3554 * t + 0.4275,
                -0.0227 * t + 5.3251,
                0.1206 * t - 2.5771,
                -0.0670 * t + 0.3703,
            ),
            p(
                -0.0193 * t - 0.2592,
                -0.0665 * t + 0.0008,
                -0.0004 * t + 0.2125,
                -0.0641 * t - 0.8989,
                -0.0033 * t + 0.0452,
            ),
            p(
                -0.0167 * t - 0.2608,
                -0.0950 * t + 0.0092,
                -0.0079 * t + 0.2102,
                -0.0441 * t - 1.6537,
                -0.0109 * t + 0.0529,
            ),
        ]
    }
}

/// Zenith luminance in kcd/m² for turbidity `t` and sun zenith angle `theta_s` (the paper's
/// Appendix A.2): `Yz = (4.0453 T − 4.9710) tan χ − 0.2155 T + 2.4192`,
/// `χ = (4/9 − T/120)(π − 2 θs)`.
pub fn zenith_luminance(t: f64, theta_s: f64) -> f64 {
    let chi = (4.0 / 9.0 - t / 120.0) * (std::f64::consts::PI - 2.0 * theta_s);
    (4.0453 * t - 4.9710) * chi.tan() - 0.2155 * t + 2.4192
}

/// Zenith chromaticity (x, y) for turbidity `t` and sun zenith angle `theta_s` (Appendix A.2):
/// `[T² T 1] M [θs³ θs² θs 1]ᵀ` with the paper's matrices.
pub fn zenith_chromaticity(t: f64, theta_s: f64) -> (f64, f64) {
    const MX: [[f64; 4]; 3] = [
        [0.00166, -0.00375, 0.00209, 0.0],
        [-0.02903, 0.06377, -0.03202, 0.00394],
        [0.11693, -0.21196, 0.06052, 0.25886],
    ];
    const MY: [[f64; 4]; 3] = [
        [0.00275, -0.00610, 0.00317, 0.0],
        [-0.04214, 0.08970, -0.04153, 0.00516],
        [0.15346, -0.26756, 0.06670, 0.26688],
    ];
    let tv = [t * t, t, 1.0];
    let sv = [theta_s.powi(3), theta_s.powi(2), theta_s, 1.0];
    let eval =
        |m: &[[f64; 4]; 3]| -> f64 { (0..3).map(|i| tv[i] * (0..4).map(|j| m[i][j] * sv[j]).sum::<f64>()).sum() };
    (eval(&MX), eval(&MY))
}

/// A clear sky for one turbidity and sun position, ready to evaluate at any direction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PreethamSky {
    /// Perez coefficients for Y, x, y.
    perez: [Perez; 3],
    /// Zenith values (Y in kcd/m², x, y) divided by `F(0, θs)`, so a direction's value is
    /// `zenith_over_f0 F(θ, γ)` (the paper's eq. 4).
    zenith_over_f0: [f64; 3],
    /// Unit vector towards the sun (its elevation clamped to the horizon).
    to_sun: DVec3,
}

impl PreethamSky {
    /// The sky of turbidity `turbidity` (in [`TURBIDITY_RANGE`](crate::scene::TURBIDITY_RANGE)) with the sun along unit
    /// `to_sun`. A sun below the horizon is evaluated at the horizon (the model has no night;
    /// the caller fades it).
    pub fn new(turbidity: f32, to_sun: Vec3) -> Self {
        let t = f64::from(turbidity);
        let mut s = to_sun.as_dvec3().normalize_or(DVec3::Y);
        if s.y < 0.0 {
            let h = DVec3::new(s.x, 0.0, s.z);
            s = h.try_normalize().unwrap_or(DVec3::X);
        }
        let theta_s = s.y.clamp(-1.0, 1.0).acos();
        let perez = Perez::coefficients(t);
        let (xz, yz) = zenith_chromaticity(t, theta_s);
        let zenith = [zenith_luminance(t, theta_s).max(0.0), xz, yz];
        let mut zenith_over_f0 = [0.0; 3];
        for k in 0..3 {
            zenith_over_f0[k] = zenith[k] / perez[k].f(1.0, theta_s);
        }
        Self { perez, zenith_over_f0, to_sun: s }
    }

    /// Luminance (kcd/m²) and chromaticity (x, y) of the sky seen along unit `dir` (at or above
    /// the horizon; a direction below it is taken at the horizon).
    pub fn yxy(&self, dir: Vec3) -> (f64, f64, f64) {
        let d = dir.as_dvec3();
        let cos_theta = d.y.max(0.0);
        let gamma = d.dot(self.to_sun).clamp(-1.0, 1.0).acos();
        let v: [f64; 3] = std::array::from_fn(|k| self.zenith_over_f0[k] * self.perez[k].f(cos_theta, gamma));
        (v[0], v[1], v[2])
    }

    /// Linear sRGB radiance along unit `dir`, in kcd/m² (luminance units: times
    /// 0.05, 1000 / 20,000 cd/m², in the renderer's unit).
    pub fn rgb(&self, dir: Vec3) -> Vec3 {
        let (y, cx, cy) = self.yxy(dir);
        xyy_to_linear_srgb(cx as f32, cy as f32, y as f32)
    }

    /// Zenith luminance of this sky, kcd/m².
    pub fn zenith_luminance(&self) -> f64 {
        self.zenith_over_f0[0] * self.perez[0].f(1.0, self.to_sun.y.clamp(-1.0, 1.0).acos())
    }
}

/// Wavelengths (µm) taken for the red, green and blue channels of the sun's transmittance.
const RGB_WAVELENGTHS_UM: [f64; 3] = [0.680, 0.550, 0.440];

/// Fraction of sunlight per red, green, blue channel that reaches the ground through the
/// atmosphere of turbidity `turbidity` with the sun `elevation` radians above the horizon:
/// Rayleigh scattering `exp(−0.008735 λ^−4.08 m)` and aerosol (Ångström) scattering
/// `exp(−β λ^−α m)`, `α = 1.3`, `β = 0.04608 T − 0.04586`, over the relative optical air mass
/// `m = 1 / (cos θs + 0.15 (93.885 − θs°)^−1.253)` (Kasten 1966), as in the paper's Appendix A.1.
/// Ozone, mixed gases and water vapour, which the paper adds, absorb mostly outside the visible
/// peaks of the three channels and are left out. A sun below the horizon is taken at it.
pub fn sun_transmittance(turbidity: f32, elevation: f32) -> Vec3 {
    let theta_deg = (90.0 - f64::from(elevation).to_degrees()).clamp(0.0, 90.0);
    let m = 1.0 / (theta_deg.to_radians().cos() + 0.15 * (93.885 - theta_deg).powf(-1.253));
    let beta = 0.04608 * f64::from(turbidity) - 0.04586;
    let tau = |l: f64| ((-0.008735 * l.powf(-4.08) - beta * l.powf(-1.3)) * m).exp() as f32;
    Vec3::from_array(RGB_WAVELENGTHS_UM.map(tau))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The paper's zenith formulas evaluated independently, term by term, in f64.
    fn zenith_by_hand(t: f64, theta_s_deg: f64) -> (f64, f64, f64) {
        let ts = theta_s_deg.to_radians();
        let chi = (4.0 / 9.0 - t / 120.0) * (std::f64::consts::PI - 2.0 * ts);
        let y = (4.0453 * t - 4.9710) * chi.tan() - 0.2155 * t + 2.4192;
        let x = t * t * (0.00166 * ts.powi(3) - 0.00375 * ts * ts + 0.00209 * ts)
            + t * (-0.02903 * ts.powi(3) + 0.06377 * ts * ts - 0.03202 * ts + 0.00394)
            + (0.11693 * ts.powi(3) - 0.21196 * ts * ts + 0.06052 * ts + 0.25886);
        let yc = t * t * (0.00275 * ts.powi(3) - 0.00610 * ts * ts + 0.00317 * ts)
            + t * (-0.04214 * ts.powi(3) + 0.08970 * ts * ts - 0.04153 * ts + 0.00516)
            + (0.15346 * ts.powi(3) - 0.26756 * ts * ts + 0.06670 * ts + 0.26688);
        (y, x, yc)
    }

    #[test]
    fn zenith_values_follow_the_paper_s_formulas() {
        for t in [2.0, 3.0, 5.0, 10.0] {
            for theta_s_deg in [0.0, 30.0, 60.0, 80.0] {
                let (y, x, yc) = zenith_by_hand(t, theta_s_deg);
                let ts = f64::to_radians(theta_s_deg);
                assert!((zenith_luminance(t, ts) - y).abs() < 1e-9, "T {t}, θs {theta_s_deg}");
                let (cx, cy) = zenith_chromaticity(t, ts);
                assert!((cx - x).abs() < 1e-9 && (cy - yc).abs() < 1e-9);
                // A daylit zenith is bluish white: x and y below the equal-energy 1/3.
                assert!((0.2..0.33).contains(&cx) && (0.2..0.34).contains(&cy), "T {t} θs {theta_s_deg}: {cx} {cy}");
            }
        }
        // Spot values (kcd/m²) of Yz computed by hand from the formula, to 0.01: T = 2, θs = 30°:
        // χ = (4/9 − 1/60)(π − π/3) = 0.8959, tan χ = 1.2497, Yz = 3.1196 · 1.2497 + 1.9882.
        assert!((zenith_luminance(2.0, 30f64.to_radians()) - 5.887).abs() < 0.01);
        // A hazier sky has a brighter zenith for a high sun (the paper's Figure 5 trend).
        assert!(zenith_luminance(6.0, 0.5) > zenith_luminance(2.0, 0.5));
        // The zenith darkens as the sun sets.
        assert!(zenith_luminance(3.0, 1.4) < zenith_luminance(3.0, 0.5));
    }

    #[test]
    fn the_sky_is_brighter_near_the_sun_and_at_the_horizon_than_at_the_zenith_far_from_it() {
        let to_sun = Vec3::new(0.0, 0.5f32.sin(), -(0.5f32.cos()));
        let sky = PreethamSky::new(3.0, to_sun);
        let near_sun = sky.yxy(Vec3::new(0.0, 0.6f32.sin(), -(0.6f32.cos()))).0;
        let zenith = sky.yxy(Vec3::Y).0;
        let away = sky.yxy(Vec3::new(0.0, 0.6f32.sin(), 0.6f32.cos())).0;
        assert!(near_sun > 2.0 * zenith && near_sun > 2.0 * away, "{near_sun} {zenith} {away}");
        // The zenith of the model is its own zenith formula.
        assert!((zenith - zenith_luminance(3.0, std::f64::consts::FRAC_PI_2 - 0.5)).abs() < 1e-3);
        // Blue sky: blue above red at the zenith, away from the sun.
        let c = sky.rgb(Vec3::Y);
        assert!(c.z > c.x && c.min_element() >= 0.0, "{c}");
    }

    #[test]
    fn a_low_sun_is_warmer_and_dimmer_than_a_high_one() {
        for t in [2.0, 4.0, 8.0] {
            let high = sun_transmittance(t, 60f32.to_radians());
            let low = sun_transmittance(t, 5f32.to_radians());
            assert!(low.x / low.z > high.x / high.z, "T {t}: {low} vs {high}");
            assert!(low.max_element() < high.max_element());
            assert!(high.max_element() <= 1.0 && low.min_element() > 0.0);
            // Red is always transmitted best (Rayleigh's λ^−4).
            assert!(high.x > high.y && high.y > high.z);
        }
        // Haze dims the sun.
        assert!(sun_transmittance(8.0, 0.5).y < sun_transmittance(2.0, 0.5).y);
        // Kasten's air mass stays finite at the horizon (about 38).
        assert!(sun_transmittance(2.0, -0.1).is_finite());
    }
}
