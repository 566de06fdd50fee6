//! `swell._swell`: the Python bindings of swell (PyO3, abi3). The Python package `swell`
//! (`python/swell/__init__.py`) re-exports it; `python/swell/_swell.pyi` holds the type stubs.
//!
//! Every heavy call releases the GIL (`Python::allow_threads`) around the library's work, which
//! runs on swell's rayon pool; arrays cross the boundary whole, never element by element.

use std::path::PathBuf;
use std::sync::{Arc, Mutex, MutexGuard};

use glam::{DVec2, DVec3, Vec3};
use numpy::{
    IntoPyArray, PyArray1, PyArray2, PyArray3, PyArrayDyn, PyArrayMethods, PyReadonlyArrayDyn, PyUntypedArrayMethods,
};
use pyo3::exceptions::{PyException, PyOSError, PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat};
use swell::render::Renderer;
use swell::scene::{Scene, MAX_IMAGE_SIDE};
use swell::world::{sea_stats, water_sea_stats, World};

mod world;

/// The name scene texts are known by in error messages (the C API's too).
const SOURCE: &str = "toml";

pyo3::create_exception!(
    swell,
    Cancelled,
    PyException,
    "A long call stopped because the progress callback returned False (`Water.set_progress`). \
     Asking again continues from where it stopped."
);

/// swell's error as a Python exception: OSError for files, `Cancelled` for a stop asked by the
/// progress callback, ValueError for everything else, with the message the CLI prints after
/// `error: `.
fn py_err(e: swell::Error) -> PyErr {
    // User text in the message is escaped and cut as the CLI prints it (issue 37).
    let message = swell::error::printable(&e.to_string());
    match e {
        swell::Error::Io { .. } => PyOSError::new_err(message),
        swell::Error::Cancelled(_) => Cancelled::new_err(message),
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
    /// The callable `set_progress` gave, told the progress of long calls.
    progress: Arc<Mutex<Option<Py<PyAny>>>>,
    /// The exception that stopped the last long call (Ctrl-C's KeyboardInterrupt, or what the
    /// progress callback raised), raised in place of swell's `Cancelled`.
    pending: Arc<Mutex<Option<PyErr>>>,
}

/// Locks `m`, taking over a lock poisoned by a panic (the state re-derives itself).
fn locked<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    m.lock().unwrap_or_else(|p| p.into_inner())
}

impl Water {
    /// Wraps `water` with a watch on its long calls (issue 37): every 10-50 ms of a long advance
    /// it takes the GIL, runs Python's signal handlers (so Ctrl-C stops the call within a second,
    /// though the GIL is released while it computes) and tells the progress callback, if any.
    fn watched(mut water: swell::Water) -> Self {
        let (progress, pending) = (Arc::new(Mutex::new(None::<Py<PyAny>>)), Arc::new(Mutex::new(None)));
        let (callback, stop) = (Arc::clone(&progress), Arc::clone(&pending));
        water.set_watch(Some(Box::new(move |fraction| {
            Python::with_gil(|py| {
                let outcome = py.check_signals().and_then(|()| match locked(&callback).as_ref() {
                    None => Ok(true),
                    // Only False stops: a callback that returns nothing goes on.
                    Some(f) => f.call1(py, (fraction,)).map(|r| !r.bind(py).is(pyo3::types::PyBool::new(py, false))),
                });
                outcome.unwrap_or_else(|e| {
                    *locked(&stop) = Some(e);
                    false
                })
            })
        })));
        Self { inner: Mutex::new(water), progress, pending }
    }

    fn lock(&self) -> MutexGuard<'_, swell::Water> {
        locked(&self.inner)
    }

    /// [`py_err`], but a stop caused by a Python exception raises that exception.
    fn err(&self, e: swell::Error) -> PyErr {
        match (&e, locked(&self.pending).take()) {
            (swell::Error::Cancelled(_), Some(raised)) => raised,
            _ => py_err(e),
        }
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
/// `None` raise TypeError naming the argument and the dtype, and a NaN or infinite coordinate, or
/// one past `MAX_QUERY_COORDINATE_M` (10^9 m), raises ValueError naming the argument, its first
/// bad index and the value: an engine must learn that its buoy went NaN, not be answered with calm
/// water.
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
    // |v| <= the limit is false for NaN and infinities too: one test finds every bad coordinate.
    let within = np
        .call_method1("less_equal", (np.call_method1("abs", (&a,))?, swell::world::MAX_QUERY_COORDINATE_M))?
        .call_method0("ravel")?;
    if within.call_method0("all")?.extract::<bool>()? {
        return Ok(a);
    }
    let first: usize = np.call_method1("argmin", (&within,))?.extract()?;
    let value: f64 = a.call_method0("ravel")?.get_item(first)?.extract()?;
    let index: Vec<usize> = np.call_method1("unravel_index", (first, a.getattr("shape")?))?.extract()?;
    let at = if index.is_empty() { String::new() } else { format!("[{}]", comma_list(&index)) };
    let range = if value.is_finite() {
        "world metres within 1e9 of the origin (MAX_QUERY_COORDINATE_M)"
    } else {
        "finite world metres"
    };
    Err(py_err(swell::Error::out_of_range(format!("{name}{at}"), swell::error::Human(value), range)))
}

/// The displaced grid's positions and normals, float32 `(rows, cols, 3)` each.
type GridArrays<'py> = (Bound<'py, PyArray3<f32>>, Bound<'py, PyArray3<f32>>);

/// A shape as Python prints it: `(9, 9, 3)`.
fn shape_text(shape: &[usize]) -> String {
    format!("({})", comma_list(shape))
}

/// Sizes or indices as `9, 9, 3`: inside a shape's parentheses or an index's brackets.
fn comma_list(v: &[usize]) -> String {
    v.iter().map(usize::to_string).collect::<Vec<_>>().join(", ")
}

/// A caller's `out=` array `name`: a writable, C-contiguous float32 array of `shape`, or a
/// TypeError / ValueError naming what is wrong.
fn out_array<'py>(name: &str, a: Bound<'py, PyAny>, shape: [usize; 3]) -> PyResult<Bound<'py, PyArray3<f32>>> {
    let a = a.downcast_into::<PyArray3<f32>>().map_err(|e| {
        PyTypeError::new_err(format!("{name}: must be a float32 numpy array of shape {} ({e})", shape_text(&shape)))
    })?;
    if a.shape() != shape {
        return Err(PyValueError::new_err(format!(
            "{name}: shape {}; must be {} (rows, cols, 3)",
            shape_text(a.shape()),
            shape_text(&shape)
        )));
    }
    if !a.is_c_contiguous() {
        return Err(PyValueError::new_err(format!("{name}: must be C-contiguous (numpy.ascontiguousarray)")));
    }
    if a.try_readwrite().is_err() {
        return Err(PyValueError::new_err(format!("{name}: must be writable and not borrowed elsewhere")));
    }
    Ok(a)
}

/// The (x, z) points of two equally shaped arrays, kept in double precision: the queries'
/// `_f64` forms take a periodic sea's whole periods off before narrowing to the models' f32, so
/// an engine's coordinates at 10^6 m keep their precision.
fn points(x: &[f64], z: &[f64]) -> Vec<DVec2> {
    x.iter().zip(z).map(|(&x, &z)| DVec2::new(x, z)).collect()
}

#[pymethods]
impl Water {
    /// Builds the water of a scene's TOML text (only `[water]` is required by the queries).
    /// Raises ValueError with the CLI's message for bad input.
    #[staticmethod]
    fn from_toml(py: Python<'_>, text: &str) -> PyResult<Self> {
        let water = py.allow_threads(|| swell::Water::from_toml(text, SOURCE)).map_err(py_err)?;
        Ok(Self::watched(water))
    }

    /// The FFT ocean of a tabulated directional spectrum `E(f, θ)`: a wavespectra/xarray
    /// DataArray `efth(freq, dir)` (its coordinates and units read), a list of them (summed), a
    /// netCDF path as wavespectra writes it, or a numpy array with `freq` (Hz) and `dir`
    /// (degrees, coming from); any other `[water]` key as a keyword (`grid`, `patch_size`,
    /// `cascades`, `seed`, `depth`, `size`, `cells`, ...). The scene text is built by
    /// `swell._spectrum.scene_text` (pure Python) and read as `from_toml` reads any scene.
    #[staticmethod]
    #[pyo3(signature = (efth, freq=None, dir=None, **keys))]
    fn from_spectrum(
        py: Python<'_>,
        efth: Bound<'_, PyAny>,
        freq: Option<Bound<'_, PyAny>>,
        dir: Option<Bound<'_, PyAny>>,
        keys: Option<Bound<'_, PyDict>>,
    ) -> PyResult<Self> {
        let text: String =
            py.import("swell._spectrum")?.getattr("scene_text")?.call((efth, freq, dir), keys.as_ref())?.extract()?;
        Self::from_toml(py, &text)
    }

    /// The sea state of this water's spectral sea (`model = "fft"`) at time `t` (s): what
    /// `swell stats` prints (Hs, Tp, Dpm, Dspr expected and realised, with wavespectra's
    /// definitions), as an xarray Dataset when xarray is installed, else a dict.
    #[pyo3(signature = (t=0.0))]
    fn stats<'py>(&self, py: Python<'py>, t: f64) -> PyResult<Bound<'py, PyAny>> {
        check_time(t)?;
        let spec = self.lock().spec().clone();
        let json = py
            .allow_threads(|| -> swell::Result<String> {
                let stats = water_sea_stats(&spec, t)?;
                Ok(serde_json::to_string_pretty(&stats).expect("plain JSON values"))
            })
            .map_err(py_err)?;
        let dict = py.import("json")?.call_method1("loads", (json,))?;
        py.import("swell._spectrum")?.getattr("stats_result")?.call1((dict,))
    }

    /// Reads a scene file (relative heightmap paths are relative to it) and builds its water.
    #[staticmethod]
    fn from_file(py: Python<'_>, path: PathBuf) -> PyResult<Self> {
        let water =
            py.allow_threads(|| Scene::load(&path).and_then(|s| swell::Water::from_scene(&s))).map_err(py_err)?;
        Ok(Self::watched(water))
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
    /// array of shape (rows, cols, 3): the numbers `swell export` writes for that time. With
    /// `out=(positions, normals)`, two writable C-contiguous float32 arrays of that shape, they
    /// are filled and returned instead of new arrays (a per-frame loop allocates nothing).
    #[pyo3(signature = (t, out=None))]
    fn displace<'py>(
        &self,
        py: Python<'py>,
        t: f64,
        out: Option<(Bound<'py, PyAny>, Bound<'py, PyAny>)>,
    ) -> PyResult<GridArrays<'py>> {
        check_time(t)?;
        let (rows, cols) = {
            let w = self.lock();
            (w.rows(), w.cols())
        };
        let shape = [rows, cols, 3];
        let (p, n) = match out {
            Some((p, n)) => (out_array("out[0]", p, shape)?, out_array("out[1]", n, shape)?),
            None => (PyArray3::<f32>::zeros(py, shape, false), PyArray3::<f32>::zeros(py, shape, false)),
        };
        if p.is(&n) {
            return Err(PyValueError::new_err("out: positions and normals must be two different arrays"));
        }
        {
            let (mut pw, mut nw) = (p.readwrite(), n.readwrite());
            let (ps, ns) = (pw.as_slice_mut()?, nw.as_slice_mut()?);
            py.allow_threads(|| {
                // SAFETY: Vec3 is #[repr(C)] {x, y, z: f32} (size 12, align 4), and each slice
                // holds 3 floats per vertex (its shape was checked).
                let as_vec3 = |s: &mut [f32]| unsafe {
                    std::slice::from_raw_parts_mut(s.as_mut_ptr().cast::<Vec3>(), s.len() / 3)
                };
                self.lock().displace(t, as_vec3(ps), as_vec3(ns))
            })
            .map_err(|e| self.err(e))?;
        }
        Ok((p, n))
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
            .map_err(|e| self.err(e))?;
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
                let mut h = vec![0.0; pts.len()];
                self.lock().heights_at_f64(t, &pts, &mut h)?;
                Ok(h)
            })
            .map_err(|e| self.err(e))?;
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
                let mut n = vec![DVec3::ZERO; pts.len()];
                self.lock().normals_at_f64(t, &pts, &mut n)?;
                Ok(n.into_iter().flat_map(|v| v.to_array()).collect::<Vec<f64>>())
            })
            .map_err(|e| self.err(e))?;
        normals.into_pyarray(py).reshape(shape)
    }

    /// Whether there is water above world (x, z) (m): bool with the broadcast shape of `x` and `z`
    /// (a bool when both are scalars). False off a finite patch, where `height_at` answers NaN and
    /// `normal_at` NaN vectors; always True for a sea over the whole plane.
    fn has_water<'py>(
        &self,
        py: Python<'py>,
        x: &Bound<'py, PyAny>,
        z: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let (xa, za, shape) = broadcast(py, x, z)?;
        let pts = points(xa.as_slice()?, za.as_slice()?);
        let water = self.lock();
        let covered: Vec<bool> = pts.iter().map(|&p| water.has_water_at_f64(p)).collect();
        drop(water);
        if shape.is_empty() {
            return Ok(PyBool::new(py, covered[0]).to_owned().into_any());
        }
        Ok(covered.into_pyarray(py).reshape(shape)?.into_any())
    }

    /// Sets (or, with None, removes) the callable told the progress of long calls (a spring mesh
    /// asked minutes ahead): it gets the fraction done in [0, 1) about every 10-50 ms, and
    /// returning False stops the call, which raises `swell.Cancelled`; an exception it raises
    /// stops the call and is raised. Ctrl-C stops long calls within a second with or without it.
    #[pyo3(signature = (callback))]
    fn set_progress(&self, callback: Option<Bound<'_, PyAny>>) -> PyResult<()> {
        if let Some(f) = &callback {
            if !f.is_callable() {
                let kind = f.get_type().name()?.to_string();
                return Err(PyTypeError::new_err(format!(
                    "callback: a {kind} is not callable; give a function of the fraction done, or None"
                )));
            }
        }
        *locked(&self.progress) = callback.map(Bound::unbind);
        Ok(())
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
            Renderer::new().render(&world).encode_rgba8(&r.display_encoding(), &mut rgba);
            let rgb: Vec<u8> = rgba.chunks_exact(4).flat_map(|p| [p[0], p[1], p[2]]).collect();
            Ok((r.width as usize, r.height as usize, rgb))
        })
        .map_err(py_err)?;
    PyArray1::from_vec(py, rgb).reshape([h, w, 3])
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
    m.add_class::<world::World>()?;
    m.add("Cancelled", m.py().get_type::<Cancelled>())?;
    m.add_function(wrap_pyfunction!(render, m)?)?;
    m.add_function(wrap_pyfunction!(stats, m)?)?;
    Ok(())
}
