//! Singular points (touching points, branch points) against constructions whose singular
//! points are known exactly: a sphere touching a plane (one touching point), a torus cut by
//! the plane tangent to its inner equator (a figure eight: one branch point), two equal
//! cylinders with perpendicular axes (two ellipses crossing at two branch points). Every
//! proven claim is checked against the construction: the true point lies at the surface
//! image of the proven root box. Cases without a singular point (transversal cuts, a plane
//! above a sphere) must get no claim, and degenerate contacts (a flat spot of order four, a
//! cylinder lying on a plane) must be left uncertified.

mod common;
use common::shapes::{exact_sphere, rotated};
use vericad::spline::NurbsSurface;
use vericad::spline::construct::{Frame, bilinear, cylinder, sphere, torus};
use vericad::ssi::report::{SingularKind, SingularOut, SingularReason};
use vericad::ssi::singular::classify;
use vericad::ssi::{PairOut, SsiParams, intersect_pair_canonical};

const TOL: f64 = 1e-7;

fn run(a: &NurbsSurface<f64, 3>, b: &NurbsSurface<f64, 3>) -> PairOut {
    let prm = SsiParams {
        tol: TOL,
        ..Default::default()
    };
    intersect_pair_canonical(a, b, (0, 1), &prm, None).expect("intersection runs")
}

fn dist(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    (0..3).map(|k| (a[k] - b[k]).powi(2)).sum::<f64>().sqrt()
}

/// The proven singular points of a pair: (kind, certificate, point).
fn proven(r: &PairOut) -> Vec<(SingularKind, SingularOut, [f64; 3])> {
    r.touch_points
        .iter()
        .filter_map(|t| {
            let s = t.singular.clone()?;
            (s.kind != SingularKind::Uncertified).then_some((s.kind, s, t.point))
        })
        .collect()
}

/// The surfaces evaluated at the centre of the proven root box both lie within `d` of
/// `truth`; the root box is inside the isolating box.
fn check_at(
    s: &SingularOut,
    a: &NurbsSurface<f64, 3>,
    b: &NurbsSurface<f64, 3>,
    truth: &[f64; 3],
    d: f64,
) {
    let (ra, rb) = (s.root_a.unwrap(), s.root_b.unwrap());
    let (xa, xb) = (s.box_a.unwrap(), s.box_b.unwrap());
    for (r, x) in [(ra, xa), (rb, xb)] {
        assert!(
            x[0] <= r[0] && r[1] <= x[1] && x[2] <= r[2] && r[3] <= x[3],
            "{r:?} {x:?}"
        );
    }
    // Closed surfaces (domains [0, 1] here): a parameter beyond the seam names the point one
    // period away.
    let w = |x: f64| {
        if x < 0.0 {
            x + 1.0
        } else if x > 1.0 {
            x - 1.0
        } else {
            x
        }
    };
    let c = |r: [f64; 4]| (w(0.5 * (r[0] + r[1])), w(0.5 * (r[2] + r[3])));
    let (ua, va) = c(ra);
    let (ub, vb) = c(rb);
    let (pa, pb) = (a.eval(&ua, &va), b.eval(&ub, &vb));
    assert!(
        dist(&pa, truth) <= d && dist(&pb, truth) <= d,
        "{pa:?} {pb:?} vs {truth:?}"
    );
    let dd = s.distance.unwrap();
    assert!(dd[0] <= dd[1] && dd[1] <= 1e-12, "{dd:?}");
}

/// The plane through `p` spanned by `e1`, `e2`: corners `p ± e1 ± e2`.
fn plane(p: [f64; 3], e1: [f64; 3], e2: [f64; 3]) -> NurbsSurface<f64, 3> {
    let at = |a: f64, b: f64| -> [f64; 3] { std::array::from_fn(|k| p[k] + a * e1[k] + b * e2[k]) };
    bilinear(at(-1.0, -1.0), at(1.0, -1.0), at(-1.0, 1.0), at(1.0, 1.0)).unwrap()
}

// ---------------------------------------------------------------------------------------
// Sphere and plane.

/// The exact sphere of radius 3 and the plane tangent to it at (1, 2, 2) (all data exact
/// integers): one proven touching point there, no curve.
#[test]
fn exact_sphere_touching_a_plane() {
    let s = exact_sphere(3.0);
    let p = plane([1.0, 2.0, 2.0], [4.0, -2.0, 0.0], [2.0, 4.0, -5.0]);
    let r = run(&s, &p);
    let got = proven(&r);
    for t in &r.touch_points {
        println!("{:?} {:?}", t.point, t.singular);
    }
    assert!(r.branches.is_empty(), "{} branches", r.branches.len());
    assert_eq!(got.len(), 1);
    assert_eq!(got[0].0, SingularKind::TouchingPoint);
    check_at(&got[0].1, &s, &p, &[1.0, 2.0, 2.0], 1e-9);
    assert!(
        r.touch_points
            .iter()
            .all(|t| t.singular.as_ref().unwrap().kind != SingularKind::Uncertified)
    );
}

/// Tangent at (0, 2, 0), where the sphere's parametrisation has knot lines of both directions
/// (the circle's joints, only C0 as B-splines): proven per piece.
#[test]
fn exact_sphere_touching_on_knot_lines() {
    let s = exact_sphere(2.0);
    let p = plane([0.0, 2.0, 0.0], [3.0, 0.0, 0.0], [0.0, 0.0, 3.0]);
    let r = run(&s, &p);
    let got = proven(&r);
    assert!(r.branches.is_empty());
    assert_eq!(got.len(), 1);
    assert_eq!(got[0].0, SingularKind::TouchingPoint);
    assert!(got[0].1.pieces >= 2, "{:?}", got[0].1);
    check_at(&got[0].1, &s, &p, &[0.0, 2.0, 0.0], 1e-9);
    // Direct: the same from the exact parameters (u = 1/4, v = 1/2; the plane's centre).
    let c = classify(&s, &p, &[0.25, 0.5], &[0.5, 0.5], TOL);
    assert_eq!(c.kind, SingularKind::TouchingPoint, "{c:?}");
}

/// Spheres in rotated frames touched by the plane z = top: the touching point is at a
/// generic point of the parametrisation.
#[test]
fn rotated_spheres_touching_a_plane() {
    for seed in 1..=4u64 {
        let f = rotated(seed);
        let s = sphere(&f, 2.0).unwrap();
        let top = [f.o[0], f.o[1], f.o[2] + 2.0];
        let p = plane(top, [3.0, 0.0, 0.0], [0.0, 3.0, 0.0]);
        let r = run(&s, &p);
        let got = proven(&r);
        println!(
            "seed {seed}: {} touch points, {} proven, {} branches",
            r.touch_points.len(),
            got.len(),
            r.branches.len()
        );
        assert_eq!(got.len(), 1, "{seed}");
        assert_eq!(got[0].0, SingularKind::TouchingPoint);
        check_at(&got[0].1, &s, &p, &top, 1e-9);
    }
}

/// A plane crossing the sphere: no singular point claimed.
#[test]
fn transversal_cut_has_no_singular_point() {
    for (seed, h) in [(1u64, 0.5), (2, -1.2), (3, 1.9)] {
        let f = rotated(seed);
        let s = sphere(&f, 2.0).unwrap();
        let p = plane(
            f.at(0.0, 0.0, h),
            f.x.map(|c| 3.0 * c),
            f.y.map(|c| 3.0 * c),
        );
        let r = run(&s, &p);
        assert_eq!(r.branches.len(), 1, "{seed}");
        assert!(proven(&r).is_empty(), "{seed} {h}");
    }
    let r = run(
        &exact_sphere(2.0),
        &plane([0.0, 0.0, 0.7], [3.0, 0.0, 0.0], [0.0, 3.0, 0.0]),
    );
    assert!(proven(&r).is_empty());
}

/// A plane 1e-3 above the sphere: no contact claimed. From the exact top's parameters the
/// critical point is proven, with the distance 1e-3 enclosed: not a touching point.
#[test]
fn plane_above_the_sphere_is_no_contact() {
    let s = exact_sphere(2.0);
    let p = plane([0.0, 2.001, 0.0], [3.0, 0.0, 0.0], [0.0, 0.0, 3.0]);
    let r = run(&s, &p);
    assert!(r.branches.is_empty());
    assert!(proven(&r).is_empty());
    let c = classify(&s, &p, &[0.25, 0.5], &[0.5, 0.5], TOL);
    assert_eq!(c.kind, SingularKind::Uncertified);
    assert_eq!(c.reason, Some(SingularReason::DistanceAboveTol));
    let d = c.distance.unwrap();
    assert!(
        d[0] <= 1e-3 + 1e-12 && d[1] >= 1e-3 - 1e-12 && d[1] - d[0] < 1e-12,
        "{d:?}"
    );
    for f in [rotated(5), rotated(6)] {
        let s = sphere(&f, 2.0).unwrap();
        let top = [f.o[0], f.o[1], f.o[2] + 2.0 + 1e-3];
        let r = run(&s, &plane(top, [3.0, 0.0, 0.0], [0.0, 3.0, 0.0]));
        assert!(r.branches.is_empty());
        assert!(proven(&r).is_empty());
    }
}

// ---------------------------------------------------------------------------------------
// Torus: the plane tangent to the inner equator cuts a figure eight.

#[test]
fn torus_figure_eight_branch_point() {
    for (alpha, psi) in [(0.3f64, 1.1f64), (0.0, 0.45)] {
        let f = Frame {
            o: [0.25, -0.5, 0.125],
            x: [alpha.cos(), alpha.sin(), 0.0],
            y: [-alpha.sin(), alpha.cos(), 0.0],
            z: [0.0, 0.0, 1.0],
        };
        let (big, small) = (2.0, 1.0);
        let t = torus(&f, big, small).unwrap();
        // The inner equator point in direction ψ; the plane tangent there is spanned by the
        // circle's tangent and the axis.
        let q = f.at((big - small) * psi.cos(), (big - small) * psi.sin(), 0.0);
        let tan: [f64; 3] =
            std::array::from_fn(|k| 3.5 * (-psi.sin() * f.x[k] + psi.cos() * f.y[k]));
        let p = plane(q, tan, f.z.map(|c| 1.5 * c));
        let r = run(&t, &p);
        let got = proven(&r);
        for tp in &r.touch_points {
            println!("{:?} ends {} {:?}", tp.point, tp.branch_ends, tp.singular);
        }
        assert_eq!(got.len(), 1, "{alpha} {psi}");
        assert_eq!(got[0].0, SingularKind::BranchPoint);
        // The inner equator lies on the profile circle's joint: proven per piece.
        assert!(got[0].1.pieces >= 2);
        check_at(&got[0].1, &t, &p, &q, 1e-9);
    }
}

// ---------------------------------------------------------------------------------------
// Two equal cylinders with perpendicular axes: ellipses crossing at (0, 0, ±1).

fn cylinders(alpha: f64, beta: f64) -> (NurbsSurface<f64, 3>, NurbsSurface<f64, 3>) {
    let fa = Frame {
        o: [0.0; 3],
        x: [0.0, alpha.cos(), alpha.sin()],
        y: [0.0, -alpha.sin(), alpha.cos()],
        z: [1.0, 0.0, 0.0],
    };
    let fb = Frame {
        o: [0.0; 3],
        x: [beta.cos(), 0.0, -beta.sin()],
        y: [-beta.sin(), 0.0, -beta.cos()],
        z: [0.0, 1.0, 0.0],
    };
    (
        cylinder(&fa, 1.0, -2.0, 2.0).unwrap(),
        cylinder(&fb, 1.0, -2.0, 2.0).unwrap(),
    )
}

#[test]
fn perpendicular_cylinders_branch_points() {
    for (alpha, beta) in [(0.3, 0.7), (0.0, 0.0)] {
        let (a, b) = cylinders(alpha, beta);
        let r = run(&a, &b);
        let got = proven(&r);
        for tp in &r.touch_points {
            println!("{:?} ends {} {:?}", tp.point, tp.branch_ends, tp.singular);
        }
        assert_eq!(got.len(), 2, "{alpha} {beta}");
        for truth in [[0.0, 0.0, 1.0], [0.0, 0.0, -1.0]] {
            let at: Vec<_> = got.iter().filter(|g| dist(&g.2, &truth) < 1e-3).collect();
            assert_eq!(at.len(), 1, "{truth:?}");
            assert_eq!(at[0].0, SingularKind::BranchPoint);
            check_at(&at[0].1, &a, &b, &truth, 1e-9);
        }
    }
}

// ---------------------------------------------------------------------------------------
// Degenerate contacts: never proven.

/// z = x⁴ + y⁴ over [-1, 1]² (a Bézier patch of degree 4: the Bernstein coefficients of
/// (2t − 1)⁴ are 1, −1, 1, −1, 1) touching z = 0 at the origin with zero curvature.
fn quartic_bowl() -> NurbsSurface<f64, 3> {
    let b = [1.0, -1.0, 1.0, -1.0, 1.0];
    let x = [-1.0, -0.5, 0.0, 0.5, 1.0];
    let mut pts = Vec::new();
    for i in 0..5 {
        for j in 0..5 {
            pts.push([x[i], x[j], b[i] + b[j]]);
        }
    }
    let k = vec![0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0, 1.0];
    NurbsSurface::new(k.clone(), 4, k, 4, 5, 5, pts, vec![1.0; 25]).unwrap()
}

#[test]
fn flat_spot_of_order_four_is_uncertified() {
    let s = quartic_bowl();
    // The construction: the surface is z = x⁴ + y⁴.
    for (u, v) in [(0.3, 0.8), (0.5, 0.5), (0.9, 0.1)] {
        let p = s.eval(&u, &v);
        let (x, y) = (2.0 * u - 1.0, 2.0 * v - 1.0);
        assert!((p[2] - (x.powi(4) + y.powi(4))).abs() < 1e-14);
    }
    let p = plane([0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0]);
    let c = classify(&s, &p, &[0.5, 0.5], &[0.5, 0.5], TOL);
    assert_eq!(c.kind, SingularKind::Uncertified, "{c:?}");
    let c = classify(&s, &p, &[0.5004, 0.4997], &[0.5, 0.5001], TOL);
    assert_eq!(c.kind, SingularKind::Uncertified, "{c:?}");
    let r = run(&s, &p);
    for t in &r.touch_points {
        println!("{:?} {:?}", t.point, t.singular);
    }
    assert!(proven(&r).is_empty());
}

/// A cylinder lying on a plane touches it along a segment: no isolated touching point.
#[test]
fn cylinder_on_a_plane_is_uncertified() {
    let f = Frame {
        o: [0.0, 0.0, 1.0],
        x: [0.0, 1.0, 0.0],
        y: [0.0, 0.0, 1.0],
        z: [1.0, 0.0, 0.0],
    };
    let c = cylinder(&f, 1.0, -2.0, 2.0).unwrap();
    let p = plane([0.0, 0.0, 0.0], [3.0, 0.0, 0.0], [0.0, 3.0, 0.0]);
    // The bottom line (0, 0, 0) + x e_x is at u = 3/4 on the cylinder.
    let b = c.eval(&0.75, &0.5);
    assert!(dist(&b, &[0.0, 0.0, 0.0]) < 1e-15);
    for v in [0.5, 0.3, 0.71] {
        let k = classify(&c, &p, &[0.75, v], &[0.5 + (v - 0.5) * 4.0 / 6.0, 0.5], TOL);
        assert_eq!(k.kind, SingularKind::Uncertified, "{k:?}");
    }
    let r = run(&c, &p);
    assert!(proven(&r).is_empty());
}

// ---------------------------------------------------------------------------------------
// The run's summary and report.

fn run_models(a: NurbsSurface<f64, 3>, b: NurbsSurface<f64, 3>) -> vericad::ssi::SsiResult {
    use vericad::model::{Model, Surface};
    let m = |s| Model {
        surfaces: vec![Surface::new("face", s)],
        ..Default::default()
    };
    let prm = SsiParams {
        tol: TOL,
        ..Default::default()
    };
    vericad::ssi::intersect_models(&m(a), Some(&m(b)), &prm, &|_, _| {}).unwrap()
}

/// Proven singular points are counted and printed; an uncertified one makes the run
/// uncertified.
#[test]
fn summary_counts_singular_points() {
    let (a, b) = cylinders(0.3, 0.7);
    let r = run_models(a, b);
    assert_eq!(r.summary.singular_points_proven, 2);
    assert_eq!(r.summary.singular_points_uncertified, 0);
    let text = r.to_string();
    assert_eq!(text.matches("branch point, proven").count(), 2, "{text}");
    assert!(text.contains("singular points: 2 proven"), "{text}");

    let p = plane([0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0]);
    let r = run_models(quartic_bowl(), p);
    assert_eq!(r.summary.singular_points_proven, 0);
    if r.summary.singular_points_uncertified > 0 {
        assert!(!r.summary.certified);
        assert!(r.to_string().contains("uncertified ("));
    }
    println!("{r}");
}

/// The exact sphere touching z = 2 at its north pole, where its parametrisation degenerates
/// (`S_u = 0`): the tangency system is degenerate in both role assignments, so the point is
/// left uncertified; a claim, if any, would have to be at the pole.
#[test]
fn touching_at_a_pole_is_not_claimed_falsely() {
    let s = exact_sphere(2.0);
    let p = plane([0.0, 0.0, 2.0], [3.0, 0.0, 0.0], [0.0, 3.0, 0.0]);
    let r = run(&s, &p);
    for t in &r.touch_points {
        println!("{:?} {:?}", t.point, t.singular);
    }
    for (_, c, _) in proven(&r) {
        check_at(&c, &s, &p, &[0.0, 0.0, 2.0], 1e-9);
    }
    let c = classify(&s, &p, &[0.3, 1.0], &[0.5, 0.5], TOL);
    println!("{c:?}");
    assert_eq!(c.kind, SingularKind::Uncertified);
}

// ---------------------------------------------------------------------------------------
// More placements: every claim at the true point.

/// Unit vectors `e1`, `e2` orthogonal to the unit vector `d` and to each other.
fn tangents(d: &[f64; 3]) -> ([f64; 3], [f64; 3]) {
    let a = if d[0].abs() < 0.6 {
        [1.0, 0.0, 0.0]
    } else {
        [0.0, 1.0, 0.0]
    };
    let cross = |a: &[f64; 3], b: &[f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let e1 = cross(d, &a);
    let l = (e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]).sqrt();
    let e1 = e1.map(|c| c / l);
    (e1, cross(d, &e1))
}

/// Spheres touched by planes in many directions, cylinders crossing at many angles, a torus
/// of other proportions: the kind is proven where the construction has its singular point.
#[test]
fn many_placements() {
    for seed in 7..=12u64 {
        let f = rotated(seed);
        let s = sphere(&f, 1.5).unwrap();
        let t = seed as f64;
        let d = [
            t.cos() * (0.3 * t).sin(),
            t.sin() * (0.3 * t).sin(),
            (0.3 * t).cos(),
        ];
        let l = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        let d = d.map(|c| c / l);
        let q: [f64; 3] = std::array::from_fn(|k| f.o[k] + 1.5 * d[k]);
        let (e1, e2) = tangents(&d);
        let p = plane(q, e1.map(|c| 2.5 * c), e2.map(|c| 2.5 * c));
        let r = run(&s, &p);
        let got = proven(&r);
        assert_eq!(got.len(), 1, "sphere {seed}");
        assert_eq!(got[0].0, SingularKind::TouchingPoint);
        check_at(&got[0].1, &s, &p, &q, 1e-9);
    }
    for (alpha, beta) in [(0.1, 1.3), (2.0, -0.4), (0.785, 2.9)] {
        let (a, b) = cylinders(alpha, beta);
        let r = run(&a, &b);
        let got = proven(&r);
        assert_eq!(got.len(), 2, "cylinders {alpha} {beta}");
        for truth in [[0.0, 0.0, 1.0], [0.0, 0.0, -1.0]] {
            let at: Vec<_> = got
                .iter()
                .filter(|g| dist(&g.1.root_point.unwrap(), &truth) < 1e-9)
                .collect();
            assert_eq!(at.len(), 1, "{truth:?}");
            assert_eq!(at[0].0, SingularKind::BranchPoint);
            check_at(&at[0].1, &a, &b, &truth, 1e-9);
        }
    }
    let f = rotated(3);
    let t = torus(&f, 3.0, 1.0).unwrap();
    let q = f.at(2.0, 0.0, 0.0);
    let p = plane(q, f.y.map(|c| 4.5 * c), f.z.map(|c| 1.5 * c));
    let r = run(&t, &p);
    for tp in &r.touch_points {
        println!("{:?} ends {} {:?}", tp.point, tp.branch_ends, tp.singular);
    }
    let got = proven(&r);
    assert_eq!(got.len(), 1);
    assert_eq!(got[0].0, SingularKind::BranchPoint);
    check_at(&got[0].1, &t, &p, &q, 1e-9);
}

/// The figure-eight's branch point on the torus's seam (u = 0, a closed direction): the box
/// runs across the seam, proven in pieces. The point is a mesh vertex there, found from the
/// surface normals at the vertices.
#[test]
fn branch_point_on_the_seam() {
    let f = Frame {
        o: [0.25, -0.5, 0.125],
        x: [0.3f64.cos(), 0.3f64.sin(), 0.0],
        y: [-0.3f64.sin(), 0.3f64.cos(), 0.0],
        z: [0.0, 0.0, 1.0],
    };
    let t = torus(&f, 2.0, 1.0).unwrap();
    let q = f.at(1.0, 0.0, 0.0);
    let p = plane(q, f.y.map(|c| 3.5 * c), f.z.map(|c| 1.5 * c));
    for seed_u in [0.0, 1.0, 1e-9, 1.0 - 1e-9] {
        let c = classify(&t, &p, &[seed_u, 0.5], &[0.5, 0.5], TOL);
        println!("{seed_u}: {c:?}");
        assert_eq!(c.kind, SingularKind::BranchPoint, "{c:?}");
        check_at(&c, &t, &p, &q, 1e-9);
    }
    let r = run(&t, &p);
    println!(
        "{} branches, ends {:?}",
        r.branches.len(),
        r.branches
            .iter()
            .map(|b| b.ends.clone())
            .collect::<Vec<_>>()
    );
    for tp in &r.touch_points {
        println!("{:?} ends {} {:?}", tp.point, tp.branch_ends, tp.singular);
    }
    let got = proven(&r);
    assert_eq!(got.len(), 1);
    assert_eq!(got[0].0, SingularKind::BranchPoint);
    check_at(&got[0].1, &t, &p, &q, 1e-9);
}
