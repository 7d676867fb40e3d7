//! IGES writer for a model with a B-rep (IGES 5.3 B-rep entities): one vertex list (502) of
//! every vertex, one edge list (504) of every edge with its model-space curve (126, from the
//! start vertex to the end vertex), a loop (508) per edge loop — each edge once in the edge
//! list, referenced by every loop that uses it, with its orientation — a face (510) per face
//! over its B-spline surface (128), the outer loop first, a shell (514, form 1 closed, form 2
//! open) per shell with each face's orientation relative to its surface normal, and a
//! manifold solid B-rep object (186) per solid, its voids as further shells.
//!
//! What is written is the B-rep with its seams made explicit
//! ([`crate::brep::seam_edges::explicit_seams`]): a face bounded by loops that run round its
//! closed surface gets one loop with a seam edge, its pole edges written as vertex uses
//! (TYPE 1), each use with the pcurve the rebuilding made.
//!
//! The other loops carry parameter-space curves where [`crate::brep::pcurve::Pcurves`] gives
//! one, each running the way the loop uses the edge (as Open CASCADE reads them): the
//! source's own on its B-spline surfaces, exact ones on planar faces (the edge curves mapped
//! by the inverse of the plane's affine parametrization), projected ones elsewhere (with a
//! proven bound where one can be had; a note sums them up). Where it gives none, readers
//! project the edge. What the file does not hold is returned as notes.

use super::write::{DEPENDENT, Params, curve_126, surface_128};
use crate::brep::pcurve::Pcurves;
use crate::brep::seam_edges::{Seamed, explicit_seams};
use crate::brep::{Brep, Face, LoopKind, OrientedEdge};
use crate::geom::dist;
use crate::model::{CurveGeometry, Model};
use crate::spline::NurbsCurve;
use std::collections::{BTreeMap, BTreeSet};

/// Status of an entity used by another (physically dependent).
pub(super) const USED: &str = "00010000";

fn de_next(p: &Params) -> usize {
    2 * p.len() + 1
}

/// Add an entity of form 0.
pub(super) fn push(p: &mut Params, ty: i64, text: String, status: &'static str) -> usize {
    push_form(p, ty, 0, text, status)
}

fn push_form(p: &mut Params, ty: i64, form: u8, text: String, status: &'static str) -> usize {
    let d = de_next(p);
    p.push((ty, text, status, form));
    d
}

/// The loop's edges in the order the loop runs (a bound with orientation .F. reversed).
pub(super) fn ordered(oes: &[OrientedEdge], orientation: bool) -> Vec<OrientedEdge> {
    if orientation {
        return oes.to_vec();
    }
    oes.iter()
        .rev()
        .map(|o| OrientedEdge {
            edge: o.edge,
            forward: !o.forward,
        })
        .collect()
}

/// Write the B-rep `b`; returns the model surfaces written as faces.
pub(super) fn brep(
    m: &Model,
    b: &Brep,
    p: &mut Params,
    notes: &mut Vec<String>,
) -> BTreeSet<usize> {
    let mut written = BTreeSet::new();
    let seamed = explicit_seams(m, b, notes);
    let b = &seamed.brep;
    let mut pcs = Pcurves::new(b, m);
    let mut coords = format!("502,{}", b.vertices.len());
    for v in &b.vertices {
        for x in v.point {
            coords += &format!(",{}", super::write::real(x));
        }
    }
    let vl = push_form(p, 502, 1, coords + ";", USED);
    // Edges with a curve, numbered from 1 in the edge list.
    let mut index = BTreeMap::new();
    let mut entries = String::new();
    for (i, e) in b.edges.iter().enumerate() {
        let Some(c) = e.curve.as_ref().filter(|_| !seamed.poles.contains(&i)) else {
            continue;
        };
        if e.start >= b.vertices.len() || e.end >= b.vertices.len() {
            continue;
        }
        let cde = push(p, 126, curve_126(&c.nurbs), USED);
        index.insert(i, index.len() + 1);
        entries += &format!(",{cde},{vl},{},{vl},{}", e.start + 1, e.end + 1);
    }
    let el = push_form(p, 504, 1, format!("504,{}{entries};", index.len()), USED);
    let mut face_de = vec![None; b.faces.len()];
    // `(edge, model surface)` of every parameter-space curve written.
    let mut written_pc = BTreeSet::new();
    for (fi, face) in b.faces.iter().enumerate() {
        let Some(si) = face_surface(m, face, notes) else {
            continue;
        };
        let mut loops: Vec<(bool, usize)> = Vec::new();
        for l in &face.loops {
            let text = match &l.kind {
                LoopKind::Vertex(v) if *v < b.vertices.len() => {
                    format!("508,1,1,{vl},{},1,0;", v + 1)
                }
                LoopKind::Vertex(v) => {
                    notes.push(format!(
                        "loop {} of face {} not written: its vertex {v} does not exist",
                        l.source, face.source
                    ));
                    continue;
                }
                LoopKind::Edges(oes) => {
                    // IGES faces have no sense: the loops run counter-clockwise about the
                    // surface's normal around the face (reversed for same_sense .F.; the
                    // shell's flag says the face is used reversed).
                    let oes = ordered(oes, l.orientation == face.same_sense);
                    let pole = |o: &OrientedEdge| seamed.poles.contains(&o.edge);
                    if let Some(bad) = oes
                        .iter()
                        .find(|o| !index.contains_key(&o.edge) && !pole(o))
                    {
                        notes.push(format!(
                            "loop {} of face {} not written: its edge {} has no 3D curve or vertex",
                            l.source,
                            face.source,
                            b.edges.get(bad.edge).map_or("?", |e| e.source.as_str())
                        ));
                        continue;
                    }
                    let mut t = format!("508,{}", oes.len());
                    let pcurves = loop_pcurves(&mut pcs, &seamed, fi, &oes);
                    for (o, pc) in oes.iter().zip(pcurves) {
                        if pc.is_some() {
                            written_pc.insert((o.edge, si));
                        }
                        let k = match pc {
                            Some(pc) => {
                                let d = push(
                                    p,
                                    126,
                                    curve_126(&CurveGeometry::Domain(pc).to_space()),
                                    DEPENDENT,
                                );
                                format!("1,0,{d}")
                            }
                            None => "0".to_string(),
                        };
                        t += &match index.get(&o.edge) {
                            Some(i) => format!(",0,{el},{i},{},{k}", u8::from(o.forward)),
                            // A pole: a degenerate edge, written as its vertex (TYPE 1).
                            None => format!(",1,{vl},{},1,{k}", b.edges[o.edge].start + 1),
                        };
                    }
                    t + ";"
                }
            };
            loops.push((l.outer, push_form(p, 508, 1, text, USED)));
        }
        if loops.is_empty() {
            notes.push(format!(
                "face {} not written: none of its loops could be written",
                face.source
            ));
            continue;
        }
        // The outer loop first: the first loop declared outer.
        let outer = loops.iter().position(|l| l.0);
        if let Some(k) = outer {
            let l = loops.remove(k);
            loops.insert(0, l);
        }
        let sde = push(p, 128, surface_128(&m.surfaces[si].nurbs), USED);
        written.insert(si);
        let ls: String = loops.iter().map(|l| format!(",{}", l.1)).collect();
        face_de[fi] = Some(push_form(
            p,
            510,
            1,
            format!(
                "510,{sde},{},{}{ls};",
                loops.len(),
                u8::from(outer.is_some())
            ),
            USED,
        ));
    }
    notes.extend(pcs.note());
    shells_and_solids(b, p, &face_de, notes);
    // A source pcurve is written back where a loop on its surface carries one for the edge.
    let lost = b
        .edges
        .iter()
        .enumerate()
        .flat_map(|(i, e)| e.pcurves.iter().map(move |pc| (i, pc)))
        .filter(|(i, pc)| {
            !b.faces.iter().any(|f| {
                f.surface_source == pc.surface_source
                    && f.surface.is_some_and(|s| written_pc.contains(&(*i, s)))
            })
        })
        .count();
    if lost > 0 {
        notes.push(format!(
            "{lost} pcurve(s) of the source not written (the edges' model-space curves are; parameter-space curves only the source's own on its B-spline surfaces and exact ones on planes)"
        ));
    }
    written
}

/// The model surface of `face`, or `None` with a note that the face is not written.
pub(super) fn face_surface(m: &Model, face: &Face, notes: &mut Vec<String>) -> Option<usize> {
    let si = face.surface.filter(|s| *s < m.surfaces.len());
    if si.is_none() {
        notes.push(format!(
            "face {} not written: its surface {} was not converted",
            face.source, face.surface_source
        ));
    }
    si
}

/// The pcurves of the uses `oes` of a loop of face `fi` of the seamed B-rep, each running the
/// way the loop uses its edge: the ones the seams' rebuilding made, else [`Pcurves`]' (made
/// on `seamed.brep`); a seam edge the face uses twice takes, per use, the side of the seam
/// whose ends meet its neighbours' pcurves (nearest in the parameter plane; ends on one pole
/// meet).
pub(super) fn loop_pcurves(
    pcs: &mut Pcurves,
    seamed: &Seamed,
    fi: usize,
    oes: &[OrientedEdge],
) -> Vec<Option<NurbsCurve<f64, 2>>> {
    let orient =
        |o: &OrientedEdge, pc: NurbsCurve<f64, 2>| if o.forward { pc } else { pc.reversed() };
    let mut out: Vec<Option<NurbsCurve<f64, 2>>> = oes
        .iter()
        .map(|o| match seamed.pcurves.get(&(fi, o.edge, o.forward)) {
            Some(pc) => Some(pc.clone()),
            None => pcs.get(o.edge, fi).map(|pc| orient(o, pc)),
        })
        .collect();
    let n = oes.len();
    let end = |c: &NurbsCurve<f64, 2>, last: bool| {
        let (a, z) = c.hom.domain();
        c.eval(if last { &z } else { &a })
    };
    for i in 0..n {
        if out[i].is_some() {
            continue;
        }
        let Some(sides) = pcs.seam_sides(oes[i].edge, fi) else {
            continue;
        };
        let before = out[(i + n - 1) % n].as_ref().map(|c| end(c, true));
        let after = out[(i + 1) % n].as_ref().map(|c| end(c, false));
        if before.is_none() && after.is_none() {
            continue;
        }
        // A gap along a pole is no gap (the loop may cross the pole there).
        let mut miss = |c: &NurbsCurve<f64, 2>| {
            let mut gap = |p: [f64; 2], q: [f64; 2]| {
                if pcs.on_one_pole(fi, p, q) {
                    0.0
                } else {
                    dist(&p, &q)
                }
            };
            before.map_or(0.0, |p| gap(p, end(c, false)))
                + after.map_or(0.0, |q| gap(end(c, true), q))
        };
        let [a, b] = sides.map(|c| orient(&oes[i], c));
        out[i] = Some(if miss(&a) <= miss(&b) { a } else { b });
    }
    out
}

/// Shells (514) and solids (186); faces in no shell go into one more open shell.
fn shells_and_solids(b: &Brep, p: &mut Params, face_de: &[Option<usize>], notes: &mut Vec<String>) {
    let in_solid: BTreeSet<usize> = b
        .solids
        .iter()
        .flat_map(|s| std::iter::once(s.outer).chain(s.voids.iter().copied()))
        .collect();
    let mut in_shell = BTreeSet::new();
    let mut shell_de = Vec::with_capacity(b.shells.len());
    for (k, s) in b.shells.iter().enumerate() {
        let mut t = String::new();
        let mut n = 0;
        for (f, orientation) in &s.faces {
            let Some(d) = face_de.get(*f).copied().flatten() else {
                notes.push(format!(
                    "shell {} written without face {} (not written)",
                    s.source,
                    b.faces.get(*f).map_or("?", |x| x.source.as_str())
                ));
                continue;
            };
            in_shell.insert(*f);
            // Orientation relative to the surface normal: the face's and the shell's use.
            let agrees = b.faces[*f].same_sense == *orientation;
            t += &format!(",{d},{}", u8::from(agrees));
            n += 1;
        }
        let form = if s.closed { 1 } else { 2 };
        let status = if in_solid.contains(&k) {
            USED
        } else {
            "00000000"
        };
        shell_de.push(push_form(p, 514, form, format!("514,{n}{t};"), status));
    }
    let loose: Vec<(usize, bool)> = face_de
        .iter()
        .enumerate()
        .filter(|(f, _)| !in_shell.contains(f))
        .filter_map(|(f, d)| Some(((*d)?, b.faces[f].same_sense)))
        .collect();
    if !loose.is_empty() {
        notes.push(format!(
            "{} face(s) in no shell written in an added open shell",
            loose.len()
        ));
        let t: String = loose
            .iter()
            .map(|(d, same)| format!(",{d},{}", u8::from(*same)))
            .collect();
        shell_de.push(push_form(
            p,
            514,
            2,
            format!("514,{}{t};", loose.len()),
            "00000000",
        ));
    }
    for s in &b.solids {
        let Some(outer) = shell_de.get(s.outer) else {
            notes.push(format!("solid {} not written: no outer shell", s.source));
            continue;
        };
        let voids: String = s
            .voids
            .iter()
            .filter_map(|v| shell_de.get(*v))
            .map(|d| format!(",{d},0"))
            .collect();
        push(
            p,
            186,
            format!("186,{outer},1,{}{voids};", s.voids.len()),
            "00000000",
        );
    }
}
