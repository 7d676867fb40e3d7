//! Border crossings: every point where a border curve of one piece meets the other piece is
//! enclosed, by subdividing the curve and the piece together, in boxes that are either proven
//! empty (disjoint control-point boxes: convex hull property) or proven to lie within the
//! match distance of the output (see [`super::near`]). What neither can be shown for, down
//! to the depth limit, is returned as a *possible crossing away from the output*.

use super::crossing_newton::{Crossings, PatchJet, crossings, patch_jet};
use super::near::Near;
use super::patch::{Box3, ICurve, IPatch, V, box_of, diagonal, disjoint, meet, separated_along};
use std::cell::OnceCell;
use std::rc::Rc;

/// What the search established for one border curve against one piece.
#[derive(Debug, Default)]
pub(crate) struct CrossingSearch {
    /// Boxes examined.
    pub boxes: usize,
    /// Boxes holding possible crossings, all proven within the match distance of the output.
    pub near_output: usize,
    /// Boxes holding possible crossings, proven inside a tube ([`super::CoverageParams::tubes`]).
    pub near_tubes: usize,
    /// A box that may hold a crossing and is not proven near the output (its model-space
    /// enclosure), if any was left at the depth or box limit.
    pub open: Option<Box3>,
}

/// A piece of the surface with its enclosed Cartesian control points, and its enclosures for
/// the crossing test (made when first asked for).
type Piece = (IPatch, Option<Vec<V>>, OnceCell<Option<PatchJet>>);

/// Search `curve` against `patch`: subdivide both until every part is empty, within `d` of
/// the output `near` or inside a tube (within its reach of its polyline); stop at `max_depth`
/// levels or `max_boxes` boxes.
pub(crate) fn search(
    curve: &ICurve,
    patch: &IPatch,
    (near, d): (&Near, f64),
    tubes: &[(Near, f64)],
    max_depth: u32,
    max_boxes: usize,
) -> CrossingSearch {
    let mut out = CrossingSearch::default();
    // A piece with its enclosed Cartesian control points, shared while only the curve splits.
    let piece = |s: IPatch| {
        let pts = s.cartesian();
        Rc::new((s, pts, OnceCell::new()))
    };
    let mut stack: Vec<(ICurve, Rc<Piece>, u32)> = vec![(curve.clone(), piece(patch.clone()), 0)];
    // Consecutive parts of the curve are usually near the same output chord.
    let hint = super::near::Hint::default();
    while let Some((c, sp, depth)) = stack.pop() {
        out.boxes += 1;
        let s = &sp.0;
        let (pc, ps) = match (c.cartesian(), sp.1.as_deref()) {
            (Some(a), Some(b)) => (a, b),
            // No enclosure (weights not positive, overflow): cannot be excluded.
            (a, b) => {
                out.open = Some(
                    a.as_deref()
                        .or(b)
                        .map(box_of)
                        .unwrap_or(([f64::NEG_INFINITY; 3], [f64::INFINITY; 3])),
                );
                return out;
            }
        };
        let (hc, hs) = (box_of(&pc), box_of(ps));
        if disjoint(&hc, &hs) || separated_along(&pc, ps, &s.rough_normal()) {
            continue;
        }
        let m = meet(&hc, &hs);
        if near.net_within_hinted(&pc, d, &hint) || near.box_within(&m, d) {
            out.near_output += 1;
            continue;
        }
        if tubes
            .iter()
            .any(|(t, r)| t.net_within(&pc, *r) || t.box_within(&m, *r))
        {
            out.near_tubes += 1;
            continue;
        }
        // Krawczyk's enclosure of every crossing of these two parts (`crossing_newton`).
        let jet = sp.2.get_or_init(|| patch_jet(s));
        match jet
            .as_ref()
            .map_or(Crossings::Undecided, |j| crossings(&c, s, j, d / 16.0))
        {
            Crossings::None => continue,
            Crossings::Within(b) => {
                if disjoint(&b, &m) {
                    continue;
                }
                let b = meet(&b, &m);
                if near.box_within(&b, d) {
                    out.near_output += 1;
                    continue;
                }
                if tubes.iter().any(|(t, r)| t.box_within(&b, *r)) {
                    out.near_tubes += 1;
                    continue;
                }
            }
            Crossings::Undecided => {}
        }
        // Parts far smaller than `d` that are not near the output will not become near by
        // splitting: a crossing away from the output is likely there.
        if depth >= max_depth
            || out.boxes >= max_boxes
            || diagonal(&hc).max(diagonal(&hs)) < 0.125 * d
        {
            out.open = Some(m);
            return out;
        }
        // Split the curve unless the piece is more than twice as large (the near test looks
        // at the curve's control points, so the curve should shrink first), else the piece
        // along its longer direction. A planar piece (flat to 1e-10 of its size) is not
        // split: its halves lie in the same slab, so separation along the normal gains
        // nothing, and a curve lying in the plane along the output is decided by its own
        // control points (a scheduling choice: any order of splits is sound).
        let planar = thickness(ps, &s.rough_normal()) <= 1e-10 * diagonal(&hs);
        if 2.0 * diagonal(&hc) >= diagonal(&hs) || planar {
            let (l, r) = c.halve();
            stack.push((l, sp.clone(), depth + 1));
            stack.push((r, sp, depth + 1));
        } else {
            let (l, r) = s.halve(s.longer_in_u());
            stack.push((c.clone(), piece(l), depth + 1));
            stack.push((c, piece(r), depth + 1));
        }
    }
    out
}

/// Width of the enclosed points along `n` (a scheduling figure only, rounded to nearest).
fn thickness(p: &[V], n: &[f64; 3]) -> f64 {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for q in p {
        let (a, b) = (0..3).fold((0.0, 0.0), |(a, b), k| {
            let (x, y) = (n[k] * q[k].lo, n[k] * q[k].hi);
            (a + x.min(y), b + x.max(y))
        });
        lo = lo.min(a);
        hi = hi.max(b);
    }
    hi - lo
}
