//! Unit tests of step 9b, the curve certificate (Krawczyk's test): planes and a sphere with a
//! known intersection curve, Newton onto the curve, and refusal at tangency.

use super::*;
use crate::spline::construct::{Frame, bilinear, sphere};

fn plane_z(h: f64) -> NurbsSurface<f64, 3> {
    bilinear(
        [-2.0, -2.0, h],
        [2.0, -2.0, h],
        [-2.0, 2.0, h],
        [2.0, 2.0, h],
    )
    .unwrap()
}

/// Planes z = 0 and through the x axis at angle θ: the curve is the x axis. Points off it
/// by `e` get a radius at least their distance and not much more.
#[test]
fn tilted_planes() {
    for th in [0.3, 1e-2, 1e-4, 1e-6] {
        let (c, s) = (2.0 * f64::cos(th), 2.0 * f64::sin(th));
        let b = bilinear([-2.0, -c, -s], [2.0, -c, -s], [-2.0, c, s], [2.0, c, s]).unwrap();
        let a = plane_z(0.0);
        for e in [0.0, 1e-9, 1e-7] {
            // u = (x+2)/4, v = (y+2)/4 on A; on B v' = (y/cos θ + 2)/4 roughly.
            let p = [0.3, e, 0.0];
            let uv_a = [(p[0] + 2.0) / 4.0, (p[1] + 2.0) / 4.0];
            let uv_b = [(p[0] + 2.0) / 4.0, 0.5];
            let cert = certify_on_curve(&a, &b, &p, &uv_a, &uv_b).unwrap();
            assert!(cert.radius >= e, "{th} {e}: {}", cert.radius);
            assert!(cert.radius <= e + 1e-13, "{th} {e}: {}", cert.radius);
        }
    }
}

/// Near tangency a point within `d` of both planes lies about `d / θ` from their common
/// line; the Newton solution is on it (closed form: the x axis), at the point's `x`, and
/// is `None` for planes that do not meet within the domains.
#[test]
fn newton_lands_on_the_line() {
    for th in [0.1, 1e-3, 1e-5] {
        let (c, s) = (2.0 * f64::cos(th), 2.0 * f64::sin(th));
        let b = bilinear([-2.0, -c, -s], [2.0, -c, -s], [-2.0, c, s], [2.0, c, s]).unwrap();
        let a = plane_z(0.0);
        // 1e-7 from A and about 1e-7 from B: 1e-7 / θ off the line.
        let e = 1e-7 / th;
        let p = [0.3, e, 1e-7];
        let uv_a = [(p[0] + 2.0) / 4.0, (p[1] + 2.0) / 4.0];
        let uv_b = [(p[0] + 2.0) / 4.0, 0.5 + e / 4.0];
        let y = newton_on_curve(&a, &b, &p, &uv_a, &uv_b).unwrap();
        let q = a.eval(&y[0], &y[1]);
        assert!(q[1].abs() < 1e-13 && q[2] == 0.0, "{th}: {q:?}");
        assert!((q[0] - 0.3).abs() < 1e-12, "{th}: {q:?}");
        let r = b.eval(&y[2], &y[3]);
        assert!(crate::geom::dist(&q, &r) < 1e-13, "{th}: {q:?} {r:?}");
    }
    // Parallel planes 1e-3 apart: no zero.
    let (a, b) = (plane_z(0.0), plane_z(1e-3));
    assert!(newton_on_curve(&a, &b, &[0.0; 3], &[0.5, 0.5], &[0.5, 0.5]).is_none());
}

/// The sphere of radius 2 cut by z = h: radius bounds the distance to the circle.
#[test]
fn sphere_and_plane() {
    let f = Frame::WORLD;
    let s = sphere(&f, 2.0).unwrap();
    let h = 0.7;
    let a = plane_z(h);
    let rho = (4.0f64 - h * h).sqrt();
    for k in 0..20 {
        // A point near the circle, its parameters from a nearby sphere point.
        let phi = 0.05 + 6.0 * k as f64 / 20.0;
        let x = [rho * phi.cos() + 1e-8, rho * phi.sin(), h];
        let u = phi / std::f64::consts::TAU;
        let v = 0.5 + (h / 2.0).asin() / std::f64::consts::PI;
        let uv_a = [(x[0] + 2.0) / 4.0, (x[1] + 2.0) / 4.0];
        let cert = certify_on_curve(&a, &s, &x, &uv_a, &[u, v]).unwrap();
        let d = ((x[0] * x[0] + x[1] * x[1]).sqrt() - rho).abs();
        assert!(
            cert.radius >= d - 1e-15 && cert.radius <= d + 1e-9,
            "{k}: {} {d}",
            cert.radius
        );
    }
}

/// Where the surfaces touch, or nearly touch without meeting, nothing is certified.
#[test]
fn tangency_is_uncertified() {
    let f = Frame::WORLD;
    let s = sphere(&f, 2.0).unwrap();
    for h in [2.0, 2.0 + 1e-9, 2.0 - 1e-12] {
        let a = plane_z(h);
        // Near the north pole on the sphere (v slightly below 1).
        for v in [1.0, 1.0 - 1e-7, 1.0 - 1e-4] {
            let q = s.eval(&0.1, &v);
            let r = certify_on_curve(
                &a,
                &s,
                &q,
                &[(q[0] + 2.0) / 4.0, (q[1] + 2.0) / 4.0],
                &[0.1, v],
            );
            if let Ok(c) = r {
                // Only a true root may be claimed: below the pole plane, z = h must be met.
                assert!(h < 2.0, "{h} {v}: {c:?}");
            }
        }
    }
}
