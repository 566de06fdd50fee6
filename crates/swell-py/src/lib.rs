//! `swell._swell`: the Python bindings of swell (PyO3, abi3). The Python package `swell`
//! (`python/swell/__init__.py`) re-exports it; `python/swell/_swell.pyi` holds the type stubs.
//!
//! Every heavy call releases the GIL (`Python::allow_threads`) around the library's work, which
//! runs on swell's rayon pool; arrays cross the boundary whole, never element by element.

use std::path::PathBuf;
use std::sync::{Mutex, MutexGuard};

use glam::{Vec2, Vec3};
use numpy::{IntoPyArray, PyArray1, PyArray2, PyArray3, PyArrayDyn, PyArrayMethods, PyReadonlyArrayDyn};
use pyo3::exceptions::{PyOSError, PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyFloat};
use swell::render::Renderer;
use swell::scene::{Scene, MAX_IMAGE_SIDE};
use swell::world::{sea_stats, World};

/// The name scene texts are known by in error messages (the C API's too).
const SOURCE: &str = "toml";

/// swell's error as a Python exception: OSError for files, ValueError for everything else, with
/// the message the CLI prints after `error: `.
fn py_err(e: swell::Error) -> PyErr {
    // User text in the message is escaped and cut as the CLI prints it (issue 37).
    let message = swell::error::printable(&e.to_string());
    match e {
        swell::Error::Io { .. } => PyOSError::new_err(message),
        _ => PyValueError::new_err(message),
    }
}

fn check_time(t: f64) -> PyResult<()> {
    if t.is_finite() {
        Ok(())
    } else {
        Err(py_err(swell::Error::out_of_range("t", t, "finite seconds")))
    }
}

/// The water of a scene, built and ready to answer queries about any time `t` (s).
///
/// Queries at one time share one evaluation of the model's state; answers depend only on the
/// scene and `t`. Calls on one object from several threads are serialised by a lock inside it.
#[pyclass(frozen, module = "swell")]
struct Water {
    inner: Mutex<swell::Water>,
}

impl Water {
    fn lock(&self) -> MutexGuard<'_, swell::Water> {
        self.inner.lock().unwrap_or_else(|p| p.into_inner())
    }
}

/// `x` and `z` broadcast against each other as contiguous float64 arrays, and their broadcast
/// shape (numpy does it; `ascontiguousarray` makes a 0-d array 1-d, hence the shape apart). Each
/// is first checked by [`real_coordinates`].
fn broadcast<'py>(
    py: Python<'py>,
    x: &Bound<'py, PyAny>,
    z: &Bound<'py, PyAny>,
) -> PyResult<(PyReadonlyArrayDyn<'py, f64>, PyReadonlyArrayDyn<'py, f64>, Vec<usize>)> {
    let np = py.import("numpy")?;
    let pair = np.call_method1("broadcast_arrays", (real_coordinates(&np, "x", x)?, real_coordinates(&np, "z", z)?))?;
    let contiguous = |k: usize| -> PyResult<PyReadonlyArrayDyn<'py, f64>> {
        let a = np.call_method1("ascontiguousarray", (pair.get_item(k)?, "float64"))?;
        Ok(a.downcast_into::<PyArrayDyn<f64>>()?.readonly())
    };
    let shape: Vec<usize> = pair.get_item(0)?.getattr("shape")?.extract()?;
    Ok((contiguous(0)?, contiguous(1)?, shape))
}

/// `v` as a float64 array if it holds real, finite coordinates (issue 37): integers and floats of
/// any layout are taken as they were; booleans, complex numbers, datetimes, strings, objects and
/// `None` raise TypeError naming the argument and the dtype, and a NaN or infinite coordinate
/// raises ValueError naming the argument, its first bad index and the value: an engine must learn
/// that its buoy went NaN, not be answered with calm water.
fn real_coordinates<'py>(np: &Bound<'py, PyModule>, name: &str, v: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyAny>> {
    let a = np.call_method1("asarray", (v,))?;
    let dtype = a.getattr("dtype")?;
    let kind: String = dtype.getattr("kind")?.extract()?;
    if !matches!(kind.as_str(), "i" | "u" | "f") {
        let printable = swell::error::printable(&dtype.str()?.to_string());
        return Err(PyTypeError::new_err(format!(
            "{name}: dtype {printable} is not a real number type; pass integers or floats (world metres)"
        )));
    }
    let a = np.call_method1("asarray", (a, "float64"))?;
    let finite = np.call_method1("isfinite", (&a,))?.call_method0("ravel")?;
    if finite.call_method0("all")?.extract::<bool>()? {
        return Ok(a);
    }
    let first: usize = np.call_method1("argmin", (&finite,))?.extract()?;
    let value: f64 = a.call_method0("ravel")?.get_item(first)?.extract()?;
    let index: Vec<usize> = np.call_method1("unravel_index", (first, a.getattr("shape")?))?.extract()?;
    let at = if index.is_empty() {
        String::new()
    } else {
        format!("[{}]", index.iter().map(usize::to_string).collect::<Vec<_>>().join(", "))
    };
    Err(py_err(swell::Error::out_of_range(format!("{name}{at}"), value, "finite world metres")))
}

/// The (x, z) points of two equally shaped arrays, as f32 (the models' precision).
fn points(x: &[f64], z: &[f64]) -> Vec<Vec2> {
    x.iter().zip(z).map(|(&x, &z)| Vec2::new(x as f32, z as f32)).collect()
}

#[pymethods]
impl Water {
    /// Builds the water of a scene's TOML text (only `[water]` is required by the queries).
    /// Raises ValueError with the CLI's message for bad input.
    #[staticmethod]
    fn from_toml(py: Python<'_>, text: &str) -> PyResult<Self> {
        let water = py.allow_threads(|| swell::Water::from_toml(text, SOURCE)).map_err(py_err)?;
        Ok(Self { inner: Mutex::new(water) })
    }

    /// Reads a scene file (relative heightmap paths are relative to it) and builds its water.
    #[staticmethod]
    fn from_file(py: Python<'_>, path: PathBuf) -> PyResult<Self> {
        let water =
            py.allow_threads(|| Scene::load(&path).and_then(|s| swell::Water::from_scene(&s))).map_err(py_err)?;
        Ok(Self { inner: Mutex::new(water) })
    }

    /// Vertices of the grid along +Z (`cells_z + 1`).
    #[getter]
    fn rows(&self) -> usize {
        self.lock().rows()
    }

    /// Vertices of the grid along +X (`cells_x + 1`).
    #[getter]
    fn cols(&self) -> usize {
        self.lock().cols()
    }

    /// Displaced world positions (m) and unit normals of the grid at time `t` (s), each a float32
    /// array of shape (rows, cols, 3): the numbers `swell export` writes for that time.
    fn displace<'py>(
        &self,
        py: Python<'py>,
        t: f64,
    ) -> PyResult<(Bound<'py, PyArray3<f32>>, Bound<'py, PyArray3<f32>>)> {
        check_time(t)?;
        let (rows, cols, p, n) = py
            .allow_threads(|| -> swell::Result<_> {
                let mut w = self.lock();
                let count = w.vertex_count();
                let (mut p, mut n) = (vec![Vec3::ZERO; count], vec![Vec3::ZERO; count]);
                w.displace(t, &mut p, &mut n)?;
                let flat = |v: Vec<Vec3>| v.into_iter().flat_map(|v| v.to_array()).collect::<Vec<f32>>();
                Ok((w.rows(), w.cols(), flat(p), flat(n)))
            })
            .map_err(py_err)?;
        let shape = [rows, cols, 3];
        Ok((p.into_pyarray(py).reshape(shape)?, n.into_pyarray(py).reshape(shape)?))
    }

    /// Foam coverage in [0, 1] of every grid vertex at time `t` (s), float32 (rows, cols), or
    /// None if the model has no foam (only the FFT ocean with `foam = true` has).
    fn foam<'py>(&self, py: Python<'py>, t: f64) -> PyResult<Option<Bound<'py, PyArray2<f32>>>> {
        check_time(t)?;
        let (rows, cols, foam) = py
            .allow_threads(|| -> swell::Result<_> {
                let mut w = self.lock();
                let mut out = vec![0.0f32; w.vertex_count()];
                let has = w.foam(t, &mut out)?;
                Ok((w.rows(), w.cols(), has.then_some(out)))
            })
            .map_err(py_err)?;
        foam.map(|f| f.into_pyarray(py).reshape([rows, cols])).transpose()
    }

    /// Heights (m above the water at rest) of the surface above world (x, z) (m) at time `t` (s):
    /// float64 with the broadcast shape of `x` and `z` (a float when both are scalars).
    fn height_at<'py>(
        &self,
        py: Python<'py>,
        x: &Bound<'py, PyAny>,
        z: &Bound<'py, PyAny>,
        t: f64,
    ) -> PyResult<Bound<'py, PyAny>> {
        check_time(t)?;
        let (xa, za, shape) = broadcast(py, x, z)?;
        let (xs, zs) = (xa.as_slice()?, za.as_slice()?);
        let heights = py
            .allow_threads(|| -> swell::Result<_> {
                let pts = points(xs, zs);
                let mut h = vec![0.0f32; pts.len()];
                self.lock().heights_at(t, &pts, &mut h)?;
                Ok(h.into_iter().map(f64::from).collect::<Vec<f64>>())
            })
            .map_err(py_err)?;
        if shape.is_empty() {
            // Two scalars in, a float out (numpy's ufunc convention).
            return Ok(PyFloat::new(py, heights[0]).into_any());
        }
        Ok(heights.into_pyarray(py).reshape(shape)?.into_any())
    }

    /// Unit normals of the surface above world (x, z) (m) at time `t` (s): float64 with the
    /// broadcast shape of `x` and `z` followed by 3. Central differences of the height over 2 cm.
    fn normal_at<'py>(
        &self,
        py: Python<'py>,
        x: &Bound<'py, PyAny>,
        z: &Bound<'py, PyAny>,
        t: f64,
    ) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
        check_time(t)?;
        let (xa, za, mut shape) = broadcast(py, x, z)?;
        shape.push(3);
        let (xs, zs) = (xa.as_slice()?, za.as_slice()?);
        let normals = py
            .allow_threads(|| -> swell::Result<_> {
                let pts = points(xs, zs);
                let mut n = vec![Vec3::ZERO; pts.len()];
                self.lock().normals_at(t, &pts, &mut n)?;
                Ok(n.into_iter().flat_map(|v| v.to_array().map(f64::from)).collect::<Vec<f64>>())
            })
            .map_err(py_err)?;
        Ok(normals.into_pyarray(py).reshape(shape)?)
    }

    fn __repr__(&self) -> String {
        let w = self.lock();
        format!("<swell.Water {} x {} vertices, at t = {} s>", w.rows(), w.cols(), w.time())
    }
}

fn check_side(name: &str, v: Option<i64>) -> PyResult<Option<u32>> {
    match v {
        None => Ok(None),
        Some(v) if (1..=i64::from(MAX_IMAGE_SIDE)).contains(&v) => Ok(Some(v as u32)),
        Some(v) => Err(py_err(swell::Error::out_of_range(name, v, format!("[1, {MAX_IMAGE_SIDE}]")))),
    }
}

/// Renders a scene's TOML text at time `t` (s) as `swell render --time t` does and returns the
/// image as a (height, width, 3) uint8 array (sRGB, top row first): the pixels of the CLI's PNG.
/// `width` and `height` override `[render]`'s, each in [1, 16384].
#[pyfunction]
#[pyo3(signature = (text, t=0.0, width=None, height=None))]
fn render<'py>(
    py: Python<'py>,
    text: &str,
    t: f64,
    width: Option<i64>,
    height: Option<i64>,
) -> PyResult<Bound<'py, PyArray3<u8>>> {
    check_time(t)?;
    let (width, height) = (check_side("width", width)?, check_side("height", height)?);
    let (w, h, rgb) = py
        .allow_threads(|| -> swell::Result<_> {
            let mut scene = Scene::from_toml(text, SOURCE)?;
            scene.render.width = width.unwrap_or(scene.render.width);
            scene.render.height = height.unwrap_or(scene.render.height);
            if width.is_some() || height.is_some() {
                scene.validate()?; // the framebuffer's memory against the budget
            }
            let r = scene.render;
            let mut world = World::new(scene)?;
            world.update(t)?;
            let mut rgba = Vec::new();
            Renderer::new().render(&world).encode_rgba8(r.exposure, r.gamma, &mut rgba);
            let rgb: Vec<u8> = rgba.chunks_exact(4).flat_map(|p| [p[0], p[1], p[2]]).collect();
            Ok((r.width as usize, r.height as usize, rgb))
        })
        .map_err(py_err)?;
    Ok(PyArray1::from_vec(py, rgb).reshape([h, w, 3])?)
}

/// The sea state of a spectral scene (`model = "fft"`) at time `t` (s), as `swell stats --time t`
/// prints it, as a dict (hs_realised_m, hs_expected_m, peak_period_s, foam_coverage, grid, ...).
#[pyfunction]
#[pyo3(signature = (text, t=0.0))]
fn stats<'py>(py: Python<'py>, text: &str, t: f64) -> PyResult<Bound<'py, PyDict>> {
    let json = py
        .allow_threads(|| -> swell::Result<String> {
            let stats = sea_stats(&Scene::from_toml(text, SOURCE)?, t)?;
            Ok(serde_json::to_string_pretty(&stats).expect("plain JSON values"))
        })
        .map_err(py_err)?;
    Ok(py.import("json")?.call_method1("loads", (json,))?.downcast_into::<PyDict>()?)
}

/// swell: water surfaces simulated and rendered on the CPU (the compiled part of the package).
#[pymodule]
fn _swell(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add_class::<Water>()?;
    m.add_function(wrap_pyfunction!(render, m)?)?;
    m.add_function(wrap_pyfunction!(stats, m)?)?;
    Ok(())
}
