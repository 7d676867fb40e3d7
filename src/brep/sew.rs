//! A B-rep from faces that carry their boundaries as separate model-space curves (IGES 143 and
//! 144 faces: each face has its own copy of every boundary curve, no shared edges): the curve
//! ends are merged into vertices within a tolerance, and two boundary curves between the same
//! vertices whose points lie within the tolerance of each other become one edge used by both
//! faces (sewing).
//!
//! Within one loop the curves are put end to end (a curve whose end, not its start, meets the
//! previous curve's end is reversed). Curves shorter than the tolerance (degenerate boundary
//! pieces at poles) are left out; the neighbours meet at their vertex. Two curves count as
//! one edge when seven interior points of each lie within the tolerance of the other (closest
//! points by [`CurveFoot`]: evidence, not a proof). The shell holds every face; it is
//! closed when every edge is used exactly twice. Nothing here changes the faces' surfaces
//! or trims.

use super::{Brep, CurveKind, Edge, EdgeCurve, Face, Loop, LoopKind, OrientedEdge, Shell, Vertex};
use crate::geom::dist;
use crate::spline::NurbsCurve;
use crate::spline::project::CurveFoot;
use std::collections::HashMap;

/// One loop of a face: declared outer, its source id, and its curves in loop order (source
/// id and model-space curve).
pub struct BoundaryLoop {
    pub outer: bool,
    pub source: String,
    pub curves: Vec<(String, NurbsCurve<f64, 3>)>,
}

/// A face with its surface and its boundary loops.
pub struct FaceBoundary {
    pub source: String,
    pub surface: usize,
    pub surface_source: String,
    pub loops: Vec<BoundaryLoop>,
}

/// What sewing found.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SewStats {
    /// Boundary curves read (all loops).
    pub curves: usize,
    /// Left out as shorter than the tolerance.
    pub degenerate: usize,
    /// Edges used by two faces, by one face, by more than two.
    pub shared: usize,
    pub free: usize,
    pub more: usize,
}

fn ends(c: &NurbsCurve<f64, 3>) -> ([f64; 3], [f64; 3]) {
    let (a, b) = c.hom.domain();
    (c.eval(&a), c.eval(&b))
}

/// The larger of the two one-way distances between `a` and `b` measured at seven interior
/// points of each (closest points by [`CurveFoot`]: evidence); infinite where a distance is
/// not a number.
pub fn curve_distance(a: &NurbsCurve<f64, 3>, b: &NurbsCurve<f64, 3>) -> f64 {
    let one_way = |x: &NurbsCurve<f64, 3>, y: &NurbsCurve<f64, 3>| {
        let (t0, t1) = x.hom.domain();
        let foot = CurveFoot::new(y);
        (1..8)
            .map(|i| foot.closest(&x.eval(&(t0 + (t1 - t0) * i as f64 / 8.0))).2)
            .fold(
                0.0,
                |m: f64, d| if d.is_nan() { f64::INFINITY } else { m.max(d) },
            )
    };
    one_way(a, b).max(one_way(b, a))
}

/// Whether `a` and `b` are the same curve within `tol` ([`curve_distance`]).
fn same_curve(a: &NurbsCurve<f64, 3>, b: &NurbsCurve<f64, 3>, tol: f64) -> bool {
    curve_distance(a, b) <= tol
}

/// Vertices merged within a tolerance (a hash grid of cells twice the tolerance).
struct Welder {
    cell: f64,
    tol: f64,
    grid: HashMap<[i64; 3], Vec<usize>>,
}

impl Welder {
    fn key(&self, p: &[f64; 3]) -> [i64; 3] {
        p.map(|x| (x / self.cell).floor() as i64)
    }
    fn vertex(&mut self, b: &mut Brep, p: [f64; 3], source: &str) -> usize {
        let k = self.key(&p);
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    let c = [k[0] + dx, k[1] + dy, k[2] + dz];
                    if let Some(v) = self.grid.get(&c).and_then(|vs| {
                        vs.iter()
                            .copied()
                            .find(|v| dist(&b.vertices[*v].point, &p) <= self.tol)
                    }) {
                        return v;
                    }
                }
            }
        }
        b.vertices.push(Vertex {
            source: source.to_string(),
            point: p,
        });
        let v = b.vertices.len() - 1;
        self.grid.entry(k).or_default().push(v);
        v
    }
}

fn kind_of(c: &NurbsCurve<f64, 3>) -> CurveKind {
    let (pts, w) = c.points_weights();
    if c.hom.degree() == 1 && pts.len() == 2 {
        CurveKind::Line
    } else if w.iter().all(|x| *x == w[0]) {
        CurveKind::BSpline
    } else {
        CurveKind::RationalBSpline
    }
}

/// Sew `faces` into a B-rep; vertices merge and curves match within `tol` (model units).
pub fn sew(faces: &[FaceBoundary], tol: f64) -> (Brep, SewStats) {
    let mut b = Brep {
        tolerance: tol,
        ..Brep::default()
    };
    let mut stats = SewStats::default();
    let mut w = Welder {
        cell: 2.0 * tol.max(f64::MIN_POSITIVE),
        tol,
        grid: HashMap::new(),
    };
    // Edges by their (smaller, larger) vertex pair.
    let mut by_ends: HashMap<(usize, usize), Vec<usize>> = HashMap::new();
    for f in faces {
        let mut loops = Vec::new();
        for l in &f.loops {
            stats.curves += l.curves.len();
            // Degenerate pieces out, then the chain oriented end to end.
            let mut chain: Vec<(&str, NurbsCurve<f64, 3>)> = Vec::new();
            for (src, c) in &l.curves {
                let (p, q) = ends(c);
                let (pts, _) = c.points_weights();
                let extent = pts.iter().map(|x| dist(x, &p)).fold(0.0, f64::max);
                if dist(&p, &q) <= tol && extent <= tol {
                    stats.degenerate += 1;
                    continue;
                }
                chain.push((src, c.clone()));
            }
            for i in 0..chain.len() {
                let prev_end = if i == 0 {
                    // The first curve faces the way that meets the second (or closes on
                    // itself).
                    match chain.get(1) {
                        Some((_, n)) => {
                            let (p, q) = ends(&chain[0].1);
                            let (np, nq) = ends(n);
                            if dist(&p, &np).min(dist(&p, &nq)) < dist(&q, &np).min(dist(&q, &nq)) {
                                chain[0].1 = chain[0].1.reversed();
                            }
                            continue;
                        }
                        None => continue,
                    }
                } else {
                    ends(&chain[i - 1].1).1
                };
                let (p, q) = ends(&chain[i].1);
                if dist(&q, &prev_end) < dist(&p, &prev_end) {
                    chain[i].1 = chain[i].1.reversed();
                }
            }
            let mut oes = Vec::with_capacity(chain.len());
            for (src, c) in chain {
                let (p, q) = ends(&c);
                let (vs, ve) = (w.vertex(&mut b, p, src), w.vertex(&mut b, q, src));
                let key = (vs.min(ve), vs.max(ve));
                let found = by_ends.get(&key).and_then(|es| {
                    es.iter().copied().find(|e| {
                        b.edges[*e]
                            .curve
                            .as_ref()
                            .is_some_and(|x| same_curve(&x.nurbs, &c, tol))
                    })
                });
                let oe = match found {
                    Some(e) => {
                        let forward = if vs != ve {
                            b.edges[e].start == vs
                        } else {
                            // A closed edge: the direction whose quarter point is nearer.
                            let x = b.edges[e].curve.as_ref().map(|x| x.nurbs.clone());
                            x.is_some_and(|x| {
                                let (a0, a1) = x.hom.domain();
                                let (c0, c1) = c.hom.domain();
                                let q = c.eval(&(c0 + 0.25 * (c1 - c0)));
                                dist(&x.eval(&(a0 + 0.25 * (a1 - a0))), &q)
                                    <= dist(&x.eval(&(a0 + 0.75 * (a1 - a0))), &q)
                            })
                        };
                        OrientedEdge { edge: e, forward }
                    }
                    None => {
                        let gap =
                            dist(&p, &b.vertices[vs].point).max(dist(&q, &b.vertices[ve].point));
                        b.edges.push(Edge {
                            source: src.to_string(),
                            start: vs,
                            end: ve,
                            curve: Some(EdgeCurve {
                                source: src.to_string(),
                                kind: kind_of(&c),
                                nurbs: c,
                                vertex_gap: gap,
                            }),
                            pcurves: vec![],
                        });
                        let e = b.edges.len() - 1;
                        by_ends.entry(key).or_default().push(e);
                        OrientedEdge {
                            edge: e,
                            forward: true,
                        }
                    }
                };
                oes.push(oe);
            }
            if !oes.is_empty() {
                loops.push(Loop {
                    source: l.source.clone(),
                    loop_source: l.source.clone(),
                    outer: l.outer,
                    orientation: true,
                    kind: LoopKind::Edges(oes),
                });
            }
        }
        b.report.converted("face (sewn)");
        for _ in &f.loops {
            b.report.converted("loop (sewn)");
        }
        b.faces.push(Face {
            source: f.source.clone(),
            surface: Some(f.surface),
            surface_source: f.surface_source.clone(),
            same_sense: true,
            loops,
        });
    }
    let all: Vec<(usize, bool)> = (0..b.faces.len()).map(|i| (i, true)).collect();
    let uses = b.edge_uses(&all);
    for e in 0..b.edges.len() {
        match uses.get(&e).copied().unwrap_or(0) {
            2 => stats.shared += 1,
            0 | 1 => stats.free += 1,
            _ => stats.more += 1,
        }
    }
    b.shells.push(Shell {
        source: "(sewn)".into(),
        closed: stats.free == 0 && stats.more == 0 && !b.edges.is_empty(),
        faces: all,
    });
    let issues = b.check();
    b.report.issues.extend(issues);
    (b, stats)
}
