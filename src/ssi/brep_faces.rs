//! Intersection of B-rep faces rather than of their whole surfaces: every output of a pair
//! (branch points, touch points, uncertified coverage regions) is kept only inside both faces'
//! loops, and in a run over one B-rep the intersection along an edge (or at a vertex) the two
//! faces share is listed as that shared edge, not as a branch — so a valid solid's
//! self-intersection check gives no branches.
//!
//! Decisions and what they rest on:
//! * *inside a face*: the face's parameter-plane polygon ([`crate::tessellate::region`]): exact
//!   for the polygon, evidence against the true loop curves (the polygon's chords).
//! * *on a shared edge*: the point lies within `δ = max(100·tol, 1e-6·size)` of the edge's 3D
//!   curve (or of a shared vertex), the distance found by a local search on the curve from its
//!   nearest of 512 samples (evidence). Such points are not claimed to be on the intersection
//!   or off it; they are where the two faces meet by construction of the B-rep.
//! * an uncertified coverage region is dropped only when its parameter box, widened by 1 % of
//!   the domain, lies wholly outside one face's polygon; the coverage claim that remains is
//!   about the faces as their polygons outline them.

use super::coverage::OutsideFaces;
use super::report::{PairOut, TouchOut};
use super::trims::{TrimRegion, clip_mask};
use crate::brep::{Brep, LoopKind};
use crate::geom::{cross, dist, norm};
use crate::model::Model;
use crate::spline::project::{point_d1, project};
use crate::spline::{NurbsCurve, NurbsSurface};
use serde::Serialize;
use std::collections::BTreeSet;
use std::sync::Arc;

/// Samples per shared edge curve for the first guess of a point's distance.
const EDGE_SAMPLES: usize = 512;
/// Margin (fraction of the domain) by which coverage boxes are widened before the outside test.
const REGION_MARGIN: f64 = 0.01;

/// The intersection of two faces along an edge they share.
#[derive(Clone, Debug, Serialize)]
pub struct SharedEdgeOut {
    /// Source id of the edge (or of the vertex, for a shared vertex).
    pub edge: String,
    /// Branch points of the surfaces' intersection lying within `within` of it.
    pub points: usize,
    /// Largest distance of those points from the edge curve (local search: evidence).
    pub max_distance: f64,
    pub within: f64,
}

/// What restricting a pair to its faces removed.
#[derive(Clone, Debug, Default, Serialize)]
pub struct FaceClipOut {
    /// Intersection along shared edges and at shared vertices (one-file runs on a B-rep).
    pub shared_edges: Vec<SharedEdgeOut>,
    /// Branch points outside either face's loops.
    pub points_outside: usize,
    /// Touch points outside either face, or on a shared edge or vertex.
    pub touch_points_outside: usize,
    pub touch_points_on_shared_edges: usize,
    /// Uncertified coverage regions wholly outside either face.
    pub regions_outside: usize,
}

/// A curve of a shared edge with its samples, for distances.
struct EdgeProbe<'a> {
    source: &'a str,
    curve: &'a NurbsCurve<f64, 3>,
    t: Vec<f64>,
    p: Vec<[f64; 3]>,
    /// Points within this distance of the curve are attributed to the edge.
    within: f64,
}

impl EdgeProbe<'_> {
    /// `base`: the least attribution distance; `cap`: the largest.
    fn new<'a>(
        source: &'a str,
        curve: &'a NurbsCurve<f64, 3>,
        sa: &NurbsSurface<f64, 3>,
        sb: &NurbsSurface<f64, 3>,
        base: f64,
        cap: f64,
    ) -> EdgeProbe<'a> {
        let (t0, t1) = curve.hom.domain();
        let t: Vec<f64> = (0..=EDGE_SAMPLES)
            .map(|i| t0 + (t1 - t0) * i as f64 / EDGE_SAMPLES as f64)
            .collect();
        let p: Vec<[f64; 3]> = t.iter().map(|x| curve.eval(x)).collect();
        let within = edge_reach(&p, sa, sb).clamp(base, cap.max(base));
        EdgeProbe {
            source,
            curve,
            t,
            p,
            within,
        }
    }

    /// Distance from `x` to the curve: nearest sample, then a golden-section search on the
    /// two sample intervals around it.
    fn distance(&self, x: &[f64; 3]) -> f64 {
        let (k, d0) = self
            .p
            .iter()
            .enumerate()
            .map(|(k, p)| (k, dist(p, x)))
            .fold((0, f64::INFINITY), |a, b| if b.1 < a.1 { b } else { a });
        let (mut lo, mut hi) = (
            self.t[k.saturating_sub(1)],
            self.t[(k + 1).min(EDGE_SAMPLES)],
        );
        let f = |t: f64| dist(&self.curve.eval(&t), x);
        let g = 0.5 * (5f64.sqrt() - 1.0);
        let (mut a, mut b) = (hi - g * (hi - lo), lo + g * (hi - lo));
        let (mut fa, mut fb) = (f(a), f(b));
        for _ in 0..60 {
            if fa < fb {
                hi = b;
                b = a;
                fb = fa;
                a = hi - g * (hi - lo);
                fa = f(a);
            } else {
                lo = a;
                a = b;
                fa = fb;
                b = lo + g * (hi - lo);
                fb = f(b);
            }
        }
        d0.min(fa).min(fb)
    }
}

/// How far from the edge curve the two surfaces' intersection may run: where the curve lies
/// `g_a`, `g_b` from the surfaces (closest points by local search) and the surfaces meet at
/// angle θ, their intersection lies within about `2 (g_a + g_b) / sin θ` of it (first order);
/// the largest over 129 samples along the edge. Evidence, as the search it rests on.
fn edge_reach(p: &[[f64; 3]], sa: &NurbsSurface<f64, 3>, sb: &NurbsSurface<f64, 3>) -> f64 {
    let step = (p.len() / 128).max(1);
    let mut reach: f64 = 0.0;
    for x in p.iter().step_by(step) {
        let foot = |s: &NurbsSurface<f64, 3>| {
            let uv = project(s, x);
            let (q, su, sv) = point_d1(s, uv[0], uv[1]);
            (dist(&q, x), cross(&su, &sv))
        };
        let ((ga, na), (gb, nb)) = (foot(sa), foot(sb));
        let (la, lb) = (norm(&na), norm(&nb));
        let sin = if la > 0.0 && lb > 0.0 {
            norm(&cross(&na, &nb)) / (la * lb)
        } else {
            0.0
        };
        let r = 2.0 * (ga + gb) / sin;
        reach = reach.max(if r.is_finite() { r } else { f64::INFINITY });
    }
    reach
}

/// Edges and vertices of the faces on one surface.
type SurfaceTopology = (BTreeSet<usize>, BTreeSet<usize>);

/// Edges and vertices of the faces on each surface of a B-rep.
fn surface_topology(brep: &Brep, surfaces: usize) -> Vec<SurfaceTopology> {
    let mut out = vec![(BTreeSet::new(), BTreeSet::new()); surfaces];
    for f in &brep.faces {
        let Some(s) = f.surface.filter(|&s| s < surfaces) else {
            continue;
        };
        for l in &f.loops {
            match &l.kind {
                LoopKind::Edges(es) => {
                    for o in es {
                        out[s].0.insert(o.edge);
                        let e = &brep.edges[o.edge];
                        out[s].1.insert(e.start);
                        out[s].1.insert(e.end);
                    }
                }
                LoopKind::Vertex(v) => {
                    out[s].1.insert(*v);
                }
            }
        }
    }
    out
}

/// The faces of the models and, for a one-file run on a B-rep, what they share.
pub struct Faces<'a> {
    a: Arc<Vec<Option<TrimRegion>>>,
    b: Arc<Vec<Option<TrimRegion>>>,
    one_file: Option<(&'a Model, &'a Brep, Vec<SurfaceTopology>)>,
    /// The least attribution distance, `max(100 tol, 1e-6 size)`, and the largest, 1 % of
    /// the model size.
    delta: f64,
    cap: f64,
    /// Faces whose region could not be outlined (their surfaces are not clipped).
    pub failed: Vec<String>,
    /// Faces (trim loops or B-rep faces) that clip.
    pub trimmed: usize,
}

fn regions(m: &Model) -> (Vec<Option<TrimRegion>>, Vec<String>) {
    if m.brep.is_some() {
        TrimRegion::of_brep(m)
    } else {
        (m.surfaces.iter().map(TrimRegion::of).collect(), vec![])
    }
}

fn model_size(m: &Model) -> f64 {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for s in &m.surfaces {
        for p in s.nurbs.points_weights().0 {
            for k in 0..3 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
    }
    let d = (0..3).map(|k| (hi[k] - lo[k]).powi(2)).sum::<f64>().sqrt();
    if d.is_finite() { d } else { 0.0 }
}

impl<'a> Faces<'a> {
    pub fn new(a: &'a Model, b: Option<&'a Model>, tol: f64) -> Faces<'a> {
        let (ra, mut failed) = regions(a);
        let rb = match b {
            Some(m) => {
                let (r, f) = regions(m);
                failed.extend(f);
                r
            }
            None => Vec::new(),
        };
        let one_file = match (b, &a.brep) {
            (None, Some(brep)) => Some((a, brep, surface_topology(brep, a.surfaces.len()))),
            _ => None,
        };
        let trimmed = ra.iter().chain(&rb).filter(|r| r.is_some()).count();
        let size = model_size(a);
        Faces {
            a: Arc::new(ra),
            b: Arc::new(rb),
            one_file,
            delta: (100.0 * tol).max(1e-6 * size),
            cap: 1e-2 * size,
            failed,
            trimmed,
        }
    }

    /// The regions face `j` of the second operand is taken from.
    fn second(&self) -> &Arc<Vec<Option<TrimRegion>>> {
        if self.one_file.is_some() || self.b.is_empty() {
            &self.a
        } else {
            &self.b
        }
    }

    /// The test the coverage certificate of pair `(i, j)` uses to skip box pairs outside the
    /// faces (`None`: neither face is trimmed).
    pub fn outside_for(&self, i: usize, j: usize) -> Option<OutsideFaces> {
        let (ra, rb) = (self.a.clone(), self.second().clone());
        let trimmed =
            |r: &Arc<Vec<Option<TrimRegion>>>, k: usize| r.get(k).is_some_and(|x| x.is_some());
        if !trimmed(&ra, i) && !trimmed(&rb, j) {
            return None;
        }
        Some(OutsideFaces(Arc::new(move |ua, ub| {
            ra[i]
                .as_ref()
                .is_some_and(|r| r.box_outside(ua, REGION_MARGIN))
                || rb[j]
                    .as_ref()
                    .is_some_and(|r| r.box_outside(ub, REGION_MARGIN))
        })))
    }

    /// Restrict pair `p` to its faces.
    pub fn apply(&self, p: &mut PairOut) {
        let ra = self.a.get(p.a).and_then(|r| r.as_ref());
        let rb = self.second().get(p.b).and_then(|r| r.as_ref());
        let mut probes: Vec<EdgeProbe> = Vec::new();
        let mut vertices: Vec<(&str, [f64; 3], f64)> = Vec::new();
        if let Some((m, brep, topo)) = &self.one_file {
            let (ea, va) = &topo[p.a];
            let (eb, vb) = &topo[p.b];
            let (sa, sb) = (&m.surfaces[p.a].nurbs, &m.surfaces[p.b].nurbs);
            for &e in ea.intersection(eb) {
                if let Some(c) = &brep.edges[e].curve {
                    probes.push(EdgeProbe::new(
                        &brep.edges[e].source,
                        &c.nurbs,
                        sa,
                        sb,
                        self.delta,
                        self.cap,
                    ));
                }
            }
            // A shared vertex reaches as far as the farthest shared edge.
            let reach = probes.iter().map(|e| e.within).fold(self.delta, f64::max);
            for &v in va.intersection(vb) {
                vertices.push((&brep.vertices[v].source, brep.vertices[v].point, reach));
            }
        }
        if ra.is_none() && rb.is_none() && probes.is_empty() && vertices.is_empty() {
            return;
        }
        let mut out = FaceClipOut::default();
        let mut shared: Vec<SharedEdgeOut> = probes
            .iter()
            .map(|e| e.source)
            .chain(vertices.iter().map(|v| v.0))
            .map(|s| SharedEdgeOut {
                edge: s.to_string(),
                points: 0,
                max_distance: 0.0,
                within: 0.0,
            })
            .collect();
        let reach: Vec<f64> = probes
            .iter()
            .map(|e| e.within)
            .chain(vertices.iter().map(|v| v.2))
            .collect();
        for (s, r) in shared.iter_mut().zip(&reach) {
            s.within = *r;
        }
        // Index of the shared edge or vertex within its reach of `x`, the nearest.
        let near_shared = |x: &[f64; 3]| -> Option<(usize, f64)> {
            let d = probes
                .iter()
                .map(|e| e.distance(x))
                .chain(vertices.iter().map(|v| dist(&v.1, x)));
            d.enumerate()
                .filter(|(i, d)| *d <= reach[*i])
                .min_by(|a, b| a.1.total_cmp(&b.1))
        };
        let inside = |uva: &[f64; 2], uvb: &[f64; 2]| {
            ra.is_none_or(|r| r.inside(uva)) && rb.is_none_or(|r| r.inside(uvb))
        };
        let mut branches = Vec::new();
        for b in &p.branches {
            let mut keep = vec![true; b.points.len()];
            for (i, k) in keep.iter_mut().enumerate() {
                if let Some((e, d)) = near_shared(&b.points[i]) {
                    shared[e].points += 1;
                    shared[e].max_distance = shared[e].max_distance.max(d);
                    *k = false;
                } else if !inside(&b.uv_a[i], &b.uv_b[i]) {
                    out.points_outside += 1;
                    *k = false;
                }
            }
            branches.extend(clip_mask(b, &keep));
        }
        p.branches = branches;
        // A tangent contact along a shared edge (a G1 join of two faces) is that edge; its
        // points outside either face are not the faces' contact.
        if let Some(c) = &mut p.tangent_contact {
            let mut keep_point = |x: &[f64; 3], ua: &[f64; 2], ub: &[f64; 2]| match near_shared(x) {
                Some((e, d)) => {
                    shared[e].points += 1;
                    shared[e].max_distance = shared[e].max_distance.max(d);
                    false
                }
                None if !inside(ua, ub) => {
                    out.points_outside += 1;
                    false
                }
                None => true,
            };
            let keep: Vec<bool> = c
                .points
                .iter()
                .zip(&c.params)
                .map(|(x, (ua, ub))| keep_point(x, ua, ub))
                .collect();
            let mut k = keep.iter();
            c.points.retain(|_| *k.next().unwrap_or(&true));
            let mut k = keep.iter();
            c.params.retain(|_| *k.next().unwrap_or(&true));
            c.unlisted.retain(|(x, ua, ub)| keep_point(x, ua, ub));
            if c.points.is_empty() && c.unlisted.is_empty() {
                p.tangent_contact = None;
            }
        }
        let touch: Vec<TouchOut> = std::mem::take(&mut p.touch_points);
        for t in touch {
            if near_shared(&t.point).is_some() {
                out.touch_points_on_shared_edges += 1;
            } else if t.uv_a.zip(t.uv_b).is_some_and(|(a, b)| !inside(&a, &b)) {
                out.touch_points_outside += 1;
            } else {
                p.touch_points.push(t);
            }
        }
        if let Some(c) = &mut p.coverage {
            let before = c.uncertified_regions.len();
            c.uncertified_regions.retain(|g| {
                !(ra.is_some_and(|r| r.box_outside(&g.uv_a, REGION_MARGIN))
                    || rb.is_some_and(|r| r.box_outside(&g.uv_b, REGION_MARGIN)))
            });
            out.regions_outside = before - c.uncertified_regions.len();
            c.uncertified -= out.regions_outside.min(c.uncertified);
            c.no_missed_branches = c.uncertified == 0;
        }
        out.shared_edges = shared.into_iter().filter(|s| s.points > 0).collect();
        p.faces = Some(out);
    }
}
