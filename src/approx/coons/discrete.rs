//! Step 2 (§3.2): the discrete bilinear Coons patch. Boundary points are uniform in arc
//! length, `x_{I,0}` on side 0, `x_{M,J}` on side 1, `x_{I,N}` on side 2 (traversed from
//! `x_{M,N}` to `x_{0,N}`), `x_{0,J}` on side 3; the parameters `u_{I,J}` vary linearly
//! between `u_{I,0} = I/M` and `u_{I,N} = I/M` (so `u = I/M`, `v = J/N`), and eq. (3)/(4):
//!
//! `x_{I,J} = (1−u) x_{0,J} + u x_{M,J} + (1−v) x_{I,0} + v x_{I,N}
//!          − [(1−u)(1−v) x_{0,0} + (1−u) v x_{0,N} + u (1−v) x_{M,0} + u v x_{M,N}]`.

use super::boundary::Loop;

/// An `(M+1) × (N+1)` array of points, row-major in `I`.
#[derive(Clone, Debug, PartialEq)]
pub struct Grid<T> {
    pub m: usize,
    pub n: usize,
    pub data: Vec<T>,
}

impl<T: Clone> Grid<T> {
    /// A grid filled with `v`.
    pub fn filled(m: usize, n: usize, v: T) -> Self {
        Grid {
            m,
            n,
            data: vec![v; (m + 1) * (n + 1)],
        }
    }
    pub fn at(&self, i: usize, j: usize) -> &T {
        &self.data[i * (self.n + 1) + j]
    }
    pub fn set(&mut self, i: usize, j: usize, v: T) {
        let n = self.n;
        self.data[i * (n + 1) + j] = v;
    }
}

/// Eq. (3)/(4): the discrete Coons patch of the loop at resolution `M × N`.
pub fn coons_patch(lp: &Loop, m: usize, n: usize) -> Grid<[f64; 3]> {
    let bottom: Vec<[f64; 3]> = (0..=m)
        .map(|i| lp.side_point(0, i as f64 / m as f64))
        .collect();
    let right: Vec<[f64; 3]> = (0..=n)
        .map(|j| lp.side_point(1, j as f64 / n as f64))
        .collect();
    let top: Vec<[f64; 3]> = (0..=m)
        .map(|i| lp.side_point(2, 1.0 - i as f64 / m as f64))
        .collect();
    let left: Vec<[f64; 3]> = (0..=n)
        .map(|j| lp.side_point(3, 1.0 - j as f64 / n as f64))
        .collect();
    let (x00, xm0, xmn, x0n) = (bottom[0], bottom[m], top[m], top[0]);
    let mut g = Grid::filled(m, n, [0.0; 3]);
    for i in 0..=m {
        let u = i as f64 / m as f64;
        for j in 0..=n {
            let v = j as f64 / n as f64;
            let p = if j == 0 {
                bottom[i]
            } else if j == n {
                top[i]
            } else if i == 0 {
                left[j]
            } else if i == m {
                right[j]
            } else {
                std::array::from_fn(|k| {
                    (1.0 - u) * left[j][k]
                        + u * right[j][k]
                        + (1.0 - v) * bottom[i][k]
                        + v * top[i][k]
                        - ((1.0 - u) * (1.0 - v) * x00[k]
                            + (1.0 - u) * v * x0n[k]
                            + u * (1.0 - v) * xm0[k]
                            + u * v * xmn[k])
                })
            };
            g.set(i, j, p);
        }
    }
    g
}
