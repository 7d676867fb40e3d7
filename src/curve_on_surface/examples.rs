//! The three inputs of the paper's §6, for tests and benchmarks. Table 2's data is printed
//! in the paper and reproduced exactly ([`table2`], the embedded demo model). The human face
//! (17 × 17 bicubic) and tiger ear (19 × 19 bicubic) surfaces are not published, so
//! [`face_like`] and [`ear_like`] are synthetic surfaces of the same size and degree, with a
//! closed cubic domain curve of 10 control points and an open cubic of 20 segments.

use crate::model::{CurveGeometry, json};
use crate::spline::{NurbsCurve, NurbsSurface};

/// Table 2: the biquadratic Bézier surface and the quadratic domain curve of the paper.
pub fn table2() -> (NurbsSurface<f64, 3>, NurbsCurve<f64, 2>) {
    let m = json::from_str(crate::model::YANG_TABLE2, "embedded").expect("embedded model");
    let CurveGeometry::Domain(c) = m.curves[0].geometry.clone() else {
        unreachable!("the embedded model's first curve is a domain curve")
    };
    (m.surfaces[0].nurbs.clone(), c)
}

/// Clamped uniform knots for `n` control points of degree 3 on `[0, 1]`.
fn clamped_cubic(n: usize) -> Vec<f64> {
    let mut k = vec![0.0; 4];
    for i in 1..n - 3 {
        k.push(i as f64 / (n - 3) as f64);
    }
    k.extend([1.0; 4]);
    k
}

/// A bicubic surface with `n × n` control points over `[0, 1]²` whose height is `z(x, y)`.
fn bicubic(n: usize, z: impl Fn(f64, f64) -> f64) -> NurbsSurface<f64, 3> {
    let k = clamped_cubic(n);
    let mut pts = Vec::with_capacity(n * n);
    for i in 0..n {
        for j in 0..n {
            let (x, y) = (i as f64 / (n - 1) as f64, j as f64 / (n - 1) as f64);
            pts.push([x, y, z(x, y)]);
        }
    }
    NurbsSurface::new(k.clone(), 3, k, 3, n, n, pts, vec![1.0; n * n]).expect("valid surface")
}

/// A "face-like" bicubic surface with 17 × 17 control points on `[0,1]²`, smooth bumps.
pub fn face_like() -> NurbsSurface<f64, 3> {
    bicubic(17, |x, y| {
        0.25 * (-((x - 0.5).powi(2) + (y - 0.45).powi(2)) * 6.0).exp()
            + 0.06 * (7.0 * x).sin() * (5.0 * y).cos()
            + 0.08 * (-((x - 0.5).powi(2) + (y - 0.7).powi(2)) * 80.0).exp()
    })
}

/// A closed cubic B-spline with 10 control points (periodic: the first 3 repeated).
pub fn closed_curve() -> NurbsCurve<f64, 2> {
    let mut p: Vec<[f64; 2]> = (0..10)
        .map(|i| {
            let a = i as f64 / 10.0 * std::f64::consts::TAU;
            let r = 0.3 + 0.06 * ((3.0 * a).cos());
            [0.5 + r * a.cos(), 0.5 + 0.9 * r * a.sin()]
        })
        .collect();
    p.extend_from_slice(&p.clone()[..3]);
    let knots: Vec<f64> = (0..17).map(|i| i as f64).collect();
    NurbsCurve::new(knots, 3, p, vec![1.0; 13]).expect("valid curve")
}

/// An "ear-like" bicubic surface with 19 × 19 control points: a curled, pointed sheet.
pub fn ear_like() -> NurbsSurface<f64, 3> {
    bicubic(19, |x, y| {
        0.4 * (1.0 - (2.0 * x - 1.0).powi(2)) * y.powf(1.5)
            + 0.05 * (9.0 * y).sin() * (4.0 * x).cos()
            + 0.1 * (-((x - 0.5).powi(2) * 30.0 + (y - 0.85).powi(2) * 20.0)).exp()
    })
}

/// An open cubic B-spline of 20 segments (23 control points) winding up the ear.
pub fn ear_curve() -> NurbsCurve<f64, 2> {
    let n = 23;
    let p: Vec<[f64; 2]> = (0..n)
        .map(|i| {
            let s = i as f64 / (n - 1) as f64;
            [
                0.5 + 0.35 * (1.0 - 0.6 * s) * (5.0 * s).sin(),
                0.08 + 0.84 * s,
            ]
        })
        .collect();
    NurbsCurve::new(clamped_cubic(n), 3, p, vec![1.0; n]).expect("valid curve")
}
