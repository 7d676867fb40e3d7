//! Step 3 of the RCA parametrization (§2, "Finding interior interpolation points").
//!
//! **Initial guess.** The parameters of the boundary points are marked on the domain
//! rectangle of S, corresponding points of opposite borders are joined by straight lines,
//! and the line intersections are the first interior points ([`Grid::initial`]). Then (not
//! in the paper) [`super::redistribute`] moves the points of each row and column along it to their
//! arc-length fractions: without it the relaxation, which propagates one neighbour at a
//! time, needed millions of moves on a 13 × 16 grid.
//!
//! **Relaxation** ([`relax`]). Each interior point `x_ij = S(u_ij, v_ij)` has the *penalty*
//! `p_ij = (d_l/(d_l+d_r) − α_i)² + (d_d/(d_d+d_u) − β_j)²`, where `d_l, d_r, d_d, d_u` are
//! the distances to its four neighbours and `α_i = (ξ_i − ξ_{i−1})/(ξ_{i+1} − ξ_{i−1})`,
//! `β_j` likewise with η, are the ratios the chord-length parametrization asks (docs/papers.md
//! §A, property (1): parameter intervals proportional to chord lengths). `p_ij = 0` at every
//! point exactly when every row and column of the grid is chord-length spaced at `(ξ, η)`.
//! Points move in the domain only (so their images stay on S), by finite steps (first the
//! Gauss–Newton step of the local penalty sum, then a pattern of 8 steps, halving); points
//! are processed in descending penalty; a point is visited again only
//! if a neighbour moved since its last visit; the relaxation stops when no point moves.
//!
//! **Termination (a theorem).** Let `P` be the sum of the stored penalties (each in
//! `[0, 2]`). A move of `x_ij` changes only `p_ij` and the penalties of its (at most four)
//! interior neighbours, and it is accepted only when the floating-point sum of those (≤ 5)
//! stored values drops by at least `δ`. Each such sum of non-negative terms ≤ 2.02 has a
//! rounding error below `4u · 10.1`, the difference one below `u · 10.1` (`u = 2⁻⁵³`), so the
//! exact `P` drops by at least `δ − γ` with `γ = 2·10⁻¹⁴ > 91u`; since `P ≥ 0`, the number of
//! accepted moves is at most `P_start / (δ − γ)` ([`RelaxStats::move_bound`]). A point is
//! dirty initially or after a neighbour's visit moved it, so visits are at most
//! `#interior + 4 · moves`, and a visit ends after at most 11 failed step halvings (the step
//! floor is `max(10⁻³ h_0, h_min)`) past its moves. The move budget [`Params::max_moves`] is enforced anyway; reaching
//! it marks the relaxation not converged.

#[cfg(doc)]
use super::Params;
use super::ReparamError;
use super::boundary::BoundaryCurve;
use crate::geom::dist;
use crate::spline::NurbsSurface;

mod relaxation;

pub use relaxation::{RelaxStats, relax};

/// Rounding allowance of the penalty decrease test (see the module documentation).
pub const GAMMA: f64 = 2e-14;

/// The grid of interpolation points: parameters `ξ_i` (u) and `η_j` (v) of the new
/// surface, the domain points `(u, v)` of S and their images `x = S(u, v)`, indexed `[i][j]`.
#[derive(Clone, Debug)]
pub struct Grid {
    pub xi: Vec<f64>,
    pub eta: Vec<f64>,
    pub uv: Vec<Vec<[f64; 2]>>,
    pub x: Vec<Vec<[f64; 3]>>,
}

/// A parameter line to insert: `ξ = const` or `η = const`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Line {
    Xi(f64),
    Eta(f64),
}

pub(super) fn eval(s: &NurbsSurface<f64, 3>, uv: [f64; 2]) -> Result<[f64; 3], ReparamError> {
    let p = s.eval(&uv[0], &uv[1]);
    if p.iter().all(|c| c.is_finite()) {
        Ok(p)
    } else {
        Err(ReparamError::NotFinite(uv[0], uv[1]))
    }
}

pub(super) fn lerp2(a: [f64; 2], b: [f64; 2], t: f64) -> [f64; 2] {
    [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])]
}

/// Index `k` with `t[k] ≤ x ≤ t[k+1]`, and the local coordinate in that interval.
pub fn locate(t: &[f64], x: f64) -> (usize, f64) {
    let k = t.partition_point(|&y| y <= x).clamp(1, t.len() - 1) - 1;
    let a = ((x - t[k]) / (t[k + 1] - t[k])).clamp(0.0, 1.0);
    (k, a)
}

impl Grid {
    /// Boundary points at their arc-length fractions `ξ_i`, `η_j` (steps 1–2), interior
    /// points at the intersections of the domain lines joining corresponding boundary
    /// parameters (Figure 4).
    pub fn initial(
        s: &NurbsSurface<f64, 3>,
        sides: &[BoundaryCurve; 4],
        xi: Vec<f64>,
        eta: Vec<f64>,
    ) -> Result<Grid, ReparamError> {
        let (n, m) = (xi.len(), eta.len());
        let bottom: Vec<[f64; 2]> = xi
            .iter()
            .map(|&f| sides[0].domain_point(sides[0].param_at_fraction(s, f)))
            .collect();
        let top: Vec<[f64; 2]> = xi
            .iter()
            .map(|&f| sides[1].domain_point(sides[1].param_at_fraction(s, f)))
            .collect();
        let left: Vec<[f64; 2]> = eta
            .iter()
            .map(|&f| sides[2].domain_point(sides[2].param_at_fraction(s, f)))
            .collect();
        let right: Vec<[f64; 2]> = eta
            .iter()
            .map(|&f| sides[3].domain_point(sides[3].param_at_fraction(s, f)))
            .collect();
        let mut uv = vec![vec![[0.0; 2]; m]; n];
        for i in 0..n {
            for j in 0..m {
                uv[i][j] = if j == 0 {
                    bottom[i]
                } else if j == m - 1 {
                    top[i]
                } else if i == 0 {
                    left[j]
                } else if i == n - 1 {
                    right[j]
                } else {
                    intersect(bottom[i], top[i], left[j], right[j], xi[i], eta[j])
                };
            }
        }
        let x = uv
            .iter()
            .map(|row| row.iter().map(|&p| eval(s, p)).collect())
            .collect::<Result<Vec<Vec<_>>, _>>()?;
        Ok(Grid { xi, eta, uv, x })
    }

    /// Interior points `(i, j)`, `0 < i < n−1`, `0 < j < m−1`.
    pub fn interior_points(&self) -> impl Iterator<Item = (usize, usize)> + '_ {
        let (n, m) = (self.xi.len(), self.eta.len());
        (1..n.saturating_sub(1)).flat_map(move |i| (1..m.saturating_sub(1)).map(move |j| (i, j)))
    }

    fn is_interior(&self, i: usize, j: usize) -> bool {
        i > 0 && j > 0 && i + 1 < self.xi.len() && j + 1 < self.eta.len()
    }

    /// The penalty of interior point `(i, j)`, with the point `at` replaced by `p` if given.
    pub fn penalty(&self, i: usize, j: usize, sub: Option<((usize, usize), &[f64; 3])>) -> f64 {
        let x = |a: usize, b: usize| match sub {
            Some((k, p)) if k == (a, b) => p,
            _ => &self.x[a][b],
        };
        let term = |dl: f64, dr: f64, target: f64| {
            let s = dl + dr;
            if s > 0.0 {
                let r = dl / s - target;
                r * r
            } else {
                0.0
            }
        };
        let (xi, eta) = (&self.xi, &self.eta);
        let alpha = (xi[i] - xi[i - 1]) / (xi[i + 1] - xi[i - 1]);
        let beta = (eta[j] - eta[j - 1]) / (eta[j + 1] - eta[j - 1]);
        let c = x(i, j);
        term(dist(c, x(i - 1, j)), dist(x(i + 1, j), c), alpha)
            + term(dist(c, x(i, j - 1)), dist(x(i, j + 1), c), beta)
    }

    /// `P`: the sum of the penalties of all interior points.
    pub fn total_penalty(&self) -> f64 {
        self.interior_points()
            .map(|(i, j)| self.penalty(i, j, None))
            .sum()
    }

    /// φ: the domain point of S for parameters `(ξ, η)` of the new surface, bilinear in each
    /// grid cell; and the cell `(i, j)`.
    pub fn map(&self, xi: f64, eta: f64) -> ([f64; 2], (usize, usize)) {
        let (i, a) = locate(&self.xi, xi);
        let (j, b) = locate(&self.eta, eta);
        let p0 = lerp2(self.uv[i][j], self.uv[i + 1][j], a);
        let p1 = lerp2(self.uv[i][j + 1], self.uv[i + 1][j + 1], a);
        (lerp2(p0, p1, b), (i, j))
    }

    /// Insert parameter lines (step 4's refinement): boundary points at their arc-length
    /// fractions, interior points first on the current grid's φ (then relaxed by [`relax`]).
    /// Returns the points to relax: the new ones and their neighbours (whose target ratios
    /// changed).
    pub fn insert_lines(
        &mut self,
        s: &NurbsSurface<f64, 3>,
        sides: &[BoundaryCurve; 4],
        lines: &[Line],
    ) -> Result<Vec<(usize, usize)>, ReparamError> {
        let mut new_xi = vec![];
        let mut new_eta = vec![];
        for line in lines {
            match *line {
                Line::Xi(f) => {
                    let (k, a) = locate(&self.xi, f);
                    if a <= 0.0 || a >= 1.0 {
                        continue;
                    }
                    let m = self.eta.len();
                    let col: Vec<[f64; 2]> = (0..m)
                        .map(|j| {
                            if j == 0 {
                                sides[0].domain_point(sides[0].param_at_fraction(s, f))
                            } else if j == m - 1 {
                                sides[1].domain_point(sides[1].param_at_fraction(s, f))
                            } else {
                                lerp2(self.uv[k][j], self.uv[k + 1][j], a)
                            }
                        })
                        .collect();
                    let xs = col
                        .iter()
                        .map(|&p| eval(s, p))
                        .collect::<Result<Vec<_>, _>>()?;
                    self.xi.insert(k + 1, f);
                    self.uv.insert(k + 1, col);
                    self.x.insert(k + 1, xs);
                    new_xi.push(f);
                }
                Line::Eta(f) => {
                    let (k, a) = locate(&self.eta, f);
                    if a <= 0.0 || a >= 1.0 {
                        continue;
                    }
                    let n = self.xi.len();
                    for i in 0..n {
                        let p = if i == 0 {
                            sides[2].domain_point(sides[2].param_at_fraction(s, f))
                        } else if i == n - 1 {
                            sides[3].domain_point(sides[3].param_at_fraction(s, f))
                        } else {
                            lerp2(self.uv[i][k], self.uv[i][k + 1], a)
                        };
                        let x = eval(s, p)?;
                        self.uv[i].insert(k + 1, p);
                        self.x[i].insert(k + 1, x);
                    }
                    self.eta.insert(k + 1, f);
                    new_eta.push(f);
                }
            }
        }
        let touched = |t: &[f64], new: &[f64], k: usize| {
            (k.saturating_sub(1)..=(k + 1).min(t.len() - 1)).any(|q| new.contains(&t[q]))
        };
        Ok(self
            .interior_points()
            .filter(|&(i, j)| touched(&self.xi, &new_xi, i) || touched(&self.eta, &new_eta, j))
            .collect())
    }
}

/// Intersection of the domain segments `b–t` (joining the two points of parameter ξ on
/// `v = v0` and `v = v1`) and `l–r` (parameter η on `u = u0` and `u = u1`). The segments
/// span the rectangle in crossing directions, so they meet once; a numerically parallel pair
/// (possible only at a corner) falls back to the parameters' bilinear position.
fn intersect(b: [f64; 2], t: [f64; 2], l: [f64; 2], r: [f64; 2], xi: f64, eta: f64) -> [f64; 2] {
    let d1 = [t[0] - b[0], t[1] - b[1]];
    let d2 = [r[0] - l[0], r[1] - l[1]];
    let det = d1[0] * (-d2[1]) - d1[1] * (-d2[0]);
    let rhs = [l[0] - b[0], l[1] - b[1]];
    let scale = (d1[0].abs() + d1[1].abs()) * (d2[0].abs() + d2[1].abs());
    if det.abs() <= 1e-12 * scale {
        let p0 = lerp2(b, t, eta);
        let p1 = lerp2(l, r, xi);
        return [(p0[0] + p1[0]) / 2.0, (p0[1] + p1[1]) / 2.0];
    }
    let a = ((rhs[0] * (-d2[1]) - rhs[1] * (-d2[0])) / det).clamp(0.0, 1.0);
    lerp2(b, t, a)
}
