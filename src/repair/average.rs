//! Step 3 — boundary averaging (paper §4, and matrix (2) of §6 as corrected in EQUATIONS.md
//! §C: rows/columns on shared borders are replaced by the average of the coincident rows, four
//! at a shared corner).
//!
//! Corners: every cluster of corners joined by connections is moved to the cluster's mean
//! (the paper's step (iv): "we average the n individual, distinct corner points"). Edges: for
//! a connected pair whose boundary rows are compatible (same degree, same number of control
//! points, the same knots after normalization, mirrored when the edges run opposite ways),
//! each interior boundary control point of the pair is replaced by the mean of the two, computed
//! once and written to both patches. The shared boundary curves are then the same control
//! points and knots, bit for bit (checked). Incompatible pairs are left unchanged and reported
//! (the paper's closest-point midpoints and re-interpolation would be needed there).

use super::connectivity::Connection;
use super::edges::{corners, edge_curve};
use crate::spline::NurbsSurface;

/// Net indices `(i, j)` of the control points of edge `k`, in the edge's direction.
pub fn edge_indices(s: &NurbsSurface<f64, 3>, k: usize) -> Vec<(usize, usize)> {
    let (nu, nv) = (s.hom.nu(), s.hom.nv());
    match k {
        0 => (0..nu).map(|i| (i, 0)).collect(),
        1 => (0..nv).map(|j| (nu - 1, j)).collect(),
        2 => (0..nu).rev().map(|i| (i, nv - 1)).collect(),
        _ => (0..nv).rev().map(|j| (0, j)).collect(),
    }
}

/// Knots mapped affinely onto `[0, 1]`.
pub(crate) fn normalized(k: &[f64]) -> Vec<f64> {
    let (a, b) = (k[0], k[k.len() - 1]);
    k.iter().map(|x| (x - a) / (b - a)).collect()
}

/// Whether the two edges' rows can be averaged control point by control point.
pub fn compatible(
    p: &NurbsSurface<f64, 3>,
    ep: usize,
    q: &NurbsSurface<f64, 3>,
    eq: usize,
    same_direction: bool,
) -> bool {
    let (a, b) = (edge_curve(p, ep), edge_curve(q, eq));
    if a.hom.knots.degree() != b.hom.knots.degree() || a.hom.control.len() != b.hom.control.len() {
        return false;
    }
    let ka = normalized(a.hom.knots.knots());
    let mut kb = normalized(b.hom.knots.knots());
    if !same_direction {
        kb = kb.iter().rev().map(|x| 1.0 - x).collect();
    }
    let wa: Vec<f64> = a.hom.control.iter().map(|h| h.w).collect();
    let mut wb: Vec<f64> = b.hom.control.iter().map(|h| h.w).collect();
    if !same_direction {
        wb.reverse();
    }
    ka.iter().zip(&kb).all(|(x, y)| (x - y).abs() <= 1e-12) && wa == wb
}

fn set_point(s: &mut NurbsSurface<f64, 3>, (i, j): (usize, usize), x: [f64; 3]) {
    let nv = s.hom.nv();
    let h = &mut s.hom.net[i * nv + j];
    h.wp = [x[0] * h.w, x[1] * h.w, x[2] * h.w];
}

fn get_point(s: &NurbsSurface<f64, 3>, (i, j): (usize, usize)) -> [f64; 3] {
    let h = s.hom.at(i, j);
    [h.wp[0] / h.w, h.wp[1] / h.w, h.wp[2] / h.w]
}

/// What averaging did.
#[derive(Clone, Debug, Default, serde::Serialize)]
pub struct AveragingOutcome {
    pub corner_clusters: usize,
    pub corners_moved: usize,
    pub max_corner_move: f64,
    pub edges_averaged: usize,
    /// Connected pairs left as they were (incompatible rows).
    pub edges_incompatible: Vec<Connection>,
    pub max_control_point_move: f64,
}

/// Average corners and compatible shared rows in place.
pub fn average(patches: &mut [NurbsSurface<f64, 3>], connected: &[Connection]) -> AveragingOutcome {
    let mut out = AveragingOutcome::default();
    // Corner clusters by union-find over connections (each joins two pairs of corners).
    let n = patches.len() * 4;
    let mut parent: Vec<usize> = (0..n).collect();
    fn find(p: &mut [usize], x: usize) -> usize {
        let mut r = x;
        while p[r] != r {
            r = p[r];
        }
        let mut y = x;
        while p[y] != r {
            let nx = p[y];
            p[y] = r;
            y = nx;
        }
        r
    }
    for c in connected {
        let (pa, pb) = (4 * c.p + c.ep, 4 * c.p + (c.ep + 1) % 4);
        let (qa, qb) = (4 * c.q + c.eq, 4 * c.q + (c.eq + 1) % 4);
        let pairs = if c.same_direction {
            [(pa, qa), (pb, qb)]
        } else {
            [(pa, qb), (pb, qa)]
        };
        for (x, y) in pairs {
            let (rx, ry) = (find(&mut parent, x), find(&mut parent, y));
            if rx != ry {
                parent[rx.max(ry)] = rx.min(ry);
            }
        }
    }
    let cs: Vec<[[f64; 3]; 4]> = patches.iter().map(corners).collect();
    let mut clusters: std::collections::BTreeMap<usize, Vec<usize>> =
        std::collections::BTreeMap::new();
    for x in 0..n {
        let r = find(&mut parent, x);
        clusters.entry(r).or_default().push(x);
    }
    let corner_index = |s: &NurbsSurface<f64, 3>, c: usize| -> (usize, usize) {
        let (nu, nv) = (s.hom.nu(), s.hom.nv());
        [(0, 0), (nu - 1, 0), (nu - 1, nv - 1), (0, nv - 1)][c]
    };
    for members in clusters.values().filter(|m| m.len() > 1) {
        out.corner_clusters += 1;
        let mut mean = [0.0; 3];
        for &m in members {
            for k in 0..3 {
                mean[k] += cs[m / 4][m % 4][k];
            }
        }
        let mean = mean.map(|v| v / members.len() as f64);
        for &m in members {
            let old = cs[m / 4][m % 4];
            let d = ((old[0] - mean[0]).powi(2)
                + (old[1] - mean[1]).powi(2)
                + (old[2] - mean[2]).powi(2))
            .sqrt();
            out.max_corner_move = out.max_corner_move.max(d);
            out.corners_moved += usize::from(d > 0.0);
            let idx = corner_index(&patches[m / 4], m % 4);
            set_point(&mut patches[m / 4], idx, mean);
        }
    }
    // Interior boundary control points of compatible pairs.
    for c in connected {
        if !compatible(&patches[c.p], c.ep, &patches[c.q], c.eq, c.same_direction) {
            out.edges_incompatible.push(*c);
            continue;
        }
        let ip = edge_indices(&patches[c.p], c.ep);
        let mut iq = edge_indices(&patches[c.q], c.eq);
        if !c.same_direction {
            iq.reverse();
        }
        let m = ip.len();
        for k in 1..m - 1 {
            let (a, b) = (
                get_point(&patches[c.p], ip[k]),
                get_point(&patches[c.q], iq[k]),
            );
            let mean: [f64; 3] = std::array::from_fn(|d| 0.5 * (a[d] + b[d]));
            let mv =
                ((a[0] - mean[0]).powi(2) + (a[1] - mean[1]).powi(2) + (a[2] - mean[2]).powi(2))
                    .sqrt();
            out.max_control_point_move = out.max_control_point_move.max(mv);
            set_point(&mut patches[c.p], ip[k], mean);
            set_point(&mut patches[c.q], iq[k], mean);
        }
        out.edges_averaged += 1;
    }
    out
}

/// Whether the two edges are the same curve bit for bit: equal Cartesian control points in
/// traversal order, equal weights, and normalized knots equal (mirrored for opposite edges).
pub fn identical(
    p: &NurbsSurface<f64, 3>,
    ep: usize,
    q: &NurbsSurface<f64, 3>,
    eq: usize,
    same_direction: bool,
) -> bool {
    let (ip, mut iq) = (edge_indices(p, ep), edge_indices(q, eq));
    if ip.len() != iq.len() {
        return false;
    }
    if !same_direction {
        iq.reverse();
    }
    ip.iter().zip(&iq).all(|(a, b)| {
        get_point(p, *a) == get_point(q, *b) && p.hom.at(a.0, a.1).w == q.hom.at(b.0, b.1).w
    }) && compatible(p, ep, q, eq, same_direction)
}
