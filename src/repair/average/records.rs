//! The records of step 3 (boundary averaging, paper §4 and matrix (2) of §6): how each shared
//! row was made, what averaging did to each patch, which connected pairs were left and why,
//! and the outcome of the whole step.

use crate::repair::connectivity::Connection;

/// How the shared row of a connected pair was made.
#[derive(Clone, Debug, serde::Serialize)]
pub struct EdgeRecord {
    pub connection: Connection,
    /// `control_points` (matrix (2): the mean of two compatible rows), `fitted_curve` (§4
    /// (i)–(v): least squares on the closest-point midpoints), or, when no fit was solvable,
    /// `control_points_after_refinement` (the mean of the two rows brought to the class's
    /// degree and knots, at equal parameters).
    pub method: &'static str,
    /// Gap measured before averaging (step 2, evidence).
    pub gap_before: f64,
    /// Fitted curves: largest residual at the midpoints (evidence, not a bound between them).
    pub fit_error_evidence: Option<f64>,
    /// Fitted curves: number of midpoints (corners included) and knots added by splitting.
    pub fit_data: Option<usize>,
    pub knots_added: usize,
    /// Degree and control points of the shared row.
    pub degree: usize,
    pub control_points: usize,
}

/// What averaging did to one patch (indices after T-junction splitting).
#[derive(Clone, Debug, serde::Serialize)]
pub struct PatchRecord {
    pub patch: usize,
    pub degrees_before: (usize, usize),
    pub degrees_after: (usize, usize),
    pub control_points_before: (usize, usize),
    pub control_points_after: (usize, usize),
    /// Edges whose row was replaced (0 south, 1 east, 2 north, 3 west).
    pub rows_replaced: Vec<usize>,
    /// Largest move of a control point (boundary and interior) against the original refined
    /// to the same knots.
    pub max_control_point_move: f64,
    /// Proven bound on `|S_new(u,v) − S_old(u,v)|` (partition of unity; hypotheses: weights
    /// unchanged, refinement exact): present only when the weights are unchanged.
    pub deviation_bound_proven: Option<f64>,
    /// Largest distance of 9 × 9 samples of the repaired patch to their closest points on the
    /// original (evidence).
    pub deviation_measured_evidence: f64,
}

/// A connected pair left as it was, and why.
#[derive(Clone, Debug, serde::Serialize)]
pub struct LeftEdge {
    pub connection: Connection,
    pub reason: String,
}

/// What averaging did.
#[derive(Clone, Debug, Default, serde::Serialize)]
pub struct AveragingOutcome {
    pub corner_clusters: usize,
    pub corners_moved: usize,
    pub max_corner_move: f64,
    /// Pairs averaged control point by control point.
    pub edges_averaged: usize,
    /// Incompatible pairs repaired (a fitted curve, or the mean of the refined rows).
    pub edges_fitted: usize,
    /// Connected pairs whose rows were incompatible before averaging (fitted or left).
    pub incompatible_before: usize,
    /// Connected pairs left as they were (see `left` for the reasons).
    pub edges_incompatible: Vec<Connection>,
    pub left: Vec<LeftEdge>,
    /// Knot classes raised and refined so that fitted curves fit in.
    pub classes_refined: usize,
    /// Rational patches brought to corner weights 1 first by a linear rational (Möbius)
    /// reparametrization in u and v ([`crate::spline::mobius`]): the same surface (up to
    /// rounding), so a shared corner's one homogeneous point changes their shape no more than
    /// the move of the corner. Their deviation bound is not claimed proven (the
    /// reparametrization is computed in `f64`); the measured deviation is against the input.
    pub corner_weights_unified: usize,
    pub max_control_point_move: f64,
    pub max_fit_error_evidence: f64,
    pub max_deviation_measured_evidence: f64,
    /// Largest proven bound over the patches that have one.
    pub max_deviation_bound_proven: Option<f64>,
    pub edges: Vec<EdgeRecord>,
    pub patches: Vec<PatchRecord>,
}
