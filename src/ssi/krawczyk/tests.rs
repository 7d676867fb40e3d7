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

/// The shared test of a run ([`RunCertifier`]) on the sphere of radius 2 cut by z = h, in
/// a tilted frame's plane: 16 consecutive points 1e-8 off the circle (spaced as output
/// points are), one Jacobian enclosure over their hull. Every point is settled; its radius is
/// at least its true distance to the circle (closed form) and the enclosed common point holds
/// a point of the circle.
#[test]
fn a_run_shares_one_test() {
    let s = sphere(&Frame::WORLD, 2.0).unwrap();
    let h = 0.7;
    let a = plane_z(h);
    let rho = (4.0f64 - h * h).sqrt();
    let pts: Vec<([f64; 3], [f64; 2], [f64; 2])> = (0..16)
        .map(|k| {
            let phi = 1.1 + 6e-4 * k as f64;
            let x = [(rho + 1e-8) * phi.cos(), (rho + 1e-8) * phi.sin(), h];
            let uv_a = [(x[0] + 2.0) / 4.0, (x[1] + 2.0) / 4.0];
            (x, uv_a, crate::spline::project::project(&s, &x))
        })
        .collect();
    let cache = JetCache::over(&a, &s, pts.iter().map(|p| (p.1, p.2))).unwrap();
    let mid = &pts[8];
    let run = RunCertifier::new(&a, &s, &cache, (&mid.1, &mid.2)).unwrap();
    let off_circle = |q: &[f64; 3]| ((q[0] * q[0] + q[1] * q[1]).sqrt() - rho).hypot(q[2] - h);
    for (x, uv_a, uv_b) in &pts {
        let c = run
            .certify(x, uv_a, uv_b)
            .expect("settled by the shared test");
        let d = off_circle(x);
        assert!(
            c.radius >= d - 1e-15 && c.radius <= d + 1e-12,
            "{} {d}",
            c.radius
        );
        let q = c.point.map(|i| i.mid());
        let half_diag = c.point.iter().map(|i| i.hi - i.lo).fold(0.0, f64::hypot) / 2.0;
        assert!(off_circle(&q) <= half_diag + 1e-15, "{q:?}");
        // The centre is the Newton solution: both surfaces meet there to f64 accuracy.
        let (pa, pb) = (
            a.eval(&c.centre[0], &c.centre[1]),
            s.eval(&c.centre[2], &c.centre[3]),
        );
        assert!(crate::geom::dist(&pa, &pb) < 1e-14 && off_circle(&pa) < 1e-14);
    }
    // A point of the circle a quarter turn away: its box leaves the shared enclosure, so it
    // is left to the one-by-one test.
    let phi = 1.1 + std::f64::consts::FRAC_PI_2;
    let far = [rho * phi.cos(), rho * phi.sin(), h];
    let uv = [(far[0] + 2.0) / 4.0, (far[1] + 2.0) / 4.0];
    assert!(
        run.certify(&far, &uv, &crate::spline::project::project(&s, &far))
            .is_none()
    );
    // A point far off the curve gets no radius below its distance.
    let off = pts[0].0.map(|c| c * 0.9);
    let uv = [(off[0] + 2.0) / 4.0, (off[1] + 2.0) / 4.0];
    if let Some(c) = run.certify(&off, &uv, &pts[0].2) {
        assert!(c.radius >= off_circle(&off) - 1e-15, "{}", c.radius);
    }
}

/// Two cylinders whose intersection crosses both seams at one point: A of radius 1 about the
/// z axis (seam at (1, 0, z)), B of radius 0.6 about the x axis through (−3, 0, 0), its frame's
/// x axis along z (seam at (x, 0, 0.6)). At `(1, 0, 0.6)` the curve leaves both parameter
/// domains at once; the domains are closed there (a proven seam each), so a true point just
/// across, on the other side of either seam, is inside them. The certificate must find one:
/// the curve point is exact, so the radius is tiny.
#[test]
fn a_point_on_both_seams_is_certified() {
    let world = Frame::WORLD;
    let fb = Frame {
        o: [-3.0, 0.0, 0.0],
        x: [0.0, 0.0, 1.0],
        y: [0.0, -1.0, 0.0],
        z: [1.0, 0.0, 0.0],
    };
    both_seams(&world, &fb, [1.0, 0.0, 0.6]);
    // The same in rotated frames (as STEP files place surfaces): a random rotation R of both
    // frames and the point; the seams move with the frames, so the point stays on both.
    let mut r = crate::spline::test_params::rng(0x0005_ea35_eed5);
    for _ in 0..6 {
        let q: [f64; 4] = std::array::from_fn(|_| 2.0 * r() - 1.0);
        let l = q.iter().map(|x| x * x).sum::<f64>().sqrt();
        let [w, x, y, z] = q.map(|c| c / l);
        let rot = |v: [f64; 3]| -> [f64; 3] {
            let m = [
                [
                    1.0 - 2.0 * (y * y + z * z),
                    2.0 * (x * y - w * z),
                    2.0 * (x * z + w * y),
                ],
                [
                    2.0 * (x * y + w * z),
                    1.0 - 2.0 * (x * x + z * z),
                    2.0 * (y * z - w * x),
                ],
                [
                    2.0 * (x * z - w * y),
                    2.0 * (y * z + w * x),
                    1.0 - 2.0 * (x * x + y * y),
                ],
            ];
            std::array::from_fn(|i| m[i][0] * v[0] + m[i][1] * v[1] + m[i][2] * v[2])
        };
        let turn = |f: &Frame| Frame {
            o: rot(f.o),
            x: rot(f.x),
            y: rot(f.y),
            z: rot(f.z),
        };
        both_seams(&turn(&world), &turn(&fb), rot([1.0, 0.0, 0.6]));
    }
}

/// Cylinder A (radius 1, frame `fa`) and B (radius 0.6, frame `fb`) meet at `p` on both seams:
/// the certificate succeeds from either side of the seams.
fn both_seams(fa: &Frame, fb: &Frame, p: [f64; 3]) {
    use crate::spline::construct::cylinder;
    let a = cylinder(fa, 1.0, -3.0, 3.0).unwrap();
    let b = cylinder(fb, 0.6, 0.0, 6.0).unwrap();
    let (ua, ub) = (
        crate::spline::project::SurfaceFoot::new(&a).closest(&p),
        crate::spline::project::SurfaceFoot::new(&b).closest(&p),
    );
    for (s, uv) in [(&a, ua), (&b, ub)] {
        let q = s.eval(&uv[0], &uv[1]);
        assert!(crate::geom::dist(&q, &p) < 1e-9, "{uv:?} {q:?}");
        let d = domain(s);
        let on_seam = uv[0] <= d[0] + 1e-9 || uv[0] >= d[1] - 1e-9;
        assert!(on_seam, "the construction puts p on the seam: {uv:?}");
    }
    for (x, y) in [(ua, ub), ([domain(&a)[1], ua[1]], [domain(&b)[1], ub[1]])] {
        let c = certify_on_curve(&a, &b, &p, &x, &y).expect("certified");
        assert!(c.radius < 1e-9, "{}", c.radius);
    }
}
