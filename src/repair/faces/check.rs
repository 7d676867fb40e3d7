//! Invariants of a faces repair's result, callable from tests, fuzz targets and debug
//! builds: the repaired B-rep's references are in range, and the report's counts are the
//! B-rep's own.

use super::{FacesResult, angles::edge_uses, closed};
use crate::brep::LoopKind;

impl FacesResult {
    /// The invariants that do not hold (empty when all do).
    pub fn check(&self) -> Vec<String> {
        let (b, r) = (&self.brep, &self.report);
        let mut out = Vec::new();
        for e in &b.edges {
            if e.start >= b.vertices.len() || e.end >= b.vertices.len() {
                out.push(format!("edge {}: a vertex out of range", e.source));
            }
        }
        for f in &b.faces {
            for l in &f.loops {
                let bad = match &l.kind {
                    LoopKind::Edges(oes) => oes.iter().any(|oe| oe.edge >= b.edges.len()),
                    LoopKind::Vertex(v) => *v >= b.vertices.len(),
                };
                if bad {
                    out.push(format!("face {}: a loop refers past the B-rep", f.source));
                }
            }
        }
        let uses = edge_uses(b);
        let free = uses.values().filter(|u| u.len() == 1).count();
        if free != r.free_edges_after || r.free_edges.len() != free {
            out.push(format!(
                "free edges: the B-rep has {free}, the report says {} ({} listed)",
                r.free_edges_after,
                r.free_edges.len()
            ));
        }
        if r.free_edges_after > r.free_edges_before {
            out.push("more free edges after than before".into());
        }
        if r.edges_after != b.edges.len() || r.edges_after > r.edges_before {
            out.push(format!(
                "edges: {} before, {} reported after, {} in the B-rep",
                r.edges_before,
                r.edges_after,
                b.edges.len()
            ));
        }
        if r.shells.len() != b.shells.len() {
            out.push("shells: the report and the B-rep differ in number".into());
        }
        for (s, rs) in b.shells.iter().zip(&r.shells) {
            if s.closed != closed(b, &s.faces) || rs.closed != s.closed {
                out.push(format!("shell {}: closure not as computed", s.source));
            }
        }
        out
    }
}
