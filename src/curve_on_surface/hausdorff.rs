//! Step 4 — the Hausdorff distance between a domain curve piece and its chord.
//!
//! The paper computes `H` from candidate points (eqs. 13–17): where the tangent is parallel to
//! the chord (roots of the derivative of `f(t) = (C(t) - P_0) × (P_n - P_0)`, eq. 15) and the
//! perpendiculars through the chord's end points (eqs. 16–17, solved iteratively there).
//! Here the *certified* value is an upper bound that needs no iteration:
//! * curve → chord: distance to a segment is convex, so on each sub-piece it is at most its
//!   value at the sub-piece's control points (convex hull property); the piece is subdivided
//!   (up to `2^HULL_LEVELS` sub-pieces) until the bound is tight enough. Computed exactly
//!   (squared distances in `Rational`), then rounded up;
//! * chord → curve: the curve joins the chord's end points, so its projection covers the
//!   chord and every chord point is within the curve → chord bound of a curve point.
//! * chord end points are rounded (or snapped onto knot lines); each carries its exact
//!   offset `e` from the curve point it stands for, and the bound grows by `2 max(e)`.
//!
//! The candidate points of eq. (15) choose where to split a piece that is too far
//! ([`farthest_parameter`]): roots isolated exactly.

use crate::geom::Point;
use crate::predicates::poly::{
    certify_squarefree, deflate_ends, descartes_isolate, integer_bernstein,
    integer_power_from_bernstein,
};
use crate::scalar::{Rational, Scalar, ratio};
use crate::spline::BezierCurve;

/// Subdivision levels used to tighten the hull bound.
pub const HULL_LEVELS: u32 = 3;

/// Exact squared distance from `p` to the segment `[a, b]`.
pub fn dist2_point_segment(p: &[Rational; 2], a: &[Rational; 2], b: &[Rational; 2]) -> Rational {
    let ab = b.sub(a);
    let ap = p.sub(a);
    let l2 = crate::geom::norm2(&ab);
    if l2.is_zero() {
        return crate::geom::norm2(&ap);
    }
    let t = crate::geom::dot(&ap, &ab);
    if Scalar::sign(&t) != crate::Sign::Positive {
        return crate::geom::norm2(&ap);
    }
    if t >= l2 {
        return crate::geom::norm2(&p.sub(b));
    }
    let c = crate::geom::cross2(&ap, &ab);
    c.clone() * c / l2
}

fn hull_bound2(c: &BezierCurve<[Rational; 2]>, a: &[Rational; 2], b: &[Rational; 2]) -> Rational {
    c.control
        .iter()
        .map(|p| dist2_point_segment(p, a, b))
        .max_by(|x, y| x.cmp(y))
        .unwrap_or_else(<Rational as Scalar>::zero)
}

/// Certified upper bound on the Hausdorff distance between the curve piece `c` (exact) and
/// the chord `[a, b]`, whose end points stand `e` (max of both) from the curve's end points.
/// Stops refining once the bound is at most `target`.
pub fn hausdorff_bound(
    c: &BezierCurve<[Rational; 2]>,
    a: &[f64; 2],
    b: &[f64; 2],
    e: f64,
    target: f64,
) -> f64 {
    let qa: [Rational; 2] = crate::geom::lift_point(a);
    let qb: [Rational; 2] = crate::geom::lift_point(b);
    let mut pieces = vec![c.clone()];
    let mut best = f64::INFINITY;
    for level in 0..=HULL_LEVELS {
        let m2 = pieces
            .iter()
            .map(|p| hull_bound2(p, &qa, &qb))
            .max_by(|x, y| x.cmp(y))
            .unwrap_or_else(<Rational as Scalar>::zero);
        let h = (super::tolerance::sqrt_up(&m2) + 2.0 * e).next_up();
        best = best.min(h);
        if best <= target || level == HULL_LEVELS {
            break;
        }
        let half = ratio(1, 2);
        pieces = pieces
            .iter()
            .flat_map(|p| {
                let (l, r) = p.subdivide(&half);
                [l, r]
            })
            .collect();
    }
    best
}

/// The parameter in `(0, 1)` of the point of `c` farthest from its chord's line: among the
/// roots of `f'(t)` (eq. 15: tangent parallel to the chord), isolated exactly, the one with
/// the largest `|f|`; `1/2` when there is none.
pub fn farthest_parameter(c: &BezierCurve<[Rational; 2]>) -> Rational {
    let half = ratio(1, 2);
    let n = c.degree();
    if n < 2 {
        return half;
    }
    let chord = c.control[n].sub(&c.control[0]);
    // f has Bernstein coefficients b_i; f' has n (b_{i+1} - b_i).
    let b: Vec<Rational> = c
        .control
        .iter()
        .map(|p| crate::geom::cross2(&p.sub(&c.control[0]), &chord))
        .collect();
    let db: Vec<Rational> = b.windows(2).map(|w| w[1].clone() - w[0].clone()).collect();
    let ib = integer_bernstein(&db);
    let g = deflate_ends(integer_power_from_bernstein(&ib));
    let roots = if g.len() > 1 && certify_squarefree(&g) {
        descartes_isolate(&ib, 4096, 40).unwrap_or_default()
    } else {
        vec![]
    };
    let fval = |t: &Rational| crate::geom::cross2(&c.eval(t).sub(&c.control[0]), &chord).abs();
    roots
        .into_iter()
        .map(|r| (r.lo + r.hi) / Rational::from(2))
        .map(|t| (fval(&t), t))
        .max_by(|x, y| x.0.cmp(&y.0))
        .map(|(_, t)| t)
        .unwrap_or(half)
}
