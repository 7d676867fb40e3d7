//! Step 9a — the point certificate: for every output point `x` with parameters `(u, v)` on a
//! surface `S`, a proven upper bound on `||x - S(u, v)||`.
//!
//! Fast path: `S(u, v)` is enclosed by [`super::enclose`] (Cox–de Boor basis, The NURBS Book
//! A2.2, in outward-rounded interval arithmetic; the homogeneous sum in `f64` with a forward
//! error bound, or in intervals where that refuses; then the quotient), which encloses the
//! exact value; `||x - S||` is bounded above from the enclosure with upward rounding. Reference path
//! (used when an interval division straddles zero, and on request): `x`, `u`, `v` and the
//! control net are `f64`, so they lift exactly into rationals; `S(u, v)` is evaluated exactly,
//! `||x - S(u,v)||²` is an exact rational `q`, and the bound is the smallest `f64` found whose
//! square is proven `>= q`. Both are rigorous; nothing is sampled: the bound holds for the
//! stated parameters (and bounds the distance to the surface, as `S(u, v)` lies on it).

use super::enclose::enclose_point;
use crate::geom::{Point, lift_point};
use crate::scalar::{Interval, Rational, sqrt_upper};
use crate::spline::NurbsSurface;
use crate::spline::exact_point::{ExactEvaluator, ExactPoint};

/// A surface with its exact evaluator (knots lifted into rationals once).
pub struct ExactSurface {
    f: NurbsSurface<f64, 3>,
    /// Fraction-free exact points ([`ExactEvaluator`]).
    ev: Option<ExactEvaluator>,
    /// Skip the interval path (reference answers only).
    pub exact_only: bool,
}

/// Upper bound on `||x - S(u, v)||` by interval evaluation; `None` if inconclusive.
fn interval_bound(s: &NurbsSurface<f64, 3>, x: &[f64; 3], uv: &[f64; 2]) -> Option<f64> {
    let sk = enclose_point(s, Interval::point(uv[0]), Interval::point(uv[1]))?;
    distance_upper(x, &sk)
}

/// Upper bound (rounded upward) on `sup ||x - q||` over the points `q` of the box `b`;
/// `None` if not finite.
pub fn distance_upper(x: &[f64; 3], b: &[Interval; 3]) -> Option<f64> {
    let mut d2 = 0.0f64;
    for k in 0..3 {
        let dk = Interval::point(x[k]) - b[k];
        let m = dk.mag();
        d2 = (d2 + (m * m).next_up()).next_up();
    }
    let r = d2.sqrt().next_up();
    r.is_finite().then_some(r)
}

impl ExactSurface {
    pub fn new(s: &NurbsSurface<f64, 3>) -> ExactSurface {
        ExactSurface {
            f: s.clone(),
            ev: ExactEvaluator::new(s),
            exact_only: false,
        }
    }

    /// Proven upper bound on `||x - S(u, v)||`; `None` when an input is not finite or the
    /// parameters lie outside the domain.
    pub fn distance_bound(&self, x: &[f64; 3], uv: &[f64; 2]) -> Option<f64> {
        if !x.iter().chain(uv).all(|c| c.is_finite()) {
            return None;
        }
        let (u0, u1, v0, v1) = self.f.hom.domain();
        if uv[0] < u0 || uv[0] > u1 || uv[1] < v0 || uv[1] > v1 {
            return None;
        }
        if !self.exact_only
            && let Some(b) = interval_bound(&self.f, x, uv)
        {
            return Some(b);
        }
        let p = self.exact_point(uv)?.rational();
        let d = lift_point::<Rational, 3>(x).sub(&p);
        let q = crate::geom::dot(&d, &d);
        Some(sqrt_upper(&q))
    }
}

impl ExactSurface {
    /// `S(u, v)` exactly (the parameters are finite `f64` values, taken exactly; `None`
    /// outside the domain, or for a weight sum of 0 — refused for the surfaces used).
    pub fn exact_point(&self, uv: &[f64; 2]) -> Option<ExactPoint> {
        self.ev.as_ref()?.point(uv[0], uv[1])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spline::construct::{Frame, torus};

    /// The interval bound is never below the exact distance, and close to it.
    #[test]
    fn interval_bound_encloses_exact_distance() {
        let f = Frame {
            o: [0.1, -0.2, 0.3],
            x: [1.0, 0.0, 0.0],
            y: [0.0, 1.0, 0.0],
            z: [0.0, 0.0, 1.0],
        };
        let s = torus(&f, 2.0, 0.7).unwrap();
        let mut e = ExactSurface::new(&s);
        for i in 0..40 {
            let uv = [i as f64 / 39.0, (i * 7 % 40) as f64 / 39.0];
            let p = s.eval(&uv[0], &uv[1]);
            let x = [p[0] + 1e-9 * i as f64, p[1], p[2] - 3e-10];
            e.exact_only = true;
            let exact = e.distance_bound(&x, &uv).unwrap();
            e.exact_only = false;
            let fast = e.distance_bound(&x, &uv).unwrap();
            assert!(fast >= exact * (1.0 - 1e-15), "{i}: {fast} < {exact}");
            assert!(fast <= exact + 1e-13, "{i}: {fast} vs {exact}");
        }
    }
}
