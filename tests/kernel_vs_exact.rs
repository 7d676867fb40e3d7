//! Differential property tests: each f64 kernel routine against the same generic code run
//! on Rational (inputs lifted exactly), within a stated forward error bound.
//!
//! Bounds, with `u = 2^-53` the unit roundoff and `M` the largest control-point coordinate
//! magnitude (the Euclidean-free, per-coordinate form):
//! * de Casteljau, degree `n` (each level is `a + t (b - a)` with `t ∈ [0,1]`: three rounded
//!   operations whose errors are bounded by `u` times a quantity ≤ `2M`):  `|e| ≤ 6 n u M`;
//! * B-spline evaluation by basis functions (A2.2: each basis value carries a relative
//!   error ≤ `3p u`, then `p+1` products and sums): `|e| ≤ 8 (p + 1) u M` per direction;
//! * knot insertion: a sequence of `r` affine combinations with weights in `[0,1]`:
//!   `|e| ≤ 6 r u M`;
//! * rational evaluation multiplies the bound by `w_max / w_min` (the homogeneous sum is
//!   divided by the interpolated weight).
//!
//! These are first-order bounds (terms in `u²` are negligible at these degrees); the tests
//! check them on random, non-uniform data.

use proptest::prelude::*;
use vericad::geom::{Hom, Point, lift_point};
use vericad::scalar::{Rational, Scalar, lift};
use vericad::spline::compose::compose;
use vericad::spline::{BSplineCurve, BSplineSurface, BezierCurve, BezierSurface};

const U: f64 = f64::EPSILON / 2.0;

fn maxerr<const D: usize>(a: &[f64; D], e: &[Rational; D]) -> f64 {
    (0..D)
        .map(|i| Scalar::to_f64(&(lift::<Rational>(a[i]) - e[i].clone()).abs()))
        .fold(0.0, f64::max)
}

fn mag<const D: usize>(pts: &[[f64; D]]) -> f64 {
    pts.iter()
        .flat_map(|p| p.iter())
        .map(|x| x.abs())
        .fold(0.0, f64::max)
}

fn knots_strategy(p: usize, n: usize) -> impl Strategy<Value = Vec<f64>> {
    // n - p - 1 interior knots, random and unsorted, on a random interval [a, a + len].
    (
        proptest::collection::vec(0.0f64..1.0, n - p - 1),
        -5.0f64..5.0,
        0.1f64..20.0,
    )
        .prop_map(move |(mut inner, a, len)| {
            inner.sort_by(|x, y| x.partial_cmp(y).unwrap());
            let mut k = vec![a; p + 1];
            k.extend(inner.iter().map(|x| a + x * len));
            k.extend(vec![a + len; p + 1]);
            k
        })
}

fn curve_case() -> impl Strategy<Value = (usize, Vec<f64>, Vec<[f64; 3]>, f64)> {
    (1usize..=5, 0usize..6).prop_flat_map(|(p, extra)| {
        let n = p + 1 + extra;
        (
            Just(p),
            knots_strategy(p, n),
            proptest::collection::vec(proptest::array::uniform3(-100.0f64..100.0), n),
            0.0f64..1.0,
        )
    })
}

fn valid_knots(k: &[f64], p: usize, n: usize) -> bool {
    vericad::spline::KnotVector::new(k.to_vec(), p, n).is_ok()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]

    #[test]
    fn bspline_curve_eval_within_bound((p, k, pts, s) in curve_case()) {
        prop_assume!(valid_knots(&k, p, pts.len()));
        let c = BSplineCurve::new(k.clone(), p, pts.clone()).unwrap();
        let q = c.map(|x| lift::<Rational>(*x), lift_point);
        let (a, b) = c.domain();
        let t = a + s * (b - a);
        let e = q.eval(&lift(t));
        let bound = 8.0 * (p + 1) as f64 * U * mag(&pts);
        prop_assert!(maxerr(&c.eval(&t), &e) <= bound);
    }

    #[test]
    fn knot_insertion_within_bound((p, k, pts, s) in curve_case(), r in 1usize..4) {
        prop_assume!(valid_knots(&k, p, pts.len()));
        let c = BSplineCurve::new(k.clone(), p, pts.clone()).unwrap();
        let q = c.map(|x| lift::<Rational>(*x), lift_point);
        let (a, b) = c.domain();
        let t = a + s * (b - a);
        let cf = c.insert_knot(&t, r);
        let cq = q.insert_knot(&lift(t), r);
        prop_assert_eq!(cf.control.len(), cq.control.len());
        let bound = 6.0 * r as f64 * U * mag(&pts);
        for (x, e) in cf.control.iter().zip(&cq.control) {
            prop_assert!(maxerr(x, e) <= bound);
        }
    }

    #[test]
    fn bezier_eval_and_subdivision_within_bound(
        pts in proptest::collection::vec(proptest::array::uniform2(-100.0f64..100.0), 2..10),
        t in 0.0f64..1.0,
    ) {
        let c = BezierCurve::new(pts.clone()).unwrap();
        let q = c.map(lift_point::<Rational, 2>);
        let n = c.degree() as f64;
        let bound = 6.0 * n * U * mag(&pts);
        prop_assert!(maxerr(&c.eval(&t), &q.eval(&lift(t))) <= bound);
        let (l, r) = c.subdivide(&t);
        let (lq, rq) = q.subdivide(&lift(t));
        for (x, e) in l.control.iter().chain(&r.control).zip(lq.control.iter().chain(&rq.control)) {
            prop_assert!(maxerr(x, e) <= bound);
        }
    }

    #[test]
    fn surface_eval_and_derivatives_within_bound(
        (p, ku, rows, _) in curve_case(),
        (q, kv, cols, _) in curve_case(),
        s in 0.0f64..1.0, t in 0.0f64..1.0,
    ) {
        let (nu, nv) = (rows.len(), cols.len());
        prop_assume!(valid_knots(&ku, p, nu) && valid_knots(&kv, q, nv));
        // A net from the two random point lists (outer sum), non-trivial in every coordinate.
        let net: Vec<[f64; 3]> = (0..nu * nv).map(|k| rows[k / nv].add(&cols[k % nv])).collect();
        let sf = BSplineSurface::new(ku, p, kv, q, nu, nv, net.clone()).unwrap();
        let sq = sf.map(|x| lift::<Rational>(*x), lift_point);
        let (u0, u1, v0, v1) = sf.domain();
        let (u, v) = (u0 + s * (u1 - u0), v0 + t * (v1 - v0));
        let bound = 8.0 * (p + q + 2) as f64 * U * mag(&net);
        prop_assert!(maxerr(&sf.eval(&u, &v), &sq.eval(&lift(u), &lift(v))) <= bound);
        // First derivatives: bounded relative to the exact derivative net's magnitude.
        let d = sf.derivatives(&u, &v, 1);
        let dq = sq.derivatives(&lift(u), &lift(v), 1);
        for (k, l) in [(1, 0), (0, 1)] {
            let exact_mag = dq[k][l].iter().map(|x| Scalar::to_f64(&x.abs())).fold(0.0, f64::max);
            // A derivative scales control differences by p / (knot span): bound them by the
            // derivative spline's own control net, computed exactly.
            let dnet = if k == 1 { sq.derivative_u() } else { sq.derivative_v() };
            let dm = dnet.map(|s| s.net.iter().flat_map(|p| p.iter()).map(|x| Scalar::to_f64(&x.abs())).fold(0.0, f64::max)).unwrap_or(exact_mag);
            let dbound = 16.0 * (p + q + 2) as f64 * U * dm.max(mag(&net));
            prop_assert!(maxerr(&d[k][l], &dq[k][l]) <= dbound, "d{k}{l}");
        }
    }

    #[test]
    fn rational_surface_eval_within_bound(
        ws in proptest::collection::vec(0.25f64..4.0, 9),
        pts in proptest::collection::vec(proptest::array::uniform3(-10.0f64..10.0), 9),
        s in 0.0f64..1.0, t in 0.0f64..1.0,
    ) {
        let k = vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0];
        let sf = vericad::spline::NurbsSurface::new(k.clone(), 2, k, 2, 3, 3, pts.clone(), ws.clone()).unwrap();
        let sq = vericad::spline::NurbsSurface { hom: sf.hom.map(|x| lift::<Rational>(*x), |h| Hom { wp: lift_point(&h.wp), w: lift(h.w) }) };
        let wr = ws.iter().cloned().fold(0.0, f64::max) / ws.iter().cloned().fold(f64::INFINITY, f64::min);
        let bound = 8.0 * 6.0 * U * mag(&pts) * wr * 4.0;
        prop_assert!(maxerr(&sf.eval(&s, &t), &sq.eval(&lift(s), &lift(t))) <= bound);
    }

    #[test]
    fn composition_within_bound(
        net in proptest::collection::vec(proptest::array::uniform3(-10.0f64..10.0), 9),
        curve in proptest::collection::vec(proptest::array::uniform2(0.0f64..1.0), 2..5),
    ) {
        let s = BezierSurface::new(2, 2, net.clone()).unwrap();
        let c = BezierCurve::new(curve.clone()).unwrap();
        let f = compose(&s, &c);
        let e = compose(&s.map(lift_point::<Rational, 3>), &c.map(lift_point::<Rational, 2>));
        // Each control point is a sum of net points times products of Bernstein products of
        // degree (p+q)d: bound 16 (p+q) d u M · (number of net points).
        let d = c.degree() as f64;
        let bound = 16.0 * 4.0 * d * U * mag(&net) * 9.0;
        for (x, y) in f.control.iter().zip(&e.control) {
            prop_assert!(maxerr(x, y) <= bound);
        }
    }
}
