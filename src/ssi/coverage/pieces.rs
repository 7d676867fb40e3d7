//! The pieces of the coverage certificate's refinement: the Bézier pieces (knot spans) of a
//! surface with enclosed control points — interval de Boor–Ramshaw extraction, or exact
//! rational knot insertion then outward rounding — and their quarters, each with its
//! control-point box and normal-cone generators, cached for reuse.

use super::cones::{cones_separated, normal_box, normal_generators};
use super::crossings::Piece;
use super::patch::{Box3, IPatch, V, box_of, diagonal};
use crate::geom::{Hom, lift_point};
use crate::scalar::{Interval, Rational, Scalar, lift};
use crate::spline::NurbsSurface;
use crate::spline::enclosed_bezier::enclosed_bezier_patches;
use std::cell::OnceCell;
use std::rc::Rc;

type Q = Rational;

/// Control points of the pieces kept for reuse (children of split pieces), per face pair:
/// 10,000 bicubic pieces, about 5 KB each, about 50 MB per face pair; a piece of higher
/// degree counts for more (its enclosures and cone generators grow with its net), so memory
/// stays about that whatever the degrees. abc-0000.step peaked at 3.7 GB before any bound,
/// 0.39 GB with it; occt-BUC50025.igs (degrees up to 9 × 12) at 1.68 GB when the bound
/// counted pieces.
const CACHED_CELLS: usize = 10_000 * 16;

/// One piece of a domain: its exact-enclosed patch, uv label, box and cached data.
pub(crate) struct Cell {
    pub(crate) uv: [f64; 4],
    /// Where the piece lies exactly: its Bézier piece's knot span `[u0, u1, v0, v1]` (exact
    /// `f64` knots) and the dyadic part `[a0, a1, b0, b1]` of that span's `[0, 1]²` it is
    /// (exact: halvings of `[0, 1]`, while fewer than 53 in a direction).
    pub(crate) span: [f64; 4],
    pub(crate) frac: [f64; 4],
    pub(crate) patch: IPatch,
    /// Enclosed Cartesian control points, their box, and a rough normal.
    pub(super) pts: Option<Vec<V>>,
    pub(super) hull: Option<Box3>,
    pub(super) normal: [f64; 3],
    polynomial: bool,
    normals: OnceCell<Vec<V>>,
    normal_box: OnceCell<Option<V>>,
    kids: OnceCell<Rc<[Rc<Cell>]>>,
    /// The piece as the border-crossing search takes it (made when first searched against).
    piece: OnceCell<Rc<Piece>>,
}

impl Cell {
    fn new(patch: IPatch, uv: [f64; 4], polynomial: bool) -> Rc<Cell> {
        Cell::at(patch, uv, (uv, [0.0, 1.0, 0.0, 1.0]), polynomial)
    }
    fn at(
        patch: IPatch,
        uv: [f64; 4],
        (span, frac): ([f64; 4], [f64; 4]),
        polynomial: bool,
    ) -> Rc<Cell> {
        let pts = patch.cartesian();
        Rc::new(Cell {
            uv,
            span,
            frac,
            hull: pts.as_deref().map(box_of),
            pts,
            normal: patch.rough_normal(),
            patch,
            polynomial,
            normals: OnceCell::new(),
            normal_box: OnceCell::new(),
            kids: OnceCell::new(),
            piece: OnceCell::new(),
        })
    }
    /// The piece for [`super::crossings::search`], made once and shared by every search
    /// against it.
    pub(super) fn piece(&self) -> Rc<Piece> {
        self.piece
            .get_or_init(|| {
                let pts = self.pts.clone().zip(self.hull);
                Piece::with(self.patch.clone(), pts, self.normal, self.uv)
            })
            .clone()
    }
    pub(super) fn normals(&self) -> &[V] {
        self.normals
            .get_or_init(|| normal_generators(&self.patch, self.polynomial))
    }
    /// Approximate normals at the piece's four corners, `(P₁₀ − P₀₀) × (P₀₁ − P₀₀)` and alike
    /// from the midpoints of the enclosed control points (the normal direction at a corner
    /// of a Bézier patch with positive weights, up to rounding), as point intervals;
    /// degenerate corners left out. Evidence for a quick filter, proves nothing.
    pub(super) fn corner_normals(&self) -> Vec<V> {
        let Some(pts) = self.pts.as_deref() else {
            return Vec::new();
        };
        let (p, q) = (self.patch.p, self.patch.q);
        if p == 0 || q == 0 || pts.len() != (p + 1) * (q + 1) {
            return Vec::new();
        }
        let at = |i: usize, j: usize| -> [f64; 3] { pts[i * (q + 1) + j].map(|c| c.mid()) };
        let sub = |x: [f64; 3], y: [f64; 3]| -> [f64; 3] { std::array::from_fn(|k| x[k] - y[k]) };
        // Corner (i, j) with its neighbours along u (i ± 1) and v (j ± 1); the signs keep
        // each product along `S_u × S_v`.
        [
            (0, 0, 1, 1),
            (p, 0, p - 1, 1),
            (0, q, 1, q - 1),
            (p, q, p - 1, q - 1),
        ]
        .into_iter()
        .filter_map(|(i, j, ni, nj)| {
            let c = at(i, j);
            let du = if ni > i {
                sub(at(ni, j), c)
            } else {
                sub(c, at(ni, j))
            };
            let dv = if nj > j {
                sub(at(i, nj), c)
            } else {
                sub(c, at(i, nj))
            };
            let n = crate::geom::cross(&du, &dv);
            (n.iter().all(|x| x.is_finite()) && n.iter().any(|x| *x != 0.0))
                .then(|| n.map(Interval::point))
        })
        .collect()
    }
    /// The piece's normals as one interval vector ([`normal_box`]).
    fn normal_box(&self) -> Option<&V> {
        self.normal_box
            .get_or_init(|| normal_box(&self.patch, self.polynomial))
            .as_ref()
    }
    /// Whether no normal of this piece is parallel to one of `other` (the separation lemma):
    /// the one-box cones first (cheap), the generators where those overlap.
    pub(super) fn cones_apart(&self, other: &Cell) -> bool {
        let boxes = match (self.normal_box(), other.normal_box()) {
            (Some(x), Some(y)) => cones_separated(std::slice::from_ref(x), std::slice::from_ref(y)),
            _ => false,
        };
        boxes || cones_separated(self.normals(), other.normals())
    }
    /// The piece's children: its two halves across the longer direction where the net is
    /// more than four times as long one way as the other (squared lengths by
    /// [`IPatch::border_lengths`] more than 16 times), else its
    /// four quarters. Any partition of the piece serves the certificate; halving a long,
    /// narrow piece (beside a pole, where the parameter lines converge) keeps the children
    /// from growing narrower still. Kept for the next pair that splits this piece while
    /// fewer than [`CACHED_CELLS`] control points are kept in this run (`kept` counts them); past
    /// that, made afresh each time, so memory stays bounded however deep the refinement goes.
    pub(super) fn kids(&self, kept: &std::cell::Cell<usize>) -> Rc<[Rc<Cell>]> {
        if let Some(k) = self.kids.get() {
            return k.clone();
        }
        let [u0, u1, v0, v1] = self.uv;
        let (um, vm) = (0.5 * (u0 + u1), 0.5 * (v0 + v1));
        let [a0, a1, b0, b1] = self.frac;
        let (am, bm) = (0.5 * (a0 + a1), 0.5 * (b0 + b1));
        let (lu, lv) = self.patch.border_lengths();
        let kid = |p: IPatch, uv: [f64; 4], frac: [f64; 4]| {
            Cell::at(p, uv, (self.span, frac), self.polynomial)
        };
        let k: Rc<[Rc<Cell>]> = if lu > 16.0 * lv {
            let (a, b) = self.patch.halve(true);
            Rc::new([
                kid(a, [u0, um, v0, v1], [a0, am, b0, b1]),
                kid(b, [um, u1, v0, v1], [am, a1, b0, b1]),
            ])
        } else if lv > 16.0 * lu {
            let (a, b) = self.patch.halve(false);
            Rc::new([
                kid(a, [u0, u1, v0, vm], [a0, a1, b0, bm]),
                kid(b, [u0, u1, vm, v1], [a0, a1, bm, b1]),
            ])
        } else {
            let [a, b, c, d] = self.patch.quarters();
            Rc::new([
                kid(a, [u0, um, v0, vm], [a0, am, b0, bm]),
                kid(b, [u0, um, vm, v1], [a0, am, bm, b1]),
                kid(c, [um, u1, v0, vm], [am, a1, b0, bm]),
                kid(d, [um, u1, vm, v1], [am, a1, bm, b1]),
            ])
        };
        if kept.get() < CACHED_CELLS {
            kept.set(kept.get() + k.len() * self.patch.x.len());
            let _ = self.kids.set(k.clone());
        }
        k
    }
    pub(super) fn diag(&self) -> f64 {
        self.hull.as_ref().map_or(f64::INFINITY, diagonal)
    }
}

fn outward(lo: &Q, hi: &Q) -> (f64, f64) {
    let (mut a, mut b) = (Scalar::to_f64(lo), Scalar::to_f64(hi));
    if lift::<Q>(a) > *lo {
        a = a.next_down();
    }
    if lift::<Q>(b) < *hi {
        b = b.next_up();
    }
    (a, b)
}

/// Interval enclosure of a rational, outward.
fn enclose(x: &Q) -> Interval {
    let (lo, hi) = outward(x, x);
    Interval { lo, hi }
}

/// The Bézier pieces of a face pair, extracted once, on first use, and shared by the pair's
/// steps — the disjointness test, the whole-surface cone test and the coverage refinement —
/// with the quarters, normal-cone generators and crossing pieces each [`Cell`] caches. Every
/// step reads the same enclosures the separate extractions gave, so its decisions are those
/// it made on its own extraction; only the work is shared. At most [`CACHED_CELLS`] control points of cells are
/// kept over all the steps together.
pub(crate) struct PairPieces<'s> {
    sa: &'s NurbsSurface<f64, 3>,
    sb: &'s NurbsSurface<f64, 3>,
    a: OnceCell<Vec<Rc<Cell>>>,
    b: OnceCell<Vec<Rc<Cell>>>,
    kept: std::cell::Cell<usize>,
    halves_kept: std::cell::Cell<usize>,
}

impl<'s> PairPieces<'s> {
    pub(crate) fn new(sa: &'s NurbsSurface<f64, 3>, sb: &'s NurbsSurface<f64, 3>) -> Self {
        PairPieces {
            sa,
            sb,
            a: OnceCell::new(),
            b: OnceCell::new(),
            kept: std::cell::Cell::new(0),
            halves_kept: std::cell::Cell::new(0),
        }
    }
    /// The surfaces, A and B.
    pub(crate) fn surfaces(&self) -> (&'s NurbsSurface<f64, 3>, &'s NurbsSurface<f64, 3>) {
        (self.sa, self.sb)
    }
    /// The pieces of A ([`roots`]).
    pub(crate) fn a(&self) -> &[Rc<Cell>] {
        self.a.get_or_init(|| roots(self.sa))
    }
    /// The pieces of B ([`roots`]).
    pub(crate) fn b(&self) -> &[Rc<Cell>] {
        self.b.get_or_init(|| roots(self.sb))
    }
    /// The count of cells whose children are kept, over every step of the pair.
    pub(crate) fn kept(&self) -> &std::cell::Cell<usize> {
        &self.kept
    }
    /// The count of border-search pieces' halves kept, over every step of the pair
    /// (`crossings::CACHED_HALVES`).
    pub(crate) fn halves_kept(&self) -> &std::cell::Cell<usize> {
        &self.halves_kept
    }
}

/// The Bézier pieces of a surface, enclosed: the interval de Boor–Ramshaw extraction
/// ([`enclosed_bezier_patches`]: every enclosure contains the exact control point), or, where
/// a knot difference cannot be certified positive in intervals, the exact rational extraction
/// ([`roots_exact`]).
pub(crate) fn roots(s: &NurbsSurface<f64, 3>) -> Vec<Rc<Cell>> {
    let polynomial = s.is_polynomial();
    match enclosed_bezier_patches(s) {
        Some(pieces) => pieces
            .into_iter()
            .map(|bp| {
                let patch = IPatch {
                    p: bp.p,
                    q: bp.q,
                    x: bp.net.iter().map(|h| [h[0], h[1], h[2]]).collect(),
                    w: bp.net.iter().map(|h| h[3]).collect(),
                };
                Cell::new(patch, bp.uv, polynomial)
            })
            .collect(),
        None => roots_exact(s),
    }
}

/// The Bézier pieces of a surface, extracted exactly (rational knot insertion) and enclosed.
pub(crate) fn roots_exact(s: &NurbsSurface<f64, 3>) -> Vec<Rc<Cell>> {
    let exact = s.hom.map(
        |k| lift::<Q>(*k),
        |h| Hom {
            wp: lift_point(&h.wp),
            w: lift(h.w),
        },
    );
    let polynomial = s.is_polynomial();
    exact
        .bezier_patches()
        .into_iter()
        .map(|bp| {
            let patch = IPatch {
                p: bp.patch.p,
                q: bp.patch.q,
                x: bp
                    .patch
                    .net
                    .iter()
                    .map(|h| std::array::from_fn(|c| enclose(&h.wp[c])))
                    .collect(),
                w: bp.patch.net.iter().map(|h| enclose(&h.w)).collect(),
            };
            let uv = [
                Scalar::to_f64(&bp.u0),
                Scalar::to_f64(&bp.u1),
                Scalar::to_f64(&bp.v0),
                Scalar::to_f64(&bp.v1),
            ];
            Cell::new(patch, uv, polynomial)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A bilinear patch with corners `c` (in the order (0,0), (0,1), (1,0), (1,1)).
    fn bilinear(c: [[f64; 3]; 4]) -> Rc<Cell> {
        let patch = IPatch {
            p: 1,
            q: 1,
            x: c.iter().map(|p| p.map(Interval::point)).collect(),
            w: vec![Interval::point(1.0); 4],
        };
        Cell::new(patch, [0.0, 1.0, 0.0, 1.0], true)
    }

    /// The bilinear point at `(u, v)` of corners `c`, evaluated the direct way.
    fn at(c: &[[f64; 3]; 4], u: f64, v: f64) -> [f64; 3] {
        std::array::from_fn(|k| {
            (1.0 - u) * ((1.0 - v) * c[0][k] + v * c[1][k])
                + u * ((1.0 - v) * c[2][k] + v * c[3][k])
        })
    }

    /// A piece ten times longer along u than along v is halved across u, one twice as long
    /// along v as along u quartered, one ten times longer along v halved across v; each
    /// child's corners are the parent's points at the corners of the child's label.
    #[test]
    fn children_partition_their_parent_and_carry_its_points() {
        let cases: [([[f64; 3]; 4], usize); 3] = [
            (
                [
                    [0.0, 0.0, 0.0],
                    [0.0, 1.0, 0.0],
                    [10.0, 0.0, 0.0],
                    [10.0, 1.0, 1.0],
                ],
                2,
            ),
            (
                [
                    [0.0, 0.0, 0.0],
                    [0.0, 2.0, 0.0],
                    [1.0, 0.0, 0.0],
                    [1.0, 2.0, 1.0],
                ],
                4,
            ),
            (
                [
                    [0.0, 0.0, 0.0],
                    [0.0, 10.0, 0.0],
                    [1.0, 0.0, 0.0],
                    [1.0, 10.0, 1.0],
                ],
                2,
            ),
        ];
        for (c, n) in cases {
            let kept = std::cell::Cell::new(0);
            let kids = bilinear(c).kids(&kept);
            assert_eq!(kids.len(), n, "{c:?}");
            // The labels tile [0, 1]²: areas sum to 1 and no two overlap in their interiors.
            let area: f64 = kids
                .iter()
                .map(|k| (k.uv[1] - k.uv[0]) * (k.uv[3] - k.uv[2]))
                .sum();
            assert_eq!(area, 1.0);
            for (i, a) in kids.iter().enumerate() {
                for b in &kids[i + 1..] {
                    let apart = a.uv[1] <= b.uv[0]
                        || b.uv[1] <= a.uv[0]
                        || a.uv[3] <= b.uv[2]
                        || b.uv[3] <= a.uv[2];
                    assert!(apart, "{:?} {:?}", a.uv, b.uv);
                }
                let [u0, u1, v0, v1] = a.uv;
                for (i, j, u, v) in [
                    (0, 0, u0, v0),
                    (0, 1, u0, v1),
                    (1, 0, u1, v0),
                    (1, 1, u1, v1),
                ] {
                    let want = at(&c, u, v);
                    let got = a.patch.x[a.patch.at(i, j)];
                    for k in 0..3 {
                        assert!(got[k].lo <= want[k] && want[k] <= got[k].hi, "{:?}", a.uv);
                    }
                }
            }
        }
    }
}
