//! The sky's light, from its parameters ([`Sky`], `[sky]`): the sun disc and its radial profile,
//! the sunlight's colour through the air and the lights the sun angles drive, and the sky's
//! radiance evaluated directly (the gradient, or Preetham et al.'s model). Renderers look the sky
//! up through [`SkyRadiance`](super::SkyRadiance), which tabulates the latter once.

use glam::Vec3;

use super::preetham::{sun_transmittance, SKY_LUMINANCE_TO_RADIANCE, SOLAR_ILLUMINANCE_KLUX};
use crate::math::{Lanes, Vec3Lanes, RADIANCE_UNIT_NITS};
use crate::scene::{Light, Sky, SkyModel};

/// The sun as drawn in the sky: a disc with a soft edge.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SunDisc {
    /// Unit vector towards the sun.
    pub to_sun: Vec3,
    /// Cosine of the disc's angular radius.
    pub cos_radius: f32,
    /// Linear RGB radiance at the centre of the disc.
    pub radiance: Vec3,
    /// How the disc's edge falls off.
    pub profile: SunProfile,
}

/// The radial profile of a [`SunDisc`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SunProfile {
    /// Full radiance inside, a smoothstep over a rim three radii wide (the `gradient` sky's).
    Smoothstep,
    /// The photosphere's linear limb darkening `I(μ) = I(1) (1 − u (1 − μ))`, u = 0.6
    /// (the classic grey-atmosphere value, Eddington's approximation; the measured visible
    /// coefficients are 0.5 to 0.8, Neckel and Labs 1994), and outside the disc an aureole
    /// falling as the inverse square of the angle from the sun's centre (forward scattering by
    /// aerosols), cut to 0 twenty radii out.
    LimbDarkened,
}

/// Limb-darkening coefficient u of [`SunProfile::LimbDarkened`].
const LIMB_DARKENING: f32 = 0.6;
/// Aureole radiance just outside the limb, relative to the disc's centre: 0.2 %, the upper end of
/// a clear sky's circumsolar jump at the limb (Buie, Monger and Dey, "Sunshape distributions for
/// terrestrial solar simulations", Solar Energy 74, 2003: 1e-4 to 1e-2 of the centre's radiance).
const GLOW: f32 = 2e-3;
/// (angle / radius)² beyond which the aureole is 0: twenty radii.
const GLOW_END: f32 = 400.0;
/// Solid angle of a [`SunProfile::LimbDarkened`] disc per unit of its centre radiance, in units of
/// the disc's solid angle: the darkened disc `∫0^1 1 − u (1 − sqrt(1 − x)) dx = 1 − u / 3`, less
/// the outer 4 % of x where the limb blends into the aureole (half of it, at the limb's 0.47),
/// plus the aureole `GLOW ∫1^400 (1/x − 1/400) dx` (x = (angle / radius)², so dΩ ∝ dx).
const LIMB_DARKENED_SOLID_ANGLE: f32 =
    1.0 - LIMB_DARKENING / 3.0 - 0.02 * (0.47 - GLOW) + GLOW * (5.991_465 - (GLOW_END - 1.0) / GLOW_END);
/// The same for [`SunProfile::Smoothstep`]: full out to the radius, then a smoothstep in the
/// cosine over three times the disc's `1 − cos r`, which holds half its weight: 1 + 1.5.
const SMOOTHSTEP_SOLID_ANGLE: f32 = 2.5;

impl SunDisc {
    /// Radiance of the disc seen along unit direction `dir`: full inside the disc, falling
    /// smoothly to 0 over a rim as wide as the radius (a crude limb and glare), 0 elsewhere.
    pub fn radiance(&self, dir: Vec3) -> Vec3 {
        let c = dir.dot(self.to_sun);
        if self.profile == SunProfile::LimbDarkened {
            return self.limb_darkened(c);
        }
        let rim = 1.0 - self.cos_radius;
        let edge = (c - (self.cos_radius - rim * 3.0)) / (rim * 3.0);
        if edge <= 0.0 {
            return Vec3::ZERO;
        }
        let k = edge.min(1.0);
        self.radiance * (k * k * (3.0 - 2.0 * k))
    }

    /// [`SunProfile::LimbDarkened`] at `c` = cos(angle from the centre). x = (1 − c) / (1 − cos r)
    /// is (angle / radius)² to within 0.01 % for small discs, so no acos per pixel.
    fn limb_darkened(&self, c: f32) -> Vec3 {
        let x = (1.0 - c) / (1.0 - self.cos_radius).max(1e-12);
        if x >= GLOW_END {
            return Vec3::ZERO;
        }
        let glow = GLOW * (1.0 / x.max(1.0) - 1.0 / GLOW_END);
        if x >= 1.0 {
            return self.radiance * glow;
        }
        // μ = cos of the angle at the photosphere = sqrt(1 − (angle / radius)²).
        let mu = (1.0 - x).sqrt();
        let disc = 1.0 - LIMB_DARKENING * (1.0 - mu);
        // The outer 2 % of the radius blends into the aureole, so the edge does not alias.
        let edge = ((1.0 - x) / 0.04).min(1.0);
        self.radiance * (glow + (disc - glow) * edge)
    }
}
impl SunDisc {
    /// [`Self::radiance`] along many unit directions.
    #[inline(always)]
    pub fn radiance_lanes(&self, dir: Vec3Lanes) -> Vec3Lanes {
        if self.profile == SunProfile::LimbDarkened {
            // The Preetham sun's limb and glow, lane by lane where any lane is near enough to the
            // sun to see its glow; most batches look elsewhere, and get zero from one vector test
            // (the same `x` as `limb_darkened` computes, so the same answer).
            let c = dir.dot1(self.to_sun);
            let x = (Lanes::splat(1.0) - c) / (1.0 - self.cos_radius).max(1e-12);
            if !x.lt(GLOW_END).any() && !x.map(|v| if v.is_nan() { 1.0 } else { 0.0 }).gt(0.0).any() {
                return Vec3Lanes::splat(Vec3::ZERO);
            }
            return Vec3Lanes::from_fn(|i| self.limb_darkened(c.0[i]));
        }
        let c = dir.dot1(self.to_sun);
        let rim = 1.0 - self.cos_radius;
        let edge = (c - (self.cos_radius - rim * 3.0)) / (rim * 3.0);
        let k = edge.min(1.0);
        let weight = edge.le(0.0).select(0.0, k * k * (3.0 - 2.0 * k));
        Vec3Lanes::splat(self.radiance).scale(weight)
    }
}

impl Sky {
    /// The sunlight at the ground as a directional light's colour × intensity, in the renderer's
    /// unit (its irradiance on a surface facing the sun is π times this, 20,000 cd/m² each):
    /// the luminous solar constant, 127.5 klux (IES Lighting Handbook; Darula et al. 2005 give
    /// 133.8), through Preetham et al.'s transmittance ([`sun_transmittance`]) per channel at
    /// `sun_elevation_deg` and `turbidity`, faded to 0 as the disc sinks below the horizon (over
    /// ±0.5°). About 1.6 (100 klux) overhead at turbidity 2.5; a low sun dim and orange.
    pub fn sunlight(&self) -> Vec3 {
        let el = self.sun_elevation_deg;
        let t = sun_transmittance(self.turbidity, el.to_radians());
        let k = ((el + 0.5) / 1.0).clamp(0.0, 1.0);
        t * (k * k * (3.0 - 2.0 * k)) * (SOLAR_ILLUMINANCE_KLUX * 1000.0 / (std::f32::consts::PI * RADIANCE_UNIT_NITS))
    }

    /// `lights` as this sky drives them, into `out` (cleared first): with `sun_drives_light`,
    /// the first directional light shines from the sun angles with its colour times
    /// [`Sky::sunlight`]; otherwise a copy.
    pub fn drive_lights(&self, lights: &[Light], out: &mut Vec<Light>) {
        out.clear();
        out.extend_from_slice(lights);
        if !self.sun_drives_light {
            return;
        }
        if let Some(Light::Directional { direction, color, .. }) =
            out.iter_mut().find(|l| matches!(l, Light::Directional { .. }))
        {
            *direction = -self.to_sun();
            *color *= self.sunlight();
        }
    }

    /// The sun disc, or `None` when it has no direction or no size. Its radiance is the
    /// sunlight's irradiance spread over the disc's profile, so that the disc seen in the sky (and
    /// in a mirror) carries exactly the light that shades the scene: E / Ω with E = π × the light.
    /// With `gradient`, it lies along `sun_direction` or the first directional light, and that
    /// light (colour × intensity; white 1 without one) is the sunlight; with `preetham`, along the
    /// sun angles, the sunlight is [`Sky::sunlight`], limb-darkened, hidden once it has set.
    /// `lights` are the lights as [`Sky::drive_lights`] gives them.
    pub fn sun(&self, lights: &[Light]) -> Option<SunDisc> {
        let cos_radius = (0.5 * self.sun_size_deg).to_radians().cos();
        // The disc's own solid angle, 2π (1 − cos r), in f64: 1 − cos r is ~1e-5.
        let disc = 2.0 * std::f64::consts::PI * (1.0 - (0.5 * f64::from(self.sun_size_deg)).to_radians().cos());
        let over_disc = |sunlight: Vec3, profile_solid_angle: f32| {
            sunlight * (std::f64::consts::PI / (disc * f64::from(profile_solid_angle))) as f32
        };
        if self.model == SkyModel::Preetham {
            if self.sun_size_deg <= 0.0 || self.sun_elevation_deg < -self.sun_size_deg {
                return None;
            }
            return Some(SunDisc {
                to_sun: self.to_sun(),
                cos_radius,
                radiance: over_disc(self.sunlight(), LIMB_DARKENED_SOLID_ANGLE),
                profile: SunProfile::LimbDarkened,
            });
        }
        let first = lights.iter().find_map(|l| match *l {
            Light::Directional { direction, color, intensity } => Some((direction, color * intensity)),
            Light::Point { .. } => None,
        });
        let direction = self.sun_direction.or(first.map(|f| f.0))?;
        if self.sun_size_deg <= 0.0 {
            return None;
        }
        let light = first.map_or(Vec3::ONE, |f| f.1);
        Some(SunDisc {
            to_sun: -direction.normalize(),
            cos_radius,
            radiance: over_disc(light, SMOOTHSTEP_SOLID_ANGLE),
            profile: SunProfile::Smoothstep,
        })
    }

    /// The gradient sky ([`Self::gradient`]) along many unit directions: the same formula lane
    /// by lane.
    #[inline(always)]
    pub(crate) fn gradient_lanes(&self, dir: Vec3Lanes) -> Vec3Lanes {
        let up = Vec3Lanes::splat(self.horizon).lerp(Vec3Lanes::splat(self.zenith), dir.y.max(0.0).sqrt());
        let down = Vec3Lanes::splat(self.horizon).lerp(Vec3Lanes::splat(self.ground), (-dir.y * 8.0).min(1.0));
        dir.y.lt(0.0).select3(down, up)
    }

    /// Radiance seen along the unit world direction `dir`, without the sun disc. The `gradient`
    /// sky is cheap; the `preetham` sky is the model evaluated exactly, which costs a dozen
    /// transcendental functions: renderers look both up through
    /// [`SkyRadiance`](super::SkyRadiance), which tabulates the latter once.
    pub fn radiance(&self, dir: Vec3) -> Vec3 {
        match self.model {
            SkyModel::Gradient => self.gradient(dir),
            SkyModel::Preetham => {
                let model = super::preetham::PreethamSky::new(self.turbidity, self.to_sun());
                self.preetham(&model, dir)
            }
        }
    }

    /// The Preetham sky `model` (built from this sky's keys) along unit `dir`, in the renderer's
    /// radiance (kcd/m² over the 20 kcd/m² unit), faded for a sun below the horizon; below the
    /// horizon the horizon's colour blends into `ground` as in the gradient sky.
    pub(crate) fn preetham(&self, model: &super::preetham::PreethamSky, dir: Vec3) -> Vec3 {
        let scale = SKY_LUMINANCE_TO_RADIANCE * self.night_fade();
        if dir.y >= 0.0 {
            return model.rgb(dir) * scale;
        }
        let h = Vec3::new(dir.x, 0.0, dir.z).normalize_or(Vec3::X);
        (model.rgb(h) * scale).lerp(self.ground * self.night_fade(), (-dir.y * 8.0).min(1.0))
    }

    /// 1 while the sun is up, falling to 0 as it sinks to −10°: `(1 + el / 10)²`.
    pub(crate) fn night_fade(&self) -> f32 {
        let k = (1.0 + self.sun_elevation_deg / 10.0).clamp(0.0, 1.0);
        k * k
    }

    /// The gradient sky along unit `dir`.
    #[inline]
    pub(crate) fn gradient(&self, dir: Vec3) -> Vec3 {
        if dir.y >= 0.0 {
            // sqrt keeps the bright horizon band narrow, as in a clear sky.
            self.horizon.lerp(self.zenith, dir.y.sqrt())
        } else {
            self.horizon.lerp(self.ground, (-dir.y * 8.0).min(1.0))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_sun_drives_the_first_directional_light_warmer_when_low() {
        let lights = [
            Light::Point { position: Vec3::Y, color: Vec3::ONE, intensity: 1.0 },
            Light::Directional { direction: Vec3::new(1.0, -1.0, 0.0), color: Vec3::ONE, intensity: 2.0 },
        ];
        let sky = |el: f32| Sky {
            model: SkyModel::Preetham,
            sun_elevation_deg: el,
            sun_azimuth_deg: 200.0,
            sun_drives_light: true,
            ..Sky::default()
        };
        let mut out = Vec::new();
        let color_at = |el: f32, out: &mut Vec<Light>| {
            sky(el).drive_lights(&lights, out);
            assert_eq!(out[0], lights[0], "point lights are left alone");
            match out[1] {
                Light::Directional { direction, color, intensity } => {
                    assert!((direction + sky(el).to_sun()).length() < 1e-6);
                    assert_eq!(intensity, 2.0);
                    color
                }
                _ => unreachable!(),
            }
        };
        let (high, low) = (color_at(70.0, &mut out), color_at(4.0, &mut out));
        assert!(low.x / low.z > 1.5 * (high.x / high.z), "low {low} vs high {high}");
        assert!(high.min_element() > 0.7 * high.max_element(), "a high sun is nearly white: {high}");
        // And as bright as sunlight: 127.5 klux through the air, over π × 20,000 cd/m².
        let lux = 0.2126 * high.x + 0.7152 * high.y + 0.0722 * high.z;
        assert!((1.4..2.0).contains(&lux), "{lux}");
        assert_eq!(color_at(-3.0, &mut out), Vec3::ZERO, "no sunlight after sunset");
        // The disc follows: warm when low, gone when set.
        let disc = sky(4.0).sun(&[]).unwrap();
        assert!(disc.radiance.x > disc.radiance.z);
        assert!(sky(-3.0).sun(&[]).is_none());
        // Without the key the lights are a copy.
        Sky::default().drive_lights(&lights, &mut out);
        assert_eq!(out, lights);
    }

    #[test]
    fn the_preetham_sun_disc_is_limb_darkened_and_glows() {
        let sky = Sky { model: SkyModel::Preetham, sun_elevation_deg: 40.0, ..Sky::default() };
        let disc = sky.sun(&[]).unwrap();
        let r = (0.5 * sky.sun_size_deg).to_radians();
        let at = |angle: f32| {
            // A direction `angle` radians from the sun's centre.
            let side = disc.to_sun.cross(Vec3::Y).normalize();
            let d = disc.to_sun * angle.cos() + side * angle.sin();
            disc.radiance(d).y / disc.radiance.y
        };
        assert!((at(0.0) - 1.0).abs() < 1e-3);
        // Half way out: μ = sqrt(0.75), I = 1 − 0.6 (1 − μ) = 0.92.
        assert!((at(0.5 * r) - 0.92).abs() < 0.01, "{}", at(0.5 * r));
        assert!(at(0.9 * r) < at(0.5 * r));
        // The aureole: present just outside, falling with angle, gone twenty radii out.
        assert!(at(1.5 * r) > 1e-4 && at(3.0 * r) < at(1.5 * r));
        assert_eq!(at(25.0 * r), 0.0);
    }

    /// The disc's radiance integrated over the sky is the sunlight's irradiance, π × the light,
    /// with both profiles, whatever the disc's size.
    #[test]
    fn the_disc_carries_the_sunlight_s_irradiance() {
        let light = [Light::Directional { direction: Vec3::new(0.3, -1.0, 0.2), color: Vec3::ONE, intensity: 1.5 }];
        for size in [0.53f32, 1.5, 4.0] {
            for model in [SkyModel::Gradient, SkyModel::Preetham] {
                let sky = Sky { model, sun_size_deg: size, sun_elevation_deg: 40.0, ..Sky::default() };
                let disc = sky.sun(&light).unwrap();
                let want = if model == SkyModel::Preetham { sky.sunlight().y } else { 1.5 } * std::f32::consts::PI;
                // Rings of equal width in the angle from the centre out to 25 radii, in f64.
                let r = f64::from(0.5 * size).to_radians();
                let side = disc.to_sun.cross(Vec3::Y).normalize();
                let n = 200_000;
                let step = 25.0 * r / f64::from(n);
                let e: f64 = (0..n)
                    .map(|i| {
                        let a = (f64::from(i) + 0.5) * step;
                        let d = disc.to_sun * a.cos() as f32 + side * a.sin() as f32;
                        f64::from(disc.radiance(d).y) * 2.0 * std::f64::consts::PI * a.sin() * step
                    })
                    .sum();
                assert!((e as f32 / want - 1.0).abs() < 0.02, "{model:?} {size}°: {e} vs {want}");
            }
        }
    }

    /// The gradient sky's defaults are the physical sky's with a 45° sun at turbidity 2.5, so a
    /// scene that switches models keeps its brightness: the zenith, and the mean around the horizon.
    #[test]
    fn the_gradient_defaults_are_the_physical_sky_at_45_degrees() {
        let gradient = Sky::default();
        let physical = Sky { model: SkyModel::Preetham, sun_elevation_deg: 45.0, turbidity: 2.5, ..gradient };
        let horizon = (0..360).fold(Vec3::ZERO, |h, i| {
            let a = (i as f32).to_radians();
            h + physical.radiance(Vec3::new(a.cos(), 0.0, a.sin())) / 360.0
        });
        for (got, want) in [(gradient.zenith, physical.radiance(Vec3::Y)), (gradient.horizon, horizon)] {
            assert!(((got - want) / want).abs().max_element() < 0.01, "{got} vs {want}");
        }
    }
}
