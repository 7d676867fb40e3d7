//! STEP writer for a model with a B-rep: ISO 10303-42 topology in an AP214 file. Solids are
//! `manifold_solid_brep` (`brep_with_voids` with voids) over `closed_shell`s; shells outside
//! solids go into one `shell_based_surface_model`. Faces are `advanced_face`s with their
//! `same_sense`, bounded by `face_outer_bound`/`face_bound` over `edge_loop`s of
//! `oriented_edge`s or `vertex_loop`s; every edge is one `edge_curve` (written once, referenced
//! by every loop that uses it) between two `vertex_point`s, its 3D curve a B-spline curve
//! running from the start vertex to the end vertex (`same_sense = .T.`). Surfaces are the
//! model's NURBS surfaces, bit for bit.
//!
//! What the file does not hold is returned as notes: analytic surfaces and curves are written
//! in their exact NURBS forms (the type is not kept), pcurves are written where
//! [`crate::brep::pcurve::Pcurves`] gives one (the source's own on its B-spline surfaces,
//! exact ones on planes, projected ones with their proven bounds elsewhere, summed up in a
//! note) and left out where it gives none, and faces without a surface or loops over an
//! edge without a curve are left out, named. A cap's vertex loop away from the pole of its
//! surface's NURBS form is written at the pole (named).

use super::write::{Out, refs, text};
use crate::brep::pcurve::Pcurves;
use crate::brep::seam_edges::caps_off_their_poles;
use crate::brep::{Brep, LoopKind};
use crate::model::{CurveGeometry, Model};
use std::collections::{BTreeMap, BTreeSet};

/// Items written once and referenced by id.
struct Topology<'a> {
    m: &'a Model,
    b: &'a Brep,
    o: Out,
    vertices: BTreeMap<usize, u64>,
    edges: BTreeMap<usize, u64>,
    surfaces: BTreeMap<usize, u64>,
    /// Model surfaces of the faces whose loops use each edge, with the first such face.
    uses: Vec<Vec<(usize, usize)>>,
    /// The parameter-space representation context of the pcurves.
    context_2d: Option<u64>,
    /// `(edge, model surface)` of every pcurve written.
    pcurves: BTreeSet<(usize, usize)>,
    /// Where the pcurves come from.
    pcs: Pcurves<'a>,
    /// `(face, loop)` → the pole a cap's vertex loop is written at
    /// ([`crate::brep::seam_edges::caps_off_their_poles`]).
    cap_poles: BTreeMap<(usize, usize), [f64; 3]>,
}

impl Topology<'_> {
    /// The `vertex_point` of vertex `v` (`None` for an index outside the B-rep's vertices).
    fn vertex(&mut self, v: usize) -> Option<u64> {
        if let Some(id) = self.vertices.get(&v) {
            return Some(*id);
        }
        let p = self.o.point(&self.b.vertices.get(v)?.point);
        let id = self.o.add(&format!("VERTEX_POINT('',#{p})"));
        self.vertices.insert(v, id);
        Some(id)
    }

    /// Whether edge `e` can be written: it exists, has a curve and both its vertices exist.
    fn writable(&self, e: usize) -> bool {
        self.b.edges.get(e).is_some_and(|x| {
            x.curve.is_some() && x.start < self.b.vertices.len() && x.end < self.b.vertices.len()
        })
    }

    /// The `edge_curve` of edge `e`; `None` when it has no curve.
    fn edge(&mut self, e: usize) -> Option<u64> {
        if let Some(id) = self.edges.get(&e) {
            return Some(*id);
        }
        if !self.writable(e) {
            return None;
        }
        let edge = &self.b.edges[e];
        let curve = edge.curve.as_ref()?;
        let (v0, v1) = (self.vertex(edge.start)?, self.vertex(edge.end)?);
        let mut g = self.o.curve(&curve.nurbs, "");
        // Pcurves on the faces along the edge: the source's on its B-spline surfaces, exact
        // ones on planes.
        let mut pcurves = Vec::new();
        for (si, fi) in self.uses.get(e).cloned().unwrap_or_default() {
            let Some(pc) = self.pcs.get(e, fi) else {
                continue;
            };
            let s = self.surface(si);
            let c2 = self.o.curve(&pc, "");
            let ctx = match self.context_2d {
                Some(c) => c,
                None => {
                    let c = self.o.add("(GEOMETRIC_REPRESENTATION_CONTEXT(2) PARAMETRIC_REPRESENTATION_CONTEXT() REPRESENTATION_CONTEXT('2D SPACE',''))");
                    self.context_2d = Some(c);
                    c
                }
            };
            let dr = self
                .o
                .add(&format!("DEFINITIONAL_REPRESENTATION('',(#{c2}),#{ctx})"));
            pcurves.push(self.o.add(&format!("PCURVE('',#{s},#{dr})")));
            self.pcurves.insert((e, si));
        }
        if !pcurves.is_empty() {
            g = self.o.add(&format!(
                "SURFACE_CURVE('',#{g},{},.CURVE_3D.)",
                refs(&pcurves)
            ));
        }
        let id = self.o.add(&format!(
            "EDGE_CURVE('{}',#{v0},#{v1},#{g},.T.)",
            text(&edge.source)
        ));
        self.edges.insert(e, id);
        Some(id)
    }

    /// The surface entity of model surface `si`.
    fn surface(&mut self, si: usize) -> u64 {
        if let Some(s) = self.surfaces.get(&si) {
            return *s;
        }
        let s = self.o.surface(&self.m.surfaces[si].nurbs, "");
        self.surfaces.insert(si, s);
        s
    }

    /// The `advanced_face` of face `f`, or why it is left out; `flip`: written reversed
    /// (`same_sense` and every bound's orientation negated: the face an `oriented_face` with
    /// orientation `.F.` would make of it).
    fn face(&mut self, f: usize, flip: bool, notes: &mut Vec<String>) -> Option<u64> {
        let face = &self.b.faces[f];
        let Some(si) = face.surface.filter(|s| *s < self.m.surfaces.len()) else {
            notes.push(format!(
                "face {} not written: its surface {} was not converted",
                face.source, face.surface_source
            ));
            return None;
        };
        let mut bounds = Vec::new();
        for (li, l) in face.loops.iter().enumerate() {
            let lp = match &l.kind {
                LoopKind::Vertex(_) if self.cap_poles.contains_key(&(f, li)) => {
                    let pole = self.cap_poles[&(f, li)];
                    let p = self.o.point(&pole);
                    let v = self.o.add(&format!("VERTEX_POINT('',#{p})"));
                    notes.push(format!(
                        "vertex loop {} of face {} written at the pole of its surface, where the face's cap closes",
                        l.source, face.source
                    ));
                    self.o.add(&format!("VERTEX_LOOP('',#{v})"))
                }
                LoopKind::Vertex(v) => {
                    let Some(v) = self.vertex(*v) else {
                        notes.push(format!(
                            "loop {} of face {} not written: its vertex {v} does not exist",
                            l.source, face.source
                        ));
                        continue;
                    };
                    self.o.add(&format!("VERTEX_LOOP('',#{v})"))
                }
                LoopKind::Edges(oes) => {
                    if let Some(bad) = oes.iter().find(|oe| !self.writable(oe.edge)) {
                        notes.push(format!(
                            "loop {} of face {} not written: its edge {} has no 3D curve or vertex",
                            l.source,
                            face.source,
                            self.b
                                .edges
                                .get(bad.edge)
                                .map_or("?", |e| e.source.as_str())
                        ));
                        continue;
                    }
                    let mut oe = Vec::with_capacity(oes.len());
                    for x in oes {
                        let e = self.edge(x.edge).unwrap_or_default();
                        oe.push(self.o.add(&format!(
                            "ORIENTED_EDGE('',*,*,#{e},{})",
                            logical(x.forward)
                        )));
                    }
                    self.o.add(&format!("EDGE_LOOP('',{})", refs(&oe)))
                }
            };
            let ty = if l.outer {
                "FACE_OUTER_BOUND"
            } else {
                "FACE_BOUND"
            };
            bounds.push(self.o.add(&format!(
                "{ty}('',#{lp},{})",
                logical(l.orientation != flip)
            )));
        }
        if bounds.is_empty() {
            // An advanced face needs at least one bound.
            notes.push(format!(
                "face {} not written: none of its loops could be written",
                face.source
            ));
            return None;
        }
        let s = self.surface(si);
        Some(self.o.add(&format!(
            "ADVANCED_FACE('{}',{},#{s},{})",
            text(&face.source),
            refs(&bounds),
            logical(face.same_sense != flip)
        )))
    }
}

/// For each edge, the model surfaces (each once) of the faces whose loops use it, each with
/// the first such face.
fn edge_surfaces(m: &Model, b: &Brep) -> Vec<Vec<(usize, usize)>> {
    let mut uses: Vec<Vec<(usize, usize)>> = vec![Vec::new(); b.edges.len()];
    for (fi, f) in b.faces.iter().enumerate() {
        let Some(si) = f.surface.filter(|s| *s < m.surfaces.len()) else {
            continue;
        };
        for l in &f.loops {
            if let LoopKind::Edges(oes) = &l.kind {
                for oe in oes {
                    if let Some(u) = uses.get_mut(oe.edge)
                        && !u.iter().any(|x| x.0 == si)
                    {
                        u.push((si, fi));
                    }
                }
            }
        }
    }
    uses
}

/// `.T.` or `.F.`.
fn logical(b: bool) -> &'static str {
    if b { ".T." } else { ".F." }
}

/// The model with its B-rep `b` as STEP text, and what the file does not hold.
pub(super) fn write(m: &Model, b: &Brep, name: &str) -> (String, Vec<String>) {
    let mut notes = Vec::new();
    let mut t = Topology {
        m,
        b,
        o: Out::default(),
        vertices: BTreeMap::new(),
        edges: BTreeMap::new(),
        surfaces: BTreeMap::new(),
        uses: edge_surfaces(m, b),
        context_2d: None,
        pcurves: BTreeSet::new(),
        pcs: Pcurves::new(b, m),
        cap_poles: caps_off_their_poles(m, b)
            .into_iter()
            .map(|(f, l, pole)| ((f, l), pole))
            .collect(),
    };
    // A face every shell uses reversed is written reversed, so that no `oriented_face` is
    // needed (Open CASCADE 8.0.1 drops faces given as `oriented_face` in a shell: it read one
    // face of three from gmsh-periodic_u_cst written this way).
    let mut uses: Vec<(bool, bool)> = vec![(false, false); b.faces.len()];
    for s in &b.shells {
        for (f, orientation) in &s.faces {
            if let Some(u) = uses.get_mut(*f) {
                if *orientation {
                    u.0 = true;
                } else {
                    u.1 = true;
                }
            }
        }
    }
    let flipped: Vec<bool> = uses.iter().map(|&(fwd, rev)| rev && !fwd).collect();
    let faces: Vec<Option<u64>> = (0..b.faces.len())
        .map(|f| t.face(f, flipped[f], &mut notes))
        .collect();
    notes.extend(t.pcs.note());
    // Shells, each face as the shell uses it.
    let mut in_shell = BTreeSet::new();
    let mut shells = Vec::with_capacity(b.shells.len());
    for s in &b.shells {
        let mut ids = Vec::with_capacity(s.faces.len());
        for (f, orientation) in &s.faces {
            let Some(id) = faces.get(*f).copied().flatten() else {
                notes.push(format!(
                    "shell {} written without face {} (not written)",
                    s.source,
                    b.faces.get(*f).map_or("?", |x| x.source.as_str())
                ));
                continue;
            };
            in_shell.insert(*f);
            ids.push(if *orientation || flipped[*f] {
                id
            } else {
                t.o.add(&format!("ORIENTED_FACE('',*,#{id},.F.)"))
            });
        }
        let ty = if s.closed {
            "CLOSED_SHELL"
        } else {
            "OPEN_SHELL"
        };
        shells.push(t.o.add(&format!("{ty}('{}',{})", text(&s.source), refs(&ids))));
    }
    // Faces of no shell: one more open shell, so that they are part of the shape.
    let loose: Vec<u64> = faces
        .iter()
        .enumerate()
        .filter(|(f, id)| id.is_some() && !in_shell.contains(f))
        .filter_map(|(_, id)| *id)
        .collect();
    let mut free_shells: Vec<u64> = Vec::new();
    if !loose.is_empty() {
        notes.push(format!(
            "{} face(s) in no shell written in an added open shell",
            loose.len()
        ));
        free_shells.push(t.o.add(&format!("OPEN_SHELL('',{})", refs(&loose))));
    }
    let mut in_solid = BTreeSet::new();
    let mut solids = Vec::with_capacity(b.solids.len());
    for s in &b.solids {
        let Some(outer) = shells.get(s.outer).copied() else {
            notes.push(format!("solid {} not written: no outer shell", s.source));
            continue;
        };
        in_solid.insert(s.outer);
        in_solid.extend(s.voids.iter().copied());
        let id = if s.voids.is_empty() {
            t.o.add(&format!(
                "MANIFOLD_SOLID_BREP('{}',#{outer})",
                text(&s.source)
            ))
        } else {
            let voids: Vec<u64> = s
                .voids
                .iter()
                .filter_map(|v| shells.get(*v))
                .map(|v| t.o.add(&format!("ORIENTED_CLOSED_SHELL('',*,#{v},.F.)")))
                .collect();
            t.o.add(&format!(
                "BREP_WITH_VOIDS('{}',#{outer},{})",
                text(&s.source),
                refs(&voids)
            ))
        };
        solids.push(id);
    }
    let mut open: Vec<u64> = (0..shells.len())
        .filter(|i| !in_solid.contains(i))
        .map(|i| shells[i])
        .collect();
    open.extend(free_shells);
    let mut items = solids.clone();
    if !open.is_empty() {
        items.push(t.o.add(&format!("SHELL_BASED_SURFACE_MODEL('',{})", refs(&open))));
    }
    let free = free_geometry(&mut t, &mut notes);
    items.extend(free);
    let rep = if items.len() == solids.len() && !solids.is_empty() {
        "ADVANCED_BREP_SHAPE_REPRESENTATION"
    } else if solids.is_empty() && items.len() == 1 && !open.is_empty() {
        "MANIFOLD_SURFACE_SHAPE_REPRESENTATION"
    } else {
        "SHAPE_REPRESENTATION"
    };
    // The file's uncertainty, so that other readers work to the tolerance the model was read to.
    let uncertainty = (b.tolerance > 0.0 && b.tolerance.is_finite()).then_some(b.tolerance);
    t.o.shape(m.unit.as_deref().unwrap_or("mm"), uncertainty, rep, &items);
    conversion_notes(m, b, &t, &mut notes);
    (t.o.finish(name, "vericad B-rep"), notes)
}

/// Surfaces no face uses and curves that are not an edge's curve, as a geometric set (`None`
/// when there are none).
fn free_geometry(t: &mut Topology, notes: &mut Vec<String>) -> Option<u64> {
    let (m, b) = (t.m, t.b);
    let used: BTreeSet<usize> = b.faces.iter().filter_map(|f| f.surface).collect();
    let mut items = Vec::new();
    for (i, s) in m.surfaces.iter().enumerate() {
        if !used.contains(&i) {
            items.push(t.o.surface(&s.nurbs, &s.name));
        }
    }
    // A curve read from the file that is an edge's curve is written as that edge's range.
    let edge_curves: BTreeMap<&str, Vec<usize>> =
        b.edges
            .iter()
            .enumerate()
            .fold(BTreeMap::new(), |mut acc, (i, e)| {
                if let Some(c) = &e.curve {
                    acc.entry(c.source.as_str()).or_default().push(i);
                }
                acc
            });
    // Pcurves of the source are read as curves too (z = 0); they are not written again.
    let pcurves: Vec<&crate::spline::NurbsCurve<f64, 2>> = b
        .edges
        .iter()
        .flat_map(|e| &e.pcurves)
        .filter_map(|p| match &p.geometry {
            crate::brep::PCurveGeometry::Nurbs(n) => Some(n),
            crate::brep::PCurveGeometry::Line { .. } => None,
        })
        .collect();
    let mut partial = Vec::new();
    for c in &m.curves {
        if c.geometry
            .to_domain()
            .is_some_and(|d| pcurves.iter().any(|p| **p == d))
        {
            continue;
        }
        match edge_curves.get(c.name.as_str()) {
            Some(es) => {
                if let CurveGeometry::Space(g) = &c.geometry {
                    let whole = es.iter().any(|e| {
                        b.edges[*e]
                            .curve
                            .as_ref()
                            .is_some_and(|x| x.nurbs == *g || x.nurbs.reversed() == *g)
                    });
                    if !whole {
                        partial.push(c.name.clone());
                    }
                }
            }
            None => items.push(t.o.curve(&c.geometry.to_space(), &c.name)),
        }
    }
    if !partial.is_empty() {
        notes.push(format!(
            "{} curve(s) of the file are written only over their edges' ranges: {}",
            partial.len(),
            crate::model::list_ids(partial)
        ));
    }
    (!items.is_empty()).then(|| t.o.add(&format!("GEOMETRIC_SET('',{})", refs(&items))))
}

/// Notes on what changes form: analytic surfaces and curves written as NURBS, source pcurves
/// replaced by the writer's or left out.
fn conversion_notes(m: &Model, b: &Brep, t: &Topology, notes: &mut Vec<String>) {
    let analytic = t
        .surfaces
        .keys()
        .filter(|i| m.surfaces[**i].kind.is_analytic())
        .count();
    if analytic > 0 {
        notes.push(format!(
            "{analytic} analytic face surface(s) (planes, cylinders, cones, spheres, tori, swept) written as their exact NURBS forms"
        ));
    }
    let conics = t
        .edges
        .keys()
        .filter_map(|e| b.edges[*e].curve.as_ref())
        .filter(|c| {
            matches!(
                c.kind,
                crate::brep::CurveKind::Line
                    | crate::brep::CurveKind::Circle
                    | crate::brep::CurveKind::Ellipse
            )
        })
        .count();
    if conics > 0 {
        notes.push(format!(
            "{conics} edge curve(s) (lines, circles, ellipses) written as their exact B-spline forms"
        ));
    }
    // A pcurve of the source is replaced when the writer computed one on the same surface.
    let mut lost = Vec::new();
    for (i, e) in b.edges.iter().enumerate() {
        for pc in &e.pcurves {
            let replaced = b.faces.iter().any(|f| {
                f.surface_source == pc.surface_source
                    && f.surface.is_some_and(|s| t.pcurves.contains(&(i, s)))
            });
            if !replaced {
                lost.push(pc.source.clone());
            }
        }
    }
    if !lost.is_empty() {
        notes.push(format!(
            "{} pcurve(s) of the source not written (the edges' 3D curves are; pcurves only the source's own on its B-spline surfaces and exact ones on planes): {}",
            lost.len(),
            crate::model::list_ids(lost)
        ));
    }
}
