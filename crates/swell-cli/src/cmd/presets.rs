//! `swell presets`: one line per built-in scene.

use swell::scene::PRESETS;
use swell::Result;

pub fn run() -> Result<()> {
    let width = PRESETS.iter().map(|p| p.name.len()).max().unwrap_or(0);
    for p in PRESETS {
        println!("{:width$}  {}", p.name, p.description);
    }
    Ok(())
}
