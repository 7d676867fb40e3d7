//! Proven disjointness before any tracing: a face pair whose bounding boxes overlap is
//! subdivided together — the Bézier pieces of both surfaces (`super::roots`), quartered —
//! until every pair of pieces is *free* (case 1 of the coverage theorem, module
//! [`super`]: disjoint boxes of the enclosed Cartesian control points, or control points
//! separated along one piece's rough normal; convex hull property) or lies outside the faces.
//! Then the two faces have no common point at all: no branch, no touching point, no
//! overlap — the coverage certificate holds with an empty output, and nothing else is
//! computed for the pair.
//!
//! A budget of pieces bounds the work: where it is not enough (the surfaces meet, or come
//! closer than the pieces reached can show), the answer is "not shown" and the pair is
//! intersected as usual. The test decides nothing else.

use super::patch::{disjoint, separated_along};
use super::{Cell, CoverageOut, CoverageParams, PairPieces};
use crate::spline::NurbsSurface;
use std::rc::Rc;
use std::time::Instant;

/// Pairs of pieces examined at most before giving up.
pub const MAX_PAIRS: usize = 256;

/// The number of Bézier pieces of `s`: its non-empty knot spans in `u` times those in `v`.
fn pieces(s: &NurbsSurface<f64, 3>) -> usize {
    let spans = |k: &crate::spline::KnotVector<f64>| {
        let t = k.knots();
        (k.degree()..k.n_ctrl())
            .filter(|&i| t[i] < t[i + 1])
            .count()
    };
    spans(&s.hom.ku).saturating_mul(spans(&s.hom.kv))
}

/// The coverage certificate of a pair proven to have no common point (every leaf pair free
/// or outside the faces), or `None` when that was not shown within [`MAX_PAIRS`].
pub fn proven_disjoint(
    sa: &NurbsSurface<f64, 3>,
    sb: &NurbsSurface<f64, 3>,
    prm: &CoverageParams,
) -> Option<CoverageOut> {
    proven_disjoint_in(&PairPieces::new(sa, sb), prm)
}

/// [`proven_disjoint`] on a pair's shared pieces.
pub(crate) fn proven_disjoint_in(pp: &PairPieces, prm: &CoverageParams) -> Option<CoverageOut> {
    let t0 = Instant::now();
    let (sa, sb) = pp.surfaces();
    // The piece count from the knots first: no extraction for pairs past the budget.
    if pieces(sa).saturating_mul(pieces(sb)) > MAX_PAIRS {
        return None;
    }
    let (ra, rb) = (pp.a(), pp.b());
    let mut out = CoverageOut {
        boxes_a: ra.len(),
        boxes_b: rb.len(),
        match_distance: prm.match_distance,
        ..Default::default()
    };
    let kept = pp.kept();
    let mut stack: Vec<(Rc<Cell>, Rc<Cell>)> = Vec::new();
    for a in ra {
        for b in rb {
            stack.push((a.clone(), b.clone()));
        }
    }
    while let Some((a, b)) = stack.pop() {
        out.pairs_examined += 1;
        if out.pairs_examined > MAX_PAIRS {
            return None;
        }
        if prm.outside.as_ref().is_some_and(|o| (o.0)(&a.uv, &b.uv)) {
            out.outside_faces += 1;
            continue;
        }
        let (ha, hb) = (a.hull?, b.hull?);
        let (pa, pb) = (a.pts.as_deref()?, b.pts.as_deref()?);
        if disjoint(&ha, &hb)
            || separated_along(pa, pb, &a.normal)
            || separated_along(pa, pb, &b.normal)
        {
            out.free += 1;
            continue;
        }
        // Quarter the larger piece.
        if a.diag() >= b.diag() {
            for k in a.kids(kept).iter() {
                stack.push((k.clone(), b.clone()));
            }
        } else {
            for k in b.kids(kept).iter() {
                stack.push((a.clone(), k.clone()));
            }
        }
    }
    out.pairs = out.free;
    out.no_missed_branches = true;
    out.free_pairs_with_branch_points = Some(0);
    out.seconds = t0.elapsed().as_secs_f64();
    Some(out)
}
