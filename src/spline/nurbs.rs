//! Rational B-spline (NURBS) curves and surfaces as B-splines of homogeneous points
//! (The NURBS Book, §4.2–4.5): evaluation by projection, derivatives by the quotient
//! rule (eqs. 4.8, 4.20), normals.

use super::SplineError;
use super::bspline_curve::BSplineCurve;
use super::bspline_surface::BSplineSurface;
use crate::geom::{Hom, Point, cross};
use crate::scalar::{RealScalar, Scalar};

/// A NURBS curve in `D` dimensions.
#[derive(Clone, Debug, PartialEq)]
pub struct NurbsCurve<S: Scalar, const D: usize> {
    pub hom: BSplineCurve<Hom<S, D>>,
}

/// A NURBS surface in `D` dimensions.
#[derive(Clone, Debug, PartialEq)]
pub struct NurbsSurface<S: Scalar, const D: usize> {
    pub hom: BSplineSurface<Hom<S, D>>,
}

pub(crate) fn check_weights<S: Scalar>(w: &[S]) -> Result<(), SplineError> {
    for (i, wi) in w.iter().enumerate() {
        if !wi.to_f64().is_finite() {
            return Err(SplineError::NotFinite(format!(
                "weight {i} ({}) is not finite",
                wi.to_f64()
            )));
        }
        if wi.sign() != crate::scalar::Sign::Positive {
            return Err(SplineError::Weight { index: i });
        }
    }
    Ok(())
}

/// The homogeneous control points of a curve or surface are usable in `f64`: every
/// coordinate `p`, every `w·p` finite, and the differences of the coordinates (hodographs,
/// bounding boxes, distances between control points) finite. `at(k)` names control point `k`.
pub(crate) fn check_control<S: Scalar, const D: usize>(
    pts: &[[S; D]],
    hom: &[Hom<S, D>],
    at: impl Fn(usize) -> String,
) -> Result<(), SplineError> {
    const AXIS: [&str; 4] = ["x", "y", "z", "w"];
    let fmt = |v: &[S]| {
        v.iter()
            .map(|x| format!("{:e}", x.to_f64()))
            .collect::<Vec<_>>()
            .join(", ")
    };
    for (k, (p, h)) in pts.iter().zip(hom).enumerate() {
        if p.iter().any(|x| !x.to_f64().is_finite()) {
            return Err(SplineError::NotFinite(format!(
                "control point {} ({}) is not finite",
                at(k),
                fmt(p)
            )));
        }
        if h.wp.iter().any(|x| !x.to_f64().is_finite()) {
            return Err(SplineError::NotFinite(format!(
                "control point {}: weight × coordinate w·p = ({}) overflows (weight {:e}, point ({}))",
                at(k),
                fmt(&h.wp),
                h.w.to_f64(),
                fmt(p)
            )));
        }
    }
    for d in 0..D {
        for (what, vals) in [
            (
                "coordinate",
                pts.iter().map(|p| p[d].to_f64()).collect::<Vec<_>>(),
            ),
            ("w·p", hom.iter().map(|h| h.wp[d].to_f64()).collect()),
        ] {
            let lo = vals.iter().cloned().fold(f64::INFINITY, f64::min);
            let hi = vals.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
            if !vals.is_empty() && !(hi - lo).is_finite() {
                return Err(SplineError::NotFinite(format!(
                    "control points span {what} {} from {lo:e} to {hi:e}: their differences overflow f64",
                    AXIS[d.min(3)]
                )));
            }
        }
    }
    Ok(())
}

fn project<S: Scalar, const D: usize>(h: &Hom<S, D>) -> [S; D] {
    // Weights are validated positive and basis functions form a partition of unity,
    // so the interpolated weight is positive inside the domain.
    h.project().unwrap_or_else(|| h.wp.clone())
}

impl<S: Scalar, const D: usize> NurbsCurve<S, D> {
    /// From Cartesian control points and positive weights.
    pub fn new(
        knots: Vec<S>,
        degree: usize,
        pts: Vec<[S; D]>,
        weights: Vec<S>,
    ) -> Result<Self, SplineError> {
        if weights.len() != pts.len() {
            return Err(SplineError::NetSize {
                got: weights.len(),
                expected: pts.len(),
                what: "one weight per control point",
            });
        }
        check_weights(&weights)?;
        let h: Vec<Hom<S, D>> = pts
            .iter()
            .zip(&weights)
            .map(|(p, w)| Hom::from_point(p, w))
            .collect();
        check_control(&pts, &h, |k| k.to_string())?;
        Ok(NurbsCurve {
            hom: BSplineCurve::new(knots, degree, h)?,
        })
    }
    /// The same curve traversed the other way (see [`BSplineCurve::reversed`]).
    pub fn reversed(&self) -> Self {
        NurbsCurve {
            hom: self.hom.reversed(),
        }
    }
    /// Point at `t`.
    pub fn eval(&self, t: &S) -> [S; D] {
        project(&self.hom.eval(t))
    }
    /// First derivative: `C' = (A' - w' C) / w` (eq. 4.8).
    pub fn derivative_at(&self, t: &S) -> [S; D] {
        let h = self.hom.eval(t);
        let dh = self.hom.derivative_at(t);
        let c = project(&h);
        dh.wp.sub(&c.scale(&dh.w)).scale(&(S::one() / h.w))
    }
    /// First and second derivatives: `C'' = (A'' - 2 w' C' - w'' C) / w` (eq. 4.8 applied
    /// twice; A4.2 up to order 2). Returns `(C, C', C'')`.
    pub fn derivatives2_at(&self, t: &S) -> ([S; D], [S; D], [S; D]) {
        let span = self.hom.knots.find_span(t);
        let p = self.hom.degree();
        let ders = super::basis::ders_basis_funs(&self.hom.knots, span, t, 2);
        let mut a = [Hom::origin(), Hom::origin(), Hom::origin()];
        for (k, ak) in a.iter_mut().enumerate() {
            for j in 0..=p {
                *ak = ak.add(&self.hom.control[span - p + j].scale(&ders[k][j]));
            }
        }
        let inv = S::one() / a[0].w.clone();
        let c = a[0].wp.scale(&inv);
        let c1 = a[1].wp.sub(&c.scale(&a[1].w)).scale(&inv);
        let c2 = a[2]
            .wp
            .sub(&c1.scale(&(S::from_i64(2) * a[1].w.clone())))
            .sub(&c.scale(&a[2].w))
            .scale(&inv);
        (c, c1, c2)
    }
    /// Control points and weights.
    pub fn points_weights(&self) -> (Vec<[S; D]>, Vec<S>) {
        self.hom
            .control
            .iter()
            .map(|h| (project(h), h.w.clone()))
            .unzip()
    }
    /// `self` followed by `next` (same degree, both clamped), one curve on `self`'s domain
    /// extended by `next`'s length, C0 at the joint (a knot of multiplicity p). `next`'s
    /// homogeneous points are scaled so that its first weight equals `self`'s last (the same
    /// curve), and its first point is replaced by `self`'s last: the caller asserts the two
    /// ends meet (for a closed curve cut in two and put back the other way round, they are
    /// the curve's own end points); the result's point there is `self`'s end.
    pub fn joined(&self, next: &Self) -> Result<Self, SplineError> {
        let p = self.hom.degree();
        if next.hom.degree() != p {
            return Err(SplineError::Invalid(format!(
                "joining curves of degrees {p} and {}",
                next.hom.degree()
            )));
        }
        let (_, e1) = self.hom.domain();
        let (s2, _) = next.hom.domain();
        let (Some(last), Some(first)) = (self.hom.control.last(), next.hom.control.first()) else {
            return Err(SplineError::Invalid("joining an empty curve".into()));
        };
        let scale = last.w.clone() / first.w.clone();
        let k1 = self.hom.knots.knots();
        let k2 = next.hom.knots.knots();
        let mut knots: Vec<S> = k1[..k1.len() - 1].to_vec();
        // Shifted onto `self`'s end; not at all when `next` starts there (so its knots stay
        // exactly as they are).
        if s2 == e1 {
            knots.extend(k2[p + 1..].iter().cloned());
        } else {
            knots.extend(
                k2[p + 1..]
                    .iter()
                    .map(|t| t.clone() - s2.clone() + e1.clone()),
            );
        }
        let mut control = self.hom.control.clone();
        control.extend(next.hom.control[1..].iter().map(|h| h.scale(&scale)));
        Ok(NurbsCurve {
            hom: BSplineCurve::new(knots, p, control)?,
        })
    }
}

impl<const D: usize> NurbsCurve<f64, D> {
    /// [`NurbsCurve::derivatives2_at`] in `f64` without allocating (the same operations in
    /// the same order, so the same numbers; degrees of 16 and more take the general path).
    pub fn derivatives2_f64(&self, t: f64) -> ([f64; D], [f64; D], [f64; D]) {
        let span = self.hom.knots.find_span(&t);
        let p = self.hom.degree();
        let Some(ders) = super::basis::ders2_f64(&self.hom.knots, span, t) else {
            return self.derivatives2_at(&t);
        };
        let mut a = [Hom::origin(), Hom::origin(), Hom::origin()];
        for (k, ak) in a.iter_mut().enumerate() {
            for j in 0..=p {
                *ak = ak.add(&self.hom.control[span - p + j].scale(&ders[k][j]));
            }
        }
        let inv = 1.0 / a[0].w;
        let c = a[0].wp.scale(&inv);
        let c1 = a[1].wp.sub(&c.scale(&a[1].w)).scale(&inv);
        let c2 = a[2]
            .wp
            .sub(&c1.scale(&(2.0 * a[1].w)))
            .sub(&c.scale(&a[2].w))
            .scale(&inv);
        (c, c1, c2)
    }
}

impl<S: Scalar, const D: usize> NurbsSurface<S, D> {
    /// From a row-major Cartesian net and positive weights.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        knots_u: Vec<S>,
        deg_u: usize,
        knots_v: Vec<S>,
        deg_v: usize,
        nu: usize,
        nv: usize,
        pts: Vec<[S; D]>,
        weights: Vec<S>,
    ) -> Result<Self, SplineError> {
        if weights.len() != pts.len() {
            return Err(SplineError::NetSize {
                got: weights.len(),
                expected: pts.len(),
                what: "one weight per control point",
            });
        }
        check_weights(&weights)?;
        let h: Vec<Hom<S, D>> = pts
            .iter()
            .zip(&weights)
            .map(|(p, w)| Hom::from_point(p, w))
            .collect();
        if nv > 0 {
            check_control(&pts, &h, |k| format!("[{}][{}]", k / nv, k % nv))?;
        }
        Ok(NurbsSurface {
            hom: BSplineSurface::new(knots_u, deg_u, knots_v, deg_v, nu, nv, h)?,
        })
    }
    /// A polynomial surface as a NURBS surface with unit weights.
    pub fn from_polynomial(s: &BSplineSurface<[S; D]>) -> Self {
        NurbsSurface {
            hom: s.map(|k| k.clone(), |p| Hom::from_point(p, &S::one())),
        }
    }
    /// Point at `(u, v)`.
    pub fn eval(&self, u: &S, v: &S) -> [S; D] {
        project(&self.hom.eval(u, v))
    }
    /// `S`, `S_u`, `S_v`, `S_uu`, `S_uv`, `S_vv` at `(u, v)` by the rational quotient rule
    /// (The NURBS Book eq. 4.20 / A4.4, up to second order).
    pub fn derivatives2(&self, u: &S, v: &S) -> [[S; D]; 6] {
        let a = self.hom.derivatives(u, v, 2);
        let w = |k: usize, l: usize| a[k][l].w.clone();
        let aw = |k: usize, l: usize| a[k][l].wp.clone();
        let inv = S::one() / w(0, 0);
        let s = aw(0, 0).scale(&inv);
        let su = aw(1, 0).sub(&s.scale(&w(1, 0))).scale(&inv);
        let sv = aw(0, 1).sub(&s.scale(&w(0, 1))).scale(&inv);
        let two = S::from_i64(2);
        let suu = aw(2, 0)
            .sub(&su.scale(&(two.clone() * w(1, 0))))
            .sub(&s.scale(&w(2, 0)))
            .scale(&inv);
        let svv = aw(0, 2)
            .sub(&sv.scale(&(two * w(0, 1))))
            .sub(&s.scale(&w(0, 2)))
            .scale(&inv);
        let suv = aw(1, 1)
            .sub(&su.scale(&w(0, 1)))
            .sub(&sv.scale(&w(1, 0)))
            .sub(&s.scale(&w(1, 1)))
            .scale(&inv);
        [s, su, sv, suu, suv, svv]
    }
    /// Control points and weights, row-major.
    pub fn points_weights(&self) -> (Vec<[S; D]>, Vec<S>) {
        self.hom
            .net
            .iter()
            .map(|h| (project(h), h.w.clone()))
            .unzip()
    }
    /// Whether every weight equals the first (then the surface is polynomial).
    pub fn is_polynomial(&self) -> bool {
        let w0 = &self.hom.net[0].w;
        self.hom.net.iter().all(|h| h.w == *w0)
    }
}

impl<S: Scalar> NurbsSurface<S, 3> {
    /// Unnormalized normal `S_u × S_v` (exact in exact arithmetic), from the first
    /// derivatives only (quotient rule, The NURBS Book eq. 4.20).
    pub fn normal(&self, u: &S, v: &S) -> [S; 3] {
        let a = self.hom.derivatives(u, v, 1);
        let inv = S::one() / a[0][0].w.clone();
        let s = a[0][0].wp.scale(&inv);
        let su = a[1][0].wp.sub(&s.scale(&a[1][0].w)).scale(&inv);
        let sv = a[0][1].wp.sub(&s.scale(&a[0][1].w)).scale(&inv);
        cross(&su, &sv)
    }
}

impl<S: RealScalar> NurbsSurface<S, 3> {
    /// Unit normal; `None` where `S_u × S_v` vanishes (degenerate point).
    pub fn unit_normal(&self, u: &S, v: &S) -> Option<[S; 3]> {
        let n = self.normal(u, v);
        let l = crate::geom::norm(&n);
        if l.is_zero() {
            None
        } else {
            Some(n.scale(&(S::one() / l)))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::norm2;
    use crate::scalar::{Rational, ratio};
    type Q = Rational;
    fn q(x: f64) -> Q {
        crate::scalar::lift(x)
    }

    /// Quadratic rational arc with control (1,0),(1,1),(0,1) and weights (1,1,2): its
    /// homogeneous form is ((1-t²), 2t, 1+t²), the rational parametrization of the unit
    /// circle. Every point must lie on the circle exactly.
    #[test]
    fn rational_quadratic_circle_is_exact() {
        let c = NurbsCurve::<Q, 2>::new(
            [0., 0., 0., 1., 1., 1.].iter().map(|&x| q(x)).collect(),
            2,
            vec![[q(1.), q(0.)], [q(1.), q(1.)], [q(0.), q(1.)]],
            vec![q(1.), q(1.), q(2.)],
        )
        .unwrap();
        for i in 0..=64 {
            let t = ratio(i, 64);
            let p = c.eval(&t);
            assert_eq!(norm2(&p), q(1.0), "point {i} off the circle");
            // On a circle: C·C' = 0 and C·C'' = -|C'|² (differentiate |C|² = 1 twice).
            let (c0, c1, c2) = c.derivatives2_at(&t);
            assert_eq!(crate::geom::dot(&c0, &c1), q(0.0));
            assert_eq!(crate::geom::dot(&c0, &c2), -norm2(&c1));
        }
    }

    /// Upper unit semicircle as a rational cubic: control (1,0),(1,2),(-1,2),(-1,0),
    /// weights (1, 1/3, 1/3, 1) (Piegl & Tiller, §7.5).
    #[test]
    fn rational_cubic_semicircle_is_exact() {
        let third = ratio(1, 3);
        let c = NurbsCurve::<Q, 2>::new(
            [0., 0., 0., 0., 1., 1., 1., 1.]
                .iter()
                .map(|&x| q(x))
                .collect(),
            3,
            vec![
                [q(1.), q(0.)],
                [q(1.), q(2.)],
                [q(-1.), q(2.)],
                [q(-1.), q(0.)],
            ],
            vec![q(1.), third.clone(), third, q(1.)],
        )
        .unwrap();
        for i in 0..=50 {
            let p = c.eval(&ratio(i, 50));
            assert_eq!(norm2(&p), q(1.0), "point {i} off the circle");
        }
    }

    /// Rational sphere patch: the surface of revolution of the quadratic circle arc
    /// (a meridian from the pole to the equator) about the z axis, by the same exact
    /// rational quarter circle. Tensor product of two rational quadratics with rational
    /// weights; every point lies on the unit sphere exactly.
    #[test]
    fn rational_sphere_patch_is_exact() {
        // Meridian in the (r, z) plane: r = 2t/(1+t²), z = (1-t²)/(1+t²): control
        // (0,1),(1,1),(1,0), weights (1,1,2) — from the pole (t=0) to the equator (t=1).
        let mer = [([0., 1.], 1.), ([1., 1.], 1.), ([1., 0.], 2.)];
        // Parallel circle of radius 1: (x, y) = ((1-s²), 2s)/(1+s²).
        let par = [([1., 0.], 1.), ([1., 1.], 1.), ([0., 1.], 2.)];
        let mut pts = Vec::new();
        let mut ws = Vec::new();
        for (rz, wm) in mer {
            for (xy, wp) in par {
                pts.push([q(rz[0] * xy[0]), q(rz[0] * xy[1]), q(rz[1])]);
                ws.push(q(wm * wp));
            }
        }
        let k: Vec<Q> = [0., 0., 0., 1., 1., 1.].iter().map(|&x| q(x)).collect();
        let s = NurbsSurface::<Q, 3>::new(k.clone(), 2, k, 2, 3, 3, pts, ws).unwrap();
        for i in 0..=12 {
            for j in 0..=12 {
                let p = s.eval(&ratio(i, 12), &ratio(j, 12));
                assert_eq!(norm2(&p), q(1.0), "({i},{j}) off the sphere");
            }
        }
        // The normal is radial: n × p = 0 exactly.
        let (u, v) = (ratio(1, 3), ratio(2, 7));
        let n = s.normal(&u, &v);
        let p = s.eval(&u, &v);
        assert_eq!(cross(&n, &p), [q(0.), q(0.), q(0.)]);
    }

    #[test]
    fn reversed_curve_runs_backwards_over_the_same_domain() {
        // A rational quadratic with interior knots on [1, 4]: C'(t) = C(5 - t), exactly in
        // rationals (the mirrored knots are exact), to rounding in f64.
        let knots = vec![1.0, 1.0, 1.0, 2.0, 3.5, 4.0, 4.0, 4.0];
        let pts = vec![[0.0, 0.0], [1.0, 2.0], [3.0, 1.0], [4.0, 3.0], [6.0, 0.5]];
        let w = vec![1.0, 0.5, 2.0, 0.75, 1.0];
        let c = NurbsCurve::new(knots, 2, pts, w).unwrap();
        let r = c.reversed();
        assert_eq!(r.hom.domain(), (1.0, 4.0));
        for i in 0..=30 {
            let t = 1.0 + 3.0 * i as f64 / 30.0;
            let (a, b) = (r.eval(&t), c.eval(&(5.0 - t)));
            assert!(
                (a[0] - b[0]).abs() < 1e-14 && (a[1] - b[1]).abs() < 1e-14,
                "{t}"
            );
        }
        let q: NurbsCurve<crate::scalar::Rational, 2> = NurbsCurve {
            hom: c.hom.map(
                |k| crate::scalar::lift(*k),
                |h| crate::geom::Hom {
                    wp: h.wp.map(crate::scalar::lift),
                    w: crate::scalar::lift(h.w),
                },
            ),
        };
        let rq = q.reversed();
        let t = crate::scalar::lift::<crate::scalar::Rational>(1.3);
        let five = crate::scalar::lift::<crate::scalar::Rational>(5.0);
        assert_eq!(rq.eval(&t), q.eval(&(five - t.clone())));
    }
}
