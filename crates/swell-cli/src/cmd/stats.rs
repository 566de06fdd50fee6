//! `swell stats`: the sea state a spectral scene realises, as JSON ([`swell::world::sea_stats`]).

use swell::world::sea_stats;
use swell::Result;

use super::load_scene;
use crate::args::StatsArgs;

pub fn run(a: StatsArgs) -> Result<()> {
    swell::limits::check_time("--time", a.time)?;
    let scene = load_scene(&a.source)?;
    let stats = sea_stats(&scene, a.time)?;
    println!("{}", serde_json::to_string_pretty(&stats).expect("plain JSON values"));
    Ok(())
}
