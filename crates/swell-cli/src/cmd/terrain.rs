//! `swell terrain`: generate a terrain and write it as a 16-bit heightmap PNG plus its sidecar.

use std::path::Path;

use swell::scene::TerrainSpec;
use swell::terrain::{sidecar_path, write_heightmap};
use swell::{Error, Result};

use super::thread_pool;
use crate::args::TerrainArgs;

pub fn run(a: TerrainArgs) -> Result<()> {
    check_output(&a.out)?;
    let spec = resolve(&a)?;
    let pool = thread_pool(a.threads)?;
    let field = pool.install(|| spec.build())?;
    let sidecar = write_heightmap(&a.out, &field)?;
    let (lo, hi) = field.min_max();
    eprintln!(
        "wrote {} ({} x {} vertices over {} x {} m, heights {lo:.2}..{hi:.2} m) and {}",
        a.out.display(),
        field.cols(),
        field.rows(),
        sidecar.extent.x,
        sidecar.extent.y,
        sidecar_path(&a.out).display()
    );
    Ok(())
}

/// Turns the arguments into a `[terrain]` table and reads it like a scene file would, so keys,
/// defaults and error messages are the scene format's.
fn resolve(a: &TerrainArgs) -> Result<TerrainSpec> {
    if a.generator == "heightmap" {
        return Err(Error::invalid("--generator", "heightmap reads a file; choose a generator that makes terrain"));
    }
    let mut table = toml::Table::new();
    table.insert("generator".into(), a.generator.clone().into());
    table.insert("size".into(), toml::Value::Integer(a.size as i64));
    if let Some(e) = &a.extent {
        let (x, z) = parse_extent(e)?;
        table.insert("extent".into(), toml::Value::Array(vec![(x as f64).into(), (z as f64).into()]));
    }
    if let Some(seed) = a.seed {
        let seed =
            i64::try_from(seed).map_err(|_| Error::out_of_range("--seed", seed, format!("[0, {}]", i64::MAX)))?;
        table.insert("seed".into(), toml::Value::Integer(seed));
    }
    for kv in &a.set {
        let (key, value) = parse_set(kv)?;
        table.insert(key, value);
    }
    let spec = TerrainSpec::from_table(table, "command line")?;
    spec.validate()?;
    Ok(spec)
}

/// Parses `KEY=VALUE`, the value as TOML (a bare word that is not TOML is taken as a string).
fn parse_set(kv: &str) -> Result<(String, toml::Value)> {
    let (key, value) = kv
        .split_once('=')
        .ok_or_else(|| Error::invalid("--set", format!("`{kv}` is not KEY=VALUE (e.g. roughness=0.6)")))?;
    let key = key.trim();
    if key.is_empty() || !key.chars().all(|c| c.is_ascii_alphanumeric() || c == '_') {
        return Err(Error::invalid("--set", format!("`{key}` is not a [terrain] key name")));
    }
    let value = match toml::from_str::<toml::Table>(&format!("v = {}", value.trim())) {
        Ok(mut t) => t.remove("v").expect("the table has the key just parsed"),
        Err(_) => toml::Value::String(value.trim().to_string()),
    };
    Ok((key.to_string(), value))
}

/// Parses `X` or `XxZ` metres.
fn parse_extent(s: &str) -> Result<(f32, f32)> {
    let bad = || Error::invalid("--extent", format!("`{s}` is not METRES or XxZ metres (e.g. 400 or 400x300)"));
    let num = |t: &str| t.trim().parse::<f32>().map_err(|_| bad());
    match s.split_once(['x', 'X']) {
        Some((x, z)) => Ok((num(x)?, num(z)?)),
        None => {
            let v = num(s)?;
            Ok((v, v))
        }
    }
}

/// Checks the output before any work: a `.png` in an existing directory.
fn check_output(out: &Path) -> Result<()> {
    let ext = out.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    if ext.as_deref() != Some("png") {
        return Err(Error::invalid("--out", format!("{} must end in .png (a 16-bit heightmap)", out.display())));
    }
    let dir = match out.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    if !dir.is_dir() {
        return Err(Error::invalid("--out", format!("directory {} does not exist", dir.display())));
    }
    Ok(())
}
