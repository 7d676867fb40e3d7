//! What the coverage certificate reports: the count of leaf pairs by class (free, near the
//! output, in a tube, transversal, uncertified), and each uncertified pair of parameter boxes
//! with the reason.

use serde::Serialize;

/// Why a pair of parameter boxes is not certified.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Reason {
    /// The normal cones could not be separated (tangency, a touching point, a small loop,
    /// a singular point, or a degenerate piece such as a pole) down to the depth limit.
    NormalsNotSeparated,
    /// A border of one piece may cross the other piece at a place not within the match
    /// distance of the output: a branch may be missing there.
    CrossingAwayFromOutput,
    /// No enclosure (a weight not proven positive, or overflow).
    NoEnclosure,
    /// The box or time budget ran out before the pair was decided.
    Budget,
    /// A trim loop runs through the pair (faces mode), its normal cones are not separated and
    /// it is not near the output within the split budget: a branch of the faces may begin
    /// or end at the loop inside it.
    TrimInPair,
}

/// A pair of parameter boxes that could not be certified.
#[derive(Clone, Debug, Serialize)]
pub struct RegionOut {
    pub uv_a: [f64; 4],
    pub uv_b: [f64; 4],
    pub reason: Reason,
    /// Centre of a model-space box holding the undecided part (for crossings: the possible
    /// crossing point).
    pub point: Option<[f64; 3]>,
}

/// Counts of leaf pairs by class, and the uncertified ones (first 100).
#[derive(Clone, Debug, Default, Serialize)]
pub struct CoverageOut {
    /// Bézier pieces (knot-span patches) of each surface.
    pub boxes_a: usize,
    pub boxes_b: usize,
    /// Leaf pairs of the refinement, by class (`pairs` = the sum of the five classes).
    pub pairs: usize,
    /// Pairs examined, split ones included.
    pub pairs_examined: usize,
    pub free: usize,
    pub near_output: usize,
    pub transversal: usize,
    /// Pairs inside the region of a proven branch point whose point is within the match
    /// distance of the output ([`crate::ssi::singular::BranchRegion`]): decided without a
    /// border search (every component of the intersection in the region runs through the
    /// branch point or to the region's border, where pairs outside it decide).
    pub branch_point_regions: usize,
    pub uncertified: usize,
    /// Pairs outside the faces (trim or B-rep loops), not examined further.
    pub outside_faces: usize,
    /// Boxes examined in border-crossing searches, and those proven near the output.
    pub crossing_boxes: usize,
    pub crossing_boxes_near_output: usize,
    /// Leaf pairs, and crossing boxes, proven inside a tube of
    /// [`CoverageParams::tubes`](super::CoverageParams::tubes) (within `r_e` of the polyline
    /// of an edge or vertex two faces of a B-rep share).
    pub near_shared_edges: usize,
    pub crossing_boxes_near_shared_edges: usize,
    /// Faces mode: crossing boxes left out as outside the faces, searches of a loop
    /// polygon's edge in a piece ([`crate::ssi::coverage`]'s trim crossings), and the
    /// transversal pairs a loop runs through (counted in `transversal` too).
    pub crossing_boxes_outside_faces: usize,
    pub trim_edge_searches: usize,
    pub transversal_with_trim_loops: usize,
    /// The match distance `d` of the claim.
    pub match_distance: f64,
    /// Whether every leaf pair is free, near the output or transversal: then every branch of
    /// the true intersection comes within `match_distance` of the output (the claim above).
    pub no_missed_branches: bool,
    pub uncertified_regions: Vec<RegionOut>,
    /// Output points whose parameters lie in a leaf pair proven free with a gap between the
    /// boxes larger than the point's proven distances to the two surfaces (a contradiction:
    /// must be 0; a self-check of the certificate). `None` when not checked (more than
    /// 2·10⁷ point–pair tests).
    pub free_pairs_with_branch_points: Option<usize>,
    pub seconds: f64,
    /// The adaptive refinement of undecided regions ([`crate::ssi::regions`]), when it ran:
    /// this certificate is then the one computed on the refined output.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub refinement: Option<crate::ssi::regions::RegionRefinement>,
}
