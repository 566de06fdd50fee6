//! `swell terrain`: generate a terrain and write it as a 16-bit heightmap PNG or a float32 EXR of
//! heights in metres, plus its sidecar.

use std::path::Path;

use swell::export::write_heightmap_exr;
use swell::scene::TerrainSpec;
use swell::terrain::{sidecar_path, write_heightmap};
use swell::{Error, Result};

use super::thread_pool;
use crate::args::TerrainArgs;

pub fn run(a: TerrainArgs) -> Result<()> {
    let format = output_format(&a.out, a.format.as_deref())?;
    let spec = resolve(&a)?;
    let pool = thread_pool(a.threads)?;
    let field = pool.install(|| spec.build())?;
    // The image is written (atomically) before its sidecar: if the sidecar then fails, an image
    // this run created is removed again, so a failed run leaves nothing behind (issue 37).
    let existed = a.out.exists();
    let written = match format {
        Format::Png => write_heightmap(&a.out, &field),
        Format::Exr => write_heightmap_exr(&a.out, &field),
    };
    let sidecar = written.inspect_err(|_| {
        if !existed {
            let _ = std::fs::remove_file(&a.out);
        }
    })?;
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

/// The `[terrain]` keys that have a flag of their own: `--set` may not set them, so that a flag
/// given on the command line is never silently beaten by a `--set` (issue 37).
const KEYS_WITH_FLAGS: [(&str, &str); 4] =
    [("generator", "--generator"), ("size", "--size"), ("extent", "--extent"), ("seed", "--seed")];

/// Parses `KEY=VALUE`, the value as one TOML value (a bare word that is not TOML is taken as a
/// string). A value that carries more than one key (a newline and a second line or table) and a
/// key with a flag of its own are refused.
fn parse_set(kv: &str) -> Result<(String, toml::Value)> {
    let (key, value) = kv
        .split_once('=')
        .ok_or_else(|| Error::invalid("--set", format!("`{kv}` is not KEY=VALUE (e.g. roughness=0.6)")))?;
    let key = key.trim();
    if key.is_empty() || !key.chars().all(|c| c.is_ascii_alphanumeric() || c == '_') {
        return Err(Error::invalid("--set", format!("`{key}` is not a [terrain] key name")));
    }
    if let Some((_, flag)) = KEYS_WITH_FLAGS.iter().find(|(k, _)| *k == key) {
        return Err(Error::invalid("--set", format!("`{key}` has a flag of its own: give {flag} instead")));
    }
    if value.contains(['\n', '\r']) {
        return Err(Error::invalid(
            format!("--set {key}"),
            "the value spans lines; give one TOML value per --set (one key each)",
        ));
    }
    let value = match toml::from_str::<toml::Table>(&format!("v = {}", value.trim())) {
        Ok(mut t) if t.len() == 1 => t.remove("v").expect("the table has the key just parsed"),
        Ok(_) => {
            return Err(Error::invalid(format!("--set {key}"), "the value holds more than one key; give one per --set"))
        }
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

/// The heightmap file formats.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Format {
    /// 16-bit grayscale PNG, heights scaled to the full grey range (the default).
    Png,
    /// One-channel float32 EXR, heights in metres.
    Exr,
}

impl Format {
    fn parse(key: &str, s: &str) -> Result<Self> {
        match s.to_ascii_lowercase().as_str() {
            "png" => Ok(Self::Png),
            "exr" => Ok(Self::Exr),
            _ => Err(Error::invalid(key, format!("`{s}` is not a heightmap format; valid: png, exr"))),
        }
    }
}

/// Checks the output before any work and picks its format: `--format` if given, else the
/// extension of `--out`; the two must agree, and the directory must exist.
fn output_format(out: &Path, format: Option<&str>) -> Result<Format> {
    let ext = out.extension().and_then(|e| e.to_str()).and_then(|e| Format::parse("--out", e).ok());
    let format = match (format.map(|f| Format::parse("--format", f)).transpose()?, ext) {
        (Some(f), Some(e)) if f != e => {
            return Err(Error::invalid(
                "--out",
                format!("{} does not end in .{} as --format {} asks", out.display(), name(f), name(f)),
            ))
        }
        (Some(f), _) | (None, Some(f)) => f,
        (None, None) => {
            return Err(Error::invalid(
                "--out",
                format!(
                    "{} must end in .png (16-bit heightmap) or .exr (float32 metres), or give --format",
                    out.display()
                ),
            ))
        }
    };
    super::check_output_dir(out)?;
    Ok(format)
}

fn name(f: Format) -> &'static str {
    match f {
        Format::Png => "png",
        Format::Exr => "exr",
    }
}
