//! One radiometric scale from the sky to the screen (issue 32, item 1): the physical sky's
//! radiance and the sun's irradiance as the renderer draws them, in its unit of 20,000 cd/m²,
//! against the published models at three sun elevations, and the display encoding.
//!
//! - **The sky**: the framebuffer's linear pixel (what `swell render --out f.exr` writes) along
//!   known directions against Preetham, Shirley and Smits (1999): the zenith luminance of their
//!   Appendix A.2 times the Perez et al. (1993) distribution with their coefficients, evaluated
//!   here independently in f64. Tolerance 3 % of the luminance (the renderer tabulates the sky).
//! - **The sun**: the directional light the sun drives, as an illuminance on a surface facing it
//!   (π × its luminance × 20,000 cd/m²), against the IES clear-sky direct normal illuminance
//!   `E = 127.5 exp(−0.21 / sin α)` klux (IES Lighting Handbook; the extinction coefficient 0.21
//!   of a clear sky), within 15 %: Preetham's transmittance has turbidity as its parameter, the
//!   IES formula one clear sky, and at turbidity 2.5 they agree to a few per cent.
//! - **The disc**: the sun disc drawn in the sky carries the sunlight's irradiance (its radiance
//!   summed over the sky's pixels times their solid angle equals the light's π × colour).

use glam::Vec3;
use swell::math::RADIANCE_UNIT_NITS;
use swell::render::Renderer;
use swell::scene::{Light, Scene};
use swell::world::World;

const TURBIDITY: f64 = 2.5;
const ELEVATIONS_DEG: [f64; 3] = [10.0, 35.0, 60.0];

/// Perez et al.'s F(θ, γ) for luminance with Preetham's coefficients at turbidity `t`.
fn perez_y(t: f64, cos_theta: f64, gamma: f64) -> f64 {
    let (a, b, c, d, e) =
        (0.1787 * t - 1.4630, -0.3554 * t + 0.4275, -0.0227 * t + 5.3251, 0.1206 * t - 2.5771, -0.0670 * t + 0.3703);
    (1.0 + a * (b / cos_theta.max(1e-3)).exp()) * (1.0 + c * (d * gamma).exp() + e * gamma.cos().powi(2))
}

/// The published sky luminance, cd/m², along unit `dir` with the sun along unit `sun`.
fn preetham_luminance(t: f64, sun: [f64; 3], dir: [f64; 3]) -> f64 {
    let theta_s = sun[1].acos();
    let chi = (4.0 / 9.0 - t / 120.0) * (std::f64::consts::PI - 2.0 * theta_s);
    let zenith_kcd = (4.0453 * t - 4.9710) * chi.tan() - 0.2155 * t + 2.4192;
    let gamma = (sun[0] * dir[0] + sun[1] * dir[1] + sun[2] * dir[2]).clamp(-1.0, 1.0).acos();
    1000.0 * zenith_kcd * perez_y(t, dir[1], gamma) / perez_y(t, 1.0, theta_s)
}

fn luminance(c: Vec3) -> f64 {
    f64::from(0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z)
}

/// A scene with Preetham's sky, the sun at `el` degrees and azimuth 0 (north, −Z), the sun driving
/// the light, no water, and the camera at the origin looking along `forward` with `fov` degrees.
fn sky_scene(el: f64, forward: Vec3, fov: f32, sun_size: f32) -> Scene {
    let up = if forward.y.abs() > 0.9 { Vec3::Z } else { Vec3::Y };
    let text = format!(
        "version = 1\n[camera]\neye = [0.0, 0.0, 0.0]\ntarget = [{}, {}, {}]\nup = [{}, {}, {}]\n\
         fov_y_deg = {fov}\nnear = 0.5\nfar = 2000.0\n\
         [[light]]\ntype = 'directional'\ndirection = [0.0, -1.0, 0.0]\n\
         [sky]\nmodel = 'preetham'\nsun_elevation_deg = {el}\nsun_azimuth_deg = 0.0\nturbidity = {TURBIDITY}\n\
         sun_drives_light = true\nsun_size_deg = {sun_size}\n[render]\nwidth = 64\nheight = 64\n",
        forward.x, forward.y, forward.z, up.x, up.y, up.z
    );
    Scene::from_toml(&text, "light_scale").unwrap()
}

#[test]
fn the_drawn_sky_is_preetham_s_luminance_in_the_renderer_s_unit() {
    for el in ELEVATIONS_DEG {
        let (se, ce) = el.to_radians().sin_cos();
        let sun = [0.0, se, -ce];
        // Straight up, towards the horizon away from the sun, 30° up beside it, 20° up across.
        let dirs = [
            Vec3::new(0.001, 1.0, 0.0),
            Vec3::new(0.0, 0.1, 1.0),
            Vec3::new(0.6, 0.5, -0.6),
            Vec3::new(1.0, 0.36, 0.0),
        ];
        for d in dirs.map(Vec3::normalize) {
            let mut world = World::new(sky_scene(el, d, 5.0, 0.53)).unwrap();
            world.update(0.0).unwrap();
            let mut renderer = Renderer::new();
            let fb = renderer.render(&world);
            // The centre 2 x 2 pixels straddle the view direction.
            let c = [(31, 31), (32, 31), (31, 32), (32, 32)]
                .iter()
                .map(|&(x, y)| fb.color[y * 64 + x])
                .fold(Vec3::ZERO, |a, b| a + b / 4.0);
            let got = luminance(c) * f64::from(RADIANCE_UNIT_NITS);
            let want = preetham_luminance(TURBIDITY, sun, d.as_dvec3().to_array());
            let err = got / want - 1.0;
            println!("sun {el}°, view {d}: drawn {got:.0} cd/m², Preetham {want:.0} cd/m² ({:+.2} %)", 100.0 * err);
            assert!(err.abs() < 0.03, "sun {el}°, view {d}: {got} vs {want} cd/m²");
        }
    }
}

#[test]
fn the_sunlight_is_the_ies_clear_sky_direct_illuminance() {
    for el in ELEVATIONS_DEG {
        let scene = sky_scene(el, -Vec3::Z, 50.0, 1.5);
        let mut lights = Vec::new();
        scene.sky.drive_lights(&scene.lights, &mut lights);
        let Light::Directional { direction, color, intensity } = lights[0] else { panic!("not directional") };
        assert!((direction + scene.sky.to_sun()).length() < 1e-5, "the light comes from the sun");
        let got_klux = std::f64::consts::PI * luminance(color * intensity) * f64::from(RADIANCE_UNIT_NITS) / 1000.0;
        let want_klux = 127.5 * (-0.21 / el.to_radians().sin()).exp();
        let err = got_klux / want_klux - 1.0;
        println!("sun {el}°: sunlight {got_klux:.1} klux, IES clear sky {want_klux:.1} klux ({:+.1} %)", 100.0 * err);
        assert!(err.abs() < 0.15, "sun {el}°: {got_klux} vs {want_klux} klux");
    }
}

#[test]
fn the_drawn_disc_carries_the_sunlight_s_irradiance() {
    // A camera looking at the sun with a 6° view: the disc (1.5°) and its aureole fill the centre.
    for el in ELEVATIONS_DEG {
        let (se, ce) = (el as f32).to_radians().sin_cos();
        let to_sun = Vec3::new(0.0, se, -ce);
        let scene = sky_scene(el, to_sun, 6.0, 1.5);
        let mut disc_only = scene.clone();
        disc_only.sky.sun_size_deg = 0.0;
        let render = |s: Scene| {
            let mut world = World::new(s).unwrap();
            world.update(0.0).unwrap();
            let mut r = Renderer::new();
            r.render_size(&world, 512, 512).clone()
        };
        let (with, without) = (render(scene.clone()), render(disc_only));
        // Each pixel's solid angle on the image plane at distance 1: (pixel side)² cos³ of its angle.
        let half = (3.0f64).to_radians().tan();
        let px = 2.0 * half / 512.0;
        let mut e = 0.0f64;
        for y in 0..512 {
            for x in 0..512 {
                let (u, v) = ((x as f64 + 0.5) * px - half, (y as f64 + 0.5) * px - half);
                let cos = 1.0 / (1.0 + u * u + v * v).sqrt();
                let i = y * 512 + x;
                e += luminance(with.color[i] - without.color[i]) * px * px * cos.powi(3);
            }
        }
        let mut lights = Vec::new();
        scene.sky.drive_lights(&scene.lights, &mut lights);
        let Light::Directional { color, intensity, .. } = lights[0] else { panic!() };
        let want = std::f64::consts::PI * luminance(color * intensity);
        // The aureole reaches 20 radii (15°), beyond the 6° view: its last part is not counted.
        println!("sun {el}°: disc irradiance {e:.4}, sunlight {want:.4} (units)");
        assert!((e / want - 1.0).abs() < 0.03, "sun {el}°: {e} vs {want}");
    }
}
