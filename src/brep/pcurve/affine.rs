//! Exact pcurves on planar patches, for the writers. A surface of degree (1, 1) with 2 × 2
//! control points of equal weight forming a parallelogram (how planes are held) is an affine
//! map `S(u, v) = O + s·A + t·B` with `s`, `t` the parameters scaled to `[0, 1]`; its inverse
//! maps an edge's NURBS curve lying in the plane to its pcurve exactly: the same knots and
//! weights, each control point mapped to `(u, v)`. Other readers then need not project the
//! edge onto the surface (Open CASCADE's projection of circles onto B-spline planes changes
//! trimmed areas by up to 3e-5).

use crate::geom::{Point, dot};
use crate::spline::{NurbsCurve, NurbsSurface};

/// The inverse of a planar patch's affine parametrization.
pub struct AffinePatch {
    o: [f64; 3],
    a: [f64; 3],
    b: [f64; 3],
    /// Inverse of the Gram matrix of `a`, `b`.
    inv: [[f64; 2]; 2],
    domain: (f64, f64, f64, f64),
    /// Largest distance from the plane accepted for a curve's control points.
    tolerance: f64,
}

impl AffinePatch {
    /// The patch's inverse, when `s` is a parallelogram patch (`None` otherwise). A curve's
    /// control points may lie 1e-9 times the patch's extent (with its distance from the
    /// origin) from the plane: rounding, not an approximation.
    pub fn new(s: &NurbsSurface<f64, 3>) -> Option<AffinePatch> {
        let h = &s.hom;
        if h.degrees() != (1, 1) || h.nu() != 2 || h.nv() != 2 || !s.is_polynomial() {
            return None;
        }
        let (p, _) = s.points_weights();
        let (o, a, b) = (p[0], p[2].sub(&p[0]), p[1].sub(&p[0]));
        // Row-major net: p[0] = P00, p[1] = P01 (v), p[2] = P10 (u), p[3] = P11.
        let size = dot(&a, &a).sqrt().max(dot(&b, &b).sqrt());
        let skew = p[3].sub(&p[2]).sub(&b);
        if dot(&skew, &skew).sqrt() > 1e-12 * size {
            return None;
        }
        let (aa, ab, bb) = (dot(&a, &a), dot(&a, &b), dot(&b, &b));
        let det = aa * bb - ab * ab;
        if !(det > 0.0 && det.is_finite()) || det <= 1e-20 * aa * bb {
            return None;
        }
        Some(AffinePatch {
            o,
            a,
            b,
            inv: [[bb / det, -ab / det], [-ab / det, aa / det]],
            domain: h.domain(),
            tolerance: 1e-9 * (size + dot(&o, &o).sqrt()),
        })
    }

    /// `(u, v)` of point `x` (its foot on the plane) and its distance from the plane.
    fn uv(&self, x: &[f64; 3]) -> ([f64; 2], f64) {
        let d = x.sub(&self.o);
        let (da, db) = (dot(&d, &self.a), dot(&d, &self.b));
        let s = self.inv[0][0] * da + self.inv[0][1] * db;
        let t = self.inv[1][0] * da + self.inv[1][1] * db;
        let foot = self.o.add(&self.a.scale(&s)).add(&self.b.scale(&t));
        let off = x.sub(&foot);
        let (u0, u1, v0, v1) = self.domain;
        (
            [u0 + s * (u1 - u0), v0 + t * (v1 - v0)],
            dot(&off, &off).sqrt(),
        )
    }

    /// The pcurve of a curve lying in the plane (`None` when a control point is farther from
    /// the plane than the tolerance).
    pub fn pcurve(&self, c: &NurbsCurve<f64, 3>) -> Option<NurbsCurve<f64, 2>> {
        let (pts, w) = c.points_weights();
        let mut uv = Vec::with_capacity(pts.len());
        for p in &pts {
            let (q, off) = self.uv(p);
            if off > self.tolerance || !q.iter().all(|x| x.is_finite()) {
                return None;
            }
            uv.push(q);
        }
        NurbsCurve::new(c.hom.knots.knots().to_vec(), c.hom.degree(), uv, w).ok()
    }
}
