//! STEP edges and vertices of a face's edge loops: `oriented_edge`s (possibly of other
//! oriented edges), `edge_curve`s (each instance one shared edge, with its curve and
//! parameter-space curves) and `vertex_point`s.

use super::TopologyReader;
use crate::brep::{Edge, IssueKind, OrientedEdge, Vertex};
use crate::io::step::edge_curve::{self, CurveFault, Found, MAX_DEPTH};
use crate::io::step::part21::Inst;

impl TopologyReader<'_> {
    /// An `oriented_edge` (possibly of another oriented edge, orientations composed).
    pub(super) fn oriented_edge(
        &mut self,
        owner: u64,
        oid: u64,
        face: u64,
    ) -> Option<OrientedEdge> {
        let mut id = oid;
        let mut forward = true;
        let mut from = (owner, "EDGE_LOOP".to_string());
        // Oriented edges on the way, tallied once the edge is read.
        let mut chain = Vec::new();
        for _ in 0..MAX_DEPTH {
            let (e, ty) = self.referenced(
                (from.0, &from.1.clone()),
                id,
                "edge",
                &["ORIENTED_EDGE", "EDGE_CURVE"],
                Some(face),
            )?;
            if ty == "EDGE_CURVE" {
                let edge = self.edge(id, e, face)?;
                for c in chain {
                    self.converted(c, "ORIENTED_EDGE");
                }
                return Some(OrientedEdge { edge, forward });
            }
            let a = e.part("ORIENTED_EDGE").unwrap_or_default();
            let (Some(next), Some(o)) = (
                a.get(3).and_then(|v| v.reference()),
                a.get(4).and_then(|v| v.enumeration()),
            ) else {
                self.invalid(
                    id,
                    "ORIENTED_EDGE",
                    Some(face),
                    IssueKind::Malformed("expected (name, *, *, edge_element, orientation)".into()),
                );
                return None;
            };
            chain.push(id);
            forward ^= o == "F";
            from = (id, "ORIENTED_EDGE".into());
            id = next;
        }
        self.invalid(
            oid,
            "ORIENTED_EDGE",
            Some(face),
            IssueKind::TooDeep(MAX_DEPTH),
        );
        None
    }

    pub(super) fn vertex(
        &mut self,
        owner: u64,
        owner_ty: &str,
        vid: u64,
        face: Option<u64>,
    ) -> Option<usize> {
        if let Some(i) = self.vertices.get(&vid) {
            return Some(*i);
        }
        let (e, _) = self.referenced((owner, owner_ty), vid, "vertex", &["VERTEX_POINT"], face)?;
        let point = e
            .part("VERTEX_POINT")
            .and_then(|a| a.get(1)?.reference())
            .map(|p| self.r.point(p));
        match point {
            Some(Ok(point)) => {
                self.converted(vid, "VERTEX_POINT");
                let i = self.brep.vertices.len();
                self.brep.vertices.push(Vertex {
                    source: format!("#{vid}"),
                    point,
                });
                self.vertices.insert(vid, i);
                Some(i)
            }
            Some(Err(err)) => {
                self.invalid(
                    vid,
                    "VERTEX_POINT",
                    face,
                    IssueKind::Malformed(format!("{}: {}", err.location, err.reason)),
                );
                None
            }
            None => {
                self.invalid(
                    vid,
                    "VERTEX_POINT",
                    face,
                    IssueKind::Malformed("vertex_geometry is not a reference".into()),
                );
                None
            }
        }
    }

    fn edge(&mut self, id: u64, e: Inst, face: u64) -> Option<usize> {
        if let Some(i) = self.edges.get(&id) {
            return *i;
        }
        self.edges.insert(id, None);
        let a = e.part("EDGE_CURVE").unwrap_or_default();
        let (Some(v0), Some(v1), Some(g)) = (
            a.get(1).and_then(|v| v.reference()),
            a.get(2).and_then(|v| v.reference()),
            a.get(3).and_then(|v| v.reference()),
        ) else {
            self.invalid(
                id,
                "EDGE_CURVE",
                Some(face),
                IssueKind::Malformed(
                    "expected (name, edge_start, edge_end, edge_geometry, same_sense)".into(),
                ),
            );
            return None;
        };
        let start = self.vertex(id, "EDGE_CURVE", v0, Some(face));
        let end = self.vertex(id, "EDGE_CURVE", v1, Some(face));
        let (Some(start), Some(end)) = (start, end) else {
            self.invalid(
                id,
                "EDGE_CURVE",
                Some(face),
                IssueKind::Malformed("a vertex was refused".into()),
            );
            return None;
        };
        let same_sense = a.get(4).and_then(|v| v.enumeration()) != Some("F");
        let (p0, p1) = (
            self.brep.vertices[start].point,
            self.brep.vertices[end].point,
        );
        let mut found = Found::default();
        let curve = edge_curve::edge_curve(self.r, g, &p0, &p1, same_sense, &mut found);
        if curve.is_ok() {
            for (cid, ty) in &found.types {
                self.converted(*cid, ty);
            }
        }
        for f in found.faults {
            self.curve_fault(f, face);
        }
        let curve = match curve {
            Ok(c) => {
                if c.vertex_gap > self.tolerance {
                    self.brep.report.issue(
                        &format!("#{id}"),
                        Some(&format!("#{face}")),
                        IssueKind::VertexOffCurve {
                            distance: c.vertex_gap,
                            tolerance: self.tolerance,
                        },
                    );
                }
                Some(c)
            }
            Err(f) => {
                self.curve_fault(f, face);
                None
            }
        };
        self.converted(id, "EDGE_CURVE");
        // Most edges have two pcurves: not the four places a first push makes.
        found.pcurves.shrink_to_fit();
        let i = self.brep.edges.len();
        self.brep.edges.push(Edge {
            source: format!("#{id}"),
            start,
            end,
            curve,
            pcurves: found.pcurves,
        });
        self.edges.insert(id, Some(i));
        Some(i)
    }

    fn curve_fault(&mut self, f: CurveFault, face: u64) {
        if f.unsupported {
            self.unsupported(f.id, &f.ty, Some(face), f.kind);
        } else {
            self.invalid(f.id, &f.ty, Some(face), f.kind);
        }
    }
}
