//! T-connectivity on trimmed faces (Algorithm 1's T-junctions, Fig. 5, with edges in place of
//! patch borders): where the end vertex of one free edge lies within `u1` of the interior of
//! another free edge and its other end within `u1` of that edge too — one face's edge running
//! along two edges of its neighbours — that edge is split there, so that each piece can be sewn to its partner. The split point's
//! parameter is the closest point on the edge's curve (Newton from samples: evidence); the
//! pieces are the exact parts of the curve (knot insertion in homogeneous form) and end at the
//! vertex itself. The pieces drop the edge's pcurves (they are made again by projection
//! where needed: `crate::brep::pcurve`).

use crate::brep::{Brep, Edge, EdgeCurve, LoopKind, OrientedEdge};
use crate::geom::dist;
use crate::spline::NurbsCurve;
use crate::spline::project::CurveFoot;
use std::collections::BTreeMap;

/// Split the free edges (edge → its face, `free`) of `b` at the end vertices of other free
/// edges that lie within `u1` of their interiors (farther than `u1` from both ends), where
/// that other edge's far end lies within `u1` of the edge too (it runs along it: a partner
/// for one of the pieces). Returns the number of splits.
pub fn split_at_vertices(b: &mut Brep, free: &BTreeMap<usize, usize>, u1: f64) -> usize {
    // Each free edge's ends, each with the edge's other end.
    let tips: Vec<(usize, usize, usize)> = free
        .keys()
        .flat_map(|&f| {
            let (s, t) = (b.edges[f].start, b.edges[f].end);
            [(f, s, t), (f, t, s)]
        })
        .collect();
    let mut splits = 0;
    for (&e, &face) in free {
        let Some(c) = b.edges[e].curve.as_ref().map(|c| c.nurbs.clone()) else {
            continue;
        };
        let (start, end) = (b.edges[e].start, b.edges[e].end);
        let (Some(ps), Some(pe)) = (b.vertices.get(start), b.vertices.get(end)) else {
            continue;
        };
        let (ps, pe) = (ps.point, pe.point);
        let foot = CurveFoot::new(&c);
        let (t0, t1) = c.hom.domain();
        let mut at: Vec<(f64, usize)> = tips
            .iter()
            .filter(|(f, v, _)| *f != e && *v != start && *v != end)
            .filter_map(|&(_, v, w)| {
                let p = b.vertices[v].point;
                if dist(&p, &ps) <= u1 || dist(&p, &pe) <= u1 {
                    return None;
                }
                let (t, _, d) = foot.closest(&p);
                let along = foot.closest(&b.vertices[w].point).2 <= u1;
                (d <= u1 && along && t > t0 && t < t1).then_some((t, v))
            })
            .collect();
        if at.is_empty() {
            continue;
        }
        at.sort_by(|a, b| a.0.total_cmp(&b.0));
        at.dedup_by(|a, b| a.0 == b.0);
        // The pieces between consecutive split parameters, as new edges (the first keeps
        // the edge's index).
        let mut cuts = vec![(t0, start)];
        cuts.extend(at.iter().copied());
        cuts.push((t1, end));
        let mut pieces = Vec::with_capacity(cuts.len() - 1);
        for w in cuts.windows(2) {
            let Ok(hom) = c.hom.sub_curve(&w[0].0, &w[1].0) else {
                pieces.clear();
                break;
            };
            pieces.push((NurbsCurve { hom }, w[0].1, w[1].1));
        }
        if pieces.len() < 2 {
            continue;
        }
        splits += pieces.len() - 1;
        let old = b.edges[e].clone();
        let mut ids = Vec::with_capacity(pieces.len());
        for (k, (nurbs, s, t)) in pieces.into_iter().enumerate() {
            let gap = {
                let (a, z) = nurbs.hom.domain();
                dist(&nurbs.eval(&a), &b.vertices[s].point)
                    .max(dist(&nurbs.eval(&z), &b.vertices[t].point))
            };
            let piece = Edge {
                source: format!("{} (part {})", old.source, k + 1),
                start: s,
                end: t,
                curve: old.curve.as_ref().map(|oc| EdgeCurve {
                    source: oc.source.clone(),
                    kind: oc.kind,
                    nurbs,
                    vertex_gap: oc.vertex_gap.max(gap),
                }),
                pcurves: vec![],
            };
            if k == 0 {
                b.edges[e] = piece;
                ids.push(e);
            } else {
                b.edges.push(piece);
                ids.push(b.edges.len() - 1);
            }
        }
        // The face's loop runs the pieces in the edge's order, or in reverse.
        for l in b.faces[face].loops.iter_mut() {
            let LoopKind::Edges(oes) = &mut l.kind else {
                continue;
            };
            if let Some(i) = oes.iter().position(|oe| oe.edge == e) {
                let forward = oes[i].forward;
                let mut run: Vec<OrientedEdge> = ids
                    .iter()
                    .map(|&edge| OrientedEdge { edge, forward })
                    .collect();
                if !forward {
                    run.reverse();
                }
                oes.splice(i..=i, run);
                break;
            }
        }
    }
    splits
}
