//! Which scene-file keys the panel edits: every panel declares, next to its widgets, the key path
//! each one edits (`water.material.absorption`, `light[].intensity`), and a test walks the keys of
//! a saved scene that sets every key, for every water model, against what the panel declared.
//!
//! Key paths are those of `docs/scene-format.md` as [`swell::scene::Scene::to_toml`] writes them:
//! tables joined with `.`, an array of tables written once as `name[]` (`light[]`,
//! `water.waves[]`), a vector or colour (an array of numbers) as one key. A declaration only
//! counts when the widget is really drawn (the branch of the model or light kind shown), so the
//! test sees what a user can reach.
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
}
