//! Thinning the traced points before the insertion, with cubic pieces
//! ([`super::refine::RefineParams::cubic`]): the mesh gives about one point per triangle the
//! curve crosses, many more than cubic pieces need (their error falls with the sixth power of
//! the arc's angle, [`super::hermite`]). A run of refined points is replaced by its two ends
//! when the Hermite piece between them ([`super::hermite::Piece`]) passes within `tol / 8` of
//! every point of the run (measured by projection onto the piece).
//!
//! Nothing is claimed from this step: it only chooses where the insertion
//! ([`super::insert::Inserter::between`]) starts. The insertion then measures every piece
//! against the true curve at a quarter, half and three quarters and splits it where it
//! strays, every output point is certified, and the coverage certificate is decided on the
//! output — exactly as for unthinned points.
//!
//! Kept always: the ends of an open branch, points without a tangent jet (surfaces at a small
//! angle, [`super::hermite::MIN_SIN`]) or not converged, and both ends of a step whose
//! parameters jump by more than a quarter of a domain (a seam crossing); a closed branch keeps
//! at least three points (else it is left as traced).

use super::hermite::{P7, Piece, tangent_jet};
use super::insert::packed;
use super::refine::{RefineStatus, Refined};
use crate::spline::NurbsSurface;

/// Most points one piece may replace (bounds the quadratic work of a run).
const MAX_RUN: usize = 32;

/// Whether the step `p → q` jumps by more than a quarter of a domain in a parameter.
fn jumps(p: &Refined, q: &Refined, da: &[f64; 4], db: &[f64; 4]) -> bool {
    let far = |a: &[f64; 2], b: &[f64; 2], d: &[f64; 4]| {
        (a[0] - b[0]).abs() > 0.25 * (d[1] - d[0]) || (a[1] - b[1]).abs() > 0.25 * (d[3] - d[2])
    };
    far(&p.uv_a, &q.uv_a, da) || far(&p.uv_b, &q.uv_b, db)
}

/// The indices of `kept` (into `pts`, in curve order) that stay; for a closed branch the
/// piece from the last back to the first is thinned too.
pub(super) fn thin(
    sa: &NurbsSurface<f64, 3>,
    sb: &NurbsSurface<f64, 3>,
    pts: &[Refined],
    kept: &[usize],
    closed: bool,
    tol: f64,
) -> Vec<usize> {
    let n = kept.len();
    if n < 3 {
        return kept.to_vec();
    }
    let (da, db) = (super::refine::domain(sa), super::refine::domain(sb));
    // The sequence walked: a closed branch returns to its first point.
    let seq: Vec<usize> = if closed {
        kept.iter().copied().chain([kept[0]]).collect()
    } else {
        kept.to_vec()
    };
    let jet = |r: &Refined| -> Option<P7> {
        (r.status == RefineStatus::Converged)
            .then(|| tangent_jet(sa, sb, &r.uv_a, &r.uv_b))
            .flatten()
    };
    let jets: Vec<Option<P7>> = seq.iter().map(|&k| jet(&pts[k])).collect();
    let m = seq.len();
    let fits = |a: usize, e: usize| -> bool {
        let (Some(ja), Some(je)) = (jets[a].as_ref(), jets[e].as_ref()) else {
            return false;
        };
        let (p, q) = (&pts[seq[a]], &pts[seq[e]]);
        let Some(piece) = Piece::cubic(&packed(p), ja, &packed(q), je) else {
            return false;
        };
        (a + 1..e).all(|j| piece.dist(&pts[seq[j]].xyz) <= tol / 8.0)
    };
    let mut out = vec![seq[0]];
    let mut a = 0;
    while a + 1 < m {
        // The farthest end `e` such that every point strictly between can be dropped.
        let mut e = a + 1;
        while e + 1 < m
            && e + 1 - a <= MAX_RUN
            && jets[e].is_some()
            && !jumps(&pts[seq[e]], &pts[seq[e + 1]], &da, &db)
            && !jumps(&pts[seq[e - 1]], &pts[seq[e]], &da, &db)
            && fits(a, e + 1)
        {
            e += 1;
        }
        out.push(seq[e]);
        a = e;
    }
    if closed {
        // The walk ended on the first point again.
        out.pop();
        // A loop smaller than `tol / 8` could come out as one or two points: keep it as traced.
        if out.len() < 3 {
            return kept.to_vec();
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spline::construct::bilinear;

    /// The planes z = 0 (A, over [−1, 1]²) and x = 0 (B, over y, z in [−1, 1]): the curve is
    /// the y axis, its tangent jet defined everywhere.
    fn planes() -> (NurbsSurface<f64, 3>, NurbsSurface<f64, 3>) {
        (
            bilinear(
                [-1.0, -1.0, 0.0],
                [1.0, -1.0, 0.0],
                [-1.0, 1.0, 0.0],
                [1.0, 1.0, 0.0],
            )
            .unwrap(),
            bilinear(
                [0.0, -1.0, -1.0],
                [0.0, 1.0, -1.0],
                [0.0, -1.0, 1.0],
                [0.0, 1.0, 1.0],
            )
            .unwrap(),
        )
    }

    /// The point `(0, y, 0)` on both planes, or `(e, y, 0)` off the curve by `e`.
    fn at(y: f64, e: f64) -> Refined {
        let v = (y + 1.0) / 2.0;
        Refined {
            xyz: [e, y, 0.0],
            uv_a: [(e + 1.0) / 2.0, v],
            uv_b: [v, 0.5],
            gap: 0.0,
            status: RefineStatus::Converged,
            iterations: 1,
            sin_angle: 1.0,
        }
    }

    #[test]
    fn straight_runs_shrink_to_their_ends_and_bends_are_kept() {
        let (a, b) = planes();
        let pts: Vec<Refined> = (0..=10).map(|k| at(-0.9 + 0.18 * k as f64, 0.0)).collect();
        let all: Vec<usize> = (0..pts.len()).collect();
        assert_eq!(thin(&a, &b, &pts, &all, false, 1e-7), vec![0, 10]);
        // A point 1e-7 off the line (more than tol / 8 from any piece through points on the
        // line) ends a run.
        let mut bent = pts.clone();
        bent[5] = at(bent[5].xyz[1], 1e-7);
        let kept = thin(&a, &b, &bent, &all, false, 1e-7);
        assert!(kept.contains(&5) && kept.len() < pts.len(), "{kept:?}");
        // A point without a tangent jet (not converged) is kept, and so are its neighbours (a
        // piece ending at it would be a chord, which is not thinned).
        let mut stuck = pts.clone();
        stuck[3].status = RefineStatus::NotConverged;
        assert_eq!(
            thin(&a, &b, &stuck, &all, false, 1e-7),
            vec![0, 2, 3, 4, 10]
        );
    }

    #[test]
    fn a_loop_below_the_tolerance_keeps_its_points() {
        let (a, b) = planes();
        // Ten points within 1e-12 of each other, as a closed branch.
        let pts: Vec<Refined> = (0..10).map(|k| at(1e-13 * k as f64, 0.0)).collect();
        let all: Vec<usize> = (0..pts.len()).collect();
        assert_eq!(thin(&a, &b, &pts, &all, true, 1e-7), all);
    }
}
