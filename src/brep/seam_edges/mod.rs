//! Seam edges made explicit, for writers whose readers need them. A face on a surface closed
//! in one direction (a cylinder, cone, sphere or torus in its revolved NURBS form) may be
//! bounded by loops that each run once around that direction — a band between two circles,
//! a cap between a circle and a pole — with no edge along the seam (STEP allows this:
//! abc-0000.step's faces are written so). Such loops bound no region of the parameter
//! rectangle on their own; a reader must add the seam. Open CASCADE's STEP reader does; its
//! IGES reader does not, and builds faces of no area from them.
//!
//! [`explicit_seams`] rebuilds such a face with one loop that bounds a region of its
//! parameter rectangle (closed in `u` here; likewise closed in `v`), `u_lo` and `u_hi` being
//! the two sides of the seam:
//!
//! * **band** (two loops, each one closed edge running round in opposite `u` directions, the
//!   `v` ranges of their samples apart): the first loop from its seam crossing `(u_lo, c₁)`
//!   round to it, the seam edge (the parameter line `u = u_lo` from `c₁` to `c₂`) on the side
//!   the loop ends at, the second loop from `c₂`, and the seam edge back on the other side;
//! * **cap** (one such loop and a vertex loop on one side of it, where the surface's border
//!   `v = c_p` is degenerate: the pole): the loop, the seam edge to the pole, a degenerate
//!   edge at the pole (a curve of zero length, its pcurve the border line), and the seam
//!   edge back. The vertex loop (a point of the face) only says which side; it is dropped.
//!
//! The face must lie where its loops' directions put it (left of each loop seen along the
//! face's normal): between the band's loops, on the cap's side of its loop. A face whose
//! loops say otherwise (outside the band: across the other direction's seam on a torus, or
//! two caps on a sphere) is not rebuilt. The loop keeps the direction the first loop had,
//! so the face stays on the same side of it. A closed edge is cut where it crosses the seam (two faces needing different seam
//! points on one circle cut it in two arcs), its old vertex dropped where no cut is at it;
//! every face using it then uses its arcs in order. Each edge use of a rebuilt loop carries
//! its pcurve: the seam and pole edges' are straight segments of the border lines; an arc's
//! is made by [`crate::brep::pcurve::project`] — a straight segment along a parameter line or
//! cubic pieces between the surface's knot lines through projected samples — and its image
//! lies within the model tolerance (at least 1e-8 of its size) of the arc: proven where the
//! surface's cells can be enclosed, otherwise checked halfway between samples.
//!
//! How a loop is recognised (evidence, sampled; not a proof): the closed edge's curve is
//! sampled at 33 parameters and each sample projected onto the surface; every sample must lie within the accepted distance of it, and the closed parameter,
//! unwrapped across the seam, must move the same way at every step and run once round (its
//! total within 1e-6 of the period). Faces with a loop that runs round otherwise, or with
//! more or fewer loops of these kinds, are left as they are and named in the notes.

mod build;
mod cut;
mod round;

use super::{Brep, Face, Loop, LoopKind};
use crate::brep::pcurve::project::{Fit, Projector};
use crate::geom::dist;
use crate::model::Model;
use crate::spline::closure::Closure;
use crate::spline::project::project;
use crate::spline::{NurbsCurve, NurbsSurface};
use build::Builder;
use cut::{cut_closed, uses};
use round::{Round, bounds, runs_round};
use std::collections::{BTreeMap, BTreeSet};

/// A B-rep with explicit seams and the pcurves of the edge uses it made.
#[derive(Debug)]
pub struct Seamed {
    pub brep: Brep,
    /// `(face, edge, forward)` → the pcurve of that use, in the face's surface parameters,
    /// running the way the loop uses the edge.
    pub pcurves: BTreeMap<(usize, usize, bool), NurbsCurve<f64, 2>>,
    /// Faces rebuilt with a seam loop.
    pub faces: usize,
    /// The degenerate edges made at poles (a curve of zero length each; IGES writes such a
    /// use as its vertex).
    pub poles: BTreeSet<usize>,
}

/// A face to rebuild: its closed direction `k`, its round loops (edge, used forward, how it
/// runs round) and its pole (the vertex loop's vertex, the other parameter at that border).
struct Plan {
    k: usize,
    rounds: Vec<(usize, bool, Round)>,
    pole: Option<(usize, f64)>,
}

/// The plan for `face` on `s`, `Ok(None)` when no loop runs round, `Err` (why) when some do
/// but the face is of neither kind.
fn plan(b: &Brep, face: &Face, s: &NurbsSurface<f64, 3>, off: f64) -> Result<Option<Plan>, String> {
    let closure = Closure::of(s);
    if !(closure.seam_u || closure.seam_v) {
        return Ok(None);
    }
    let mut rounds = Vec::new();
    let mut poles = Vec::new();
    let mut others = 0;
    for l in &face.loops {
        match &l.kind {
            LoopKind::Edges(oes) if oes.len() == 1 => {
                let Some(e) = b.edges.get(oes[0].edge) else {
                    others += 1;
                    continue;
                };
                let closed = e.start == e.end && e.start < b.vertices.len();
                let round = match e.curve.as_ref().filter(|_| closed) {
                    Some(c) => runs_round(s, &closure, &c.nurbs, off)?,
                    None => None,
                };
                match round {
                    Some(r) => rounds.push((oes[0].edge, oes[0].forward == l.orientation, r)),
                    None => others += 1,
                }
            }
            LoopKind::Vertex(v) => poles.push(*v),
            LoopKind::Edges(_) => others += 1,
        }
    }
    if rounds.is_empty() {
        return Ok(None);
    }
    let refuse = |why: &str| {
        Err(format!(
            "{} loop(s) run round its closed surface with no seam edge, beside {others} other and {} vertex loop(s): {why}",
            rounds.len(),
            poles.len()
        ))
    };
    let k = rounds[0].2.k;
    if rounds.iter().any(|r| r.2.k != k) {
        return refuse("they run round different directions");
    }
    let r = 1 - k;
    let (lo, hi) = bounds(s);
    // The direction a round loop runs in: the closed parameter increasing or not.
    let up = |x: &(usize, bool, Round)| x.1 == x.2.up;
    // The face lies left of its loops seen along its normal, so in the parameter plane
    // (normal S_u × S_v) a loop on the low side of the face (in the other parameter) runs
    // counter-clockwise round it: towards +u when closed in u, towards −v when closed in v;
    // the other way when the face's normal is reversed.
    let low_side_up = (k == 0) == face.same_sense;
    match (rounds.len(), poles.as_slice()) {
        (2, []) => {
            let (a, z) = (rounds[0].2.other_range(), rounds[1].2.other_range());
            if up(&rounds[0]) == up(&rounds[1]) {
                refuse("both run the same way")
            } else if !(a.1 < z.0 || z.1 < a.0) {
                refuse("their ranges across the closed direction overlap")
            } else if up(&rounds[if a.1 < z.0 { 0 } else { 1 }]) != low_side_up {
                // The face is the other band, across the seam of the other direction.
                refuse("the face lies outside the band between them")
            } else {
                Ok(Some(Plan {
                    k,
                    rounds,
                    pole: None,
                }))
            }
        }
        (1, [v]) => {
            let Some(x) = b.vertices.get(*v) else {
                return refuse("the vertex loop has no vertex");
            };
            let p = project(s, &x.point);
            let along = rounds[0].2.other_at(p[k], hi[k] - lo[k]);
            // The side of the loop the vertex is on (a pole vertex counts as its side).
            let side_of = |c: f64| dist(&build::point(s, k, lo[k], c), &x.point) <= off;
            let margin = 1e-6 * (hi[r] - lo[r]);
            let high = if side_of(hi[r]) || p[r] > along + margin {
                true
            } else if side_of(lo[r]) || p[r] < along - margin {
                false
            } else {
                return refuse("the vertex loop lies on the loop");
            };
            // Borders of the closed direction's other parameter: [low, high] per direction.
            let border = if k == 0 { [2, 3] } else { [0, 1] }[high as usize];
            if !closure.degenerate[border] {
                return refuse("the side of the vertex loop reaches a border that is not a pole");
            }
            // The loop is the low side of a cap towards the high border.
            if up(&rounds[0]) != (low_side_up == high) {
                return refuse("the face lies on the side of its loop away from the vertex loop");
            }
            let cp = if high { hi[r] } else { lo[r] };
            Ok(Some(Plan {
                k,
                rounds,
                pole: Some((*v, cp)),
            }))
        }
        _ => refuse("neither a band of two nor a cap with one vertex loop"),
    }
}

/// The accepted distance between points of `b` meant to coincide.
fn accepted(b: &Brep) -> f64 {
    (100.0 * b.tolerance).max(1e-6 * b.extent())
}

/// The NURBS surface of `f` in `m`.
fn surface<'a>(m: &'a Model, f: &Face) -> Option<&'a NurbsSurface<f64, 3>> {
    f.surface.and_then(|s| m.surfaces.get(s)).map(|s| &s.nurbs)
}

/// The plan of every face of `b` to rebuild; notes name the faces with a loop that runs
/// round that are of neither kind.
fn plans(m: &Model, b: &Brep, notes: &mut Vec<String>) -> BTreeMap<usize, Plan> {
    let off = accepted(b);
    let mut plans = BTreeMap::new();
    for (fi, face) in b.faces.iter().enumerate() {
        let Some(s) = surface(m, face) else { continue };
        match plan(b, face, s, off) {
            Ok(Some(p)) => {
                plans.insert(fi, p);
            }
            Ok(None) => {}
            Err(why) => notes.push(format!("face {}: {why}; written as read", face.source)),
        }
    }
    plans
}

/// The caps of `b` (module comment) whose vertex loop lies away from the pole it stands
/// for: `(face, loop, the pole's point)`. The vertex loop only says which side of the circle
/// the face is on, and the pole lies on that side; readers that take a cap's vertex loop
/// for its pole (Open CASCADE's STEP reader does, on B-spline surfaces, and then builds the
/// complement of the cap) read the same face when the vertex loop is written at the pole.
pub fn caps_off_their_poles(m: &Model, b: &Brep) -> Vec<(usize, usize, [f64; 3])> {
    let off = accepted(b);
    let mut out = Vec::new();
    for (fi, p) in plans(m, b, &mut Vec::new()) {
        let (Some((v, cp)), Some(s)) = (p.pole, surface(m, &b.faces[fi])) else {
            continue;
        };
        let pole = build::point(s, p.k, bounds(s).0[p.k], cp);
        let Some(x) = b.vertices.get(v) else { continue };
        if dist(&x.point, &pole) <= off {
            continue;
        }
        let loops = &b.faces[fi].loops;
        if let Some(li) = loops
            .iter()
            .position(|l| matches!(l.kind, LoopKind::Vertex(w) if w == v))
        {
            out.push((fi, li, pole));
        }
    }
    out
}

/// The faces of `b` (on `m`'s surfaces) rebuilt with explicit seams (module comment); notes
/// name the faces with a loop that runs round their surface that were left as they are.
pub fn explicit_seams(m: &Model, b: &Brep, notes: &mut Vec<String>) -> Seamed {
    let mut out = b.clone();
    let off = accepted(b);
    let mut cuts: BTreeMap<usize, Vec<f64>> = BTreeMap::new();
    let plans = plans(m, b, notes);
    for p in plans.values() {
        for (edge, _, r) in &p.rounds {
            cuts.entry(*edge).or_default().push(r.t);
        }
    }
    let arcs: BTreeMap<usize, Vec<usize>> = cuts
        .iter()
        .map(|(e, ts)| (*e, cut_closed(&mut out, *e, ts, off)))
        .collect();
    // Every loop uses the arcs of a cut edge in its place.
    for f in &mut out.faces {
        for l in &mut f.loops {
            if let LoopKind::Edges(oes) = &mut l.kind {
                *oes = oes.iter().flat_map(|o| uses(&arcs, *o)).collect();
            }
        }
    }
    let mut pcurves = BTreeMap::new();
    let mut poles = BTreeSet::new();
    let mut faces = 0;
    for (fi, p) in plans {
        let face = &b.faces[fi];
        let round = |l: &Loop| matches!(&l.kind, LoopKind::Edges(o) if o.len() == 1 && p.rounds.iter().any(|r| r.0 == o[0].edge));
        let (Some(s), Some(first)) = (surface(m, face), face.loops.iter().find(|l| round(l)))
        else {
            continue;
        };
        let (lo, hi) = bounds(s);
        let (edges, vertices) = (out.edges.len(), out.vertices.len());
        let proj = Projector::new(s);
        let mut builder = Builder {
            b: &mut out,
            s,
            proj: &proj,
            fi,
            k: p.k,
            lo: lo[p.k],
            hi: hi[p.k],
            off,
            fit: Fit {
                aim: 1e-8 * b.extent(),
                off: b.tolerance.max(1e-8 * b.extent()),
            },
            pcurves: &mut pcurves,
            poles: &mut poles,
        };
        let Some(l) = builder.build(&p, &arcs) else {
            out.edges.truncate(edges);
            out.vertices.truncate(vertices);
            poles.retain(|e| *e < edges);
            pcurves.retain(|key, _| key.0 != fi);
            notes.push(format!(
                "face {}: its loops run round its closed surface, but no seam loop could be built; written as read",
                face.source
            ));
            continue;
        };
        let mut loops = vec![Loop {
            outer: true,
            orientation: true,
            kind: LoopKind::Edges(l),
            ..first.clone()
        }];
        for l in &face.loops {
            if round(l) || matches!(l.kind, LoopKind::Vertex(_)) {
                continue;
            }
            let mut l = l.clone();
            l.outer = false;
            if let LoopKind::Edges(oes) = &mut l.kind {
                *oes = oes.iter().flat_map(|o| uses(&arcs, *o)).collect();
            }
            loops.push(l);
        }
        out.faces[fi].loops = loops;
        faces += 1;
    }
    Seamed {
        brep: out,
        pcurves,
        faces,
        poles,
    }
}
