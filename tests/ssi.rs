//! Surface–surface intersection: analytic cases with known answers (exact NURBS forms), the
//! topology invariants, determinism and symmetry.

use vericad::spline::NurbsSurface;
use vericad::spline::construct::{Frame, bilinear, cylinder, sphere};
use vericad::ssi::{EndKind, PairOut, SsiParams, intersect_pair_canonical};

const Z: Frame = Frame {
    o: [0.0, 0.0, 0.0],
    x: [1.0, 0.0, 0.0],
    y: [0.0, 1.0, 0.0],
    z: [0.0, 0.0, 1.0],
};

fn run(a: &NurbsSurface<f64, 3>, b: &NurbsSurface<f64, 3>, tol: f64) -> PairOut {
    let prm = SsiParams {
        tol,
        ..Default::default()
    };
    intersect_pair_canonical(a, b, (0, 1), &prm, None).expect("intersection runs")
}

fn plane_z(h: f64, s: f64) -> NurbsSurface<f64, 3> {
    bilinear([-s, -s, h], [s, -s, h], [-s, s, h], [s, s, h]).unwrap()
}

fn norm(p: &[f64; 3]) -> f64 {
    (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt()
}

/// Sphere of radius 2 cut by the plane z = h: one closed circle of radius sqrt(4 - h²).
fn plane_sphere(h: f64) {
    let tol = 1e-7;
    let r = run(&sphere(&Z, 2.0).unwrap(), &plane_z(h, 3.0), tol);
    assert_eq!(r.branches.len(), 1, "{h}: {:?}", r.stats);
    let b = &r.branches[0];
    assert!(b.closed, "{h}: the circle is closed");
    let rho = (4.0 - h * h).sqrt();
    for p in &b.points {
        let d = ((p[0] * p[0] + p[1] * p[1]).sqrt() - rho)
            .abs()
            .max((p[2] - h).abs());
        assert!(
            d <= 2.0 * tol,
            "{h}: point {p:?} is {d} off the exact circle"
        );
    }
    assert!(
        b.dist_a_max <= tol && b.dist_b_max <= tol,
        "{h}: proven {} {}",
        b.dist_a_max,
        b.dist_b_max
    );
    assert!(b.max_chord_deviation <= tol);
    assert!(b.points.len() >= 8);
    let fit = b.fit.as_ref().expect("every branch is fitted");
    assert!(
        fit.max_deviation_at_points <= 1e-12,
        "{h}: {}",
        fit.max_deviation_at_points
    );
}

#[test]
fn plane_cuts_sphere_in_a_circle() {
    plane_sphere(0.7);
}

#[test]
fn plane_through_the_equator_lattice() {
    // z = 0 holds a whole row of mesh vertices of the sphere: exact degeneracy, resolved by
    // symbolic perturbation into one closed branch.
    plane_sphere(0.0);
}

#[test]
fn spheres_apart_do_not_meet() {
    let far = Frame {
        o: [5.0, 0.0, 0.0],
        ..Z
    };
    let r = run(&sphere(&Z, 2.0).unwrap(), &sphere(&far, 2.0).unwrap(), 1e-6);
    assert!(r.branches.is_empty() && r.touch_points.is_empty());
}

/// Cylinders about z and x, radii `ra`, `rb`.
fn cylinders(ra: f64, rb: f64) -> (NurbsSurface<f64, 3>, NurbsSurface<f64, 3>) {
    let fx = Frame {
        o: [-3.0, 0.0, 0.0],
        x: [0.0, 1.0, 0.0],
        y: [0.0, 0.0, 1.0],
        z: [1.0, 0.0, 0.0],
    };
    (
        cylinder(&Z, ra, -3.0, 3.0).unwrap(),
        cylinder(&fx, rb, 0.0, 6.0).unwrap(),
    )
}

#[test]
fn unequal_cylinders_meet_in_two_closed_loops() {
    let tol = 1e-7;
    let (a, b) = cylinders(1.0, 0.6);
    let r = run(&a, &b, tol);
    assert_eq!(r.branches.len(), 2, "{:?}", r.stats);
    for br in &r.branches {
        assert!(br.closed);
        for p in &br.points {
            // On both cylinders: x² + y² = 1, y² + z² = 0.36.
            let e1 = ((p[0] * p[0] + p[1] * p[1]).sqrt() - 1.0).abs();
            let e2 = ((p[1] * p[1] + p[2] * p[2]).sqrt() - 0.6).abs();
            assert!(e1.max(e2) <= 2.0 * tol, "{p:?}: {e1} {e2}");
        }
        assert!(br.dist_a_max <= tol && br.dist_b_max <= tol);
    }
    // One loop on each side x > 0 and x < 0.
    let sides: Vec<f64> = r.branches.iter().map(|b| b.points[0][0].signum()).collect();
    assert!(sides[0] != sides[1]);
}

#[test]
fn steinmetz_equal_cylinders_cross_at_branch_points() {
    // Two ellipses in the planes z = x and z = -x, crossing at (0, ±1, 0), where the
    // cylinders are tangent: four arcs, each from one branch point to the other.
    let tol = 1e-6;
    let (a, b) = cylinders(1.0, 1.0);
    let r = run(&a, &b, tol);
    assert_eq!(r.branches.len(), 4, "{:?}", r.stats);
    let singular: Vec<_> = r
        .touch_points
        .iter()
        .filter(|t| t.branch_ends > 2)
        .collect();
    assert_eq!(singular.len(), 2, "two branch points");
    for t in &singular {
        assert_eq!(t.branch_ends, 4);
        let p = t.point;
        assert!(
            p[0].abs() < 1e-6 && (p[1].abs() - 1.0).abs() < 1e-6 && p[2].abs() < 1e-6,
            "{p:?}"
        );
    }
    for br in &r.branches {
        assert!(!br.closed);
        assert_eq!(br.ends, vec![EndKind::BranchPoint, EndKind::BranchPoint]);
        let (first, last) = (br.points[0], br.points[br.points.len() - 1]);
        assert!(
            (first[1] * last[1]) < 0.0,
            "an arc joins the two branch points"
        );
        for p in &br.points {
            let e1 = ((p[0] * p[0] + p[1] * p[1]).sqrt() - 1.0).abs();
            let e2 = ((p[1] * p[1] + p[2] * p[2]).sqrt() - 1.0).abs();
            // On one of the planes z = ±x.
            let e3 = (p[2].abs() - p[0].abs()).abs();
            assert!(e1.max(e2).max(e3) <= 2.0 * tol, "{p:?}: {e1} {e2} {e3}");
        }
        assert!(br.dist_a_max <= tol && br.dist_b_max <= tol);
    }
}

/// `z = x² + y²` over `[-1, 1]²` as a biquadratic Bézier patch (exact).
fn paraboloid() -> NurbsSurface<f64, 3> {
    let c = [-1.0, 0.0, 1.0];
    let z = [1.0, -1.0, 1.0];
    let mut pts = Vec::new();
    for i in 0..3 {
        for j in 0..3 {
            pts.push([c[i], c[j], z[i] + z[j]]);
        }
    }
    let k = vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0];
    NurbsSurface::new(k.clone(), 2, k, 2, 3, 3, pts, vec![1.0; 9]).unwrap()
}

#[test]
fn paraboloid_touching_a_plane_is_a_tangential_contact() {
    let r = run(&paraboloid(), &plane_z(0.0, 2.0), 1e-7);
    assert!(
        r.branches.is_empty(),
        "no curve: {:?}",
        r.branches
            .iter()
            .map(|b| b.points.len())
            .collect::<Vec<_>>()
    );
    assert_eq!(r.touch_points.len(), 1, "{:?}", r.touch_points);
    let t = &r.touch_points[0];
    assert_eq!(t.branch_ends, 0);
    assert!(norm(&t.point) < 1e-6, "{:?}", t.point);
    assert!(t.dist_a.unwrap() <= 1e-7 && t.dist_b.unwrap() <= 1e-7);
    // Lowered, the plane misses; raised, it cuts a circle of radius sqrt(h).
    let miss = run(&paraboloid(), &plane_z(-0.01, 2.0), 1e-7);
    assert!(miss.branches.is_empty() && miss.touch_points.is_empty());
    let cut = run(&paraboloid(), &plane_z(0.25, 2.0), 1e-7);
    assert_eq!(cut.branches.len(), 1);
    assert!(cut.branches[0].closed);
    for p in &cut.branches[0].points {
        assert!(((p[0] * p[0] + p[1] * p[1]).sqrt() - 0.5).abs() <= 2e-7);
    }
}

/// A bicubic surface over `[0, 1]²` (10 × 10 net, z = -0.1) with four isolated bumps.
fn bumpy() -> (NurbsSurface<f64, 3>, Vec<[f64; 2]>) {
    let n = 10;
    let bumps = [(2, 2), (2, 7), (7, 2), (7, 6)];
    let mut pts = Vec::new();
    for i in 0..n {
        for j in 0..n {
            let z = if bumps.contains(&(i, j)) { 0.3 } else { -0.1 };
            pts.push([i as f64 / (n - 1) as f64, j as f64 / (n - 1) as f64, z]);
        }
    }
    let mut k = vec![0.0; 4];
    k.extend((1..n - 3).map(|i| i as f64 / (n - 3) as f64));
    k.extend([1.0; 4]);
    let s = NurbsSurface::new(k.clone(), 3, k, 3, n, n, pts, vec![1.0; n * n]).unwrap();
    let centres = bumps
        .iter()
        .map(|&(i, j)| [i as f64 / 9.0, j as f64 / 9.0])
        .collect();
    (s, centres)
}

#[test]
fn wavy_surface_meets_a_plane_in_several_small_loops() {
    let tol = 1e-7;
    let (s, centres) = bumpy();
    // Lowest bump top (dense sampling of the test surface), minus a little: small loops.
    let peak = |c: &[f64; 2]| {
        let mut m = f64::NEG_INFINITY;
        for i in 0..=100 {
            for j in 0..=100 {
                let (u, v) = (
                    (c[0] - 0.1 + 0.002 * i as f64).clamp(0.0, 1.0),
                    (c[1] - 0.1 + 0.002 * j as f64).clamp(0.0, 1.0),
                );
                m = m.max(s.eval(&u, &v)[2]);
            }
        }
        m
    };
    let h = centres.iter().map(peak).fold(f64::INFINITY, f64::min) - 0.01;
    assert!(h > 0.0);
    let r = run(&s, &plane_z(h, 2.0), tol);
    assert_eq!(r.branches.len(), 4, "{:?}", r.stats);
    let mut hit = [false; 4];
    for br in &r.branches {
        assert!(br.closed);
        assert!(br.dist_a_max <= tol && br.dist_b_max <= tol);
        let n = br.points.len() as f64;
        let c = [
            br.points.iter().map(|p| p[0]).sum::<f64>() / n,
            br.points.iter().map(|p| p[1]).sum::<f64>() / n,
        ];
        let radius = br
            .points
            .iter()
            .map(|p| ((p[0] - c[0]).powi(2) + (p[1] - c[1]).powi(2)).sqrt())
            .fold(0.0, f64::max);
        assert!(radius < 0.1, "small loop: radius {radius}");
        for p in &br.points {
            assert!((p[2] - h).abs() <= 2.0 * tol);
        }
        let k = centres
            .iter()
            .position(|q| ((q[0] - c[0]).powi(2) + (q[1] - c[1]).powi(2)).sqrt() < 0.1)
            .expect("loop around a bump");
        hit[k] = true;
    }
    assert!(hit.iter().all(|h| *h), "one loop per bump");
}

/// Same branches, bit for bit, for (A, B) and (B, A), and between runs.
#[test]
fn symmetric_and_deterministic() {
    let (a, b) = cylinders(1.0, 0.6);
    let ab = run(&a, &b, 1e-7);
    let ba = run(&b, &a, 1e-7);
    let again = run(&a, &b, 1e-7);
    assert_eq!(ab.branches.len(), ba.branches.len());
    for ((x, y), z) in ab.branches.iter().zip(&ba.branches).zip(&again.branches) {
        assert_eq!(x.points, y.points);
        assert_eq!(x.uv_a, y.uv_b);
        assert_eq!(x.uv_b, y.uv_a);
        assert_eq!(x.points, z.points);
        assert_eq!(x.uv_a, z.uv_a);
    }
}

#[test]
fn bad_parameters_are_typed_errors() {
    let (a, b) = cylinders(1.0, 0.6);
    for tol in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        let prm = SsiParams {
            tol,
            ..Default::default()
        };
        assert!(prm.validate().is_err(), "{tol}");
    }
    let prm = SsiParams {
        flatness: Some(f64::NAN),
        ..Default::default()
    };
    assert!(prm.validate().is_err());
    let _ = intersect_pair_canonical(&a, &b, (0, 1), &SsiParams::default(), None).unwrap();
}

/// The coverage certificate proves that no branch was missed on analytic cases, and at a
/// touching point it is either refused there or rests on the reported touching point.
#[test]
fn coverage_certificate_on_analytic_cases() {
    let (a, b) = cylinders(1.0, 0.6);
    for (name, r) in [
        ("cylinders", run(&a, &b, 1e-6)),
        (
            "plane-sphere",
            run(&sphere(&Z, 2.0).unwrap(), &plane_z(0.7, 3.0), 1e-6),
        ),
    ] {
        let c = r.coverage.expect("coverage");
        assert!(c.no_missed_branches, "{name}: {c:?}");
        assert_eq!(c.free_pairs_with_branch_points, Some(0));
        assert!(
            c.free > 0 && c.near_output + c.transversal > 0,
            "{name}: {c:?}"
        );
        assert_eq!(
            c.free + c.near_output + c.transversal + c.uncertified,
            c.pairs
        );
    }
    // Touching: the normals are parallel at the contact; certified only through a reported
    // touching point there, else refused at the contact.
    let r = run(&paraboloid(), &plane_z(0.0, 2.0), 1e-6);
    let c = r.coverage.unwrap();
    let touch_at_contact = r.touch_points.iter().any(|t| norm(&t.point) <= 1e-5);
    assert!(!c.no_missed_branches || touch_at_contact, "{c:?}");
    if !c.no_missed_branches {
        assert!(
            c.uncertified_regions
                .iter()
                .all(|r| r.point.is_some_and(|p| norm(&p) <= 0.1)),
            "uncertified boxes are those at the touching point: {:?}",
            c.uncertified_regions
        );
    }
    // Apart: everything free.
    let far = Frame {
        o: [5.0, 0.0, 0.0],
        ..Z
    };
    let c = run(&sphere(&Z, 2.0).unwrap(), &sphere(&far, 2.0).unwrap(), 1e-6)
        .coverage
        .unwrap();
    assert_eq!(c.free, c.pairs);
    assert!(c.no_missed_branches);
}

/// Trims respected (the default; `--untrimmed` turns it off): a plane face with a rectangular hole (u in [0.45, 0.55]) cut by a
/// sphere: the circle loses the two stretches over the hole and becomes two open arcs, ending
/// at the trim boundary, with every point outside the hole.
#[test]
fn branches_are_clipped_to_trim_loops() {
    use vericad::model::{Model, Surface, TrimLoop};
    use vericad::spline::NurbsCurve;
    let line = |a: [f64; 2], b: [f64; 2]| {
        NurbsCurve::new(vec![0.0, 0.0, 1.0, 1.0], 1, vec![a, b], vec![1.0, 1.0]).unwrap()
    };
    let rect = |u0: f64, u1: f64, v0: f64, v1: f64| {
        vec![
            line([u0, v0], [u1, v0]),
            line([u1, v0], [u1, v1]),
            line([u1, v1], [u0, v1]),
            line([u0, v1], [u0, v0]),
        ]
    };
    let mut plane = Surface::new("plane", plane_z(0.7, 3.0));
    plane.trim_loops = vec![
        TrimLoop {
            outer: true,
            curves: rect(0.0, 1.0, 0.0, 1.0),
        },
        TrimLoop {
            outer: false,
            curves: rect(0.45, 0.55, 0.05, 0.95),
        },
    ];
    let a = Model {
        surfaces: vec![Surface::new("sphere", sphere(&Z, 2.0).unwrap())],
        ..Default::default()
    };
    let b = Model {
        surfaces: vec![plane],
        ..Default::default()
    };
    let no = |_: usize, _: usize| {};
    let full = vericad::ssi::intersect_models(
        &a,
        Some(&b),
        &SsiParams {
            tol: 1e-7,
            respect_trims: false,
            ..Default::default()
        },
        &no,
    )
    .unwrap();
    assert_eq!(full.summary.branches, 1);
    let prm = SsiParams {
        tol: 1e-7,
        ..Default::default()
    };
    let r = vericad::ssi::intersect_models(&a, Some(&b), &prm, &no).unwrap();
    let br = &r.pairs[0].branches;
    assert_eq!(br.len(), 2, "two arcs");
    for x in br {
        assert!(!x.closed);
        assert_eq!(x.ends, vec![EndKind::TrimBoundary, EndKind::TrimBoundary]);
        assert!(x.fit.is_some());
        // Only an end may lie in the hole: the outer end of the chord that leaves the face,
        // kept so that the output reaches the loop — a chord's length (here < 1e-3) from it.
        let n = x.uv_b.len();
        for (k, uv) in x.uv_b.iter().enumerate() {
            let in_hole = 0.45 < uv[0] && uv[0] < 0.55;
            let near_edge = (uv[0] - 0.45).abs() < 1e-3 || (uv[0] - 0.55).abs() < 1e-3;
            assert!(
                !in_hole || ((k == 0 || k + 1 == n) && near_edge),
                "{uv:?} is in the hole"
            );
        }
    }
    assert!(
        r.summary
            .certificate
            .iter()
            .any(|c| c.contains("trim loops"))
    );
}
