//! Closed edges cut at the seam points of the faces that use them.

use crate::brep::{Brep, Edge, EdgeCurve, OrientedEdge, Vertex};
use crate::geom::dist;
use crate::spline::NurbsCurve;
use std::collections::BTreeMap;

/// Cut the closed edge `e` of `b` at the curve parameters `ts` (module comment of
/// [`super`]); returns the edges it became, in its direction, the first at index `e`.
pub(super) fn cut_closed(b: &mut Brep, e: usize, ts: &[f64], off: f64) -> Vec<usize> {
    let Some(curve) = b.edges[e].curve.clone() else {
        return vec![e];
    };
    let c = &curve.nurbs;
    let (d0, d1) = c.hom.domain();
    let v = b.edges[e].start;
    // A cut within 1e-9 of the domain from a knot is made at the knot: a span of a few ulps
    // next to it would not survive the rounding of the arc's reversal.
    let near = 1e-9 * (d1 - d0);
    let knots = c.hom.knots.knots();
    let mut ts: Vec<f64> = ts
        .iter()
        .map(|t| {
            knots
                .iter()
                .copied()
                .find(|k| (k - t).abs() <= near)
                .unwrap_or(*t)
        })
        .collect();
    ts.sort_by(f64::total_cmp);
    ts.dedup_by(|a, b| (*a - *b).abs() <= near);
    // Cuts at the edge's own vertex need none.
    let at_vertex = |t: f64| dist(&c.eval(&t), &b.vertices[v].point) <= off;
    let keep_v = ts.iter().any(|t| at_vertex(*t));
    let inner: Vec<f64> = ts
        .into_iter()
        .filter(|t| !at_vertex(*t) && *t > d0 && *t < d1)
        .collect();
    if inner.is_empty() {
        return vec![e];
    }
    let sub = |a: f64, z: f64| c.hom.sub_curve(&a, &z).ok().map(|hom| NurbsCurve { hom });
    let mut pieces: Vec<(Option<NurbsCurve<f64, 3>>, usize, usize)> = Vec::new();
    let first = b.vertices.len();
    for t in &inner {
        b.vertices.push(Vertex {
            source: format!("{} (cut at its seam)", b.edges[e].source),
            point: c.eval(t),
        });
    }
    let n = inner.len();
    if keep_v {
        let mut bounds = vec![(d0, v)];
        bounds.extend(inner.iter().enumerate().map(|(i, t)| (*t, first + i)));
        bounds.push((d1, v));
        for w in bounds.windows(2) {
            pieces.push((sub(w[0].0, w[1].0), w[0].1, w[1].1));
        }
    } else {
        for i in 0..n - 1 {
            pieces.push((sub(inner[i], inner[i + 1]), first + i, first + i + 1));
        }
        let wrap = match (sub(inner[n - 1], d1), sub(d0, inner[0])) {
            (Some(x), Some(y)) => x.joined(&y).ok(),
            _ => None,
        };
        pieces.push((wrap, first + n - 1, first));
    }
    let mut ids = Vec::with_capacity(pieces.len());
    for (i, (arc, start, end)) in pieces.into_iter().enumerate() {
        let edge = Edge {
            source: b.edges[e].source.clone(),
            start,
            end,
            curve: arc.map(|nurbs| EdgeCurve {
                nurbs,
                vertex_gap: 0.0,
                ..curve.clone()
            }),
            pcurves: Vec::new(),
        };
        if i == 0 {
            b.edges[e] = edge;
            ids.push(e);
        } else {
            ids.push(b.edges.len());
            b.edges.push(edge);
        }
    }
    ids
}

/// The uses of the edges `o` became (`arcs`), in the order `o` runs.
pub(super) fn uses(arcs: &BTreeMap<usize, Vec<usize>>, o: OrientedEdge) -> Vec<OrientedEdge> {
    match arcs.get(&o.edge) {
        None => vec![o],
        Some(a) if o.forward => a
            .iter()
            .map(|&edge| OrientedEdge {
                edge,
                forward: true,
            })
            .collect(),
        Some(a) => a
            .iter()
            .rev()
            .map(|&edge| OrientedEdge {
                edge,
                forward: false,
            })
            .collect(),
    }
}
