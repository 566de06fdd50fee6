//! `swell.World`: a scene's water and floating bodies (issue 34) stepped in time, the Python face
//! of the library's [`swell::world::World`] as `SwellScene` is its C face (crates/swell-capi): the
//! same bodies float the same way from both (the tests hold both to the Rust library's poses).

use std::path::PathBuf;
use std::sync::{Mutex, MutexGuard};

use glam::DVec3;
use numpy::{IntoPyArray, PyArray2, PyArrayMethods};
use pyo3::exceptions::{PyIndexError, PyKeyError, PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};
use swell::error::Human;
use swell::limits::MAX_TIME_S;
use swell::scene::Scene;

use super::{locked, py_err, SOURCE};

/// A scene built and stepped in time: its water and its floating bodies (`[[body]]`), which ride
/// the water the scene draws, stepped at a fixed 120 Hz whatever times are asked.
///
/// `advance(t)` moves it to `t` (s); `positions` and `rotations` are then the bodies' poses at
/// `t`. Calls on one object from several threads are serialised by a lock inside it.
#[pyclass(frozen, module = "swell")]
pub(crate) struct World {
    inner: Mutex<swell::world::World>,
}

/// Refuses a time the bodies cannot be asked for, with the C API's message: not finite, before
/// t = 0 (when the bodies start) or past `MAX_TIME_S`.
fn check_body_time(t: f64) -> PyResult<()> {
    if t.is_finite() && (0.0..=MAX_TIME_S).contains(&t) {
        return Ok(());
    }
    let range = format!("[0, {MAX_TIME_S:e}] seconds (floating bodies start at t = 0)");
    Err(py_err(swell::Error::out_of_range("t", Human(t), range)))
}

/// A keyword argument of `add_body` as a TOML value, `key` naming it in errors: booleans,
/// integers, floats, strings, paths (`os.PathLike`) and lists, tuples or numpy arrays of them.
fn toml_value(key: &str, v: &Bound<'_, PyAny>) -> PyResult<toml::Value> {
    let py = v.py();
    if v.is_instance_of::<PyBool>() {
        return Ok(toml::Value::Boolean(v.extract()?));
    }
    if v.is_instance_of::<PyString>() {
        return Ok(toml::Value::String(v.extract()?));
    }
    if v.is_instance_of::<PyInt>() {
        return Ok(toml::Value::Integer(v.extract()?));
    }
    if v.is_instance_of::<PyFloat>() {
        return Ok(toml::Value::Float(v.extract()?));
    }
    if v.hasattr("__fspath__")? {
        let path = py.import("os")?.call_method1("fspath", (v,))?;
        return toml_value(key, &path);
    }
    // numpy arrays and scalars (float32, int64, ...): as the Python values they stand for.
    if v.hasattr("tolist")? {
        let plain = v.call_method0("tolist")?;
        if !plain.is(v) && !plain.hasattr("tolist")? {
            return toml_value(key, &plain);
        }
    }
    if v.is_instance_of::<PyList>() || v.is_instance_of::<PyTuple>() {
        let items = v.try_iter()?.enumerate().map(|(i, item)| toml_value(&format!("{key}[{i}]"), &item?));
        return Ok(toml::Value::Array(items.collect::<PyResult<_>>()?));
    }
    let kind = v.get_type().name()?.to_string();
    Err(PyTypeError::new_err(format!(
        "{key}: a value of type {} is not one a [[body]] key takes; give numbers, strings, paths or lists of them",
        swell::error::printable(&kind)
    )))
}

/// `rows` as a float64 array of shape (len, width).
fn rows_array<'py, const W: usize>(py: Python<'py>, rows: Vec<[f64; W]>) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let n = rows.len();
    rows.into_iter().flatten().collect::<Vec<f64>>().into_pyarray(py).reshape([n, W])
}

impl World {
    fn lock(&self) -> MutexGuard<'_, swell::world::World> {
        locked(&self.inner)
    }

    /// The index of `body`: an int in [0, len) or a name.
    fn resolve(&self, body: &Bound<'_, PyAny>) -> PyResult<usize> {
        let w = self.lock();
        let bodies = w.bodies.bodies();
        if body.is_instance_of::<PyString>() {
            let name: String = body.extract()?;
            return bodies.iter().position(|b| b.name == name).ok_or_else(|| {
                let shown = swell::error::printable(&name);
                PyKeyError::new_err(format!("body: \"{shown}\" names none of the world's {} bodies", bodies.len()))
            });
        }
        if body.is_instance_of::<PyBool>() || !body.hasattr("__index__")? {
            let kind = body.get_type().name()?.to_string();
            return Err(PyTypeError::new_err(format!("body: a {kind} is not a body's index or name")));
        }
        let k: i128 = body.call_method0("__index__")?.extract()?;
        match usize::try_from(k) {
            Ok(k) if k < bodies.len() => Ok(k),
            _ => Err(PyIndexError::new_err(format!("body: {k} is outside [0, {}) (the world's bodies)", bodies.len()))),
        }
    }

    /// The poses at the world's time (`World::body_poses`), each as `pick` takes it, checked
    /// finite: no NaN is ever handed out (the library checks every step's state; a pose between
    /// steps is integrated on from it).
    fn poses<const W: usize>(&self, pick: impl Fn(&swell::body::BodyPose) -> [f64; W]) -> PyResult<Vec<[f64; W]>> {
        let w = self.lock();
        let rows: Vec<[f64; W]> = w.body_poses().iter().map(pick).collect();
        if rows.len() != w.bodies.len() || !rows.iter().flatten().all(|v| v.is_finite()) {
            return Err(PyValueError::new_err(format!(
                "simulation unstable: the bodies' poses at t = {} s are not finite numbers",
                Human(w.time())
            )));
        }
        Ok(rows)
    }
}

#[pymethods]
impl World {
    /// Builds a scene's TOML text (water, terrain, `[[body]]`s) at t = 0; relative mesh and
    /// heightmap paths are relative to the working directory. Raises ValueError with the CLI's
    /// message for bad input.
    #[staticmethod]
    fn from_toml(py: Python<'_>, text: &str) -> PyResult<Self> {
        let world =
            py.allow_threads(|| Scene::from_toml(text, SOURCE).and_then(swell::world::World::new)).map_err(py_err)?;
        Ok(Self { inner: Mutex::new(world) })
    }

    /// Reads a scene file (relative mesh and heightmap paths are relative to it) and builds it.
    #[staticmethod]
    fn from_file(py: Python<'_>, path: PathBuf) -> PyResult<Self> {
        let world = py.allow_threads(|| Scene::load(&path).and_then(swell::world::World::new)).map_err(py_err)?;
        Ok(Self { inner: Mutex::new(world) })
    }

    /// How many floating bodies the world has, added ones included.
    fn __len__(&self) -> usize {
        self.lock().bodies.len()
    }

    /// The bodies' names, in body order (an unnamed `[[body]]` is `body<index>`).
    #[getter]
    fn names(&self) -> Vec<String> {
        self.lock().bodies.bodies().iter().map(|b| b.name.clone()).collect()
    }

    /// The index of the body named `name`; KeyError if none is.
    fn index(&self, name: Bound<'_, PyString>) -> PyResult<usize> {
        self.resolve(name.as_any())
    }

    /// The time (s) the world was last moved to: that of `positions` and `rotations`.
    #[getter]
    fn time(&self) -> f64 {
        self.lock().time()
    }

    /// Moves the world to time `t` (s, in [0, 1e7]): the bodies step at 120 Hz up to `t`, each
    /// step on the water at that step's time, and the water moves to `t`. The poses do not depend
    /// on the frame rate (`t` reached in one call or in 60 fps steps gives the same numbers). A
    /// `t` before the world's time replays from t = 0 (added bodies held until their release,
    /// thrusts as they are now), costing the steps from 0 to `t`; each step moves the water model
    /// to its time (for the FFT ocean, one synthesis a step). ValueError for a bad `t` or a body
    /// that left the finite numbers (the bodies are then back at t = 0).
    fn advance(&self, py: Python<'_>, t: f64) -> PyResult<()> {
        check_body_time(t)?;
        py.allow_threads(|| self.lock().advance(t)).map_err(py_err)
    }

    /// Every body's centre of mass at the world's `time`, world metres: float64 (len, 3).
    #[getter]
    fn positions<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        rows_array(py, self.poses(|p| p.position.to_array())?)
    }

    /// Every body's rotation (body frame to world) at the world's `time`, unit quaternions
    /// (x, y, z, w): float64 (len, 4).
    #[getter]
    fn rotations<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        rows_array(py, self.poses(|p| p.rotation.to_array())?)
    }

    /// Adds a floating body and returns its index: either `toml`, the text of one `[[body]]`
    /// table as a scene file holds it (header included), or its keys as keywords
    /// (`add_body(shape="box", size=[1.0, 0.5, 2.0], density=500.0, position=[0.0, 2.0, 0.0])`,
    /// every key of docs/scene-format.md; lists, tuples and numpy arrays for vectors; a mesh's
    /// relative `path` is relative to the working directory). It is held still at its initial
    /// pose until the next body step after the world's time (later if its `release_time` says so),
    /// then falls free; `positions` and `rotations` include it at once. ValueError naming the key
    /// as the world numbers the new body (`body[3].size[0] = -1 is outside [0.02, 1000]`),
    /// TypeError for a value no scene key takes. The world is moved to its own time again to give
    /// the new body its pose, which can raise as `advance` does only if the last advance failed.
    #[pyo3(signature = (toml=None, **keys))]
    fn add_body(&self, py: Python<'_>, toml: Option<&str>, keys: Option<Bound<'_, PyDict>>) -> PyResult<usize> {
        let keys = keys.filter(|k| !k.is_empty());
        let (text, source) = match (toml, keys) {
            (Some(text), None) => (text.to_string(), SOURCE),
            (None, Some(keys)) => {
                let mut table = toml::Table::new();
                for (k, v) in keys.iter() {
                    let k: String = k.extract()?;
                    let value = toml_value(&k, &v)?;
                    table.insert(k, value);
                }
                let mut root = toml::Table::new();
                root.insert("body".into(), toml::Value::Array(vec![toml::Value::Table(table)]));
                let text = toml::to_string(&root)
                    .map_err(|e| PyValueError::new_err(format!("add_body: the keys cannot be written as TOML: {e}")))?;
                (text, "add_body")
            }
            _ => {
                return Err(PyTypeError::new_err(
                    "add_body: give either the TOML text of one [[body]] table or its keys as keywords, not both or neither",
                ))
            }
        };
        py.allow_threads(|| {
            let mut w = self.lock();
            // Released at the next body step after the world's time, posed at once
            // (World::add_body).
            let spec = w.scene.body_from_toml(&text, source)?;
            w.add_body(spec).map_err(|e| e.in_source(source))
        })
        .map_err(py_err)
    }

    /// Sets the thrust of `body` (its index or name): `force`, three numbers in newtons along the
    /// world's x, y, z, applied at its centre of mass from the next body step on, on top of
    /// gravity's, the water's and the ground's (a propeller, a push); (0, 0, 0) removes it. Not
    /// part of the scene: a time before the world's replays from t = 0 with the thrust as it is
    /// now.
    fn set_thrust(&self, body: Bound<'_, PyAny>, force: Bound<'_, PyAny>) -> PyResult<()> {
        let k = self.resolve(&body)?;
        let f: Vec<f64> = if force.is_instance_of::<PyString>() {
            Err(PyTypeError::new_err("force: a str is not three numbers"))
        } else {
            force
                .extract()
                .map_err(|e| PyTypeError::new_err(format!("force: must be three numbers (N along x, y, z) ({e})")))
        }?;
        let [x, y, z] = f[..] else {
            return Err(PyValueError::new_err(format!("force: {} values; must be 3 (N along x, y, z)", f.len())));
        };
        for (i, v) in [x, y, z].into_iter().enumerate() {
            if !v.is_finite() {
                return Err(py_err(swell::Error::out_of_range(format!("force[{i}]"), v, "finite newtons")));
            }
        }
        self.lock().bodies.bodies_mut()[k].thrust = DVec3::new(x, y, z);
        Ok(())
    }

    /// The thrusts `set_thrust` gave, N, world axes: float64 (len, 3), zeros where none was set.
    #[getter]
    fn thrusts<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let rows = self.lock().bodies.bodies().iter().map(|b| b.thrust.to_array()).collect();
        rows_array(py, rows)
    }

    fn __repr__(&self) -> String {
        let w = self.lock();
        format!("<swell.World {} floating bodies, at t = {} s>", w.bodies.len(), w.time())
    }
}
