//! The relaxation of step 3 of the RCA parametrization (§2, "Finding interior interpolation
//! points"): the Gauss–Newton step on a point's local penalty sum, the pattern of 8 steps,
//! the visiting order by descending penalty, and the statistics with the proven bound on the
//! number of moves (the termination theorem of the parent module).

use super::{GAMMA, Grid};
use crate::geom::dist;
use crate::reparam::{Params, ReparamError};
use crate::spline::NurbsSurface;
use std::collections::BinaryHeap;

struct Candidate {
    dec: f64,
    q: [f64; 2],
    xq: [f64; 3],
    own: f64,
    others: Vec<f64>,
    len: f64,
}

/// The Gauss–Newton step for the local penalty sum of point `(i, j)`: the ratio residuals
/// of the point itself (`d_l/(d_l+d_r) − α_i`, `d_d/(d_d+d_u) − β_j`) and those of its
/// interior neighbours that involve it, linearized in the domain (chain rule through `S_u`,
/// `S_v`); shortened to at most `cap` (normalized). `None` where the normal equations are
/// singular.
fn newton(
    s: &NurbsSurface<f64, 3>,
    g: &Grid,
    i: usize,
    j: usize,
    cap: f64,
    scale: [f64; 2],
) -> Option<[f64; 2]> {
    use crate::geom::{Point, dot};
    let [u, v] = g.uv[i][j];
    let (c, su, sv) = crate::spline::project::point_d1(s, u, v);
    let (n, m) = (g.xi.len(), g.eta.len());
    let mut res: Vec<(f64, [f64; 3])> = Vec::with_capacity(6);
    // d/dc of l/(l+r), l = |c − a| (c at the near end of the first distance).
    let near = |a: &[f64; 3], b: &[f64; 3], target: f64| -> Option<(f64, [f64; 3])> {
        let (l, r) = (dist(&c, a), dist(b, &c));
        if l <= 0.0 || r <= 0.0 {
            return None;
        }
        let dl = c.sub(a).scale(&(1.0 / l));
        let dr = c.sub(b).scale(&(1.0 / r));
        let grad = dl
            .scale(&r)
            .sub(&dr.scale(&l))
            .scale(&(1.0 / ((l + r) * (l + r))));
        Some((l / (l + r) - target, grad))
    };
    // Residual l/(l+r) − target of a neighbour y whose first distance l = |y − y_prev| is
    // fixed and second r = |c − y| moves (`first = false`), or whose first distance
    // l = |y − c| moves and second r = |y_next − y| is fixed (`first = true`).
    let nbr =
        |y: &[f64; 3], other: &[f64; 3], target: f64, first: bool| -> Option<(f64, [f64; 3])> {
            let dc = dist(&c, y);
            let fixed = dist(y, other);
            if dc <= 0.0 || fixed <= 0.0 {
                return None;
            }
            let e = c.sub(y).scale(&(1.0 / dc));
            let t = dc + fixed;
            Some(if first {
                (dc / t - target, e.scale(&(fixed / (t * t))))
            } else {
                (fixed / t - target, e.scale(&(-fixed / (t * t))))
            })
        };
    let ratio = |t: &[f64], k: usize| (t[k] - t[k - 1]) / (t[k + 1] - t[k - 1]);
    res.push(near(&g.x[i - 1][j], &g.x[i + 1][j], ratio(&g.xi, i))?);
    res.push(near(&g.x[i][j - 1], &g.x[i][j + 1], ratio(&g.eta, j))?);
    if i >= 2 && g.is_interior(i - 1, j) {
        res.extend(nbr(
            &g.x[i - 1][j],
            &g.x[i - 2][j],
            ratio(&g.xi, i - 1),
            false,
        ));
    }
    if i + 2 < n && g.is_interior(i + 1, j) {
        res.extend(nbr(
            &g.x[i + 1][j],
            &g.x[i + 2][j],
            ratio(&g.xi, i + 1),
            true,
        ));
    }
    if j >= 2 && g.is_interior(i, j - 1) {
        res.extend(nbr(
            &g.x[i][j - 1],
            &g.x[i][j - 2],
            ratio(&g.eta, j - 1),
            false,
        ));
    }
    if j + 2 < m && g.is_interior(i, j + 1) {
        res.extend(nbr(
            &g.x[i][j + 1],
            &g.x[i][j + 2],
            ratio(&g.eta, j + 1),
            true,
        ));
    }
    let (mut a11, mut a12, mut a22, mut b1, mut b2) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for (f, gr) in &res {
        let (ju, jv) = (dot(gr, &su), dot(gr, &sv));
        a11 += ju * ju;
        a12 += ju * jv;
        a22 += jv * jv;
        b1 += ju * f;
        b2 += jv * f;
    }
    let damp = 1e-12 * (a11 + a22);
    let (a11, a22) = (a11 + damp, a22 + damp);
    let det = a11 * a22 - a12 * a12;
    if !det.is_finite() || det <= 0.0 {
        return None;
    }
    let mut d = [-(a22 * b1 - a12 * b2) / det, -(a11 * b2 - a12 * b1) / det];
    let len = ((d[0] / scale[0]).powi(2) + (d[1] / scale[1]).powi(2)).sqrt();
    if !len.is_finite() || len == 0.0 {
        return None;
    }
    if len > cap {
        d = [d[0] * cap / len, d[1] * cap / len];
    }
    Some([u + d[0], v + d[1]])
}

/// What one relaxation did.
#[derive(Clone, Debug, Default)]
pub struct RelaxStats {
    pub visits: usize,
    pub moves: usize,
    /// `P_start / (δ − γ)`: the proven bound on `moves`.
    pub move_bound: f64,
    pub penalty_start: f64,
    pub penalty_end: f64,
    /// Stopped because no point could move (not by the budget).
    pub converged: bool,
}

const DIRS: [(f64, f64); 8] = [
    (1.0, 0.0),
    (-1.0, 0.0),
    (0.0, 1.0),
    (0.0, -1.0),
    (1.0, 1.0),
    (1.0, -1.0),
    (-1.0, 1.0),
    (-1.0, -1.0),
];

/// The relaxation of step 3, starting with the points `start` dirty (see the module
/// documentation for the rules and the termination theorem).
pub fn relax(
    s: &NurbsSurface<f64, 3>,
    g: &mut Grid,
    start: &[(usize, usize)],
    p: &Params,
) -> Result<RelaxStats, ReparamError> {
    let (n, m) = (g.xi.len(), g.eta.len());
    let (u0, u1, v0, v1) = s.hom.domain();
    let (du, dv) = (u1 - u0, v1 - v0);
    let mut pen = vec![vec![0.0; m]; n];
    for (i, j) in g.interior_points().collect::<Vec<_>>() {
        pen[i][j] = g.penalty(i, j, None);
    }
    let p_start: f64 = pen.iter().flatten().sum();
    let mut st = RelaxStats {
        move_bound: p_start * (1.0 + 1e-9) / (p.delta - GAMMA),
        penalty_start: p_start,
        converged: true,
        ..Default::default()
    };
    // Normalized domain distance from (i, j) to its nearest neighbour.
    let near = |g: &Grid, i: usize, j: usize| {
        let c = g.uv[i][j];
        [(i - 1, j), (i + 1, j), (i, j - 1), (i, j + 1)]
            .iter()
            .map(|&(a, b)| {
                let q = g.uv[a][b];
                (((q[0] - c[0]) / du).powi(2) + ((q[1] - c[1]) / dv).powi(2)).sqrt()
            })
            .fold(f64::INFINITY, f64::min)
    };
    let mut h = vec![vec![p.min_step; m]; n];
    let mut dirty = vec![vec![false; m]; n];
    let mut heap: BinaryHeap<(u64, usize)> = BinaryHeap::new();
    for &(i, j) in start {
        if g.is_interior(i, j) {
            dirty[i][j] = true;
            h[i][j] = (0.25 * near(g, i, j)).max(p.min_step);
            heap.push((pen[i][j].to_bits(), i * m + j));
        }
    }
    while let Some((bits, k)) = heap.pop() {
        let (i, j) = (k / m, k % m);
        if !dirty[i][j] || bits != pen[i][j].to_bits() {
            continue;
        }
        dirty[i][j] = false;
        st.visits += 1;
        let nbrs: Vec<(usize, usize)> = [(i - 1, j), (i + 1, j), (i, j - 1), (i, j + 1)]
            .into_iter()
            .filter(|&(a, b)| g.is_interior(a, b))
            .collect();
        let cap = (0.5 * near(g, i, j)).max(p.min_step);
        let mut step = h[i][j].clamp(p.min_step, cap);
        let floor = (step * 1e-3).max(p.min_step);
        let mut moved = 0.0;
        loop {
            let old: f64 = pen[i][j] + nbrs.iter().map(|&(a, b)| pen[a][b]).sum::<f64>();
            let c = g.uv[i][j];
            // The decrease of the local penalty sum if (i, j) moved to q.
            let trial = |q: [f64; 2]| -> Option<Candidate> {
                if !(q[0] >= u0 && q[0] <= u1 && q[1] >= v0 && q[1] <= v1) {
                    return None;
                }
                let xq = s.eval(&q[0], &q[1]);
                if !xq.iter().all(|v| v.is_finite()) {
                    return None;
                }
                let own = g.penalty(i, j, Some(((i, j), &xq)));
                let others: Vec<f64> = nbrs
                    .iter()
                    .map(|&(a, b)| g.penalty(a, b, Some(((i, j), &xq))))
                    .collect();
                let dec = old - (own + others.iter().sum::<f64>());
                let len = (((q[0] - c[0]) / du).powi(2) + ((q[1] - c[1]) / dv).powi(2)).sqrt();
                Some(Candidate {
                    dec,
                    q,
                    xq,
                    own,
                    others,
                    len,
                })
            };
            // First the Newton step on the point's own two ratio conditions (a finite move
            // like any other, accepted by the same rule), then the pattern of 8 steps.
            let mut best = newton(s, g, i, j, cap, [du, dv]).and_then(trial);
            if best.as_ref().is_none_or(|b| b.dec < p.delta) {
                best = None;
                for (dx, dy) in DIRS {
                    if let Some(t) = trial([c[0] + step * du * dx, c[1] + step * dv * dy])
                        && best.as_ref().is_none_or(|b| t.dec > b.dec)
                    {
                        best = Some(t);
                    }
                }
            }
            match best {
                Some(b) if b.dec >= p.delta => {
                    g.uv[i][j] = b.q;
                    g.x[i][j] = b.xq;
                    pen[i][j] = b.own;
                    for (&(a, bb), v) in nbrs.iter().zip(b.others) {
                        pen[a][bb] = v;
                    }
                    st.moves += 1;
                    moved += b.len;
                    if st.moves >= p.max_moves {
                        st.converged = false;
                        break;
                    }
                }
                _ => {
                    step /= 2.0;
                    if step < floor {
                        break;
                    }
                }
            }
        }
        h[i][j] = p.min_step;
        if !st.converged {
            break;
        }
        if moved > 0.0 {
            for &(a, b) in &nbrs {
                dirty[a][b] = true;
                h[a][b] = h[a][b].max(moved.min(0.25));
                heap.push((pen[a][b].to_bits(), a * m + b));
            }
        }
    }
    st.penalty_end = pen.iter().flatten().sum();
    Ok(st)
}
