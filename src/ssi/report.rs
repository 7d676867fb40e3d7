//! Result types of the intersection (the JSON schema of `vericad ssi`, see docs/ssi.md).

use super::refine::RefineStatus;
use serde::Serialize;

/// Where an open branch ends.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum EndKind {
    /// On the border of surface A's or B's parameter domain (or the mesh's boundary).
    Boundary,
    /// At a singular point where three or more curves meet (PointUse count > 2).
    BranchPoint,
    /// Where the surfaces become tangent (refinement detected parallel normals).
    Tangential,
    /// Where the curve leaves a trimmed face (or meets an edge it shares with the other face).
    TrimBoundary,
    /// Where the curve meets a border the two faces have in common and was cut there (its
    /// points along the border are that border's, [`super::common_borders`]).
    CommonBorder,
    /// None of the above: the mesh curve stops at a point with one use that is not on a
    /// border (reported, never hidden).
    Unexplained,
}

impl EndKind {
    /// The name used in the JSON result.
    pub fn as_str(&self) -> &'static str {
        match self {
            EndKind::Boundary => "boundary",
            EndKind::BranchPoint => "branch_point",
            EndKind::Tangential => "tangential",
            EndKind::TrimBoundary => "trim_boundary",
            EndKind::CommonBorder => "common_border",
            EndKind::Unexplained => "unexplained",
        }
    }
}

/// One intersection curve.
#[derive(Clone, Debug, Default, Serialize)]
pub struct BranchOut {
    pub closed: bool,
    pub points: Vec<[f64; 3]>,
    /// Parameters on each surface (empty in mesh mode).
    pub uv_a: Vec<[f64; 2]>,
    pub uv_b: Vec<[f64; 2]>,
    /// Proven upper bounds on the distance of every point to surface A / B at its own
    /// parameters (mesh mode: to the triangulation). These bound the distance to each
    /// *surface*, not to the intersection curve: near tangency a point within `d` of both
    /// surfaces can lie much farther than `d` from the curve (see `dist_curve_max`).
    pub dist_a_max: f64,
    pub dist_b_max: f64,
    /// Proven upper bound on the distance of every point to the intersection *curve* (a true
    /// common point of both faces lies within it: Krawczyk's test, [`super::krawczyk`]), the
    /// largest over the points; `None` when some point is uncertified. Mesh mode: the bound
    /// on the distance to the exact crossing of the triangulations.
    pub dist_curve_max: Option<f64>,
    /// Points without a proven distance to the curve (tangency, singular points, ...).
    pub curve_uncertified_points: usize,
    /// Per point, the proven distance to the intersection curve, or `None` (uncertified).
    pub curve_radius: Vec<Option<f64>>,
    /// The uncertified points: index into `points` and the reason.
    pub curve_uncertified: Vec<CurveUncertified>,
    /// Points whose `curve_radius` comes from another argument than Krawczyk's test (index
    /// and kind: `sign_change` near a proven branch point, [`super::sign_change`]); every
    /// other point with a radius has Krawczyk's.
    pub curve_cert: Vec<CurveCertOut>,
    /// Ends of an open branch (empty for closed ones).
    pub ends: Vec<EndKind>,
    /// Points whose refinement met tangential surfaces / did not converge.
    pub tangential_points: usize,
    pub unconverged_points: usize,
    /// Points inserted where the polyline deviated from the true curve by more than tol.
    pub inserted_points: usize,
    /// Chord midpoints whose refinement broke down or jumped away (chord kept as is).
    pub refused_insertions: usize,
    /// Largest measured deviation of a segment midpoint from the refined true curve point
    /// after insertion (with cubic pieces: of the curve points found from each piece at a
    /// quarter, half and three quarters, from the piece); evidence; 0 in mesh mode.
    pub max_chord_deviation: f64,
    /// Cubic fits: control points and knots in 3D and in each domain (empty if too short).
    pub fit: Option<FitOut>,
    /// With cubic pieces ([`super::Pieces::Cubic`]): per point, the tangent jet of the curve
    /// (unit tangent and parameter rates, oriented along the branch), `None` where the
    /// surfaces meet at too small an angle (the pieces at that point are chords); empty with
    /// chords. Each piece is rebuilt from its ends' points and jets ([`super::hermite`]).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub tangents: Vec<Option<super::hermite::Jet>>,
}

/// A point of a branch not certified against the intersection curve, and why.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct CurveUncertified {
    pub index: usize,
    pub reason: super::krawczyk::Uncertified,
}

/// The argument behind a point's curve radius.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum CurveCertKind {
    /// Krawczyk's test on the plane across the curve ([`super::krawczyk`]): a unique zero.
    Krawczyk,
    /// A proven sign change of the signed distance along a segment, next to a proven branch
    /// point ([`super::sign_change`]): a zero exists, not claimed unique.
    SignChange,
}

/// A point whose curve radius is not from Krawczyk's test.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct CurveCertOut {
    pub index: usize,
    pub kind: CurveCertKind,
}

/// A point's curve result: the radius and its argument, or why there is none.
pub type CurveResult = Result<(f64, CurveCertKind), super::krawczyk::Uncertified>;

impl BranchOut {
    /// The points packed as `(x, y, z, u_A, v_A, s_B, t_B)` ([`super::hermite::P7`]).
    pub fn packed(&self) -> Vec<super::hermite::P7> {
        super::hermite::pack(&self.points, &self.uv_a, &self.uv_b)
    }
    /// The pieces between consecutive points: chords, or with tangents the cubic pieces
    /// ([`super::hermite::branch_pieces`]).
    pub fn pieces(&self) -> Vec<super::hermite::Piece> {
        super::hermite::branch_pieces(&self.packed(), &self.tangents, self.closed)
    }
    /// The branch as a polyline for drawing: the points, with `per_piece − 1` samples of each
    /// cubic piece between them (equally spaced in its parameter; none for chords), the
    /// first point repeated at the end of a closed branch.
    pub fn drawn(&self, per_piece: usize) -> Vec<[f64; 3]> {
        let n = self.points.len();
        let mut out = Vec::with_capacity(n * per_piece.max(1) + 1);
        if n == 0 {
            return out;
        }
        out.push(self.points[0]);
        let pieces = if self.tangents.is_empty() {
            Vec::new()
        } else {
            self.pieces()
        };
        let spans = if self.closed { n } else { n - 1 };
        for k in 0..spans {
            if let Some(h) = pieces.get(k) {
                out.extend(h.interior(per_piece));
            }
            out.push(self.points[(k + 1) % n]);
        }
        out
    }
    /// Set the curve certificate from per-point Krawczyk results (radius, or why there is
    /// none).
    pub fn set_curve_radii(&mut self, radii: Vec<Result<f64, super::krawczyk::Uncertified>>) {
        self.set_curve_results(
            radii
                .into_iter()
                .map(|r| r.map(|x| (x, CurveCertKind::Krawczyk)))
                .collect(),
        );
    }
    /// Set the curve certificate from per-point results with their kinds.
    pub fn set_curve_results(&mut self, radii: Vec<CurveResult>) {
        self.curve_uncertified = radii
            .iter()
            .enumerate()
            .filter_map(|(index, r)| r.err().map(|reason| CurveUncertified { index, reason }))
            .collect();
        self.curve_cert = radii
            .iter()
            .enumerate()
            .filter_map(|(index, r)| match r {
                Ok((_, kind)) if *kind != CurveCertKind::Krawczyk => {
                    Some(CurveCertOut { index, kind: *kind })
                }
                _ => None,
            })
            .collect();
        self.curve_radius = radii.into_iter().map(|r| r.ok().map(|x| x.0)).collect();
        self.curve_uncertified_points = self.curve_uncertified.len();
        self.dist_curve_max = (self.curve_uncertified_points == 0).then(|| {
            self.curve_radius
                .iter()
                .flatten()
                .fold(0.0f64, |m, r| m.max(*r))
        });
    }
    /// The per-point curve results (inverse of [`BranchOut::set_curve_results`]).
    pub fn curve_results(&self) -> Vec<CurveResult> {
        let mut out: Vec<CurveResult> = self
            .curve_radius
            .iter()
            .map(|r| {
                r.map(|x| (x, CurveCertKind::Krawczyk))
                    .ok_or(super::krawczyk::Uncertified::NotFinite)
            })
            .collect();
        for c in &self.curve_cert {
            if let Some(Ok(o)) = out.get_mut(c.index) {
                o.1 = c.kind;
            }
        }
        for c in &self.curve_uncertified {
            if let Some(o) = out.get_mut(c.index) {
                *o = Err(c.reason);
            }
        }
        out
    }
}

#[derive(Clone, Debug, Serialize)]
pub struct FitOut {
    pub degree: usize,
    pub knots: Vec<f64>,
    pub control_points: Vec<[f64; 3]>,
    pub control_points_uv_a: Vec<[f64; 2]>,
    pub control_points_uv_b: Vec<[f64; 2]>,
    /// Measured largest distance of the 3D fit from the points it interpolates.
    pub max_deviation_at_points: f64,
}

/// A real contact of the triangulations that is not a transversal crossing.
#[derive(Clone, Debug, Serialize)]
pub struct ContactOut {
    pub kind: super::tri_tri::ContactKind,
    pub triangle_a: u32,
    pub triangle_b: u32,
}

/// A touching point of the two surfaces (a branch of zero length, or a tangential contact
/// refined onto both surfaces).
#[derive(Clone, Debug, Serialize)]
pub struct TouchOut {
    pub point: [f64; 3],
    pub uv_a: Option<[f64; 2]>,
    pub uv_b: Option<[f64; 2]>,
    pub status: Option<RefineStatus>,
    pub dist_a: Option<f64>,
    pub dist_b: Option<f64>,
    /// Number of branch ends at this point: 0 for an isolated touching point, more than two
    /// at a branch point of the intersection.
    pub branch_ends: usize,
    /// The proof of the point's kind ([`super::singular`]), or why there is none (`None` in
    /// mesh mode).
    pub singular: Option<SingularOut>,
}

/// Proven kind of a singular point.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum SingularKind {
    /// A unique non-degenerate critical point of the normal distance in the box, an
    /// extremum, at which the surfaces are within `distance` (≤ tol).
    TouchingPoint,
    /// The same, a saddle: two intersection branches cross there when the distance is 0.
    BranchPoint,
    /// Not proven; see `reason`.
    Uncertified,
}

/// Why a singular point is not proven.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum SingularReason {
    /// A parameter is not finite.
    NotFinite,
    /// An interval enclosure failed (a weight enclosure holds 0, overflow, too many spans).
    Enclosure,
    /// The `f64` Jacobian of the tangency system is singular: a degenerate contact (higher
    /// order, or along a curve), or a parametric degeneracy (a pole).
    Singular,
    /// No box passed Krawczyk's test (degenerate or nearly degenerate contact).
    NoContraction,
    /// The root may lie outside a face's closed parameter domain (or Newton left it).
    OutsideDomain,
    /// The sign of the Hessian determinant was not decided.
    TypeUndecided,
    /// A unique critical point is proven, but the distance between the surfaces there is not
    /// proven within tol (a near miss, not a contact).
    DistanceAboveTol,
}

impl SingularReason {
    /// The name used in the JSON output.
    pub fn as_str(&self) -> &'static str {
        match self {
            SingularReason::NotFinite => "not_finite",
            SingularReason::Enclosure => "enclosure",
            SingularReason::Singular => "singular",
            SingularReason::NoContraction => "no_contraction",
            SingularReason::OutsideDomain => "outside_domain",
            SingularReason::TypeUndecided => "type_undecided",
            SingularReason::DistanceAboveTol => "distance_above_tol",
        }
    }
}

/// The certificate of a singular point (see [`super::singular`] for the theorem).
#[derive(Clone, Debug, Serialize)]
pub struct SingularOut {
    pub kind: SingularKind,
    /// The isolating box `[u0, u1, v0, v1]` on A and `[s0, s1, t0, t1]` on B, in which the
    /// tangency system has a unique root (per piece).
    pub box_a: Option<[f64; 4]>,
    pub box_b: Option<[f64; 4]>,
    /// The enclosure of that root (inside the isolating box).
    pub root_a: Option<[f64; 4]>,
    pub root_b: Option<[f64; 4]>,
    /// `S_A` at the centre of `root_a` (f64): where the proven point is, which may differ
    /// slightly from the search's `point`.
    pub root_point: Option<[f64; 3]>,
    /// Lower and upper bound of `|S_A − S_B|` at the root.
    pub distance: Option<[f64; 2]>,
    /// Smooth pieces the box meets (1: one smooth function per surface; more: cut at knot
    /// lines where the parametrisation is only C0, the claim holds per piece).
    pub pieces: usize,
    /// The surface (`a` or `b`) whose parameters the normal distance is a function of.
    pub critical_on: Option<char>,
    pub reason: Option<SingularReason>,
}

/// Counts and diagnostics of one pair.
#[derive(Clone, Debug, Default, Serialize)]
pub struct PairStats {
    pub triangles_a: usize,
    pub triangles_b: usize,
    pub unresolved_cells_a: usize,
    pub unresolved_cells_b: usize,
    pub candidate_pairs: usize,
    pub segments: usize,
    pub points: usize,
    pub degenerate_triangle_pairs: usize,
    pub inconsistent_triangle_pairs: usize,
    pub duplicate_segments: usize,
    /// Triangle pairs in real (unperturbed) non-transversal contact.
    pub contacts: usize,
    pub tangency_refinement_rounds: usize,
    /// Mesh mode: crossing points not listed because the one before lies within their two
    /// bounds (an edge of one mesh meeting an edge of the other gives two perturbed crossing
    /// points at one location); the branches' points plus these are the segments' ends.
    pub merged_points: usize,
    /// The faces were proven to have no common point before anything was traced
    /// ([`super::coverage::disjoint`]): not triangulated, the coverage is all free pairs.
    pub proven_disjoint: bool,
    pub seconds: f64,
}

/// Result for one pair of faces.
#[derive(Clone, Debug, Serialize)]
pub struct PairOut {
    pub a: usize,
    pub b: usize,
    pub branches: Vec<BranchOut>,
    pub touch_points: Vec<TouchOut>,
    /// Up to 100 contacts listed; `stats.contacts` counts all.
    pub contacts: Vec<ContactOut>,
    pub stats: PairStats,
    /// The coverage certificate (see [`super::coverage`]); absent in mesh mode or when off.
    pub coverage: Option<super::coverage::CoverageOut>,
    /// `false` when the time limit stopped this pair before it finished.
    pub complete: bool,
    /// The faces are proven to coincide (identical, or coplanar): their intersection is a
    /// region, not curves; no curves or certificates are computed for the pair.
    pub coincident: Option<super::coincide::CoincidenceOut>,
    /// What restricting the pair to its faces (trim loops, B-rep faces) removed, and the
    /// intersection along the edges the faces share; absent when neither face is trimmed.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub faces: Option<super::brep_faces::FaceClipOut>,
    /// The faces were measured to touch along a curve ([`super::tangent_contact`], evidence):
    /// the touch points and uncertified branches along it are listed there.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tangent_contact: Option<super::tangent_contact::TangentContactOut>,
    /// Borders the two faces have in common ([`super::common_borders`]): listed as such, not
    /// as branches.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub common_borders: Vec<super::common_borders::CommonBorderOut>,
}

/// What the whole run proves and what it does not.
#[derive(Clone, Debug, Serialize)]
pub struct Summary {
    pub tol: f64,
    pub faces_a: usize,
    pub faces_b: usize,
    pub pairs_considered: usize,
    pub pairs_culled_by_bounds: usize,
    pub pairs_intersected: usize,
    pub pairs_with_branches: usize,
    pub branches: usize,
    pub closed_branches: usize,
    pub points: usize,
    /// Largest proven point-to-surface distance over all branches (each point to each
    /// surface at its own parameters).
    pub dist_max: f64,
    /// Largest proven point-to-curve distance over all branches (`None` when some point is
    /// uncertified against the curve).
    pub dist_curve_max: Option<f64>,
    /// Points without a proven distance to the intersection curve.
    pub points_curve_uncertified: usize,
    /// Whether every point is proven within `tol` of the intersection curve (false when any
    /// point is uncertified).
    pub all_points_within_tol: bool,
    pub pairs_not_run: usize,
    /// Whether the coverage certificate proves, in every pair, that every branch of the true
    /// intersection comes within the match distance of the output.
    pub no_missed_branches: bool,
    /// Box pairs (over all face pairs) neither proven free nor loop-free.
    pub uncertified_box_pairs: usize,
    /// Face pairs proven to coincide (see `PairOut::coincident`).
    pub coincident_pairs: usize,
    /// Face pairs measured to touch along a curve (see `PairOut::tangent_contact`).
    pub tangent_contact_pairs: usize,
    /// Borders two faces have in common (see `PairOut::common_borders`), and those of them
    /// not proven on the intersection (within a gap): any such one makes the run uncertified.
    pub common_borders: usize,
    pub common_borders_not_proven: usize,
    /// Tangential points whose kind is proven (touching point or branch point) and those
    /// left uncertified ([`super::singular`]); any uncertified one makes the run uncertified.
    pub singular_points_proven: usize,
    pub singular_points_uncertified: usize,
    pub partial: bool,
    /// Everything above is proven: every point within tol of the intersection curve
    /// (`all_points_within_tol`), no branch missed (coverage), every singular point's kind
    /// proven, the run complete. The command exits with 3 when this is false.
    pub certified: bool,
    pub seconds: f64,
    /// Plain words on what is proven (points) and what is not (completeness).
    pub certificate: Vec<String>,
}

#[derive(Clone, Debug, Serialize)]
pub struct SsiResult {
    pub pairs: Vec<PairOut>,
    pub summary: Summary,
}
