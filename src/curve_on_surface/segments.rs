//! The domain polyline under construction: segments of exact domain-curve pieces with their
//! chords, and the exact split operation every step uses.

use super::cells::Cells;
use crate::geom::{Point, lift_point};
use crate::scalar::{Rational, Scalar, ratio};
use crate::spline::BezierCurve;

type Q = Rational;

/// A piece of the domain curve, `pieces[piece]` restricted to local `[t0, t1]`, with its
/// chord `a → b` (f64) in cell `cell`. `ea`/`eb`: proven distance from `a`/`b` to the curve
/// point they stand for (rounding and snapping).
#[derive(Clone, Debug)]
pub struct Seg {
    pub piece: usize,
    pub t0: Q,
    pub t1: Q,
    pub a: [f64; 2],
    pub b: [f64; 2],
    pub ea: f64,
    pub eb: f64,
    pub cell: usize,
    /// Certified 2D Hausdorff bound to the curve piece (`INFINITY` until computed).
    pub h: f64,
    /// Certified Lipschitz constant of S on a region holding the piece and its chord.
    pub k: f64,
}

/// Exact distance bound (rounded up) between an f64 point and an exact point.
pub fn offset(v: &[f64; 2], exact: &[Q; 2]) -> f64 {
    let d = lift_point::<Q, 2>(v).sub(exact);
    super::tolerance::sqrt_up(&crate::geom::norm2(&d))
}

/// Round an exact point to f64.
pub fn round(p: &[Q; 2]) -> [f64; 2] {
    [Scalar::to_f64(&p[0]), Scalar::to_f64(&p[1])]
}

impl Seg {
    /// The exact sub-curve of this segment (reparametrized to `[0, 1]`).
    pub fn curve(&self, pieces: &[BezierCurve<[Q; 2]>]) -> BezierCurve<[Q; 2]> {
        pieces[self.piece].segment(&self.t0, &self.t1)
    }

    /// Split at local parameter `s ∈ (0, 1)` of this segment: the new vertex is the exact
    /// curve point rounded to f64 and kept inside the segment's cell.
    pub fn split(&self, s: &Q, pieces: &[BezierCurve<[Q; 2]>], cells: &Cells) -> (Seg, Seg) {
        // The split location is a choice, not a claim: take the nearest k/256 of the
        // segment (1 <= k <= 255), which keeps the exact parameters short.
        let k = (Scalar::to_f64(s) * 256.0).round().clamp(1.0, 255.0) as i64;
        let s = ratio(k, 256);
        let t = self.t0.clone() + (self.t1.clone() - self.t0.clone()) * s;
        let exact = pieces[self.piece].eval(&t);
        let v = cells.clamp(self.cell, &round(&exact));
        let e = offset(&v, &exact);
        let left = Seg {
            t1: t.clone(),
            b: v,
            eb: e,
            h: f64::INFINITY,
            k: f64::INFINITY,
            ..self.clone()
        };
        let right = Seg {
            t0: t,
            a: v,
            ea: e,
            h: f64::INFINITY,
            k: f64::INFINITY,
            ..self.clone()
        };
        (left, right)
    }
}
