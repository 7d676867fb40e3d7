//! Cases whose answer is known from their construction: the curves' points are compared at
//! the matched parameters in exact rational arithmetic, independently of the piece test.

use super::*;
use crate::spline::construct::{Frame, bilinear, cone, cylinder, sphere};

/// `|C_A(t) − C_B(s)|²` exactly, on the borders `m.a` of `sa` and `m.b` of `sb`.
fn exact_gap2(
    sa: &NurbsSurface<f64, 3>,
    sb: &NurbsSurface<f64, 3>,
    m: &BorderMatch,
    t: f64,
) -> f64 {
    let s = m.map(t);
    let (pa, pb) = (m.a.at(t, sa.hom.domain()), m.b.at(s, sb.hom.domain()));
    let ea = crate::spline::exact_point::ExactEvaluator::new(sa).unwrap();
    let eb = crate::spline::exact_point::ExactEvaluator::new(sb).unwrap();
    let (xa, xb) = (
        ea.point(pa[0], pa[1]).unwrap().rational(),
        eb.point(pb[0], pb[1]).unwrap().rational(),
    );
    (0..3)
        .map(|k| {
            let d = xa[k].clone() - xb[k].clone();
            crate::scalar::Scalar::to_f64(&(d.clone() * d))
        })
        .sum()
}

/// A floor and a wall meeting along the line x = z = 0: the floor's border u_min and the
/// wall's v_min are the same segment, exactly; the map takes a point to itself.
#[test]
fn l_shape_shares_its_edge_exactly() {
    let floor = bilinear(
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [1.0, 1.0, 0.0],
    )
    .unwrap();
    let wall = bilinear(
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 0.0],
        [0.0, 1.0, 1.0],
        [0.0, 0.0, 1.0],
    )
    .unwrap();
    let m = common_borders(&floor, &wall, 1e-6);
    assert_eq!(m.len(), 1, "{m:?}");
    let m = &m[0];
    assert!(m.exact && m.gap == 0.0);
    assert_eq!((m.a.label(), m.b.label()), ("u_min", "v_min"));
    assert!(m.reversed, "the wall's border runs from y = 1 to y = 0");
    for k in 0..=8 {
        let t = k as f64 / 8.0;
        assert_eq!(m.map(t), 1.0 - t);
        assert_eq!(exact_gap2(&floor, &wall, m, t), 0.0);
    }
}

/// The wall lifted by 1e-9 at one end: the borders match within a gap proven at least the
/// true largest distance (1e-9, at that end) and not much above it; past a tolerance below the
/// gap they do not match.
#[test]
fn a_near_border_gets_a_proven_gap() {
    let floor = bilinear(
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [1.0, 1.0, 0.0],
    )
    .unwrap();
    let wall = bilinear(
        [0.0, 1.0, 1e-9],
        [0.0, 0.0, 0.0],
        [0.0, 1.0, 1.0],
        [0.0, 0.0, 1.0],
    )
    .unwrap();
    let m = common_borders(&floor, &wall, 1e-6);
    assert_eq!(m.len(), 1);
    assert!(!m[0].exact);
    assert!(
        m[0].gap >= 1e-9 && m[0].gap <= 1e-9 * (1.0 + 1e-12),
        "{}",
        m[0].gap
    );
    for k in 0..=8 {
        let t = k as f64 / 8.0;
        assert!(exact_gap2(&floor, &wall, &m[0], t).sqrt() <= m[0].gap * (1.0 + 1e-12));
    }
    assert!(common_borders(&floor, &wall, 5e-10).is_empty());
}

/// Two cylinders stacked on one axis, the upper one built in a frame turned half a turn
/// and upside down: their common circle starts at the opposite point and runs the other way
/// on the upper one. Matched exactly through rotated, reversed pieces, and every matched
/// parameter pair gives one point.
#[test]
fn stacked_cylinders_share_a_circle_started_elsewhere() {
    let lower = cylinder(&Frame::WORLD, 2.0, -1.0, 0.0).unwrap();
    let flipped = Frame {
        o: [0.0; 3],
        x: [-1.0, 0.0, 0.0],
        y: [0.0, 1.0, 0.0],
        z: [0.0, 0.0, -1.0],
    };
    let upper = cylinder(&flipped, 2.0, -1.0, 0.0).unwrap();
    let m = common_borders(&lower, &upper, 1e-6);
    assert_eq!(m.len(), 1, "{m:?}");
    let m = &m[0];
    assert!(m.exact, "{m:?}");
    assert!(m.reversed);
    for k in 0..=64 {
        let t = k as f64 / 64.0;
        assert!(exact_gap2(&lower, &upper, m, t) <= 1e-28, "t {t}");
    }
}

/// An hourglass of two cones whose waist radii differ by 4.5e-12 (as two solids of a STEP
/// file meet): matched within a gap at least that difference; cones of radii 1e-3 apart are
/// not matched at tol 1e-6.
#[test]
fn hourglass_cones_meet_within_their_radius_difference() {
    let r = 0.0366948444;
    let up = cone(&Frame::WORLD, r, 0.3, 0.0, 0.2).unwrap();
    let down_frame = Frame {
        o: [0.0; 3],
        x: [-1.0, 0.0, 0.0],
        y: [0.0, 1.0, 0.0],
        z: [0.0, 0.0, -1.0],
    };
    let down = cone(&down_frame, r + 4.5e-12, 0.5, 0.0, 0.1).unwrap();
    let m = common_borders(&up, &down, 1e-6);
    assert_eq!(m.len(), 1, "{m:?}");
    assert!(
        !m[0].exact && m[0].gap >= 4.5e-12 * 0.999 && m[0].gap < 1e-10,
        "{:?}",
        m[0]
    );
    let far = cone(&down_frame, r + 1e-3, 0.5, 0.0, 0.1).unwrap();
    assert!(common_borders(&up, &far, 1e-6).is_empty());
}

/// A sphere's poles are borders of one point: two spheres touching at a pole share no
/// border; nor do a sphere and a plane through its equator.
#[test]
fn poles_and_unrelated_borders_are_not_matched() {
    let s1 = sphere(&Frame::WORLD, 1.0).unwrap();
    let f2 = Frame {
        o: [0.0, 0.0, 2.0],
        ..Frame::WORLD
    };
    let s2 = sphere(&f2, 1.0).unwrap();
    assert!(common_borders(&s1, &s2, 1e-6).is_empty());
    let plane = bilinear(
        [-1.0, -1.0, 0.0],
        [1.0, -1.0, 0.0],
        [-1.0, 1.0, 0.0],
        [1.0, 1.0, 0.0],
    )
    .unwrap();
    assert!(common_borders(&s1, &plane, 1e-6).is_empty());
}

/// A floor (bilinear) and a wall of degree 2 along its border — the same segment as the
/// floor's, the wall's border row being the floor's degree-1 border raised to degree 2
/// (control points P0, (P0 + P1)/2, P1: exact in `f64`): matched exactly after degree
/// elevation, every point at the matched parameters the same. With the wall's middle border
/// point lifted by 1e-9 it matches within a gap of at least 5e-10 (the true largest distance,
/// at the middle: Bernstein weight 1/2) and at most 1e-9 (the lemma), and not at all below it.
#[test]
fn borders_of_different_degrees_match_after_elevation() {
    let floor = bilinear(
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [1.0, 1.0, 0.0],
    )
    .unwrap();
    // Wall: u (degree 2) along y at x = 0, v (degree 1) up in z; net row-major in u.
    let wall = |lift: f64| {
        NurbsSurface::new(
            vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
            2,
            vec![0.0, 0.0, 1.0, 1.0],
            1,
            3,
            2,
            vec![
                [0.0, 0.0, 0.0],
                [0.0, 0.0, 1.0],
                [0.0, 0.5, lift],
                [0.0, 0.5, 1.0],
                [0.0, 1.0, 0.0],
                [0.0, 1.0, 1.0],
            ],
            vec![1.0; 6],
        )
        .unwrap()
    };
    let exact = wall(0.0);
    let m = common_borders(&floor, &exact, 1e-6);
    assert_eq!(m.len(), 1, "{m:?}");
    let m = &m[0];
    assert!(m.exact && m.gap == 0.0, "{m:?}");
    for k in 0..=8 {
        let t = k as f64 / 8.0;
        assert_eq!(exact_gap2(&floor, &exact, m, t), 0.0, "t = {t}");
    }
    let near = wall(1e-9);
    let m = common_borders(&floor, &near, 1e-6);
    assert_eq!(m.len(), 1, "{m:?}");
    let m = &m[0];
    assert!(!m.exact && m.gap >= 5e-10 && m.gap <= 1.0000001e-9, "{m:?}");
    let mid = exact_gap2(&floor, &near, m, 0.5).sqrt();
    assert!(mid <= m.gap && mid >= 0.49e-9, "{mid}");
    assert!(common_borders(&floor, &near, 1e-10).is_empty());
}
