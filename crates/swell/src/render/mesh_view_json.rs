//! The JSON camera and light files of the OBJ comparison mode (`swell render --obj M --camera
//! C.json --light L.json`), read here rather than in the CLI so that the fuzz targets
//! (`fuzz/fuzz_targets/mesh_view_json.rs`) exercise exactly what users' files go through.
//!
//! Both files are single JSON objects with a fixed set of keys (documented in
//! `docs/scene-format.md`, "OBJ comparison mode"); an unknown key, a wrong type, a non-finite or
//! out-of-range value is an error naming the file and the key. The text is at most
//! [`MAX_VIEW_JSON_BYTES`]; serde_json refuses nesting past 128 levels, so no input can overflow
//! the stack.

use glam::Vec3;
use serde_json::{Map, Value};

use super::MeshLight;
use crate::error::{Error, Result};
use crate::scene::{Camera, MAX_IMAGE_SIDE};

/// Most bytes of a camera or light JSON file: 1 MiB. A real one is under 300 bytes.
pub const MAX_VIEW_JSON_BYTES: u64 = 1 << 20;

/// A camera file: the camera and the image size it is meant for.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeshView {
    /// The camera, validated.
    pub camera: Camera,
    /// Image width, pixels, in [1, [`MAX_IMAGE_SIDE`]].
    pub width: u32,
    /// Image height, pixels, in [1, [`MAX_IMAGE_SIDE`]].
    pub height: u32,
}

/// Parses a camera file: `eye`, `target` (`[x, y, z]`, metres, required), `up` (default +Y),
/// `fov_y_deg` (default 45), `near` (default 0.1 m), `far` (default 5000 m), `width`, `height`
/// (whole pixels in [1, 16384], required). `source` names the file in errors.
pub fn parse_camera_json(text: &str, source: &str) -> Result<MeshView> {
    let keys = ["eye", "target", "up", "fov_y_deg", "near", "far", "width", "height"];
    let map = parse_object(text, source, &keys)?;
    let missing = |k: &str| Error::Parse { path: source.into(), message: format!("{k} is missing") };
    let mut camera = Camera {
        eye: vec3(&map, "eye", source, false)?.ok_or_else(|| missing("eye"))?,
        target: vec3(&map, "target", source, false)?.ok_or_else(|| missing("target"))?,
        up: Vec3::Y,
        fov_y_deg: 45.0,
        near: 0.1,
        far: 5000.0,
    };
    if let Some(up) = vec3(&map, "up", source, false)? {
        camera.up = up;
    }
    for (key, field) in [("fov_y_deg", &mut camera.fov_y_deg), ("near", &mut camera.near), ("far", &mut camera.far)] {
        if let Some(v) = number(&map, key, source)? {
            *field = v as f32;
        }
    }
    camera.validate("camera")?;
    let side = |k: &str| -> Result<u32> {
        let v = number(&map, k, source)?.ok_or_else(|| missing(k))?;
        if v.fract() != 0.0 || !(1.0..=MAX_IMAGE_SIDE as f64).contains(&v) {
            return Err(Error::out_of_range(format!("camera.{k}"), v, format!("[1, {MAX_IMAGE_SIDE}] (whole pixels)")));
        }
        Ok(v as u32)
    };
    Ok(MeshView { camera, width: side("width")?, height: side("height")? })
}

/// Parses a light file: `dir` (`[x, y, z]`, the direction light travels, non-zero), `color`,
/// `ambient`, `base_color`, `background` (linear RGB `[r, g, b]`, `[r, g, b, a]` with alpha ignored,
/// or one number for grey; each >= 0). Every key is optional ([`MeshLight::default`]).
pub fn parse_light_json(text: &str, source: &str) -> Result<MeshLight> {
    let map = parse_object(text, source, &["dir", "color", "ambient", "base_color", "background"])?;
    let d = MeshLight::default();
    let light = MeshLight {
        dir: vec3(&map, "dir", source, false)?.unwrap_or(d.dir),
        color: vec3(&map, "color", source, true)?.unwrap_or(d.color),
        ambient: vec3(&map, "ambient", source, true)?.unwrap_or(d.ambient),
        base_color: vec3(&map, "base_color", source, true)?.unwrap_or(d.base_color),
        background: vec3(&map, "background", source, true)?.unwrap_or(d.background),
    };
    light.validate("light")?;
    Ok(light)
}

/// A JSON object within the size limit, refusing keys outside `allowed`.
fn parse_object(text: &str, source: &str, allowed: &[&str]) -> Result<Map<String, Value>> {
    let parse_err = |message: String| Error::Parse { path: source.into(), message };
    if text.len() as u64 > MAX_VIEW_JSON_BYTES {
        return Err(parse_err(format!(
            "{} bytes is over the camera/light file limit of {MAX_VIEW_JSON_BYTES} bytes (MAX_VIEW_JSON_BYTES)",
            text.len()
        )));
    }
    let value: Value = serde_json::from_str(text).map_err(|e| parse_err(e.to_string()))?;
    let Value::Object(map) = value else { return Err(parse_err("must be a JSON object {...}".into())) };
    if let Some(k) = map.keys().find(|k| !allowed.contains(&k.as_str())) {
        return Err(parse_err(format!("unknown key `{k}`; valid: {}", allowed.join(", "))));
    }
    Ok(map)
}

/// A number, `[x, y, z]` or `[r, g, b, a]` (alpha ignored); a single number `c` means `[c, c, c]`
/// where `scalar_ok`. Numbers past f32's range become infinite here and are refused by the
/// caller's `validate`.
fn vec3(map: &Map<String, Value>, key: &str, source: &str, scalar_ok: bool) -> Result<Option<Vec3>> {
    let bad = || Error::Parse {
        path: source.into(),
        message: format!("{key} must be [x, y, z]{}", if scalar_ok { " or a number" } else { "" }),
    };
    match map.get(key) {
        None => Ok(None),
        Some(Value::Number(n)) if scalar_ok => Ok(Some(Vec3::splat(n.as_f64().ok_or_else(bad)? as f32))),
        Some(Value::Array(a)) if a.len() == 3 || a.len() == 4 => {
            let c: Vec<f32> = a.iter().map(|v| v.as_f64().map(|f| f as f32)).collect::<Option<_>>().ok_or_else(bad)?;
            Ok(Some(Vec3::new(c[0], c[1], c[2])))
        }
        Some(_) => Err(bad()),
    }
}

fn number(map: &Map<String, Value>, key: &str, source: &str) -> Result<Option<f64>> {
    match map.get(key) {
        None => Ok(None),
        Some(v) => v
            .as_f64()
            .map(Some)
            .ok_or_else(|| Error::Parse { path: source.into(), message: format!("{key} must be a number") }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn camera_and_light_files_read_with_defaults_and_name_bad_keys() {
        let v = parse_camera_json(r#"{"eye":[0,1,5],"target":[0,0,0],"width":64,"height":32}"#, "c.json").unwrap();
        assert_eq!((v.width, v.height, v.camera.up, v.camera.fov_y_deg), (64, 32, Vec3::Y, 45.0));
        let l = parse_light_json(r#"{"color":0.5,"background":[0.1,0.2,0.3,1]}"#, "l.json").unwrap();
        assert_eq!((l.color, l.background), (Vec3::splat(0.5), Vec3::new(0.1, 0.2, 0.3)));
        for (text, want) in [
            (r#"{"eye":[0,1,5],"target":[0,0,0],"width":64}"#, "height is missing"),
            (r#"{"eye":[0,1,5],"target":[0,0,0],"width":64.5,"height":2}"#, "camera.width = 64.5"),
            (r#"{"eye":[0,1,5],"target":[0,0,0],"width":64,"height":2,"zoom":1}"#, "unknown key `zoom`"),
            (r#"{"eye":[0,1],"target":[0,0,0],"width":64,"height":2}"#, "eye must be [x, y, z]"),
            (r#"{"eye":[0,1,1e39],"target":[0,0,0],"width":64,"height":2}"#, "camera.eye"),
            (r#"{"eye":[3e38,0,0],"target":[-3e38,0,0],"width":64,"height":2}"#, "camera"),
            ("[1,2]", "must be a JSON object"),
        ] {
            let e = parse_camera_json(text, "c.json").unwrap_err().to_string();
            assert!(e.contains("c.json") || e.contains("camera."), "{e}");
            assert!(e.contains(want), "{text}: {e}");
        }
        let e = parse_light_json(r#"{"dir":[0,0,0]}"#, "l.json").unwrap_err().to_string();
        assert!(e.contains("light.dir"), "{e}");
        let e = parse_light_json(r#"{"color":-1}"#, "l.json").unwrap_err().to_string();
        assert!(e.contains("light.color[0]"), "{e}");
        let deep = format!("{}{}", "[".repeat(100_000), "]".repeat(100_000));
        assert!(parse_light_json(&deep, "l.json").is_err());
    }
}
