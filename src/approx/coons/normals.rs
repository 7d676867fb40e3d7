//! §3.3: normals by central differences (5), the offset points `a`, `b` (6) and the offset
//! distance `d` (7):
//!
//! `n_{I,J} = (x_{I+1,J} − x_{I−1,J}) × (x_{I,J+1} − x_{I,J−1})`, normalized (one-sided
//! differences on the border), `a = x + d n`, `b = x − d n`,
//! `d = (‖x_{M,0}−x_{0,0}‖ + ‖x_{M,N}−x_{M,0}‖ + ‖x_{0,N}−x_{M,N}‖ + ‖x_{0,0}−x_{0,N}‖) / 8`.

use super::discrete::Grid;
use crate::geom::{Point, cross, dist, norm};

/// Eq. (7), times `scale`.
pub fn offset_distance(x: &Grid<[f64; 3]>, scale: f64) -> f64 {
    let (m, n) = (x.m, x.n);
    let s = dist(x.at(m, 0), x.at(0, 0))
        + dist(x.at(m, n), x.at(m, 0))
        + dist(x.at(0, n), x.at(m, n))
        + dist(x.at(0, 0), x.at(0, n));
    scale * s / 8.0
}

/// Eq. (5): unit normals; where the difference vectors are parallel (a collapsed corner),
/// the normal of the nearest neighbour along the diagonal, or `fallback`.
pub fn normals(x: &Grid<[f64; 3]>, fallback: [f64; 3]) -> Grid<[f64; 3]> {
    let (m, n) = (x.m, x.n);
    let mut out = Grid::filled(m, n, [f64::NAN; 3]);
    for i in 0..=m {
        for j in 0..=n {
            let (i0, i1) = (i.saturating_sub(1), (i + 1).min(m));
            let (j0, j1) = (j.saturating_sub(1), (j + 1).min(n));
            let c = cross(&x.at(i1, j).sub(x.at(i0, j)), &x.at(i, j1).sub(x.at(i, j0)));
            let l = norm(&c);
            if l > 0.0 && l.is_finite() {
                out.set(i, j, c.scale(&(1.0 / l)));
            }
        }
    }
    for i in 0..=m {
        for j in 0..=n {
            if out.at(i, j)[0].is_nan() {
                // The nearest interior point (itself when a direction has one interval).
                let inner = |k: usize, len: usize| if len >= 2 { k.clamp(1, len - 1) } else { k };
                let (ii, jj) = (inner(i, m), inner(j, n));
                let v = *out.at(ii, jj);
                out.set(i, j, if v[0].is_nan() { fallback } else { v });
            }
        }
    }
    out
}

/// Eq. (6): the segment ends `a = x + d n` and `b = x − d n`.
pub fn offsets(
    x: &Grid<[f64; 3]>,
    nrm: &Grid<[f64; 3]>,
    d: f64,
) -> (Grid<[f64; 3]>, Grid<[f64; 3]>) {
    let mut a = x.clone();
    let mut b = x.clone();
    for k in 0..x.data.len() {
        a.data[k] = x.data[k].add(&nrm.data[k].scale(&d));
        b.data[k] = x.data[k].sub(&nrm.data[k].scale(&d));
    }
    (a, b)
}
