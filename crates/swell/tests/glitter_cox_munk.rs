//! The sun's glitter on the open FFT sea follows Cox and Munk (issue 32, item 2).
//!
//! The sun stands 30° up straight ahead, the wind blows along the view, the camera looks down at
//! the specular point (30° below the horizon, so it is the image's centre). The glitter alone is
//! the frame's linear radiance (what `swell render --out f.exr` writes) with the water's
//! `specular = 1` minus the same frame with `specular = 0`, averaged over 32 times 2.37 s apart.
//!
//! Cox and Munk (1954) measured the sea's slopes as a Gaussian of variances `3.16e-3 U` upwind
//! and `0.003 + 1.92e-3 U` crosswind (U at 12.5 m). Over a flat mean surface that distribution
//! reflects a sun of irradiance `E` as `L = E F(v·h) p(ζ_h) / (4 cos θv cos⁴β)` (docs/scene-format.md,
//! "The sun glitter"); the test evaluates that along the same pixels' rays and compares:
//! - the half-width (half maximum) of the glitter across the view, within 20 %;
//! - the radiance at the specular point, within 0.7 to 1.4 times `E F p(0) / (4 cos θv)`.
//!
//! The render's sea gets there from three parts: the slopes its mesh resolves, those its pixels
//! filter, and the micro-roughness that makes up the rest of Cox and Munk's variance.

use glam::Vec3;
use swell::render::Renderer;
use swell::scene::Scene;
use swell::world::World;

const WIDTH: u32 = 480;
const HEIGHT: u32 = 320;
const FOV_Y_DEG: f32 = 50.0;
const SUN_ELEVATION_DEG: f32 = 30.0;
const EYE_HEIGHT: f32 = 40.0;
/// Frames averaged: the long waves tilt the whole glitter one way or another at any instant (at
/// 12 m/s the peak wave is 90 m long), so the average needs many of their periods.
const FRAMES: usize = 32;
/// Seconds between the frames averaged: unrelated to the waves' periods.
const FRAME_STEP: f64 = 2.37;
const IOR: f32 = 1.333;

fn scene(wind: f32, specular: f32) -> Scene {
    let el = SUN_ELEVATION_DEG.to_radians();
    // Looking along −Z at the specular point, the sun ahead (its light travels towards +Z, down).
    let target_z = -EYE_HEIGHT / el.tan();
    let text = format!(
        r#"
version = 1
[camera]
eye = [0.0, {EYE_HEIGHT}, 0.0]
target = [0.0, 0.0, {target_z}]
fov_y_deg = {FOV_Y_DEG}
near = 0.5
far = 5000.0
[[light]]
type = "directional"
direction = [0.0, {dy}, {dz}]
color = [1.0, 1.0, 1.0]
intensity = 1.0
[sky]
sun_size_deg = 0.53
[render]
width = {WIDTH}
height = {HEIGHT}
[water]
model = "fft"
extent = "unbounded"
wind_speed = {wind}
wind_direction_deg = 270.0
foam = false
[water.material]
shading = "blinn-phong"
specular = {specular}
"#,
        dy = -el.sin(),
        dz = el.cos(),
    );
    Scene::from_toml(&text, "glitter test").unwrap()
}

/// The frame's linear radiance (red channel: the light is white) at each time.
fn frames(scene: &Scene) -> Vec<Vec<f32>> {
    let mut world = World::new(scene.clone()).unwrap();
    let mut renderer = Renderer::new();
    (0..FRAMES)
        .map(|i| {
            let t = 10.0 + FRAME_STEP * i as f64;
            world.update(t).unwrap();
            renderer.render(&world).color.iter().map(|c| c.x).collect()
        })
        .collect()
}

/// The time-averaged glitter: specular 1 minus specular 0, per pixel.
fn glitter(wind: f32) -> Vec<f64> {
    let on = frames(&scene(wind, 1.0));
    let off = frames(&scene(wind, 0.0));
    let mut mean = vec![0.0f64; (WIDTH * HEIGHT) as usize];
    for (a, b) in on.iter().zip(&off) {
        for (m, (x, y)) in mean.iter_mut().zip(a.iter().zip(b)) {
            *m += f64::from(x - y) / FRAMES as f64;
        }
    }
    mean
}

/// Unit view ray through pixel column `x` of the centre row (the camera pitched down so that the
/// centre row looks at the specular point), and its angle across the view, degrees.
fn ray(x: u32) -> (Vec3, f32) {
    let el = SUN_ELEVATION_DEG.to_radians();
    let forward = Vec3::new(0.0, -el.sin(), -el.cos());
    let right = Vec3::X;
    let up = right.cross(forward);
    let tan_half = (FOV_Y_DEG.to_radians() / 2.0).tan();
    let ndc_x = 2.0 * (x as f32 + 0.5) / WIDTH as f32 - 1.0;
    // The centre row sits between rows HEIGHT/2 − 1 and HEIGHT/2: half a pixel up.
    let ndc_y = 1.0 / HEIGHT as f32;
    let aspect = WIDTH as f32 / HEIGHT as f32;
    let d = (forward + right * (ndc_x * tan_half * aspect) + up * (ndc_y * tan_half)).normalize();
    (d, (ndc_x * tan_half * aspect).atan().to_degrees())
}

/// Cox and Munk's glitter over a flat mean sea along the view ray `d`, for the sun's irradiance
/// `e` (W/m²-like renderer units: π times the light's radiance).
fn cox_munk_radiance(d: Vec3, wind: f32, e: f32) -> f32 {
    let el = SUN_ELEVATION_DEG.to_radians();
    let to_sun = Vec3::new(0.0, el.sin(), -el.cos());
    let v = -d;
    let h = (to_sun + v).normalize();
    // Slopes of the facet: along the wind (z) and across it (x).
    let (zu, zc) = (-h.z / h.y, -h.x / h.y);
    let u = wind * 1.25f32.powf(1.0 / 7.0);
    let (su, sc) = (3.16e-3 * u, 0.003 + 1.92e-3 * u);
    let p = (-0.5 * (zu * zu / su + zc * zc / sc)).exp() / (std::f32::consts::TAU * (su * sc).sqrt());
    e * swell::shading::fresnel_dielectric(v.dot(h), IOR) * p / (4.0 * v.y * h.y.powi(4))
}

/// Half-width at half maximum of `profile` (values at the angles `angles`, degrees), from the
/// maximum out to each side, averaged.
fn half_width(profile: &[f64], angles: &[f32]) -> f32 {
    let (peak, &max) = profile.iter().enumerate().max_by(|a, b| a.1.total_cmp(b.1)).unwrap();
    let half = max / 2.0;
    let crossing = |range: Box<dyn Iterator<Item = usize>>| -> f32 {
        let mut prev = peak;
        for i in range {
            if profile[i] < half {
                let f = ((profile[prev] - half) / (profile[prev] - profile[i])) as f32;
                return (angles[prev] + f * (angles[i] - angles[prev]) - angles[peak]).abs();
            }
            prev = i;
        }
        panic!("the glitter does not fall to half its maximum inside the image");
    };
    0.5 * (crossing(Box::new(peak + 1..profile.len())) + crossing(Box::new((0..peak).rev())))
}

fn check(wind: f32) -> (f32, f32, f64, f64) {
    let g = glitter(wind);
    let e = std::f32::consts::PI; // a white light of intensity 1
    let rows = HEIGHT / 2 - 3..HEIGHT / 2 + 3;
    let rendered: Vec<f64> = (0..WIDTH)
        .map(|x| rows.clone().map(|y| g[(y * WIDTH + x) as usize]).sum::<f64>() / rows.len() as f64)
        .collect();
    let angles: Vec<f32> = (0..WIDTH).map(|x| ray(x).1).collect();
    let expected: Vec<f64> = (0..WIDTH).map(|x| f64::from(cox_munk_radiance(ray(x).0, wind, e))).collect();
    let centre = (WIDTH / 2 - 4..WIDTH / 2 + 4).map(|x| rendered[x as usize]).sum::<f64>() / 8.0;
    let centre_expected = (WIDTH / 2 - 4..WIDTH / 2 + 4).map(|x| expected[x as usize]).sum::<f64>() / 8.0;
    (half_width(&rendered, &angles), half_width(&expected, &angles), centre, centre_expected)
}

#[test]
fn the_glitter_has_cox_and_munks_width_and_radiance() {
    let mut failures = Vec::new();
    for wind in [4.0f32, 12.0] {
        let (w, w_cm, l, l_cm) = check(wind);
        eprintln!(
            "U10 {wind} m/s: half-width across the view {w:.2}° (Cox-Munk {w_cm:.2}°, ratio {:.3}); radiance at the \
             specular point {l:.3} (Cox-Munk {l_cm:.3}, ratio {:.3})",
            w / w_cm,
            l / l_cm
        );
        if (w / w_cm - 1.0).abs() > 0.2 {
            failures.push(format!("{wind} m/s: half-width {w:.2}° vs Cox-Munk {w_cm:.2}°"));
        }
        if !(0.7..=1.4).contains(&(l / l_cm)) {
            failures.push(format!("{wind} m/s: radiance {l:.3} vs Cox-Munk {l_cm:.3}"));
        }
    }
    assert!(failures.is_empty(), "{failures:?}");
}
