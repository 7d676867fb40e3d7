//! IGES B-rep vertices and edges: a vertex per entry of a 502 vertex list, an edge per entry
//! of a 504 edge list with its model-space curve running from the start to the terminate
//! vertex, and the parameter-space curves a 508 loop gives an edge.

use super::Topo;
use crate::brep::{CurveKind, Edge, EdgeCurve, IssueKind, PCurve, PCurveGeometry, Vertex};
use crate::spline::NurbsCurve;

impl Topo<'_, '_> {
    /// A parameter-space curve of `edge` on `surface`, stored along the edge's curve.
    pub(super) fn pcurve(&mut self, edge: usize, c: usize, surface: usize, forward: bool) {
        let Ok(Some(segs)) = self.r.segments(c, 0) else {
            return;
        };
        let [seg] = segs.as_slice() else {
            return;
        };
        let flat = NurbsCurve {
            hom: seg.hom.map(
                |k| *k,
                |h| crate::geom::Hom {
                    wp: [h.wp[0], h.wp[1]],
                    w: h.w,
                },
            ),
        };
        let flat = if forward { flat } else { flat.reversed() };
        self.brep.edges[edge].pcurves.push(PCurve {
            source: format!("DE {c}"),
            surface_source: format!("DE {surface}"),
            geometry: PCurveGeometry::Nurbs(flat),
        });
    }

    pub(super) fn vertex(&mut self, key: (usize, usize), face: usize) -> Option<usize> {
        if let Some(v) = self.vertices.get(&key) {
            return *v;
        }
        let v = match self.r.list_vertex(key.0, key.1) {
            Ok(point) => {
                self.converted(key.0);
                self.brep.vertices.push(Vertex {
                    source: format!("DE {}[{}]", key.0, key.1),
                    point,
                });
                Some(self.brep.vertices.len() - 1)
            }
            Err(e) => {
                self.invalid(key.0, Some(face), e.reason);
                None
            }
        };
        self.vertices.insert(key, v);
        v
    }

    pub(super) fn edge(&mut self, key: (usize, usize), face: usize) -> Option<usize> {
        if let Some(e) = self.edges.get(&key) {
            return *e;
        }
        self.edges.insert(key, None);
        let (c, s, t) = match self.r.list_edge(key.0, key.1) {
            Ok(x) => x,
            Err(e) => {
                self.invalid(key.0, Some(face), e.reason);
                return None;
            }
        };
        let (start, end) = (self.vertex(s, face)?, self.vertex(t, face)?);
        let (p0, p1) = (
            self.brep.vertices[start].point,
            self.brep.vertices[end].point,
        );
        let source = format!("DE {}[{}]", key.0, key.1);
        let curve = match self.edge_curve(c, &p0, &p1) {
            Ok(c) => {
                if c.vertex_gap > self.brep.tolerance {
                    self.brep.report.issue(
                        &source,
                        Some(&format!("DE {face}")),
                        IssueKind::VertexOffCurve {
                            distance: c.vertex_gap,
                            tolerance: self.brep.tolerance,
                        },
                    );
                }
                Some(c)
            }
            Err(kind) => {
                self.brep
                    .report
                    .issue(&format!("DE {c}"), Some(&format!("DE {face}")), kind);
                None
            }
        };
        self.converted(key.0);
        self.brep.edges.push(Edge {
            source,
            start,
            end,
            curve,
            pcurves: vec![],
        });
        let i = self.brep.edges.len() - 1;
        self.edges.insert(key, Some(i));
        Some(i)
    }

    /// The model-space curve of an edge, from the start vertex `p0` to the end vertex `p1`.
    fn edge_curve(&self, c: usize, p0: &[f64; 3], p1: &[f64; 3]) -> Result<EdgeCurve, IssueKind> {
        let x = &self.r.e[&c];
        let segs = self
            .r
            .segments(c, 0)
            .map_err(|e| IssueKind::Malformed(e.reason))?;
        let seg = match segs.as_deref() {
            Some([s]) => s.clone(),
            Some(v) => {
                return Err(IssueKind::UnsupportedCurve(format!(
                    "{} ({} segments joined end to end)",
                    x.etype,
                    v.len()
                )));
            }
            None => return Err(IssueKind::UnsupportedCurve(x.etype.to_string())),
        };
        let (a, b) = seg.hom.domain();
        let (ca, cb) = (seg.eval(&a), seg.eval(&b));
        let fwd = crate::geom::dist(&ca, p0).max(crate::geom::dist(&cb, p1));
        let rev = crate::geom::dist(&cb, p0).max(crate::geom::dist(&ca, p1));
        let (nurbs, vertex_gap) = if rev < fwd {
            (seg.reversed(), rev)
        } else {
            (seg, fwd)
        };
        let kind = match x.etype {
            110 => CurveKind::Line,
            100 => CurveKind::Circle,
            104 => CurveKind::Ellipse,
            _ if nurbs.points_weights().1.windows(2).any(|w| w[0] != w[1]) => {
                CurveKind::RationalBSpline
            }
            _ => CurveKind::BSpline,
        };
        Ok(EdgeCurve {
            source: format!("DE {c}"),
            kind,
            nurbs,
            vertex_gap,
        })
    }
}
