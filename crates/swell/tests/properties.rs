//! Property tests: any finite parameter set either validates and then gives finite meshes and
//! finite pixels, or is refused with an error. Never a panic, never NaN or infinity in a mesh or a
//! framebuffer.
//!
//! Scenes are written as TOML text and read with `Scene::from_toml`, so the parser, validation,
//! `World::new`, `World::update` and the renderer are all exercised. Values are drawn from wide
//! finite ranges (including many that validation must refuse) so both outcomes are common.
//! 64 cases per property keep the suite fast; `PROPTEST_CASES=10000` runs more.

use proptest::prelude::*;
use swell::render::Renderer;
use swell::scene::Scene;
use swell::world::World;

/// Any finite f32, weighted towards the ranges where parameters are valid.
fn finite() -> impl Strategy<Value = f32> {
    prop_oneof![
        3 => -2.0f32..2.0,
        3 => -100.0f32..100.0,
        1 => -1.0e6f32..1.0e6,
        1 => proptest::num::f32::NORMAL | proptest::num::f32::SUBNORMAL | proptest::num::f32::ZERO,
    ]
}

fn positive() -> impl Strategy<Value = f32> {
    mostly(0.01f32..100.0)
}

/// Mostly `range` (where the key is valid), sometimes any finite value, so that a scene with
/// several keys is still accepted often enough to reach the renderer.
fn mostly(range: std::ops::Range<f32>) -> impl Strategy<Value = f32> {
    prop_oneof![15 => range, 1 => finite()]
}

/// A float as TOML text (Debug prints the shortest exact form, always with `.` or an exponent).
fn f(v: f32) -> String {
    format!("{v:?}")
}

fn v3(v: (f32, f32, f32)) -> String {
    format!("[{}, {}, {}]", f(v.0), f(v.1), f(v.2))
}

prop_compose! {
    fn camera_and_render()(
        eye in (finite(), 1.0f32..50.0, finite()),
        target in (finite(), finite(), finite()),
        fov in mostly(5.0f32..120.0),
        near in mostly(0.01f32..1.0),
        far in mostly(100.0f32..5000.0),
        exposure in mostly(0.1f32..4.0),
        gamma in proptest::option::of(mostly(1.0f32..5.0)),
        ambient in (0.0f32..1.0, 0.0f32..1.0, positive()),
        light in (finite(), -1.0f32..-0.01, finite()),
        intensity in mostly(0.0f32..5.0),
    ) -> String {
        let gamma = gamma.map(|g| format!("gamma = {}\n", f(g))).unwrap_or_default();
        format!(
            "version = 1\n[camera]\neye = {}\ntarget = {}\nfov_y_deg = {}\nnear = {}\nfar = {}\n\
             [render]\nwidth = 32\nheight = 18\nexposure = {}\n{gamma}ambient = {}\n\
             [[light]]\ntype = 'directional'\ndirection = {}\nintensity = {}\n",
            v3(eye), v3(target), f(fov), f(near), f(far), f(exposure), v3(ambient), v3(light), f(intensity)
        )
    }
}

prop_compose! {
    /// A `[[water.waves]]` entry; `steep` adds the Gerstner steepness.
    fn wave(steep: bool)(
        amplitude in mostly(0.0f32..3.0),
        wavelength in prop_oneof![0.5f32..200.0, positive()],
        speed in mostly(0.0f32..20.0),
        direction in [finite(), finite()],
        steepness in mostly(0.0f32..1.0),
    ) -> String {
        let q = if steep { format!("steepness = {}\n", f(steepness)) } else { String::new() };
        format!(
            "[[water.waves]]\namplitude = {}\nwavelength = {}\nspeed = {}\ndirection = [{}, {}]\n{q}",
            f(amplitude), f(wavelength), f(speed), f(direction[0]), f(direction[1])
        )
    }
}

prop_compose! {
    fn water()(
        gerstner in any::<bool>(),
        size in [mostly(10.0f32..500.0), mostly(10.0f32..500.0)],
        cells in [1u32..24, 1u32..24],
        center in [finite(), finite()],
        waves in proptest::collection::vec((wave(true), wave(false)), 0..5),
        color in (0.0f32..1.0, 0.0f32..1.0, finite()),
        ior in mostly(1.0f32..2.0),
    ) -> String {
        let model = if gerstner { "gerstner" } else { "sines" };
        let waves: String = waves.into_iter().map(|(g, s)| if gerstner { g } else { s }).collect();
        format!(
            "[water]\nmodel = '{model}'\nsize = [{}, {}]\ncells = [{}, {}]\ncenter = [{}, {}]\n{waves}\
             [water.material]\ncolor = {}\nrefractive_index = {}\n",
            f(size[0]), f(size[1]), cells[0], cells[1], f(center[0]), f(center[1]), v3(color), f(ior)
        )
    }
}

/// Builds, updates to `t` and renders `text`; every stage may refuse, none may produce non-finite
/// data. Returns whether the scene rendered.
fn render_or_refuse(text: &str, t: f64) -> Result<bool, TestCaseError> {
    let Ok(scene) = Scene::from_toml(text, "prop") else { return Ok(false) };
    let Ok(mut world) = World::new(scene) else { return Ok(false) };
    if world.update(t).is_err() {
        return Ok(false);
    }
    if let Some(w) = &world.water {
        prop_assert!(w.surface.positions().iter().all(|p| p.is_finite()), "non-finite water position");
        prop_assert!(w.surface.normals().iter().all(|n| n.is_finite()), "non-finite water normal");
    }
    let mut renderer = Renderer::new();
    let fb = renderer.render(&world);
    prop_assert_eq!((fb.width(), fb.height()), (32, 18));
    prop_assert!(fb.color.iter().all(|c| c.is_finite()), "non-finite pixel");
    let mut rgba = Vec::new();
    fb.encode_rgba8(&world.scene.render.display_encoding(), &mut rgba);
    prop_assert_eq!(rgba.len(), 32 * 18 * 4);
    Ok(true)
}

/// Scenes that reached the renderer in the wide property, so a run can show both outcomes occur.
static RENDERED: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    #[test]
    fn any_finite_scene_renders_finite_pixels_or_is_refused(
        head in camera_and_render(),
        water in proptest::option::of(water()),
        t in prop_oneof![0.0f64..100.0, -1.0e4f64..1.0e4],
    ) {
        let text = format!("{head}{}", water.unwrap_or_default());
        if render_or_refuse(&text, t)? {
            let n = RENDERED.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
            if std::env::var_os("SWELL_PROP_VERBOSE").is_some() {
                eprintln!("rendered {n}");
            }
        }
    }

    /// Valid Gerstner and sines scenes (every value in range) always render.
    #[test]
    fn in_range_water_always_renders(
        gerstner in any::<bool>(),
        waves in proptest::collection::vec(
            (0.0f32..2.0, 1.0f32..100.0, 0.0f32..15.0, -1.0f32..1.0, 0.1f32..1.0, 0.0f32..1.0), 1..6),
        cells in 1u32..24,
        t in 0.0f64..1000.0,
    ) {
        let model = if gerstner { "gerstner" } else { "sines" };
        let mut text = format!(
            "version = 1\n[camera]\neye = [0.0, 20.0, 60.0]\ntarget = [0.0, 0.0, 0.0]\n\
             [render]\nwidth = 32\nheight = 18\n[water]\nmodel = '{model}'\nsize = [100.0, 100.0]\n\
             cells = [{cells}, {cells}]\n"
        );
        for (a, l, s, dx, dz, q) in waves {
            text += &format!(
                "[[water.waves]]\namplitude = {}\nwavelength = {}\nspeed = {}\ndirection = [{}, {}]\n",
                f(a), f(l), f(s), f(dx), f(dz)
            );
            if gerstner {
                text += &format!("steepness = {}\n", f(q));
            }
        }
        prop_assert!(render_or_refuse(&text, t)?, "a valid scene was refused:\n{text}");
    }
}
