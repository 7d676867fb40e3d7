//! Cubic pieces (`--pieces cubic`) against constructions whose curves are known in closed
//! form: spheres and tori in rotated frames cut by planes (circles). Each piece is sampled
//! at 64 parameters and measured against the true circles by their closed-form distance, not
//! by the code under test; the points' certificates and the coverage claim are checked as
//! for chords, and the point count against a chords run of the same case.

mod common;
use common::shapes::rotated;
use vericad::spline::NurbsSurface;
use vericad::spline::construct::{Frame, bilinear, cylinder, sphere, torus};
use vericad::ssi::report::BranchOut;
use vericad::ssi::{PairOut, Pieces, SsiParams, intersect_pair_canonical};

fn run(a: &NurbsSurface<f64, 3>, b: &NurbsSurface<f64, 3>, tol: f64, pieces: Pieces) -> PairOut {
    let prm = SsiParams {
        tol,
        pieces,
        fits: true,
        ..Default::default()
    };
    intersect_pair_canonical(a, b, (0, 1), &prm, None).expect("runs")
}

/// Distance from `q` to the circle of radius `rho` at height `h` about the frame's z axis.
fn circle_dist(f: &Frame, rho: f64, h: f64, q: &[f64; 3]) -> f64 {
    let d: [f64; 3] = std::array::from_fn(|k| q[k] - f.o[k]);
    let dot = |u: &[f64; 3]| d[0] * u[0] + d[1] * u[1] + d[2] * u[2];
    let (a, b, c) = (dot(&f.x), dot(&f.y), dot(&f.z));
    (((a * a + b * b).sqrt() - rho).powi(2) + (c - h).powi(2)).sqrt()
}

/// The plane through the frame's point at height `h`, normal to its z axis, `3 e` across.
fn cut(f: &Frame, h: f64, e: f64) -> NurbsSurface<f64, 3> {
    let at = |a: f64, b: f64| f.at(a, b, h);
    bilinear(at(-e, -e), at(e, -e), at(-e, e), at(e, e)).unwrap()
}

/// Largest distance of the branch's pieces (64 samples each) to the nearest true circle,
/// the fitted B-spline's value at its knots against the points, and whether the pieces
/// include cubic ones.
fn pieces_off(b: &BranchOut, dist: &dyn Fn(&[f64; 3]) -> f64) -> (f64, bool) {
    let mut worst = 0.0f64;
    let mut cubic = false;
    for h in b.pieces() {
        cubic |= h.dp != h.dq;
        for i in 0..=64 {
            let x = h.eval(i as f64 / 64.0);
            worst = worst.max(dist(&[x[0], x[1], x[2]]));
        }
    }
    (worst, cubic)
}

/// The least value of `e` over one period `[0, 2π)`: a scan at 720 parameters, refined by
/// golden section about the best (the distance to a closed curve `a ↦ c(a)` when `e(a)` is
/// the distance to `c(a)`).
fn scan_min(e: &dyn Fn(f64) -> f64) -> f64 {
    let n = 720;
    let step = std::f64::consts::TAU / n as f64;
    let a0 = (0..n)
        .map(|i| i as f64 * step)
        .min_by(|a, b| e(*a).total_cmp(&e(*b)))
        .unwrap();
    let (mut lo, mut hi) = (a0 - step, a0 + step);
    let g = 0.5 * (5f64.sqrt() - 1.0);
    for _ in 0..80 {
        let (m1, m2) = (hi - g * (hi - lo), lo + g * (hi - lo));
        if e(m1) < e(m2) {
            hi = m2;
        } else {
            lo = m1;
        }
    }
    e(0.5 * (lo + hi))
}

/// Spheres of radius 2 in rotated frames cut at heights from the equator to 1e-3 below the
/// pole: one closed branch, every point certified within tol, every piece within tol of the
/// circle at 64 samples, coverage certified, and far fewer points than chords need.
#[test]
fn sphere_sections_in_cubic_pieces() {
    let tol = 1e-7;
    for (seed, h) in [
        (1u64, 0.3),
        (2, 1.5),
        (3, -1.9),
        (4, 1.99),
        (5, 1.999),
        (6, 0.0),
    ] {
        let f = rotated(seed);
        let s = sphere(&f, 2.0).unwrap();
        let p = cut(&f, h, 3.0);
        let rho = (4.0 - h * h).sqrt();
        let r = run(&s, &p, tol, Pieces::Cubic);
        let chords = run(&s, &p, tol, Pieces::Chords);
        assert_eq!(r.branches.len(), 1, "seed {seed} h {h}");
        let b = &r.branches[0];
        assert!(b.closed, "seed {seed} h {h}");
        assert_eq!(b.tangents.len(), b.points.len());
        let radius = b.dist_curve_max.expect("every point certified");
        assert!(radius <= tol, "seed {seed} h {h}: radius {radius}");
        let (worst, cubic) = pieces_off(b, &|q| circle_dist(&f, rho, h, q));
        assert!(cubic, "seed {seed} h {h}: no cubic piece");
        assert!(
            worst <= tol,
            "seed {seed} h {h}: a piece {worst:.3e} from the circle"
        );
        // The drawn polyline (VTK, picture): the pieces' samples, on the circle.
        let drawn = b.drawn(16);
        assert!(drawn.len() > 10 * b.points.len() && drawn[0] == drawn[drawn.len() - 1]);
        assert!(drawn.iter().all(|x| circle_dist(&f, rho, h, x) <= tol));
        let cov = r.coverage.as_ref().unwrap();
        assert!(cov.no_missed_branches, "seed {seed} h {h}");
        let n_chords: usize = chords.branches.iter().map(|b| b.points.len()).sum();
        assert!(
            10 * b.points.len() < n_chords,
            "seed {seed} h {h}: {} points against {n_chords} with chords",
            b.points.len()
        );
        // The fit is the pieces: through every point at its knots.
        let fit = b.fit.as_ref().expect("a fit");
        assert!(
            fit.max_deviation_at_points <= 1e-12,
            "{}",
            fit.max_deviation_at_points
        );
        assert!(fit.control_points.len() <= 3 * b.points.len() + 1);
        assert_eq!(fit.control_points.len() % 3, 1);
    }
}

/// The equator of the sphere's net lies in a plane through its centre: a border of the net's
/// pieces runs along the loop. Its parts are decided against the loop's cubic pieces whole
/// (`along`), not in parts short enough for straight segments: the coverage is certified with
/// under a fifth of the border-crossing boxes of the same run in chords.
#[test]
fn a_border_along_the_loop_is_decided_along_the_pieces() {
    let f = rotated(6);
    let (s, p) = (sphere(&f, 2.0).unwrap(), cut(&f, 0.0, 3.0));
    let cubic = run(&s, &p, 1e-7, Pieces::Cubic);
    let chords = run(&s, &p, 1e-7, Pieces::Chords);
    let boxes = |r: &PairOut| {
        let c = r.coverage.as_ref().unwrap();
        assert!(c.no_missed_branches);
        c.crossing_boxes
    };
    assert_eq!(cubic.branches.len(), 1);
    let (b, c) = (boxes(&cubic), boxes(&chords));
    assert!(
        5 * b < c,
        "{b} crossing boxes in cubic pieces, {c} in chords"
    );
}

/// A torus (3, 1) in a rotated frame cut by z' = 0.5: two circles of radii 3 ± √0.75. Both
/// found closed, in cubic pieces within tol of their circles.
#[test]
fn torus_sections_in_cubic_pieces() {
    let tol = 1e-7;
    for seed in [7u64, 8] {
        let f = rotated(seed);
        let t = torus(&f, 3.0, 1.0).unwrap();
        let p = cut(&f, 0.5, 5.0);
        let r = run(&t, &p, tol, Pieces::Cubic);
        let w = 0.75f64.sqrt();
        let dist =
            |q: &[f64; 3]| circle_dist(&f, 3.0 - w, 0.5, q).min(circle_dist(&f, 3.0 + w, 0.5, q));
        assert_eq!(r.branches.len(), 2, "seed {seed}");
        for b in &r.branches {
            assert!(b.closed);
            assert!(b.dist_curve_max.is_some_and(|x| x <= tol));
            let (worst, cubic) = pieces_off(b, &dist);
            assert!(cubic && worst <= tol, "seed {seed}: {worst:.3e}");
        }
        assert!(r.coverage.as_ref().unwrap().no_missed_branches);
    }
}

/// A cylinder of radius 1 in a rotated frame cut by the plane `z' = tan 60° · x'`: the
/// ellipse `(cos a, sin a, tan 60° cos a)`, whose curvature varies, so the pieces between the
/// traced points are split (points inserted) at tol 1e-9. Every piece within tol of the
/// ellipse at 64 samples (distance by a scan of the ellipse's parameter refined by golden
/// section, in the test).
#[test]
fn ellipses_need_inserted_pieces() {
    let tol = 1e-9;
    let k = 3f64.sqrt();
    for seed in [9u64, 10] {
        let f = rotated(seed);
        let c = cylinder(&f, 1.0, -3.0, 3.0).unwrap();
        let at = |a: f64, b: f64| f.at(a, b, k * a);
        let p = bilinear(at(-1.5, -1.5), at(1.5, -1.5), at(-1.5, 1.5), at(1.5, 1.5)).unwrap();
        let r = run(&c, &p, tol, Pieces::Cubic);
        let local = |q: &[f64; 3]| {
            let d: [f64; 3] = std::array::from_fn(|i| q[i] - f.o[i]);
            let dot = |u: &[f64; 3]| d[0] * u[0] + d[1] * u[1] + d[2] * u[2];
            [dot(&f.x), dot(&f.y), dot(&f.z)]
        };
        let dist = |q: &[f64; 3]| {
            let x = local(q);
            scan_min(&|a: f64| {
                ((a.cos() - x[0]).powi(2) + (a.sin() - x[1]).powi(2) + (k * a.cos() - x[2]).powi(2))
                    .sqrt()
            })
        };
        assert_eq!(r.branches.len(), 1, "seed {seed}");
        let b = &r.branches[0];
        assert!(
            b.closed && b.inserted_points > 0,
            "seed {seed}: {} inserted",
            b.inserted_points
        );
        assert!(b.dist_curve_max.is_some_and(|x| x <= tol));
        let (worst, cubic) = pieces_off(b, &dist);
        assert!(
            cubic && worst <= tol,
            "seed {seed}: a piece {worst:.3e} from the ellipse"
        );
        assert!(r.coverage.as_ref().unwrap().no_missed_branches);
    }
}

/// Two cylinders of radius 1 in a rotated frame, the axes along its z and x axes: the
/// ellipses `(cos a, sin a, ±cos a)` (in the frame), crossing at the branch points
/// `(0, ±1, 0)`. Four open branches between the branch points, every point certified within
/// tol, every piece within tol of the nearer ellipse at 64 samples (scanned distance, in the
/// test), coverage certified; and fewer than 500 points (379 here): without the thinning of
/// the traced points 638, with each chord next to a branch point split by the chords' square
/// law 749.
#[test]
fn crossed_cylinders_in_cubic_pieces() {
    let tol = 1e-7;
    let f = rotated(3);
    let g = Frame {
        o: f.o,
        x: f.y,
        y: f.z,
        z: f.x,
    };
    let (c1, c2) = (
        cylinder(&f, 1.0, -2.0, 2.0).unwrap(),
        cylinder(&g, 1.0, -2.0, 2.0).unwrap(),
    );
    let r = run(&c1, &c2, tol, Pieces::Cubic);
    let dist = |q: &[f64; 3]| {
        let d: [f64; 3] = std::array::from_fn(|i| q[i] - f.o[i]);
        let dot = |u: &[f64; 3]| d[0] * u[0] + d[1] * u[1] + d[2] * u[2];
        let x = [dot(&f.x), dot(&f.y), dot(&f.z)];
        [1.0, -1.0]
            .map(|s: f64| {
                scan_min(&|a: f64| {
                    ((a.cos() - x[0]).powi(2)
                        + (a.sin() - x[1]).powi(2)
                        + (s * a.cos() - x[2]).powi(2))
                    .sqrt()
                })
            })
            .into_iter()
            .fold(f64::INFINITY, f64::min)
    };
    assert_eq!(r.branches.len(), 4);
    let mut points = 0;
    for b in &r.branches {
        assert!(!b.closed);
        assert!(b.dist_curve_max.is_some_and(|x| x <= tol));
        let (worst, cubic) = pieces_off(b, &dist);
        assert!(
            cubic && worst <= tol,
            "a piece {worst:.3e} from the ellipses"
        );
        points += b.points.len();
    }
    assert!(r.coverage.as_ref().unwrap().no_missed_branches);
    assert!(points < 500, "{points} points");
}

/// The biquadratic dome `z = r² − ((x − ½)² + (y − ½)²)` over the unit square against the
/// plane `z = 0`: the circle of radius r about `(½, ½, 0)`, where the surfaces meet at an
/// angle whose tangent is `2r`. Few traced points (long pieces, where the midpoint alone can
/// be within tol while the quarters are not): every piece within tol at 64 samples.
#[test]
fn dome_loops_in_cubic_pieces() {
    let tol = 1e-7;
    for radius in [0.2, 0.1, 0.05] {
        let (dome, plane) = (
            common::shapes::dome(radius * radius, 1.0),
            common::shapes::square(5.0),
        );
        let r = run(&dome, &plane, tol, Pieces::Cubic);
        let dist = |q: &[f64; 3]| {
            let rho = ((q[0] - 0.5).powi(2) + (q[1] - 0.5).powi(2)).sqrt();
            ((rho - radius).powi(2) + q[2] * q[2]).sqrt()
        };
        assert_eq!(r.branches.len(), 1, "r {radius}");
        let b = &r.branches[0];
        assert!(b.closed && b.dist_curve_max.is_some_and(|x| x <= tol));
        let (worst, cubic) = pieces_off(b, &dist);
        assert!(
            cubic && worst <= tol,
            "r {radius}: a piece {worst:.3e} from the circle"
        );
        assert!(
            r.coverage.as_ref().unwrap().no_missed_branches,
            "r {radius}"
        );
    }
}

/// `certify-ssi` reads a result in cubic pieces as its pieces (sampled within tol/4 of them)
/// and checks every sample with its own global, certified closest points: the unit sphere's
/// cut by z = 0 (tol 1e-5) is accepted (exit 0, every sample within tol of the curve). A result whose
/// tangents are turned by 90° (pieces bulging off the circle) is rejected (exit 3).
#[test]
fn certify_ssi_checks_the_pieces() {
    let dir = std::env::temp_dir().join(format!("vericad-cubic-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let data = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data");
    let sphere = data.join("public/gmsh-sphere_Rhino3D_default.igs");
    let plane = data.join("faulty/plane-z0.step");
    let (sphere, plane) = (sphere.to_str().unwrap(), plane.to_str().unwrap());
    let out = dir.join("r.json");
    let out_s = out.to_str().unwrap();
    let (code, _, err) = common::cli::vericad(&[
        "ssi", sphere, plane, "--tol", "1e-5", "--pieces", "cubic", "--out", out_s,
    ]);
    assert_eq!(code, 0, "{err}");
    let check = |curves: &str| {
        common::cli::vericad(&[
            "certify-ssi",
            sphere,
            plane,
            "--curves",
            curves,
            "--tol",
            "1e-5",
            "--json",
        ])
    };
    let (code, text, err) = check(out_s);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    let n = v["points_checked"].as_u64().unwrap();
    let r: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    let pts = r["summary"]["points"].as_u64().unwrap();
    assert!(n > 4 * pts, "{n} samples checked for {pts} points");
    // Tangents turned about the z axis by 90°: still horizontal, now radial.
    let mut bad = r.clone();
    for b in bad["pairs"][0]["branches"].as_array_mut().unwrap() {
        for j in b["tangents"].as_array_mut().unwrap() {
            let t = j["t"]
                .as_array()
                .unwrap()
                .iter()
                .map(|x| x.as_f64().unwrap())
                .collect::<Vec<_>>();
            j["t"] = serde_json::json!([0.8 * t[1] + 0.6 * t[0], -0.8 * t[0] + 0.6 * t[1], t[2]]);
        }
    }
    let bad_path = dir.join("bad.json");
    std::fs::write(&bad_path, serde_json::to_string(&bad).unwrap()).unwrap();
    let (code, text, _) = check(bad_path.to_str().unwrap());
    assert_eq!(code, 3, "{text}");
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    assert!(v["curves_off"].as_u64().unwrap() > 0, "{text}");
    std::fs::remove_dir_all(&dir).ok();
}

/// No two consecutive output points coincide (traced points on both sides of a knot line or
/// mesh vertex refine to one curve point and are merged), with chords and with cubic pieces:
/// planes crossing at 0.1 rad in a rotated frame (a straight segment, many mesh vertices on
/// it) and a rotated sphere cut at h = 1.5.
#[test]
fn no_repeated_points() {
    let f = rotated(3);
    let at = |x: f64, y: f64, z: f64| f.at(x, y, z);
    let a = bilinear(
        at(-1.0, -1.0, 0.0),
        at(1.0, -1.0, 0.0),
        at(-1.0, 1.0, 0.0),
        at(1.0, 1.0, 0.0),
    )
    .unwrap();
    let t = 0.1f64.tan();
    let b = bilinear(
        at(-0.9, -1.2, -0.9 * t),
        at(0.9, -1.2, 0.9 * t),
        at(-0.9, 1.2, -0.9 * t),
        at(0.9, 1.2, 0.9 * t),
    )
    .unwrap();
    let s = sphere(&f, 2.0).unwrap();
    let p = cut(&f, 1.5, 3.0);
    for (x, y) in [(&a, &b), (&s, &p)] {
        for pieces in [Pieces::Chords, Pieces::Cubic] {
            let r = run(x, y, 1e-7, pieces);
            assert!(!r.branches.is_empty());
            for br in &r.branches {
                let n = br.points.len();
                let spans = if br.closed { n } else { n - 1 };
                for k in 0..spans {
                    let (u, v) = (br.points[k], br.points[(k + 1) % n]);
                    assert!(
                        u != v,
                        "{pieces:?}: points {k} and {} coincide at {u:?}",
                        (k + 1) % n
                    );
                }
            }
        }
    }
}
