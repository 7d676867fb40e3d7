//! The coverage certificate: no branch of the true intersection — closed loop or open arc —
//! is missing from the output, except in listed regions.
//!
//! # The theorem
//!
//! Let `S_A`, `S_B` be NURBS surfaces with positive weights on the parameter rectangles `D_A`,
//! `D_B`, `I = {(z_a, z_b) : S_A(z_a) = S_B(z_b)}` their true intersection in `D_A × D_B`, and
//! `O` the output (reported branch polylines, closed ones closed, touching points, and the
//! polylines of common borders, [`crate::ssi::common_borders`]). The
//! rectangles are cut into Bézier pieces (knot spans) and these, adaptively, into quarters
//! (or halves across the longer direction of a long, narrow piece: `pieces::Cell::kids`);
//! the *leaf pairs* `α × β` of this refinement cover `D_A × D_B`. Every leaf pair is
//! classified as one of:
//!
//! 1. **free** — the boxes of the enclosed control points of the two pieces are disjoint.
//!    (Convex hull property: a piece with positive weights lies in the convex hull of its
//!    Cartesian control points.) Then `I ∩ (α × β) = ∅`.
//! 2. **near the output** — the common part of the two boxes, which holds every intersection
//!    point of the pair, lies within the match distance `d` of one segment of `O`
//!    ([`near`]).
//!
//! 2′. **in a tube** (one-file runs on a B-rep only) — that common part, or one piece's
//!    control-point hull, lies within the reach `r_e` of one segment of a listed polyline
//!    `E_e` (an edge or vertex two faces share, [`crate::ssi::shared_tubes`]): every
//!    intersection point of the pair lies in the tube `T_e`.
//! 3. **transversal** — (in faces mode, for a pair a trim loop runs through, also every
//!    crossing of a loop edge with the other piece: the lemma in `pair_search.rs`) the normal
//!    cones are separated ([`cones`]: no parallel normals, both pieces regular), and every point where a border curve of `α` meets the piece `β`, or a
//!    border curve of `β` meets `α`, is enclosed in boxes proven within `d` of `O` or inside a
//!    tube ([`crossings`]). With separated cones, `I ∩ (α × β)` is a 1-manifold (implicit
//!    function theorem: the Jacobian `[S_Au S_Av −S_Bs −S_Bt]` has rank 3), and a component
//!    that does not meet the border of `α × β` would be a closed curve whose tangent is
//!    parallel to `n_A × n_B`, along which `w·x` is strictly monotone — impossible. So every
//!    component of `I ∩ (α × β)` contains a border crossing, which lies within `d` of `O` or
//!    in a tube.
//! 3′. **in a branch-point region** — both pieces lie inside the region `W = W_x × W_y` of a
//!    proven branch point `z*` whose point is within `d` of `O`
//!    ([`crate::ssi::singular::BranchRegion`]; regions pairwise disjoint, none on trimmed
//!    faces): every component of `I ∩ W` contains `z*` or meets `∂W_x × W_y`.
//! 4. **uncertified** — none of the above within the budget; listed with the reason.
//!
//! **Claim.** Every connected component of `I` (every branch: closed loop, open arc, isolated
//! touching point) contains a point within `d` of `O`, or a point in a tube `T_e`, or meets a
//! listed uncertified pair. Proof: a component contains a point of some leaf pair; that pair
//! is not free; in a pair near the output every point is within `d` of `O`, in a pair in a
//! tube every point is in that tube; in a transversal pair the component's piece contains a
//! border crossing within `d` of `O` or in a tube; in a region pair the component's part in
//! `W` contains `z*` or a point of `∂W_x × W_y`, which lies in a pair in no region (pairs in
//! a region lie strictly inside it), where the other cases apply. Without tubes (every run but one-file runs
//! on a B-rep) the second case is empty. With them the claim says nothing of a component with a
//! point in a tube, also where it runs on outside it: there the faces meet by construction, and what the B-rep's edge curve and the reach
//! `r_e` rest on is evidence (see [`crate::ssi::shared_tubes`]); the tubes' polylines and
//! reaches are the numbers the decisions used, so the claim is a theorem about them.
//!
//! Hypotheses: positive weights (checked on the enclosures: a weight interval that is not
//! strictly positive makes the piece uncertified), control points finite. Nothing depends on
//! the tracer, the triangulation or the placement of the surfaces (seams and poles of closed
//! surfaces included: a loop through a seam is, in the parameter rectangle, an arc whose ends
//! are border crossings). The claim is one-sided: that the reported points lie on the true
//! curve is the point certificate's business.
//!
//! Every piece is extracted with enclosed control points (the interval de Boor–Ramshaw
//! recurrence on the exact f64 data, or exact rational knot insertion where a knot difference
//! cannot be certified positive in intervals); every halving and every sign is computed in
//! outward-rounded interval arithmetic. The uv
//! labels of pieces (for reports) are rounded midpoints; the pieces themselves are exact
//! halves.

mod along;
mod apart;
pub mod cones;
mod crossing_newton;
pub mod crossings;
pub mod disjoint;
pub mod near;
pub mod numerator;
pub mod patch;

mod outcome;
mod output;
mod pair_search;
mod pieces;
mod trim_crossings;

pub use along::piece_bound;
pub(crate) use apart::{Suspects, tangency_suspects};
pub use outcome::{CoverageOut, Reason, RegionOut};
pub(crate) use output::output_set;
pub use output::{BoxTest, EdgesTest, FaceRestriction, keep_mask};
pub(crate) use pieces::{Cell, PairPieces, roots};

use super::report::{BranchOut, TouchOut};
use super::singular::{BranchRegion, branch_region, disjoint_regions};
use crate::spline::NurbsSurface;
use cones::cones_separated;
use near::Near;
use pair_search::SearchCtx;
use patch::{Box3, V, disjoint, meet, separated_along};
use std::rc::Rc;
use std::time::Instant;

/// Splits (of both pieces together) of a pair a trim loop runs through, past which a pair
/// neither decided transversal nor near the output is listed (`trim_in_pair`) rather than
/// split further: a budget only.
const TRIM_DEPTH: u32 = 12;

/// Budgets and the match distance.
#[derive(Clone, Debug)]
pub struct CoverageParams {
    /// `d`: every branch must come within this distance of the output.
    pub match_distance: f64,
    /// Splits (quarterings or halvings) of a piece in the pair refinement.
    pub max_pair_depth: u32,
    /// Halvings in one border-crossing search.
    pub max_crossing_depth: u32,
    /// Boxes examined in all, per face pair (pairs and crossing boxes).
    pub max_boxes: usize,
    pub deadline: Option<Instant>,
    /// Set from another thread to stop: past it (or the deadline) the pairs not yet examined
    /// are listed as budget-limited without being examined.
    pub cancel: Option<std::sync::Arc<std::sync::atomic::AtomicBool>>,
    /// Pairs of parameter boxes lying outside the faces (trim or B-rep loops) are not
    /// examined: no point of the faces' intersection lies in them (counted `outside_faces`).
    pub outside: Option<OutsideFaces>,
    /// Tubes `T_e`: a polyline `E_e` (segments; a point as a zero-length one) with a reach
    /// `r_e`, the points within `r_e` of `E_e`. Pairs and crossing boxes proven inside one are
    /// decided by it, and the claim excludes them (one-file runs on a B-rep: the edges and
    /// vertices the faces share, [`crate::ssi::shared_tubes`]). Empty for other runs.
    pub tubes: Tubes,
    /// Polylines that are part of the output `O` besides the branches and touch points: the
    /// borders the two faces have in common ([`crate::ssi::common_borders`]).
    pub borders: std::sync::Arc<Vec<Vec<[f64; 3]>>>,
    /// Faces mode: the output is restricted to the faces before the claim is made about it
    /// (the borders in `borders` are given restricted already).
    pub restrict: Option<FaceRestriction>,
}

/// Polylines with their reach (see [`CoverageParams::tubes`]).
pub type Tubes = std::sync::Arc<Vec<TubeLine>>;

/// One tube: the segments of its polyline `E_e` and its reach `r_e`.
pub type TubeLine = (Vec<([f64; 3], [f64; 3])>, f64);

/// `outside(uv_a, uv_b)`: the box pair `[u0, u1, v0, v1]` of surface A and of surface B lies
/// outside face A or face B (see [`crate::ssi::brep_faces`] for what that decision rests on).
#[derive(Clone)]
pub struct OutsideFaces(pub std::sync::Arc<BoxPairTest>);

/// A decision on a pair of parameter boxes `[u0, u1, v0, v1]` (of A, of B).
pub type BoxPairTest = dyn Fn(&[f64; 4], &[f64; 4]) -> bool + Send + Sync;

impl std::fmt::Debug for OutsideFaces {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("OutsideFaces")
    }
}

impl OutsideFaces {
    /// The same test with the two surfaces' roles exchanged.
    pub fn swapped(&self) -> OutsideFaces {
        let o = self.0.clone();
        OutsideFaces(std::sync::Arc::new(move |a, b| o(b, a)))
    }
}

/// Most Bézier pieces per surface for [`normals_never_parallel`] (larger nets are not
/// tested: their normal cones are wide anyway).
const MAX_CONE_PIECES: usize = 64;

/// Whether no normal of `sa` is parallel (or antiparallel) to any normal of `sb`, and neither
/// vanishes, anywhere on the two surfaces: the separation lemma ([`cones`]) applied to the
/// union of the normal-cone generators of all Bézier pieces of each surface (every normal of
/// a piece is a non-negative combination of its own generators, so of the union's). Then the
/// surfaces have no tangential points at all — no touching point, no singular point of the
/// intersection. `false` (no claim) when the test fails, a piece's cone cannot be enclosed,
/// or a surface has more than `MAX_CONE_PIECES` pieces.
pub fn normals_never_parallel(sa: &NurbsSurface<f64, 3>, sb: &NurbsSurface<f64, 3>) -> bool {
    normals_never_parallel_in(&PairPieces::new(sa, sb))
}

/// [`normals_never_parallel`] on a pair's shared pieces. The test is tried first on the
/// pieces' corner normals ([`Cell::corner_normals`], points of the two surfaces' normal sets,
/// so inside the cones): where even those are not separated, the generators are not
/// computed. That filter decides only how often the claim is made, never what it claims —
/// `false` claims nothing.
pub(crate) fn normals_never_parallel_in(pp: &PairPieces) -> bool {
    if pp.a().len() > MAX_CONE_PIECES || pp.b().len() > MAX_CONE_PIECES {
        return false;
    }
    let corners = |pieces: &[Rc<Cell>]| -> Vec<V> {
        pieces.iter().flat_map(|c| c.corner_normals()).collect()
    };
    if !cones_separated(&corners(pp.a()), &corners(pp.b())) {
        return false;
    }
    let cone = |pieces: &[Rc<Cell>]| -> Option<Vec<V>> {
        let mut all = Vec::new();
        for c in pieces {
            let g = c.normals();
            if g.is_empty() {
                return None;
            }
            all.extend_from_slice(g);
        }
        Some(all)
    };
    match (cone(pp.a()), cone(pp.b())) {
        (Some(a), Some(b)) => cones_separated(&a, &b),
        _ => false,
    }
}

fn centre(b: &Box3) -> [f64; 3] {
    std::array::from_fn(|k| 0.5 * b.0[k] + 0.5 * b.1[k])
}

fn inside(uv: &[f64; 2], c: &[f64; 4]) -> bool {
    c[0] <= uv[0] && uv[0] <= c[1] && c[2] <= uv[1] && uv[1] <= c[3]
}

/// Classify the leaf pairs of an adaptive refinement of `sa × sb` (see the module comment).
pub fn coverage(
    sa: &NurbsSurface<f64, 3>,
    sb: &NurbsSurface<f64, 3>,
    branches: &[BranchOut],
    touches: &[TouchOut],
    prm: &CoverageParams,
) -> CoverageOut {
    coverage_in(&PairPieces::new(sa, sb), branches, touches, prm)
}

/// [`coverage`] on a pair's shared pieces.
pub(crate) fn coverage_in(
    pp: &PairPieces,
    branches: &[BranchOut],
    touches: &[TouchOut],
    prm: &CoverageParams,
) -> CoverageOut {
    let t0 = Instant::now();
    let (sa, sb) = pp.surfaces();
    let restricted;
    let (branches, touches) = match &prm.restrict {
        Some(r) => {
            restricted = r.apply(branches, touches);
            (&restricted.0[..], &restricted.1[..])
        }
        None => (branches, touches),
    };
    let (near, slack) = output_set(branches, touches, &prm.borders, prm.match_distance);
    let along = along::Along::new(
        branches
            .iter()
            .filter(|b| !b.tangents.is_empty())
            .flat_map(|b| b.pieces()),
    );
    // Every nearness test is against the output set: within `d` of it is within
    // `match_distance` of the output (a slack as large as the match distance leaves no
    // distance to decide with: what is not free is then listed uncertified).
    let d = (prm.match_distance - slack).max(0.0);
    let tubes: Vec<(Near, f64)> = prm
        .tubes
        .iter()
        .map(|(segs, r)| (Near::with_chords(segs.clone(), *r), *r))
        .collect();
    // Regions of proven branch points whose point is within `d` of the output (class 3′ of
    // the module comment); none on trimmed faces.
    let regions: Vec<BranchRegion> = touches
        .iter()
        .filter(|_| prm.outside.is_none())
        .filter_map(|t| t.singular.as_ref())
        .filter_map(|s| branch_region(sa, sb, s))
        .filter(|r| near.box_within(&r.point, d))
        .collect();
    let regions = disjoint_regions(regions);
    let (ra, rb) = (pp.a(), pp.b());
    let mut out = CoverageOut {
        boxes_a: ra.len(),
        boxes_b: rb.len(),
        match_distance: prm.match_distance,
        ..Default::default()
    };
    let can_split = |c: &Cell, depth: u32| depth < prm.max_pair_depth && c.diag() > 0.25 * d;
    let mut free_leaves: Vec<([f64; 4], [f64; 4], f64)> = Vec::new();
    let mut stack: Vec<(Rc<Cell>, Rc<Cell>, u32, u32)> = Vec::new();
    for a in ra {
        for b in rb {
            stack.push((a.clone(), b.clone(), 0, 0));
        }
    }
    let mut boxes = 0usize;
    let kept = pp.kept();
    let halves_kept = pp.halves_kept();
    let mut searched: rustc_hash::FxHashSet<[u64; 8]> = Default::default();
    let uncertified = |out: &mut CoverageOut, a: &Cell, b: &Cell, reason, point| {
        out.uncertified += 1;
        if out.uncertified_regions.len() < 100 {
            out.uncertified_regions.push(RegionOut {
                uv_a: a.uv,
                uv_b: b.uv,
                reason,
                point,
            });
        }
    };
    while let Some((a, b, da, db)) = stack.pop() {
        if out.pairs_examined.is_multiple_of(256)
            && (prm.deadline.is_some_and(|t| Instant::now() > t)
                || prm
                    .cancel
                    .as_ref()
                    .is_some_and(|c| c.load(std::sync::atomic::Ordering::Relaxed)))
        {
            uncertified(&mut out, &a, &b, Reason::Budget, None);
            out.uncertified += stack.len();
            break;
        }
        out.pairs_examined += 1;
        boxes += 1;
        if prm.outside.as_ref().is_some_and(|o| (o.0)(&a.uv, &b.uv)) {
            out.outside_faces += 1;
            continue;
        }
        // Past the box or time budget, or with 100 undecided pairs listed already (the pair of
        // faces is not certified either way), the rest is listed as budget-limited.
        let over = boxes > prm.max_boxes
            || out.uncertified >= 100
            || prm.deadline.is_some_and(|t| Instant::now() > t);
        let (Some(ha), Some(hb)) = (a.hull, b.hull) else {
            uncertified(&mut out, &a, &b, Reason::NoEnclosure, None);
            continue;
        };
        let (pa, pb) = (
            a.pts.as_deref().unwrap_or(&[]),
            b.pts.as_deref().unwrap_or(&[]),
        );
        if disjoint(&ha, &hb)
            || separated_along(pa, pb, &a.normal)
            || separated_along(pa, pb, &b.normal)
        {
            out.free += 1;
            // A lower bound on the gap for the self-check (0 when separated by a normal).
            let gap = (0..3)
                .map(|k| (hb.0[k] - ha.1[k]).max(ha.0[k] - hb.1[k]))
                .fold(0.0, f64::max);
            free_leaves.push((a.uv, b.uv, gap));
            continue;
        }
        let m = meet(&ha, &hb);
        if near.box_within(&m, d) || near.net_within(pa, d) || near.net_within(pb, d) {
            out.near_output += 1;
            continue;
        }
        if tubes
            .iter()
            .any(|(t, r)| t.box_within(&m, *r) || t.net_within(pa, *r) || t.net_within(pb, *r))
        {
            out.near_shared_edges += 1;
            continue;
        }
        if regions.iter().any(|r| r.holds(&a.uv, &b.uv)) {
            out.branch_point_regions += 1;
            continue;
        }
        if over {
            uncertified(&mut out, &a, &b, Reason::Budget, Some(centre(&m)));
            continue;
        }
        // Faces mode: a component of the faces' intersection may end at a trim loop inside
        // the pair, away from its border: such a pair is transversal only with every
        // crossing of the loops' edges with the other piece found too (`trim_crossings`).
        let trim_in_pair = prm
            .restrict
            .as_ref()
            .is_some_and(|r| !(r.pair_inside)(&a.uv, &b.uv));
        if a.cones_apart(&b) {
            let mut ctx = SearchCtx {
                near: &near,
                along: &along,
                d,
                tubes: &tubes,
                prm,
                halves_kept,
                boxes: &mut boxes,
                out: &mut out,
            };
            let open = ctx
                .borders(&a, &b, &mut searched)
                .or_else(|| trim_in_pair.then(|| ctx.trim_edges(&a, &b)).flatten());
            match open {
                None => {
                    out.transversal += 1;
                    out.transversal_with_trim_loops += usize::from(trim_in_pair);
                    continue;
                }
                Some(bx) => {
                    let reason = if boxes > prm.max_boxes {
                        Reason::Budget
                    } else {
                        Reason::CrossingAwayFromOutput
                    };
                    uncertified(&mut out, &a, &b, reason, Some(centre(&bx)));
                    continue;
                }
            }
        }
        // A pair a loop runs through whose cones are not separated is split while its
        // budget lasts: in smaller pairs the loop's part may be decided near the output.
        if trim_in_pair && (da + db >= TRIM_DEPTH || !(can_split(&a, da) || can_split(&b, db))) {
            uncertified(&mut out, &a, &b, Reason::TrimInPair, Some(centre(&m)));
            continue;
        }
        // Not decided: split the larger piece (pieces below a quarter of the match
        // distance are not split further: they are decided by the output or listed).
        let can_a = can_split(&a, da);
        let can_b = can_split(&b, db);
        let split_a = can_a && (!can_b || a.diag() >= b.diag());
        if split_a {
            for k in a.kids(kept).iter() {
                stack.push((k.clone(), b.clone(), da + 1, db));
            }
        } else if can_b {
            for k in b.kids(kept).iter() {
                stack.push((a.clone(), k.clone(), da, db + 1));
            }
        } else {
            uncertified(
                &mut out,
                &a,
                &b,
                Reason::NormalsNotSeparated,
                Some(centre(&m)),
            );
        }
    }
    // Self-check: no output point may have its parameters in a free pair whose boxes are
    // farther apart than the point is from the two surfaces.
    let npts: usize = branches.iter().map(|b| b.uv_a.len()).sum();
    if free_leaves.len().saturating_mul(npts) <= 20_000_000 {
        let mut bad = 0;
        for br in branches {
            let slack = br.dist_a_max + br.dist_b_max;
            for (x, y) in br.uv_a.iter().zip(&br.uv_b) {
                bad += usize::from(
                    free_leaves
                        .iter()
                        .any(|(ua, ub, gap)| *gap > slack && inside(x, ua) && inside(y, ub)),
                );
            }
        }
        out.free_pairs_with_branch_points = Some(bad);
    }
    out.pairs = out.free
        + out.near_output
        + out.near_shared_edges
        + out.transversal
        + out.branch_point_regions
        + out.uncertified;
    out.no_missed_branches = out.uncertified == 0;
    out.seconds = t0.elapsed().as_secs_f64();
    out
}
