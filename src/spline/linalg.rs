//! Dense Gaussian elimination with pivoting on the largest magnitude, generic over the
//! scalar and the right-hand-side point type. Exact for exact backends; for `f64` it is
//! partial pivoting. Sizes here are small (interpolation and fitting systems).

use super::SplineError;
use crate::geom::Point;
use crate::scalar::Scalar;

/// Solve `A X = B` for `X` (rows of `B` are points). `A` is `n × n`, row-major.
pub fn solve<P: Point>(mut a: Vec<Vec<P::S>>, mut b: Vec<P>) -> Result<Vec<P>, SplineError> {
    let n = a.len();
    if b.len() != n || a.iter().any(|r| r.len() != n) {
        return Err(SplineError::Singular);
    }
    for col in 0..n {
        let piv = (col..n)
            .max_by(|&i, &j| {
                a[i][col]
                    .abs()
                    .partial_cmp(&a[j][col].abs())
                    .unwrap_or(std::cmp::Ordering::Equal)
            })
            .ok_or(SplineError::Singular)?;
        if a[piv][col].is_zero() {
            return Err(SplineError::Singular);
        }
        a.swap(col, piv);
        b.swap(col, piv);
        for r in col + 1..n {
            if a[r][col].is_zero() {
                continue;
            }
            let f = a[r][col].clone() / a[col][col].clone();
            for c in col..n {
                let v = a[r][c].clone() - f.clone() * a[col][c].clone();
                a[r][c] = v;
            }
            b[r] = b[r].sub(&b[col].scale(&f));
        }
    }
    let mut x = vec![P::origin(); n];
    for r in (0..n).rev() {
        let mut acc = b[r].clone();
        for c in r + 1..n {
            acc = acc.sub(&x[c].scale(&a[r][c]));
        }
        x[r] = acc.scale(&(P::S::one() / a[r][r].clone()));
    }
    Ok(x)
}
