//! The native part of the `vericad` Python package: every function reads its inputs, calls
//! the vericad library job the command line calls, and converts the result to Python objects
//! (dicts and lists, with numpy arrays for points, knots, weights and control nets). The work
//! runs with the GIL released; errors become typed exceptions and a panic inside the library
//! becomes a `ComputationError`.

use numpy::ndarray::{Array1, Array2, Array3};
use numpy::{IntoPyArray, PyArray1};
use pyo3::create_exception;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use serde_json::Value;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};
use vericad::model::{CurveGeometry, Model};
use vericad::spline::{NurbsCurve, NurbsSurface};

create_exception!(
    vericad,
    VericadError,
    PyException,
    "Base class of the errors vericad raises."
);
create_exception!(
    vericad,
    BadInputError,
    VericadError,
    "Bad input: a file that cannot be read or is not valid input, or a bad option (the command line's exit code 2)."
);
create_exception!(
    vericad,
    ComputationError,
    VericadError,
    "The computation failed an internal check (the command line's exit code 1)."
);
create_exception!(
    vericad,
    OutputError,
    VericadError,
    "An output file could not be written (the command line's exit code 1)."
);

/// How a job's error is raised.
enum Fault {
    BadInput(String),
    Computation(String),
    Output(String),
}

impl From<Fault> for PyErr {
    fn from(f: Fault) -> PyErr {
        match f {
            Fault::BadInput(m) => BadInputError::new_err(m),
            Fault::Computation(m) => ComputationError::new_err(m),
            Fault::Output(m) => OutputError::new_err(m),
        }
    }
}

fn bad(msg: impl std::fmt::Display) -> Fault {
    Fault::BadInput(msg.to_string())
}

/// Classify a job error: bad input, a failed write, or a failed computation.
fn fault<E: std::fmt::Display>(e: &E, bad_input: bool, write: bool) -> Fault {
    if bad_input {
        Fault::BadInput(e.to_string())
    } else if write {
        Fault::Output(e.to_string())
    } else {
        Fault::Computation(e.to_string())
    }
}

/// The text of a panic's payload.
fn panic_message(p: &(dyn std::any::Any + Send)) -> String {
    if let Some(s) = p.downcast_ref::<&str>() {
        (*s).to_string()
    } else if let Some(s) = p.downcast_ref::<String>() {
        s.clone()
    } else {
        "panic with a non-text payload".to_string()
    }
}

/// Run `work` with the GIL released; a panic becomes a `ComputationError`.
fn detached<T: Send>(
    py: Python<'_>,
    work: impl FnOnce() -> Result<T, Fault> + Send,
) -> PyResult<T> {
    py.detach(|| {
        catch_unwind(AssertUnwindSafe(work)).unwrap_or_else(|p| {
            Err(Fault::Computation(format!(
                "internal error (panic): {}",
                panic_message(p.as_ref())
            )))
        })
    })
    .map_err(PyErr::from)
}

fn serialize<T: serde::Serialize>(v: &T) -> Result<Value, Fault> {
    serde_json::to_value(v).map_err(|e| Fault::Computation(format!("result conversion: {e}")))
}

/// Keys whose values become numpy arrays: rows of 3 or 2 coordinates, or flat numbers.
fn array_width(key: &str) -> Option<usize> {
    match key {
        "points" | "control_points" | "vertices" => Some(3),
        "uv_a" | "uv_b" | "control_points_uv_a" | "control_points_uv_b" | "domain_polyline" => {
            Some(2)
        }
        "knots" | "knots_u" | "knots_v" | "weights" => Some(0),
        _ => None,
    }
}

/// A list of numbers (width 0) or of rows of `width` numbers as an array; `None` when it is
/// not one (nulls, ragged rows).
fn as_array<'py>(py: Python<'py>, v: &[Value], width: usize) -> Option<Bound<'py, PyAny>> {
    if width == 0 {
        let xs: Option<Vec<f64>> = v.iter().map(Value::as_f64).collect();
        return Some(Array1::from(xs?).into_pyarray(py).into_any());
    }
    let mut flat = Vec::with_capacity(v.len() * width);
    for row in v {
        let row = row.as_array()?;
        if row.len() != width {
            return None;
        }
        for x in row {
            flat.push(x.as_f64()?);
        }
    }
    Array2::from_shape_vec((v.len(), width), flat)
        .ok()
        .map(|a| a.into_pyarray(py).into_any())
}

/// A JSON value as Python objects; the arrays under the keys of [`array_width`] as numpy
/// arrays.
fn to_py<'py>(py: Python<'py>, v: &Value, key: Option<&str>) -> PyResult<Bound<'py, PyAny>> {
    Ok(match v {
        Value::Null => py.None().into_bound(py),
        Value::Bool(b) => b.into_pyobject(py)?.to_owned().into_any(),
        Value::Number(n) => {
            if let Some(i) = n.as_i64() {
                i.into_pyobject(py)?.into_any()
            } else if let Some(u) = n.as_u64() {
                u.into_pyobject(py)?.into_any()
            } else {
                n.as_f64().unwrap_or(f64::NAN).into_pyobject(py)?.into_any()
            }
        }
        Value::String(s) => s.into_pyobject(py)?.into_any(),
        Value::Array(xs) => {
            if let Some(w) = key.and_then(array_width)
                && let Some(a) = as_array(py, xs, w)
            {
                return Ok(a);
            }
            let items = xs
                .iter()
                .map(|x| to_py(py, x, None))
                .collect::<PyResult<Vec<_>>>()?;
            PyList::new(py, items)?.into_any()
        }
        Value::Object(m) => {
            let d = PyDict::new(py);
            for (k, x) in m {
                d.set_item(k, to_py(py, x, Some(k))?)?;
            }
            d.into_any()
        }
    })
}

/// A NURBS surface: degrees, knots, the control net `(nu, nv, 3)` and weights `(nu, nv)`.
fn surface_py<'py>(py: Python<'py>, s: &NurbsSurface<f64, 3>) -> PyResult<Bound<'py, PyDict>> {
    let (pts, w) = s.points_weights();
    let (nu, nv) = (s.hom.nu(), s.hom.nv());
    let (du, dv) = s.hom.degrees();
    let flat: Vec<f64> = pts.iter().flatten().copied().collect();
    let d = PyDict::new(py);
    d.set_item("degree_u", du)?;
    d.set_item("degree_v", dv)?;
    d.set_item(
        "knots_u",
        PyArray1::from_slice(py, s.hom.ku.knots()).into_any(),
    )?;
    d.set_item(
        "knots_v",
        PyArray1::from_slice(py, s.hom.kv.knots()).into_any(),
    )?;
    let net = Array3::from_shape_vec((nu, nv, 3), flat)
        .map_err(|e| ComputationError::new_err(e.to_string()))?;
    d.set_item("control_points", net.into_pyarray(py))?;
    let w = Array2::from_shape_vec((nu, nv), w)
        .map_err(|e| ComputationError::new_err(e.to_string()))?;
    d.set_item("weights", w.into_pyarray(py))?;
    Ok(d)
}

/// A NURBS curve of dimension `D`: degree, knots, control points `(n, D)`, weights `(n,)`.
fn curve_py<'py, const D: usize>(
    py: Python<'py>,
    c: &NurbsCurve<f64, D>,
) -> PyResult<Bound<'py, PyDict>> {
    let (pts, w) = c.points_weights();
    let flat: Vec<f64> = pts.iter().flatten().copied().collect();
    let d = PyDict::new(py);
    d.set_item("dimension", D)?;
    d.set_item("degree", c.hom.degree())?;
    d.set_item(
        "knots",
        PyArray1::from_slice(py, c.hom.knots.knots()).into_any(),
    )?;
    let p = Array2::from_shape_vec((pts.len(), D), flat)
        .map_err(|e| ComputationError::new_err(e.to_string()))?;
    d.set_item("control_points", p.into_pyarray(py))?;
    d.set_item("weights", PyArray1::from_vec(py, w))?;
    Ok(d)
}

/// The model as a dict: unit, surfaces, curves, triangulations, B-rep counts, warnings.
fn model_py<'py>(py: Python<'py>, m: &Model) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("unit", m.unit.clone())?;
    let surfaces = PyList::empty(py);
    for s in &m.surfaces {
        let x = surface_py(py, &s.nurbs)?;
        x.set_item("name", &s.name)?;
        x.set_item("source", s.source.clone())?;
        x.set_item("kind", format!("{:?}", s.kind))?;
        x.set_item("reversed", s.reversed)?;
        x.set_item("trim_loops", s.trim_loops.len())?;
        surfaces.append(x)?;
    }
    d.set_item("surfaces", surfaces)?;
    let curves = PyList::empty(py);
    for c in &m.curves {
        let x = match &c.geometry {
            CurveGeometry::Domain(g) => curve_py(py, g)?,
            CurveGeometry::Space(g) => curve_py(py, g)?,
        };
        x.set_item("name", &c.name)?;
        curves.append(x)?;
    }
    d.set_item("curves", curves)?;
    let tris = PyList::empty(py);
    for t in &m.triangulations {
        let x = PyDict::new(py);
        x.set_item("name", &t.name)?;
        let v: Vec<f64> = t.vertices.iter().flatten().copied().collect();
        let v = Array2::from_shape_vec((t.vertices.len(), 3), v)
            .map_err(|e| ComputationError::new_err(e.to_string()))?;
        x.set_item("vertices", v.into_pyarray(py))?;
        let f: Vec<u32> = t.triangles.iter().flatten().copied().collect();
        let f = Array2::from_shape_vec((t.triangles.len(), 3), f)
            .map_err(|e| ComputationError::new_err(e.to_string()))?;
        x.set_item("triangles", f.into_pyarray(py))?;
        tris.append(x)?;
    }
    d.set_item("triangulations", tris)?;
    d.set_item("brep_faces", m.brep.as_ref().map(|b| b.faces.len()))?;
    d.set_item("brep_edges", m.brep.as_ref().map(|b| b.edges.len()))?;
    d.set_item("warnings", m.warnings.clone())?;
    Ok(d)
}

fn read(path: &Path) -> Result<Model, Fault> {
    vericad::io::read_model(path).map_err(bad)
}

/// Read a model file (native JSON, STEP, IGES, STL, Plot3D).
#[pyfunction]
fn read_model(py: Python<'_>, path: PathBuf) -> PyResult<Py<PyAny>> {
    let m = detached(py, || read(&path))?;
    Ok(model_py(py, &m)?.into_any().unbind())
}

/// From now on, read STEP and IGES files whose faces are partly invalid by skipping those
/// faces (accounted `invalid`, named in the warnings), as the command line's `--skip-invalid`.
#[pyfunction]
fn set_skip_invalid(on: bool) {
    vericad::io::set_skip_invalid_faces(on);
}

/// The model's summary, as `vericad info --json` prints it.
#[pyfunction]
fn info(py: Python<'_>, path: PathBuf) -> PyResult<Py<PyAny>> {
    let v = detached(py, || {
        let m = read(&path)?;
        serialize(&vericad::tessellate::model_info(&m))
    })?;
    Ok(to_py(py, &v, None)?.unbind())
}

fn threads_arg(threads: Option<i64>) -> Result<Option<usize>, Fault> {
    match threads {
        None => Ok(None),
        Some(n) if (1..=vericad::budget::MAX_THREADS as i64).contains(&n) => Ok(Some(n as usize)),
        Some(n) => Err(bad(format!(
            "threads must be in 1..={}, not {n}",
            vericad::budget::MAX_THREADS
        ))),
    }
}

/// Intersect surfaces: `vericad ssi`.
#[pyfunction]
#[pyo3(signature = (file, file2=None, *, tol=1e-6, flatness=None, time_limit=None,
    untrimmed=false, threads=None, out=None, vtk=None, iges=None, fits=false, certify=true,
    svg=None, view=String::from("-60,25"), pieces=String::from("chords")))]
#[allow(clippy::too_many_arguments)]
fn ssi(
    py: Python<'_>,
    file: PathBuf,
    file2: Option<PathBuf>,
    tol: f64,
    flatness: Option<f64>,
    time_limit: Option<f64>,
    untrimmed: bool,
    threads: Option<i64>,
    out: Option<PathBuf>,
    vtk: Option<PathBuf>,
    iges: Option<PathBuf>,
    fits: bool,
    certify: bool,
    svg: Option<PathBuf>,
    view: String,
    pieces: String,
) -> PyResult<Py<PyAny>> {
    use vericad::ssi::job::{self, JobError};
    let v = detached(py, || {
        let threads = threads_arg(threads)?;
        let view = vericad::io::picture::View::parse(&view).map_err(bad)?;
        let pieces: vericad::ssi::Pieces = pieces.parse().map_err(bad)?;
        let prm = vericad::ssi::SsiParams {
            tol,
            flatness,
            time_limit,
            respect_trims: !untrimmed,
            certify,
            pieces,
            ..Default::default()
        };
        let outputs = job::Outputs {
            progress: Default::default(),
            json: out.as_deref(),
            vtk: vtk.as_deref(),
            iges: iges.as_deref(),
            fits,
            svg: svg.as_deref(),
            view,
        };
        let r = job::run(&file, file2.as_deref(), &prm, threads, outputs)
            .map_err(|e| fault(&e, e.is_bad_input(), matches!(e, JobError::Write(..))))?;
        serialize(&r)
    })?;
    Ok(to_py(py, &v, None)?.unbind())
}

/// Check another system's intersection curves: `vericad certify-ssi`.
#[pyfunction]
#[pyo3(signature = (a, b=None, *, curves, tol=1e-6, match_distance=None, out=None))]
fn certify_ssi(
    py: Python<'_>,
    a: PathBuf,
    b: Option<PathBuf>,
    curves: PathBuf,
    tol: f64,
    match_distance: Option<f64>,
    out: Option<PathBuf>,
) -> PyResult<Py<PyAny>> {
    use vericad::ssi::job::{JobError, run_certify};
    let v = detached(py, || {
        let prm = vericad::ssi::SsiParams {
            tol,
            ..Default::default()
        };
        let r = run_certify(
            &a,
            b.as_deref(),
            &curves,
            &prm,
            match_distance,
            (out.as_deref(), Default::default()),
        )
        .map_err(|e| fault(&e, e.is_bad_input(), matches!(e, JobError::Write(..))))?;
        serialize(&r)
    })?;
    Ok(to_py(py, &v, None)?.unbind())
}

/// A curve of a surface's domain as a curve on it: `vericad curve-on-surface`.
#[pyfunction]
#[pyo3(signature = (surface, curve, *, tol=1e-3, angle=10.0, bound="local", exact=false,
    evidence=0, out=None, svg=None, iges=None, vtk=None, svg_3d=None,
    view=String::from("-60,25")))]
#[allow(clippy::too_many_arguments)]
fn curve_on_surface(
    py: Python<'_>,
    surface: String,
    curve: String,
    tol: f64,
    angle: f64,
    bound: &str,
    exact: bool,
    evidence: usize,
    out: Option<PathBuf>,
    svg: Option<PathBuf>,
    iges: Option<PathBuf>,
    vtk: Option<PathBuf>,
    svg_3d: Option<PathBuf>,
    view: String,
) -> PyResult<Py<PyAny>> {
    use vericad::curve_on_surface::{Bound, Params, job};
    let Some(bound) = Bound::from_name(bound) else {
        return Err(bad(format!("bound must be `local` or `paper`, not `{bound}`")).into());
    };
    let view = vericad::io::picture::View::parse(&view).map_err(bad)?;
    let v = detached(py, || {
        let params = Params::from_options(tol, angle, bound, exact, evidence);
        let outputs = job::Outputs {
            progress: Default::default(),
            json: out.as_deref(),
            svg: svg.as_deref(),
            iges: iges.as_deref(),
            vtk: vtk.as_deref(),
            svg_3d: svg_3d.as_deref(),
            view,
        };
        let r = job::run(&surface, &curve, &params, outputs)
            .map_err(|e| fault(&e, e.is_bad_input(), matches!(e, job::JobError::Write(..))))?;
        serialize(&r)
    })?;
    Ok(to_py(py, &v, None)?.unbind())
}

/// Certified curves along the loops of B-rep faces: `vericad curve-on-surface --face`.
#[pyfunction]
#[pyo3(signature = (file, faces="all", *, tol=1e-3, angle=10.0, bound="local", exact=false,
    out=None, iges=None))]
#[allow(clippy::too_many_arguments)]
fn curve_on_faces(
    py: Python<'_>,
    file: String,
    faces: &str,
    tol: f64,
    angle: f64,
    bound: &str,
    exact: bool,
    out: Option<PathBuf>,
    iges: Option<PathBuf>,
) -> PyResult<Py<PyAny>> {
    use vericad::curve_on_surface::{Bound, Params, face_job};
    let Some(bound) = Bound::from_name(bound) else {
        return Err(bad(format!("bound must be `local` or `paper`, not `{bound}`")).into());
    };
    let v = detached(py, || {
        let params = Params::from_options(tol, angle, bound, exact, 0);
        let r = face_job::run(
            &file,
            faces,
            &params,
            (out.as_deref(), iges.as_deref()),
            Default::default(),
        )
        .map_err(
            |e| {
                fault(
                    &e,
                    e.is_bad_input(),
                    matches!(e, vericad::curve_on_surface::job::JobError::Write(..)),
                )
            },
        )?;
        serialize(&r)
    })?;
    Ok(to_py(py, &v, None)?.unbind())
}

/// Repair a patch set or a B-rep's faces: `vericad repair`. Returns `{"report": ...,
/// "patches": [...]}` (no patches from the faces repair, which writes its B-rep to `out`).
/// `mode`: `"auto"` (faces when the B-rep has trimmed faces), `"patches"` or `"faces"`.
#[pyfunction]
#[pyo3(signature = (input, *, mode=String::from("auto"), u1=1e-3, u2=1e-3, feature_angle=30.0,
    features=None, out=None, report=None, vtk=None, svg=None, view=String::from("-60,25")))]
#[allow(clippy::too_many_arguments)]
fn repair(
    py: Python<'_>,
    input: PathBuf,
    mode: String,
    u1: f64,
    u2: f64,
    feature_angle: f64,
    features: Option<PathBuf>,
    out: Option<PathBuf>,
    report: Option<PathBuf>,
    vtk: Option<PathBuf>,
    svg: Option<PathBuf>,
    view: String,
) -> PyResult<Py<PyAny>> {
    use vericad::repair::faces::job::{Mode, Repaired, run};
    use vericad::repair::job;
    let r = detached(py, || {
        let view = vericad::io::picture::View::parse(&view).map_err(bad)?;
        let mode: Mode = mode.parse().map_err(bad)?;
        let prm = vericad::repair::RepairParams {
            u1,
            u2,
            feature_angle_deg: feature_angle,
            ..Default::default()
        };
        let outputs = job::Outputs {
            progress: Default::default(),
            model: out.as_deref(),
            report: report.as_deref(),
            vtk: vtk.as_deref(),
            svg: svg.as_deref(),
            view,
        };
        let r = run(&input, &prm, features.as_deref(), outputs, mode)
            .map_err(|e| fault(&e, e.is_bad_input(), matches!(e, job::JobError::Write(..))))?;
        Ok(match r {
            Repaired::Patches(r) => (serialize(&r.report)?, r.patches),
            Repaired::Faces(r) => (serialize(&r.report)?, Vec::new()),
        })
    })?;
    let d = PyDict::new(py);
    d.set_item("report", to_py(py, &r.0, None)?)?;
    let patches = PyList::empty(py);
    for s in &r.1 {
        patches.append(surface_py(py, s)?)?;
    }
    d.set_item("patches", patches)?;
    Ok(d.into_any().unbind())
}

/// Reparametrize faces to chord length: `vericad reparam`.
#[pyfunction]
#[pyo3(signature = (model, *, tol=1e-4, max_lines=500, bound=true, out=None, report=None,
    svg=None, vtk=None))]
#[allow(clippy::too_many_arguments)]
fn reparam(
    py: Python<'_>,
    model: String,
    tol: f64,
    max_lines: i64,
    bound: bool,
    out: Option<PathBuf>,
    report: Option<PathBuf>,
    svg: Option<PathBuf>,
    vtk: Option<PathBuf>,
) -> PyResult<Py<PyAny>> {
    use vericad::reparam::job;
    let v = detached(py, || {
        let max_lines = usize::try_from(max_lines)
            .map_err(|_| bad(format!("max_lines {max_lines}: must not be negative")))?;
        let params = vericad::reparam::Params {
            tol,
            max_lines,
            prove_bound: bound,
            ..Default::default()
        };
        let outputs = job::Outputs {
            progress: Default::default(),
            model: out.as_deref(),
            report: report.as_deref(),
            svg: svg.as_deref(),
            vtk: vtk.as_deref(),
        };
        let r = job::run(&model, &params, outputs)
            .map_err(|e| fault(&e, e.is_bad_input(), matches!(e, job::JobError::Write(..))))?;
        serialize(&r)
    })?;
    Ok(to_py(py, &v, None)?.unbind())
}

/// The Coons approximant's parameters, as `vericad coons` and `vericad approximate` take them.
fn coons_params(
    tol: f64,
    m: i64,
    n: i64,
    max_resolution: i64,
    closure: Option<f64>,
    k: i64,
) -> Result<vericad::approx::coons::Params, Fault> {
    let count = |name: &str, v: i64| -> Result<usize, Fault> {
        usize::try_from(v).map_err(|_| bad(format!("{name} {v}: must not be negative")))
    };
    Ok(vericad::approx::coons::Params {
        tol,
        m: count("m", m)?,
        n: count("n", n)?,
        max_resolution: count("max_resolution", max_resolution)?,
        closure,
        k_nearest: count("k", k)?,
        ..Default::default()
    })
}

/// One Coons approximant over four boundary curves: `vericad coons`. Returns
/// `{"report": ..., "surface": ...}`.
#[pyfunction]
#[pyo3(signature = (model, *, boundary, tol=1e-3, m=8, n=8, max_resolution=128, closure=None,
    k=8, out=None, report=None, vtk=None))]
#[allow(clippy::too_many_arguments)]
fn coons(
    py: Python<'_>,
    model: PathBuf,
    boundary: PathBuf,
    tol: f64,
    m: i64,
    n: i64,
    max_resolution: i64,
    closure: Option<f64>,
    k: i64,
    out: Option<PathBuf>,
    report: Option<PathBuf>,
    vtk: Option<PathBuf>,
) -> PyResult<Py<PyAny>> {
    use vericad::approx::coons::job;
    let (rep, surface) = detached(py, || {
        let params = coons_params(tol, m, n, max_resolution, closure, k)?;
        let outputs = job::Outputs {
            progress: Default::default(),
            model: out.as_deref(),
            report: report.as_deref(),
            vtk: vtk.as_deref(),
        };
        let (r, s) = job::run_surface(&model, &boundary, &params, outputs)
            .map_err(|e| fault(&e, e.is_bad_input(), matches!(e, job::JobError::Write(..))))?;
        Ok((serialize(&r)?, s))
    })?;
    let d = PyDict::new(py);
    d.set_item("report", to_py(py, &rep, None)?)?;
    d.set_item("surface", surface_py(py, &surface)?)?;
    Ok(d.into_any().unbind())
}

/// Many Coons approximants over a layout: `vericad approximate`. Returns
/// `{"report": ..., "surfaces": [...]}`.
#[pyfunction]
#[pyo3(signature = (model, *, layout, tol=1e-3, m=8, n=8, max_resolution=128, closure=None,
    k=8, out=None, report=None, vtk=None))]
#[allow(clippy::too_many_arguments)]
fn approximate(
    py: Python<'_>,
    model: PathBuf,
    layout: PathBuf,
    tol: f64,
    m: i64,
    n: i64,
    max_resolution: i64,
    closure: Option<f64>,
    k: i64,
    out: Option<PathBuf>,
    report: Option<PathBuf>,
    vtk: Option<PathBuf>,
) -> PyResult<Py<PyAny>> {
    use vericad::approx::coons::layout_job::{self, ApproximateError};
    let (rep, surfaces) = detached(py, || {
        let params = coons_params(tol, m, n, max_resolution, closure, k)?;
        let outputs = layout_job::Outputs {
            progress: Default::default(),
            model: out.as_deref(),
            report: report.as_deref(),
            vtk: vtk.as_deref(),
        };
        let r = layout_job::run(&model, &layout, &params, outputs).map_err(|e| {
            fault(
                &e,
                e.is_bad_input(),
                matches!(e, ApproximateError::Write(..)),
            )
        })?;
        let surfaces: Vec<_> = r.approximants.into_iter().map(|a| a.surface).collect();
        Ok((serialize(&r.report)?, surfaces))
    })?;
    let d = PyDict::new(py);
    d.set_item("report", to_py(py, &rep, None)?)?;
    let list = PyList::empty(py);
    for s in &surfaces {
        list.append(surface_py(py, s)?)?;
    }
    d.set_item("surfaces", list)?;
    Ok(d.into_any().unbind())
}

/// The batch job named `job` with the options `vericad batch` checks the same way.
fn batch_job(job: &str, tol: f64, time_limit: Option<f64>) -> Result<vericad::batch::Job, Fault> {
    use vericad::batch::Job;
    if let Some(t) = time_limit
        && !(t.is_finite() && t > 0.0)
    {
        return Err(bad(format!(
            "time_limit must be a positive number of seconds, not {t}"
        )));
    }
    if !(tol.is_finite() && tol > 0.0) {
        return Err(bad(format!(
            "tol must be a positive finite number, not {tol}"
        )));
    }
    let j = match job {
        "info" => Job::Info,
        "ssi" => Job::Ssi { tol, time_limit },
        "repair" => Job::Repair(
            vericad::repair::RepairParams::default(),
            vericad::repair::faces::job::Mode::Auto,
        ),
        other => {
            return Err(bad(format!(
                "job must be `info`, `ssi` or `repair`, not `{other}`"
            )));
        }
    };
    j.validate().map_err(bad)?;
    Ok(j)
}

/// Check a batch job's name and options as `vericad batch` does (raises `BadInputError`).
#[pyfunction]
#[pyo3(signature = (job="info", *, tol=1e-6, time_limit=None))]
fn batch_check(job: &str, tol: f64, time_limit: Option<f64>) -> PyResult<()> {
    batch_job(job, tol, time_limit)?;
    Ok(())
}

/// One model's batch record as the JSON line `vericad batch` writes (without the newline).
/// Faults of the model (unreadable file, failed job, panic) are in the record, not raised.
/// With `threads`, the job runs in a pool of that many threads (otherwise in rayon's global
/// pool, one thread per core).
#[pyfunction]
#[pyo3(signature = (path, job="info", *, tol=1e-6, time_limit=None, threads=None))]
fn batch_record_line(
    py: Python<'_>,
    path: PathBuf,
    job: &str,
    tol: f64,
    time_limit: Option<f64>,
    threads: Option<i64>,
) -> PyResult<String> {
    let job = batch_job(job, tol, time_limit)?;
    let threads = threads_arg(threads)?;
    detached(py, || {
        let record = || job.record(&path);
        let r = match threads {
            None => record(),
            Some(n) => rayon::ThreadPoolBuilder::new()
                .num_threads(n)
                .build()
                .map_err(|e| Fault::Computation(format!("thread pool: {e}")))?
                .install(record),
        };
        r.to_line()
            .map_err(|e| Fault::Computation(format!("record: {e}")))
    })
}

/// The models `vericad batch` would run on for these inputs (directories, files, `@LIST`),
/// sorted, without repeats.
#[pyfunction]
fn discover(py: Python<'_>, inputs: Vec<String>) -> PyResult<Vec<String>> {
    detached(py, || {
        let found = vericad::batch::discover(&inputs).map_err(bad)?;
        Ok(found.iter().map(|p| p.display().to_string()).collect())
    })
}

/// Run `vericad batch` in this process (rayon threads): records appended to `out`, models
/// with records there skipped. Returns the counts by status and the wall time.
#[pyfunction]
#[pyo3(signature = (inputs, job="info", *, out, tol=1e-6, time_limit=None, threads=None,
    shard=None))]
#[allow(clippy::too_many_arguments)]
fn batch(
    py: Python<'_>,
    inputs: Vec<String>,
    job: &str,
    out: PathBuf,
    tol: f64,
    time_limit: Option<f64>,
    threads: Option<i64>,
    shard: Option<String>,
) -> PyResult<Py<PyAny>> {
    let job = batch_job(job, tol, time_limit)?;
    let v = detached(py, || {
        let threads = threads_arg(threads)?;
        let shard = match shard.as_deref().map(vericad::batch::parse_shard) {
            None => None,
            Some(Ok(s)) => Some(s),
            Some(Err(e)) => return Err(bad(e)),
        };
        let opts = vericad::batch::Options {
            inputs,
            job,
            out,
            shard,
            threads,
            progress: Default::default(),
        };
        let s = vericad::batch::run(&opts).map_err(|e| fault(&e, e.is_bad_input(), true))?;
        let counts: serde_json::Map<String, Value> = vericad::batch::Status::ALL
            .iter()
            .map(|st| (st.name().to_string(), Value::from(s.count(*st))))
            .collect();
        Ok(serde_json::json!({
            "models": s.models,
            "resumed": s.resumed,
            "counts": counts,
            "seconds": s.seconds,
        }))
    })?;
    Ok(to_py(py, &v, None)?.unbind())
}

/// The records already in a batch output (none when it does not exist), as dicts; a last
/// line cut short is removed from the file, as `vericad batch` does when it resumes.
#[pyfunction]
fn read_records(py: Python<'_>, out: PathBuf) -> PyResult<Py<PyAny>> {
    let v = detached(py, || {
        let r = vericad::batch::read_done(&out).map_err(|e| fault(&e, e.is_bad_input(), true))?;
        serialize(&r)
    })?;
    Ok(to_py(py, &v, None)?.unbind())
}

#[pymodule]
fn _vericad(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("VericadError", py.get_type::<VericadError>())?;
    m.add("BadInputError", py.get_type::<BadInputError>())?;
    m.add("ComputationError", py.get_type::<ComputationError>())?;
    m.add("OutputError", py.get_type::<OutputError>())?;
    m.add_function(wrap_pyfunction!(read_model, m)?)?;
    m.add_function(wrap_pyfunction!(info, m)?)?;
    m.add_function(wrap_pyfunction!(set_skip_invalid, m)?)?;
    m.add_function(wrap_pyfunction!(ssi, m)?)?;
    m.add_function(wrap_pyfunction!(certify_ssi, m)?)?;
    m.add_function(wrap_pyfunction!(curve_on_surface, m)?)?;
    m.add_function(wrap_pyfunction!(curve_on_faces, m)?)?;
    m.add_function(wrap_pyfunction!(repair, m)?)?;
    m.add_function(wrap_pyfunction!(reparam, m)?)?;
    m.add_function(wrap_pyfunction!(coons, m)?)?;
    m.add_function(wrap_pyfunction!(approximate, m)?)?;
    m.add_function(wrap_pyfunction!(batch_check, m)?)?;
    m.add_function(wrap_pyfunction!(batch_record_line, m)?)?;
    m.add_function(wrap_pyfunction!(discover, m)?)?;
    m.add_function(wrap_pyfunction!(batch, m)?)?;
    m.add_function(wrap_pyfunction!(read_records, m)?)?;
    Ok(())
}
