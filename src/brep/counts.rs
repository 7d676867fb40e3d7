//! Counts of a B-rep's items, as `vericad info` prints them and as they are compared with
//! other readers (faces, loops, edges, vertices).

use super::{Brep, LoopKind};
use std::collections::{BTreeMap, BTreeSet};

/// How many of each item a B-rep holds.
#[derive(Clone, Debug, PartialEq, Eq, Default, serde::Serialize)]
pub struct BrepCounts {
    pub solids: usize,
    pub closed_shells: usize,
    pub open_shells: usize,
    pub faces: usize,
    /// Faces whose surface could not be converted.
    pub faces_without_surface: usize,
    /// Bounds of faces (`face_bound`s, outer ones included).
    pub loops: usize,
    /// Of which `vertex_loop`s.
    pub vertex_loops: usize,
    /// Oriented edges in all loops.
    pub oriented_edges: usize,
    /// Distinct edges.
    pub edges: usize,
    /// Edges used twice by the loops of one face (seams of closed surfaces).
    pub seam_edges: usize,
    /// Connected pieces of the face boundaries without their seams: per face, the
    /// components (joined at shared vertices) of the edges its loops use once, summed over
    /// the faces. Unchanged when another reader splits an edge at a new vertex, adds seam
    /// edges joining two loops of a closed surface, or adds degenerate edges at poles —
    /// a count to compare readers by.
    pub boundary_components: usize,
    /// Edges without a converted 3D curve.
    pub edges_without_curve: usize,
    pub vertices: usize,
    /// Edges by the kind of their 3D curve.
    pub edges_by_curve: BTreeMap<String, usize>,
}

impl Brep {
    /// Count every item.
    pub fn counts(&self) -> BrepCounts {
        let mut c = BrepCounts {
            solids: self.solids.len(),
            closed_shells: self.shells.iter().filter(|s| s.closed).count(),
            open_shells: self.shells.iter().filter(|s| !s.closed).count(),
            faces: self.faces.len(),
            faces_without_surface: self.faces.iter().filter(|f| f.surface.is_none()).count(),
            edges: self.edges.len(),
            vertices: self.vertices.len(),
            ..BrepCounts::default()
        };
        let mut seams = BTreeSet::new();
        for f in &self.faces {
            c.boundary_components += self.boundary_components(f);
            let mut seen = BTreeSet::new();
            for l in &f.loops {
                c.loops += 1;
                match &l.kind {
                    LoopKind::Vertex(_) => c.vertex_loops += 1,
                    LoopKind::Edges(es) => {
                        c.oriented_edges += es.len();
                        for oe in es {
                            if !seen.insert(oe.edge) {
                                seams.insert(oe.edge);
                            }
                        }
                    }
                }
            }
        }
        c.seam_edges = seams.len();
        for e in &self.edges {
            let k = match &e.curve {
                Some(ec) => format!("{:?}", ec.kind),
                None => {
                    c.edges_without_curve += 1;
                    "(none)".to_string()
                }
            };
            *c.edges_by_curve.entry(k).or_insert(0) += 1;
        }
        c
    }
}

impl Brep {
    /// Components of the edges used once by the loops of `f` (see
    /// [`BrepCounts::boundary_components`]).
    fn boundary_components(&self, f: &super::Face) -> usize {
        let mut uses: BTreeMap<usize, usize> = BTreeMap::new();
        for l in &f.loops {
            if let LoopKind::Edges(es) = &l.kind {
                for oe in es {
                    *uses.entry(oe.edge).or_insert(0) += 1;
                }
            }
        }
        // Union-find over the vertices of the once-used edges.
        let mut parent: BTreeMap<usize, usize> = BTreeMap::new();
        fn root(p: &mut BTreeMap<usize, usize>, x: usize) -> usize {
            let mut r = x;
            while let Some(&q) = p.get(&r) {
                if q == r {
                    break;
                }
                r = q;
            }
            p.insert(x, r);
            r
        }
        for (&e, &n) in &uses {
            if n != 1 {
                continue;
            }
            let (a, b) = (self.edges[e].start, self.edges[e].end);
            parent.entry(a).or_insert(a);
            parent.entry(b).or_insert(b);
            let (ra, rb) = (root(&mut parent, a), root(&mut parent, b));
            if ra != rb {
                parent.insert(ra, rb);
            }
        }
        let keys: Vec<usize> = parent.keys().copied().collect();
        keys.into_iter()
            .filter(|&v| root(&mut parent, v) == v)
            .count()
    }
}

impl std::fmt::Display for BrepCounts {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        writeln!(
            f,
            "  topology: {} solid(s), {} closed shell(s), {} open shell(s), {} face(s), {} loop(s) ({} vertex loop(s)), {} edge(s) ({} seam), {} vertex(es)",
            self.solids,
            self.closed_shells,
            self.open_shells,
            self.faces,
            self.loops,
            self.vertex_loops,
            self.edges,
            self.seam_edges,
            self.vertices
        )?;
        write!(
            f,
            "  edges by 3D curve: {}; {} oriented edge(s) in loops; {} boundary component(s) without seams",
            crate::model::info::counts_text(&self.edges_by_curve),
            self.oriented_edges,
            self.boundary_components
        )?;
        if self.faces_without_surface > 0 || self.edges_without_curve > 0 {
            write!(
                f,
                "; {} face(s) without surface, {} edge(s) without curve",
                self.faces_without_surface, self.edges_without_curve
            )?;
        }
        writeln!(f)
    }
}
