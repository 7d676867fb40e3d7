//! Step 5 (§3.5): the bicubic C1 interpolant (14) of the `(M+1) × (N+1)` points.
//!
//! Order 4, `m = 3M`, `n = 3N`, uniform `ξ_i = i/M`, `η_j = j/N`, quadruple end knots and
//! triple interior knots (15): every span is a bicubic Bézier patch and
//! `s(ξ_I, η_J) = d_{3I,3J} = y_{I,J}`. Rows and columns are interpolated by a C1 cubic
//! scheme with tangents from the neighbours (central differences; the parabola through the
//! first or last three points at the ends), `d_{3I±1,3J} = d_{3I,3J} ± (Δξ/3) T`, and the
//! four interior control points of each patch follow the twist rule (16):
//! `d_{3I±1,3J±1} = d_{3I±1,3J} + (d_{3I,3J±1} − d_{3I,3J})`.
//!
//! C1 across `ξ_I` holds because, on uniform knots, every column of control points has
//! `d_{3I,k} = (d_{3I−1,k} + d_{3I+1,k}) / 2` — for `k = 3J` by the row scheme, for
//! `k = 3J ± 1` by (16) summed over both sides. [`c1_defect`] measures the rounding left.

use super::CoonsError;
use super::discrete::Grid;
use crate::geom::Point;
use crate::spline::NurbsSurface;

/// Tangents `dP/dξ` of a row of `k + 1` points on uniform parameters `i / k`.
fn tangents(p: &[[f64; 3]]) -> Vec<[f64; 3]> {
    let k = p.len() - 1;
    let h = 1.0 / k as f64;
    (0..=k)
        .map(|i| {
            if k == 1 {
                p[1].sub(&p[0]).scale(&(1.0 / h))
            } else if i == 0 {
                // Parabola through p0, p1, p2: (−3 p0 + 4 p1 − p2) / (2h).
                p[1].scale(&4.0)
                    .sub(&p[0].scale(&3.0))
                    .sub(&p[2])
                    .scale(&(0.5 / h))
            } else if i == k {
                p[k].scale(&3.0)
                    .sub(&p[k - 1].scale(&4.0))
                    .add(&p[k - 2])
                    .scale(&(0.5 / h))
            } else {
                p[i + 1].sub(&p[i - 1]).scale(&(0.5 / h))
            }
        })
        .collect()
}

/// The control net `(3M+1) × (3N+1)` (row-major in the `u` index).
pub fn control_net(y: &Grid<[f64; 3]>) -> Vec<[f64; 3]> {
    let (m, n) = (y.m, y.n);
    let (cu, cv) = (3 * m + 1, 3 * n + 1);
    let mut d = vec![[0.0; 3]; cu * cv];
    let id = |i: usize, j: usize| i * cv + j;
    for i in 0..=m {
        for j in 0..=n {
            d[id(3 * i, 3 * j)] = *y.at(i, j);
        }
    }
    // Rows (u direction) at every J.
    let hu = 1.0 / (3.0 * m as f64);
    for j in 0..=n {
        let row: Vec<[f64; 3]> = (0..=m).map(|i| *y.at(i, j)).collect();
        let t = tangents(&row);
        for i in 0..=m {
            if i > 0 {
                d[id(3 * i - 1, 3 * j)] = row[i].sub(&t[i].scale(&hu));
            }
            if i < m {
                d[id(3 * i + 1, 3 * j)] = row[i].add(&t[i].scale(&hu));
            }
        }
    }
    // Columns (v direction) at every I.
    let hv = 1.0 / (3.0 * n as f64);
    for i in 0..=m {
        let col: Vec<[f64; 3]> = (0..=n).map(|j| *y.at(i, j)).collect();
        let t = tangents(&col);
        for j in 0..=n {
            if j > 0 {
                d[id(3 * i, 3 * j - 1)] = col[j].sub(&t[j].scale(&hv));
            }
            if j < n {
                d[id(3 * i, 3 * j + 1)] = col[j].add(&t[j].scale(&hv));
            }
        }
    }
    // Eq. (16): the twist rule.
    for i in 0..=m {
        for j in 0..=n {
            let c = d[id(3 * i, 3 * j)];
            for (di, ok_i) in [(-1i64, i > 0), (1, i < m)] {
                for (dj, ok_j) in [(-1i64, j > 0), (1, j < n)] {
                    if ok_i && ok_j {
                        let ii = (3 * i as i64 + di) as usize;
                        let jj = (3 * j as i64 + dj) as usize;
                        d[id(ii, jj)] = d[id(ii, 3 * j)].add(&d[id(3 * i, jj)].sub(&c));
                    }
                }
            }
        }
    }
    d
}

/// The knot vector (15) for `k` intervals: `0,0,0,0, ξ_1×3, …, ξ_{k−1}×3, 1,1,1,1`.
pub fn knots(k: usize) -> Vec<f64> {
    let mut v = vec![0.0; 4];
    for i in 1..k {
        let x = i as f64 / k as f64;
        v.extend([x, x, x]);
    }
    v.extend([1.0; 4]);
    v
}

/// Eq. (14): the bicubic interpolant of `y`.
pub fn interpolant(y: &Grid<[f64; 3]>) -> Result<NurbsSurface<f64, 3>, CoonsError> {
    let net = control_net(y);
    if net.iter().flatten().any(|c| !c.is_finite()) {
        return Err(CoonsError::NotFinite(
            "the control net of the interpolant".into(),
        ));
    }
    let w = vec![1.0; net.len()];
    NurbsSurface::new(
        knots(y.m),
        3,
        knots(y.n),
        3,
        3 * y.m + 1,
        3 * y.n + 1,
        net,
        w,
    )
    .map_err(|e| CoonsError::Spline(e.to_string()))
}

/// Largest `‖d_{3I−1,k} + d_{3I+1,k} − 2 d_{3I,k}‖` over interior knot lines of both
/// directions: zero in exact arithmetic (C1 on uniform knots), rounding in `f64`.
pub fn c1_defect(s: &NurbsSurface<f64, 3>, m: usize, n: usize) -> f64 {
    let (cu, cv) = (3 * m + 1, 3 * n + 1);
    let (pts, _) = s.points_weights();
    let at = |i: usize, j: usize| pts[i * cv + j];
    let mut worst: f64 = 0.0;
    let defect =
        |a: [f64; 3], c: [f64; 3], b: [f64; 3]| crate::geom::norm(&a.add(&b).sub(&c.scale(&2.0)));
    for i in 1..m {
        for k in 0..cv {
            worst = worst.max(defect(at(3 * i - 1, k), at(3 * i, k), at(3 * i + 1, k)));
        }
    }
    for j in 1..n {
        for k in 0..cu {
            worst = worst.max(defect(at(k, 3 * j - 1), at(k, 3 * j), at(k, 3 * j + 1)));
        }
    }
    worst
}
