//! The ranges docs/scene-format.md gives are the ranges the code enforces (issue 22): for every
//! key whose documented range is an interval (`[a, b]`, `(a, b]`, ...), a scene setting it just
//! outside is refused, and the error's range is the documented one.

use std::path::PathBuf;

use swell::scene::Scene;

/// A scene for a section's keys, and the dotted path of the table they go in (`water.waves` for
/// a list's first entry).
fn section_scene(header: &str) -> Option<(String, String)> {
    const BASE: &str = "version = 1\n[camera]\neye = [0.0, 5.0, 9.0]\ntarget = [0.0, 0.0, 0.0]\n";
    let h = header.trim_start_matches('#').trim();
    let table = |name: &str, extra: &str| Some((format!("{BASE}[{name}]\n{extra}"), name.to_string()));
    if h.starts_with("`[camera]`") {
        return Some((BASE.into(), "camera".into()));
    }
    if h.starts_with("`[sky]`") {
        return table("sky", "");
    }
    if h.starts_with("`[render]`") {
        return table("render", "");
    }
    if h.starts_with("`[water]`") {
        return table("water", "model = \"sines\"\n");
    }
    if h.starts_with("`[[body]]`") {
        let body = "shape = \"box\"\nsize = [1.0, 1.0, 1.0]\n";
        return Some((format!("{BASE}[[body]]\n{body}"), "body".into()));
    }
    if h.starts_with("`[water.material]`") {
        return Some((format!("{BASE}[water]\nmodel = \"sines\"\n[water.material]\n"), "water.material".into()));
    }
    if h.starts_with("`[water.swell]`") {
        return Some((format!("{BASE}[water]\nmodel = \"fft\"\ngrid = 16\n[water.swell]\n"), "water.swell".into()));
    }
    if let Some(rest) = h.strip_prefix("`model = \"") {
        let model = rest.split('"').next()?;
        if model == "gerstner" {
            // The section's keys are those of each `[[water.waves]]` entry.
            let wave = "amplitude = 0.5\nwavelength = 10.0\nspeed = 3.0\ndirection = [1.0, 0.0]\nsteepness = 0.5\n";
            return Some((
                format!("{BASE}[water]\nmodel = \"gerstner\"\n[[water.waves]]\n{wave}"),
                "water.waves".into(),
            ));
        }
        let extra = if model == "fft" { "grid = 16\n" } else { "" };
        return table("water", &format!("model = \"{model}\"\n{extra}"));
    }
    None
}

/// An interval `[a, b]`, `(a, b]`, ... as (lower closed, lower, upper, upper closed).
fn interval(s: &str) -> Option<(bool, f64, f64, bool)> {
    let s = s.trim().trim_end_matches(" seconds");
    let lower_closed = match s.chars().next()? {
        '[' => true,
        '(' => false,
        _ => return None,
    };
    let upper_closed = match s.chars().last()? {
        ']' => true,
        ')' => false,
        _ => return None,
    };
    let (a, b) = s[1..s.len() - 1].split_once(',')?;
    let num = |t: &str| -> Option<f64> {
        match t.trim() {
            "inf" => Some(f64::INFINITY),
            "-inf" => Some(f64::NEG_INFINITY),
            t => t.replace('_', "").parse().ok(),
        }
    };
    Some((lower_closed, num(a)?, num(b)?, upper_closed))
}

fn same(a: (bool, f64, f64, bool), b: (bool, f64, f64, bool)) -> bool {
    let close = |x: f64, y: f64| x == y || (x - y).abs() <= 1e-6 * x.abs().max(y.abs());
    a.0 == b.0 && a.3 == b.3 && close(a.1, b.1) && close(a.2, b.2)
}

#[test]
fn every_documented_interval_is_the_one_the_code_enforces() {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../docs/scene-format.md");
    let doc = std::fs::read_to_string(&path).unwrap();
    let mut section: Option<(String, String)> = None;
    let (mut checked, mut problems) = (0, Vec::new());
    for line in doc.lines() {
        if line.starts_with('#') {
            section = section_scene(line);
            continue;
        }
        let Some((base, _)) = &section else { continue };
        let base = base.as_str();
        let cells: Vec<&str> = line.split('|').map(str::trim).collect();
        // | key | type | default | range | meaning |
        if cells.len() < 6 || !cells[1].starts_with('`') {
            continue;
        }
        let key = cells[1].trim_matches('`');
        if key.contains(['[', '.', ' ']) {
            continue; // list entries and nested tables are checked with their own tables
        }
        let Some(documented) = interval(cells[4]) else { continue };
        let integer = cells[2].contains("integer");
        // Just past the upper end, or below the lower one when the upper is unbounded.
        let bad = if documented.2.is_finite() {
            documented.2 + documented.2.abs().max(1.0)
        } else {
            documented.1 - documented.1.abs().max(1.0)
        };
        let set = |value: toml::Value| {
            let mut doc: toml::Table = toml::from_str(base).unwrap();
            let mut table = &mut doc;
            for part in section.as_ref().unwrap().1.split('.').filter(|p| !p.is_empty()) {
                table = match table.get_mut(part).unwrap() {
                    toml::Value::Table(t) => t,
                    toml::Value::Array(a) => a[0].as_table_mut().unwrap(),
                    _ => unreachable!(),
                };
            }
            table.insert(key.to_string(), value);
            toml::to_string(&doc).unwrap()
        };
        let mut value = if integer { toml::Value::Integer(bad.round() as i64) } else { toml::Value::Float(bad) };
        let mut result = Scene::from_toml(&set(value.clone()), "doc");
        // A whole-number key (pixels, counts) refuses a float by type: ask again with an integer.
        if result.as_ref().is_err_and(|e| e.to_string().contains("invalid type: floating point")) {
            value = toml::Value::Integer(bad.round() as i64);
            result = Scene::from_toml(&set(value.clone()), "doc");
        }
        checked += 1;
        match result {
            Ok(_) => problems.push(format!("{key} = {value}: accepted, but the docs give {}", cells[4])),
            Err(e) => {
                let message = e.without_source().to_string();
                // serde's own refusal of an integer past u32 is the range [0, 4294967295].
                if message.contains("expected u32") && documented == (true, 0.0, f64::from(u32::MAX), true) {
                    continue;
                }
                let enforced = message.split(" is outside ").nth(1).and_then(interval);
                match enforced {
                    Some(r) if same(r, documented) => {}
                    _ => problems.push(format!("{key}: the docs give {}, the code says `{message}`", cells[4])),
                }
            }
        }
    }
    assert!(checked >= 40, "only {checked} documented intervals found: is the table layout still | key | type | default | range | meaning |?");
    assert!(
        problems.is_empty(),
        "{} of {checked} documented ranges differ from the code:\n{}",
        problems.len(),
        problems.join("\n")
    );
}
