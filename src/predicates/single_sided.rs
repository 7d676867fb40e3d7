//! The single-sided test of a planar Bézier curve against its chord (Yang et al. §3).
//!
//! A curve `C(t) = Σ P_i B_i^n(t)` is *single-sided* when it stays in one closed half-plane
//! of the line through `P_0` and `P_n`. With `f(t) = (C(t) - P_0) × (P_n - P_0)` — a
//! polynomial of degree `n` whose Bernstein coefficients are
//! `b_i = (P_i - P_0) × (P_n - P_0) = -orient2d(P_0, P_n, P_i)` — the curve is single-sided
//! iff `f` does not change sign on `(0, 1)`. Decided exactly, never with a tolerance:
//! 1. all `b_i` on one closed side (signs by the exact `orient2d`) ⇒ single-sided
//!    (Bernstein polynomials are non-negative on `[0,1]`);
//! 2. otherwise the coefficients are formed exactly in `BigRational` and `f` is tested for a
//!    root of odd multiplicity in `(0, 1)`: Yun's square-free decomposition, then Sturm's
//!    theorem on the odd-multiplicity part.
//!
//! The odd-multiplicity roots are also where a double-sided piece must be split (the paper's
//! `t_1` for cubics generalizes to all of them); [`split_parameters`] isolates them.

use super::poly::{Poly, count_roots, descartes_isolate, integer_bernstein, isolate_roots};
use crate::geom::Point;
use crate::scalar::{Scalar, Sign};
use num_rational::BigRational;
use num_traits::{One, Zero};

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

/// Bisection depth of the Descartes fast path before falling back to Sturm sequences.
const DESCARTES_DEPTH: u32 = 64;

/// Exact Bernstein coefficients of `f(t) = (C(t) - P_0) × (P_n - P_0)`.
pub fn chord_cross_coefficients<S: Scalar>(ctrl: &[[S; 2]]) -> Vec<BigRational> {
    let q: Vec<[BigRational; 2]> = ctrl
        .iter()
        .map(|p| [p[0].to_big_rational(), p[1].to_big_rational()])
        .collect();
    let n = q.len() - 1;
    let chord = q[n].sub(&q[0]);
    q.iter()
        .map(|p| crate::geom::cross2(&p.sub(&q[0]), &chord))
        .collect()
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
    // Step 2a: exact Bernstein–Descartes bisection (integer arithmetic): decides every
    // case whose roots in (0,1) are simple and off the dyadic bisection points.
    let b = chord_cross_coefficients(ctrl);
    if let Some(roots) = descartes_isolate(&integer_bernstein(&b), DESCARTES_DEPTH) {
        return if roots.is_empty() {
            Sidedness::SingleSided {
                decided_by_hull: false,
            }
        } else {
            Sidedness::DoubleSided {
                crossings: roots.len(),
            }
        };
    }
    // Step 2b: multiple roots or a root on a bisection point: square-free odd part + Sturm.
    let odd = odd_crossing_polynomial(ctrl);
    let k = count_roots(
        &odd,
        &<BigRational as Zero>::zero(),
        &<BigRational as One>::one(),
    );
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
        return Poly::new(vec![<BigRational as One>::one()]);
    }
    f.odd_multiplicity_part()
}

/// The parameters in `(0, 1)` at which the curve crosses its chord (odd-multiplicity roots
/// of `f`), each isolated in an exact rational interval of width ≤ `width`, ascending.
/// Splitting there leaves pieces that are single-sided (the paper's `t_1` for cubics).
pub fn split_parameters<S: Scalar>(ctrl: &[[S; 2]], width: f64) -> Vec<(BigRational, BigRational)> {
    let n = ctrl.len() - 1;
    if ctrl[0] == ctrl[n] {
        return vec![];
    }
    let w = BigRational::from_float(width.abs().max(f64::MIN_POSITIVE))
        .unwrap_or_else(<BigRational as One>::one);
    isolate_roots(
        &odd_crossing_polynomial(ctrl),
        &<BigRational as Zero>::zero(),
        &<BigRational as One>::one(),
        &w,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn classic_cases() {
        // Arc: single-sided by the hull.
        let arc = [[0., 0.], [0.3, 1.], [0.7, 1.], [1., 0.]];
        assert_eq!(
            single_sided(&arc),
            Sidedness::SingleSided {
                decided_by_hull: true
            }
        );
        // S-curve: double-sided, one crossing.
        let s = [[0., 0.], [0.3, 1.], [0.7, -1.], [1., 0.]];
        assert_eq!(single_sided(&s), Sidedness::DoubleSided { crossings: 1 });
        let roots = split_parameters(&s, 1e-9);
        assert_eq!(roots.len(), 1);
        // Symmetric S: crossing exactly at t = 1/2.
        assert!(roots[0].0 <= BigRational::new(1.into(), 2.into()));
        assert!(roots[0].1 >= BigRational::new(1.into(), 2.into()));
        // Mixed coefficient signs, but the curve only touches its chord (double root at
        // 1/2): f = 48 t(1-t)(t-1/2)^2 has Bernstein coefficients (0, 3, -4, 3, 0), and with
        // P0=(0,0), P4=(1,0), b_i = -y_i.
        let q = [[0., 0.], [0.25, -3.], [0.5, 4.], [0.75, -3.], [1., 0.]];
        assert_eq!(
            single_sided(&q),
            Sidedness::SingleSided {
                decided_by_hull: false
            }
        );
        assert_eq!(
            single_sided(&[[0., 0.], [1., 1.], [0., 0.]]),
            Sidedness::DegenerateChord
        );
    }
}
