//! Camera and light JSON readers of `swell render --obj`: the same bytes go to both. Whatever is
//! accepted gives finite view and projection matrices and a valid light; everything else is an
//! error. Never a panic or a stack overflow.
#![no_main]

use libfuzzer_sys::fuzz_target;
use swell::render::{parse_camera_json, parse_light_json};

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else { return };
    if let Ok(view) = parse_camera_json(text, "fuzz.json") {
        assert!((1..=swell::scene::MAX_IMAGE_SIDE).contains(&view.width));
        assert!((1..=swell::scene::MAX_IMAGE_SIDE).contains(&view.height));
        let aspect = view.width as f32 / view.height as f32;
        let m = view.camera.clip_from_view(aspect) * view.camera.view_from_world();
        assert!(m.is_finite(), "{view:?} gives {m:?}");
    }
    if let Ok(light) = parse_light_json(text, "fuzz.json") {
        light.validate("light").expect("an accepted light validates again");
        assert!(light.dir.normalize_or_zero().is_finite());
    }
});
