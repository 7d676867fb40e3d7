//! The single-sided test of a planar Bézier curve against its chord (Yang et al. §3).
//!
//! A curve `C(t) = Σ P_i B_i^n(t)` is *single-sided* when it stays in one closed half-plane
//! of the line through `P_0` and `P_n`. With `f(t) = (C(t) - P_0) × (P_n - P_0)` — a
//! polynomial of degree `n` whose Bernstein coefficients are
//! `b_i = (P_i - P_0) × (P_n - P_0) = -orient2d(P_0, P_n, P_i)` — the curve is single-sided
//! iff `f` does not change sign on `(0, 1)`. Decided exactly, never with a tolerance:
//! 1. all `b_i` on one closed side (signs by the exact `orient2d`) ⇒ single-sided
//!    (Bernstein polynomials are non-negative on `[0,1]`);
//! 2. otherwise the coefficients are formed exactly in `Rational` and `f` is tested for a
//!    root of odd multiplicity in `(0, 1)`: Yun's square-free decomposition, then Sturm's
//!    theorem on the odd-multiplicity part.
//!
//! The odd-multiplicity roots are also where a double-sided piece must be split (the paper's
//! `t_1` for cubics generalizes to all of them); [`split_parameters`] isolates them.

use super::poly::{
    Poly, certify_squarefree, deflate_ends, descartes_isolate, integer_bernstein,
    integer_power_from_bernstein, isolate_roots,
};
use crate::geom::Point;
use crate::scalar::{Rational, Scalar, Sign, pow2};
use dashu_int::ops::BitTest;

/// Outcome of the single-sided test.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
pub enum Sidedness {
    /// The curve stays in one closed half-plane of its chord; `decided_by_hull` says whether
    /// the control-point signs sufficed (step 1) or the exact root analysis was needed.
    SingleSided { decided_by_hull: bool },
    /// The curve crosses its chord inside `(0, 1)` at `crossings` distinct parameters.
    DoubleSided { crossings: usize },
    /// `P_0 == P_n`: there is no chord (closed piece); the caller must split first.
    DegenerateChord,
}

impl std::fmt::Display for Sidedness {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Sidedness::SingleSided {
                decided_by_hull: true,
            } => f.write_str("single-sided (decided by the control points' signs)"),
            Sidedness::SingleSided {
                decided_by_hull: false,
            } => f.write_str("single-sided (decided by the exact root analysis)"),
            Sidedness::DoubleSided { crossings } => {
                write!(f, "double-sided ({crossings} crossings of the chord)")
            }
            Sidedness::DegenerateChord => f.write_str("no chord (closed piece)"),
        }
    }
}

/// Exact Bernstein coefficients of `f(t) = (C(t) - P_0) × (P_n - P_0)`.
pub fn chord_cross_coefficients<S: Scalar>(ctrl: &[[S; 2]]) -> Vec<Rational> {
    let q: Vec<[Rational; 2]> = ctrl
        .iter()
        .map(|p| [p[0].to_rational(), p[1].to_rational()])
        .collect();
    let n = q.len() - 1;
    let chord = q[n].sub(&q[0]);
    q.iter()
        .map(|p| crate::geom::cross2(&p.sub(&q[0]), &chord))
        .collect()
}

/// Exact crossings of the curve with its chord in `(0, 1)`, isolated to width
/// `2^-min_depth`: the Descartes path when square-freeness is certified (fast, integer
/// arithmetic), otherwise Yun's square-free decomposition and Sturm sequences.
fn crossings<S: Scalar>(ctrl: &[[S; 2]], min_depth: u32) -> Vec<(Rational, Rational)> {
    let b = chord_cross_coefficients(ctrl);
    let ib = integer_bernstein(&b);
    let g = deflate_ends(integer_power_from_bernstein(&ib));
    if g.len() <= 1 {
        // Constant after removing the end roots (or identically zero: the curve lies on its
        // chord): no crossing inside.
        return vec![];
    }
    if certify_squarefree(&g) {
        let bits = ib.iter().map(|x| x.bit_len()).max().unwrap_or(0) as u32;
        let n = ib.len() as u32;
        // Generous cap above the root-separation depth of a square-free integer polynomial
        // (Mahler: about n·(bits + log n)); reached only if the certificate were wrong.
        let cap = 64 + n.saturating_mul(bits + 2 * n);
        if let Some(r) = descartes_isolate(&ib, cap, min_depth) {
            return r.into_iter().map(|x| (x.lo, x.hi)).collect();
        }
    }
    let odd = odd_crossing_polynomial(ctrl);
    let w = pow2(-i64::from(min_depth));
    isolate_roots(&odd, &Rational::ZERO, &Rational::ONE, &w)
}

/// Classify a planar Bézier curve (at least 2 control points) against its chord.
pub fn single_sided<S: Scalar>(ctrl: &[[S; 2]]) -> Sidedness {
    let n = ctrl.len() - 1;
    if ctrl[0] == ctrl[n] {
        return Sidedness::DegenerateChord;
    }
    // Step 1: exact signs of the Bernstein coefficients.
    let (mut pos, mut neg) = (false, false);
    for p in &ctrl[1..n] {
        match S::orient2d(&ctrl[0], &ctrl[n], p).flip() {
            Sign::Positive => pos = true,
            Sign::Negative => neg = true,
            Sign::Zero => {}
        }
    }
    if !(pos && neg) {
        return Sidedness::SingleSided {
            decided_by_hull: true,
        };
    }
    // Step 2: exact root analysis.
    let k = crossings(ctrl, 0).len();
    if k == 0 {
        Sidedness::SingleSided {
            decided_by_hull: false,
        }
    } else {
        Sidedness::DoubleSided { crossings: k }
    }
}

fn odd_crossing_polynomial<S: Scalar>(ctrl: &[[S; 2]]) -> Poly {
    let f = Poly::from_bernstein(&chord_cross_coefficients(ctrl));
    if f.is_zero() {
        return Poly::new(vec![Rational::ONE]);
    }
    f.odd_multiplicity_part()
}

/// The parameters in `(0, 1)` at which the curve crosses its chord (odd-multiplicity roots
/// of `f`), each isolated in an exact rational interval of width ≤ `width` (a point when
/// exact), ascending. Splitting there leaves pieces that are single-sided (the paper's `t_1`
/// for cubics).
pub fn split_parameters<S: Scalar>(ctrl: &[[S; 2]], width: f64) -> Vec<(Rational, Rational)> {
    let n = ctrl.len() - 1;
    if ctrl[0] == ctrl[n] {
        return vec![];
    }
    let w = width.abs().clamp(1e-300, 1.0);
    let depth = (-w.log2()).ceil().max(0.0) as u32;
    crossings(ctrl, depth)
}
