//! The sky's parameters (`[sky]`): what the background shows and what water reflects, the sun
//! disc, the sun's direction and colour, and the haze of distance.
//!
//! **Sun angles** (one convention for the whole crate, +Y up, right-handed): the elevation is
//! degrees above the horizon; the azimuth is degrees clockwise from north seen from above, with
//! north = −Z and east = +X (so 90° is +X, 180° is +Z, 270° is −X). The unit vector towards
//! the sun is `(sin az cos el, sin el, −cos az cos el)` ([`Sky::to_sun`]).
//!
//! What the keys give (the sun disc, the sunlight's colour, the radiance along a direction) is
//! computed beside the shading that uses it, in `shading/sky_light.rs` and `shading/preetham.rs`.

use glam::Vec3;
use serde::{Deserialize, Serialize};

use super::SkyModel;
use crate::error::{check_finite_vec, check_non_negative, check_range, Error, Result};

/// The valid turbidity range of the Preetham model's fitted coefficients (the paper fits T in
/// [2, 10]; 1.7 is the clearest sky its figures show). Scenes are refused outside it.
pub const TURBIDITY_RANGE: (f32, f32) = (1.7, 10.0);

/// The sky: `[sky]`. Every key has a default; the default sky is the original gradient.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Sky {
    /// Which model computes the sky's radiance. Default `gradient`.
    pub model: SkyModel,
    /// Linear RGB radiance at the horizon, >= 0 (`gradient`), in the renderer's unit (20,000
    /// cd/m²). The default is the `preetham` sky's mean around the horizon with a 45° sun at
    /// turbidity 2.5.
    pub horizon: Vec3,
    /// Linear RGB radiance straight up, >= 0 (`gradient`), in the renderer's unit. The default is
    /// the `preetham` sky's zenith with a 45° sun at turbidity 2.5.
    pub zenith: Vec3,
    /// Linear RGB radiance seen below the horizon where nothing is drawn (the far ground), >= 0.
    pub ground: Vec3,
    /// Direction the sunlight travels (world, any non-zero length), as for a directional light;
    /// absent: the first directional `[[light]]`'s direction (no sun disc without one). Only with
    /// `gradient`: `preetham` takes the sun angles.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sun_direction: Option<Vec3>,
    /// Angular diameter of the drawn sun disc in degrees, in [0, 20]; 0 hides it. Default 1.5 (the
    /// real sun is 0.53°; a larger disc stays visible at a few hundred pixels). The disc's
    /// radiance is the sunlight's irradiance spread over it (E / Ω), so a larger disc is dimmer
    /// and the sunlight is the same.
    pub sun_size_deg: f32,
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
    /// Aerial perspective: surfaces `d` metres from the eye fade towards the sky's horizon colour
    /// in the view's direction by `1 − exp(−d / haze_distance)`; metres, in [0, 1e7]; 0 (the
    /// default) turns it off.
    pub haze_distance: f32,
    /// When true, the sun angles drive the first directional `[[light]]`: it becomes the sun,
    /// its direction the sunlight's and its colour multiplied by the sunlight the air lets
    /// through ([`Sky::sunlight`], in the renderer's unit: about 1.6 for a high sun, less and
    /// warmer for a low one), with either model; its `color` and `intensity` then scale that
    /// sun (1 = the model's). Without a directional light it changes nothing. Default false.
    pub sun_drives_light: bool,
}

impl Default for Sky {
    fn default() -> Self {
        Self {
            horizon: Vec3::new(0.612, 0.532, 0.602),
            zenith: Vec3::new(0.184, 0.298, 0.599),
            ground: Vec3::new(0.18, 0.20, 0.22),
            sun_direction: None,
            sun_size_deg: 1.5,
            model: SkyModel::Gradient,
            sun_elevation_deg: 45.0,
            sun_azimuth_deg: 135.0,
            turbidity: 2.5,
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
        check_range(&format!("{key}.sun_elevation_deg"), self.sun_elevation_deg, -10.0, 90.0)?;
        // [0, 360): 360 itself is refused so that every direction has one azimuth.
        if !(self.sun_azimuth_deg >= 0.0 && self.sun_azimuth_deg < 360.0) {
            return Err(Error::out_of_range(format!("{key}.sun_azimuth_deg"), self.sun_azimuth_deg, "[0, 360)"));
        }
        check_range(&format!("{key}.turbidity"), self.turbidity, TURBIDITY_RANGE.0, TURBIDITY_RANGE.1)?;
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
            ("haze_distance = -5.0", "t: sky.haze_distance = -5 is outside [0, 10000000]"),
        ] {
            let e = scene_with_sky(keys).err().unwrap_or_else(|| panic!("{keys} accepted"));
            assert_eq!(e.to_string(), message);
        }
        // The free scales of before one radiometric scale are gone, and said to be unknown.
        for old in ["luminance_scale = 0.05", "sun_intensity = 20.0"] {
            let e = scene_with_sky(old).err().unwrap().to_string();
            assert!(e.contains("unknown field") && e.contains(old.split(' ').next().unwrap()), "{e}");
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
}
