//! Oracles from the construction: a straight line lifted off a plane by a known height (the
//! Hausdorff distance is that height), and circles on a sphere, whose distance from any point
//! has a closed form (measured on the composed curve, not by nearest sample).

use super::*;
use crate::geom::{Point, cross, dot};
use crate::spline::construct::{Frame, arc, bilinear, sphere};
use crate::spline::interpolate::interpolate_with_parameters;
use crate::spline::project::project;
use crate::spline::scaled_bernstein::{mul, scaled, unscaled};

fn line2(a: [f64; 2], b: [f64; 2]) -> NurbsCurve<f64, 2> {
    NurbsCurve::new(vec![0.0, 0.0, 1.0, 1.0], 1, vec![a, b], vec![1.0; 2]).unwrap()
}

fn plane() -> NurbsSurface<f64, 3> {
    bilinear(
        [0.0, 0.0, 0.0],
        [10.0, 0.0, 0.0],
        [0.0, 10.0, 0.0],
        [10.0, 10.0, 0.0],
    )
    .unwrap()
}

#[test]
fn a_lifted_line_is_bounded_by_its_height_and_not_below_it() {
    let s = plane();
    let cells = SurfaceCells::new(&s).unwrap();
    let p = line2([0.1, 0.2], [0.8, 0.9]);
    for delta in [0.0, 1e-9, 3e-4, 0.5] {
        let a = s.eval(&0.1, &0.2).add(&[0.0, 0.0, delta]);
        let b = s.eval(&0.8, &0.9).add(&[0.0, 0.0, delta]);
        let c = NurbsCurve::new(vec![2.0, 2.0, 5.0, 5.0], 1, vec![a, b], vec![1.0; 2]).unwrap();
        let r = cells.bound(&p, &c, (2.0, 5.0), 1e-12).unwrap();
        assert!(r >= delta, "bound {r} below the true distance {delta}");
        assert!(r <= delta * (1.0 + 1e-12) + 1e-13, "bound {r} for {delta}");
    }
}

#[test]
fn a_pcurve_leaving_the_domain_or_of_too_high_degree_is_refused() {
    let s = plane();
    let cells = SurfaceCells::new(&s).unwrap();
    let p = line2([0.5, 0.5], [1.2, 0.5]);
    let c = NurbsCurve::new(
        vec![0.0, 0.0, 1.0, 1.0],
        1,
        vec![[5.0, 5.0, 0.0], [12.0, 5.0, 0.0]],
        vec![1.0; 2],
    )
    .unwrap();
    assert!(matches!(
        cells.bound(&p, &c, (0.0, 1.0), 1e-9),
        Err(Unproven::OffDomain { .. })
    ));
    // Degree 29 on a bilinear patch: (1 + 1)·29 + 1 = 59 > 56.
    let n = 30;
    let mut k = vec![0.0; n];
    k.extend(vec![1.0; n]);
    let pts: Vec<[f64; 2]> = (0..n).map(|i| [0.2 + 0.01 * i as f64, 0.5]).collect();
    let high = NurbsCurve::new(k, n - 1, pts, vec![1.0; n]).unwrap();
    assert_eq!(
        cells.bound(&high, &c, (0.0, 1.0), 1e-9),
        Err(Unproven::Degree(59))
    );
}

/// The distance from `x` to the circle of centre `o`, unit normal `n` and radius `rho`.
fn to_circle(x: &[f64; 3], o: &[f64; 3], n: &[f64; 3], rho: f64) -> f64 {
    let d = x.sub(o);
    let h = dot(&d, n);
    let radial = d.sub(&n.scale(&h));
    ((dot(&radial, &radial).sqrt() - rho).powi(2) + h * h).sqrt()
}

/// A cubic pcurve through the projections of `c` at `m` parameters spread evenly over its
/// domain (how the writers make them).
fn projected(s: &NurbsSurface<f64, 3>, c: &NurbsCurve<f64, 3>, m: usize) -> NurbsCurve<f64, 2> {
    let (t0, t1) = c.hom.domain();
    let f: Vec<f64> = (0..m).map(|i| i as f64 / (m - 1) as f64).collect();
    let uv: Vec<[f64; 2]> = f
        .iter()
        .map(|x| project(s, &c.eval(&(t0 + (t1 - t0) * x))))
        .collect();
    let b = interpolate_with_parameters(&uv, &f, 3).unwrap();
    let w = vec![1.0; b.control.len()];
    NurbsCurve::new(b.knots.knots().to_vec(), 3, b.control, w).unwrap()
}

/// A quarter of a small circle on a sphere of radius 2 round the direction (1, 1, 0.3): it
/// crosses the equator, a knot line of the sphere's NURBS form, inside the pcurve's pieces.
/// The bound stays within 4× of the distance measured at 4001 points (2× here), falls with
/// the samples, and is never below the measurement.
#[test]
fn circles_on_a_sphere_are_bounded_soundly_and_tightly() {
    let s = sphere(&Frame::WORLD, 2.0).unwrap();
    let cells = SurfaceCells::new(&s).unwrap();
    let n = [1.0, 1.0, 0.3].scale(&(1.0 / (2.09f64).sqrt()));
    let x = cross(&n, &[0.0, 0.0, 1.0]);
    let x = x.scale(&(1.0 / dot(&x, &x).sqrt()));
    let (rho, d) = (0.5, (4.0f64 - 0.25).sqrt());
    let frame = Frame {
        o: n.scale(&d),
        x,
        y: cross(&n, &x),
        z: n,
    };
    let q = std::f64::consts::FRAC_PI_2;
    let c = arc(&frame, rho, -q, 0.0).unwrap();
    let (t0, t1) = c.hom.domain();
    let mut last = f64::INFINITY;
    for m in [5, 9, 17, 33] {
        let p = projected(&s, &c, m);
        let r = cells.bound(&p, &c, (t0, t1), 1e-12).unwrap();
        // S∘p measured against the true circle at 4001 points: a lower bound on the distance.
        let (f0, f1) = p.hom.domain();
        let measured = (0..=4000)
            .map(|i| {
                let uv = p.eval(&(f0 + (f1 - f0) * i as f64 / 4000.0));
                to_circle(&s.eval(&uv[0], &uv[1]), &frame.o, &n, rho)
            })
            .fold(0.0, f64::max);
        assert!(
            r >= measured,
            "m = {m}: bound {r} below measured {measured}"
        );
        assert!(
            r <= 4.0 * measured + 1e-12,
            "m = {m}: bound {r}, measured {measured}"
        );
        assert!(r < last, "m = {m}: {r} not below {last}");
        last = r;
        // The same pcurve against a circle 1e-3 wider: at least the widening, measured.
        let wide = arc(&frame, rho + 1e-3, -q, 0.0).unwrap();
        let rw = cells.bound(&p, &wide, (t0, t1), 1e-12).unwrap();
        let mw = (0..=4000)
            .map(|i| {
                let uv = p.eval(&(f0 + (f1 - f0) * i as f64 / 4000.0));
                to_circle(&s.eval(&uv[0], &uv[1]), &frame.o, &n, rho + 1e-3)
            })
            .fold(0.0, f64::max);
        assert!(mw > 9e-4 && rw >= mw, "m = {m}: bound {rw}, measured {mw}");
    }
    assert!(last < 1e-6, "33 samples: {last}");
}

/// De Casteljau's value of Bernstein coefficients `c` at `s` (f64).
fn bernstein_at(c: &[f64], s: f64) -> f64 {
    let mut b = c.to_vec();
    for r in 1..b.len() {
        for k in 0..b.len() - r {
            b[k] = (1.0 - s) * b[k] + s * b[k + 1];
        }
    }
    b[0]
}

/// The scaled form's product, back in Bernstein form, is the product polynomial: at every
/// sample its value (by de Casteljau on the enclosures' midpoints) is `f(s) g(s)`, and the
/// enclosures are narrow (degrees 3 × 4, then 7 × 2).
#[test]
fn scaled_products_are_the_product_polynomial() {
    let f = [0.3, -1.2, 2.5, 0.7];
    let g = [1.1, 0.4, -0.9, 2.0, -0.3];
    let pts = |v: &[f64]| v.iter().map(|x| I::point(*x)).collect::<Vec<_>>();
    let fg = unscaled(&mul(
        &scaled(pts(&f).into_iter()),
        &scaled(pts(&g).into_iter()),
    ));
    assert_eq!(fg.len(), 8);
    let h = [2.0, -1.0, 0.5];
    let fgh = unscaled(&mul(
        &scaled(fg.clone().into_iter()),
        &scaled(pts(&h).into_iter()),
    ));
    assert_eq!(fgh.len(), 10);
    for i in 0..=20 {
        let s = i as f64 / 20.0;
        let mid = |v: &[I]| v.iter().map(|x| 0.5 * (x.lo + x.hi)).collect::<Vec<_>>();
        let want = bernstein_at(&f, s) * bernstein_at(&g, s);
        assert!(
            (bernstein_at(&mid(&fg), s) - want).abs() <= 1e-13,
            "s = {s}"
        );
        let want = want * bernstein_at(&h, s);
        assert!(
            (bernstein_at(&mid(&fgh), s) - want).abs() <= 1e-13,
            "s = {s}"
        );
    }
    assert!(fgh.iter().all(|x| x.hi - x.lo <= 1e-14));
}
