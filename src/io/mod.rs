//! Readers and writers of exchange and viewing formats, one file (or folder) per format.
//! [`read_model`] picks the reader from the file's extension.

pub mod iges;
pub mod step;
pub mod stl;
pub mod svg;

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
    #[error("{0}: unknown file type (expected .json, .step/.stp, .igs/.iges, .stl)")]
    UnknownFormat(String),
}

/// The formats [`read_model`] knows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    Json,
    Step,
    Iges,
    Stl,
}

/// Format from a file name's extension (case-insensitive).
pub fn format_of(path: &std::path::Path) -> Option<Format> {
    match path.extension()?.to_str()?.to_ascii_lowercase().as_str() {
        "json" => Some(Format::Json),
        "step" | "stp" | "p21" => Some(Format::Step),
        "igs" | "iges" => Some(Format::Iges),
        "stl" => Some(Format::Stl),
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
        None => Err(ReadError::UnknownFormat(path.display().to_string())),
    }
}
