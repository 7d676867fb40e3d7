//! Least-squares B-spline fitting on a given knot vector, with interpolated end points
//! (The NURBS Book §9.4.1, eqs. 9.63–9.67, with the knots supplied by the caller instead of
//! eq. 9.69): minimize `Σ |Q_k - C(t_k)|²` over the interior control points.

use super::SplineError;
use super::basis::basis_funs;
use super::bspline_curve::BSplineCurve;
use super::knots::KnotVector;
use crate::geom::Point;
use crate::scalar::Scalar;

/// Fit `data` at parameters `t` (increasing, inside the knots' domain) with the spline space
/// of `kv`; the first and last control points are the first and last data points. Errors when
/// the data are too few, the parameters not increasing, or the normal equations singular
/// (a basis function without data in its support).
pub fn fit_with_knots<P: Point>(
    data: &[P],
    t: &[P::S],
    kv: &KnotVector<P::S>,
) -> Result<BSplineCurve<P>, SplineError> {
    fit_rational_with_knots(data, t, kv, None)
}

/// As [`fit_with_knots`] for a rational curve with the given `weights` (one per control
/// point): the basis is `R_i = w_i N_i / Σ w_j N_j`, still linear in the control points.
/// The result's control points are Cartesian; with `weights` it represents
/// `Σ w_i N_i P_i / Σ w_i N_i`.
pub fn fit_rational_with_knots<P: Point>(
    data: &[P],
    t: &[P::S],
    kv: &KnotVector<P::S>,
    weights: Option<&[P::S]>,
) -> Result<BSplineCurve<P>, SplineError> {
    let m = data.len();
    let n_ctrl = kv.n_ctrl();
    let p = kv.degree();
    if weights.is_some_and(|w| w.len() != n_ctrl) {
        return Err(SplineError::NetSize {
            got: weights.map_or(0, |w| w.len()),
            expected: n_ctrl,
            what: "one weight per control point",
        });
    }
    if m < n_ctrl || t.len() != m || m < 2 {
        return Err(SplineError::TooFewPoints {
            need: n_ctrl.max(2),
            got: m,
        });
    }
    for i in 1..m {
        if t[i] <= t[i - 1] {
            return Err(SplineError::Parameters(i));
        }
    }
    let (q0, qm) = (data[0].clone(), data[m - 1].clone());
    if n_ctrl == 2 {
        return Ok(BSplineCurve {
            knots: kv.clone(),
            control: vec![q0, qm],
        });
    }
    let rows: Vec<Vec<P::S>> = t[1..m - 1]
        .iter()
        .map(|tk| {
            let mut row = vec![P::S::zero(); n_ctrl];
            let span = kv.find_span(tk);
            for (j, nj) in basis_funs(kv, span, tk).into_iter().enumerate() {
                row[span - p + j] = nj;
            }
            if let Some(w) = weights {
                let mut sum = P::S::zero();
                for (r, wi) in row.iter_mut().zip(w) {
                    *r = r.clone() * wi.clone();
                    sum = sum + r.clone();
                }
                for r in row.iter_mut() {
                    *r = r.clone() / sum.clone();
                }
            }
            row
        })
        .collect();
    let control = super::fit::solve_fixed_ends(&rows, data)?;
    Ok(BSplineCurve {
        knots: kv.clone(),
        control,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reproduces_a_spline_of_its_space() {
        let kv =
            KnotVector::new(vec![0., 0., 0., 0., 0.3, 0.55, 0.55, 1., 1., 1., 1.], 3, 7).unwrap();
        let truth = BSplineCurve {
            knots: kv.clone(),
            control: vec![
                [0.0, 0.0],
                [1.0, 2.0],
                [2.0, -1.0],
                [3.0, 0.5],
                [4.0, 4.0],
                [5.0, 1.0],
                [6.0, 0.0],
            ],
        };
        let t: Vec<f64> = (0..60).map(|i| i as f64 / 59.0).collect();
        let data: Vec<[f64; 2]> = t.iter().map(|x| truth.eval(x)).collect();
        let c = fit_with_knots(&data, &t, &kv).unwrap();
        for (a, b) in c.control.iter().zip(&truth.control) {
            assert!((a[0] - b[0]).abs() < 1e-9 && (a[1] - b[1]).abs() < 1e-9);
        }
    }
}
