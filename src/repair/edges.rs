//! Patch corners and boundary edges (paper §3: "each patch is four-sided; triangular patches
//! are degenerate four-sided patches, where one edge is collapsed to a corner").
//!
//! Corners and edges run counter-clockwise in the parameter domain `[u0,u1]×[v0,v1]`:
//! corner 0 = (u0,v0), 1 = (u1,v0), 2 = (u1,v1), 3 = (u0,v1); edge `k` runs from corner `k`
//! to corner `k+1`: 0 south (v = v0), 1 east (u = u1), 2 north (v = v1), 3 west (u = u0).

use crate::geom::Hom;
pub use crate::spline::project::CurveFoot;
use crate::spline::{BSplineCurve, NurbsCurve, NurbsSurface};

/// Names of the edges, by index.
pub const EDGE_NAMES: [&str; 4] = ["south", "east", "north", "west"];

/// The boundary edge `k` of a patch as a NURBS curve (exact: the boundary row or column of
/// the clamped net), oriented from corner `k` to corner `k+1`.
pub fn edge_curve(s: &NurbsSurface<f64, 3>, k: usize) -> NurbsCurve<f64, 3> {
    let h = &s.hom;
    let (nu, nv) = (h.nu(), h.nv());
    let (row, knots): (Vec<Hom<f64, 3>>, Vec<f64>) = match k {
        0 => (
            (0..nu).map(|i| h.at(i, 0).clone()).collect(),
            h.ku.knots().to_vec(),
        ),
        1 => (
            (0..nv).map(|j| h.at(nu - 1, j).clone()).collect(),
            h.kv.knots().to_vec(),
        ),
        2 => (
            (0..nu).rev().map(|i| h.at(i, nv - 1).clone()).collect(),
            mirror(h.ku.knots()),
        ),
        _ => (
            (0..nv).rev().map(|j| h.at(0, j).clone()).collect(),
            mirror(h.kv.knots()),
        ),
    };
    let degree = if k.is_multiple_of(2) {
        h.ku.degree()
    } else {
        h.kv.degree()
    };
    NurbsCurve {
        hom: BSplineCurve {
            // The surface's own (valid) knots, or their mirror image (order-preserving).
            knots: crate::spline::KnotVector::new_unchecked(knots, degree),
            control: row,
        },
    }
}

/// Knots of the reversed curve: `a + b - k` in reverse order.
fn mirror(k: &[f64]) -> Vec<f64> {
    let (a, b) = (k[0], k[k.len() - 1]);
    k.iter().rev().map(|x| a + b - x).collect()
}

/// Corner points 0..3.
pub fn corners(s: &NurbsSurface<f64, 3>) -> [[f64; 3]; 4] {
    let (u0, u1, v0, v1) = s.hom.domain();
    [
        s.eval(&u0, &v0),
        s.eval(&u1, &v0),
        s.eval(&u1, &v1),
        s.eval(&u0, &v1),
    ]
}

/// Parameters `(u, v)` of the point at curve parameter `t` of edge `k` (the edge's own
/// parameter runs over the surface's knot range in that direction, reversed for north/west).
pub fn edge_uv(s: &NurbsSurface<f64, 3>, k: usize, t: f64) -> [f64; 2] {
    let (u0, u1, v0, v1) = s.hom.domain();
    match k {
        0 => [t, v0],
        1 => [u1, t],
        2 => [u0 + u1 - t, v1],
        _ => [u0, v0 + v1 - t],
    }
}

/// Whether the edge is collapsed to a point (all its control points equal).
pub fn collapsed(c: &NurbsCurve<f64, 3>) -> bool {
    let (pts, _) = c.points_weights();
    pts.windows(2).all(|w| w[0] == w[1])
}

/// `n` points on the curve, equally spaced in arc length (measured on a 16·n polyline), with
/// their curve parameters.
pub fn arc_length_samples(c: &NurbsCurve<f64, 3>, n: usize) -> Vec<(f64, [f64; 3])> {
    let (t0, t1) = c.hom.domain();
    let m = 16 * n.max(2);
    let ts: Vec<f64> = (0..=m)
        .map(|i| t0 + (t1 - t0) * i as f64 / m as f64)
        .collect();
    let ps: Vec<[f64; 3]> = ts.iter().map(|t| c.eval(t)).collect();
    let mut acc = vec![0.0];
    for w in ps.windows(2) {
        let d = ((w[1][0] - w[0][0]).powi(2)
            + (w[1][1] - w[0][1]).powi(2)
            + (w[1][2] - w[0][2]).powi(2))
        .sqrt();
        acc.push(acc[acc.len() - 1] + d);
    }
    let total = acc[m];
    (0..n)
        .map(|i| {
            let target = if n == 1 {
                0.0
            } else {
                total * i as f64 / (n - 1) as f64
            };
            let k = acc.partition_point(|a| *a < target).min(m);
            let t = if k == 0 || total == 0.0 {
                ts[k]
            } else {
                let f = (target - acc[k - 1]) / (acc[k] - acc[k - 1]).max(f64::MIN_POSITIVE);
                ts[k - 1] + f * (ts[k] - ts[k - 1])
            };
            (t, c.eval(&t))
        })
        .collect()
}

/// Closest point of curve `c` to `x` ([`CurveFoot`] for one query).
pub fn closest_on_curve(c: &NurbsCurve<f64, 3>, x: &[f64; 3]) -> (f64, [f64; 3], f64) {
    CurveFoot::new(c).closest(x)
}
