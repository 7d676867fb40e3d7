//! Step 3 — boundary averaging (paper §4, and matrix (2) of §6 as corrected in docs/papers.md
//! §C: rows/columns on shared borders are replaced by the average of the coincident rows, four
//! at a shared corner).
//!
//! Corners (§4 (iv)): every cluster of corners joined by connections is moved to the
//! cluster's mean ("we average the n individual, distinct corner points"), written last and
//! the same homogeneous point in every patch of the cluster, whatever its valence.
//!
//! Edges: a connected pair whose boundary rows are compatible (same degree, number of control
//! points, knots after normalization, weights; mirrored when the edges run opposite ways) gets
//! each boundary control point replaced by the mean of the two (control-point averaging,
//! matrix (2)). Any other pair gets the shared curve of §4 (i)–(v) fitted to the closest-point
//! midpoints ([`super::fit_edge`]); both patches are first brought to a representation that
//! holds it — their knot class raised to the class degree and refined to the class knots
//! ([`super::classes`]) — and the curve's control points become the boundary row of both.
//! Either way the row is computed once and written to both patches: the shared edges are then
//! the same control points, weights and knots, bit for bit (checked: [`identical`]). The
//! interior follows the boundary ([`super::blend`]); the deviation from the original patch is
//! reported per patch.

use super::blend::{blend_interior, control_move, measured_deviation};
use super::classes::{KnotClass, MAX_CLASS_CONTROL_POINTS, Member, classes, refine_member, side};
use super::connectivity::Connection;
use super::edges::{collapsed, corners, edge_curve};
use super::fit_edge::{EdgeFit, end_corner, fit_edge};
use crate::geom::{Hom, dist};
use crate::spline::NurbsSurface;
use crate::spline::elevate::refine_to;
use crate::spline::mobius::unit_corner_weights;
use std::collections::{BTreeMap, HashMap};

mod edge_rows;
mod records;

pub(crate) use edge_rows::normalized;
pub use edge_rows::{compatible, edge_indices, identical};
pub use records::{AveragingOutcome, EdgeRecord, LeftEdge, PatchRecord};

fn put(s: &mut NurbsSurface<f64, 3>, (i, j): (usize, usize), h: &Hom<f64, 3>) {
    let nv = s.hom.nv();
    s.hom.net[i * nv + j] = h.clone();
}

/// Net indices of edge `e`'s row in the order of the patch's own parameter.
fn row_positions(s: &NurbsSurface<f64, 3>, e: usize) -> Vec<(usize, usize)> {
    let (nu, nv) = (s.hom.nu(), s.hom.nv());
    match e {
        0 => (0..nu).map(|i| (i, 0)).collect(),
        2 => (0..nu).map(|i| (i, nv - 1)).collect(),
        1 => (0..nv).map(|j| (nu - 1, j)).collect(),
        _ => (0..nv).map(|j| (0, j)).collect(),
    }
}

/// Net indices of edge `e`'s row in the order of the knot class (reversed for a flipped
/// member).
fn class_positions(s: &NurbsSurface<f64, 3>, e: usize, flipped: bool) -> Vec<(usize, usize)> {
    let mut r = row_positions(s, e);
    if flipped {
        r.reverse();
    }
    r
}

fn mean_hom(a: &Hom<f64, 3>, b: &Hom<f64, 3>) -> Hom<f64, 3> {
    Hom {
        wp: std::array::from_fn(|k| 0.5 * (a.wp[k] + b.wp[k])),
        w: 0.5 * (a.w + b.w),
    }
}

/// Corner clusters (union-find over connections, each joining two pairs of corners, and, with
/// `collapsed_too`, over collapsed edges, whose two corners are one point): corner id
/// `4 p + c` → cluster root.
fn corner_clusters(
    patches: &[NurbsSurface<f64, 3>],
    connected: &[Connection],
    collapsed_too: bool,
) -> Vec<usize> {
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
    let mut pairs: Vec<(usize, usize)> = Vec::new();
    for c in connected {
        let (pa, pb) = (4 * c.p + c.ep, 4 * c.p + (c.ep + 1) % 4);
        let (qa, qb) = (4 * c.q + c.eq, 4 * c.q + (c.eq + 1) % 4);
        if c.same_direction {
            pairs.extend([(pa, qa), (pb, qb)]);
        } else {
            pairs.extend([(pa, qb), (pb, qa)]);
        }
    }
    for (p, s) in patches.iter().enumerate().filter(|_| collapsed_too) {
        for e in 0..4 {
            if collapsed(&edge_curve(s, e)) {
                pairs.push((4 * p + e, 4 * p + (e + 1) % 4));
            }
        }
    }
    {
        for (x, y) in pairs {
            let (rx, ry) = (find(&mut parent, x), find(&mut parent, y));
            if rx != ry {
                parent[rx.max(ry)] = rx.min(ry);
            }
        }
    }
    (0..n).map(|x| find(&mut parent, x)).collect()
}

fn corner_index(s: &NurbsSurface<f64, 3>, c: usize) -> (usize, usize) {
    let (nu, nv) = (s.hom.nu(), s.hom.nv());
    [(0, 0), (nu - 1, 0), (nu - 1, nv - 1), (0, nv - 1)][c]
}

/// Average corners and shared rows in place; `gaps[k]` is the measured gap of
/// `connected[k]`.
pub fn average(
    patches: &mut [NurbsSurface<f64, 3>],
    connected: &[Connection],
    gaps: &[f64],
) -> AveragingOutcome {
    let mut out = AveragingOutcome::default();
    let original = patches.to_vec();
    // Corner weights brought to 1 where a reparametrization can (see the outcome's field).
    let mut unified = vec![false; patches.len()];
    for (p, s) in patches.iter_mut().enumerate() {
        if let Some(r) = unit_corner_weights(s) {
            *s = r;
            unified[p] = true;
            out.corner_weights_unified += 1;
        }
    }
    // Corner clusters and their means (§4 (iv)).
    // Positions: clusters through connections and collapsed edges. Weights: one per group of
    // corners joined by connections (the ends of shared rows, which must be one homogeneous
    // point); the two corners of a collapsed edge keep their own weights.
    let root = corner_clusters(patches, connected, true);
    let link = corner_clusters(patches, connected, false);
    let mut groups: BTreeMap<usize, Vec<usize>> = BTreeMap::new();
    for (x, r) in link.iter().enumerate() {
        groups.entry(*r).or_default().push(x);
    }
    let cs: Vec<[[f64; 3]; 4]> = patches.iter().map(corners).collect();
    let mut clusters: BTreeMap<usize, Vec<usize>> = BTreeMap::new();
    for (x, r) in root.iter().enumerate() {
        clusters.entry(*r).or_default().push(x);
    }
    let mut mean_of: HashMap<usize, [f64; 3]> = HashMap::new();
    for (r, members) in clusters.iter().filter(|(_, m)| m.len() > 1) {
        let mut mean = [0.0; 3];
        for &m in members {
            for k in 0..3 {
                mean[k] += cs[m / 4][m % 4][k];
            }
        }
        mean_of.insert(*r, mean.map(|v| v / members.len() as f64));
    }
    let corner_pt = |x: usize| mean_of.get(&root[x]).copied().unwrap_or(cs[x / 4][x % 4]);
    // One weight per cluster: the members' common corner weight, or their mean.
    let mut weight_of: HashMap<usize, f64> = HashMap::new();
    for (r, members) in groups.iter().filter(|(_, m)| m.len() > 1) {
        let ws: Vec<f64> = members
            .iter()
            .map(|&m| {
                let s = &patches[m / 4];
                let (i, j) = corner_index(s, m % 4);
                s.hom.at(i, j).w
            })
            .collect();
        // Equal weights stay; different ones meet at their mean (the least largest change of
        // any member's weight: a corner weight forced to 1 moved rational patches of
        // occt-hammer.iges by up to 3.8 mm to close gaps of 4e-5).
        let w = if ws.iter().all(|x| *x == ws[0]) {
            ws[0]
        } else {
            ws.iter().sum::<f64>() / ws.len() as f64
        };
        weight_of.insert(*r, w);
    }
    let cw: Vec<f64> = (0..4 * patches.len())
        .map(|x| {
            weight_of.get(&link[x]).copied().unwrap_or_else(|| {
                let s = &patches[x / 4];
                let (i, j) = corner_index(s, x % 4);
                s.hom.at(i, j).w
            })
        })
        .collect();
    let corner_w = |x: usize| cw[x];
    // Knot classes; a class is refined when it ties incompatible rows.
    let compat: Vec<bool> = connected
        .iter()
        .map(|c| compatible(&patches[c.p], c.ep, &patches[c.q], c.eq, c.same_direction))
        .collect();
    let incompatible: Vec<bool> = compat.iter().map(|c| !c).collect();
    out.incompatible_before = incompatible.iter().filter(|x| **x).count();
    let (mut cls, of) = classes(patches, connected, &incompatible);
    let member = |cls: &[KnotClass], p: usize, dir: usize| -> Option<Member> {
        let k = *of.get(&(p, dir))?;
        cls[k]
            .members
            .iter()
            .find(|m| m.patch == p && m.dir == dir)
            .copied()
    };
    let mut left: Vec<Option<String>> = vec![None; connected.len()];
    // Fitted shared curves (§4 (i)–(v)) for the incompatible pairs.
    let mut fits: Vec<Option<EdgeFit>> = vec![None; connected.len()];
    for (k, c) in connected.iter().enumerate() {
        if compat[k] {
            continue;
        }
        let ((dp, _), (dq, _)) = (side(c.ep), side(c.eq));
        let ci = of[&(c.p, dp)];
        if !cls[ci].consistent {
            left[k] = Some("the knot class's ties reverse orientation around a cycle: no common orientation for the shared rows".into());
            continue;
        }
        let (Some(mp), Some(mq)) = (member(&cls, c.p, dp), member(&cls, c.q, dq)) else {
            left[k] = Some("a patch direction is missing from its knot class".into());
            continue;
        };
        let ends = [0, 1].map(|e| {
            let x = 4 * c.p + end_corner(c.ep, mp.flipped, e);
            (corner_pt(x), corner_w(x))
        });
        let scale = dist(&ends[0].0, &ends[1].0).max(gaps[k]);
        let tol = (0.05 * gaps[k]).max(1e-9 * scale);
        // Without a fit (`None`) the pair is averaged control point by control point once both
        // rows are in the class's representation (below).
        fits[k] = fit_edge(
            &mut cls[ci],
            &patches[c.p],
            c.ep,
            &mp,
            &patches[c.q],
            c.eq,
            &mq,
            ends,
            tol,
        );
    }
    // Bring every member of a refined class to the class degree and knots.
    let mut refined_class = vec![false; cls.len()];
    let mut class_reason: Vec<Option<String>> = vec![None; cls.len()];
    for (ci, cl) in cls.iter().enumerate() {
        if !(cl.refine && cl.consistent) {
            continue;
        }
        let n = cl.knots().len() - cl.degree - 1;
        if n > MAX_CLASS_CONTROL_POINTS {
            class_reason[ci] = Some(format!(
                "the knot class ({} patch directions tied through shared edges) would need {n} control points per row (limit {MAX_CLASS_CONTROL_POINTS}): left rather than refined",
                cl.members.len()
            ));
            continue;
        }
        let trial: Option<Vec<NurbsSurface<f64, 3>>> = cl
            .members
            .iter()
            .map(|m| refine_member(cl, &patches[m.patch], m))
            .collect();
        if let Some(t) = trial {
            for (m, s) in cl.members.iter().zip(t) {
                patches[m.patch] = s;
            }
            refined_class[ci] = true;
            out.classes_refined += 1;
        }
    }
    let before = patches.to_vec();
    let mut replaced: Vec<Vec<usize>> = vec![Vec::new(); patches.len()];
    for (k, c) in connected.iter().enumerate() {
        if left[k].is_some() {
            continue;
        }
        let ((dp, _), (dq, _)) = (side(c.ep), side(c.eq));
        let ci = of[&(c.p, dp)];
        let rec = |method, fit: Option<&EdgeFit>, degree, n| EdgeRecord {
            connection: *c,
            method,
            gap_before: gaps[k],
            fit_error_evidence: fit.map(|f| f.fit_error),
            fit_data: fit.map(|f| f.data),
            knots_added: fit.map_or(0, |f| f.knots_added),
            degree,
            control_points: n,
        };
        if refined_class[ci] {
            let (Some(mp), Some(mq)) = (member(&cls, c.p, dp), member(&cls, c.q, dq)) else {
                left[k] = Some("a patch direction is missing from its knot class".into());
                continue;
            };
            let ip = class_positions(&patches[c.p], c.ep, mp.flipped);
            let iq = class_positions(&patches[c.q], c.eq, mq.flipped);
            let homs: Vec<Hom<f64, 3>> = if compat[k] || fits[k].is_none() {
                ip.iter()
                    .zip(&iq)
                    .map(|(a, b)| {
                        mean_hom(before[c.p].hom.at(a.0, a.1), before[c.q].hom.at(b.0, b.1))
                    })
                    .collect()
            } else {
                let Some(f) = &fits[k] else { continue };
                let Some(cv) = refine_to(&f.curve, &cls[ci].knots()) else {
                    left[k] = Some("the fitted curve's knots are not in its class".into());
                    continue;
                };
                cv.control
            };
            if homs.len() != ip.len() || homs.len() != iq.len() {
                left[k] = Some("rows of different lengths after refinement".into());
                continue;
            }
            for ((a, b), h) in ip.iter().zip(&iq).zip(&homs) {
                put(&mut patches[c.p], *a, h);
                put(&mut patches[c.q], *b, h);
            }
            if compat[k] {
                out.edges_averaged += 1;
                out.edges
                    .push(rec("control_points", None, cls[ci].degree, homs.len()));
            } else if fits[k].is_none() {
                // No solvable fit: the two refined rows averaged (at equal parameters).
                out.edges_fitted += 1;
                out.edges.push(rec(
                    "control_points_after_refinement",
                    None,
                    cls[ci].degree,
                    homs.len(),
                ));
            } else {
                out.edges_fitted += 1;
                let f = fits[k].as_ref();
                out.max_fit_error_evidence = out
                    .max_fit_error_evidence
                    .max(f.map_or(0.0, |f| f.fit_error));
                out.edges
                    .push(rec("fitted_curve", f, cls[ci].degree, homs.len()));
            }
        } else if compat[k] {
            let ip = edge_indices(&patches[c.p], c.ep);
            let mut iq = edge_indices(&patches[c.q], c.eq);
            if !c.same_direction {
                iq.reverse();
            }
            for (a, b) in ip.iter().zip(&iq) {
                let h = mean_hom(before[c.p].hom.at(a.0, a.1), before[c.q].hom.at(b.0, b.1));
                put(&mut patches[c.p], *a, &h);
                put(&mut patches[c.q], *b, &h);
            }
            let deg = edge_curve(&patches[c.p], c.ep).hom.knots.degree();
            out.edges_averaged += 1;
            out.edges.push(rec("control_points", None, deg, ip.len()));
        } else {
            left[k] = Some(if let Some(r) = &class_reason[ci] {
                r.clone()
            } else if cls[ci].consistent {
                "a patch of the knot class could not be refined to the class knots (knots not clamped, or two knots closer than the snapping tolerance)".into()
            } else {
                "the knot class's ties reverse orientation around a cycle".into()
            });
            continue;
        }
        replaced[c.p].push(c.ep);
        replaced[c.q].push(c.eq);
    }
    // Corners last: one point per cluster, written to every member with its group's weight
    // (one homogeneous point for the corners joined by connections).
    for (r, members) in clusters.iter().filter(|(_, m)| m.len() > 1) {
        let mut owners: Vec<usize> = members.iter().map(|m| m / 4).collect();
        owners.dedup();
        out.corner_clusters += usize::from(owners.len() > 1);
        let mean = mean_of[r];
        for &m in members {
            let h = Hom::from_point(&mean, &cw[m]);
            let d = dist(&cs[m / 4][m % 4], &mean);
            out.max_corner_move = out.max_corner_move.max(d);
            out.corners_moved += usize::from(d > 0.0);
            let idx = corner_index(&patches[m / 4], m % 4);
            put(&mut patches[m / 4], idx, &h);
        }
    }
    // A collapsed row (the degenerate side of a triangular patch) stays one point: its corners
    // are one cluster, and its other control points follow them (each keeping its weight).
    for (p, s) in patches.iter_mut().enumerate() {
        for e in 0..4 {
            if collapsed(&edge_curve(&before[p], e)) {
                let Some(apex) = mean_of.get(&root[4 * p + e]) else {
                    continue;
                };
                let idx = edge_indices(s, e);
                for x in &idx[1..idx.len() - 1] {
                    let w = s.hom.at(x.0, x.1).w;
                    put(s, *x, &Hom::from_point(apex, &w));
                }
            }
        }
    }
    // The interior follows the boundary; per patch what moved and the deviation.
    for (p, s) in patches.iter_mut().enumerate() {
        if !unified[p]
            && s.hom.net == before[p].hom.net
            && s.hom.ku == original[p].hom.ku
            && s.hom.kv == original[p].hom.kv
        {
            continue;
        }
        blend_interior(&before[p], s);
        let (mv, same_w) = control_move(&before[p], s);
        let measured = measured_deviation(&original[p], s, 9);
        out.max_control_point_move = out.max_control_point_move.max(mv);
        out.max_deviation_measured_evidence = out.max_deviation_measured_evidence.max(measured);
        let same_w = same_w && !unified[p];
        if same_w {
            out.max_deviation_bound_proven =
                Some(out.max_deviation_bound_proven.unwrap_or(0.0).max(mv));
        }
        let mut rows = replaced[p].clone();
        rows.sort_unstable();
        rows.dedup();
        let o = &original[p].hom;
        out.patches.push(PatchRecord {
            patch: p,
            degrees_before: o.degrees(),
            degrees_after: s.hom.degrees(),
            control_points_before: (o.nu(), o.nv()),
            control_points_after: (s.hom.nu(), s.hom.nv()),
            rows_replaced: rows,
            max_control_point_move: mv,
            deviation_bound_proven: same_w.then_some(mv),
            deviation_measured_evidence: measured,
        });
    }
    for (c, reason) in connected.iter().zip(left) {
        if let Some(reason) = reason {
            out.edges_incompatible.push(*c);
            out.left.push(LeftEdge {
                connection: *c,
                reason,
            });
        }
    }
    out
}
