//! Joining neighbouring approximants along a shared boundary curve.
//!
//! Both neighbours have the same count along the shared side ([`super::layout::build_all`]).
//! The boundary grid points `y` of the later approximant (in layout order) along the curve
//! are replaced by those of the earlier one (matched in the curve's own direction), and its
//! interpolant (14)–(16) is rebuilt. The boundary row of control points of (14) is a
//! function of the boundary points alone (the row scheme of step 5), so the rows should
//! now agree; this is **checked** bit for bit, and where they do not, the later row is
//! overwritten by the earlier one (reported). Overwriting a boundary row keeps the C1
//! conditions of step 5 (they are column-wise averages within the row and across it; the
//! copied row satisfies its own). Interior corners shared by several curves take the value
//! of the earliest approximant: the copies are repeated until nothing changes.
//!
//! The error of every changed approximant is measured again (17): evidence.

use super::error::{measure, prove};
use super::layout::Topology;
use super::project::triangulate;
use super::{Approximant, CoonsError, Params, bicubic};
use crate::geom::dist;
use crate::model::Model;
use crate::spline::NurbsSurface;
use serde::Serialize;

/// What the join did to one shared curve.
#[derive(Clone, Debug, Serialize)]
pub struct SharedCurve {
    pub curve: String,
    /// The two approximants (layout index) and their sides.
    pub approximants: [usize; 2],
    pub sides: [usize; 2],
    /// Grid intervals along the curve (equal on both sides).
    pub count: usize,
    /// Largest distance between the two boundary rows of control points before the join
    /// (the gap between the neighbours).
    pub gap: f64,
    /// Largest distance a boundary grid point of the second approximant moved.
    pub moved: f64,
    /// `"already identical"`, `"equalized"` (boundary points copied, rows then identical) or
    /// `"row overwritten"` (the rebuilt rows still differed; the second's row was replaced).
    pub status: String,
    /// The two boundary rows of control points are identical bit for bit (checked).
    pub identical: bool,
}

/// Grid indices `(I, J)` of side `k` of an `M × N` grid, in the curve's own direction
/// (`reversed`: the loop traverses the curve backwards). With `3M × 3N` it gives the
/// control-net indices of the side.
pub fn side_indices(m: usize, n: usize, k: usize, reversed: bool) -> Vec<(usize, usize)> {
    let mut v: Vec<(usize, usize)> = match k {
        0 => (0..=m).map(|i| (i, 0)).collect(),
        1 => (0..=n).map(|j| (m, j)).collect(),
        2 => (0..=m).rev().map(|i| (i, n)).collect(),
        _ => (0..=n).rev().map(|j| (0, j)).collect(),
    };
    if reversed {
        v.reverse();
    }
    v
}

fn net(ap: &Approximant) -> (Vec<[f64; 3]>, usize) {
    (ap.surface.points_weights().0, 3 * ap.report.n + 1)
}

/// The boundary row of control points of side `k`, in the curve's direction.
fn control_row(ap: &Approximant, k: usize) -> Vec<[f64; 3]> {
    let (pts, cv) = net(ap);
    let r = &ap.report;
    side_indices(3 * r.m, 3 * r.n, k, r.reversed[k])
        .into_iter()
        .map(|(i, j)| pts[i * cv + j])
        .collect()
}

fn grid_row(ap: &Approximant, k: usize) -> Vec<(usize, usize)> {
    let r = &ap.report;
    side_indices(r.m, r.n, k, r.reversed[k])
}

fn max_dist(a: &[[f64; 3]], b: &[[f64; 3]]) -> f64 {
    a.iter().zip(b).map(|(p, q)| dist(p, q)).fold(0.0, f64::max)
}

/// Join the approximants along the shared curves of `topo`; re-measure the changed ones.
pub fn join(
    model: &Model,
    aps: &mut [Approximant],
    topo: &Topology,
    params: &Params,
) -> Result<Vec<SharedCurve>, CoonsError> {
    let mut out = Vec::new();
    let mut changed = vec![false; aps.len()];
    for (curve, [p, q]) in &topo.shared {
        let (a, b) = (p.approximant, q.approximant);
        let (ra, rb) = (control_row(&aps[a], p.side), control_row(&aps[b], q.side));
        let count = grid_row(&aps[a], p.side).len() - 1;
        if ra.len() != rb.len() {
            return Err(CoonsError::Spline(format!(
                "curve {curve}: the neighbours have {} and {} control points along it",
                ra.len(),
                rb.len()
            )));
        }
        out.push(SharedCurve {
            curve: curve.clone(),
            approximants: [a, b],
            sides: [p.side, q.side],
            count,
            gap: max_dist(&ra, &rb),
            moved: 0.0,
            status: String::new(),
            identical: ra == rb,
        });
    }
    // Copy the boundary points from the earlier to the later approximant until nothing
    // changes (shared corners settle on the earliest approximant's value).
    for _ in 0..=aps.len() {
        let mut any = false;
        for (s, (_, [p, q])) in out.iter_mut().zip(&topo.shared) {
            let (a, b) = if p.approximant < q.approximant {
                (p, q)
            } else {
                (q, p)
            };
            let src: Vec<([f64; 3], bool)> = grid_row(&aps[a.approximant], a.side)
                .into_iter()
                .map(|(i, j)| {
                    let ap = &aps[a.approximant];
                    (*ap.points.at(i, j), *ap.artificial.at(i, j))
                })
                .collect();
            let dst = grid_row(&aps[b.approximant], b.side);
            let t = &mut aps[b.approximant];
            for ((i, j), (y, art)) in dst.into_iter().zip(src) {
                if *t.points.at(i, j) != y {
                    s.moved = s.moved.max(dist(t.points.at(i, j), &y));
                    t.points.set(i, j, y);
                    any = true;
                    changed[b.approximant] = true;
                }
                if art && !*t.artificial.at(i, j) {
                    t.artificial.set(i, j, true);
                }
            }
        }
        if !any {
            break;
        }
    }
    for (a, ap) in aps.iter_mut().enumerate() {
        if changed[a] {
            ap.surface = bicubic::interpolant(&ap.points)?;
        }
    }
    // The check: the rows are identical bit for bit; otherwise overwrite the later row.
    for (s, (_, [p, q])) in out.iter_mut().zip(&topo.shared) {
        let (a, b) = if p.approximant < q.approximant {
            (p, q)
        } else {
            (q, p)
        };
        let ra = control_row(&aps[a.approximant], a.side);
        let rb = control_row(&aps[b.approximant], b.side);
        if ra == rb {
            s.status = if s.identical {
                "already identical"
            } else {
                "equalized"
            }
            .into();
        } else {
            let ap = &mut aps[b.approximant];
            let (mut pts, cv) = net(ap);
            let r = &ap.report;
            for ((i, j), c) in side_indices(3 * r.m, 3 * r.n, b.side, r.reversed[b.side])
                .into_iter()
                .zip(&ra)
            {
                pts[i * cv + j] = *c;
            }
            ap.surface = with_net(&ap.surface, pts, r.m, r.n)?;
            changed[b.approximant] = true;
            s.status = "row overwritten".into();
        }
        s.identical =
            control_row(&aps[a.approximant], a.side) == control_row(&aps[b.approximant], b.side);
    }
    for (a, ap) in aps.iter_mut().enumerate() {
        if changed[a] {
            remeasure(model, ap, params);
        }
    }
    Ok(out)
}

fn with_net(
    s: &NurbsSurface<f64, 3>,
    pts: Vec<[f64; 3]>,
    m: usize,
    n: usize,
) -> Result<NurbsSurface<f64, 3>, CoonsError> {
    let w = s.points_weights().1;
    NurbsSurface::new(
        bicubic::knots(m),
        3,
        bicubic::knots(n),
        3,
        3 * m + 1,
        3 * n + 1,
        pts,
        w,
    )
    .map_err(|e| CoonsError::Spline(e.to_string()))
}

/// Measure (17) again on the joined surface (the triangulation covers the box of its
/// control net enlarged by the offset distance and a tenth of the diagonal); the proven
/// claims are checked again.
fn remeasure(model: &Model, ap: &mut Approximant, params: &Params) {
    let (pts, _) = ap.surface.points_weights();
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in &pts {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let pad = ap.report.offset_distance + 0.1 * dist(&lo, &hi);
    let mesh = triangulate(model, (lo.map(|c| c - pad), hi.map(|c| c + pad)), {
        params.triangles_per_span
    });
    let (samples, ev) = measure(model, &mesh, &ap.surface, &ap.artificial);
    let r = &mut ap.report;
    r.proven = prove(&ap.surface, &ap.points);
    r.c1_defect = bicubic::c1_defect(&ap.surface, r.m, r.n);
    let ok = ev.max_error <= params.tol && ev.measured > 0;
    r.within_tol = ok && r.proven.interpolates_grid_points;
    r.reason = format!(
        "{}; after the join: measured error {:.3e} {} tol {:e} at {} samples (evidence)",
        r.reason,
        ev.max_error,
        if ok { "≤" } else { ">" },
        params.tol,
        ev.measured
    );
    r.evidence = ev;
    ap.samples = samples;
}
