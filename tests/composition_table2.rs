//! Yang et al. (2008), Table 2 data: the quadratic domain curve (0.1,0.1),(0.5,1.8),(0.8,0.1)
//! on the biquadratic Bézier surface of the paper composes to a degree-8 curve with 9
//! control points that equals S(C(t)) exactly at 50 rational parameters. The same generic
//! code is run on every exact backend.

use vericad::geom::{Point, lift_point};
use vericad::model::{CurveGeometry, json};
use vericad::scalar::{Rational, Scalar, ratio};
use vericad::spline::compose::{compose, compose_line};
use vericad::spline::{BezierCurve, BezierSurface};

fn table2() -> (BezierSurface<[f64; 3]>, BezierCurve<[f64; 2]>) {
    let m = json::from_str(vericad::demo::DEFAULT_MODEL, "embedded").unwrap();
    let s = &m.surfaces[0].nurbs.hom;
    let surf =
        BezierSurface::new(2, 2, s.net.iter().map(|h| h.project().unwrap()).collect()).unwrap();
    let CurveGeometry::Domain(c) = &m.curves[0].geometry else {
        panic!("domain curve expected")
    };
    let curve =
        BezierCurve::new(c.hom.control.iter().map(|h| h.project().unwrap()).collect()).unwrap();
    (surf, curve)
}

fn check_backend<S: Scalar>() -> Vec<[S; 3]> {
    let (s, c) = table2();
    let sq = s.map(lift_point::<S, 3>);
    let cq = c.map(lift_point::<S, 2>);
    let r = compose(&sq, &cq);
    assert_eq!(r.degree(), 8);
    assert_eq!(r.control.len(), 9);
    for k in 0..50i64 {
        let t = S::from_i64(k) / S::from_i64(49);
        let uv = cq.eval(&t);
        assert_eq!(
            r.eval(&t),
            sq.eval(&uv[0], &uv[1]),
            "{} at t = {k}/49",
            S::NAME
        );
    }
    r.control
}

#[test]
fn table2_composition_is_exact_in_bigrational() {
    let cps = check_backend::<Rational>();
    // The end points are S at the curve's end points.
    let (s, c) = table2();
    let sq = s.map(lift_point::<Rational, 3>);
    let p0 = lift_point::<Rational, 2>(&c.control[0]);
    assert_eq!(cps[0], sq.eval(&p0[0], &p0[1]));
}

#[cfg(feature = "rug")]
#[test]
fn table2_composition_is_exact_in_rug_rational_and_agrees() {
    let a = check_backend::<rug::Rational>();
    let b = check_backend::<Rational>();
    for (x, y) in a.iter().zip(&b) {
        for i in 0..3 {
            assert_eq!(x[i].to_rational(), y[i]);
        }
    }
}

#[cfg(feature = "rug")]
#[test]
fn table2_composition_in_bigfloat_is_close_to_exact() {
    use vericad::scalar::rug_backend::BigFloat;
    let (s, c) = table2();
    let r = compose(
        &s.map(lift_point::<BigFloat<256>, 3>),
        &c.map(lift_point::<BigFloat<256>, 2>),
    );
    let e = check_backend::<Rational>();
    for (x, y) in r.control.iter().zip(&e) {
        for i in 0..3 {
            let d = Scalar::to_f64(&(x[i].to_rational() - y[i].clone()).abs());
            assert!(d < 1e-60, "{d}");
        }
    }
}

/// The chord case used by curve-on-surface: the segment's image (degree p+q = 4) from the
/// surface blossom equals the general composition and lies on S exactly.
#[test]
fn chord_images_lie_on_the_surface_exactly() {
    let (s, _) = table2();
    let sq = s.map(lift_point::<Rational, 3>);
    let (a, b) = (
        lift_point::<Rational, 2>(&[0.1, 0.1]),
        lift_point::<Rational, 2>(&[0.45, 0.9]),
    );
    let l = compose_line(&sq, &a, &b);
    assert_eq!(l.degree(), 4);
    for k in 0..50i64 {
        let t = ratio(k, 49);
        let uv = a.lerp(&b, &t);
        assert_eq!(l.eval(&t), sq.eval(&uv[0], &uv[1]));
    }
}
