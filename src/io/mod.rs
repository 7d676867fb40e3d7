//! Readers and writers of exchange and viewing formats, one file (or folder) per format.
//! [`read_model`] picks the reader from the file's extension.

pub mod iges;
pub mod obj;
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
}

/// Write a model in the format named by the path's extension.
pub fn write_model(
    path: &std::path::Path,
    m: &crate::model::Model,
) -> Result<Vec<String>, WriteError> {
    write_model_as(path, m, None)
}

/// Format names accepted by `--format`.
pub const FORMAT_NAMES: &str = "json, step, iges, stl, stl-binary, vtp, obj";

/// Write a model in the format named by `format` (see [`FORMAT_NAMES`]) or, when `None`, by
/// the path's extension. Returns what the format could not hold (e.g. trim loops in IGES 128 / STEP geometric sets), so nothing is lost
/// silently.
pub fn write_model_as(
    path: &std::path::Path,
    m: &crate::model::Model,
    format: Option<&str>,
) -> Result<Vec<String>, WriteError> {
    let mut warnings = Vec::new();
    let ext = match format {
        Some(f) => f.to_ascii_lowercase(),
        None => path
            .extension()
            .and_then(|e| e.to_str())
            .unwrap_or("")
            .to_ascii_lowercase(),
    };
    let name0 = path.display().to_string();
    if ext == "stl-binary" {
        let t = m
            .triangulations
            .first()
            .ok_or_else(|| WriteError::NoTriangulation(name0.clone()))?;
        std::fs::write(path, stl::to_binary(t)).map_err(|e| WriteError::Io(name0, e))?;
        return Ok(warnings);
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
    let name = path.display().to_string();
    let stem = path
        .file_name()
        .and_then(|s| s.to_str())
        .unwrap_or("vericad");
    let text = match format_of(path_fmt) {
        Some(Format::Json) => crate::model::json::to_string(m),
        Some(Format::Step) => step::write::to_string(m, stem),
        Some(Format::Iges) => iges::write::to_string(m, stem),
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
    std::fs::write(path, text).map_err(|e| WriteError::Io(name, e))?;
    Ok(warnings)
}
