//! STEP topology (ISO 10303-42) into a [`Brep`]: `advanced_face`/`face_surface` with their
//! `face_bound`/`face_outer_bound`s, `edge_loop`s of `oriented_edge`s over `edge_curve`s
//! (shared: each instance becomes one edge), `vertex_point`s, `vertex_loop`s,
//! `closed_shell`/`open_shell` (faces possibly `oriented_face`s), `manifold_solid_brep` and
//! `brep_with_voids`. Every instance is tallied in the report as converted, unsupported or
//! invalid; a fault is a [`crate::brep::TopologyIssue`] naming the face and the entity, and
//! the rest of the model is still read. Topology instances no face, shell or solid reaches
//! are listed as not read.

mod edges;

use super::entities::Reader;
use super::part21::Inst;
use crate::brep::{Brep, Face, IssueKind, Loop, LoopKind};
use std::collections::{BTreeMap, BTreeSet};

/// Topology entity types this reader walks or reports.
const TOPOLOGY_TYPES: [&str; 20] = [
    "ADVANCED_FACE",
    "FACE_SURFACE",
    "FACE_BOUND",
    "FACE_OUTER_BOUND",
    "EDGE_LOOP",
    "VERTEX_LOOP",
    "POLY_LOOP",
    "ORIENTED_EDGE",
    "EDGE_CURVE",
    "SUBEDGE",
    "VERTEX_POINT",
    "ORIENTED_FACE",
    "CLOSED_SHELL",
    "OPEN_SHELL",
    "ORIENTED_CLOSED_SHELL",
    "MANIFOLD_SOLID_BREP",
    "BREP_WITH_VOIDS",
    "SHELL_BASED_SURFACE_MODEL",
    "FACETED_BREP",
    "PCURVE",
];

/// Builds a [`Brep`] from the parsed file.
pub(super) struct TopologyReader<'a> {
    pub(super) r: &'a Reader<'a>,
    pub(super) brep: Brep,
    pub(super) vertices: BTreeMap<u64, usize>,
    /// `None`: the instance was refused (already reported).
    pub(super) edges: BTreeMap<u64, Option<usize>>,
    pub(super) faces: BTreeMap<u64, usize>,
    pub(super) shells: BTreeMap<u64, Option<usize>>,
    /// Instances tallied (each once).
    pub(super) seen: BTreeSet<u64>,
    /// Vertex-to-curve distances above this are reported.
    pub(super) tolerance: f64,
}

/// The type name of an instance for the report (the first of `names` it contains, else its
/// own name).
pub(super) fn type_of(e: Inst, names: &[&str]) -> String {
    names
        .iter()
        .find(|n| e.is(n))
        .map_or_else(|| e.name().to_string(), |n| n.to_string())
}

impl<'a> TopologyReader<'a> {
    /// `tolerance`: largest vertex-to-curve distance accepted silently (model units).
    pub(super) fn new(r: &'a Reader<'a>, tolerance: f64) -> Self {
        TopologyReader {
            r,
            brep: Brep::default(),
            vertices: BTreeMap::new(),
            edges: BTreeMap::new(),
            faces: BTreeMap::new(),
            shells: BTreeMap::new(),
            seen: BTreeSet::new(),
            tolerance,
        }
    }

    pub(super) fn converted(&mut self, id: u64, ty: &str) {
        if self.seen.insert(id) {
            self.brep.report.converted(ty);
        }
    }
    pub(super) fn invalid(&mut self, id: u64, ty: &str, face: Option<u64>, kind: IssueKind) {
        if self.seen.insert(id) {
            let face = face.map(|f| format!("#{f}"));
            self.brep
                .report
                .invalid(ty, &format!("#{id}"), face.as_deref(), kind);
        }
    }
    pub(super) fn unsupported(&mut self, id: u64, ty: &str, face: Option<u64>, kind: IssueKind) {
        if self.seen.insert(id) {
            self.brep.report.unsupported(ty, &format!("#{id}"));
            let face = face.map(|f| format!("#{f}"));
            self.brep
                .report
                .issue(&format!("#{id}"), face.as_deref(), kind);
        }
    }
    /// The instance `id` when it is (or contains) one of `types`; otherwise the fault is
    /// reported against `owner` and `None` returned.
    pub(super) fn referenced(
        &mut self,
        owner: (u64, &str),
        id: u64,
        attribute: &str,
        types: &[&str],
        face: Option<u64>,
    ) -> Option<(Inst<'a>, String)> {
        let Some(e) = self.r.p.entities.inst(id) else {
            self.invalid(
                owner.0,
                owner.1,
                face,
                IssueKind::DanglingReference {
                    to: format!("#{id}"),
                },
            );
            return None;
        };
        match types.iter().find(|t| e.is(t)) {
            Some(t) => Some((e, t.to_string())),
            None => {
                self.invalid(
                    owner.0,
                    owner.1,
                    face,
                    IssueKind::WrongType {
                        attribute: format!("{attribute} #{id}"),
                        expected: types.join(" or "),
                        found: e.name().to_string(),
                    },
                );
                None
            }
        }
    }

    /// Read every face, shell and solid of the file. `surface_of`: the model surface index
    /// of each face whose surface was converted; `no_surface`: why each face whose
    /// surface was not has none (an unsupported type, or invalid data skipped).
    pub(super) fn read(
        mut self,
        surface_of: &BTreeMap<u64, usize>,
        no_surface: &BTreeMap<u64, IssueKind>,
    ) -> Brep {
        let p = self.r.p;
        for (id, e) in p.entities.insts() {
            if e.is("ADVANCED_FACE") || e.is("FACE_SURFACE") {
                self.face(id, e, surface_of.get(&id).copied(), no_surface.get(&id));
            }
        }
        for (id, e) in p.entities.insts() {
            if e.is("CLOSED_SHELL") || e.is("OPEN_SHELL") {
                self.shell(id);
            }
        }
        for (id, e) in p.entities.insts() {
            if e.is("MANIFOLD_SOLID_BREP") || e.is("BREP_WITH_VOIDS") {
                self.solid(id, e);
            } else if let Some(a) = e.part("SHELL_BASED_SURFACE_MODEL") {
                // A set of shells, each read above.
                let ok = a
                    .get(1)
                    .and_then(|v| v.list_refs())
                    .is_some_and(|mut l| l.all(|v| v.is_some()));
                if ok {
                    self.converted(id, "SHELL_BASED_SURFACE_MODEL");
                } else {
                    self.invalid(
                        id,
                        "SHELL_BASED_SURFACE_MODEL",
                        None,
                        IssueKind::Malformed("sbsm_boundary is not a list of references".into()),
                    );
                }
            }
        }
        // Topology instances nothing reached: listed, not dropped silently.
        for (id, e) in p.entities.insts() {
            if self.seen.contains(&id) {
                continue;
            }
            if let Some(t) = TOPOLOGY_TYPES.iter().find(|t| e.is(t)) {
                self.brep
                    .report
                    .entities
                    .entry(t.to_string())
                    .or_default()
                    .not_read
                    .push(format!("#{id}"));
            }
        }
        self.brep.tolerance = self.tolerance;
        let issues = self.brep.check();
        self.brep.report.issues.extend(issues);
        self.brep
    }

    fn face(&mut self, id: u64, e: Inst, surface: Option<usize>, no_surface: Option<&IssueKind>) {
        let ty = type_of(e, &["ADVANCED_FACE", "FACE_SURFACE"]);
        let a = e.part(&ty).unwrap_or_default();
        let (Some(bounds), Some(sid)) = (
            a.get(1).and_then(|v| v.list_refs()),
            a.get(2).and_then(|v| v.reference()),
        ) else {
            self.invalid(
                id,
                &ty,
                Some(id),
                IssueKind::Malformed("expected (name, bounds, face_geometry, same_sense)".into()),
            );
            return;
        };
        if let Some(why) = no_surface {
            self.brep
                .report
                .issue(&format!("#{sid}"), Some(&format!("#{id}")), why.clone());
        }
        let mut loops = Vec::new();
        for b in bounds {
            let Some(bid) = b else {
                self.invalid(
                    id,
                    &ty,
                    Some(id),
                    IssueKind::Malformed("a bound is not a reference".into()),
                );
                return;
            };
            if let Some(l) = self.bound(id, bid) {
                loops.push(l);
            }
        }
        self.converted(id, &ty);
        self.faces.insert(id, self.brep.faces.len());
        self.brep.faces.push(Face {
            source: format!("#{id}"),
            surface,
            surface_source: format!("#{sid}"),
            same_sense: a.get(3).and_then(|v| v.enumeration()) != Some("F"),
            loops,
        });
    }

    fn bound(&mut self, face: u64, bid: u64) -> Option<Loop> {
        let (e, ty) = self.referenced(
            (face, "ADVANCED_FACE"),
            bid,
            "bound",
            &["FACE_OUTER_BOUND", "FACE_BOUND"],
            Some(face),
        )?;
        let a = e.part(&ty).unwrap_or_default();
        let Some(lid) = a.get(1).and_then(|v| v.reference()) else {
            self.invalid(
                bid,
                &ty,
                Some(face),
                IssueKind::Malformed("bound is not a reference".into()),
            );
            return None;
        };
        let orientation = a.get(2).and_then(|v| v.enumeration()) != Some("F");
        let (le, lty) = self.referenced(
            (bid, &ty),
            lid,
            "bound",
            &["EDGE_LOOP", "VERTEX_LOOP", "POLY_LOOP"],
            Some(face),
        )?;
        let kind = match lty.as_str() {
            "VERTEX_LOOP" => {
                let v = le.part("VERTEX_LOOP").and_then(|a| a.get(1)?.reference());
                let vi = v.and_then(|v| self.vertex(lid, "VERTEX_LOOP", v, Some(face)));
                let Some(vi) = vi else {
                    self.invalid(
                        lid,
                        "VERTEX_LOOP",
                        Some(face),
                        IssueKind::Malformed("loop_vertex is not a VERTEX_POINT".into()),
                    );
                    return None;
                };
                LoopKind::Vertex(vi)
            }
            "EDGE_LOOP" => {
                let list = le
                    .part("EDGE_LOOP")
                    .and_then(|a| a.get(1))
                    .and_then(|v| v.list_refs())
                    .unwrap_or_default();
                let mut es = Vec::with_capacity(list.len());
                for v in list {
                    let oe = v.and_then(|o| self.oriented_edge(lid, o, face));
                    match oe {
                        Some(oe) => es.push(oe),
                        None => {
                            self.invalid(
                                lid,
                                "EDGE_LOOP",
                                Some(face),
                                IssueKind::Malformed("an edge of the loop was refused".into()),
                            );
                            return None;
                        }
                    }
                }
                LoopKind::Edges(es)
            }
            _ => {
                self.unsupported(
                    lid,
                    &lty,
                    Some(face),
                    IssueKind::Malformed(format!("{lty} bounds are not supported")),
                );
                return None;
            }
        };
        self.converted(lid, &lty);
        self.converted(bid, &ty);
        Some(Loop {
            source: format!("#{bid}"),
            loop_source: format!("#{lid}"),
            outer: ty == "FACE_OUTER_BOUND",
            orientation,
            kind,
        })
    }
}
