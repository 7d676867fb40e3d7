//! The edges and vertices two faces of one B-rep share, as tubes: in a one-file run the
//! intersection of the two surfaces along a shared edge is where the faces meet by
//! construction, listed as that edge ([`super::brep_faces`]), not traced as a branch, and the
//! coverage certificate accounts for it through the tube ([`crate::ssi::coverage`]).
//!
//! A tube is the set of points within its reach `r` of the edge's sample polyline (513
//! samples of the edge's 3D curve), or of a shared vertex. What rests on what:
//! * attributing a point to an edge: its distance to the edge *curve*, found by a local search
//!   from the nearest sample (evidence);
//! * the reach `r = clamp(2 (g_a + g_b) / sin θ, base, cap)` from measured gaps and angles
//!   (evidence, `edge_reach`);
//! * the coverage's use of a tube is a theorem about the polyline and the number `r` as they
//!   are, whatever their accuracy: the claim then excludes every branch with a point in the
//!   tube (also where it runs on outside it: a border crossing in a tube decides its pair).

use crate::geom::{cross, dist, norm};
use crate::spline::project::{point_d1, project};
use crate::spline::{NurbsCurve, NurbsSurface};
use serde::Serialize;

/// Samples per shared edge curve: the polyline of the tube and the first guess of a
/// point's distance.
const EDGE_SAMPLES: usize = 512;

/// The intersection of two faces along an edge they share.
#[derive(Clone, Debug, Serialize)]
pub struct SharedEdgeOut {
    /// Source id of the edge (or of the vertex, for a shared vertex).
    pub edge: String,
    /// Points of the surfaces' intersection attributed to it: branch points lying within
    /// `within` of it, and the traced points of curves lying wholly along it (these are not
    /// refined further, nor certified).
    pub points: usize,
    /// Largest distance of those points from the edge curve (local search: evidence).
    pub max_distance: f64,
    pub within: f64,
}

/// A shared edge's curve with its samples, or a shared vertex.
enum Shape {
    Edge {
        curve: NurbsCurve<f64, 3>,
        t: Vec<f64>,
        p: Vec<[f64; 3]>,
    },
    Vertex([f64; 3]),
}

struct Tube {
    source: String,
    shape: Shape,
    /// Points within this distance are attributed to the edge or vertex.
    within: f64,
}

/// The tubes around the edges and vertices two faces share.
pub struct SharedTubes {
    tubes: Vec<Tube>,
}

impl Tube {
    /// Distance from `x` to the edge curve: nearest sample, then a golden-section search on
    /// the two sample intervals around it (evidence); to a vertex, exact up to rounding.
    fn distance(&self, x: &[f64; 3]) -> f64 {
        let (curve, t, p) = match &self.shape {
            Shape::Vertex(v) => return dist(v, x),
            Shape::Edge { curve, t, p } => (curve, t, p),
        };
        let (k, d0) = p
            .iter()
            .enumerate()
            .map(|(k, p)| (k, dist(p, x)))
            .fold((0, f64::INFINITY), |a, b| if b.1 < a.1 { b } else { a });
        let (mut lo, mut hi) = (t[k.saturating_sub(1)], t[(k + 1).min(t.len() - 1)]);
        let f = |s: f64| dist(&curve.eval(&s), x);
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

impl SharedTubes {
    /// Tubes around `edges` (source id, 3D curve) and `vertices` (source id, point) shared by
    /// the faces on `sa` and `sb`. `base`: the least reach; `cap`: the largest. A vertex
    /// reaches as far as the farthest shared edge.
    pub fn new(
        edges: Vec<(String, NurbsCurve<f64, 3>)>,
        vertices: Vec<(String, [f64; 3])>,
        sa: &NurbsSurface<f64, 3>,
        sb: &NurbsSurface<f64, 3>,
        base: f64,
        cap: f64,
    ) -> SharedTubes {
        let mut tubes: Vec<Tube> = edges
            .into_iter()
            .map(|(source, curve)| {
                let (t0, t1) = curve.hom.domain();
                let t: Vec<f64> = (0..=EDGE_SAMPLES)
                    .map(|i| t0 + (t1 - t0) * i as f64 / EDGE_SAMPLES as f64)
                    .collect();
                let p: Vec<[f64; 3]> = t.iter().map(|x| curve.eval(x)).collect();
                let within = edge_reach(&p, sa, sb).clamp(base, cap.max(base));
                Tube {
                    source,
                    shape: Shape::Edge { curve, t, p },
                    within,
                }
            })
            .collect();
        let reach = tubes.iter().map(|e| e.within).fold(base, f64::max);
        tubes.extend(vertices.into_iter().map(|(source, v)| Tube {
            source,
            shape: Shape::Vertex(v),
            within: reach,
        }));
        SharedTubes { tubes }
    }

    pub fn is_empty(&self) -> bool {
        self.tubes.is_empty()
    }

    /// One empty tally per edge and vertex, in order.
    pub fn tally(&self) -> Vec<SharedEdgeOut> {
        self.tubes
            .iter()
            .map(|e| SharedEdgeOut {
                edge: e.source.clone(),
                points: 0,
                max_distance: 0.0,
                within: e.within,
            })
            .collect()
    }

    /// The edge or vertex within its reach of `x`, the nearest, with the distance.
    pub fn nearest(&self, x: &[f64; 3]) -> Option<(usize, f64)> {
        self.tubes
            .iter()
            .map(|e| e.distance(x))
            .enumerate()
            .filter(|(i, d)| *d <= self.tubes[*i].within)
            .min_by(|a, b| a.1.total_cmp(&b.1))
    }

    /// Count `x` to its nearest edge or vertex in `tally`; `false` when it is in no tube.
    pub fn attribute(&self, x: &[f64; 3], tally: &mut [SharedEdgeOut]) -> bool {
        match self.nearest(x) {
            Some((e, d)) => {
                tally[e].points += 1;
                tally[e].max_distance = tally[e].max_distance.max(d);
                true
            }
            None => false,
        }
    }

    /// The tubes as the coverage certificate takes them: each edge's sample polyline (a
    /// vertex as a point) with its reach.
    pub fn polylines(&self) -> Vec<crate::ssi::coverage::TubeLine> {
        self.tubes
            .iter()
            .map(|e| {
                let segs = match &e.shape {
                    Shape::Edge { p, .. } => p.windows(2).map(|w| (w[0], w[1])).collect(),
                    Shape::Vertex(v) => vec![(*v, *v)],
                };
                (segs, e.within)
            })
            .collect()
    }
}

impl std::fmt::Debug for SharedTubes {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let names: Vec<&str> = self.tubes.iter().map(|t| t.source.as_str()).collect();
        write!(f, "SharedTubes({names:?})")
    }
}
