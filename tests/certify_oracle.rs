//! `certify-ssi` as an oracle: verdicts on foreign curves whose truth is known from the
//! construction (sphere ∩ plane circles, a tangent contact, torus ∩ plane loops), not from
//! vericad's own output.

use vericad::model::{Model, Surface};
use vericad::spline::NurbsSurface;
use vericad::spline::construct::{Frame, bilinear, sphere, torus};
use vericad::ssi::SsiParams;
use vericad::ssi::foreign::{CertifyReport, ForeignInput, certify};

/// A rotated frame (rotation about (1, 2, 2)/3 by 0.7 rad), placed away from the origin.
fn rotated(o: [f64; 3]) -> Frame {
    let k = [1.0 / 3.0, 2.0 / 3.0, 2.0 / 3.0];
    let (c, s) = (0.7f64.cos(), 0.7f64.sin());
    let rot = |v: [f64; 3]| -> [f64; 3] {
        let kv = k[0] * v[0] + k[1] * v[1] + k[2] * v[2];
        let kx = [
            k[1] * v[2] - k[2] * v[1],
            k[2] * v[0] - k[0] * v[2],
            k[0] * v[1] - k[1] * v[0],
        ];
        std::array::from_fn(|i| v[i] * c + kx[i] * s + k[i] * kv * (1.0 - c))
    };
    Frame {
        o,
        x: rot([1.0, 0.0, 0.0]),
        y: rot([0.0, 1.0, 0.0]),
        z: rot([0.0, 0.0, 1.0]),
    }
}

/// The plane through `f.at(0, 0, h)` spanned by the frame's x and y, `±half` wide.
fn plane(f: &Frame, h: f64, half: f64) -> NurbsSurface<f64, 3> {
    bilinear(
        f.at(-half, -half, h),
        f.at(half, -half, h),
        f.at(-half, half, h),
        f.at(half, half, h),
    )
    .unwrap()
}

fn model(s: Vec<NurbsSurface<f64, 3>>) -> Model {
    Model {
        surfaces: s
            .into_iter()
            .enumerate()
            .map(|(i, s)| Surface::new(format!("face {i}"), s))
            .collect(),
        ..Default::default()
    }
}

/// `n` points of the circle `f.at(ρ cos φ, ρ sin φ, h)`, moved by `shift`, as a closed
/// polyline (the first point repeated at the end).
fn circle(f: &Frame, rho: f64, h: f64, n: usize, shift: [f64; 3]) -> Vec<[f64; 3]> {
    (0..=n)
        .map(|k| {
            let phi = 0.05 + std::f64::consts::TAU * k as f64 / n as f64;
            let p = f.at(rho * phi.cos(), rho * phi.sin(), h);
            std::array::from_fn(|i| p[i] + shift[i])
        })
        .collect()
}

fn run(a: &Model, b: &Model, curves: Vec<Vec<[f64; 3]>>, tol: f64) -> CertifyReport {
    let prm = SsiParams {
        tol,
        ..Default::default()
    };
    let r = vericad::ssi::intersect_models(a, Some(b), &prm, &|_, _| {}).unwrap();
    let foreign: Vec<ForeignInput> = curves
        .into_iter()
        .enumerate()
        .map(|(i, c)| (format!("c{i}"), "polyline", c))
        .collect();
    certify(a, Some(b), &foreign, &r, tol, 100.0 * tol, &|_, _| {})
}

const TOL: f64 = 1e-6;

/// Sphere of radius 1 in a rotated frame cut by a plane 5e-7 below the pole: a circle of
/// radius 1e-3. A correct foreign circle is accepted; moved by 10·tol along the plane's
/// normal it is proven off; moved by 10·tol within the plane it is not accepted.
#[test]
fn circle_near_a_pole() {
    let f = rotated([0.4, -1.2, 2.5]);
    let rho = 1e-3f64;
    let h = (1.0 - rho * rho).sqrt();
    let (a, b) = (
        model(vec![sphere(&f, 1.0).unwrap()]),
        model(vec![plane(&f, h, 0.5)]),
    );
    let good = run(&a, &b, vec![circle(&f, rho, h, 64, [0.0; 3])], TOL);
    let c = &good.curves[0];
    assert_eq!(c.status, "within_tol", "{good}");
    assert_eq!(c.points_on_curve, 65);
    // The proven radius is far below tol (the points are ~1e-16 from the true circle), and
    // the global distance bounds are tight.
    assert!(c.curve_dist_max.unwrap() < 1e-9, "{good}");
    assert!(c.dist_a_max < 1e-9 && c.dist_b_max < 1e-9, "{good}");
    assert_eq!(good.missing_branches, 0, "{good}");

    let up: [f64; 3] = f.z.map(|z| 10.0 * TOL * z);
    let off = run(&a, &b, vec![circle(&f, rho, h, 64, up)], TOL);
    let c = &off.curves[0];
    assert_eq!(c.status, "off", "{off}");
    assert_eq!(c.points_off, 65, "{off}");
    assert!(c.dist_lower_max > 9.0 * TOL, "{off}");
    assert!(!off.certified);

    let side: [f64; 3] = f.x.map(|x| 10.0 * TOL * x);
    let moved = run(&a, &b, vec![circle(&f, rho, h, 64, side)], TOL);
    let c = &moved.curves[0];
    assert!(!c.within_tol, "{moved}");
    // Within the tangent plane near the pole the moved points stay within tol of both
    // surfaces; only the distance to the intersection curve tells them apart.
    assert!(c.dist_a_max < TOL && c.dist_b_max < TOL, "{moved}");
    assert!(c.points_on_curve < 65, "{moved}");
    assert!(!moved.certified);
}

/// A plane tangent to a sphere (rotated frame) at a generic point, and a fake circle of
/// radius 1e-3 drawn in the tangent plane around the contact: every point lies within tol
/// of both surfaces (≈ 5e-7 from the sphere), but none within tol of the intersection
/// (which is the contact point, up to the rounding of the sphere's weights). Never accepted.
#[test]
fn fake_circle_at_a_tangent_contact() {
    let f = rotated([-0.3, 0.8, 0.1]);
    let (th, ph) = (0.52f64, 0.35f64);
    let n: [f64; 3] = std::array::from_fn(|i| {
        th.cos() * ph.cos() * f.x[i] + th.sin() * ph.cos() * f.y[i] + ph.sin() * f.z[i]
    });
    let c: [f64; 3] = std::array::from_fn(|i| f.o[i] + n[i]);
    // An orthonormal pair in the tangent plane.
    let e1: [f64; 3] = std::array::from_fn(|i| -th.sin() * f.x[i] + th.cos() * f.y[i]);
    let e2 = [
        n[1] * e1[2] - n[2] * e1[1],
        n[2] * e1[0] - n[0] * e1[2],
        n[0] * e1[1] - n[1] * e1[0],
    ];
    let tangent = Frame {
        o: c,
        x: e1,
        y: e2,
        z: n,
    };
    let (a, b) = (
        model(vec![sphere(&f, 1.0).unwrap()]),
        model(vec![plane(&tangent, 0.0, 0.5)]),
    );
    let fake = circle(&tangent, 1e-3, 0.0, 48, [0.0; 3]);
    let r = run(&a, &b, vec![fake], TOL);
    let cv = &r.curves[0];
    // The case is the hard one: near both surfaces ...
    assert!(cv.dist_a_max < TOL && cv.dist_b_max < TOL, "{r}");
    // ... and never accepted.
    assert!(!cv.within_tol, "{r}");
    assert_eq!(cv.points_on_curve, 0, "{r}");
    assert!(!r.certified);
}

/// Torus (major 2, minor 0.7, rotated frame) cut by the plane at height 0.3: two circles of
/// radii 2 ± √0.4. The outer circle alone is accepted and the inner loop is reported missing
/// with a witness on the true inner circle; both circles: nothing missing.
#[test]
fn torus_loop_removed_is_missing() {
    let f = rotated([1.0, 0.5, -0.7]);
    let h = 0.3;
    let (a, b) = (
        model(vec![torus(&f, 2.0, 0.7).unwrap()]),
        model(vec![plane(&f, h, 3.0)]),
    );
    let (ro, ri) = (2.0 + 0.4f64.sqrt(), 2.0 - 0.4f64.sqrt());
    let outer = circle(&f, ro, h, 2000, [0.0; 3]);
    let inner = circle(&f, ri, h, 2000, [0.0; 3]);
    let one = run(&a, &b, vec![outer.clone()], TOL);
    assert_eq!(one.curves[0].status, "within_tol", "{one}");
    assert!(one.missing_branches >= 1, "{one}");
    assert!(!one.certified);
    for br in one.branches.iter().filter(|b| b.status == "missing") {
        // The witness is on the inner circle (checked against the construction).
        let w = br.witness.unwrap();
        let d: [f64; 3] = std::array::from_fn(|i| w[i] - f.o[i]);
        let z = d[0] * f.z[0] + d[1] * f.z[1] + d[2] * f.z[2];
        let rr = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2] - z * z).sqrt();
        assert!((z - h).abs() < 1e-5 && (rr - ri).abs() < 1e-5, "{w:?}");
    }
    let both = run(&a, &b, vec![outer, inner], TOL);
    assert_eq!(both.curves_within_tol, 2, "{both}");
    assert_eq!(both.missing_branches + both.partial_branches, 0, "{both}");
    assert_eq!(
        both.certified,
        both.vericad_no_missed_branches && both.unverified_branches == 0,
        "{both}"
    );
}

/// One-file mode through the command line: a model with a sphere and a plane as its two
/// faces, the true circle as the foreign curve; every distinct face pair, never a face with
/// itself. (Foreign polylines are dense enough that their chords stay within the match
/// distance of the true curve: a chord farther than that from a certified true point is a
/// gap in the foreign result.)
#[test]
fn one_file_mode() {
    let dir = std::env::temp_dir().join(format!("vericad-oracle-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let f = rotated([0.2, 0.1, -0.3]);
    let h = 0.45;
    let m = model(vec![sphere(&f, 1.0).unwrap(), plane(&f, h, 1.5)]);
    let file = dir.join("two_faces.json");
    vericad::io::write_model(&file, &m).unwrap();
    let rho = (1.0f64 - h * h).sqrt();
    let curves = dir.join("curves.json");
    let good = serde_json::json!({ "curves": [circle(&f, rho, h, 1000, [0.0; 3])] });
    std::fs::write(&curves, good.to_string()).unwrap();
    let exe = env!("CARGO_BIN_EXE_vericad");
    let run = |curves: &std::path::Path| {
        let out = std::process::Command::new(exe)
            .args([
                "certify-ssi",
                file.to_str().unwrap(),
                "--curves",
                curves.to_str().unwrap(),
                "--json",
            ])
            .output()
            .unwrap();
        let v: serde_json::Value = serde_json::from_slice(&out.stdout)
            .unwrap_or_else(|e| panic!("{e}: {}", String::from_utf8_lossy(&out.stderr)));
        (out.status.code(), v)
    };
    let (code, v) = run(&curves);
    assert_eq!(v["mode"], "one_file");
    assert_eq!(v["curves_within_tol"], 1, "{v}");
    assert_eq!(v["missing_branches"], 0, "{v}");
    // vericad's own branches come from distinct faces only (never a face with itself).
    let brs = v["branches"].as_array().unwrap();
    assert!(!brs.is_empty(), "{v}");
    assert!(brs.iter().all(|b| b["face_a"] != b["face_b"]), "{v}");
    let certified = v["certified"].as_bool().unwrap();
    assert_eq!(code, Some(if certified { 0 } else { 3 }), "{v}");
    // The circle lifted off the plane by 1e-4: proven off, exit 3.
    let lifted = dir.join("lifted.json");
    let up = f.z.map(|z| 1e-4 * z);
    std::fs::write(
        &lifted,
        serde_json::json!({ "curves": [circle(&f, rho, h, 1000, up)] }).to_string(),
    )
    .unwrap();
    let (code, v) = run(&lifted);
    assert_eq!(v["curves"][0]["status"], "off", "{v}");
    assert_eq!(code, Some(3));
    std::fs::remove_dir_all(&dir).ok();
}

/// Two cylinders crossing, the true curve from the construction: A is `x² + y² = 1` (frame
/// `f`, its seam along `f.at(1, 0, ·)`), B is `y² + z² = 0.36` about the frame's x axis with its
/// seam along `f.at(·, 0, 0.6)`; the branch `x > 0` is `(√(1 − 0.36 sin²θ), 0.6 sin θ, 0.6 cos θ)`
/// and crosses both seams at once at `θ = 0`, the point `(1, 0, 0.6)`; the branch `x < 0` is
/// its mirror. Correct foreign polylines of both branches (2,048 chords each, sagitta below
/// 1e-6) are accepted, every vertex certified on the curve (the vertex on both seams too),
/// nothing missing, in the world frame and in a rotated one; with the `x < 0` branch left out
/// it is reported missing; moved by 10 tol, the curve is rejected.
#[test]
fn a_curve_through_both_seams_is_accepted() {
    use vericad::spline::construct::cylinder;
    for f in [Frame::WORLD, rotated([0.3, 0.2, -0.4])] {
        let fb = Frame {
            o: f.at(-3.0, 0.0, 0.0),
            x: f.z,
            y: f.y.map(|c| -c),
            z: f.x,
        };
        let (a, b) = (
            model(vec![cylinder(&f, 1.0, -3.0, 3.0).unwrap()]),
            model(vec![cylinder(&fb, 0.6, 0.0, 6.0).unwrap()]),
        );
        let n = 2048;
        let curve = |sign: f64, shift: [f64; 3]| -> Vec<[f64; 3]> {
            (0..=n)
                .map(|k| {
                    let t = std::f64::consts::TAU * k as f64 / n as f64;
                    let (s, c) = (0.6 * t.sin(), 0.6 * t.cos());
                    let p = f.at(sign * (1.0 - s * s).sqrt(), s, c);
                    std::array::from_fn(|i| p[i] + shift[i])
                })
                .collect()
        };
        let good = run(
            &a,
            &b,
            vec![curve(1.0, [0.0; 3]), curve(-1.0, [0.0; 3])],
            TOL,
        );
        for c in &good.curves {
            assert_eq!(c.status, "within_tol", "{good}");
            assert_eq!(c.points_on_curve, n + 1, "{good}");
            assert!(c.curve_dist_max.unwrap() < 1e-9, "{good}");
        }
        assert_eq!(good.missing_branches, 0, "{good}");
        assert!(good.certified, "{good}");
        let one = run(&a, &b, vec![curve(1.0, [0.0; 3])], TOL);
        assert_eq!(one.missing_branches, 1, "{one}");
        assert!(!one.certified, "{one}");
        let up: [f64; 3] = f.x.map(|x| 10.0 * TOL * x);
        let off = run(&a, &b, vec![curve(1.0, up), curve(-1.0, up)], TOL);
        assert!(off.curves.iter().all(|c| !c.within_tol), "{off}");
        assert!(!off.certified, "{off}");
    }
}

/// A sphere touching the plane z = 1 at one point and another crossing it in a circle of
/// radius √0.75: a foreign result with the circle alone is not complete (the touching point
/// is a component of the intersection it misses) — never certified; with the point as well,
/// nothing of vericad's output is left uncovered.
#[test]
fn a_missing_touching_point_is_not_complete() {
    let at = |o: [f64; 3]| Frame { o, ..Frame::WORLD };
    // The touching sphere in a rotated frame: its poles are away from the contact.
    let a = model(vec![
        sphere(&rotated([0.0, 0.0, 0.0]), 1.0).unwrap(),
        sphere(&at([3.0, 0.0, 0.5]), 1.0).unwrap(),
    ]);
    let b = model(vec![plane(&Frame::WORLD, 1.0, 5.0)]);
    let ring = circle(&at([3.0, 0.0, 0.0]), 0.75f64.sqrt(), 1.0, 2000, [0.0; 3]);
    let r = run(&a, &b, vec![ring.clone()], TOL);
    // vericad's own coverage holds and the circle is within tol: only the touching point
    // tells the result is incomplete.
    assert!(
        r.vericad_no_missed_branches && r.curves[0].within_tol,
        "{r}"
    );
    assert!(r.touch_and_border_points_not_covered >= 1, "{r}");
    assert!(!r.foreign_complete && !r.certified, "{r}");
    let r = run(&a, &b, vec![ring, vec![[0.0, 0.0, 1.0]]], TOL);
    assert_eq!(r.touch_and_border_points_not_covered, 0, "{r}");
}
