//! Invariants of a faces repair's result, callable from tests, fuzz targets and debug
//! builds: the repaired B-rep's references are in range, and the report's counts are the
//! B-rep's own.

use super::{FacesResult, angles::edge_uses, closed};
use crate::brep::LoopKind;

/// The first reference of `b` that points past what it refers to (loops to edges and
/// vertices, edges to vertices, faces to the model's `surfaces`, shells to faces, solids to
/// shells, occurrences to solids and shells), or a vertex that is not finite; `None` when
/// there is none.
pub fn dangling(b: &crate::brep::Brep, surfaces: usize) -> Option<String> {
    let (nv, ne, nf, ns) = (
        b.vertices.len(),
        b.edges.len(),
        b.faces.len(),
        b.shells.len(),
    );
    if let Some(v) = b
        .vertices
        .iter()
        .find(|v| v.point.iter().any(|x| !x.is_finite()))
    {
        return Some(format!("vertex {} is not finite", v.source));
    }
    if let Some(e) = b.edges.iter().find(|e| e.start >= nv || e.end >= nv) {
        return Some(format!(
            "edge {} names a vertex that does not exist",
            e.source
        ));
    }
    for f in &b.faces {
        if f.surface.is_some_and(|s| s >= surfaces) {
            return Some(format!(
                "face {} names a surface that does not exist",
                f.source
            ));
        }
        for l in &f.loops {
            let bad = match &l.kind {
                LoopKind::Edges(oes) => oes.iter().any(|oe| oe.edge >= ne),
                LoopKind::Vertex(v) => *v >= nv,
            };
            if bad {
                return Some(format!(
                    "face {}: a loop names an edge or vertex that does not exist",
                    f.source
                ));
            }
        }
    }
    if let Some(s) = b
        .shells
        .iter()
        .find(|s| s.faces.iter().any(|(f, _)| *f >= nf))
    {
        return Some(format!(
            "shell {} names a face that does not exist",
            s.source
        ));
    }
    if let Some(s) = b
        .solids
        .iter()
        .find(|s| s.outer >= ns || s.voids.iter().any(|v| *v >= ns))
    {
        return Some(format!(
            "solid {} names a shell that does not exist",
            s.source
        ));
    }
    let nsol = b.solids.len();
    if let Some(o) = b
        .occurrences
        .iter()
        .find(|o| o.shells.iter().any(|s| *s >= ns) || o.solids.iter().any(|s| *s >= nsol))
    {
        return Some(format!(
            "occurrence {} names a shell or solid that does not exist",
            o.source
        ));
    }
    None
}

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
        // A T-split adds an edge, which may be left free when no partner matches its piece.
        let splits = r.sewing.t_splits;
        if r.free_edges_after > r.free_edges_before + splits {
            out.push("more free edges after than before, beyond the T-splits".into());
        }
        if r.edges_after != b.edges.len() || r.edges_after > r.edges_before + splits {
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
