//! vericad — verification-first computer-aided geometric design for surface grid generation.
//!
//! Layers (nothing below imports from above), see `ARCHITECTURE.md`:
//! `cli` → pipelines → `io`/`model` → `spline` → `predicates` → `scalar`, `geom`.

// Index loops mirror the published algorithms (The NURBS Book, de Casteljau); keep them.
#![allow(clippy::needless_range_loop)]

pub mod approx;
pub mod batch;
pub mod brep;
pub mod budget;
#[cfg(feature = "cli")]
pub mod cli;
pub mod curve_on_surface;
pub mod demo;
#[doc(hidden)]
pub mod fuzz_entry;
pub mod geom;
pub mod io;
pub mod model;
pub mod predicates;
pub mod progress;
pub mod repair;
pub mod reparam;
pub mod scalar;
pub mod spline;
pub mod ssi;
pub mod tessellate;

pub use scalar::{RealScalar, Scalar, Sign};
