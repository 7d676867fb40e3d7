//! The source's own pcurve of an edge, restricted to the edge, for the writers. Where a
//! face's surface is the source's B-spline surface (the same parametrization), the pcurve
//! the file gave is the curve its author's system trimmed with; writing it back keeps the
//! trimmed face exactly as the file had it, also where the edge's 3D curve lies off the
//! surface by the file's tolerance (a projection of that curve would not).
//!
//! The edge's range on the pcurve is found from its vertices: a vertex's parameters on the
//! surface (projection), then the pcurve's parameter nearest to them (a line: the foot on the
//! line; a B-spline: the nearest of 65 samples refined by golden section on the distance in
//! space). The restricted curve is used only if its image follows the edge's 3D curve within
//! `off` at 9 points and its ends lie within `off` of the vertices.

use crate::brep::{Brep, Face, PCurveGeometry};
use crate::geom::dist;
use crate::spline::project::{CurveFoot, project};
use crate::spline::{NurbsCurve, NurbsSurface};

/// The source's pcurve of edge `e` on `face` (surface `s`, the source's own B-spline
/// surface), restricted to the edge and running from its start vertex to its end vertex.
/// `None` when the source gave none on that surface, gave two (a seam), the edge is closed,
/// or the restricted curve does not follow the edge within `off`.
pub fn source_pcurve(
    b: &Brep,
    e: usize,
    face: &Face,
    s: &NurbsSurface<f64, 3>,
    off: f64,
) -> Option<NurbsCurve<f64, 2>> {
    let edge = b.edges.get(e)?;
    let c = &edge.curve.as_ref()?.nurbs;
    let mut on = edge
        .pcurves
        .iter()
        .filter(|p| p.surface_source == face.surface_source);
    let pc = on.next()?;
    if on.next().is_some() || edge.start == edge.end {
        return None;
    }
    let v0 = b.vertices.get(edge.start)?.point;
    let v1 = b.vertices.get(edge.end)?.point;
    let img = |q: [f64; 2]| s.eval(&q[0], &q[1]);
    let out = match &pc.geometry {
        PCurveGeometry::Line { origin, direction } => {
            let dd = direction[0] * direction[0] + direction[1] * direction[1];
            if !(dd > 0.0 && dd.is_finite()) {
                return None;
            }
            let at = |v: &[f64; 3]| {
                let q = project(s, v);
                ((q[0] - origin[0]) * direction[0] + (q[1] - origin[1]) * direction[1]) / dd
            };
            let pt = |t: f64| [origin[0] + t * direction[0], origin[1] + t * direction[1]];
            let (a, z) = (at(&v0), at(&v1));
            if !(a != z && a.is_finite() && z.is_finite()) {
                return None;
            }
            NurbsCurve::new(
                vec![0.0, 0.0, 1.0, 1.0],
                1,
                vec![pt(a), pt(z)],
                vec![1.0; 2],
            )
            .ok()?
        }
        PCurveGeometry::Nurbs(n) => {
            let (d0, d1) = n.hom.domain();
            let near = |v: &[f64; 3]| -> f64 {
                let f = |t: f64| {
                    let q = n.eval(&t);
                    dist(&img(q), v)
                };
                let h = (d1 - d0) / 64.0;
                let k = (0..=64)
                    .map(|i| (f(d0 + h * i as f64), i))
                    .min_by(|a, b| a.0.total_cmp(&b.0))
                    .map_or(0, |x| x.1);
                // Golden section on the samples' neighbourhood.
                let (mut lo, mut hi) = (
                    (d0 + h * (k as f64 - 1.0)).max(d0),
                    (d0 + h * (k as f64 + 1.0)).min(d1),
                );
                let g = 0.5 * (5f64.sqrt() - 1.0);
                for _ in 0..80 {
                    let (x1, x2) = (hi - g * (hi - lo), lo + g * (hi - lo));
                    if f(x1) <= f(x2) {
                        hi = x2;
                    } else {
                        lo = x1;
                    }
                }
                0.5 * (lo + hi)
            };
            let (a, z) = (near(&v0), near(&v1));
            let snap = |t: f64| {
                let w = 1e-12 * (d1 - d0);
                if (t - d0).abs() <= w {
                    d0
                } else if (d1 - t).abs() <= w {
                    d1
                } else {
                    t
                }
            };
            let (a, z) = (snap(a), snap(z));
            if a < z {
                NurbsCurve {
                    hom: n.hom.sub_curve(&a, &z).ok()?,
                }
            } else if z < a {
                NurbsCurve {
                    hom: n.hom.sub_curve(&z, &a).ok()?,
                }
                .reversed()
            } else {
                return None;
            }
        }
    };
    // The restricted curve must follow the edge.
    let (t0, t1) = out.hom.domain();
    let foot = CurveFoot::new(c);
    let ends = dist(&img(out.eval(&t0)), &v0).max(dist(&img(out.eval(&t1)), &v1));
    let along = (0..=8)
        .map(|k| {
            let x = img(out.eval(&(t0 + (t1 - t0) * k as f64 / 8.0)));
            let (_, p, _) = foot.closest(&x);
            dist(&x, &p)
        })
        .fold(0.0, f64::max);
    (ends <= off && along <= off).then_some(out)
}

#[cfg(test)]
mod tests {
    //! A cylinder held as a B-spline surface (`u` around, `v` linear in the height over
    //! `[0, 3]`), an edge on the circle at height 1.2 given 1e-6 off the surface (a file's
    //! tolerance) and the source's pcurve the iso-line `v = 0.4`: the written pcurve is that
    //! line, restricted to the edge's vertices.
    use super::*;
    use crate::brep::{CurveKind, Edge, EdgeCurve, PCurve, Vertex};
    use crate::spline::construct::{Frame, arc, cylinder};

    fn model(lines: Vec<PCurveGeometry>) -> (Brep, NurbsSurface<f64, 3>) {
        let s = cylinder(&Frame::WORLD, 2.0, 0.0, 3.0).unwrap();
        let lift = Frame {
            o: [0.0, 0.0, 1.2 + 1e-6],
            ..Frame::WORLD
        };
        let c = arc(&lift, 2.0, 0.5, 2.0).unwrap();
        let (t0, t1) = c.hom.domain();
        let b = Brep {
            vertices: [t0, t1]
                .iter()
                .map(|t| Vertex {
                    source: String::new(),
                    point: c.eval(t),
                })
                .collect(),
            edges: vec![Edge {
                source: "#1".into(),
                start: 0,
                end: 1,
                curve: Some(EdgeCurve {
                    source: "#2".into(),
                    kind: CurveKind::Circle,
                    nurbs: c,
                    vertex_gap: 0.0,
                }),
                pcurves: lines
                    .into_iter()
                    .map(|g| PCurve {
                        source: "#3".into(),
                        surface_source: "#9".into(),
                        geometry: g,
                    })
                    .collect(),
            }],
            faces: vec![Face {
                source: "#8".into(),
                surface: Some(0),
                surface_source: "#9".into(),
                same_sense: true,
                loops: vec![],
            }],
            ..Brep::default()
        };
        (b, s)
    }

    fn line(v: f64) -> PCurveGeometry {
        PCurveGeometry::Line {
            origin: [0.0, v],
            direction: [1.0, 0.0],
        }
    }

    #[test]
    fn the_source_line_restricted_to_the_vertices() {
        for g in [
            line(0.4),
            // The same line as a B-spline over a wider range than the edge.
            PCurveGeometry::Nurbs(
                NurbsCurve::new(
                    vec![-1.0, -1.0, 2.0, 2.0],
                    1,
                    vec![[-1.0, 0.4], [2.0, 0.4]],
                    vec![1.0; 2],
                )
                .unwrap(),
            ),
        ] {
            let (b, s) = model(vec![g]);
            let p = source_pcurve(&b, 0, &b.faces[0], &s, 1e-5).expect("kept");
            assert!(p.points_weights().0.iter().all(|q| q[1] == 0.4));
            let (t0, t1) = p.hom.domain();
            for (t, v) in [(t0, 0), (t1, 1)] {
                let q = p.eval(&t);
                let d = dist(&s.eval(&q[0], &q[1]), &b.vertices[v].point);
                // The vertex lies 1e-6 above the line's image; its foot is found to rounding.
                assert!((d - 1e-6).abs() <= 1e-9, "end {v}: {d:e}");
            }
        }
    }

    #[test]
    fn a_pcurve_that_does_not_follow_the_edge_or_a_seam_pair_is_not_used() {
        let (b, s) = model(vec![line(0.6)]);
        assert!(source_pcurve(&b, 0, &b.faces[0], &s, 1e-5).is_none());
        let (b, s) = model(vec![line(0.4), line(0.4)]);
        assert!(source_pcurve(&b, 0, &b.faces[0], &s, 1e-5).is_none());
        let (b, s) = model(vec![]);
        assert!(source_pcurve(&b, 0, &b.faces[0], &s, 1e-5).is_none());
    }
}
