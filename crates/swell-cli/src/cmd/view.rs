//! `swell view`: the interactive viewer (crate `swell-viewer`), optionally scripted to take a
//! screenshot and exit.

use swell::{Error, Result};
use swell_viewer::ViewerOptions;

use super::load_scene;
use crate::args::ViewArgs;

pub fn run(a: ViewArgs) -> Result<()> {
    // Flags first: a bad --screenshot is refused before the scene is read or a window opens.
    let exit_after_frames = match a.exit_after_frames {
        Some(n) => Some(
            u32::try_from(n)
                .map_err(|_| Error::out_of_range("--exit-after-frames", n, format!("[1, {}]", u32::MAX)))?,
        ),
        None => None,
    };
    swell_viewer::check_flags(a.screenshot.as_deref(), exit_after_frames)?;
    let scene = load_scene(&a.source)?;
    let source = match (&a.source.preset, &a.source.scene) {
        (Some(name), _) => format!("preset {name}"),
        (None, Some(path)) => path.display().to_string(),
        (None, None) => unreachable!("clap requires one of --preset and --scene"),
    };
    swell_viewer::run(ViewerOptions { scene, source, screenshot: a.screenshot, exit_after_frames })
}
