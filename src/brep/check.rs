//! Invariants of a B-rep, callable from readers, tests and fuzz targets: every edge loop is
//! closed (each oriented edge ends at the vertex where the next begins, the last where the
//! first begins), every face has at most one outer bound, and a closed shell uses each of
//! its edges exactly twice (once in each direction when the faces are consistently
//! oriented; only the count is checked here).

use super::{Brep, IssueKind, LoopKind, TopologyIssue};
use std::collections::BTreeMap;

impl Brep {
    /// The faults of the topology, each naming the face and the entity (empty when sound).
    pub fn check(&self) -> Vec<TopologyIssue> {
        let mut out = Vec::new();
        let issue = |entity: &str, face: &str, kind| TopologyIssue {
            entity: entity.to_string(),
            face: Some(face.to_string()),
            kind,
        };
        for f in &self.faces {
            if f.loops.is_empty() {
                out.push(issue(&f.source, &f.source, IssueKind::NoBounds));
            }
            let outer = f.loops.iter().filter(|l| l.outer).count();
            if outer > 1 {
                out.push(issue(
                    &f.source,
                    &f.source,
                    IssueKind::SeveralOuterBounds { count: outer },
                ));
            }
            for l in &f.loops {
                let LoopKind::Edges(es) = &l.kind else {
                    continue;
                };
                if es.is_empty() {
                    out.push(issue(&l.loop_source, &f.source, IssueKind::EmptyLoop));
                    continue;
                }
                for (i, oe) in es.iter().enumerate() {
                    let next = es[(i + 1) % es.len()];
                    let end = self.edges[oe.edge].last_vertex(oe.forward);
                    let start = self.edges[next.edge].first_vertex(next.forward);
                    if end != start {
                        out.push(issue(
                            &l.loop_source,
                            &f.source,
                            IssueKind::OpenLoop {
                                position: i + 1,
                                end: self.vertices[end].source.clone(),
                                next: self.vertices[start].source.clone(),
                            },
                        ));
                    }
                }
            }
        }
        for s in self.shells.iter().filter(|s| s.closed) {
            for (e, uses) in self.edge_uses(&s.faces) {
                if uses != 2 {
                    out.push(TopologyIssue {
                        entity: self.edges[e].source.clone(),
                        face: None,
                        kind: IssueKind::EdgeUse {
                            shell: s.source.clone(),
                            uses,
                        },
                    });
                }
            }
        }
        out
    }

    /// How many times the loops of `faces` use each edge (index into [`Brep::edges`]).
    pub fn edge_uses(&self, faces: &[(usize, bool)]) -> BTreeMap<usize, usize> {
        let mut uses = BTreeMap::new();
        for (fi, _) in faces {
            for l in &self.faces[*fi].loops {
                if let LoopKind::Edges(es) = &l.kind {
                    for oe in es {
                        *uses.entry(oe.edge).or_insert(0) += 1;
                    }
                }
            }
        }
        uses
    }
}
