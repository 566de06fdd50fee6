//! `swell stats`: the sea state a spectral scene realises, as JSON ([`swell::scene::SeaStats`]).

use swell::scene::SeaStats;
use swell::{Error, Result};

use super::load_scene;
use crate::args::StatsArgs;

pub fn run(a: StatsArgs) -> Result<()> {
    if !a.time.is_finite() {
        return Err(Error::out_of_range("--time", a.time, "finite seconds"));
    }
    let scene = load_scene(&a.source)?;
    println!("{}", SeaStats::of_scene(&scene, a.time)?.to_json());
    Ok(())
}
