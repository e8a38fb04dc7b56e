//! `scratchwave._native`: the compiled half of the Python package. Thin: every call goes
//! to `scratchwave_capi` (materials, batch eval/pdf/sample), `scratchwave_render` (scenes)
//! or the CPU table backend, with the GIL released around the work. Shapes and dtypes are
//! normalised by the Python half (`scratchwave/__init__.py`); here arrays arrive flat and
//! contiguous, and the batch core checks their lengths.

use numpy::{PyArray1, PyReadonlyArray1};
use pyo3::create_exception;
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use scratchwave_capi::{Bsdf, Error, Queries, ScratchSet};
use scratchwave_host::TableBackend;
use scratchwave_render::{Backend, Region, RenderError, scene_file};
use std::path::{Path, PathBuf};

/// A NumPy float32 vector handed back to Python.
type Arr<'py> = Bound<'py, PyArray1<f32>>;

create_exception!(
    _native,
    InputError,
    PyValueError,
    "Rejected input: the message names the field (JSON path) or argument."
);

fn py_err(e: Error) -> PyErr {
    match e {
        Error::Input(e) => InputError::new_err(e.to_string()),
        Error::Argument(m) => PyValueError::new_err(m),
        Error::Internal(m) => PyRuntimeError::new_err(m),
    }
}

fn render_err(e: RenderError) -> PyErr {
    match e {
        RenderError::Input(e) => InputError::new_err(e.to_string()),
        other => PyRuntimeError::new_err(other.to_string()),
    }
}

fn slice<'a>(a: &'a Option<PyReadonlyArray1<'_, f32>>, name: &str) -> PyResult<Option<&'a [f32]>> {
    a.as_ref()
        .map(|a| {
            a.as_slice()
                .map_err(|_| PyValueError::new_err(format!("{name}: not contiguous")))
        })
        .transpose()
}

/// A set of scratch segments (µm of scratch space).
#[pyclass(module = "scratchwave._native", frozen)]
struct NativeScratchSet(ScratchSet);

#[pymethods]
impl NativeScratchSet {
    /// From the JSON text of a list of scratch sources.
    #[staticmethod]
    #[pyo3(signature = (text, base_dir=None))]
    fn from_json(text: &str, base_dir: Option<PathBuf>) -> PyResult<Self> {
        ScratchSet::from_json(text, base_dir.as_deref())
            .map(NativeScratchSet)
            .map_err(py_err)
    }

    /// From flat rows `x0, y0, x1, y1, width, depth` (f64) and one triangle flag per row.
    #[staticmethod]
    fn from_rows(rows: PyReadonlyArray1<'_, f64>, triangle: Vec<bool>) -> PyResult<Self> {
        let flat = rows
            .as_slice()
            .map_err(|_| PyValueError::new_err("rows: not contiguous"))?;
        if flat.len() % 6 != 0 {
            return Err(PyValueError::new_err("rows: expected 6 values per row"));
        }
        let r: Vec<[f64; 6]> = flat
            .chunks_exact(6)
            .map(|c| [c[0], c[1], c[2], c[3], c[4], c[5]])
            .collect();
        ScratchSet::from_rows(&r, &triangle)
            .map(NativeScratchSet)
            .map_err(py_err)
    }

    fn __len__(&self) -> usize {
        self.0.len()
    }
}

/// A material with its scratch lookup.
#[pyclass(module = "scratchwave._native", frozen)]
struct NativeBsdf(Bsdf);

/// Flat query arrays as the batch core takes them.
struct Arrays<'py> {
    wo: PyReadonlyArray1<'py, f32>,
    wi: Option<PyReadonlyArray1<'py, f32>>,
    x_um: Option<PyReadonlyArray1<'py, f32>>,
    footprint: Option<PyReadonlyArray1<'py, f32>>,
    lambda_nm: Option<PyReadonlyArray1<'py, f32>>,
    lambda_count: usize,
}

impl Arrays<'_> {
    fn queries(&self) -> PyResult<Queries<'_>> {
        Ok(Queries {
            wo: self
                .wo
                .as_slice()
                .map_err(|_| PyValueError::new_err("wo: not contiguous"))?,
            wi: slice(&self.wi, "wi")?,
            x_um: slice(&self.x_um, "x_um")?,
            footprint: slice(&self.footprint, "footprint")?,
            lambda_nm: slice(&self.lambda_nm, "lambda_nm")?,
            lambda_count: self.lambda_count,
        })
    }
}

impl NativeBsdf {
    /// A batch call with one output array (`k` values per query when `per_wavelength`, else
    /// one), the GIL released.
    fn one_output<'py>(
        &self,
        py: Python<'py>,
        a: &Arrays<'py>,
        per_wavelength: bool,
        call: fn(&Bsdf, &Queries<'_>, &mut [f32]) -> Result<(), Error>,
    ) -> PyResult<Arr<'py>> {
        let q = a.queries()?;
        let per = if per_wavelength {
            q.wavelengths_per_query()
        } else {
            1
        };
        let mut out = vec![0.0f32; q.len() * per];
        py.detach(|| call(&self.0, &q, &mut out)).map_err(py_err)?;
        Ok(PyArray1::from_vec(py, out))
    }
}

#[pymethods]
impl NativeBsdf {
    /// From the material JSON text of a scene file.
    #[staticmethod]
    #[pyo3(signature = (text, base_dir=None, scratches=None))]
    fn from_json(
        text: &str,
        base_dir: Option<PathBuf>,
        scratches: Option<&NativeScratchSet>,
    ) -> PyResult<Self> {
        Bsdf::from_json(text, base_dir.as_deref(), scratches.map(|s| &s.0))
            .map(NativeBsdf)
            .map_err(py_err)
    }

    /// Number of scratch segments.
    fn scratch_count(&self) -> usize {
        self.0.scratch_count()
    }

    /// BRDF values, flat (`k` per query).
    #[pyo3(signature = (wo, wi, x_um, footprint, lambda_nm, lambda_count))]
    fn eval<'py>(
        &self,
        py: Python<'py>,
        wo: PyReadonlyArray1<'py, f32>,
        wi: PyReadonlyArray1<'py, f32>,
        x_um: Option<PyReadonlyArray1<'py, f32>>,
        footprint: Option<PyReadonlyArray1<'py, f32>>,
        lambda_nm: Option<PyReadonlyArray1<'py, f32>>,
        lambda_count: usize,
    ) -> PyResult<Arr<'py>> {
        let a = Arrays {
            wo,
            wi: Some(wi),
            x_um,
            footprint,
            lambda_nm,
            lambda_count,
        };
        self.one_output(py, &a, true, Bsdf::eval)
    }

    /// Pdf values, one per query.
    #[pyo3(signature = (wo, wi, x_um, footprint, lambda_nm, lambda_count))]
    fn pdf<'py>(
        &self,
        py: Python<'py>,
        wo: PyReadonlyArray1<'py, f32>,
        wi: PyReadonlyArray1<'py, f32>,
        x_um: Option<PyReadonlyArray1<'py, f32>>,
        footprint: Option<PyReadonlyArray1<'py, f32>>,
        lambda_nm: Option<PyReadonlyArray1<'py, f32>>,
        lambda_count: usize,
    ) -> PyResult<Arr<'py>> {
        let a = Arrays {
            wo,
            wi: Some(wi),
            x_um,
            footprint,
            lambda_nm,
            lambda_count,
        };
        self.one_output(py, &a, false, Bsdf::pdf)
    }

    /// Sampled directions, weights and pdfs, flat.
    #[pyo3(signature = (wo, u, x_um, footprint, lambda_nm, lambda_count))]
    fn sample<'py>(
        &self,
        py: Python<'py>,
        wo: PyReadonlyArray1<'py, f32>,
        u: PyReadonlyArray1<'py, f32>,
        x_um: Option<PyReadonlyArray1<'py, f32>>,
        footprint: Option<PyReadonlyArray1<'py, f32>>,
        lambda_nm: Option<PyReadonlyArray1<'py, f32>>,
        lambda_count: usize,
    ) -> PyResult<(Arr<'py>, Arr<'py>, Arr<'py>)> {
        let a = Arrays {
            wo,
            wi: None,
            x_um,
            footprint,
            lambda_nm,
            lambda_count,
        };
        let q = a.queries()?;
        let u = u
            .as_slice()
            .map_err(|_| PyValueError::new_err("u: not contiguous"))?;
        let (n, k) = (q.len(), q.wavelengths_per_query());
        let (mut wi, mut w, mut p) = (vec![0.0f32; 3 * n], vec![0.0f32; k * n], vec![0.0f32; n]);
        py.detach(|| self.0.sample(&q, u, &mut wi, &mut w, &mut p))
            .map_err(py_err)?;
        Ok((
            PyArray1::from_vec(py, wi),
            PyArray1::from_vec(py, w),
            PyArray1::from_vec(py, p),
        ))
    }
}

/// Renders a scene (JSON text; files relative to `base_dir`) on `backend` ("cpu" or
/// "embree"), optionally only `region = (x0, y0, width, height)`. Returns the flat linear
/// RGB values, the width, the height and a dict of statistics.
#[pyfunction]
#[pyo3(signature = (text, name, base_dir, backend, region=None))]
fn render<'py>(
    py: Python<'py>,
    text: &str,
    name: &str,
    base_dir: PathBuf,
    backend: &str,
    region: Option<(u32, u32, u32, u32)>,
) -> PyResult<(Arr<'py>, u32, u32, Bound<'py, PyDict>)> {
    let b = match backend {
        "cpu" => Backend::Cpu,
        "embree" => Backend::Embree,
        other => {
            return Err(PyValueError::new_err(format!(
                "backend: expected \"cpu\" or \"embree\", got {other:?}"
            )));
        }
    };
    let v = scratchwave_spec::json::parse(text, name)
        .map_err(|e| InputError::new_err(e.to_string()))?;
    let scene = scene_file::scene_from_value(&v, name, Path::new(&base_dir))
        .map_err(|e| InputError::new_err(e.to_string()))?;
    let r = match region {
        Some((x0, y0, width, height)) => Region {
            x0,
            y0,
            width,
            height,
        },
        None => Region::full(scene.camera.width_px, scene.camera.height_px),
    };
    let out = py
        .detach(|| scratchwave_render::render_scene_region(&scene, b, r, &|_, _| {}))
        .map_err(render_err)?;
    let flat: Vec<f32> = out.image.rgb.iter().flatten().copied().collect();
    let stats = PyDict::new(py);
    stats.set_item("primary_rays", out.stats.primary_rays)?;
    stats.set_item("shadow_rays", out.stats.shadow_rays)?;
    stats.set_item("shading_evaluations", out.stats.shading_evaluations)?;
    stats.set_item("seconds", out.stats.seconds)?;
    stats.set_item("build_seconds", out.build_seconds)?;
    Ok((
        PyArray1::from_vec(py, flat),
        out.image.width,
        out.image.height,
        stats,
    ))
}

/// The table spec's values (the CLI's `scratchwave table SPEC --backend cpu|simd`), flat.
#[pyfunction]
#[pyo3(signature = (text, backend="cpu"))]
fn table<'py>(py: Python<'py>, text: &str, backend: &str) -> PyResult<Arr<'py>> {
    use scratchwave_cpu::{Backend as CpuBackend, Cpu};
    let b = match backend {
        "cpu" => Cpu(CpuBackend::Scalar),
        "simd" => Cpu(CpuBackend::Simd),
        other => {
            return Err(PyValueError::new_err(format!(
                "backend: expected \"cpu\" or \"simd\", got {other:?}"
            )));
        }
    };
    let v = scratchwave_spec::json::parse(text, "spec")
        .map_err(|e| InputError::new_err(e.to_string()))?;
    let batch =
        scratchwave_spec::spec::table_spec(&v).map_err(|e| InputError::new_err(e.to_string()))?;
    let values = py
        .detach(|| b.evaluate(&batch))
        .map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
    Ok(PyArray1::from_vec(py, values))
}

/// The compiled module.
#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<NativeScratchSet>()?;
    m.add_class::<NativeBsdf>()?;
    m.add_function(wrap_pyfunction!(render, m)?)?;
    m.add_function(wrap_pyfunction!(table, m)?)?;
    m.add("InputError", m.py().get_type::<InputError>())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
