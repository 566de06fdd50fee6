//! Which scene-file keys the panel edits: every panel declares, next to its widgets, the key path
//! each one edits (`water.material.absorption`, `light[].intensity`), and a test walks the keys of
//! a saved scene that sets every key, for every water model, against what the panel declared.
//!
//! Key paths are those of `docs/scene-format.md` as [`swell::scene::Scene::to_toml`] writes them:
//! tables joined with `.`, an array of tables written once as `name[]` (`light[]`,
//! `water.waves[]`), a vector or colour (an array of numbers) as one key. A declaration only
//! counts when the widget is really drawn (the branch of the model or light kind shown), so the
//! test sees what a user can reach. A switch that adds or removes an optional table declares the
//! table's own path (`water.blender`): it is what edits the table while the file leaves it out.
//!
//! Recording is off outside [`recording`], where declaring costs one thread-local check.

use std::cell::RefCell;
use std::collections::BTreeSet;

thread_local! {
    /// The key paths declared since [`recording`] started, if it is running on this thread.
    static DECLARED: RefCell<Option<BTreeSet<String>>> = const { RefCell::new(None) };
}

/// Declares that the widgets being drawn edit `prefix.name` for each name (just `name` when
/// `prefix` is empty).
pub fn edits(prefix: &str, names: &[&str]) {
    DECLARED.with(|d| {
        if let Some(set) = d.borrow_mut().as_mut() {
            for name in names {
                set.insert(if prefix.is_empty() { (*name).to_owned() } else { format!("{prefix}.{name}") });
            }
        }
    });
}

/// Whether a [`recording`] is running on this thread (sections then open by default, so that
/// every widget is drawn).
pub fn is_recording() -> bool {
    DECLARED.with(|d| d.borrow().is_some())
}

/// Runs `f` (which shows panels) and returns what it returned with the key paths the panels
/// declared meanwhile.
pub fn recording<R>(f: impl FnOnce() -> R) -> (R, BTreeSet<String>) {
    let previous = DECLARED.with(|d| d.borrow_mut().replace(BTreeSet::new()));
    let out = f();
    let declared = DECLARED.with(|d| std::mem::replace(&mut *d.borrow_mut(), previous)).unwrap_or_default();
    (out, declared)
}

/// The key paths of a scene file's text, in the form panels declare them: every leaf of the
/// TOML document (a number, string, switch, or an array of numbers), arrays of tables as `name[]`.
pub fn key_paths(table: &toml::Table) -> BTreeSet<String> {
    let mut out = BTreeSet::new();
    walk("", table, &mut out);
    out
}

fn walk(prefix: &str, table: &toml::Table, out: &mut BTreeSet<String>) {
    for (k, v) in table {
        let path = if prefix.is_empty() { k.clone() } else { format!("{prefix}.{k}") };
        match v {
            toml::Value::Table(t) => walk(&path, t, out),
            toml::Value::Array(items) if !items.is_empty() && items.iter().all(toml::Value::is_table) => {
                for item in items {
                    if let toml::Value::Table(t) = item {
                        walk(&format!("{path}[]"), t, out);
                    }
                }
            }
            _ => {
                out.insert(path);
            }
        }
    }
}

/// Every key path of a scene, the ones its file leaves out at their defaults included, for the
/// key-coverage test.
///
/// A saved scene has only the keys that differ from their defaults (`extent`, `[water.lod]`,
/// `yaw_deg` and every unset optional key are left out), so its keys alone cannot show that a
/// key left at its default has a widget. This walks the scene's sections through their own serde
/// serialisation with a serialiser that records key paths instead of writing them, and that
/// also hears of the fields serde leaves out (`skip_serializing_if` calls
/// [`serde::ser::SerializeStruct::skip_field`]; an unset option arrives as `none`). A new key in
/// a scene type therefore shows up here whatever its value, without a list to keep.
#[cfg(test)]
pub(crate) mod format {
    use std::collections::BTreeSet;
    use std::fmt;

    use serde::ser::{self, Serialize};
    use swell::scene::Scene;

    /// The key paths of one scene, as [`super::key_paths`] spells them.
    #[derive(Clone, Debug, Default, PartialEq)]
    pub struct SceneKeys {
        /// Keys its file writes: [`super::key_paths`] of its TOML, exactly.
        pub written: BTreeSet<String>,
        /// Keys its file leaves out (at their defaults, or unset). A table left out whole
        /// (`water.lod`) is named alone: its own keys are not known until it is written.
        pub left_out: BTreeSet<String>,
    }

    impl SceneKeys {
        /// Whether `declared` (what the panel declared) covers `key`: the key itself, or for a
        /// table left out whole, a key inside it.
        pub fn covered(declared: &BTreeSet<String>, key: &str) -> bool {
            declared.contains(key)
                || declared.iter().any(|d| d.starts_with(&format!("{key}.")) || d.starts_with(&format!("{key}[].")))
        }
    }

    /// Walks every section of `scene` the way [`Scene::to_toml`] lays it out.
    pub fn scene_keys(scene: &Scene) -> SceneKeys {
        let mut out = SceneKeys::default();
        walk("version", &scene.version, &mut out);
        walk("camera", &scene.camera, &mut out);
        walk("light", &scene.lights, &mut out);
        walk("sky", &scene.sky, &mut out);
        walk("render", &scene.render, &mut out);
        if let Some(w) = &scene.water {
            // The model's keys and the patch's share `[water]`.
            walk("water", &w.model, &mut out);
            walk("water", &w.surface, &mut out);
            walk("water.material", &w.material, &mut out);
            // Not a serde field: the file writes it only when it is not sea water's.
            let density = "water.density".to_owned();
            if w.density == swell::body::SEA_WATER_DENSITY {
                out.left_out.insert(density);
            } else {
                out.written.insert(density);
            }
        }
        if let Some(t) = &scene.terrain {
            walk("terrain", &t.generator, &mut out);
            walk("terrain.size", &t.size, &mut out);
            walk("terrain.extent", &t.extent, &mut out);
            walk("terrain.transform", &t.transform, &mut out);
            walk("terrain.material", &t.material, &mut out);
            walk("terrain.far_land", &t.far_land, &mut out);
        }
        // `[[body]]`: the file leaves the list out when it is empty.
        if scene.bodies.is_empty() {
            out.left_out.insert("body".to_owned());
        } else {
            walk("body", &scene.bodies, &mut out);
        }
        out
    }

    fn walk<T: Serialize + ?Sized>(path: &str, value: &T, out: &mut SceneKeys) {
        value.serialize(Keys { path: path.to_owned(), out }).expect("the key walk accepts every value");
    }

    fn join(path: &str, key: &str) -> String {
        if path.is_empty() {
            key.to_owned()
        } else {
            format!("{path}.{key}")
        }
    }

    /// Never returned by the walk itself; serde's traits need an error type.
    #[derive(Debug)]
    pub struct WalkError(String);

    impl fmt::Display for WalkError {
        fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
            f.write_str(&self.0)
        }
    }

    impl std::error::Error for WalkError {}

    impl ser::Error for WalkError {
        fn custom<T: fmt::Display>(msg: T) -> Self {
            WalkError(msg.to_string())
        }
    }

    /// Serialises the value at `path`: a plain value is one key, a struct or map a table of keys.
    struct Keys<'a> {
        path: String,
        out: &'a mut SceneKeys,
    }

    impl Keys<'_> {
        fn leaf(self) -> Result<(), WalkError> {
            self.out.written.insert(self.path);
            Ok(())
        }
    }

    macro_rules! leaves {
        ($($method:ident($ty:ty)),+ $(,)?) => {
            $(fn $method(self, _: $ty) -> Result<(), WalkError> { self.leaf() })+
        };
    }

    impl<'a> ser::Serializer for Keys<'a> {
        type Ok = ();
        type Error = WalkError;
        type SerializeSeq = Items<'a>;
        type SerializeTuple = Items<'a>;
        type SerializeTupleStruct = Items<'a>;
        type SerializeTupleVariant = Items<'a>;
        type SerializeMap = Fields<'a>;
        type SerializeStruct = Fields<'a>;
        type SerializeStructVariant = Fields<'a>;

        leaves!(
            serialize_bool(bool),
            serialize_i8(i8),
            serialize_i16(i16),
            serialize_i32(i32),
            serialize_i64(i64),
            serialize_u8(u8),
            serialize_u16(u16),
            serialize_u32(u32),
            serialize_u64(u64),
            serialize_f32(f32),
            serialize_f64(f64),
            serialize_char(char),
            serialize_str(&str),
            serialize_bytes(&[u8]),
        );

        fn serialize_none(self) -> Result<(), WalkError> {
            // An unset option: TOML leaves the key out.
            self.out.left_out.insert(self.path);
            Ok(())
        }
        fn serialize_some<T: Serialize + ?Sized>(self, value: &T) -> Result<(), WalkError> {
            value.serialize(self)
        }
        fn serialize_unit(self) -> Result<(), WalkError> {
            self.leaf()
        }
        fn serialize_unit_struct(self, _: &'static str) -> Result<(), WalkError> {
            self.leaf()
        }
        fn serialize_unit_variant(self, _: &'static str, _: u32, _: &'static str) -> Result<(), WalkError> {
            self.leaf()
        }
        fn serialize_newtype_struct<T: Serialize + ?Sized>(self, _: &'static str, v: &T) -> Result<(), WalkError> {
            v.serialize(self)
        }
        fn serialize_newtype_variant<T: Serialize + ?Sized>(
            self,
            _: &'static str,
            _: u32,
            variant: &'static str,
            v: &T,
        ) -> Result<(), WalkError> {
            // TOML writes an externally tagged variant as `{ variant = value }`.
            v.serialize(Keys { path: join(&self.path, variant), out: self.out })
        }
        fn serialize_seq(self, _: Option<usize>) -> Result<Items<'a>, WalkError> {
            Ok(Items { path: self.path, out: self.out, items: SceneKeys::default() })
        }
        fn serialize_tuple(self, len: usize) -> Result<Items<'a>, WalkError> {
            self.serialize_seq(Some(len))
        }
        fn serialize_tuple_struct(self, _: &'static str, len: usize) -> Result<Items<'a>, WalkError> {
            self.serialize_seq(Some(len))
        }
        fn serialize_tuple_variant(
            self,
            _: &'static str,
            _: u32,
            variant: &'static str,
            _: usize,
        ) -> Result<Items<'a>, WalkError> {
            Ok(Items { path: join(&self.path, variant), out: self.out, items: SceneKeys::default() })
        }
        fn serialize_map(self, _: Option<usize>) -> Result<Fields<'a>, WalkError> {
            Ok(Fields { path: self.path, out: self.out, key: None })
        }
        fn serialize_struct(self, _: &'static str, _: usize) -> Result<Fields<'a>, WalkError> {
            Ok(Fields { path: self.path, out: self.out, key: None })
        }
        fn serialize_struct_variant(
            self,
            _: &'static str,
            _: u32,
            variant: &'static str,
            _: usize,
        ) -> Result<Fields<'a>, WalkError> {
            Ok(Fields { path: join(&self.path, variant), out: self.out, key: None })
        }
    }

    /// An array: of plain values (a vector, a colour) it is one key, as in [`super::key_paths`];
    /// of tables it is `path[]` with the keys of every entry.
    struct Items<'a> {
        path: String,
        out: &'a mut SceneKeys,
        items: SceneKeys,
    }

    impl Items<'_> {
        fn item<T: Serialize + ?Sized>(&mut self, v: &T) -> Result<(), WalkError> {
            v.serialize(Keys { path: format!("{}[]", self.path), out: &mut self.items })
        }
        fn finish(self) -> Result<(), WalkError> {
            let entry = format!("{}[]", self.path);
            let plain = |set: &BTreeSet<String>| set.iter().all(|k| *k == entry);
            if plain(&self.items.written) && plain(&self.items.left_out) {
                self.out.written.insert(self.path);
            } else {
                self.out.written.extend(self.items.written);
                self.out.left_out.extend(self.items.left_out);
            }
            Ok(())
        }
    }

    /// Sequences, tuples and tuple structs and variants are one list of items to the walk: the
    /// four serde traits differ only in their method's name.
    macro_rules! items_as {
        ($($tr:ident :: $method:ident),+ $(,)?) => {$(
            impl ser::$tr for Items<'_> {
                type Ok = ();
                type Error = WalkError;
                fn $method<T: Serialize + ?Sized>(&mut self, v: &T) -> Result<(), WalkError> {
                    self.item(v)
                }
                fn end(self) -> Result<(), WalkError> {
                    self.finish()
                }
            }
        )+};
    }
    items_as!(
        SerializeSeq::serialize_element,
        SerializeTuple::serialize_element,
        SerializeTupleStruct::serialize_field,
        SerializeTupleVariant::serialize_field,
    );

    /// A table: each field (or map entry) is a key under `path`; a field serde skips is recorded
    /// as left out.
    struct Fields<'a> {
        path: String,
        out: &'a mut SceneKeys,
        /// The map key whose value comes next.
        key: Option<String>,
    }

    impl Fields<'_> {
        fn field<T: Serialize + ?Sized>(&mut self, key: &str, v: &T) -> Result<(), WalkError> {
            v.serialize(Keys { path: join(&self.path, key), out: self.out })
        }
    }

    /// A struct and a struct variant's fields walk alike: each field under its key, a skipped
    /// one recorded as left out.
    macro_rules! fields_as {
        ($($tr:ident),+ $(,)?) => {$(
            impl ser::$tr for Fields<'_> {
                type Ok = ();
                type Error = WalkError;
                fn serialize_field<T: Serialize + ?Sized>(&mut self, key: &'static str, v: &T) -> Result<(), WalkError> {
                    self.field(key, v)
                }
                fn skip_field(&mut self, key: &'static str) -> Result<(), WalkError> {
                    // `skip_serializing_if` said the value is its default: the file leaves it out.
                    self.out.left_out.insert(join(&self.path, key));
                    Ok(())
                }
                fn end(self) -> Result<(), WalkError> {
                    Ok(())
                }
            }
        )+};
    }

    fields_as!(SerializeStruct, SerializeStructVariant);

    impl ser::SerializeMap for Fields<'_> {
        type Ok = ();
        type Error = WalkError;
        fn serialize_key<T: Serialize + ?Sized>(&mut self, key: &T) -> Result<(), WalkError> {
            let key = toml::Value::try_from(key).map_err(ser::Error::custom)?;
            self.key = Some(key.as_str().map_or_else(|| key.to_string(), str::to_owned));
            Ok(())
        }
        fn serialize_value<T: Serialize + ?Sized>(&mut self, v: &T) -> Result<(), WalkError> {
            let key = self.key.take().ok_or_else(|| ser::Error::custom("a map value without its key"))?;
            self.field(&key, v)
        }
        fn end(self) -> Result<(), WalkError> {
            Ok(())
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paths_flatten_tables_and_arrays_of_tables() {
        let t: toml::Table = toml::from_str(
            "version = 1\n[camera]\neye = [0.0, 1.0, 2.0]\n[[light]]\ntype = 'point'\n[[light]]\ncolor = [1.0, 1.0, 1.0]\n\
             [water]\ndispersion = { type = 'deep' }\n",
        )
        .unwrap();
        let paths: Vec<_> = key_paths(&t).into_iter().collect();
        assert_eq!(paths, ["camera.eye", "light[].color", "light[].type", "version", "water.dispersion.type"]);
        let ((), declared) = recording(|| {
            edits("sky", &["horizon", "zenith"]);
            edits("", &["version"]);
        });
        assert_eq!(declared.into_iter().collect::<Vec<_>>(), ["sky.horizon", "sky.zenith", "version"]);
        // Outside a recording nothing is kept.
        edits("sky", &["ground"]);
        assert!(recording(|| ()).1.is_empty());
    }

    #[test]
    fn the_walk_finds_the_keys_a_file_leaves_out_and_writes_the_others_as_the_file_does() {
        let mut scene = swell::scene::preset("sea").unwrap();
        let keys = format::scene_keys(&scene);
        let file: toml::Table = toml::from_str(&scene.to_toml()).unwrap();
        assert_eq!(keys.written, key_paths(&file));
        for left_out in ["water.extent", "water.lod", "water.yaw_deg", "render.gamma", "water.material.bottom_depth"] {
            assert!(keys.left_out.contains(left_out), "{left_out} in {:?}", keys.left_out);
        }
        // Set, they are written, and a table's own unset keys are then left out by name.
        let w = scene.water.as_mut().unwrap();
        w.surface.extent = Some(swell::scene::WaterExtent::Patch);
        w.surface.lod.levels = 4;
        let keys = format::scene_keys(&scene);
        assert_eq!(keys.written, key_paths(&toml::from_str(&scene.to_toml()).unwrap()));
        assert!(keys.written.contains("water.extent") && keys.written.contains("water.lod.levels"));
        assert!(keys.left_out.contains("water.lod.spacing") && !keys.left_out.contains("water.lod"));
        // Bodies and the water's density: left out while absent or at their defaults.
        assert!(keys.left_out.contains("body") && keys.left_out.contains("water.density"));
        scene.water.as_mut().unwrap().density = 1000.0;
        let mut crate_ = swell::body::BodySpec::new(swell::body::BodyShape::Box, &[1.0; 3], glam::Vec3::ZERO);
        crate_.mass = Some(300.0);
        scene.bodies.push(crate_);
        let keys = format::scene_keys(&scene);
        assert_eq!(keys.written, key_paths(&toml::from_str(&scene.to_toml()).unwrap()));
        for written in ["water.density", "body[].shape", "body[].size", "body[].mass", "body[].position"] {
            assert!(keys.written.contains(written), "{written} in {:?}", keys.written);
        }
        for left_out in ["body[].density", "body[].path", "body[].release_time", "body[].friction"] {
            assert!(keys.left_out.contains(left_out), "{left_out} in {:?}", keys.left_out);
        }
        let declared: BTreeSet<String> = ["water.lod.levels".to_owned()].into();
        assert!(format::SceneKeys::covered(&declared, "water.lod"));
        assert!(!format::SceneKeys::covered(&declared, "water.lo"));
    }
}
