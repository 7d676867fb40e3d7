//! Surface–surface intersection (paper: "CAGD techniques for surface grid generation", §4;
//! docs/papers.md §A), one file per step:
//!
//! | step | file |
//! |---|---|
//! | 1 adaptive triangulation | [`triangulate`] |
//! | 2–3 trees and culling | [`crate::geom::tri_tree`] (shared with repair) |
//! | 4 triangle intersection (exact, perturbed, named points) | [`tri_tri`] |
//! | 5 Point / PointUse / Segment topology | [`topology`] |
//! | 6–7 loop detection and tracing | [`trace`] |
//! | 8 refinement (barycentric, Auxiliary Plane Method) | [`refine`], [`branch`] |
//! | 9 spline fitting | [`fit`] |
//! | certificate of every point: distance to each surface | [`certify`] |
//! | certificate of every point: distance to the intersection curve (Krawczyk) | [`krawczyk`], [`enclose`] |
//! | coverage: no branch missed | [`coverage`] |
//! | coincident faces | [`coincide`]; overlapping faces (measured) | [`overlap`] |
//! | faces touching along a curve (measured) | [`tangent_contact`] |
//! | certifying a foreign result: global distance, proven curve points | [`foreign`], [`closest`] (curve points by [`krawczyk`]) |
//! | tangential contacts | [`touch`] |
//! | singular points (touching, branch) proven by Krawczyk's test on the tangency system | [`singular`] |
//! | certificate of the points at and next to a proven branch point: a proven sign change | [`sign_change`] |
//! | two surfaces / many faces / meshes | [`pair`], [`driver`], [`mesh`] |
//! | cancel flag and progress inside a pair | [`control`] |

pub mod branch;
pub mod brep_faces;
pub mod certify;
pub mod closest;
pub mod coincide;
pub mod common_borders;
pub mod control;
pub mod coverage;
pub mod driver;
mod point_certs;
/// The box enclosures live in the kernel ([`crate::spline::enclose`],
/// [`crate::spline::enclose2`]); re-exported here for the certificate, the Krawczyk test and
/// the singular points.
pub use crate::spline::enclose;
pub use crate::spline::enclose2;
pub mod fit;
pub mod foreign;
pub mod foreign_read;
pub mod hermite;
pub mod insert;
pub mod jet_cache;
pub mod job;
pub mod krawczyk;
mod linalg4;
pub mod mesh;
pub mod overlap;
pub mod pair;
mod pair_meshes;
pub mod picture;
pub mod refine;
pub mod regions;
pub mod report;
pub mod shared_tubes;
pub mod sign_change;
pub mod singular;
pub mod tangent_contact;
mod thin;
pub mod topology;
pub mod touch;
pub mod trace;
pub mod tri_tri;
pub mod triangulate;
pub mod trims;

pub use driver::{intersect_models, intersect_pair_canonical};
pub use report::{BranchOut, EndKind, PairOut, SsiResult, Summary};

/// What can go wrong.
#[derive(Debug, thiserror::Error)]
pub enum SsiError {
    #[error("tolerance must be a positive finite number, got {0}")]
    Tolerance(f64),
    #[error("{0} must be a positive finite number, got {1}")]
    Parameter(&'static str, f64),
    #[error("face index {index} out of range: the model has {count} faces")]
    FaceIndex { index: usize, count: usize },
    #[error("the model has no faces or triangulations to intersect")]
    Empty,
    #[error("internal topology check failed: {0}")]
    Topology(#[from] trace::InvariantError),
    /// A triangulation of mesh-mode input (faces `a`, `b`) is not usable.
    #[error(
        "internal topology check failed: triangulation {a} or {b} has a vertex index out of range or a non-finite coordinate"
    )]
    InvalidMesh { a: usize, b: usize },
    #[error("internal topology check failed: mesh intersection stopped")]
    MeshStopped,
    /// Geometry the intersection cannot compute with: not finite (a model built in code
    /// without [`crate::model::Model::validate`]) or outside the coordinate range.
    #[error("{0}")]
    Input(String),
}

/// Parameters of an intersection run.
#[derive(Clone, Debug)]
pub struct SsiParams {
    /// Requested tolerance: refined points agree on both surfaces within it, and chords are
    /// split until their midpoints are within it of the true curve.
    pub tol: f64,
    /// Flatness of the triangulation (default: 0.2% of the control-net diagonal).
    pub flatness: Option<f64>,
    /// Cells per net diagonal at least (bounds the triangle size).
    pub min_cells_per_diagonal: u32,
    pub max_depth: u32,
    /// Normals closer than this angle count as near-tangent (refinement and touch search).
    pub tangent_angle_deg: f64,
    pub tangency_rounds: u32,
    /// `sin` of the normal angle below which the Auxiliary Plane Method is said to break down.
    pub refine_tangent_sin: f64,
    pub max_insert_depth: u32,
    /// Stop starting new work after this many seconds; the result is marked partial.
    pub time_limit: Option<f64>,
    /// Compute the coverage certificate ([`coverage`]): every branch of the true
    /// intersection comes within `coverage_match` of the output, or its region is listed.
    pub coverage: bool,
    /// The match distance of the coverage claim (default: 10 × tol).
    pub coverage_match: Option<f64>,
    /// Quarterings of a piece in the coverage refinement.
    pub coverage_max_depth: u32,
    /// Boxes examined by the coverage certificate per face pair.
    pub coverage_max_boxes: usize,
    /// Intersect faces, not whole surfaces: outputs restricted to the faces' trim loops or
    /// B-rep loops, and in one-file runs on a B-rep the intersection along shared edges listed
    /// as such ([`brep_faces`]). On by default; off intersects the untrimmed surfaces.
    pub respect_trims: bool,
    /// The coverage certificate skips box pairs outside the faces (set per pair by the
    /// driver when faces are trimmed).
    pub coverage_outside: Option<coverage::OutsideFaces>,
    /// Faces mode: the restriction of the output to the faces, made before the coverage
    /// claim (set per pair by the driver when faces are trimmed or share edges).
    pub coverage_restrict: Option<coverage::FaceRestriction>,
    /// In a one-file run on a B-rep, the tubes around the edges and vertices the pair's faces
    /// share (set per pair by the driver): a traced curve lying wholly in them is counted to
    /// the edge and not refined, and the coverage certificate accounts for them
    /// ([`shared_tubes`]).
    pub shared_tubes: Option<std::sync::Arc<shared_tubes::SharedTubes>>,
    /// Compute the certificates: the curve radius of every point ([`krawczyk`]) and, with
    /// [`SsiParams::coverage`], the coverage. Off gives a faster run that is reported as not
    /// certified (every point `not_requested`, no coverage); the distances to each surface
    /// are bounded either way.
    pub certify: bool,
    /// Fit each branch's C1 cubic ([`report::BranchOut::fit`]). On by default for library
    /// callers; `vericad ssi` (and Python's `ssi`) asks for it only with `--fits` or `--iges`
    /// (`fits=`, `iges=`), `certify-ssi` and batch runs never (about 8 % of a run on a circle
    /// of 9,000 points).
    pub fits: bool,
    /// Cancel flag and progress from inside face pairs ([`control`]).
    pub control: control::Control,
    /// How branches run between their points: chords (each midpoint within `tol` of the
    /// curve) or cubic Hermite pieces with the curve's tangents at the ends ([`hermite`]),
    /// each within `tol` of the curve where measured: far fewer points, each certified.
    pub pieces: Pieces,
}

/// The pieces of a branch between consecutive points ([`SsiParams::pieces`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Pieces {
    /// Straight chords, split until every midpoint is within `tol` of the curve.
    #[default]
    Chords,
    /// Cubic Hermite pieces ([`hermite`]), split until each is within `tol` of the curve at
    /// a quarter, half and three quarters of its parameter.
    Cubic,
}

impl std::str::FromStr for Pieces {
    type Err = String;
    fn from_str(s: &str) -> Result<Pieces, String> {
        match s {
            "chords" => Ok(Pieces::Chords),
            "cubic" => Ok(Pieces::Cubic),
            _ => Err(format!("pieces must be `chords` or `cubic`, not `{s}`")),
        }
    }
}

impl Default for SsiParams {
    fn default() -> Self {
        SsiParams {
            tol: 1e-6,
            flatness: None,
            min_cells_per_diagonal: 16,
            max_depth: 12,
            tangent_angle_deg: 10.0,
            tangency_rounds: 2,
            refine_tangent_sin: 1e-6,
            max_insert_depth: 12,
            time_limit: None,
            coverage: true,
            coverage_match: None,
            coverage_max_depth: 24,
            coverage_max_boxes: 200_000,
            respect_trims: true,
            coverage_outside: None,
            coverage_restrict: None,
            shared_tubes: None,
            certify: true,
            fits: true,
            control: control::Control::default(),
            pieces: Pieces::Chords,
        }
    }
}

impl SsiParams {
    pub fn validate(&self) -> Result<(), SsiError> {
        if !(self.tol > 0.0 && self.tol.is_finite()) {
            return Err(SsiError::Tolerance(self.tol));
        }
        if let Some(f) = self.flatness
            && !(f > 0.0 && f.is_finite())
        {
            return Err(SsiError::Parameter("flatness", f));
        }
        if !(self.tangent_angle_deg > 0.0 && self.tangent_angle_deg < 90.0) {
            return Err(SsiError::Parameter(
                "tangent angle (degrees, below 90)",
                self.tangent_angle_deg,
            ));
        }
        if let Some(m) = self.coverage_match
            && !(m > 0.0 && m.is_finite())
        {
            return Err(SsiError::Parameter("coverage match distance", m));
        }
        if let Some(t) = self.time_limit
            && !(t > 0.0 && t.is_finite())
        {
            return Err(SsiError::Parameter("time limit", t));
        }
        Ok(())
    }
}
