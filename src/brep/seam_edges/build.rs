//! The one loop of a rebuilt face: its round loops' arcs, the seam edge and the pole edge,
//! each use with its pcurve (module comment of [`super`]).

use super::Plan;
use super::cut::uses;
use super::round::at;
use crate::brep::pcurve::project::{Fit, Projector, segment};
use crate::brep::{Brep, CurveKind, Edge, EdgeCurve, OrientedEdge, Vertex};
use crate::geom::{Hom, dist};
use crate::spline::{BSplineCurve, NurbsCurve, NurbsSurface};
use std::collections::{BTreeMap, BTreeSet};

/// The surface point with the `k`-th parameter `x` and the other `y`.
pub(super) fn point(s: &NurbsSurface<f64, 3>, k: usize, x: f64, y: f64) -> [f64; 3] {
    let p = at(k, x, y);
    s.eval(&p[0], &p[1])
}

/// The parameter line "`k`-th parameter at its low end" of `s`, the other running over
/// `[a, b]`, `a < b` (clamped knots: the first row of the net).
fn seam_curve(s: &NurbsSurface<f64, 3>, k: usize, a: f64, b: f64) -> Option<NurbsCurve<f64, 3>> {
    let h = &s.hom;
    let nv = h.kv.n_ctrl();
    let (knots, p, control): (&[f64], usize, Vec<Hom<f64, 3>>) = if k == 0 {
        (h.kv.knots(), h.kv.degree(), h.net[..nv].to_vec())
    } else {
        (
            h.ku.knots(),
            h.ku.degree(),
            (0..h.ku.n_ctrl()).map(|i| h.net[i * nv].clone()).collect(),
        )
    };
    let line = BSplineCurve::new(knots.to_vec(), p, control).ok()?;
    Some(NurbsCurve {
        hom: line.sub_curve(&a, &b).ok()?,
    })
}

fn start_of(b: &Brep, o: &OrientedEdge) -> usize {
    let e = &b.edges[o.edge];
    if o.forward { e.start } else { e.end }
}

/// Context of one face's rebuilding.
pub(super) struct Builder<'a> {
    pub b: &'a mut Brep,
    pub s: &'a NurbsSurface<f64, 3>,
    /// The pcurves' maker on `s`.
    pub proj: &'a Projector<'a>,
    pub fi: usize,
    pub k: usize,
    pub lo: f64,
    pub hi: f64,
    /// The accepted distance between vertices and points meant to coincide.
    pub off: f64,
    /// How near an arc's pcurve's image is to lie to it.
    pub fit: Fit,
    pub pcurves: &'a mut BTreeMap<(usize, usize, bool), NurbsCurve<f64, 2>>,
    /// The pole edges made.
    pub poles: &'a mut BTreeSet<usize>,
}

impl Builder<'_> {
    /// The uses of round loop `o`, crossing the seam at `other = c`, from its vertex there
    /// round to it, each with its pcurve; the closed parameter runs up when `up`.
    fn round(
        &mut self,
        arcs: &BTreeMap<usize, Vec<usize>>,
        o: OrientedEdge,
        c: f64,
        up: bool,
    ) -> Option<(Vec<OrientedEdge>, usize)> {
        let mut us = uses(arcs, o);
        let seam = point(self.s, self.k, self.lo, c);
        let first = us
            .iter()
            .position(|u| dist(&self.b.vertices[start_of(self.b, u)].point, &seam) <= self.off)?;
        us.rotate_left(first);
        let v = start_of(self.b, &us[0]);
        let (from, to) = if up {
            (self.lo, self.hi)
        } else {
            (self.hi, self.lo)
        };
        let mut x = at(self.k, from, c);
        let n = us.len();
        for (i, u) in us.iter().enumerate() {
            let curve = &self.b.edges[u.edge].curve.as_ref()?.nurbs;
            let arc = if u.forward {
                curve.clone()
            } else {
                curve.reversed()
            };
            let end = (i + 1 == n).then(|| at(self.k, to, c));
            let p = self.proj.project(&arc, Some(x), end, self.fit)?;
            self.pcurves.insert((self.fi, u.edge, u.forward), p.curve);
            x = p.end;
        }
        Some((us, v))
    }
    /// A new edge of this face (`what`: seam or pole) between `ends` along `nurbs`; its index.
    fn edge(
        &mut self,
        what: &str,
        ends: (usize, usize),
        kind: CurveKind,
        nurbs: NurbsCurve<f64, 3>,
    ) -> usize {
        self.b.edges.push(Edge {
            source: format!("{what} of face {}", self.b.faces[self.fi].source),
            start: ends.0,
            end: ends.1,
            curve: Some(EdgeCurve {
                source: String::new(),
                kind,
                nurbs,
                vertex_gap: 0.0,
            }),
            pcurves: Vec::new(),
        });
        self.b.edges.len() - 1
    }
    /// A new edge from vertex `va` (at `other = a`) to `vb` (at `z`) along the seam, and its
    /// two uses: forward on the closed parameter's high side when `high`, backward on the
    /// other.
    fn seam(
        &mut self,
        va: usize,
        a: f64,
        vb: usize,
        z: f64,
        high: bool,
    ) -> Option<(OrientedEdge, OrientedEdge)> {
        let curve = if a < z {
            seam_curve(self.s, self.k, a, z)?
        } else {
            seam_curve(self.s, self.k, z, a)?.reversed()
        };
        let e = self.edge("seam", (va, vb), CurveKind::RationalBSpline, curve);
        let (x, y) = if high {
            (self.hi, self.lo)
        } else {
            (self.lo, self.hi)
        };
        self.pcurves.insert(
            (self.fi, e, true),
            segment(at(self.k, x, a), at(self.k, x, z))?,
        );
        self.pcurves.insert(
            (self.fi, e, false),
            segment(at(self.k, y, z), at(self.k, y, a))?,
        );
        Some((
            OrientedEdge {
                edge: e,
                forward: true,
            },
            OrientedEdge {
                edge: e,
                forward: false,
            },
        ))
    }
    /// A degenerate edge at the pole vertex `v` (other parameter `c`), used once, its pcurve
    /// along the border from the end side of the first round loop (the high end when `up`)
    /// to its start side.
    fn pole(&mut self, v: usize, c: f64, up: bool) -> Option<OrientedEdge> {
        let x = self.b.vertices.get(v)?.point;
        let e = self.edge("pole", (v, v), CurveKind::Line, segment(x, x)?);
        let (from, to) = if up {
            (self.hi, self.lo)
        } else {
            (self.lo, self.hi)
        };
        self.pcurves.insert(
            (self.fi, e, true),
            segment(at(self.k, from, c), at(self.k, to, c))?,
        );
        self.poles.insert(e);
        Some(OrientedEdge {
            edge: e,
            forward: true,
        })
    }
    /// The rebuilt loop of plan `p` (module comment of [`super`]).
    pub fn build(
        &mut self,
        p: &Plan,
        arcs: &BTreeMap<usize, Vec<usize>>,
    ) -> Option<Vec<OrientedEdge>> {
        let (e1, fwd1, r1) = &p.rounds[0];
        let up = *fwd1 == r1.up;
        let first = OrientedEdge {
            edge: *e1,
            forward: *fwd1,
        };
        let (mut l, va) = self.round(arcs, first, r1.c, up)?;
        match p.pole {
            None => {
                let (e2, fwd2, r2) = p.rounds.get(1)?;
                let second = OrientedEdge {
                    edge: *e2,
                    forward: *fwd2,
                };
                let (us, vb) = self.round(arcs, second, r2.c, !up)?;
                let (go, back) = self.seam(va, r1.c, vb, r2.c, up)?;
                l.push(go);
                l.extend(us);
                l.push(back);
            }
            Some((vp, cp)) => {
                // The pole vertex: the vertex loop's where it lies at the pole, else a new one.
                let x = point(self.s, self.k, self.lo, cp);
                let vp = match self.b.vertices.get(vp) {
                    Some(v) if dist(&v.point, &x) <= self.off => vp,
                    _ => {
                        self.b.vertices.push(Vertex {
                            source: format!("pole of face {}", self.b.faces[self.fi].source),
                            point: x,
                        });
                        self.b.vertices.len() - 1
                    }
                };
                let (go, back) = self.seam(va, r1.c, vp, cp, up)?;
                let pole = self.pole(vp, cp, up)?;
                l.extend([go, pole, back]);
            }
        }
        Some(l)
    }
}
