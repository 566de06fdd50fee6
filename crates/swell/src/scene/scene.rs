//! The scene file: a versioned TOML document composing every part of a frame.

use serde::{Deserialize, Serialize};

use super::water_spec::{deserialize_at, WaterSpec};
use super::TerrainSpec;
use super::{Camera, Light, RenderSettings, Sky};
use crate::body::BodySpec;
use crate::error::{Error, Result};

/// The scene-file format version this build reads and writes.
pub const SCENE_VERSION: u32 = 1;

/// Most lights a scene may have.
pub const MAX_LIGHTS: usize = 16;

/// Everything needed to simulate and render: camera, lights, sky, water and render settings.
///
/// Read with [`Scene::from_toml`], written with [`Scene::to_toml`]; `docs/scene-format.md` lists
/// every key with its unit, default and range.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    /// File-format version; must be [`SCENE_VERSION`] (the default when a file leaves it out).
    pub version: u32,
    /// The camera; [`Camera::default`] when a file has no `[camera]` (a water-only scene for a
    /// bake, an export or `swell stats`, which need none).
    pub camera: Camera,
    /// Light sources, 0 to [`MAX_LIGHTS`]; `[[light]]` in the file.
    pub lights: Vec<Light>,
    /// The sky.
    pub sky: Sky,
    /// The water body, if any.
    pub water: Option<WaterSpec>,
    /// The terrain, if any; `[terrain]` in the file.
    pub terrain: Option<TerrainSpec>,
    /// Image settings.
    pub render: RenderSettings,
    /// Floating bodies, 0 to [`crate::body::MAX_BODIES`]; `[[body]]` in the file.
    pub bodies: Vec<BodySpec>,
}

/// The scene's sections other than `[water]`, which needs a two-step read (model first).
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct SceneFile {
    #[serde(default = "current_version")]
    version: u32,
    #[serde(default)]
    camera: Camera,
    #[serde(default, rename = "light")]
    lights: Vec<Light>,
    #[serde(default)]
    sky: Sky,
    #[serde(default)]
    render: RenderSettings,
    #[serde(default, rename = "body", skip_serializing_if = "Vec::is_empty")]
    bodies: Vec<BodySpec>,
}

/// A scene with nothing in it but `bodies`: what a `[[body]]` snippet read alone must equal once
/// its body is taken out ([`Scene::body_from_toml`]), and the text a scene's bodies are written in
/// before a snippet. Parsed rather than built field by field, so that a section added to `Scene`
/// later still gets its default here.
fn bodies_only(bodies: Vec<BodySpec>) -> Scene {
    let mut scene =
        Scene::from_toml("[[body]]\nshape = 'sphere'\nsize = [1.0]\n", "reference").expect("a valid one-body scene");
    scene.bodies = bodies;
    scene
}

/// `version` when a file leaves it out: the current one.
fn current_version() -> u32 {
    SCENE_VERSION
}

/// Rewrites every float of `table` (nested tables and arrays included) that is exactly an `f32` as
/// the `f64` of that `f32`'s shortest decimal form, so that a saved `near = 0.1` is written as
/// `0.1`, not `0.10000000149011612` (the `f64` serde widens the `f32` to).
///
/// Reading the shortest form back as `f32` gives the same `f32` bits (shortest round-trip
/// formatting guarantees it), so the scene loads back equal. A float that is not exactly an `f32`
/// (an `f64` parameter) is left as it is.
fn shortest_floats(table: &mut toml::Table) {
    table.iter_mut().for_each(|(_, v)| shortest_float(v));
}

/// [`shortest_floats`] for one value.
fn shortest_float(value: &mut toml::Value) {
    match value {
        toml::Value::Float(x) => {
            let single = *x as f32;
            if single.is_finite() && f64::from(single) == *x {
                // `Display` of an f32 is its shortest decimal that reads back to the same f32.
                if let Ok(short) = single.to_string().parse::<f64>() {
                    *x = short;
                }
            }
        }
        toml::Value::Array(items) => items.iter_mut().for_each(shortest_float),
        toml::Value::Table(t) => shortest_floats(t),
        _ => {}
    }
}

impl Scene {
    /// Parses and validates a scene; `source` (a path or `preset NAME`) is named in errors.
    pub fn from_toml(text: &str, source: &str) -> Result<Self> {
        // Size and nesting are checked before parsing, so hostile text cannot exhaust the stack.
        crate::limits::check_scene_text(text, source)?;
        let mut table: toml::Table = toml::from_str(text)
            .map_err(|e| Error::Parse { path: source.into(), message: e.to_string().trim_end().into() })?;
        if !table.values().any(|v| v.is_table() || v.is_array()) {
            // Every table has a default, but a file with none is a mistake (a wrong path, an
            // emptied file), not a request for an empty sky.
            return Err(Error::Parse {
                path: source.into(),
                message: "the scene is empty: give at least one table, such as [water] or [terrain]".into(),
            });
        }
        let water = match table.remove("water") {
            Some(toml::Value::Table(t)) => Some(WaterSpec::from_table(t, source)?),
            Some(other) => {
                return Err(Error::Parse {
                    path: source.into(),
                    message: format!("water must be a table ([water]), found a {}", other.type_str()),
                })
            }
            None => None,
        };
        let terrain = match table.remove("terrain") {
            Some(toml::Value::Table(t)) => Some(TerrainSpec::from_table(t, source)?),
            Some(other) => {
                return Err(Error::Parse {
                    path: source.into(),
                    message: format!("terrain must be a table ([terrain]), found a {}", other.type_str()),
                })
            }
            None => None,
        };
        let file: SceneFile = deserialize_at(table, "", source)?;
        let scene = Scene {
            version: file.version,
            camera: file.camera,
            lights: file.lights,
            sky: file.sky,
            water,
            terrain,
            render: file.render,
            bodies: file.bodies,
        };
        scene.validate().map_err(|e| e.in_source(source))?;
        Ok(scene)
    }

    /// Reads, parses and validates the scene file `path`: the one loader of the CLI, the viewer and
    /// the Python package.
    ///
    /// At most [`crate::limits::MAX_SCENE_BYTES`] are read (one byte past it is enough to refuse a
    /// huge file or `/dev/zero`), nesting is bounded before parsing ([`Scene::from_toml`]), and
    /// relative file paths in the scene (heightmaps, water textures) are resolved against the
    /// scene file's directory, made absolute so that the scene still finds them once saved
    /// elsewhere (the viewer's "save as"). The file is opened by [`crate::io::read_input`]: a FIFO
    /// that no process writes to is refused at once instead of blocking, while a pipe with a
    /// writer (`<(...)`, `/dev/stdin`) is read as a file. Errors name the file.
    pub fn load(path: &std::path::Path) -> Result<Self> {
        let bytes = crate::io::read_input(path, crate::limits::MAX_SCENE_BYTES)?;
        let dir = path.parent().unwrap_or(std::path::Path::new(""));
        Scene::from_bytes(bytes, &path.display().to_string(), dir)
    }

    /// The scene in `bytes`, read from `source` (a file path, or the CLI's standard input), with
    /// relative file paths resolved against `dir` (the current directory if `dir` is empty) and
    /// made absolute: what [`Scene::load`] does once it has read the file, for a caller that read
    /// the text itself. Refuses more than [`crate::limits::MAX_SCENE_BYTES`] (a reader that stops
    /// one byte past the limit hands all it read, and is refused here) and text that is not UTF-8.
    pub fn from_bytes(bytes: Vec<u8>, source: &str, dir: &std::path::Path) -> Result<Self> {
        let max = crate::limits::MAX_SCENE_BYTES;
        if bytes.len() as u64 > max {
            return Err(Error::Parse {
                path: source.into(),
                message: format!("over the scene-file limit of {max} bytes (MAX_SCENE_BYTES)"),
            });
        }
        let text = String::from_utf8(bytes).map_err(|_| Error::Parse {
            path: source.into(),
            message: "not UTF-8 text (a scene file is TOML)".into(),
        })?;
        let mut scene = Scene::from_toml(&text, source)?;
        let dir = if dir.as_os_str().is_empty() { std::path::Path::new(".") } else { dir };
        // `absolute` only fails without a current directory; the relative directory then still
        // resolves the paths for this process.
        let dir = std::path::absolute(dir).unwrap_or_else(|_| dir.to_path_buf());
        scene.resolve_paths(&dir);
        Ok(scene)
    }

    /// Writes the scene as TOML that [`Scene::from_toml`] reads back to an equal scene.
    pub fn to_toml(&self) -> String {
        let file = SceneFile {
            version: self.version,
            camera: self.camera,
            lights: self.lights.clone(),
            sky: self.sky,
            render: self.render,
            bodies: self.bodies.clone(),
        };
        let mut table = toml::Table::try_from(&file).expect("scene sections serialise to TOML");
        if let Some(w) = &self.water {
            table.insert("water".into(), toml::Value::Table(w.to_table()));
        }
        if let Some(t) = &self.terrain {
            table.insert("terrain".into(), toml::Value::Table(t.to_table()));
        }
        shortest_floats(&mut table);
        toml::to_string_pretty(&table).expect("a TOML table always serialises")
    }

    /// Checks every value against its range, then the memory the whole scene would take, without
    /// building a model or allocating anything large; the error names the key path, value and
    /// range. [`crate::world::World::new`] then builds each model once.
    pub fn validate(&self) -> Result<()> {
        if self.version != SCENE_VERSION {
            return Err(Error::out_of_range(
                "version",
                self.version,
                format!("[{SCENE_VERSION}, {SCENE_VERSION}] (this build reads version {SCENE_VERSION})"),
            ));
        }
        self.camera.validate("camera")?;
        if self.lights.len() > MAX_LIGHTS {
            return Err(Error::out_of_range(
                "light",
                format!("{} lights", self.lights.len()),
                format!("[0, {MAX_LIGHTS}] lights"),
            ));
        }
        for (i, l) in self.lights.iter().enumerate() {
            l.validate(&format!("light[{i}]"))?;
        }
        self.sky.validate("sky")?;
        self.render.validate("render")?;
        if let Some(w) = &self.water {
            w.validate()?;
        }
        if let Some(t) = &self.terrain {
            t.validate()?;
        }
        crate::body::validate_bodies(&self.bodies)?;
        // Every size is in range on its own; their sum must also fit before anything is allocated.
        crate::limits::check_memory("scene (water grid + terrain + framebuffer)", self.estimate_bytes())?;
        Ok(())
    }

    /// How far the scene's water reaches as far as the scene alone tells: its `[water] extent`,
    /// else the default for water no terrain holds ([`super::WaterExtent::default_for`]).
    /// With terrain and no key, whether the terrain holds the water is known only once it is
    /// built: [`crate::world::WaterBody::extent`] is the extent drawn, and this is the widest
    /// it can be (what the memory estimate counts). `None` without water.
    pub fn water_extent(&self) -> Option<super::WaterExtent> {
        let w = self.water.as_ref()?;
        Some(w.surface.extent.unwrap_or_else(|| super::WaterExtent::default_for(&w.model, false)))
    }

    /// The one `[[body]]` table of `text` (header included, as a scene file holds it), read as
    /// body number `k = self.bodies.len()` of this scene, `source` naming the text in errors: what
    /// the C API and the Python package take to add a body. Refuses text with no `[[body]]`,
    /// several, or other sections. Key errors name the key as this scene would once the body is
    /// in it (`body[3].size`); TOML syntax errors count the lines of `text`. Relative paths are
    /// left as given.
    pub fn body_from_toml(&self, text: &str, source: &str) -> Result<BodySpec> {
        let k = self.bodies.len();
        let first = match Scene::from_toml(text, source) {
            Ok(mut own) => {
                let n = own.bodies.len();
                let spec = own.bodies.pop();
                own.bodies.clear();
                let alone = own == bodies_only(Vec::new());
                return match spec {
                    Some(spec) if n == 1 && alone => Ok(spec),
                    _ => Err(Error::Parse {
                        path: source.into(),
                        message: format!(
                            "holds {n} [[body]] table{}{}; give exactly one [[body]] table (its header and keys) and nothing else",
                            if n == 1 { "" } else { "s" },
                            if alone { "" } else { " and other sections" }
                        ),
                    }),
                };
            }
            Err(e) => e,
        };
        // Read alone, the snippet's body is body[0]: read it again after this scene's bodies so
        // that a key error names body[k], the body it would be. That reading is used only when it
        // names body[k] (a snippet that also holds other keys could be read differently there).
        if k > 0 && first.to_string().contains("body[0]") {
            let after = format!("{}\n{text}", bodies_only(self.bodies.clone()).to_toml());
            if let Err(e) = Scene::from_toml(&after, source) {
                if e.to_string().contains(&format!("body[{k}]")) {
                    return Err(e);
                }
            }
        }
        Err(first)
    }

    /// Makes relative file paths in the scene (heightmaps, water textures, spectrum files) relative to `dir`, the
    /// directory of the scene file they were written in.
    pub fn resolve_paths(&mut self, dir: &std::path::Path) {
        for b in &mut self.bodies {
            b.resolve_paths(dir);
        }
        if let Some(t) = &mut self.terrain {
            t.resolve_paths(dir);
        }
        if let Some(w) = &mut self.water {
            w.material.resolve_paths(dir);
            if let super::WaterModelSpec::Fft(p) = &mut w.model {
                p.resolve_paths(dir);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const MINIMAL: &str = "version = 1\n[camera]\neye = [0.0, 5.0, 10.0]\ntarget = [0.0, 0.0, 0.0]\n";

    #[test]
    fn a_minimal_scene_gets_defaults() {
        let s = Scene::from_toml(MINIMAL, "t").unwrap();
        assert_eq!(s.render.width, 1280);
        assert!(s.water.is_none());
        assert_eq!(s.camera.fov_y_deg, 45.0);
    }

    #[test]
    fn a_water_only_scene_parses_and_an_empty_one_is_refused() {
        let s = Scene::from_toml("[water]\nmodel = 'fft'\n", "t").unwrap();
        assert_eq!((s.version, s.camera), (SCENE_VERSION, Camera::default()));
        assert!(s.water.is_some());
        for text in ["# nothing\n", "version = 1\n"] {
            let e = Scene::from_toml(text, "empty.toml").unwrap_err().to_string();
            assert!(e.starts_with("empty.toml: the scene is empty"), "{e}");
        }
    }

    #[test]
    fn bad_input_names_key_value_and_range() {
        let e = Scene::from_toml(&format!("{MINIMAL}[render]\nwidth = 0\n"), "t.toml").unwrap_err();
        assert_eq!(e.to_string(), "t.toml: render.width = 0 is outside [1, 16384]");
        assert_eq!(e.without_source().to_string(), "render.width = 0 is outside [1, 16384]");
        let e = Scene::from_toml(&format!("{MINIMAL}[render]\nwidht = 5\n"), "t").unwrap_err();
        assert!(e.to_string().contains("unknown field `widht`"), "{e}");
        let e =
            Scene::from_toml(&format!("{MINIMAL}[[light]]\ntype = 'directional'\ndirection = [0.0, 'a', 0.0]\n"), "t")
                .unwrap_err();
        assert!(e.to_string().contains("light[0]"), "{e}");
        let e = Scene::from_toml("version = 2\n[camera]\neye = [0.0, 5.0, 10.0]\ntarget = [0.0, 0.0, 0.0]\n", "t")
            .unwrap_err();
        assert!(e.to_string().starts_with("t: version = 2 is outside"), "{e}");
        let e = Scene::from_toml("version = 1\n[camera\n", "f.toml").unwrap_err();
        assert!(e.to_string().starts_with("f.toml: TOML parse error"), "{e}");
        let e = Scene::from_toml(&format!("{MINIMAL}[render]\nexposure = nan\n"), "t").unwrap_err();
        assert!(e.to_string().starts_with("t: render.exposure = NaN"), "{e}");
    }

    /// serde would read a table written as an array field by position; a scene file names its
    /// fields (issue 37), at any depth: a section, a nested table, an element of an array.
    #[test]
    fn tables_written_as_arrays_are_refused_naming_the_key() {
        let cases = [
            ("[water]\nmodel = 'fft'\nextent = 'unbounded'\nlod = [4, 96, 0.5]\n", "water.lod"),
            ("camera = [[0.0, 5.0, 10.0], [0.0, 0.0, 0.0], [0.0, 1.0, 0.0], 45.0, 0.1, 1000.0]\n[water]\nmodel = 'fft'\n", "camera"),
            ("[water]\nmodel = 'fft'\nmaterial = [[0.0, 0.1, 0.2]]\n", "water.material"),
            ("[water]\nmodel = 'gerstner'\nwaves = [[0.5, 20.0, 5.0, [1.0, 0.0], 0.5]]\n", "water.waves[0]"),
        ];
        for (text, key) in cases {
            let e = Scene::from_toml(text, "t").unwrap_err().to_string();
            assert!(e.starts_with(&format!("t: {key}: must be a table")), "{text}: {e}");
        }
        // Arrays that are arrays stay arrays, and every preset still reads.
        for p in crate::scene::PRESETS {
            let text = crate::scene::preset(p.name).unwrap().to_toml();
            Scene::from_toml(&text, p.name).unwrap();
        }
    }

    /// Every float of a saved scene is written in its shortest form: no `0.10000000149011612`.
    #[test]
    fn saved_floats_are_shortest_and_load_back_equal() {
        let mut s = Scene::from_toml(MINIMAL, "t").unwrap();
        s.camera.near = 0.1;
        s.camera.fov_y_deg = 33.3;
        s.render.exposure = 1.7;
        let text = s.to_toml();
        assert!(text.contains("near = 0.1\n"), "{text}");
        assert!(text.contains("fov_y_deg = 33.3\n"), "{text}");
        assert_eq!(Scene::from_toml(&text, "t").unwrap(), s);
        for p in super::super::PRESETS {
            let scene = super::super::preset(p.name).unwrap();
            let text = scene.to_toml();
            assert_eq!(Scene::from_toml(&text, "t").unwrap(), scene, "preset {}", p.name);
            // Float noise: 8 or more significant digits after the point, as an f32 widened to
            // f64 prints (0.10000000149011612), never a shortest f32 form (at most 9, rarely).
            for line in text.lines() {
                for number in line.split(|c: char| !(c.is_ascii_digit() || c == '.')) {
                    let decimals = number.split_once('.').map_or(0, |(_, d)| d.len());
                    assert!(decimals < 10, "preset {}: float noise in `{line}`", p.name);
                }
            }
        }
    }
}
