//! Proven absence of tangential points near the pair's common points: every pair of pieces
//! (Bézier pieces of the two surfaces, split as the coverage refinement splits them) either
//! lies farther apart than a margin or has normal cones proven apart.
//!
//! **Claim.** If the test succeeds with margin `δ ≥ 0` ([`tangency_suspects`] leaves no
//! suspect pair), then for every point `p` of A and `q` of B with `|S_a(p) − S_b(q)| ≤ δ`,
//! the normals `n_A(p)` and `n_B(q)` are neither parallel nor antiparallel, and neither
//! vanishes. *Proof.* The leaves of the refinement partition
//! each parameter domain, so `p` lies in a leaf `α` and `q` in a leaf `β` (a point on a
//! split line lies in the pieces on both sides; any one serves). `S_a(p)` lies in the box of
//! `α`'s control points and `S_b(q)` in that of `β`'s (convex hull property, positive
//! weights, enclosures outward); if those boxes, the first grown by `δ` (outward rounded),
//! are disjoint, then `|S_a(p) − S_b(q)|_∞ > δ`, so the Euclidean distance is too,
//! contradicting the hypothesis. Otherwise the leaf pair was accepted only with its cones
//! proven apart ([`super::cones`], the separation lemma), which is the claim at `(p, q)`.
//!
//! In particular the two surfaces have no touching point and their intersection no singular
//! point (those are common points, `δ = 0`, with parallel normals). The tangential-point
//! search ([`crate::ssi::touch`]) only proposes points, so skipping it where this holds
//! changes no claim: the coverage certificate proves the output either way.

use super::PairPieces;
use super::patch::{Box3, V, disjoint, range_along};
use super::pieces::Cell;
use std::rc::Rc;

/// Pairs of pieces examined at most beyond the pairs of root pieces (the Bézier pieces
/// themselves, each examined once).
pub const MAX_PAIRS: usize = 4096;
/// Splits of one piece at most.
pub const MAX_DEPTH: u32 = 8;

/// Whether the hulls of `a` and `b` are more than `d` apart along the direction of `n`: the
/// projections onto `u ≈ n/|n|` (rounded; `|u| ≤ 1 + 10⁻¹⁵`) enclosed, and a gap of more than
/// `1.000001 d` between them (rounded up), so `|x − y| ≥ |(x − y)·u| / |u| > d`.
fn apart_along(a: &[V], b: &[V], n: &[f64; 3], d: f64) -> bool {
    let l = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    if !(l > 0.0 && l.is_finite()) {
        return false;
    }
    let u = n.map(|c| c / l);
    let g = 1.000001 * d;
    match (range_along(a, &u), range_along(b, &u)) {
        (Some(ra), Some(rb)) => (ra.1 + g).next_up() < rb.0 || (rb.1 + g).next_up() < ra.0,
        _ => false,
    }
}

fn grown(b: &Box3, d: f64) -> Box3 {
    (
        b.0.map(|x| (x - d).next_down()),
        b.1.map(|x| (x + d).next_up()),
    )
}

/// Most suspect pairs listed; past it, no list is given (a tangency along a curve, as
/// between faces meeting along a tangent-continuous edge, gives many: the test stops early
/// there, where it could not succeed).
pub const MAX_SUSPECTS: usize = 64;

/// The pairs of parameter boxes `[u0, u1, v0, v1]` (of A, of B) left undecided at
/// [`MAX_DEPTH`]: every `(p, q)` with `|S_a(p) − S_b(q)| ≤ margin` and parallel (or
/// antiparallel, or vanishing) normals has `p` in the first box and `q` in the second of one
/// of them (the proof of the module comment: every other leaf pair is farther apart or has
/// cones apart), up to the rounding of the boxes' labels (rounded midpoints of the exact
/// halves): a scheduling guide for the tangential-point search and the meshes, which prove
/// nothing. Empty: the claim of the module comment (the test succeeds). `None` (no claim)
/// past [`MAX_PAIRS`] pairs beyond the roots or [`MAX_SUSPECTS`] suspects, where an
/// enclosure fails, or for a margin that is not a finite non-negative number.
pub(crate) fn tangency_suspects(pp: &PairPieces, margin: f64) -> Option<Vec<([f64; 4], [f64; 4])>> {
    if !(margin >= 0.0 && margin.is_finite()) {
        return None;
    }
    let mut stack: Vec<(Rc<Cell>, Rc<Cell>, u32, u32)> = Vec::new();
    for a in pp.a() {
        for b in pp.b() {
            stack.push((a.clone(), b.clone(), 0, 0));
        }
    }
    let mut suspects = Vec::new();
    let roots = stack.len();
    let mut examined = 0usize;
    while let Some((a, b, da, db)) = stack.pop() {
        examined += 1;
        if examined > roots + MAX_PAIRS {
            return None;
        }
        let (Some(ha), Some(hb), Some(pa), Some(pb)) =
            (a.hull, b.hull, a.pts.as_deref(), b.pts.as_deref())
        else {
            return None;
        };
        if disjoint(&grown(&ha, margin), &hb)
            || apart_along(pa, pb, &a.normal, margin)
            || apart_along(pa, pb, &b.normal, margin)
            || a.cones_apart(&b)
        {
            continue;
        }
        let can_a = da < MAX_DEPTH;
        let can_b = db < MAX_DEPTH;
        if can_a && (!can_b || a.diag() >= b.diag()) {
            for k in a.kids(pp.kept()).iter() {
                stack.push((k.clone(), b.clone(), da + 1, db));
            }
        } else if can_b {
            for k in b.kids(pp.kept()).iter() {
                stack.push((a.clone(), k.clone(), da, db + 1));
            }
        } else {
            if suspects.len() >= MAX_SUSPECTS {
                return None;
            }
            suspects.push((a.uv, b.uv));
        }
    }
    Some(suspects)
}

/// The suspect pairs of [`tangency_suspects`] as a filter on parameter boxes (closed, grown by
/// `10⁻⁹` of their size for the labels' rounding).
pub(crate) struct Suspects(Vec<([f64; 4], [f64; 4])>);

fn overlap(a: &[f64; 4], b: &[f64; 4]) -> bool {
    let g = 1e-9 * (b[1] - b[0]).abs().max((b[3] - b[2]).abs());
    a[0] <= b[1] + g && b[0] - g <= a[1] && a[2] <= b[3] + g && b[2] - g <= a[3]
}

impl Suspects {
    pub(crate) fn new(pairs: Vec<([f64; 4], [f64; 4])>) -> Self {
        Suspects(pairs)
    }
    /// No pair: no tangential point (with the margin it was found with).
    pub(crate) fn is_empty(&self) -> bool {
        self.0.is_empty()
    }
    /// Whether some suspect pair meets box `a` of A and box `b` of B.
    pub(crate) fn meets(&self, a: &[f64; 4], b: &[f64; 4]) -> bool {
        self.0.iter().any(|(x, y)| overlap(a, x) && overlap(b, y))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spline::construct::{Frame, bilinear, sphere};

    /// The claim of the module comment, proven (no suspect pair left).
    fn no_tangential_points_in(pp: &PairPieces, margin: f64) -> bool {
        tangency_suspects(pp, margin).is_some_and(|s| s.is_empty())
    }

    fn plane_at(z: f64) -> crate::spline::NurbsSurface<f64, 3> {
        bilinear(
            [-2.0, -2.0, z],
            [2.0, -2.0, z],
            [-2.0, 2.0, z],
            [2.0, 2.0, z],
        )
        .unwrap()
    }

    /// Ground truth from the construction: the unit sphere's normal at its pole `(0, 0, 1)` is
    /// the plane `z = h`'s normal. Tangent (`h = 1`): no claim. A plane `0.5·10⁻⁶` above the
    /// pole is within a margin of `10⁻⁶` of a point with a parallel normal: no claim with that
    /// margin, while with margin 0 the claim holds (the margin is what excludes it). A plane
    /// at `h = 0.5` crosses the sphere at 60° and the pole is 0.5 away: the claim is proven.
    #[test]
    fn tangency_and_near_tangency_are_never_claimed_absent() {
        let s = sphere(&Frame::WORLD, 1.0).unwrap();
        let tangent = plane_at(1.0);
        assert!(!no_tangential_points_in(
            &PairPieces::new(&s, &tangent),
            0.0
        ));
        assert!(!no_tangential_points_in(
            &PairPieces::new(&s, &tangent),
            1e-6
        ));
        let above = plane_at(1.0 + 0.5e-6);
        assert!(!no_tangential_points_in(&PairPieces::new(&s, &above), 1e-6));
        assert!(no_tangential_points_in(&PairPieces::new(&s, &above), 0.0));
        let crossing = plane_at(0.5);
        assert!(no_tangential_points_in(
            &PairPieces::new(&s, &crossing),
            1e-6
        ));
        // A contact at a regular point: the plane y = 1 touches the sphere at (0, 1, 0), its
        // parameters (0.25, 0.5) (a quarter turn, the equator); the plane's are (0.5, 0.5).
        // The suspects are listed and hold it.
        let side = bilinear(
            [-2.0, 1.0, -2.0],
            [2.0, 1.0, -2.0],
            [-2.0, 1.0, 2.0],
            [2.0, 1.0, 2.0],
        )
        .unwrap();
        let sus = tangency_suspects(&PairPieces::new(&s, &side), 1e-6).unwrap();
        let holds = |b: &[f64; 4], u: f64, v: f64| b[0] <= u && u <= b[1] && b[2] <= v && v <= b[3];
        assert!(
            sus.iter()
                .any(|(a, b)| holds(a, 0.25, 0.5) && holds(b, 0.5, 0.5)),
            "{sus:?}"
        );
        // At the pole every piece around it holds the contact: more than `MAX_SUSPECTS`,
        // so no list (and no claim).
        assert!(tangency_suspects(&PairPieces::new(&s, &tangent), 1e-6).is_none());
        // Not a number: no claim.
        assert!(!no_tangential_points_in(
            &PairPieces::new(&s, &crossing),
            f64::NAN
        ));
    }
}
