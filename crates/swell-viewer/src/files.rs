//! Files the viewer reads and writes: scene TOML (the same format as `swell render --scene`) and
//! PNG screenshots, always written atomically.

use std::path::Path;

use swell::export::{write_atomically, write_png};
use swell::scene::Scene;
use swell::{Error, Result};

/// Reads and validates a scene file through the library's one loader ([`Scene::load`]: size and
/// nesting limits, paths resolved beside the file); errors name the file and the key.
pub fn read_scene(path: &Path) -> Result<Scene> {
    Scene::load(path)
}

/// Writes `scene` as TOML to `path`, atomically.
pub fn write_scene(path: &Path, scene: &Scene) -> Result<()> {
    let text = scene.to_toml();
    write_atomically(path, |out| out.write_all(text.as_bytes()).map_err(|e| Error::io(path, e)))
}

/// Writes an RGBA8 image (top row first) as PNG, atomically. Sizes come from the window, so they
/// are checked here rather than trusted.
pub fn write_screenshot(path: &Path, width: usize, height: usize, rgba: &[u8]) -> Result<()> {
    if width == 0 || height == 0 || rgba.len() != 4 * width * height {
        return Err(Error::invalid(
            "screenshot",
            format!("{width}x{height} image with {} bytes cannot be saved as {}", rgba.len(), path.display()),
        ));
    }
    write_png(path, width as u32, height as u32, rgba)
}
