//! Whether a face's closed polygons cross: the even-odd rule outlines the face only when no
//! two polygon edges meet except consecutive edges at their common corner and corners shared
//! exactly (a loop touching itself at a vertex). A cut closing a band across the seam can run
//! through a loop that folds back, or through a hole placed across it; the polygon then
//! crosses itself, and even-odd would take a pocket of the face for its complement.
//!
//! Exact: the edges' meeting is decided with the orientation predicate ([`orient2d`]) on the
//! polygons' own coordinates (the ones the face-region tests use); candidate pairs come from
//! a uniform grid of the polygons' bounding box, each edge entered in every cell its bounding
//! box meets (a conservative filter: two edges that meet share a cell).

use super::domain::BoundaryPoint;
use crate::predicates::orient2d;
use crate::scalar::Sign;
use std::collections::HashMap;

/// An edge: polygon index, corner index (the edge runs from it to the next corner).
type EdgeId = (usize, usize);

/// Whether the closed segments `a b` and `c d` (neither of zero length) have a common point
/// (exact).
fn meet(a: &[f64; 2], b: &[f64; 2], c: &[f64; 2], d: &[f64; 2]) -> bool {
    let (o1, o2) = (orient2d(a, b, c), orient2d(a, b, d));
    let (o3, o4) = (orient2d(c, d, a), orient2d(c, d, b));
    if o1 == Sign::Zero && o2 == Sign::Zero {
        // Collinear: their extents overlap in both coordinates.
        return (0..2)
            .all(|k| a[k].min(b[k]).max(c[k].min(d[k])) <= a[k].max(b[k]).min(c[k].max(d[k])));
    }
    let apart = |x: Sign, y: Sign| x != Sign::Zero && x == y;
    !(apart(o1, o2) || apart(o3, o4))
}

/// Whether two segments that meet and share exactly the corner `p` (their other ends `q`, `r`)
/// meet only there: they are not collinear, or `q` and `r` lie on opposite sides of `p`.
fn only_at(p: &[f64; 2], q: &[f64; 2], r: &[f64; 2]) -> bool {
    if orient2d(p, q, r) != Sign::Zero {
        return true;
    }
    let k = if q[0] != p[0] { 0 } else { 1 };
    (q[k] > p[k] && r[k] < p[k]) || (q[k] < p[k] && r[k] > p[k])
}

/// The first pair of edges that meet where they may not, if any (`polys` closed: the last
/// corner joins the first). Consecutive edges of one polygon may share their corner; any two
/// edges may meet at a corner both have exactly (same coordinates) and nowhere else; two
/// edges both on a pole line (`on_pole`: a degenerate border of the domain, one point of the
/// surface, where loops through the pole lay their expanded pole points) may overlap: they
/// are parallel to the even-odd rule's rays and bound no area.
pub fn first_crossing(
    polys: &[Vec<BoundaryPoint>],
    on_pole: &dyn Fn(&[f64; 2], &[f64; 2]) -> bool,
) -> Option<(EdgeId, EdgeId)> {
    let edges: Vec<(EdgeId, [f64; 2], [f64; 2])> = polys
        .iter()
        .enumerate()
        .flat_map(|(i, p)| (0..p.len()).map(move |k| ((i, k), p[k].uv, p[(k + 1) % p.len()].uv)))
        .filter(|(_, a, b)| a != b)
        .collect();
    if edges.len() < 2 {
        return None;
    }
    let mut lo = [f64::INFINITY; 2];
    let mut hi = [f64::NEG_INFINITY; 2];
    for (_, a, b) in &edges {
        for k in 0..2 {
            lo[k] = lo[k].min(a[k]).min(b[k]);
            hi[k] = hi[k].max(a[k]).max(b[k]);
        }
    }
    let cells = ((edges.len() as f64).sqrt().ceil() as usize).clamp(1, 1024);
    let size = [0, 1].map(|k| ((hi[k] - lo[k]) / cells as f64).max(f64::MIN_POSITIVE));
    let cell =
        |x: f64, k: usize| (((x - lo[k]) / size[k]).floor().max(0.0) as usize).min(cells - 1);
    let mut grid: HashMap<(usize, usize), Vec<usize>> = HashMap::new();
    for (e, (_, a, b)) in edges.iter().enumerate() {
        // Widened by one cell: the cell index is rounded; a neighbour cell more is safe.
        let (i0, i1) = (cell(a[0].min(b[0]), 0), cell(a[0].max(b[0]), 0));
        let (j0, j1) = (cell(a[1].min(b[1]), 1), cell(a[1].max(b[1]), 1));
        for i in i0.saturating_sub(1)..=(i1 + 1).min(cells - 1) {
            for j in j0.saturating_sub(1)..=(j1 + 1).min(cells - 1) {
                grid.entry((i, j)).or_default().push(e);
            }
        }
    }
    for list in grid.values() {
        for (s, &e) in list.iter().enumerate() {
            for &f in &list[s + 1..] {
                let ((ie, a, b), (jf, c, d)) = (edges[e], edges[f]);
                if !meet(&a, &b, &c, &d) || (on_pole(&a, &b) && on_pole(&c, &d)) {
                    continue;
                }
                // Allowed: one common corner and no other common point.
                let p = [a, b].into_iter().find(|p| *p == c || *p == d);
                let shared = usize::from(a == c || a == d) + usize::from(b == c || b == d);
                if let (Some(p), 1) = (p, shared) {
                    let q = if a == p { b } else { a };
                    let r = if c == p { d } else { c };
                    if only_at(&p, &q, &r) {
                        continue;
                    }
                }
                return Some((ie, jf));
            }
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    fn no_pole(_: &[f64; 2], _: &[f64; 2]) -> bool {
        false
    }

    fn poly(pts: &[[f64; 2]]) -> Vec<BoundaryPoint> {
        pts.iter()
            .map(|uv| BoundaryPoint::straight(*uv, 0))
            .collect()
    }

    #[test]
    fn squares_apart_touching_and_crossing() {
        let sq = |x: f64, y: f64, s: f64| poly(&[[x, y], [x + s, y], [x + s, y + s], [x, y + s]]);
        assert!(first_crossing(&[sq(0.0, 0.0, 1.0)], &no_pole).is_none());
        assert!(
            first_crossing(&[sq(0.0, 0.0, 4.0), sq(1.0, 1.0, 1.0)], &no_pole).is_none(),
            "a hole"
        );
        assert!(
            first_crossing(&[sq(0.0, 0.0, 1.0), sq(0.5, 0.5, 1.0)], &no_pole).is_some(),
            "overlap"
        );
        // A corner of one on the other's edge (not a shared corner): a crossing.
        let tri = poly(&[[1.0, 0.5], [2.0, 0.0], [2.0, 1.0]]);
        assert!(
            first_crossing(&[sq(0.0, 0.0, 1.0), tri], &no_pole).is_some(),
            "corner on an edge"
        );
        // Collinear consecutive edges (a cut line's points): allowed.
        let cut = poly(&[[0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [2.0, 1.0], [0.0, 1.0]]);
        assert!(first_crossing(&[cut], &no_pole).is_none());
        // Two squares sharing exactly one corner: allowed.
        assert!(first_crossing(&[sq(0.0, 0.0, 1.0), sq(1.0, 1.0, 1.0)], &no_pole).is_none());
        // Collinear overlapping edges (two squares side by side): a crossing.
        assert!(first_crossing(&[sq(0.0, 0.0, 1.0), sq(1.0, 0.0, 1.0)], &no_pole).is_some());
        // A bow tie crosses itself.
        let bow = poly(&[[0.0, 0.0], [1.0, 1.0], [1.0, 0.0], [0.0, 1.0]]);
        assert!(first_crossing(&[bow], &no_pole).is_some());
        // A spike folding back along itself.
        let spike = poly(&[[0.0, 0.0], [2.0, 0.0], [1.0, 0.0], [1.0, 1.0]]);
        assert!(first_crossing(&[spike], &no_pole).is_some());
    }
}
