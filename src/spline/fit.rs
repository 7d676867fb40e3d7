//! Least-squares B-spline fitting with interpolated end points (The NURBS Book §9.4.1,
//! eqs. 9.63–9.67): minimize `Σ |Q_k - C(t_k)|²` over the free control points.

use super::SplineError;
use super::basis::basis_funs;
use super::bspline_curve::BSplineCurve;
use super::knots::KnotVector;
use super::linalg::solve;
use crate::geom::Point;
use crate::scalar::Scalar;

/// Knots for `n_ctrl` control points and parameters `t` (eq. 9.69, de Boor's placement).
pub fn fitting_knots<S: Scalar>(t: &[S], p: usize, n_ctrl: usize) -> Vec<S> {
    let m = t.len() - 1;
    let n = n_ctrl - 1;
    let mut k = vec![S::zero(); p + 1];
    let d = S::from_i64((m + 1) as i64) / S::from_i64((n - p + 1) as i64);
    for j in 1..=n - p {
        // i = floor(j d), alpha = j d - i, u_{p+j} = (1 - alpha) t_{i-1} + alpha t_i.
        let jd = S::from_i64(j as i64) * d.clone();
        let mut i = 0usize;
        while S::from_i64((i + 1) as i64) <= jd {
            i += 1;
        }
        let alpha = jd - S::from_i64(i as i64);
        let i = i.clamp(1, m);
        k.push((S::one() - alpha.clone()) * t[i - 1].clone() + alpha * t[i].clone());
    }
    k.extend(std::iter::repeat_n(S::one(), p + 1));
    k
}

/// The least-squares control points with the first and last fixed at the end data points:
/// `rows[k]` holds the basis values `N_0..N_n` at interior datum `k + 1`; with
/// `R_k = Q_k − N_0 Q_0 − N_n Q_m`, the normal equations `(NᵀN) P = Nᵀ R` give `P_1..P_{n−1}`.
pub(crate) fn solve_fixed_ends<P: Point>(
    rows: &[Vec<P::S>],
    data: &[P],
) -> Result<Vec<P>, SplineError> {
    let m = data.len();
    let n = rows.first().map_or(1, |r| r.len() - 1);
    let (q0, qm) = (data[0].clone(), data[m - 1].clone());
    let r: Vec<P> = rows
        .iter()
        .zip(&data[1..m - 1])
        .map(|(row, qk)| qk.sub(&q0.scale(&row[0])).sub(&qm.scale(&row[n])))
        .collect();
    let k = n - 1;
    let mut a = vec![vec![P::S::zero(); k]; k];
    let mut b = vec![P::origin(); k];
    for (row, rk) in rows.iter().zip(&r) {
        for i in 0..k {
            if row[i + 1].is_zero() {
                continue;
            }
            b[i] = b[i].add(&rk.scale(&row[i + 1]));
            for j in 0..k {
                a[i][j] = a[i][j].clone() + row[i + 1].clone() * row[j + 1].clone();
            }
        }
    }
    let inner = solve(a, b)?;
    let mut control = vec![q0];
    control.extend(inner);
    control.push(qm);
    Ok(control)
}

/// Degree-`p` least-squares fit with `n_ctrl` control points through the first and last
/// data point, at parameters `t` (increasing, from 0 to 1).
pub fn fit_least_squares<P: Point>(
    data: &[P],
    t: &[P::S],
    p: usize,
    n_ctrl: usize,
) -> Result<BSplineCurve<P>, SplineError> {
    let m = data.len();
    if n_ctrl < p + 1 || m < n_ctrl || t.len() != m {
        return Err(SplineError::TooFewPoints {
            need: n_ctrl.max(p + 1),
            got: m,
        });
    }
    for i in 1..m {
        if t[i] <= t[i - 1] {
            return Err(SplineError::Parameters(i));
        }
    }
    let kv = KnotVector::new(fitting_knots(t, p, n_ctrl), p, n_ctrl)?;
    let n = n_ctrl - 1;
    let (q0, qm) = (data[0].clone(), data[m - 1].clone());
    if n_ctrl == 2 || n == 1 {
        return Ok(BSplineCurve {
            knots: kv,
            control: vec![q0, qm],
        });
    }
    // N[k][i] for interior data k = 1..m-2 and all i.
    let rows: Vec<Vec<P::S>> = t[1..m - 1]
        .iter()
        .map(|tk| {
            let mut row = vec![P::S::zero(); n_ctrl];
            let span = kv.find_span(tk);
            for (j, nj) in basis_funs(&kv, span, tk).into_iter().enumerate() {
                row[span - p + j] = nj;
            }
            row
        })
        .collect();
    let control = solve_fixed_ends(&rows, data)?;
    Ok(BSplineCurve { knots: kv, control })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reproduces_a_spline_it_can_represent() {
        // Data sampled from a cubic polynomial: a fit with any n_ctrl >= 4 reproduces it
        // (up to rounding), since the polynomial lies in every such spline space.
        let f = |t: f64| [t, 2.0 * t * t * t - t * t + 0.5];
        let m = 40;
        let t: Vec<f64> = (0..m).map(|i| i as f64 / (m - 1) as f64).collect();
        let data: Vec<[f64; 2]> = t.iter().map(|&x| f(x)).collect();
        let c = fit_least_squares(&data, &t, 3, 7).unwrap();
        for i in 0..=100 {
            let x = i as f64 / 100.0;
            let e = c.eval(&x);
            let g = f(x);
            assert!(
                (e[0] - g[0]).abs() < 1e-10 && (e[1] - g[1]).abs() < 1e-10,
                "{x}"
            );
        }
    }
}
