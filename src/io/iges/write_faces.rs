//! IGES writer for a model with a B-rep: each face a trimmed surface (144) over its B-spline
//! surface (128), each edge loop a curve on the surface (142) whose model-space curve is the
//! loop's edge curves in order (126, joined by a composite curve 102), and — on planar faces,
//! where they are exact — the parameter-space curve too (the edge curves' control points mapped
//! by the inverse of the plane's affine parametrization).
//!
//! Entity 144 holds no topology: what is not kept is returned as notes (shared edges and
//! vertices, shells and solids, reversed faces, vertex loops, faces or loops that cannot be
//! written).

use super::write::{DEPENDENT, curve_126, surface_128};
use crate::brep::{Brep, LoopKind, OrientedEdge};
use crate::io::step::write_pcurve::AffinePatch;
use crate::model::{CurveGeometry, Model};
use crate::spline::NurbsCurve;
use std::collections::BTreeSet;

/// Entity type, parameter text and directory status of each entity, in DE order.
pub(super) type Params = Vec<(i64, String, &'static str)>;

/// Status of a model-space curve used by another entity (physically dependent).
const USED: &str = "00010000";

fn de_next(p: &Params) -> usize {
    2 * p.len() + 1
}

/// One curve or a composite (102) of several: the DE of the result.
fn chain(p: &mut Params, curves: &[NurbsCurve<f64, 3>], status: &'static str) -> usize {
    let des: Vec<usize> = curves
        .iter()
        .map(|c| {
            let d = de_next(p);
            p.push((126, curve_126(c), status));
            d
        })
        .collect();
    if des.len() == 1 {
        return des[0];
    }
    let d = de_next(p);
    let list: Vec<String> = des.iter().map(|x| x.to_string()).collect();
    p.push((
        102,
        format!("102,{},{};", des.len(), list.join(",")),
        status,
    ));
    d
}

/// The loop's edges in the order the loop runs (a bound with orientation .F. reversed).
fn ordered(oes: &[OrientedEdge], orientation: bool) -> Vec<OrientedEdge> {
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

/// Write every face of `b` as a 144; returns the model surfaces written as faces.
pub(super) fn faces(
    m: &Model,
    b: &Brep,
    p: &mut Params,
    notes: &mut Vec<String>,
) -> BTreeSet<usize> {
    let mut written = BTreeSet::new();
    let (mut reversed, mut vertex_loops, mut count) = (Vec::new(), 0, 0);
    for face in &b.faces {
        let Some(si) = face.surface.filter(|s| *s < m.surfaces.len()) else {
            notes.push(format!(
                "face {} not written: its surface {} was not converted",
                face.source, face.surface_source
            ));
            continue;
        };
        let patch = AffinePatch::new(&m.surfaces[si].nurbs);
        // Each loop's edge curves in the loop's direction; loops over an edge without a
        // curve are left out.
        let mut loops: Vec<(bool, Vec<NurbsCurve<f64, 3>>)> = Vec::new();
        for l in &face.loops {
            let oes = match &l.kind {
                LoopKind::Vertex(_) => {
                    vertex_loops += 1;
                    continue;
                }
                LoopKind::Edges(oes) => ordered(oes, l.orientation),
            };
            let curves: Option<Vec<_>> = oes
                .iter()
                .map(|o| {
                    let c = &b.edges.get(o.edge)?.curve.as_ref()?.nurbs;
                    Some(if o.forward { c.clone() } else { c.reversed() })
                })
                .collect();
            match curves {
                Some(c) if !c.is_empty() => loops.push((l.outer, c)),
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
        let sde = de_next(p);
        p.push((128, surface_128(&m.surfaces[si].nurbs), "00010000"));
        written.insert(si);
        let mut bounds = Vec::new();
        for (_, curves) in &loops {
            let cde = chain(p, curves, USED);
            let pcurves: Option<Vec<NurbsCurve<f64, 3>>> = patch.as_ref().and_then(|a| {
                curves
                    .iter()
                    .map(|c| a.pcurve(c).map(|d| CurveGeometry::Domain(d).to_space()))
                    .collect()
            });
            let (bde, pref) = match pcurves {
                Some(pc) => (chain(p, &pc, DEPENDENT), 3),
                None => (0, 2),
            };
            bounds.push(de_next(p));
            p.push((142, format!("142,0,{sde},{bde},{cde},{pref};"), DEPENDENT));
        }
        if !face.same_sense {
            reversed.push(face.source.clone());
        }
        let (outer, holes) = match bounds.split_first() {
            Some((o, h)) => (*o, h),
            None => (0, &[][..]),
        };
        let hs: String = holes.iter().map(|h| format!(",{h}")).collect();
        p.push((
            144,
            format!(
                "144,{sde},{},{},{outer}{hs};",
                usize::from(outer != 0),
                holes.len()
            ),
            "00000000",
        ));
        count += 1;
    }
    notes.push(format!(
        "the B-rep is written as {} trimmed surfaces (144): its {} shell(s), {} solid(s), shared edges and vertices are not kept (each face holds its own boundary curves)",
        count,
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
    if vertex_loops > 0 {
        notes.push(format!(
            "{vertex_loops} vertex loop(s) (degenerate boundaries at a point) not written"
        ));
    }
    written
}
