//! Cubic B-spline interpolation of points (The NURBS Book §9.2.1, A9.1) with chord-length
//! or centripetal parameters (eq. 9.5, 9.6) and knots by averaging (eq. 9.8).

use super::bspline_curve::BSplineCurve;
use super::linalg::solve;
use super::{SplineError, basis::basis_funs, knots::KnotVector};
use crate::geom::Point;
use crate::scalar::{RealScalar, Scalar};

/// How interpolation parameters are chosen.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Parametrization {
    /// Proportional to chord lengths (eq. 9.5).
    ChordLength,
    /// Proportional to square roots of chord lengths (eq. 9.6, Lee 1989).
    Centripetal,
}

/// Parameters `0 = t_0 < … < t_n = 1` for the points; coincident consecutive points are an
/// error (they make the parameters repeat).
pub fn parameters<S: RealScalar, const D: usize>(
    pts: &[[S; D]],
    kind: Parametrization,
) -> Result<Vec<S>, SplineError> {
    if pts.len() < 2 {
        return Err(SplineError::TooFewPoints {
            need: 2,
            got: pts.len(),
        });
    }
    let mut d = Vec::with_capacity(pts.len() - 1);
    for (i, w) in pts.windows(2).enumerate() {
        let l = crate::geom::dist(&w[0], &w[1]);
        if l.is_zero() {
            return Err(SplineError::Parameters(i + 1));
        }
        d.push(match kind {
            Parametrization::ChordLength => l,
            Parametrization::Centripetal => l.sqrt(),
        });
    }
    let total = d.iter().fold(S::zero(), |a, b| a + b.clone());
    let mut t = vec![S::zero()];
    let mut acc = S::zero();
    for di in &d[..d.len() - 1] {
        acc = acc + di.clone();
        t.push(acc.clone() / total.clone());
    }
    t.push(S::one());
    Ok(t)
}

/// Knots by averaging (eq. 9.8) for degree `p` and parameters `t`.
pub fn averaged_knots<S: Scalar>(t: &[S], p: usize) -> Vec<S> {
    let n = t.len() - 1;
    let mut k = vec![S::zero(); p + 1];
    for j in 1..=n.saturating_sub(p) {
        let mut s = S::zero();
        for tt in &t[j..j + p] {
            s = s + tt.clone();
        }
        k.push(s / S::from_i64(p as i64));
    }
    k.extend(std::iter::repeat_n(S::one(), p + 1));
    k
}

/// The degree-`p` B-spline through `pts` at parameters `t` (strictly increasing from 0 to
/// 1), knots by averaging. Generic: exact on exact backends.
pub fn interpolate_with_parameters<P: Point>(
    pts: &[P],
    t: &[P::S],
    p: usize,
) -> Result<BSplineCurve<P>, SplineError> {
    let n = pts.len();
    if n < p + 1 {
        return Err(SplineError::TooFewPoints {
            need: p + 1,
            got: n,
        });
    }
    if t.len() != n {
        return Err(SplineError::TooFewPoints {
            need: n,
            got: t.len(),
        });
    }
    for i in 1..n {
        if t[i] <= t[i - 1] {
            return Err(SplineError::Parameters(i));
        }
    }
    let kv = KnotVector::new(averaged_knots(t, p), p, n)?;
    let mut a = vec![vec![P::S::zero(); n]; n];
    for (r, tr) in t.iter().enumerate() {
        let span = kv.find_span(tr);
        for (j, nj) in basis_funs(&kv, span, tr).into_iter().enumerate() {
            a[r][span - p + j] = nj;
        }
    }
    let ctrl = solve(a, pts.to_vec())?;
    Ok(BSplineCurve {
        knots: kv,
        control: ctrl,
    })
}

/// Cubic interpolation with chord-length or centripetal parameters.
pub fn interpolate_cubic<S: RealScalar, const D: usize>(
    pts: &[[S; D]],
    kind: Parametrization,
) -> Result<BSplineCurve<[S; D]>, SplineError> {
    let t = parameters(pts, kind)?;
    let p = 3.min(pts.len() - 1);
    interpolate_with_parameters(pts, &t, p)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::Rational;
    type Q = Rational;

    #[test]
    fn interpolates_exactly_in_rationals() {
        let pts: Vec<[Q; 2]> = [[0., 0.], [1., 2.], [3., 3.], [4., 1.], [6., 0.5], [7., 2.]]
            .iter()
            .map(crate::geom::lift_point)
            .collect();
        let t: Vec<Q> = [0., 0.1, 0.35, 0.5, 0.8, 1.]
            .iter()
            .map(|&x| crate::scalar::lift(x))
            .collect();
        let c = interpolate_with_parameters(&pts, &t, 3).unwrap();
        for (p, ti) in pts.iter().zip(&t) {
            assert_eq!(&c.eval(ti), p);
        }
    }

    #[test]
    fn chord_and_centripetal_interpolate_in_f64() {
        let pts = [
            [0., 0., 0.],
            [1., 2., 0.],
            [3., 3., 1.],
            [4., 1., 1.],
            [6., 0.5, 2.],
        ];
        for kind in [Parametrization::ChordLength, Parametrization::Centripetal] {
            let t = parameters(&pts, kind).unwrap();
            let c = interpolate_cubic(&pts, kind).unwrap();
            for (p, ti) in pts.iter().zip(&t) {
                let e = c.eval(ti);
                for k in 0..3 {
                    assert!((e[k] - p[k]).abs() < 1e-12);
                }
            }
        }
        assert!(matches!(
            parameters(&[[0., 0.], [0., 0.]], Parametrization::ChordLength),
            Err(SplineError::Parameters(1))
        ));
    }
}
