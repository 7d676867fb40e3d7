//! Boundary representation: faces bounded by loops of oriented edges, edges shared between
//! faces with their 3D curve and, where the source has them, one parameter-space curve
//! (pcurve) per face, vertices, shells and solids (ISO 10303-42 topology: `face`,
//! `face_bound`, `edge_loop`, `vertex_loop`, `oriented_edge`, `edge_curve`, `vertex_point`,
//! `closed_shell`/`open_shell`, `manifold_solid_brep`).
//!
//! Every item keeps its source id (`"#12"` for a STEP instance) so that every report names
//! the entity it is about. Geometry stays with the [`crate::model::Model`]: a face refers
//! to its surface by index into `Model::surfaces`. What a reader could not convert is in
//! [`BrepReport`], counted per entity type with the ids, and faults of the topology (open
//! loops, dangling references, wrong entity types) are [`TopologyIssue`]s naming the face and
//! the entity.

pub mod check;
pub mod counts;
pub mod edge_check;
pub mod natural;
pub mod pcurve;
pub mod place;
pub mod report;
pub mod seam_edges;
pub mod seams;
pub mod sew;

use crate::spline::NurbsCurve;
pub use counts::BrepCounts;
pub use report::{BrepReport, IssueKind, TopologyIssue};

/// A vertex (`vertex_point`): a point in space.
#[derive(Clone, Debug, PartialEq)]
pub struct Vertex {
    /// Source id, e.g. `"#31"`.
    pub source: String,
    pub point: [f64; 3],
}

/// What an edge's 3D curve was in the source (all are held as exact NURBS forms).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, serde::Serialize)]
pub enum CurveKind {
    Line,
    Circle,
    Ellipse,
    BSpline,
    RationalBSpline,
}

/// The 3D curve of an edge, restricted to the edge and running from its start vertex to its
/// end vertex.
#[derive(Clone, Debug, PartialEq)]
pub struct EdgeCurve {
    /// Source id of the geometric curve (the basis curve of a `trimmed_curve` or the
    /// `curve_3d` of a `surface_curve`), e.g. `"#40"`.
    pub source: String,
    pub kind: CurveKind,
    /// The curve from the start vertex to the end vertex (exact NURBS form of the source
    /// curve over the edge's range).
    pub nurbs: NurbsCurve<f64, 3>,
    /// Largest distance between a vertex and the curve end it bounds (the source curve's
    /// endpoints over the edge's range), in the model's length unit.
    pub vertex_gap: f64,
}

/// A curve in the parameter plane of a surface, as the source gives it (`pcurve`): in the
/// parametrization of the source surface entity, which for analytic surfaces differs from
/// the NURBS form in the model (angles versus rational parameters).
#[derive(Clone, Debug, PartialEq)]
pub enum PCurveGeometry {
    /// An unbounded line `origin + t·direction` (2D `line`; `direction` includes the
    /// vector's magnitude).
    Line {
        origin: [f64; 2],
        direction: [f64; 2],
    },
    /// A 2D B-spline (possibly rational) over its own domain.
    Nurbs(NurbsCurve<f64, 2>),
}

/// A pcurve of an edge on one surface.
#[derive(Clone, Debug, PartialEq)]
pub struct PCurve {
    /// Source id of the `pcurve`.
    pub source: String,
    /// Source id of the surface it lies on (the `basis_surface`).
    pub surface_source: String,
    pub geometry: PCurveGeometry,
}

/// An edge (`edge_curve`): two vertices and the curve joining them; shared by the faces
/// whose loops use it.
#[derive(Clone, Debug, PartialEq)]
pub struct Edge {
    pub source: String,
    /// Index into [`Brep::vertices`].
    pub start: usize,
    pub end: usize,
    /// `None` when the source curve could not be converted (then a line in the report).
    pub curve: Option<EdgeCurve>,
    /// Pcurves from the source (`surface_curve`/`seam_curve`), one per surface.
    pub pcurves: Vec<PCurve>,
}

/// An edge as a loop uses it (`oriented_edge`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct OrientedEdge {
    /// Index into [`Brep::edges`].
    pub edge: usize,
    /// Traversed from start to end (`orientation = .T.`).
    pub forward: bool,
}

/// The contents of a loop.
#[derive(Clone, Debug, PartialEq)]
pub enum LoopKind {
    /// An `edge_loop`: oriented edges, each ending where the next begins.
    Edges(Vec<OrientedEdge>),
    /// A `vertex_loop`: a single vertex (a degenerate boundary such as a cone's apex or a
    /// sphere's pole). Index into [`Brep::vertices`].
    Vertex(usize),
}

/// A boundary of a face (`face_bound` / `face_outer_bound` with its loop).
#[derive(Clone, Debug, PartialEq)]
pub struct Loop {
    /// Source id of the bound.
    pub source: String,
    /// Source id of the loop.
    pub loop_source: String,
    /// Declared the outer boundary (`face_outer_bound`).
    pub outer: bool,
    /// The bound's `orientation`: `false` reverses the loop.
    pub orientation: bool,
    pub kind: LoopKind,
}

/// A face (`advanced_face` / `face_surface`).
#[derive(Clone, Debug, PartialEq)]
pub struct Face {
    pub source: String,
    /// Index into `Model::surfaces`; `None` when the surface could not be converted.
    pub surface: Option<usize>,
    /// Source id of the face geometry.
    pub surface_source: String,
    /// `same_sense`: the face normal agrees with the surface normal `S_u × S_v`.
    pub same_sense: bool,
    pub loops: Vec<Loop>,
}

/// A shell (`closed_shell` / `open_shell`): faces, each with its orientation in the shell.
#[derive(Clone, Debug, PartialEq)]
pub struct Shell {
    pub source: String,
    /// Declared closed (`closed_shell`).
    pub closed: bool,
    /// `(index into Brep::faces, orientation)`; `false` for an `oriented_face` reversing it.
    pub faces: Vec<(usize, bool)>,
}

/// A solid (`manifold_solid_brep` or `brep_with_voids`).
#[derive(Clone, Debug, PartialEq)]
pub struct Solid {
    pub source: String,
    /// Index into [`Brep::shells`].
    pub outer: usize,
    pub voids: Vec<usize>,
}

/// A boundary representation read from a file.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Brep {
    pub vertices: Vec<Vertex>,
    pub edges: Vec<Edge>,
    pub faces: Vec<Face>,
    pub shells: Vec<Shell>,
    pub solids: Vec<Solid>,
    /// The length uncertainty the reader worked to, in the model's unit (for STEP the
    /// file's `uncertainty_measure_with_unit`, at least 1e-9 times the model's size); 0 when
    /// unknown. Writers declare it, so that other systems read the model to the same tolerance.
    pub tolerance: f64,
    /// What was read, converted, unsupported or invalid, and the topology faults.
    pub report: BrepReport,
    /// The assembly tree, depth-first, when the source has one (STEP product structure):
    /// every solid and shell above is the shape of one occurrence, placed.
    pub occurrences: Vec<Occurrence>,
}

impl Brep {
    /// Diagonal of the box of the vertices (1 when there are none or they coincide): the
    /// model size that relative tolerances scale with.
    pub fn extent(&self) -> f64 {
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for v in &self.vertices {
            for k in 0..3 {
                lo[k] = lo[k].min(v.point[k]);
                hi[k] = hi[k].max(v.point[k]);
            }
        }
        let d = (0..3).map(|k| (hi[k] - lo[k]).powi(2)).sum::<f64>().sqrt();
        if d.is_finite() && d > 0.0 { d } else { 1.0 }
    }
}

/// An occurrence of a product in an assembly (STEP `next_assembly_usage_occurrence`, or a
/// root product), with the motion placing it and the solids and shells of its own shape.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Occurrence {
    /// Depth in the tree (0: a root product).
    pub depth: usize,
    /// Source id of the usage occurrence (`"#376"`), or of the product definition for a root.
    pub source: String,
    /// The occurrence ids from the root down (`"#54/#403"`; a root's own id for a root).
    pub path: String,
    /// The product's name.
    pub product: String,
    /// Source id of the product definition.
    pub definition: String,
    /// From the product's coordinates to the model's (composed along the tree).
    pub motion: place::Motion,
    /// Indices into [`Brep::solids`] and [`Brep::shells`] of the product's own shape (its
    /// mapped items included); sub-assemblies' shapes belong to their own occurrences.
    pub solids: Vec<usize>,
    pub shells: Vec<usize>,
}

impl Edge {
    /// The vertex where the edge begins when traversed `forward` (else its end).
    pub fn first_vertex(&self, forward: bool) -> usize {
        if forward { self.start } else { self.end }
    }
    /// The vertex where the edge ends when traversed `forward`.
    pub fn last_vertex(&self, forward: bool) -> usize {
        if forward { self.end } else { self.start }
    }
}
