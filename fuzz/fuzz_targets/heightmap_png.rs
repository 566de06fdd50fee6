//! Heightmap loader: any bytes either decode into grey levels in [0, 1] that make a valid height
//! field, or are refused with an error. Never a panic, and never an allocation past the
//! heightmap budget (libFuzzer's -rss_limit_mb catches that).
#![no_main]

use glam::Vec2;
use libfuzzer_sys::fuzz_target;
use swell::terrain::{decode_grey_png, HeightField};

fuzz_target!(|data: &[u8]| {
    if let Ok((w, h, grey)) = decode_grey_png(data, std::path::Path::new("fuzz.png")) {
        assert_eq!(grey.len(), w as usize * h as usize);
        assert!(grey.iter().all(|g| (0.0..=1.0).contains(g)));
        let field = HeightField::new(w, h, Vec2::new(100.0, 100.0), grey.iter().map(|g| 10.0 * g).collect());
        assert!(field.is_ok(), "{:?}", field.err());
    }
});
