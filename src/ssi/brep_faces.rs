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
//! * an uncertified coverage region is dropped, and a coverage box pair skipped, only when
//!   its parameter box, widened by 1e-9 of the domain (the rounding of the boxes' labels),
//!   lies wholly outside one face's polygon;
//! * the coverage claim is made about the output *as restricted here*
//!   ([`Faces::restrict_for`]: the same inside and shared-edge decisions, taken before the
//!   claim), so no output removed here can have decided a box pair: the claim is about the
//!   faces as their polygons outline them.

use super::coverage::OutsideFaces;
use super::coverage::{BoxTest, EdgesTest, FaceRestriction};
use super::report::{PairOut, TouchOut};
pub use super::shared_tubes::SharedEdgeOut;
use super::shared_tubes::SharedTubes;
use super::trims::{TrimRegion, clip_mask};
use crate::brep::{Brep, LoopKind};
use crate::model::Model;
use serde::Serialize;
use std::collections::BTreeSet;
use std::sync::Arc;

/// Margin (fraction of the domain) by which parameter boxes are widened before a test
/// against a face's loop polygons (coverage boxes outside a face, uncertified regions outside
/// it, common borders on it): the rounding of the coverage's box labels, and common borders
/// that *are* the face's boundary, on its loop polygon up to rounding.
const FACE_MARGIN: f64 = 1e-9;

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
    /// Branch points outside either face kept as the outer end of a chord leaving the faces
    /// (the output reaches the loop along it).
    pub chord_ends_outside: usize,
    /// Points of common borders farther than `1e-9` of the domain outside either face's
    /// loops, or on a shared edge or vertex.
    pub border_points_outside: usize,
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
    /// The two models (the second absent in a one-file run).
    models: (&'a Model, Option<&'a Model>),
    /// The least attribution distance, `max(100 tol, 1e-6 size)`, and the largest, 1 % of
    /// the model size.
    delta: f64,
    cap: f64,
    /// Faces whose region could not be outlined (their surfaces are not clipped).
    pub failed: Vec<String>,
    /// Faces outlined against their declared outer loop (the run is not certified).
    pub ambiguous: Vec<String>,
    /// Faces (trim loops or B-rep faces) that clip.
    pub trimmed: usize,
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

/// [`FaceRestriction::outside_a`] for face `k` of `r`.
fn outside_one(r: &Arc<Vec<Option<TrimRegion>>>, k: usize) -> Arc<BoxTest> {
    let r = r.clone();
    Arc::new(move |b| {
        r.get(k)
            .and_then(|x| x.as_ref())
            .is_some_and(|x| x.box_outside(b, FACE_MARGIN))
    })
}

/// [`FaceRestriction::inside_a`] for face `k` of `r`.
fn inside_one(r: &Arc<Vec<Option<TrimRegion>>>, k: usize) -> Arc<BoxTest> {
    let r = r.clone();
    Arc::new(move |b| {
        r.get(k)
            .and_then(|x| x.as_ref())
            .is_none_or(|x| x.box_inside_widened(b, FACE_MARGIN))
    })
}

/// [`FaceRestriction::edges_a`] for face `k` of `r`.
fn edges_one(r: &Arc<Vec<Option<TrimRegion>>>, k: usize) -> Arc<EdgesTest> {
    let r = r.clone();
    Arc::new(move |b| {
        r.get(k)
            .and_then(|x| x.as_ref())
            .map_or_else(Vec::new, |x| x.edges_meeting(b, FACE_MARGIN))
    })
}

impl<'a> Faces<'a> {
    pub fn new(a: &'a Model, b: Option<&'a Model>, tol: f64) -> Faces<'a> {
        let (ra, mut failed, mut ambiguous) = TrimRegion::of_model(a);
        let rb = match b {
            Some(m) => {
                let (r, f, amb) = TrimRegion::of_model(m);
                failed.extend(f);
                ambiguous.extend(amb);
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
            models: (a, b),
            b: Arc::new(rb),
            one_file,
            delta: (100.0 * tol).max(1e-6 * size),
            cap: 1e-2 * size,
            failed,
            ambiguous,
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
                .is_some_and(|r| r.box_outside(ua, FACE_MARGIN))
                || rb[j]
                    .as_ref()
                    .is_some_and(|r| r.box_outside(ub, FACE_MARGIN))
        })))
    }

    /// The restriction of pair `(i, j)`'s output to its faces, as [`Faces::apply`] makes it,
    /// for the coverage claim to be made about the restricted output (`None`: neither face is
    /// trimmed and they share nothing). `tubes`: those of [`Faces::tubes_for`].
    pub fn restrict_for(
        &self,
        i: usize,
        j: usize,
        tubes: Option<Arc<SharedTubes>>,
    ) -> Option<FaceRestriction> {
        let (ra, rb) = (self.a.clone(), self.second().clone());
        let trimmed =
            |r: &Arc<Vec<Option<TrimRegion>>>, k: usize| r.get(k).is_some_and(|x| x.is_some());
        if !trimmed(&ra, i) && !trimmed(&rb, j) && tubes.is_none() {
            return None;
        }
        let (ra2, rb2) = (ra.clone(), rb.clone());
        let (ra3, rb3) = (ra.clone(), rb.clone());
        let widen = |b: &[f64; 4], r: &TrimRegion| r.box_inside_widened(b, FACE_MARGIN);
        Some(FaceRestriction {
            pair_inside: Arc::new(move |ba, bb| {
                ra3[i].as_ref().is_none_or(|r| widen(ba, r))
                    && rb3[j].as_ref().is_none_or(|r| widen(bb, r))
            }),
            inside: Arc::new(move |ua, ub| {
                ra[i].as_ref().is_none_or(|r| r.inside(ua))
                    && rb[j].as_ref().is_none_or(|r| r.inside(ub))
            }),
            meets: Arc::new(move |ba, bb| {
                ra2[i]
                    .as_ref()
                    .is_none_or(|r| !r.box_outside(ba, FACE_MARGIN))
                    && rb2[j]
                        .as_ref()
                        .is_none_or(|r| !r.box_outside(bb, FACE_MARGIN))
            }),
            shared: Arc::new(move |x| tubes.as_ref().is_some_and(|t| t.nearest(x).is_some())),
            outside_a: outside_one(&self.a, i),
            outside_b: outside_one(self.second(), j),
            inside_a: inside_one(&self.a, i),
            inside_b: inside_one(self.second(), j),
            edges_a: edges_one(&self.a, i),
            edges_b: edges_one(self.second(), j),
        })
    }

    /// The tubes around the edges and vertices faces `i` and `j` share, in a one-file run on a
    /// B-rep (`None` otherwise, or when they share nothing).
    pub fn tubes_for(&self, i: usize, j: usize) -> Option<Arc<SharedTubes>> {
        let (m, brep, topo) = self.one_file.as_ref()?;
        let ((ea, va), (eb, vb)) = (topo.get(i)?, topo.get(j)?);
        let edges: Vec<_> = ea
            .intersection(eb)
            .filter_map(|&e| {
                let c = brep.edges[e].curve.as_ref()?;
                Some((brep.edges[e].source.clone(), c.nurbs.clone()))
            })
            .collect();
        let vertices: Vec<_> = va
            .intersection(vb)
            .map(|&v| (brep.vertices[v].source.clone(), brep.vertices[v].point))
            .collect();
        let (sa, sb) = (&m.surfaces[i].nurbs, &m.surfaces[j].nurbs);
        let t = SharedTubes::new(edges, vertices, sa, sb, self.delta, self.cap);
        (!t.is_empty()).then(|| Arc::new(t))
    }

    /// Restrict pair `p` to its faces; `tubes`: those of [`Faces::tubes_for`] for the pair,
    /// which the pair's run may have counted points to already (curves lying wholly along a
    /// shared edge, [`super::branch::refine_branch`]).
    pub fn apply(&self, p: &mut PairOut, tubes: Option<&SharedTubes>) {
        let ra = self.a.get(p.a).and_then(|r| r.as_ref());
        let rb = self.second().get(p.b).and_then(|r| r.as_ref());
        if ra.is_none() && rb.is_none() && tubes.is_none() {
            return;
        }
        let mut out = p.faces.take().unwrap_or_default();
        let mut shared = match tubes {
            Some(t) if out.shared_edges.is_empty() => t.tally(),
            _ => std::mem::take(&mut out.shared_edges),
        };
        let mut on_shared = |x: &[f64; 3]| tubes.is_some_and(|t| t.attribute(x, &mut shared));
        let inside = |uva: &[f64; 2], uvb: &[f64; 2]| {
            ra.is_none_or(|r| r.inside(uva)) && rb.is_none_or(|r| r.inside(uvb))
        };
        // Parameter boxes on A and on B meeting both faces (within 1e-9 of the domain).
        let meets = |ba: &[f64; 4], bb: &[f64; 4]| {
            ra.is_none_or(|r| !r.box_outside(ba, FACE_MARGIN))
                && rb.is_none_or(|r| !r.box_outside(bb, FACE_MARGIN))
        };
        // The same decisions as [`Faces::restrict_for`], which the coverage claim was made
        // about; here with the counts and the shared edges' tallies.
        let mut branches = Vec::new();
        for b in &p.branches {
            let shared: Vec<bool> = b.points.iter().map(&mut on_shared).collect();
            let ins: Vec<bool> = (0..b.points.len())
                .map(|i| inside(&b.uv_a[i], &b.uv_b[i]))
                .collect();
            let keep = super::coverage::keep_mask(b, &shared, &ins);
            for (i, k) in keep.iter().enumerate() {
                if !shared[i] && !ins[i] {
                    if *k {
                        out.chord_ends_outside += 1;
                    } else {
                        out.points_outside += 1;
                    }
                }
            }
            branches.extend(clip_mask(b, &keep));
        }
        p.branches = branches;
        // Common borders: the parts on both faces ([`super::common_borders::clip_to_faces`]);
        // points on a shared edge are that edge (not counted to it: they are samples of the
        // border, not traced points).
        let (ma, mb) = self.models;
        let mb = if self.one_file.is_some() {
            ma
        } else {
            mb.unwrap_or(ma)
        };
        if let (Some(sa), Some(sb)) = (ma.surfaces.get(p.a), mb.surfaces.get(p.b)) {
            let shared = |x: &[f64; 3]| tubes.is_some_and(|t| t.nearest(x).is_some());
            let mut borders = Vec::new();
            for c in &p.common_borders {
                let (parts, removed) = super::common_borders::clip_to_faces(
                    c,
                    (&sa.nurbs, &sb.nurbs),
                    &meets,
                    &shared,
                );
                out.border_points_outside += removed;
                borders.extend(parts);
            }
            p.common_borders = borders;
        }
        // A tangent contact along a shared edge (a G1 join of two faces) is that edge; its
        // points outside either face are not the faces' contact.
        if let Some(c) = &mut p.tangent_contact {
            let mut keep_point = |x: &[f64; 3], ua: &[f64; 2], ub: &[f64; 2]| {
                if on_shared(x) {
                    false
                } else if !inside(ua, ub) {
                    out.points_outside += 1;
                    false
                } else {
                    true
                }
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
            if tubes.is_some_and(|s| s.nearest(&t.point).is_some()) {
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
                !(ra.is_some_and(|r| r.box_outside(&g.uv_a, FACE_MARGIN))
                    || rb.is_some_and(|r| r.box_outside(&g.uv_b, FACE_MARGIN)))
            });
            out.regions_outside = before - c.uncertified_regions.len();
            c.uncertified -= out.regions_outside.min(c.uncertified);
            c.no_missed_branches = c.uncertified == 0;
        }
        // Every tube the coverage may have used is listed with its reach (the claim rests on
        // it), also when no point went to it; otherwise only those with points.
        let used_tubes = p
            .coverage
            .as_ref()
            .is_some_and(|c| c.near_shared_edges + c.crossing_boxes_near_shared_edges > 0);
        out.shared_edges = shared
            .into_iter()
            .filter(|s| s.points > 0 || used_tubes)
            .collect();
        p.faces = Some(out);
    }
}
