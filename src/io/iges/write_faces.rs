//! IGES writer for a model with a B-rep as trimmed surfaces, the form most IGES readers take:
//! each face a trimmed surface (144) over its B-spline surface (128), each edge loop a curve
//! on the surface (142) whose model-space curve is the loop's edge curves in order (126,
//! joined by a composite curve 102) and whose parameter-space curve is the loop's pcurves in
//! order (126 in `(u, v, 0)`, a 102 likewise) where every use of the loop has one.
//!
//! What is written is the B-rep with its seams made explicit
//! ([`crate::brep::seam_edges::explicit_seams`]), so that a face bounded by loops running
//! round its closed surface is one region of its parameter rectangle; the degenerate edge at a
//! pole is in the parameter-space curve only (in model space it is a point). Entity 144 holds
//! no topology: what is not kept is returned as notes (shared edges and vertices, shells and
//! solids, reversed faces, vertex loops, faces or loops that cannot be written). The B-rep
//! entities (186 and below, [`super::write_brep`]) keep it.

use super::write::{DEPENDENT, Params, curve_126, surface_128};
use super::write_brep::{USED, face_surface, loop_pcurves, ordered, push};
use crate::brep::pcurve::Pcurves;
use crate::brep::seam_edges::explicit_seams;
use crate::brep::{Brep, LoopKind};
use crate::model::{CurveGeometry, Model};
use crate::spline::NurbsCurve;
use std::collections::BTreeSet;

/// One curve or a composite (102) of several: the DE of the result.
fn chain(p: &mut Params, curves: &[NurbsCurve<f64, 3>], status: &'static str) -> usize {
    let des: Vec<usize> = curves
        .iter()
        .map(|c| push(p, 126, curve_126(c), status))
        .collect();
    if des.len() == 1 {
        return des[0];
    }
    let list: Vec<String> = des.iter().map(|x| x.to_string()).collect();
    push(
        p,
        102,
        format!("102,{},{};", des.len(), list.join(",")),
        status,
    )
}

/// One loop: its model-space curves and, when every use has one, its parameter-space curves
/// (in `(u, v, 0)`).
type LoopCurves = (Vec<NurbsCurve<f64, 3>>, Option<Vec<NurbsCurve<f64, 3>>>);

/// Write every face of `b` as a 144; returns the model surfaces written as faces.
pub(super) fn faces(
    m: &Model,
    b: &Brep,
    p: &mut Params,
    notes: &mut Vec<String>,
) -> BTreeSet<usize> {
    let mut written = BTreeSet::new();
    let seamed = explicit_seams(m, b, notes);
    let b = &seamed.brep;
    let mut pcs = Pcurves::new(b, m);
    let (mut reversed, mut vertex_loops, mut count) = (Vec::new(), 0, 0);
    let mut model_space_only = 0;
    for (fi, face) in b.faces.iter().enumerate() {
        let Some(si) = face_surface(m, face, notes) else {
            continue;
        };
        let mut loops: Vec<(bool, LoopCurves)> = Vec::new();
        for l in &face.loops {
            let oes = match &l.kind {
                LoopKind::Vertex(_) => {
                    vertex_loops += 1;
                    continue;
                }
                // IGES faces have no sense: the loops run counter-clockwise about the
                // surface's normal around the face (reversed for a face with same_sense .F.).
                LoopKind::Edges(oes) => ordered(oes, l.orientation == face.same_sense),
            };
            // Model space: the edge curves the loop runs along (a pole is a point there).
            let curves: Option<Vec<_>> = oes
                .iter()
                .filter(|o| !seamed.poles.contains(&o.edge))
                .map(|o| {
                    let c = &b.edges.get(o.edge)?.curve.as_ref()?.nurbs;
                    Some(if o.forward { c.clone() } else { c.reversed() })
                })
                .collect();
            let pcurves: Option<Vec<_>> = loop_pcurves(&mut pcs, &seamed, fi, &oes)
                .into_iter()
                .collect::<Option<Vec<_>>>()
                .map(|pc| {
                    let pc = pcs.pole_joins(fi, pc);
                    pc.into_iter()
                        .map(|d| CurveGeometry::Domain(d).to_space())
                        .collect()
                });
            match curves {
                Some(c) if !c.is_empty() => loops.push((l.outer, (c, pcurves))),
                _ => notes.push(format!(
                    "loop {} of face {} not written: an edge has no 3D curve",
                    l.source, face.source
                )),
            }
        }
        if loops.is_empty() && !face.loops.is_empty() {
            notes.push(format!(
                "face {} not written: none of its loops could be written",
                face.source
            ));
            continue;
        }
        // The outer boundary: the first loop declared outer, else the first loop.
        if let Some(k) = loops.iter().position(|l| l.0) {
            loops.swap(0, k);
        }
        let sde = push(p, 128, surface_128(&m.surfaces[si].nurbs), USED);
        written.insert(si);
        let mut bounds = Vec::new();
        for (_, (curves, pcurves)) in &loops {
            let cde = chain(p, curves, USED);
            let (bde, pref) = match pcurves {
                Some(pc) => (chain(p, pc, DEPENDENT), 3),
                None => {
                    model_space_only += 1;
                    (0, 2)
                }
            };
            bounds.push(push(
                p,
                142,
                format!("142,0,{sde},{bde},{cde},{pref};"),
                DEPENDENT,
            ));
        }
        if !face.same_sense {
            reversed.push(face.source.clone());
        }
        let (outer, holes) = match bounds.split_first() {
            Some((o, h)) => (*o, h),
            None => (0, &[][..]),
        };
        let hs: String = holes.iter().map(|h| format!(",{h}")).collect();
        push(
            p,
            144,
            format!(
                "144,{sde},{},{},{outer}{hs};",
                usize::from(outer != 0),
                holes.len()
            ),
            "00000000",
        );
        count += 1;
    }
    notes.push(format!(
        "the B-rep is written as {count} trimmed surfaces (144): its {} shell(s), {} solid(s), shared edges and vertices are not kept (each face holds its own boundary curves; the default IGES form writes the B-rep entities 186/514/510/508/504/502)",
        b.shells.len(),
        b.solids.len()
    ));
    if !reversed.is_empty() {
        notes.push(format!(
            "{} face(s) with same_sense .F. (normal opposite to S_u x S_v): entity 144 keeps the surface's orientation: {}",
            reversed.len(),
            crate::model::list_ids(reversed)
        ));
    }
    notes.extend(pcs.note());
    if model_space_only > 0 {
        notes.push(format!(
            "{model_space_only} loop(s) written with their model-space curves only (a use without a pcurve: see the note on projected pcurves): readers project them"
        ));
    }
    if vertex_loops > 0 {
        notes.push(format!(
            "{vertex_loops} vertex loop(s) (degenerate boundaries at a point) not written"
        ));
    }
    written
}
