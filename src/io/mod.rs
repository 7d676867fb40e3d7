//! Readers and writers of exchange and viewing formats, one file (or folder) per format.
//! [`read_model`] picks the reader from the file's extension.

pub mod iges;
pub mod json_text;
pub mod obj;
pub mod picture;
pub mod plot3d;
pub mod step;
pub mod stl;
pub mod svg;
pub mod vtk;

use crate::model::{Model, ModelError};

/// A fault reading any supported format.
#[derive(Debug, thiserror::Error)]
pub enum ReadError {
    #[error(transparent)]
    Json(#[from] ModelError),
    #[error(transparent)]
    Step(#[from] step::StepError),
    #[error(transparent)]
    Iges(#[from] iges::IgesError),
    #[error(transparent)]
    Stl(#[from] stl::StlError),
    #[error(transparent)]
    Plot3d(#[from] plot3d::Plot3dError),
    #[error("{0}: unknown file type (expected .json, .step/.stp, .igs/.iges, .stl, .xyz/.p3d)")]
    UnknownFormat(String),
}

/// The formats [`read_model`] knows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    Json,
    Step,
    Iges,
    Stl,
    Plot3d,
}

/// Format from a file name's extension (case-insensitive).
pub fn format_of(path: &std::path::Path) -> Option<Format> {
    match path.extension()?.to_str()?.to_ascii_lowercase().as_str() {
        "json" => Some(Format::Json),
        "step" | "stp" | "p21" => Some(Format::Step),
        "igs" | "iges" => Some(Format::Iges),
        "stl" => Some(Format::Stl),
        "xyz" | "p3d" | "x" | "g" => Some(Format::Plot3d),
        _ => None,
    }
}

/// Whether the STEP and IGES readers skip a face whose own geometry is invalid (non-finite
/// or malformed surface, or its trims) instead of refusing the file.
static SKIP_INVALID_FACES: std::sync::atomic::AtomicBool =
    std::sync::atomic::AtomicBool::new(false);

/// From now on, read a STEP or IGES file whose faces are partly invalid by skipping those
/// faces: each one is accounted `invalid` (with its id and the reason) in the model's
/// accounts, named in a warning, and left out of the B-rep as a face without a surface.
/// Faults of the file as a whole (syntax, units, an exhausted expansion budget) still refuse
/// it. The command line's `--skip-invalid`; off by default (a fault refuses the file).
pub fn set_skip_invalid_faces(on: bool) {
    SKIP_INVALID_FACES.store(on, std::sync::atomic::Ordering::Relaxed);
}

/// How the STEP and IGES readers treat faulty faces.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ReadOptions {
    /// Skip (and account) a face whose own geometry is invalid instead of refusing the file
    /// (see [`set_skip_invalid_faces`]).
    pub skip_invalid_faces: bool,
}

impl ReadOptions {
    /// The options [`read_model`] and the readers' `from_str` use: off unless
    /// [`set_skip_invalid_faces`] turned skipping on.
    pub fn current() -> ReadOptions {
        ReadOptions {
            skip_invalid_faces: SKIP_INVALID_FACES.load(std::sync::atomic::Ordering::Relaxed),
        }
    }
}

/// Read a model file of any supported format.
pub fn read_model(path: &std::path::Path) -> Result<Model, ReadError> {
    match format_of(path) {
        Some(Format::Json) => Ok(crate::model::json::read(path)?),
        Some(Format::Step) => Ok(step::read(path)?),
        Some(Format::Iges) => Ok(iges::read(path)?),
        Some(Format::Stl) => Ok(stl::read(path)?),
        Some(Format::Plot3d) => Ok(plot3d::read(path)?),
        None => Err(ReadError::UnknownFormat(path.display().to_string())),
    }
}

/// A fault writing a model.
#[derive(Debug, thiserror::Error)]
pub enum WriteError {
    #[error(
        "{0}: unknown or unsupported output type (expected .json, .step/.stp, .igs/.iges, .stl)"
    )]
    UnknownFormat(String),
    #[error("{0}: the model has no triangulation to write as STL")]
    NoTriangulation(String),
    #[error("cannot write {0}: {1}")]
    Io(String, std::io::Error),
    #[error(
        "{0}: vertex {1} has coordinate {2:e}, beyond the f32 range of binary STL (it would be written as infinity)"
    )]
    NotRepresentable(String, usize, f64),
}

/// Write `bytes` to `path` atomically: into a temporary file in the same directory, then
/// renamed over `path`. A failed write (disk full, file size limit) leaves the previous
/// file untouched and removes the temporary file.
pub fn write_atomic(path: &std::path::Path, bytes: impl AsRef<[u8]>) -> std::io::Result<()> {
    use std::io::Write;
    write_atomic_with(path, |f| f.write_all(bytes.as_ref()))
}

/// [`write_atomic`] with the content written by `fill` (for output streamed as it is made).
pub fn write_atomic_with(
    path: &std::path::Path,
    fill: impl FnOnce(&mut std::fs::File) -> std::io::Result<()>,
) -> std::io::Result<()> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => std::path::PathBuf::from("."),
    };
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "output".into());
    let tmp = dir.join(format!(".{name}.{}.tmp", std::process::id()));
    let result = (|| {
        let mut f = std::fs::File::create(&tmp)?;
        fill(&mut f)?;
        f.sync_all()?;
        drop(f);
        std::fs::rename(&tmp, path)
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}

/// Check, before a long run, that `path` can be written the way [`write_atomic`] writes it:
/// a temporary file in its directory is created and removed again; an existing file at
/// `path` is not touched.
pub fn check_writable(path: &std::path::Path) -> std::io::Result<()> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => std::path::PathBuf::from("."),
    };
    if path.is_dir() {
        return Err(std::io::Error::other("is a directory"));
    }
    let tmp = dir.join(format!(".vericad-write-check.{}.tmp", std::process::id()));
    std::fs::File::create(&tmp)?;
    std::fs::remove_file(&tmp)
}

/// `s` at the `(n + 1)²` points of an `n × n` grid of its domain, `u` major: the point
/// `(i, j)` is at index `i (n + 1) + j` (the views' surface sampling).
pub fn surface_grid(s: &crate::spline::NurbsSurface<f64, 3>, n: usize) -> Vec<[f64; 3]> {
    let (u0, u1, v0, v1) = s.hom.domain();
    let mut pts = Vec::with_capacity((n + 1) * (n + 1));
    for i in 0..=n {
        for j in 0..=n {
            let (u, v) = (
                u0 + (u1 - u0) * i as f64 / n as f64,
                v0 + (v1 - v0) * j as f64 / n as f64,
            );
            pts.push(s.eval(&u, &v));
        }
    }
    pts
}

/// [`check_writable`] for every given path; the first that cannot be written, with why.
pub fn check_all_writable<'a>(
    paths: impl IntoIterator<Item = Option<&'a std::path::Path>>,
) -> Result<(), (&'a std::path::Path, std::io::Error)> {
    for p in paths.into_iter().flatten() {
        check_writable(p).map_err(|e| (p, e))?;
    }
    Ok(())
}

/// Write a model in the format named by the path's extension.
pub fn write_model(
    path: &std::path::Path,
    m: &crate::model::Model,
) -> Result<Vec<String>, WriteError> {
    write_model_as(path, m, None)
}

/// The model as mesh formats see it: the B-rep's faces triangulated inside their trims (one
/// triangulation, shared edges with shared vertices), no surfaces; and a line for every face
/// left out.
fn trimmed_mesh_model(
    m: &crate::model::Model,
    b: &crate::brep::Brep,
    chordal: Option<f64>,
    prove: bool,
) -> (crate::model::Model, Vec<String>, Option<Chordal>) {
    let (mesh, reached) = match chordal {
        Some(tol) => {
            let (mesh, c) = crate::tessellate::chordal::mesh_within(m, b, tol, prove);
            (mesh, Some(c))
        }
        None => (
            crate::tessellate::mesh_brep(m, b, &crate::tessellate::MeshParams::default()),
            None,
        ),
    };
    let mut notes = mesh.issues(b);
    let ok = mesh.faces.iter().filter(|f| f.is_ok()).count();
    if ok < b.faces.len() {
        notes.push(format!(
            "{} of {} faces triangulated; the others are missing from the output",
            ok,
            b.faces.len()
        ));
    }
    (with_mesh(m, mesh.triangulation), notes, reached)
}

/// The model a mesh format gets: `mesh`, then the model's own triangulations; its unit and
/// warnings, no surfaces.
fn with_mesh(m: &crate::model::Model, mesh: crate::model::Triangulation) -> crate::model::Model {
    let mut triangulations = vec![mesh];
    triangulations.extend(m.triangulations.iter().cloned());
    crate::model::Model {
        unit: m.unit.clone(),
        triangulations,
        warnings: m.warnings.clone(),
        ..Default::default()
    }
}

pub use crate::tessellate::chordal::Chordal;

/// Format names accepted by `--format`.
pub const FORMAT_NAMES: &str = "json, step, iges, iges-faces, stl, stl-binary, vtp, obj";

/// Write a model in the format named by `format` (see [`FORMAT_NAMES`]) or, when `None`, by
/// the path's extension. Returns what the format could not hold (e.g. trim loops in IGES 128 / STEP geometric sets), so nothing is lost
/// silently.
pub fn write_model_as(
    path: &std::path::Path,
    m: &crate::model::Model,
    format: Option<&str>,
) -> Result<Vec<String>, WriteError> {
    Ok(write_model_chordal(path, m, format, None, false)?.0)
}

/// The output format a write takes: `format` when given, else the path's extension; lower
/// case (see [`FORMAT_NAMES`]).
pub fn output_format(path: &std::path::Path, format: Option<&str>) -> String {
    format
        .or_else(|| path.extension().and_then(|e| e.to_str()))
        .unwrap_or("")
        .to_ascii_lowercase()
}

/// Whether an output format ([`output_format`]) holds triangles only: STL, OBJ, VTP.
pub fn is_mesh_format(ext: &str) -> bool {
    matches!(ext, "stl" | "stl-binary" | "vtp" | "obj")
}

/// [`write_model_as`], a B-rep written to a mesh format (STL, OBJ, VTP) triangulated until
/// its measured chordal deviation is at most `chordal` when given
/// ([`crate::tessellate::chordal`]); with what that refinement reached (`None` when nothing
/// was triangulated). A model of surfaces without a B-rep is triangulated surface by surface
/// (untrimmed, [`crate::tessellate::surfaces`]) for STL, and for OBJ and VTP when `chordal`
/// is given. With `prove` (and `chordal`), the final mesh also gets a proven bound on its
/// deviation ([`crate::tessellate::bound`]).
pub fn write_model_chordal(
    path: &std::path::Path,
    m: &crate::model::Model,
    format: Option<&str>,
    chordal: Option<f64>,
    prove: bool,
) -> Result<(Vec<String>, Option<Chordal>), WriteError> {
    let mut warnings = Vec::new();
    let ext = output_format(path, format);
    // `iges-faces`: IGES with a B-rep as trimmed surfaces rather than its B-rep entities.
    let (ext, brep_form) = match ext.as_str() {
        "iges-faces" => ("igs".to_string(), iges::write::BrepForm::TrimmedSurfaces),
        _ => (ext, iges::write::BrepForm::default()),
    };
    if let Some(b) = &m.brep {
        if is_mesh_format(&ext) {
            // Mesh formats get the faces triangulated inside their trims.
            let (meshed, mut notes, reached) = trimmed_mesh_model(m, b, chordal, prove);
            warnings.append(&mut notes);
            let mut rest = write_model_as(path, &meshed, Some(&ext))?;
            warnings.append(&mut rest);
            return Ok((warnings, reached));
        }
        if !matches!(
            format_of(std::path::Path::new(&format!("x.{ext}"))),
            Some(Format::Step | Format::Iges)
        ) {
            warnings.push(format!(
                "the B-rep topology ({} faces, their loops, edges and vertices) is not written: this writer stores the faces' surfaces, untrimmed",
                b.faces.len()
            ));
        }
    } else if !m.surfaces.is_empty()
        && (matches!(ext.as_str(), "stl" | "stl-binary")
            || (chordal.is_some() && matches!(ext.as_str(), "vtp" | "obj")))
    {
        // Surfaces without a B-rep, to a mesh format that holds triangles only (or a chordal
        // tolerance asked for): each surface triangulated whole.
        // Surfaces with their own trim loops are triangulated inside them; those whose
        // loops cannot be (crossing, winding twice...) are written untrimmed, each named.
        let (mesh, reached, notes) = crate::tessellate::surfaces::mesh_surfaces(m, chordal, prove);
        warnings.extend(notes);
        let mut rest = write_model_as(path, &with_mesh(m, mesh), Some(&ext))?;
        warnings.append(&mut rest);
        return Ok((warnings, reached));
    }
    let name0 = path.display().to_string();
    if ext == "stl-binary" {
        let t = m
            .triangulations
            .first()
            .ok_or_else(|| WriteError::NoTriangulation(name0.clone()))?;
        let bytes = stl::to_binary(t)
            .map_err(|(k, x)| WriteError::NotRepresentable(name0.clone(), k, x))?;
        write_atomic(path, bytes).map_err(|e| WriteError::Io(name0, e))?;
        return Ok((warnings, None));
    }
    let for_format = std::path::PathBuf::from(format!("x.{ext}"));
    let path_fmt = for_format.as_path();
    let trimmed = m
        .surfaces
        .iter()
        .filter(|s| !s.trim_loops.is_empty())
        .count();
    let fmt = format_of(path_fmt);
    if trimmed > 0 && !matches!(fmt, Some(Format::Json | Format::Iges)) {
        warnings.push(format!("{trimmed} surface(s) have trim loops, which this writer does not store: written untrimmed"));
    }
    if !m.triangulations.is_empty()
        && matches!(fmt, Some(Format::Json | Format::Step | Format::Iges))
    {
        warnings.push(format!(
            "{} triangulation(s) not written (the format holds NURBS only)",
            m.triangulations.len()
        ));
    }
    if matches!(fmt, Some(Format::Step | Format::Iges)) || matches!(ext.as_str(), "vtp" | "obj") {
        let domain: Vec<String> = m
            .curves
            .iter()
            .filter(|c| matches!(c.geometry, crate::model::CurveGeometry::Domain(_)))
            .map(|c| c.name.clone())
            .collect();
        if !domain.is_empty() {
            warnings.push(format!(
                "{} domain curve(s) (u, v) written as space curves (u, v, 0), which is how they read back: {}",
                domain.len(),
                crate::model::list_ids(domain)
            ));
        }
    }
    if matches!(fmt, Some(Format::Step | Format::Iges)) {
        let reversed = m.surfaces.iter().filter(|s| s.reversed).count();
        // A STEP B-rep keeps each face's orientation (`same_sense`); the IGES writer names
        // the reversed faces of a B-rep itself.
        let topology = m.brep.is_some();
        if reversed > 0 && !topology {
            warnings.push(format!(
                "{reversed} reversed face(s) (normal opposite to S_u x S_v): this writer stores surfaces, not faces, so the orientation is not kept"
            ));
        }
        if !m.patch_sets.is_empty() {
            warnings.push(format!(
                "{} patch set(s) not written (the writer stores one set of surfaces)",
                m.patch_sets.len()
            ));
        }
    }
    if fmt == Some(Format::Step)
        && let Some(u) = &m.unit
        && !step::write::unit_supported(u)
    {
        warnings.push(format!(
            "unit '{u}' has no STEP form in this writer: coordinates written unchanged, labelled mm"
        ));
    }
    let name = path.display().to_string();
    let stem = path
        .file_name()
        .and_then(|s| s.to_str())
        .unwrap_or("vericad");
    let text = match format_of(path_fmt) {
        Some(Format::Json) => crate::model::json::to_string(m),
        Some(Format::Step) => {
            let (text, mut notes) = step::write::write(m, stem);
            warnings.append(&mut notes);
            text
        }
        Some(Format::Iges) => {
            let (text, mut notes) = iges::write::write_with(m, stem, brep_form);
            warnings.append(&mut notes);
            text
        }
        Some(Format::Plot3d) => return Err(WriteError::UnknownFormat(name)),
        Some(Format::Stl) => match m.triangulations.first() {
            Some(t) => stl::to_string(t),
            None => return Err(WriteError::NoTriangulation(name)),
        },
        None => match Some(ext.as_str()) {
            Some("vtp") => vtk::model_to_vtp(m, 16),
            Some("obj") => obj::model_to_obj(m, 16),
            _ => return Err(WriteError::UnknownFormat(name)),
        },
    };
    write_atomic(path, text).map_err(|e| WriteError::Io(name, e))?;
    Ok((warnings, None))
}
