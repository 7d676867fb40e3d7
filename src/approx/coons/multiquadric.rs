//! Step 4 (§3.4): artificial projections where a segment `a–b` meets no original surface.
//!
//! Each found projection is `p = (1 − t) a + t b` (10). Hardy's reciprocal multiquadric
//! interpolates the known `t` over the Coons parameters `(u, v) = (I/M, J/N)`, localized to
//! the K known projections nearest in index (12):
//!
//! `t(u, v) = Σ_k c_k (R + (u − u_k)² + (v − v_k)²)^μ  [+ λ_0 + λ_1 u + λ_2 v]`,
//!
//! and the artificial projection is `z = (1 − t) a + t b` (13). Defaults: `μ = −1/2` (the
//! reciprocal multiquadric; the paper's exponent lost its sign in the extracted text),
//! `R = 0.5 (δ_u + δ_v)` with the mean parameter spacings `δ_u = 1/M`, `δ_v = 1/N` (the
//! paper's value). The optional linear part (with `Σ c_k = Σ c_k u_k = Σ c_k v_k = 0`) is an
//! addition: it makes the fill exact on linear data, which the paper's form is not. The
//! reciprocal multiquadric is strictly positive definite (Micchelli), so the plain system is
//! regular for distinct centres; with the linear part it is regular when the centres are not
//! collinear — otherwise the linear part is dropped and that is counted. Every system's
//! 1-norm condition number is computed from its inverse and the largest is reported.

use super::CoonsError;
use super::discrete::Grid;
use serde::Serialize;

/// Condition numbers above this are reported as ill-conditioned.
pub const ILL_CONDITIONED: f64 = 1e12;

/// A multiquadric interpolant of scattered values.
#[derive(Clone, Debug)]
pub struct Interpolant {
    centers: Vec<[f64; 2]>,
    coef: Vec<f64>,
    linear: Option<[f64; 3]>,
    r: f64,
    mu: f64,
    /// 1-norm condition number of the system solved.
    pub condition: f64,
}

/// The basis function `(R + d²)^μ`.
fn phi(r: f64, mu: f64, d2: f64) -> f64 {
    if mu == -0.5 {
        1.0 / (r + d2).sqrt()
    } else {
        (r + d2).powf(mu)
    }
}

/// Solve `A x = b` and estimate the 1-norm condition number via the inverse (Gauss–Jordan
/// with partial pivoting); `None` when a pivot vanishes.
fn solve_with_condition(a: &[Vec<f64>], rhs: &[f64]) -> Option<(Vec<f64>, f64)> {
    let n = a.len();
    let mut m: Vec<Vec<f64>> = a
        .iter()
        .enumerate()
        .map(|(i, row)| {
            let mut r = row.clone();
            r.extend((0..n).map(|j| if i == j { 1.0 } else { 0.0 }));
            r.push(rhs[i]);
            r
        })
        .collect();
    let norm1 = |x: &dyn Fn(usize, usize) -> f64| {
        (0..n)
            .map(|j| (0..n).map(|i| x(i, j).abs()).sum::<f64>())
            .fold(0.0, f64::max)
    };
    let a_norm = norm1(&|i, j| a[i][j]);
    for col in 0..n {
        let piv = (col..n).max_by(|&i, &j| m[i][col].abs().total_cmp(&m[j][col].abs()))?;
        if m[piv][col] == 0.0 || m[piv][col].is_nan() {
            return None;
        }
        m.swap(col, piv);
        let d = m[col][col];
        for c in 0..2 * n + 1 {
            m[col][c] /= d;
        }
        for r in 0..n {
            if r != col && m[r][col] != 0.0 {
                let f = m[r][col];
                for c in 0..2 * n + 1 {
                    let v = m[col][c];
                    m[r][c] -= f * v;
                }
            }
        }
    }
    let inv_norm = norm1(&|i, j| m[i][n + j]);
    let x: Vec<f64> = (0..n).map(|i| m[i][2 * n]).collect();
    let cond = a_norm * inv_norm;
    (x.iter().all(|v| v.is_finite()) && cond.is_finite()).then_some((x, cond))
}

/// Interpolate `values` at `centers` by `(R + d²)^μ`, with a linear part if `linear` (and
/// the centres are not collinear); errors when the system is singular.
pub fn interpolate(
    centers: &[[f64; 2]],
    values: &[f64],
    r: f64,
    mu: f64,
    linear: bool,
) -> Result<Interpolant, CoonsError> {
    let k = centers.len();
    if k == 0 || values.len() != k {
        return Err(CoonsError::Parameter {
            name: "multiquadric centres",
            value: k as f64,
            why: "need at least one centre and one value per centre",
        });
    }
    let build = |lin: bool| {
        let n = k + if lin { 3 } else { 0 };
        let mut a = vec![vec![0.0; n]; n];
        let mut b = vec![0.0; n];
        for i in 0..k {
            for j in 0..k {
                let d2 = (centers[i][0] - centers[j][0]).powi(2)
                    + (centers[i][1] - centers[j][1]).powi(2);
                a[i][j] = phi(r, mu, d2);
            }
            if lin {
                let row = [1.0, centers[i][0], centers[i][1]];
                for q in 0..3 {
                    a[i][k + q] = row[q];
                    a[k + q][i] = row[q];
                }
            }
            b[i] = values[i];
        }
        solve_with_condition(&a, &b)
    };
    // Collinear centres (decided exactly) leave the linear part undetermined; a system
    // whose condition exceeds [`ILL_CONDITIONED`] with the linear part is replaced by the
    // plain one when that is better conditioned.
    let far = centers
        .iter()
        .max_by(|a, b| {
            let d = |p: &[f64; 2]| (p[0] - centers[0][0]).powi(2) + (p[1] - centers[0][1]).powi(2);
            d(a).total_cmp(&d(b))
        })
        .unwrap_or(&centers[0]);
    let collinear = centers
        .iter()
        .all(|c| crate::predicates::orient2d(&centers[0], far, c) == crate::scalar::Sign::Zero);
    let with_linear = (linear && k >= 3 && !collinear)
        .then(|| build(true))
        .flatten();
    let with_linear = match with_linear {
        Some(s) if s.1 > ILL_CONDITIONED => match build(false) {
            Some(p) if p.1 < s.1 => Some((p, false)),
            _ => Some((s, true)),
        },
        Some(s) => Some((s, true)),
        None => None,
    };
    let (sol, linear_used) = match with_linear {
        Some(x) => x,
        None => (
            build(false).ok_or(CoonsError::Parameter {
                name: "multiquadric system",
                value: k as f64,
                why: "singular (repeated centres?)",
            })?,
            false,
        ),
    };
    let (x, condition) = sol;
    Ok(Interpolant {
        centers: centers.to_vec(),
        coef: x[..k].to_vec(),
        linear: linear_used.then(|| [x[k], x[k + 1], x[k + 2]]),
        r,
        mu,
        condition,
    })
}

impl Interpolant {
    /// `t(u, v)`.
    pub fn eval(&self, p: &[f64; 2]) -> f64 {
        let mut s = 0.0;
        for (c, w) in self.centers.iter().zip(&self.coef) {
            let d2 = (p[0] - c[0]).powi(2) + (p[1] - c[1]).powi(2);
            s += w * phi(self.r, self.mu, d2);
        }
        if let Some(l) = self.linear {
            s += l[0] + l[1] * p[0] + l[2] * p[1];
        }
        s
    }
    /// Whether the linear part was used.
    pub fn has_linear_part(&self) -> bool {
        self.linear.is_some()
    }
}

/// What the fill did.
#[derive(Clone, Debug, Default, Serialize)]
pub struct FillStats {
    /// Artificial projections made.
    pub filled: usize,
    /// K, R and μ used.
    pub k: usize,
    pub r: f64,
    pub mu: f64,
    /// Largest 1-norm condition number of the systems (12).
    pub max_condition: f64,
    /// Systems whose condition number exceeds 1e12 (their `t` may carry few digits).
    pub ill_conditioned: usize,
    /// Systems solved without the linear part (collinear centres).
    pub without_linear_part: usize,
    /// Artificial `t` outside `[0, 1]`, clamped to the segment by the caller.
    pub clamped: usize,
}

/// Eq. (12)/(13): `t` at every grid point without a projection, from the K known nearest in
/// index; `known` holds the `t` of the found projections.
pub fn fill(
    known: &Grid<Option<f64>>,
    k: usize,
    r_scale: f64,
    mu: f64,
    linear: bool,
) -> Result<(Grid<f64>, FillStats), CoonsError> {
    let (m, n) = (known.m, known.n);
    let r = r_scale * 0.5 * (1.0 / m as f64 + 1.0 / n as f64);
    let found: Vec<(usize, usize, f64)> = (0..=m)
        .flat_map(|i| (0..=n).map(move |j| (i, j)))
        .filter_map(|(i, j)| known.at(i, j).map(|t| (i, j, t)))
        .collect();
    let mut stats = FillStats {
        k,
        r,
        mu,
        ..Default::default()
    };
    let mut out = Grid::filled(m, n, 0.0);
    for i in 0..=m {
        for j in 0..=n {
            if let Some(t) = known.at(i, j) {
                out.set(i, j, *t);
                continue;
            }
            let mut near: Vec<(i64, usize)> = found
                .iter()
                .enumerate()
                .map(|(q, (a, b, _))| {
                    let (di, dj) = (*a as i64 - i as i64, *b as i64 - j as i64);
                    (di * di + dj * dj, q)
                })
                .collect();
            let kk = k.min(near.len());
            if kk == 0 {
                return Err(CoonsError::Parameter {
                    name: "projections found",
                    value: 0.0,
                    why: "no projection to fill gaps from",
                });
            }
            near.select_nth_unstable(kk - 1);
            near.truncate(kk);
            near.sort_unstable();
            let centers: Vec<[f64; 2]> = near
                .iter()
                .map(|(_, q)| [found[*q].0 as f64 / m as f64, found[*q].1 as f64 / n as f64])
                .collect();
            let values: Vec<f64> = near.iter().map(|(_, q)| found[*q].2).collect();
            let ip = interpolate(&centers, &values, r, mu, linear)?;
            stats.max_condition = stats.max_condition.max(ip.condition);
            if ip.condition > ILL_CONDITIONED {
                stats.ill_conditioned += 1;
            }
            if linear && !ip.has_linear_part() {
                stats.without_linear_part += 1;
            }
            let t = ip.eval(&[i as f64 / m as f64, j as f64 / n as f64]);
            if !t.is_finite() {
                return Err(CoonsError::NotFinite(format!(
                    "the multiquadric fill at ({i}, {j})"
                )));
            }
            out.set(i, j, t);
            stats.filled += 1;
        }
    }
    Ok((out, stats))
}
