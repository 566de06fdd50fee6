//! Scene-file parser and validation: any bytes either parse into a scene that validates and whose
//! memory estimate is within budget, or are refused with an error. Never a panic, a hang or a
//! stack overflow.
#![no_main]

use libfuzzer_sys::fuzz_target;
use swell::scene::Scene;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else { return };
    if let Ok(scene) = Scene::from_toml(text, "fuzz") {
        // What parses must validate again, write back and read back to the same scene.
        scene.validate().expect("a parsed scene validates");
        assert!(scene.estimate_bytes() <= swell::limits::MEMORY_BUDGET_BYTES);
        let again = Scene::from_toml(&scene.to_toml(), "round trip").expect("a written scene reads back");
        assert_eq!(again.to_toml(), scene.to_toml());
    }
});
