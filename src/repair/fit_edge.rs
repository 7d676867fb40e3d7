//! Step 3 — the shared curve of two incompatible boundary rows (paper §4, steps (i)–(v)):
//!
//! (i) each of the two edges is discretized by points uniform in arc length; (ii) each point's
//! closest point on the opposing edge is found; (iii) the midpoints of the pairs are the data,
//! each at the mean of the two points' normalized parameters along the edge (in the knot
//! class's orientation, so the shared curve keeps both patches' parametrizations as far as
//! they agree and the interior of either patch is sheared least); (iv) the two ends are the
//! averaged corners of all patches there, and the midpoints follow the two ends' moves by
//! their linear blend in the parameter; (v) a B-spline of the class degree (cubic, or higher when a member is)
//! is fitted to the data by least squares with interpolated ends. The fit starts on the union
//! of the two rows' knots (after elevation), a space that holds both original edges; while the
//! largest residual exceeds the tolerance, every span holding such a residual is split at its
//! middle (the data are uniform in arc length, so the knots follow arc length where the
//! space was too coarse). The largest residual at the data is the stated fit error: evidence
//! (at the data points), not a bound between them.

use super::blend::greville;
use super::classes::{KnotClass, Member, expand, member_runs, side};
use super::edges::{CurveFoot, arc_length_samples, edge_curve, edge_uv};
use crate::geom::{Hom, dist};
use crate::spline::elevate::{elevate_curve_to, refine_to};
use crate::spline::fit_knots::fit_rational_with_knots;
use crate::spline::{BSplineCurve, KnotVector, NurbsSurface};

/// Largest number of splitting rounds.
const ROUNDS: usize = 8;

/// A fitted shared curve on `[0, 1]` in the class orientation (homogeneous control points:
/// rational when the two rows are).
#[derive(Clone, Debug)]
pub struct EdgeFit {
    pub curve: BSplineCurve<Hom<f64, 3>>,
    /// Largest distance from a midpoint to the curve at its parameter (evidence).
    pub fit_error: f64,
    /// Midpoints fitted (corners included).
    pub data: usize,
    /// Knots added to the two rows' union by splitting.
    pub knots_added: usize,
}

/// Normalized parameter of `(u, v)` along `dir`, in the orientation of `flipped`.
fn oriented_param(s: &NurbsSurface<f64, 3>, dir: usize, flipped: bool, uv: [f64; 2]) -> f64 {
    let (u0, u1, v0, v1) = s.hom.domain();
    let x = if dir == 0 {
        (uv[0] - u0) / (u1 - u0)
    } else {
        (uv[1] - v0) / (v1 - v0)
    };
    let x = x.clamp(0.0, 1.0);
    if flipped { 1.0 - x } else { x }
}

/// The corner (0..3) of edge `e` at the class-parameter end `end` (0 or 1).
pub fn end_corner(e: usize, flipped: bool, end: usize) -> usize {
    let (_, forward) = side(e);
    let own_end = end ^ usize::from(flipped);
    if (own_end == 0) == forward {
        e
    } else {
        (e + 1) % 4
    }
}

/// Midpoint data of two edges: `(parameters, points)`, sorted, the ends `c0`, `c1` at 0, 1.
#[allow(clippy::too_many_arguments)]
fn midpoints(
    p: &NurbsSurface<f64, 3>,
    ep: usize,
    mp: &Member,
    q: &NurbsSurface<f64, 3>,
    eq: usize,
    mq: &Member,
    n: usize,
    ends: [[f64; 3]; 2],
) -> (Vec<f64>, Vec<[f64; 3]>) {
    let mut data: Vec<(f64, [f64; 3])> = Vec::with_capacity(2 * n + 2);
    for ((a, ea, ma), (b, eb, mb)) in [((p, ep, mp), (q, eq, mq)), ((q, eq, mq), (p, ep, mp))] {
        let (ca, cb) = (edge_curve(a, ea), edge_curve(b, eb));
        let foot = CurveFoot::new(&cb);
        for (t, x) in arc_length_samples(&ca, n) {
            let (tb, y, _) = foot.closest(&x);
            let sa = oriented_param(a, ma.dir, ma.flipped, edge_uv(a, ea, t));
            let sb = oriented_param(b, mb.dir, mb.flipped, edge_uv(b, eb, tb));
            let mid: [f64; 3] = std::array::from_fn(|k| 0.5 * (x[k] + y[k]));
            data.push((0.5 * (sa + sb), mid));
        }
    }
    data.sort_by(|a, b| a.0.total_cmp(&b.0));
    // The pair's own ends (the mean of its two corners) move to the averaged corners of all
    // patches there; the midpoints follow by the linear blend of the two moves.
    let corner = |s: &NurbsSurface<f64, 3>, e: usize, m: &Member, end: usize| {
        super::edges::corners(s)[end_corner(e, m.flipped, end)]
    };
    let shift: [[f64; 3]; 2] = [0, 1].map(|end| {
        let (a, b) = (corner(p, ep, mp, end), corner(q, eq, mq, end));
        std::array::from_fn(|k| ends[end][k] - 0.5 * (a[k] + b[k]))
    });
    for (s, x) in &mut data {
        for k in 0..3 {
            x[k] += (1.0 - *s) * shift[0][k] + *s * shift[1][k];
        }
    }
    let mut t = vec![0.0];
    let mut pts = vec![ends[0]];
    for (s, x) in data {
        if s > t[t.len() - 1] + 1e-9 && s < 1.0 - 1e-9 {
            t.push(s);
            pts.push(x);
        }
    }
    t.push(1.0);
    pts.push(ends[1]);
    (t, pts)
}

fn residuals(c: &BSplineCurve<Hom<f64, 3>>, t: &[f64], pts: &[[f64; 3]]) -> Vec<f64> {
    t.iter()
        .zip(pts)
        .map(|(s, x)| {
            let h = c.eval(s);
            dist(&h.wp.map(|v| v / h.w), x)
        })
        .collect()
}

/// The boundary row of edge `e` as a homogeneous curve on `[0, 1]` in the class orientation,
/// its knots snapped to the class, raised to the class degree.
fn class_row(
    class: &KnotClass,
    s: &NurbsSurface<f64, 3>,
    e: usize,
    m: &Member,
) -> Option<BSplineCurve<Hom<f64, 3>>> {
    let h = &s.hom;
    let mut c = match e {
        0 => h.column(0),
        2 => h.column(h.nv() - 1),
        1 => h.row(h.nu() - 1),
        _ => h.row(0),
    };
    let own = super::average::normalized(c.knots.knots());
    let knots: Vec<f64> = if m.flipped {
        c.control.reverse();
        own.iter().rev().map(|x| class.snap(1.0 - x)).collect()
    } else {
        own.iter().map(|x| class.snap(*x)).collect()
    };
    let p = c.knots.degree();
    c.knots = KnotVector::new(knots, p, c.control.len()).ok()?;
    Some(elevate_curve_to(&c, class.degree))
}

/// Weights for the space `space`: the mean of the two rows' weights there, or of their weight
/// functions at the space's Greville abscissae when a row is not in the space; the ends those
/// of the corners. `None` when both rows are polynomial.
fn space_weights(
    rows: &[Option<BSplineCurve<Hom<f64, 3>>>; 2],
    space: &[(f64, usize)],
    ends: &[([f64; 3], f64); 2],
) -> Option<Vec<f64>> {
    let k = expand(space);
    let [Some(a), Some(b)] = rows else {
        return None;
    };
    if a.control.iter().chain(&b.control).all(|h| h.w == 1.0) && ends.iter().all(|e| e.1 == 1.0) {
        return None;
    }
    let mut w: Vec<f64> = match (refine_to(a, &k), refine_to(b, &k)) {
        (Some(ra), Some(rb)) => (ra.control.iter().zip(&rb.control))
            .map(|(x, y)| 0.5 * (x.w + y.w))
            .collect(),
        // A row that the space does not hold (the fit space lost one of its knots): the two
        // rows' weight functions (their denominators) at the space's Greville abscissae,
        // averaged, so the shape those weights carry stays near both rows' (weights 1 there
        // bent conic rows by 0.4 on occt-hammer.iges).
        _ => greville(&k, a.degree().max(1))
            .iter()
            .map(|g| 0.5 * (a.eval(g).w + b.eval(g).w))
            .collect(),
    };
    let last = w.len().checked_sub(1)?;
    w[0] = ends[0].1;
    w[last] = ends[1].1;
    Some(w)
}

/// Fit the shared curve of edge `ep` of `p` and edge `eq` of `q` (members `mp`, `mq` of
/// `class`), with tolerance `tol` on the residuals; knots added by splitting go into `class`.
/// `ends` are the averaged corners at class parameters 0 and 1 with their weights. When the
/// rows are rational, the curve's weights are the mean of the two rows' weights in the fit
/// space (the fit stays linear in the control points). `None` when no space gives a solvable
/// fit.
#[allow(clippy::too_many_arguments)]
pub fn fit_edge(
    class: &mut KnotClass,
    p: &NurbsSurface<f64, 3>,
    ep: usize,
    mp: &Member,
    q: &NurbsSurface<f64, 3>,
    eq: usize,
    mq: &Member,
    ends: [([f64; 3], f64); 2],
    tol: f64,
) -> Option<EdgeFit> {
    let rows = [class_row(class, p, ep, mp), class_row(class, q, eq, mq)];
    let d = class.degree;
    // The union of the two rows' knots (after elevation, snapped to the class).
    let mut space: Vec<(f64, usize)> = member_runs(class, p, mp);
    for (v, k) in member_runs(class, q, mq) {
        match space.iter_mut().find(|r| r.0 == v) {
            Some(r) => r.1 = r.1.max(k),
            None => space.push((v, k)),
        }
    }
    space.sort_by(|a, b| a.0.total_cmp(&b.0));
    let n_ctrl = |sp: &[(f64, usize)]| expand(sp).len() - d - 1;
    let n = (3 * n_ctrl(&space)).clamp(48, 400);
    let (t, pts) = midpoints(p, ep, mp, q, eq, mq, n, [ends[0].0, ends[1].0]);
    let mut added = 0;
    let mut best: Option<(BSplineCurve<Hom<f64, 3>>, f64)> = None;
    for _ in 0..ROUNDS {
        let kv = KnotVector::new(expand(&space), d, n_ctrl(&space)).ok()?;
        let w = space_weights(&rows, &space, &ends);
        let fit = fit_rational_with_knots(&pts, &t, &kv, w.as_deref())
            .ok()
            .filter(|c| c.control.iter().flatten().all(|x| x.is_finite()))
            .map(|c| BSplineCurve {
                knots: c.knots,
                control: c
                    .control
                    .iter()
                    .enumerate()
                    .map(|(i, x)| {
                        let wi = w.as_ref().map_or(1.0, |w| w[i]);
                        Hom::from_point(x, &wi)
                    })
                    .collect(),
            });
        let Some(c) = fit else {
            // Unsolvable (a basis function without data): drop the interior value of the
            // shortest span and try again.
            if space.len() <= 2 {
                return None;
            }
            let k = (1..space.len() - 1)
                .min_by(|&a, &b| {
                    let w = |i: usize| (space[i + 1].0 - space[i - 1].0).abs();
                    w(a).total_cmp(&w(b))
                })
                .unwrap_or(1);
            space.remove(k);
            continue;
        };
        let r = residuals(&c, &t, &pts);
        let err = r.iter().copied().fold(0.0, f64::max);
        if best.as_ref().is_none_or(|b| err < b.1) {
            best = Some((c, err));
        }
        if err <= tol {
            break;
        }
        // Split every span holding a residual above the tolerance at its middle.
        let mut split = Vec::new();
        for w in space.windows(2) {
            let (a, b) = (w[0].0, w[1].0);
            let bad = t
                .iter()
                .zip(&r)
                .any(|(s, e)| *s >= a && *s <= b && *e > tol);
            let mid = class.snap(0.5 * (a + b));
            // A span too short to split (or data too sparse in it) is left.
            let inside = t.iter().filter(|s| **s > a && **s < b).count();
            if bad && mid > a && mid < b && inside > d + 1 {
                split.push(mid);
            }
        }
        if split.is_empty() {
            break;
        }
        for x in split {
            class.add(x, 1);
            space.push((x, 1));
            added += 1;
        }
        space.sort_by(|a, b| a.0.total_cmp(&b.0));
    }
    let (curve, fit_error) = best?;
    // The space may have lost values while the class kept them: the fitted curve is refined
    // to the class knots later, which requires its values to be class values (they are).
    Some(EdgeFit {
        curve,
        fit_error,
        data: t.len(),
        knots_added: added,
    })
}
