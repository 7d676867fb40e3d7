//! IGES 5.3 B-rep topology (§4.146–4.151 of the 5.3 specification) into a [`Brep`]:
//! manifold solid B-rep objects (186), shells (514, form 1 closed, form 2 open), faces (510),
//! loops (508), edge lists (504) and vertex lists (502).
//!
//! * 502 (vertex list): N, then X, Y, Z per vertex. A vertex is named `DE d[k]` (entry `k`,
//!   from 1, of the list at DE `d`); each (list, entry) becomes one [`Vertex`].
//! * 504 (edge list): N, then per edge CURV (model-space curve), SVP, SV, TVP, TV (start and
//!   terminate vertex: list DE and entry). Each (list, entry) becomes one [`Edge`], shared
//!   by every loop that uses it; its curve runs from SV to TV (the reverse is taken when only
//!   it matches the vertices, and a gap above the tolerance is an issue either way).
//! * 508 (loop): N, then per edge TYPE (0 edge, 1 vertex), EDGE (list DE), NDX (entry), OF
//!   (1: the loop runs along the edge's curve), K, and K pairs (ISOP, CURV) of
//!   parameter-space curves. A TYPE 1 entry is a degenerate edge (a pole): inside a loop of
//!   edges it is left out (the neighbours meet at its vertex, as in STEP), a loop of that one
//!   entry is a vertex loop.
//! * 510 (face): SURF, N, OF (1: the first loop is the outer one), the N loops. IGES faces
//!   have no sense flag: the face normal is the surface's.
//! * 514 (shell): N, then (FACE, OF) pairs, OF = 1 when the face's normal agrees with the
//!   surface's.
//! * 186 (solid): SHELL, SOF, N, then (VOID shell, VOF) pairs.
//!
//! Every entity is tallied in the report as converted or invalid (with the reason naming the
//! face); B-rep entities no solid, shell or face reaches are listed as not read.
//!
//! [`Edge`]: crate::brep::Edge
//! [`Vertex`]: crate::brep::Vertex

mod edges;

use super::{R, Reader};
use crate::brep::{Brep, Face, IssueKind, Loop, LoopKind, OrientedEdge, Shell, Solid};
use std::collections::{BTreeMap, BTreeSet};

/// B-rep entity types this reader walks.
const TYPES: [i64; 6] = [186, 514, 510, 508, 504, 502];

fn type_name(t: i64) -> String {
    match t {
        186 => "186 solid",
        514 => "514 shell",
        510 => "510 face",
        508 => "508 loop",
        504 => "504 edge list",
        502 => "502 vertex list",
        _ => return format!("{t}"),
    }
    .to_string()
}

/// Builds a [`Brep`] from the parsed file.
struct Topo<'a, 'r> {
    r: &'a Reader<'r>,
    brep: Brep,
    vertices: BTreeMap<(usize, usize), Option<usize>>,
    edges: BTreeMap<(usize, usize), Option<usize>>,
    faces: BTreeMap<usize, usize>,
    shells: BTreeMap<usize, Option<usize>>,
    seen: BTreeSet<usize>,
}

/// A loop entry: the list DE, the entry (from 1), whether it is a vertex (TYPE 1), the
/// orientation flag and the parameter-space curve DEs.
struct Use {
    list: usize,
    ndx: usize,
    vertex: bool,
    forward: bool,
    pcurves: Vec<usize>,
}

/// An edge list entry: its curve DE and its start and end vertices (list DE, entry).
type ListEdge = (usize, (usize, usize), (usize, usize));

impl Reader<'_> {
    /// The entries of loop `lp` (508).
    fn loop_uses(&self, lp: usize) -> R<Vec<Use>> {
        let n = self.count(lp, 1)?;
        let mut at = 2;
        let mut out = Vec::with_capacity(n.min(1024));
        for _ in 0..n {
            let v = self.nums(lp, at, 5)?;
            let k = self.count(lp, at + 4)?;
            let mut pcurves = Vec::new();
            for j in 0..k {
                pcurves.push(self.ptr(lp, at + 6 + 2 * j)?);
            }
            let ndx = v[2];
            if !(ndx >= 1.0 && ndx.fract() == 0.0 && ndx < 1e9) {
                return self.err(lp, format!("edge {} has entry number {ndx}", out.len() + 1));
            }
            out.push(Use {
                list: self.ptr(lp, at + 1)?,
                ndx: ndx as usize,
                vertex: v[0] == 1.0,
                forward: v[3] != 0.0,
                pcurves,
            });
            at += 5 + 2 * k;
        }
        Ok(out)
    }

    /// A non-negative whole count parameter, at most 10⁶.
    fn count(&self, de: usize, i: usize) -> R<usize> {
        let x = self.nums(de, i, 1)?[0];
        if !(x >= 0.0 && x.fract() == 0.0 && x <= 1e6) {
            return self.err(de, format!("parameter {i} ({x}) is not a count"));
        }
        Ok(x as usize)
    }

    /// Vertex `k` (from 1) of vertex list `list` (502).
    fn list_vertex(&self, list: usize, k: usize) -> R<[f64; 3]> {
        if self.e[&list].etype != 502 {
            return self.err(list, "expected a 502 vertex list");
        }
        let n = self.count(list, 1)?;
        if k == 0 || k > n {
            return self.err(list, format!("vertex {k} asked of a list of {n}"));
        }
        let v = self.nums(list, 2 + 3 * (k - 1), 3)?;
        let mut p = [[v[0], v[1], v[2]]];
        self.apply(list, &mut p)?;
        Ok(p[0])
    }

    /// Edge `k` (from 1) of edge list `list` (504): curve DE, start (list, entry), end.
    fn list_edge(&self, list: usize, k: usize) -> R<ListEdge> {
        if self.e[&list].etype != 504 {
            return self.err(list, "expected a 504 edge list");
        }
        let n = self.count(list, 1)?;
        if k == 0 || k > n {
            return self.err(list, format!("edge {k} asked of a list of {n}"));
        }
        let at = 2 + 5 * (k - 1);
        let v = self.nums(list, at, 5)?;
        let whole = |x: f64| x >= 1.0 && x.fract() == 0.0 && x < 1e9;
        if !whole(v[2]) || !whole(v[4]) {
            return self.err(
                list,
                format!("edge {k}: vertex entry numbers {} {}", v[2], v[4]),
            );
        }
        Ok((
            self.ptr(list, at)?,
            (self.ptr(list, at + 1)?, v[2] as usize),
            (self.ptr(list, at + 3)?, v[4] as usize),
        ))
    }

    /// Points of face `face` (510): its vertices and the control points of its edge curves
    /// (whose convex hull holds the edges). Faults give fewer points, never an error: the
    /// topology reader reports them.
    pub(super) fn face_points(&self, face: usize) -> Vec<[f64; 3]> {
        let mut pts = Vec::new();
        let Ok(n) = self.count(face, 2) else {
            return pts;
        };
        for k in 0..n {
            let Some(uses) = self.ptr(face, 4 + k).ok().and_then(|lp| {
                (self.e[&lp].etype == 508)
                    .then(|| self.loop_uses(lp).ok())
                    .flatten()
            }) else {
                continue;
            };
            for u in uses {
                if u.vertex {
                    pts.extend(self.list_vertex(u.list, u.ndx).ok());
                    continue;
                }
                let Ok((c, s, t)) = self.list_edge(u.list, u.ndx) else {
                    continue;
                };
                pts.extend(self.list_vertex(s.0, s.1).ok());
                pts.extend(self.list_vertex(t.0, t.1).ok());
                if let Ok(Some(segs)) = self.segments(c, 0) {
                    for s in segs {
                        pts.extend(s.points_weights().0);
                    }
                }
            }
        }
        pts
    }
}

/// Read the B-rep of a file with 510 faces. `surface_of`: the model surface index of each
/// face DE whose surface was converted; `tolerance`: vertex-to-curve gaps above it are issues.
pub(super) fn read(r: &Reader, surface_of: &BTreeMap<usize, usize>, tolerance: f64) -> Brep {
    let mut t = Topo {
        r,
        brep: Brep {
            tolerance,
            ..Brep::default()
        },
        vertices: BTreeMap::new(),
        edges: BTreeMap::new(),
        faces: BTreeMap::new(),
        shells: BTreeMap::new(),
        seen: BTreeSet::new(),
    };
    for (de, x) in r.e {
        if x.etype == 510 {
            t.face(*de, surface_of.get(de).copied());
        }
    }
    for (de, x) in r.e {
        if x.etype == 514 {
            t.shell(*de);
        }
    }
    for (de, x) in r.e {
        if x.etype == 186 {
            t.solid(*de);
        }
    }
    for (de, x) in r.e {
        if TYPES.contains(&x.etype) && !t.seen.contains(de) {
            t.brep
                .report
                .entities
                .entry(type_name(x.etype))
                .or_default()
                .not_read
                .push(format!("DE {de}"));
        }
    }
    let issues = t.brep.check();
    t.brep.report.issues.extend(issues);
    t.brep
}

impl Topo<'_, '_> {
    fn converted(&mut self, de: usize) {
        if self.seen.insert(de) {
            self.brep.report.converted(&type_name(self.r.e[&de].etype));
        }
    }

    fn invalid(&mut self, de: usize, face: Option<usize>, reason: String) {
        let ty = type_name(self.r.e.get(&de).map_or(0, |x| x.etype));
        self.seen.insert(de);
        self.brep.report.invalid(
            &ty,
            &format!("DE {de}"),
            face.map(|f| format!("DE {f}")).as_deref(),
            IssueKind::Malformed(reason),
        );
    }

    fn face(&mut self, de: usize, surface: Option<usize>) {
        let r = self.r;
        let head = r
            .ptr(de, 1)
            .and_then(|s| Ok((s, r.count(de, 2)?, r.nums(de, 3, 1)?[0])));
        let (sde, n, of) = match head {
            Ok(h) => h,
            Err(e) => return self.invalid(de, Some(de), e.reason),
        };
        let mut loops = Vec::new();
        for k in 0..n {
            let lp = match r.ptr(de, 4 + k) {
                Ok(lp) if r.e[&lp].etype == 508 => lp,
                Ok(lp) => {
                    let ty = r.e[&lp].etype;
                    return self.invalid(
                        de,
                        Some(de),
                        format!("loop {k} is DE {lp} of type {ty}, not a 508 loop"),
                    );
                }
                Err(e) => return self.invalid(de, Some(de), e.reason),
            };
            if let Some(l) = self.loop_(de, sde, lp, k == 0 && of == 1.0) {
                loops.push(l);
            }
        }
        self.converted(de);
        self.faces.insert(de, self.brep.faces.len());
        self.brep.faces.push(Face {
            source: format!("DE {de}"),
            surface,
            surface_source: format!("DE {sde}"),
            same_sense: true,
            loops,
        });
    }

    fn loop_(&mut self, face: usize, surface: usize, lp: usize, outer: bool) -> Option<Loop> {
        let uses = match self.r.loop_uses(lp) {
            Ok(u) => u,
            Err(e) => {
                self.invalid(lp, Some(face), e.reason);
                return None;
            }
        };
        let kind = if uses.len() == 1 && uses[0].vertex {
            LoopKind::Vertex(self.vertex((uses[0].list, uses[0].ndx), face)?)
        } else {
            let mut es = Vec::with_capacity(uses.len());
            for u in &uses {
                if u.vertex {
                    // A degenerate edge: its vertex must exist; the loop runs through it.
                    self.vertex((u.list, u.ndx), face)?;
                    continue;
                }
                let edge = self.edge((u.list, u.ndx), face)?;
                for &c in &u.pcurves {
                    self.pcurve(edge, c, surface, u.forward);
                }
                es.push(OrientedEdge {
                    edge,
                    forward: u.forward,
                });
            }
            LoopKind::Edges(es)
        };
        self.converted(lp);
        Some(Loop {
            source: format!("DE {lp}"),
            loop_source: format!("DE {lp}"),
            outer,
            orientation: true,
            kind,
        })
    }

    fn shell(&mut self, de: usize) -> Option<usize> {
        if let Some(s) = self.shells.get(&de) {
            return *s;
        }
        self.shells.insert(de, None);
        let r = self.r;
        let n = match r.count(de, 1) {
            Ok(n) => n,
            Err(e) => {
                self.invalid(de, None, e.reason);
                return None;
            }
        };
        let mut faces = Vec::with_capacity(n.min(1 << 16));
        for k in 0..n {
            let f = r
                .ptr(de, 2 + 2 * k)
                .and_then(|f| Ok((f, r.nums(de, 3 + 2 * k, 1)?[0])));
            match f {
                Ok((f, of)) if self.faces.contains_key(&f) => {
                    faces.push((self.faces[&f], of != 0.0));
                }
                Ok((f, _)) => {
                    let ty = r.e[&f].etype;
                    self.invalid(
                        de,
                        None,
                        format!("face {k} is DE {f} of type {ty}, not a read 510 face"),
                    );
                    return None;
                }
                Err(e) => {
                    self.invalid(de, None, e.reason);
                    return None;
                }
            }
        }
        self.converted(de);
        self.brep.shells.push(Shell {
            source: format!("DE {de}"),
            closed: r.e[&de].form == 1,
            faces,
        });
        let i = self.brep.shells.len() - 1;
        self.shells.insert(de, Some(i));
        Some(i)
    }

    fn solid(&mut self, de: usize) {
        let r = self.r;
        let head = r.ptr(de, 1).and_then(|s| Ok((s, r.count(de, 3)?)));
        let (outer, n) = match head {
            Ok(h) => h,
            Err(e) => return self.invalid(de, None, e.reason),
        };
        let shell = |t: &mut Self, s: usize| -> Option<usize> {
            (r.e[&s].etype == 514).then(|| t.shell(s)).flatten()
        };
        let Some(outer) = shell(self, outer) else {
            return self.invalid(
                de,
                None,
                format!("shell DE {outer} is not a read 514 shell"),
            );
        };
        let mut voids = Vec::new();
        for k in 0..n {
            match r.ptr(de, 4 + 2 * k).map(|v| (v, shell(self, v))) {
                Ok((_, Some(v))) => voids.push(v),
                Ok((v, None)) => {
                    return self.invalid(
                        de,
                        None,
                        format!("void shell DE {v} is not a read 514 shell"),
                    );
                }
                Err(e) => return self.invalid(de, None, e.reason),
            }
        }
        self.converted(de);
        self.brep.solids.push(Solid {
            source: format!("DE {de}"),
            outer,
            voids,
        });
    }
}
