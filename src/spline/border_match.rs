//! Two surfaces whose borders are one curve: a border of `S_A` and a border of `S_B` that
//! are, piece by piece, the same rational Bézier curves up to a proven gap.
//!
//! Each border is the NURBS curve of its border row of the control net
//! ([`super::sides::borders`]: clamped knots, The NURBS Book eq. (2.5)), split into its Bézier
//! pieces by knot insertion in exact rational arithmetic ([`crate::scalar::Rational`]), the
//! border of lower degree first raised to the other's degree (exact degree elevation,
//! [`super::elevate::elevate_curve_to`]: the same curve, with the same parametrization). The
//! borders *match* when they have as many pieces, and piece `i` of A's border corresponds to
//! piece `j(i)` of B's — in order, or in reverse order with each piece reversed, and for a
//! closed border (first point equal to the last, exactly) also with the pieces rotated — such
//! that every corresponding pair has
//!
//! * the same degree and proportional weights: `w^B_k · w^A_0 = w^A_k · w^B_0` for every
//!   control point `k` (exactly), all weights positive;
//! * Cartesian control points `P^A_k`, `P^B_k` no farther apart than `g` (exact rational
//!   distances, the bound `g` rounded upward).
//!
//! **Lemma.** Then for every `λ ∈ [0, 1]` the pieces' points satisfy
//! `|C_A(λ) − C_B(λ)| ≤ g`. Proof: with `w^B_k = c w^A_k` (`c > 0`),
//! `C_A(λ) − C_B(λ) = Σ_k β_k (P^A_k − P^B_k)` where `β_k = B_k(λ) w^A_k / Σ_j B_j(λ) w^A_j`
//! are non-negative and sum to one (Bernstein polynomials, positive weights), a convex
//! combination of vectors each no longer than `g`. ∎
//!
//! So every point of A's border lies within `g` of B's border at the corresponding parameter
//! (affine on each piece, [`BorderMatch::map`]), and with `g = 0` (`exact`) the two borders
//! are one curve, every point of which lies on both surfaces. Borders that are the same point
//! set under another parametrization (pieces cut at other parameters, weights not
//! proportional) are not matched: this is a sufficient test, not a decision.

use super::NurbsSurface;
use super::nurbs::NurbsCurve;
use super::sides::{Border, borders};
use crate::geom::{Hom, lift_point};
use crate::scalar::{Rational, Scalar, lift};

/// A border of A matched with a border of B (see the module comment).
#[derive(Clone, Debug, PartialEq)]
pub struct BorderMatch {
    pub a: Border,
    pub b: Border,
    /// B's border runs the other way.
    pub reversed: bool,
    /// Per piece of A's border, in order: `[t0, t1, s0, s1]`, the piece's parameter range on
    /// A's border and the corresponding range on B's (`s0 > s1` where it runs the other way).
    pub pieces: Vec<[f64; 4]>,
    /// Proven upper bound on `|C_A(t) − C_B(s(t))|` over the whole border.
    pub gap: f64,
    /// The borders are one curve exactly (`gap` 0).
    pub exact: bool,
}

impl BorderMatch {
    /// The parameter on B's border corresponding to `t` on A's (affine on each piece; `f64`).
    pub fn map(&self, t: f64) -> f64 {
        let k = self
            .pieces
            .iter()
            .position(|p| t <= p[1])
            .unwrap_or(self.pieces.len().saturating_sub(1));
        let Some([t0, t1, s0, s1]) = self.pieces.get(k).copied() else {
            return t;
        };
        if t1 <= t0 {
            return s0;
        }
        let l = ((t - t0) / (t1 - t0)).clamp(0.0, 1.0);
        s0 + (s1 - s0) * l
    }
}

/// A Bézier piece of a border: its parameter range and exact homogeneous control points.
struct Piece {
    t0: f64,
    t1: f64,
    ctrl: Vec<Hom<Rational, 3>>,
}

/// The Bézier pieces of `c` raised to degree `degree` (when lower), exactly.
fn exact_pieces(c: &NurbsCurve<f64, 3>, degree: usize) -> Option<Vec<Piece>> {
    let r = c.hom.map(
        |k| lift::<Rational>(*k),
        |h| Hom {
            wp: lift_point::<Rational, 3>(&h.wp),
            w: lift(h.w),
        },
    );
    let r = super::elevate::elevate_curve_to(&r, degree);
    let out: Vec<Piece> = r
        .bezier_pieces()
        .into_iter()
        .map(|p| Piece {
            // Breakpoints are knots of the f64 curve: exact in f64.
            t0: Scalar::to_f64(&p.t0),
            t1: Scalar::to_f64(&p.t1),
            ctrl: p.curve.control,
        })
        .collect();
    let positive = out.iter().all(|p| {
        p.ctrl
            .iter()
            .all(|h| Scalar::sign(&h.w) == crate::scalar::Sign::Positive)
    });
    positive.then_some(out)
}

fn cartesian(h: &Hom<Rational, 3>) -> [Rational; 3] {
    std::array::from_fn(|i| h.wp[i].clone() / h.w.clone())
}

/// Squared gap of two pieces with `b` reversed or not; `None` when degrees differ or weights
/// are not proportional.
fn piece_gap2(a: &Piece, b: &Piece, reversed: bool) -> Option<Rational> {
    let n = a.ctrl.len();
    if b.ctrl.len() != n {
        return None;
    }
    let bk = |k: usize| &b.ctrl[if reversed { n - 1 - k } else { k }];
    let (wa0, wb0) = (&a.ctrl[0].w, &bk(0).w);
    let mut worst = Rational::zero();
    for k in 0..n {
        if bk(k).w.clone() * wa0.clone() != a.ctrl[k].w.clone() * wb0.clone() {
            return None;
        }
        let (pa, pb) = (cartesian(&a.ctrl[k]), cartesian(bk(k)));
        let d2 = (0..3)
            .map(|i| {
                let d = pa[i].clone() - pb[i].clone();
                d.clone() * d
            })
            .fold(Rational::zero(), |s, x| s + x);
        if d2 > worst {
            worst = d2;
        }
    }
    Some(worst)
}

/// The first and last point of a border, exactly equal (a closed border).
fn closed(p: &[Piece]) -> bool {
    match (p.first(), p.last()) {
        (Some(f), Some(l)) => match (f.ctrl.first(), l.ctrl.last()) {
            (Some(x), Some(y)) => cartesian(x) == cartesian(y),
            _ => false,
        },
        _ => false,
    }
}

/// The best correspondence of A's pieces with B's within `tol` (see the module comment).
fn match_pieces(pa: &[Piece], pb: &[Piece], tol: f64) -> Option<(bool, Vec<[f64; 4]>, Rational)> {
    let n = pa.len();
    if n == 0 || pb.len() != n {
        return None;
    }
    let rotations = if closed(pa) && closed(pb) { n } else { 1 };
    let tol2: Rational = lift::<Rational>(tol) * lift::<Rational>(tol);
    let mut best: Option<(bool, Vec<[f64; 4]>, Rational)> = None;
    for reversed in [false, true] {
        'rot: for r in 0..rotations {
            let mut worst = Rational::zero();
            let mut map = Vec::with_capacity(n);
            for (i, a) in pa.iter().enumerate() {
                let j = if reversed {
                    (r + n - 1 - i) % n
                } else {
                    (r + i) % n
                };
                let b = &pb[j];
                let Some(g2) = piece_gap2(a, b, reversed) else {
                    continue 'rot;
                };
                if g2 > tol2 {
                    continue 'rot;
                }
                if g2 > worst {
                    worst = g2;
                }
                let (s0, s1) = if reversed { (b.t1, b.t0) } else { (b.t0, b.t1) };
                map.push([a.t0, a.t1, s0, s1]);
            }
            if best.as_ref().is_none_or(|(_, _, g)| worst < *g) {
                best = Some((reversed, map, worst));
            }
        }
    }
    best
}

/// Cheap necessary test in `f64`: the boxes of the curves' points at their breakpoints (the
/// pieces' end points, which matched pieces hold within the gap) agree within `tol` plus a
/// rounding allowance, and the borders are not single points (poles).
fn may_match(a: &NurbsCurve<f64, 3>, b: &NurbsCurve<f64, 3>, tol: f64) -> bool {
    let boxed = |c: &NurbsCurve<f64, 3>| {
        let br = c.hom.knots.breakpoints();
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for t in &br {
            let p = c.eval(t);
            for k in 0..3 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        (br.len(), lo, hi)
    };
    let ((na, la, ha), (nb, lb, hb)) = (boxed(a), boxed(b));
    let size = (0..3).map(|k| ha[k] - la[k]).fold(0.0f64, f64::max);
    let slack = tol + 1e-9 * (size + la.iter().chain(&ha).fold(0.0f64, |m, x| m.max(x.abs())));
    let degenerate = size <= tol;
    na == nb
        && !degenerate
        && size.is_finite()
        && (0..3).all(|k| (la[k] - lb[k]).abs() <= slack && (ha[k] - hb[k]).abs() <= slack)
}

/// Every border of `sa` matched with a border of `sb` within `tol` (see the module comment),
/// the smallest gap for each border of A.
pub fn common_borders(
    sa: &NurbsSurface<f64, 3>,
    sb: &NurbsSurface<f64, 3>,
    tol: f64,
) -> Vec<BorderMatch> {
    let (Some(ba), Some(bb)) = (borders(sa), borders(sb)) else {
        return Vec::new();
    };
    let mut out = Vec::new();
    for (a, ca) in &ba {
        let mut best: Option<BorderMatch> = None;
        // A's pieces per degree they are raised to.
        let mut pa_at: Vec<(usize, Option<Vec<Piece>>)> = Vec::new();
        for (b, cb) in &bb {
            if !may_match(ca, cb, tol) {
                continue;
            }
            let d = ca.hom.degree().max(cb.hom.degree());
            let k = match pa_at.iter().position(|(e, _)| *e == d) {
                Some(k) => k,
                None => {
                    pa_at.push((d, exact_pieces(ca, d)));
                    pa_at.len() - 1
                }
            };
            let Some(pa) = pa_at[k].1.as_ref() else {
                break;
            };
            let Some(pb) = exact_pieces(cb, d) else {
                continue;
            };
            if let Some((reversed, pieces, g2)) = match_pieces(pa, &pb, tol) {
                let gap = crate::scalar::sqrt_upper(&g2);
                if best.as_ref().is_none_or(|m| gap < m.gap) {
                    best = Some(BorderMatch {
                        a: *a,
                        b: *b,
                        reversed,
                        pieces,
                        gap,
                        exact: g2.is_zero(),
                    });
                }
            }
        }
        out.extend(best);
    }
    out
}

#[cfg(test)]
mod tests;
