//! The model: named NURBS curves (2D domain curves and 3D curves), surfaces and patch sets,
//! in `f64` as read from files. Exact backends get their data by exact lifting
//! ([`crate::geom::lift_point`]).
//!
//! [`json`] reads and writes the native JSON format (schema in `docs/model-format.md`);
//! every fault in a file is a [`ModelError`] naming the file, the JSON path and the reason.

/// The embedded default model: Yang et al. (2008) Table 2 (a biquadratic Bézier surface and
/// a quadratic domain curve), native JSON.
pub const YANG_TABLE2: &str = include_str!("../models/yang-table2.json");

pub mod accounting;
pub mod check;
pub mod eval;
pub mod info;
pub mod json;

use crate::spline::{NurbsCurve, NurbsSurface};
pub use accounting::{Accounting, Outcome};
pub use check::{MAX_COORDINATE, RangeError, list_ids};

/// A curve in the parameter plane of a surface (`u, v`) or in space.
#[derive(Clone, Debug, PartialEq)]
pub enum CurveGeometry {
    Domain(NurbsCurve<f64, 2>),
    Space(NurbsCurve<f64, 3>),
}

impl CurveGeometry {
    /// The curve in space; a domain curve `(u, v)` is lifted to `(u, v, 0)` (the IGES
    /// convention for curves in a parameter plane). Exact: control points and weights kept.
    pub fn to_space(&self) -> NurbsCurve<f64, 3> {
        match self {
            CurveGeometry::Space(s) => s.clone(),
            CurveGeometry::Domain(d) => NurbsCurve {
                hom: d.hom.map(
                    |k| *k,
                    |h| crate::geom::Hom {
                        wp: [h.wp[0], h.wp[1], 0.0],
                        w: h.w,
                    },
                ),
            },
        }
    }
    /// The curve as a domain curve `(u, v)`: a space curve qualifies when every control point
    /// has `z = 0` (the inverse of [`Self::to_space`]).
    pub fn to_domain(&self) -> Option<NurbsCurve<f64, 2>> {
        match self {
            CurveGeometry::Domain(d) => Some(d.clone()),
            CurveGeometry::Space(s) => {
                s.hom
                    .control
                    .iter()
                    .all(|h| h.wp[2] == 0.0)
                    .then(|| NurbsCurve {
                        hom: s.hom.map(
                            |k| *k,
                            |h| crate::geom::Hom {
                                wp: [h.wp[0], h.wp[1]],
                                w: h.w,
                            },
                        ),
                    })
            }
        }
    }
}

/// A named curve.
#[derive(Clone, Debug, PartialEq)]
pub struct Curve {
    pub name: String,
    pub geometry: CurveGeometry,
}

/// What a surface was in its source file (all are held as exact NURBS forms).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Default, serde::Serialize)]
pub enum SurfaceKind {
    #[default]
    BSpline,
    Plane,
    Cylinder,
    Cone,
    Sphere,
    Torus,
    Revolution,
    Extrusion,
}

impl SurfaceKind {
    /// Whether the source surface was analytic (converted to NURBS on reading).
    pub fn is_analytic(self) -> bool {
        self != SurfaceKind::BSpline
    }
}

/// A trimming loop in a surface's parameter space: curve segments `(u, v)` in order.
#[derive(Clone, Debug, PartialEq)]
pub struct TrimLoop {
    /// The outer boundary (otherwise a hole).
    pub outer: bool,
    pub curves: Vec<NurbsCurve<f64, 2>>,
}

/// A named surface (a face or patch of the model).
#[derive(Clone, Debug, PartialEq)]
pub struct Surface {
    pub name: String,
    pub nurbs: NurbsSurface<f64, 3>,
    /// Where it came from: `"#123"` (STEP instance), `"DE 45"` (IGES directory entry).
    pub source: Option<String>,
    pub kind: SurfaceKind,
    /// Trimming loops (empty: the whole parameter domain is the face).
    pub trim_loops: Vec<TrimLoop>,
    /// The face's normal is opposite to `S_u × S_v` (STEP `same_sense = .F.`).
    pub reversed: bool,
}

impl Surface {
    /// A B-spline surface without source information.
    pub fn new(name: impl Into<String>, nurbs: NurbsSurface<f64, 3>) -> Surface {
        Surface {
            name: name.into(),
            nurbs,
            source: None,
            kind: SurfaceKind::BSpline,
            trim_loops: vec![],
            reversed: false,
        }
    }
}

/// A named set of surfaces (indices into [`Model::surfaces`]) meant to form one shape.
#[derive(Clone, Debug, PartialEq)]
pub struct PatchSet {
    pub name: String,
    pub surfaces: Vec<usize>,
}

/// A triangulation (e.g. from STL): vertices welded, triangles as vertex indices.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Triangulation {
    pub name: String,
    pub vertices: Vec<[f64; 3]>,
    pub triangles: Vec<[u32; 3]>,
}

/// Everything a model file holds.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Model {
    /// Length unit as written in the file (e.g. `"mm"`), if any.
    pub unit: Option<String>,
    pub curves: Vec<Curve>,
    pub surfaces: Vec<Surface>,
    pub patch_sets: Vec<PatchSet>,
    pub triangulations: Vec<Triangulation>,
    /// Entity counts by type in the source file (IGES entity numbers, STEP entity names).
    pub source_entities: std::collections::BTreeMap<String, usize>,
    /// What a reader skipped or approximated, counted and named (never silent).
    pub warnings: Vec<String>,
    /// Faces, loops, edges, vertices, shells and solids, when the source has topology.
    pub brep: Option<crate::brep::Brep>,
    /// What the reader did with each geometric entity of the source file, by kind (read,
    /// converted, used, unsupported, invalid); empty for models not read from STEP or IGES.
    pub accounts: accounting::Accounting,
}

/// Canonical short name of a length unit (`"m"`, `"mm"`, `"cm"`, `"km"`, `"um"`, `"inch"`,
/// `"foot"`); other names are kept, lowercased.
pub fn normalize_unit(name: &str) -> String {
    let n = name.trim().to_lowercase();
    match n.as_str() {
        "m" | "metre" | "meter" | "metres" | "meters" => "m",
        "mm" | "millimetre" | "millimeter" | "millimetres" | "millimeters" => "mm",
        "cm" | "centimetre" | "centimeter" => "cm",
        "km" | "kilometre" | "kilometer" => "km",
        "um" | "micrometre" | "micrometer" | "micron" => "um",
        "in" | "inch" | "inches" => "inch",
        "ft" | "foot" | "feet" => "foot",
        _ => return n,
    }
    .to_string()
}

/// A fault in a model file: where, and why.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{file}: {path}: {reason}")]
pub struct ModelError {
    /// File name, or `<input>` for in-memory text.
    pub file: String,
    /// JSON path of the offending value, e.g. `surfaces[0].knots_u[4]`.
    pub path: String,
    pub reason: String,
}
