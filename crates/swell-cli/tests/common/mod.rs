//! What the CLI test files share: running the real binary and reading what it wrote.

// Each test file uses its own subset.
#![allow(dead_code)]

use std::collections::BTreeMap;
use std::path::Path;
use std::process::{Command, Output};

/// The binary under test.
pub const SWELL: &str = env!("CARGO_BIN_EXE_swell");

/// Runs `swell` with `args` to completion.
pub fn swell(args: &[&str]) -> Output {
    Command::new(SWELL).args(args).output().unwrap()
}

/// A run's standard error as text.
pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Every visible file of `dir` (temporaries of killed runs start with a dot) and its bytes.
pub fn files(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap())
        .filter(|e| !e.file_name().to_string_lossy().starts_with('.'))
        .map(|e| (e.file_name().to_string_lossy().into_owned(), std::fs::read(e.path()).unwrap()))
        .collect()
}

/// The one-channel (`Y`) float EXR at `path` (a foam map), row-major.
pub fn read_exr_y(path: &Path) -> Vec<f32> {
    use exr::prelude::{ReadChannels, ReadLayers, ReadSpecificChannel};
    let img = exr::prelude::read()
        .no_deep_data()
        .largest_resolution_level()
        .specific_channels()
        .required("Y")
        .collect_pixels(
            |res, _| (res.width(), vec![0.0f32; res.width() * res.height()]),
            |(w, px), pos, (y,): (f32,)| px[pos.y() * *w + pos.x()] = y,
        )
        .first_valid_layer()
        .all_attributes()
        .from_file(path)
        .unwrap();
    img.layer_data.channel_data.pixels.1
}

/// The RGB float EXR at `path` (a normal or displacement map, a rendered frame's radiance),
/// row-major, first row first.
pub fn read_exr_rgb(path: &Path) -> Vec<glam::Vec3> {
    let img = exr::prelude::read_first_rgba_layer_from_file(
        path,
        |res, _| (res.width(), vec![glam::Vec3::ZERO; res.width() * res.height()]),
        |(w, px), pos, (r, g, b, _a): (f32, f32, f32, f32)| px[pos.y() * *w + pos.x()] = glam::Vec3::new(r, g, b),
    )
    .unwrap();
    img.layer_data.channel_data.pixels.1
}
