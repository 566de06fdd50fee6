//! `swell stats`: the sea state a spectral scene realises, as JSON ([`swell::scene::sea_stats`]).

use swell::scene::sea_stats;
use swell::{Error, Result};

use super::load_scene;
use crate::args::StatsArgs;

pub fn run(a: StatsArgs) -> Result<()> {
    if !a.time.is_finite() {
        return Err(Error::out_of_range("--time", a.time, "finite seconds"));
    }
    let scene = load_scene(&a.source)?;
    let stats = sea_stats(&scene, a.time)?;
    println!("{}", serde_json::to_string_pretty(&stats).expect("plain JSON values"));
    Ok(())
}
