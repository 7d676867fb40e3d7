//! Border crossings: every point where a border curve of one piece meets the other piece is
//! enclosed, by subdividing the curve and the piece together, in boxes that are either proven
//! empty (disjoint control-point boxes: convex hull property) or proven to lie within the
//! match distance of the output (see [`super::near`]; a curve part along one of the output's
//! cubic pieces, by `coverage::along`). What neither can be shown for, down
//! to the depth limit, is returned as a *possible crossing away from the output*.

use super::along::Along;
use super::crossing_newton::{Crossings, PatchJet, crossings, patch_jet};
use super::near::Near;
use super::output::BoxTest;
use super::patch::{Box3, ICurve, IPatch, V, apart, box_of, diagonal, disjoint, meet, range_along};
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
    /// Boxes left out as outside the faces ([`Skip`]).
    pub outside_faces: usize,
    /// A box that may hold a crossing and is not proven near the output (its model-space
    /// enclosure), if any was left at the depth or box limit.
    pub open: Option<Box3>,
}

/// A piece of the surface with what every part of the curve is tested against: its enclosed
/// Cartesian control points and their box, its rough normal with the control points'
/// projection onto it, and its enclosures for the crossing test (made when first asked for).
pub(crate) struct Piece {
    s: IPatch,
    /// Its parameter box on its surface (a label: rounded midpoints of the refinement), and
    /// whether that box lies outside its face, or wholly inside it ([`Skip::piece`]'s tests,
    /// made when first asked for: the face of a surface is the same in every search of the
    /// face pair).
    uv: [f64; 4],
    outside_face: OnceCell<bool>,
    inside_face: OnceCell<bool>,
    pts: Option<(Vec<V>, Box3)>,
    normal: [f64; 3],
    range: Option<(f64, f64)>,
    jet: OnceCell<Option<PatchJet>>,
    /// The two halves along the longer direction, made when first asked for and shared by
    /// every later search against this piece (the split is a function of the piece alone).
    halves: OnceCell<[Rc<Piece>; 2]>,
}

impl Piece {
    fn new(s: IPatch, uv: [f64; 4]) -> Rc<Piece> {
        let pts = s.cartesian().map(|p| {
            let b = box_of(&p);
            (p, b)
        });
        let normal = s.rough_normal();
        Piece::with(s, pts, normal, uv)
    }
    /// A piece from its enclosed Cartesian control points with their box (as
    /// [`IPatch::cartesian`] gives them), its rough normal ([`IPatch::rough_normal`]) and
    /// its parameter box: made once per piece of the refinement and shared by every search
    /// against it.
    pub(crate) fn with(
        s: IPatch,
        pts: Option<(Vec<V>, Box3)>,
        normal: [f64; 3],
        uv: [f64; 4],
    ) -> Rc<Piece> {
        let range = pts.as_ref().and_then(|(p, _)| range_along(p, &normal));
        Rc::new(Piece {
            s,
            uv,
            outside_face: OnceCell::new(),
            inside_face: OnceCell::new(),
            pts,
            normal,
            range,
            jet: OnceCell::new(),
            halves: OnceCell::new(),
        })
    }
    /// The piece halved along its longer parameter direction: made once and kept while
    /// fewer than [`CACHED_HALVES`] control points of halves are kept for the pair (`kept`
    /// counts them); past
    /// that, made anew on every call (memory stays bounded on large runs).
    fn halves(&self, kept: &std::cell::Cell<usize>) -> [Rc<Piece>; 2] {
        if let Some(h) = self.halves.get() {
            return h.clone();
        }
        let along_u = self.s.longer_in_u();
        let (l, r) = self.s.halve(along_u);
        let [u0, u1, v0, v1] = self.uv;
        let h = if along_u {
            let um = 0.5 * (u0 + u1);
            [
                Piece::new(l, [u0, um, v0, v1]),
                Piece::new(r, [um, u1, v0, v1]),
            ]
        } else {
            let vm = 0.5 * (v0 + v1);
            [
                Piece::new(l, [u0, u1, v0, vm]),
                Piece::new(r, [u0, u1, vm, v1]),
            ]
        };
        if kept.get() < CACHED_HALVES {
            kept.set(kept.get() + 2 * self.s.x.len());
            let _ = self.halves.set(h.clone());
        }
        h
    }
}

/// Control points of the search pieces' halves kept per pair of faces: 4,096 bicubic halves
/// (each a few kilobytes of enclosures); halves of higher degree count for more.
pub(crate) const CACHED_HALVES: usize = 4096 * 16;

/// Which crossings a search may leave out: those outside the faces (faces mode). A crossing
/// is a point of the curve's surface, at the curve's parameters, and one of the piece's
/// surface; where the curve part's parameter box lies outside its face, or the piece part's
/// outside its own, no crossing of the two parts is a point of the faces' intersection.
#[derive(Clone, Copy, Default)]
pub(crate) struct Skip<'a> {
    /// The curve's parameter segment on its surface (`t ↦ a + t (b − a)`, a label of the
    /// border it is: rounded like the pieces' labels) with the test of its face.
    pub curve: Option<(&'a BoxTest, [f64; 2], [f64; 2])>,
    /// The tests of the piece's face: outside it, and wholly inside it.
    pub piece: Option<(&'a BoxTest, &'a BoxTest)>,
}

impl Skip<'_> {
    /// Whether the curve part on `[t0, t1]` against the piece part `sp` can be left out.
    fn outside(&self, (t0, t1): (f64, f64), sp: &Piece) -> bool {
        self.piece
            .is_some_and(|(f, _)| *sp.outside_face.get_or_init(|| f(&sp.uv)))
            || self.curve.is_some_and(|(f, a, b)| {
                let at = |t: f64| [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])];
                let (p, q) = (at(t0), at(t1));
                f(&[
                    p[0].min(q[0]),
                    p[0].max(q[0]),
                    p[1].min(q[1]),
                    p[1].max(q[1]),
                ])
            })
    }
}

/// Search `curve` against the piece `patch`: subdivide both until every part is empty, within `d` of
/// the output (`near`, or `along` one of its cubic pieces), inside a tube (within its reach
/// of its polyline) or, by `skip`, outside the faces; stop at `max_depth` levels or
/// `max_boxes` boxes. `kept` counts the pieces' halves kept for the pair ([`CACHED_HALVES`]).
pub(crate) fn search(
    curve: &ICurve,
    patch: &Rc<Piece>,
    (near, along, d): (&Near, &Along, f64),
    tubes: &[(Near, f64)],
    (max_depth, max_boxes): (u32, usize),
    kept: &std::cell::Cell<usize>,
    skip: Skip,
) -> CrossingSearch {
    let mut out = CrossingSearch::default();
    // Pieces are shared while only the curve splits; each curve part with its parameter range.
    type Part = (ICurve, (f64, f64), Rc<Piece>, u32);
    let mut stack: Vec<Part> = vec![(curve.clone(), (0.0, 1.0), patch.clone(), 0)];
    // Consecutive parts of the curve are usually near the same output chord.
    let hint = super::near::Hint::default();
    while let Some((c, tr, sp, depth)) = stack.pop() {
        out.boxes += 1;
        let s = &sp.s;
        let (pc, (ps, hs)) = match (c.cartesian(), sp.pts.as_ref()) {
            (Some(a), Some(b)) => (a, b),
            // No enclosure (weights not positive, overflow): cannot be excluded.
            (a, b) => {
                out.open = Some(
                    a.as_deref()
                        .map(box_of)
                        .or(b.map(|b| b.1))
                        .unwrap_or(([f64::NEG_INFINITY; 3], [f64::INFINITY; 3])),
                );
                return out;
            }
        };
        let hc = box_of(&pc);
        if disjoint(&hc, hs)
            || sp
                .range
                .zip(range_along(&pc, &sp.normal))
                .is_some_and(|(a, b)| apart(a, b))
        {
            continue;
        }
        // Parts whose crossings all lie outside the faces (tested after the cheap box tests).
        if skip.outside(tr, &sp) {
            out.outside_faces += 1;
            continue;
        }
        let m = meet(&hc, hs);
        // The box test is skipped where the common part is the curve part's whole box: that
        // box holds the hull the net test has just failed on (skipping a test never decides).
        if near.net_within_hinted(&pc, d, &hint)
            || (m != hc && near.box_within(&m, d))
            || along.curve_within(&c, &hc, diagonal(&hc), d)
        {
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
        let jet = sp.jet.get_or_init(|| patch_jet(s));
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
            || diagonal(&hc).max(diagonal(hs)) < 0.125 * d
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
        // A planar piece the border of its face runs through is split too: its parts outside
        // the face are then left out.
        let planar = skip
            .piece
            .is_none_or(|(_, inside)| *sp.inside_face.get_or_init(|| inside(&sp.uv)))
            && thickness(ps, &sp.normal) <= 1e-10 * diagonal(hs);
        if 2.0 * diagonal(&hc) >= diagonal(hs) || planar {
            let (l, r) = c.halve();
            let tm = 0.5 * (tr.0 + tr.1);
            stack.push((l, (tr.0, tm), sp.clone(), depth + 1));
            stack.push((r, (tm, tr.1), sp, depth + 1));
        } else {
            let [l, r] = sp.halves(kept);
            stack.push((c.clone(), tr, l, depth + 1));
            stack.push((c, tr, r, depth + 1));
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
