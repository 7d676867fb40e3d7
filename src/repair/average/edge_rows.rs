//! The boundary rows of step 3 (paper §4, matrix (2) of §6): net indices of an edge's control
//! points, the compatibility test that decides whether two rows can be averaged control point
//! by control point, and the bit-for-bit check that the shared edges came out identical.

use crate::repair::edges::edge_curve;
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

/// Whether the two edges' rows can be averaged control point by control point: same degree,
/// number of control points, normalized knots (within 1e-12) and weights (within a relative
/// 1e-12), mirrored when the edges run opposite ways.
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
    // Weights equal up to rounding (a relative 1e-12): the mean row, written to both
    // patches, then has one weight per control point on both sides.
    ka.iter().zip(&kb).all(|(x, y)| (x - y).abs() <= 1e-12)
        && wa
            .iter()
            .zip(&wb)
            .all(|(x, y)| (x - y).abs() <= 1e-12 * x.abs().max(y.abs()))
}

fn get_point(s: &NurbsSurface<f64, 3>, (i, j): (usize, usize)) -> [f64; 3] {
    let h = s.hom.at(i, j);
    [h.wp[0] / h.w, h.wp[1] / h.w, h.wp[2] / h.w]
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
