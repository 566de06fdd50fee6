//! The sky's parameters (`[sky]`): what the background shows and what water reflects, the sun
//! disc, the sun's direction and colour, and the haze of distance.
//!
//! **Sun angles** (one convention for the whole crate, +Y up, right-handed): the elevation is
//! degrees above the horizon; the azimuth is degrees clockwise from north seen from above, with
//! north = −Z and east = +X (so 90° is +X, 180° is +Z, 270° is −X). The unit vector towards
//! the sun is `(sin az cos el, sin el, −cos az cos el)` ([`Sky::to_sun`]).

use glam::Vec3;
use serde::{Deserialize, Serialize};

use super::preetham::{sun_transmittance, TURBIDITY_RANGE};
use super::SkyModel;
use crate::error::{check_finite_vec, check_non_negative, check_range, Error, Result};
use crate::math::{Lanes, Vec3Lanes};
use crate::scene::Light;

/// The sky: `[sky]`. Every key has a default; the default sky is the original gradient.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Sky {
    /// Which model computes the sky's radiance. Default `gradient`.
    pub model: SkyModel,
    /// Linear RGB radiance at the horizon, >= 0 (`gradient`).
    pub horizon: Vec3,
    /// Linear RGB radiance straight up, >= 0 (`gradient`).
    pub zenith: Vec3,
    /// Linear RGB radiance seen below the horizon where nothing is drawn (the far ground), >= 0.
    pub ground: Vec3,
    /// Direction the sunlight travels (world, any non-zero length), as for a directional light;
    /// absent: the first directional `[[light]]`'s direction (no sun disc without one). Only with
    /// `gradient`: `preetham` takes the sun angles.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sun_direction: Option<Vec3>,
    /// Angular diameter of the drawn sun disc in degrees, in [0, 20]; 0 hides it. Default 1.5 (the
    /// real sun is 0.53°; a larger disc stays visible at a few hundred pixels).
    pub sun_size_deg: f32,
    /// Radiance of the disc relative to white (linear), >= 0. Default 20, so that its reflection
    /// stays bright after Fresnel's 2 % at normal incidence.
    pub sun_intensity: f32,
    /// Sun elevation above the horizon, degrees, in [-10, 90] (`preetham`, and the light when
    /// `sun_drives_light`). Default 45. Below 0 the sun has set: no disc, no sunlight, and the
    /// sky fades to dark at −10 (the model has no twilight of its own).
    pub sun_elevation_deg: f32,
    /// Sun azimuth, degrees clockwise from north (−Z) seen from above, in [0, 360) (see the
    /// [module documentation](self)). Default 135 (south-east: behind and to the right of a
    /// camera looking north along −Z).
    pub sun_azimuth_deg: f32,
    /// Atmospheric turbidity T (`preetham`): 2 a very clear sky, 3 clear, 6 hazy, 10 thin fog; in
    /// [1.7, 10], the range of the model's fit. Default 2.5.
    pub turbidity: f32,
    /// Renderer radiance per kcd/m² of sky luminance (`preetham`), in (0, 10]. Default 0.05:
    /// a 45° sun at T = 2.5 gives a zenith of about 6 kcd/m², so 0.3, and a horizon of about
    /// 0.5 to 0.8, the range of the gradient sky; a white Lambert surface under a light of
    /// intensity 1 is 1. Raise it for a dusk that reads as bright as day (a camera's exposure).
    pub luminance_scale: f32,
    /// Aerial perspective: surfaces `d` metres from the eye fade towards the sky's horizon colour
    /// in the view's direction by `1 − exp(−d / haze_distance)`; metres, in [0, 1e7]; 0 (the
    /// default) turns it off.
    pub haze_distance: f32,
    /// When true, the sun angles drive the first directional `[[light]]`: its direction becomes
    /// the sunlight's and its colour is multiplied by the sun's transmittance through the air
    /// relative to an overhead sun ([`Sky::sun_color`]: a low sun is dimmer and warmer), with
    /// either model. Without a directional light it changes nothing. Default false.
    pub sun_drives_light: bool,
}

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
/// Aureole radiance just outside the limb, relative to the disc's centre.
const GLOW: f32 = 0.08;
/// (angle / radius)² beyond which the aureole is 0: twenty radii.
const GLOW_END: f32 = 400.0;

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

impl Default for Sky {
    fn default() -> Self {
        Self {
            horizon: Vec3::new(0.62, 0.72, 0.82),
            zenith: Vec3::new(0.12, 0.28, 0.62),
            ground: Vec3::new(0.18, 0.20, 0.22),
            sun_direction: None,
            sun_size_deg: 1.5,
            sun_intensity: 20.0,
            model: SkyModel::Gradient,
            sun_elevation_deg: 45.0,
            sun_azimuth_deg: 135.0,
            turbidity: 2.5,
            luminance_scale: 0.05,
            haze_distance: 0.0,
            sun_drives_light: false,
        }
    }
}

impl Sky {
    /// Checks every key, naming it under `key` (normally `sky`) with its value and range.
    pub fn validate(&self, key: &str) -> Result<()> {
        for (name, c) in [("horizon", self.horizon), ("zenith", self.zenith), ("ground", self.ground)] {
            for (i, v) in c.to_array().into_iter().enumerate() {
                check_non_negative(&format!("{key}.{name}[{i}]"), v)?;
            }
        }
        if let Some(d) = self.sun_direction {
            check_finite_vec(&format!("{key}.sun_direction"), &d.to_array())?;
            if d.length() < 1e-6 {
                return Err(Error::invalid(format!("{key}.sun_direction"), "must be non-zero"));
            }
        }
        check_range(&format!("{key}.sun_size_deg"), self.sun_size_deg, 0.0, 20.0)?;
        check_non_negative(&format!("{key}.sun_intensity"), self.sun_intensity)?;
        check_range(&format!("{key}.sun_elevation_deg"), self.sun_elevation_deg, -10.0, 90.0)?;
        // [0, 360): 360 itself is refused so that every direction has one azimuth.
        if !(self.sun_azimuth_deg >= 0.0 && self.sun_azimuth_deg < 360.0) {
            return Err(Error::out_of_range(format!("{key}.sun_azimuth_deg"), self.sun_azimuth_deg, "[0, 360)"));
        }
        check_range(&format!("{key}.turbidity"), self.turbidity, TURBIDITY_RANGE.0, TURBIDITY_RANGE.1)?;
        if !(self.luminance_scale > 0.0 && self.luminance_scale <= 10.0) {
            return Err(Error::out_of_range(format!("{key}.luminance_scale"), self.luminance_scale, "(0, 10]"));
        }
        check_range(&format!("{key}.haze_distance"), self.haze_distance, 0.0, 1e7)?;
        if self.model == SkyModel::Preetham && self.sun_direction.is_some() {
            return Err(Error::invalid(
                format!("{key}.sun_direction"),
                "is not used with model = \"preetham\"; set sun_elevation_deg and sun_azimuth_deg",
            ));
        }
        Ok(())
    }

    /// Unit vector towards the sun of `sun_elevation_deg` and `sun_azimuth_deg` (the
    /// [module documentation](self) gives the convention).
    pub fn to_sun(&self) -> Vec3 {
        let (se, ce) = self.sun_elevation_deg.to_radians().sin_cos();
        let (sa, ca) = self.sun_azimuth_deg.to_radians().sin_cos();
        Vec3::new(sa * ce, se, -ca * ce)
    }

    /// The sunlight's colour relative to an overhead sun: Preetham et al.'s transmittance
    /// ([`sun_transmittance`]) at `sun_elevation_deg` divided by that at 90°, per channel, so a
    /// high sun is nearly white and a low one dim and orange; faded to 0 as the disc sinks below
    /// the horizon (over ±0.5°).
    pub fn sun_color(&self) -> Vec3 {
        let el = self.sun_elevation_deg;
        let t = sun_transmittance(self.turbidity, el.to_radians())
            / sun_transmittance(self.turbidity, std::f32::consts::FRAC_PI_2);
        let k = ((el + 0.5) / 1.0).clamp(0.0, 1.0);
        t * (k * k * (3.0 - 2.0 * k))
    }

    /// `lights` as this sky drives them, into `out` (cleared first): with `sun_drives_light`,
    /// the first directional light shines from the sun angles with its colour times
    /// [`Sky::sun_color`]; otherwise a copy.
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
            *color *= self.sun_color();
        }
    }

    /// The sun disc, or `None` when it has no direction or no size. With `gradient`, it lies along
    /// `sun_direction` or the first directional light, lit by that light's colour (white without
    /// one); with `preetham`, along the sun angles, coloured by [`Sky::sun_color`] and
    /// limb-darkened, hidden once it has set.
    pub fn sun(&self, lights: &[Light]) -> Option<SunDisc> {
        if self.model == SkyModel::Preetham {
            if self.sun_size_deg <= 0.0 || self.sun_intensity <= 0.0 || self.sun_elevation_deg < -self.sun_size_deg {
                return None;
            }
            return Some(SunDisc {
                to_sun: self.to_sun(),
                cos_radius: (0.5 * self.sun_size_deg).to_radians().cos(),
                radiance: self.sun_color() * self.sun_intensity,
                profile: SunProfile::LimbDarkened,
            });
        }
        let first = lights.iter().find_map(|l| match *l {
            Light::Directional { direction, color, .. } => Some((direction, color)),
            Light::Point { .. } => None,
        });
        let direction = self.sun_direction.or(first.map(|f| f.0))?;
        if self.sun_size_deg <= 0.0 || self.sun_intensity <= 0.0 {
            return None;
        }
        let color = first.map_or(Vec3::ONE, |f| f.1);
        Some(SunDisc {
            to_sun: -direction.normalize(),
            cos_radius: (0.5 * self.sun_size_deg).to_radians().cos(),
            radiance: color * self.sun_intensity,
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
    /// radiance: luminance times `luminance_scale`, faded for a sun below the horizon; below the
    /// horizon the horizon's colour blends into `ground` as in the gradient sky.
    pub(crate) fn preetham(&self, model: &super::preetham::PreethamSky, dir: Vec3) -> Vec3 {
        let scale = self.luminance_scale * self.night_fade();
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
    use crate::scene::Scene;

    fn scene_with_sky(keys: &str) -> crate::Result<Scene> {
        let text = format!(
            "version = 1\n[camera]\neye = [0.0, 5.0, 9.0]\ntarget = [0.0, 0.0, 0.0]\n\
             [[light]]\ntype = 'directional'\ndirection = [0.0, -1.0, 0.0]\n[sky]\n{keys}\n"
        );
        Scene::from_toml(&text, "t")
    }

    #[test]
    fn bad_sky_keys_are_refused_naming_key_value_and_range() {
        for (keys, message) in [
            ("sun_elevation_deg = 95.0", "t: sky.sun_elevation_deg = 95 is outside [-10, 90]"),
            ("sun_elevation_deg = -11.0", "t: sky.sun_elevation_deg = -11 is outside [-10, 90]"),
            ("sun_azimuth_deg = 360.0", "t: sky.sun_azimuth_deg = 360 is outside [0, 360)"),
            ("sun_azimuth_deg = -1.0", "t: sky.sun_azimuth_deg = -1 is outside [0, 360)"),
            ("turbidity = 1.5", "t: sky.turbidity = 1.5 is outside [1.7, 10]"),
            ("turbidity = 12.0", "t: sky.turbidity = 12 is outside [1.7, 10]"),
            ("luminance_scale = 0.0", "t: sky.luminance_scale = 0 is outside (0, 10]"),
            ("haze_distance = -5.0", "t: sky.haze_distance = -5 is outside [0, 10000000]"),
        ] {
            let e = scene_with_sky(keys).err().unwrap_or_else(|| panic!("{keys} accepted"));
            assert_eq!(e.to_string(), message);
        }
        let e = scene_with_sky("model = 'preetham'\nsun_direction = [0.0, -1.0, 0.0]").err().unwrap();
        assert!(e.to_string().starts_with("t: sky.sun_direction"), "{e}");
        let e = scene_with_sky("model = 'bruneton'").err().unwrap().to_string();
        assert!(e.starts_with("t: sky.model") && e.contains("bruneton") && e.contains("preetham"), "{e}");
        // The new keys round-trip.
        let s = scene_with_sky("model = 'preetham'\nsun_elevation_deg = 7.5\nhaze_distance = 300.0").unwrap();
        assert_eq!(Scene::from_toml(&s.to_toml(), "again").unwrap(), s);
    }

    #[test]
    fn the_sun_angles_follow_the_stated_convention() {
        let at = |el: f32, az: f32| Sky { sun_elevation_deg: el, sun_azimuth_deg: az, ..Sky::default() }.to_sun();
        let close = |a: Vec3, b: Vec3| (a - b).length() < 1e-6;
        assert!(close(at(0.0, 0.0), -Vec3::Z), "north is -Z");
        assert!(close(at(0.0, 90.0), Vec3::X), "east is +X");
        assert!(close(at(0.0, 180.0), Vec3::Z));
        assert!(close(at(0.0, 270.0), -Vec3::X));
        assert!(close(at(90.0, 123.0), Vec3::Y));
        assert!((at(30.0, 45.0).y - 0.5).abs() < 1e-6);
    }

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
        assert!(high.min_element() > 0.85, "a high sun is nearly white: {high}");
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
        assert!(at(1.5 * r) > 0.01 && at(3.0 * r) < at(1.5 * r));
        assert_eq!(at(25.0 * r), 0.0);
    }
}
