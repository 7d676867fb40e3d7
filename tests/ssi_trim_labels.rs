//! A false coverage certificate once came from the labels' rounding: the faces' margin is a
//! fraction of the domain's *extent*, but a label's rounding is an ulp of its *coordinate*,
//! and with parameters near 2^30 on a domain of width 1 a half piece's label stopped 2^-23
//! short of its exact box, so the box test called it outside a face it reaches into. The
//! region's box tests now widen every box by ulps of its coordinates as well.
//!
//! A = the plane z = 0, x = (u − U0)/(U1 − U0), y = v, on u ∈ [U0, U1] = [2^30 + 2^-22,
//! 2^30 + 1] (the ulp there is 2^-22 ≈ 2.4e-7, the face margin 1e-9 · (U1 − U0) ≈ 1e-9).
//! The first u-midpoint label is m = fl((U0 + U1)/2) = 2^30 + 1/2, while the exact midpoint
//! is M = m + 2^-23: the left half's exact piece reaches u = M, its label stops at m.
//! Face A = the polygon right of the edge from (m + 2^-22, −1) to (m − 2^-22, 3): at
//! v ∈ [0, 1) the edge runs in (m, M], inside the left half's exact piece, right of its label.
//! B = the wall x = X (X = 0.5 − 3e-8), y ∈ [0.3, 0.4], z ∈ [−1, 1], untrimmed.
//! I = {(X, y, 0) : y ∈ [0.3, 0.4]}; all of it lies in face A (x_edge(y) ≈ 0.5 − 1.19e-7 y < X),
//! so it is a component of the faces' intersection. Output: nothing.
use std::sync::Arc;
use vericad::spline::NurbsSurface;
use vericad::ssi::coverage::{FaceRestriction, OutsideFaces, coverage};
use vericad::tessellate::region::FaceRegion;

mod common;

const FACE_MARGIN: f64 = 1e-9;

fn restriction(r: FaceRegion) -> (FaceRestriction, OutsideFaces) {
    let r = Arc::new(r);
    let (r1, r2, r3, r4, r5, r6) = (
        r.clone(),
        r.clone(),
        r.clone(),
        r.clone(),
        r.clone(),
        r.clone(),
    );
    let widen = move |b: &[f64; 4], r: &FaceRegion| {
        let mu = FACE_MARGIN * (r.domain[1] - r.domain[0]).abs();
        let mv = FACE_MARGIN * (r.domain[3] - r.domain[2]).abs();
        r.box_inside(&[b[0] - mu, b[1] + mu, b[2] - mv, b[3] + mv])
    };
    let f = FaceRestriction {
        inside: Arc::new(move |a, _| r1.inside(a)),
        meets: Arc::new(move |a, _| !r2.box_outside(a, FACE_MARGIN)),
        shared: Arc::new(|_| false),
        pair_inside: Arc::new(move |a, _| widen(a, &r3)),
        outside_a: Arc::new(move |b| r4.box_outside(b, FACE_MARGIN)),
        outside_b: Arc::new(|_| false),
        inside_a: Arc::new(move |b| widen(b, &r5)),
        inside_b: Arc::new(|_| true),
        edges_a: Arc::new(move |b| r6.edges_meeting(b, FACE_MARGIN)),
        edges_b: Arc::new(|_| Vec::new()),
    };
    let o = OutsideFaces(Arc::new(move |a, _| r.box_outside(a, FACE_MARGIN)));
    (f, o)
}

/// The faces meet in a segment of length 0.1 and nothing is output: never certified, with
/// or without the pair-level outside test.
#[test]
fn label_rounding_hides_a_branch() {
    let u0 = 2f64.powi(30) + 2f64.powi(-22);
    let u1 = 2f64.powi(30) + 1.0;
    let m = 0.5 * (u0 + u1);
    let ulp = 2f64.powi(-22);
    assert_eq!(m, 2f64.powi(30) + 0.5, "the label rounds down by 2^-23");
    // A: t = (u − u0)/(u1 − u0); (x, z) = quadratic Bézier (0,0), (1,0), (1,1) in t:
    // x = 2t − t², z = t², y = v. Its normals (−2t, 0, 2 − 2t) reach ±x at t = 1, so the root
    // pair's cones are not separated against the wall and the root is split.
    let a = NurbsSurface::new(
        vec![u0, u0, u0, u1, u1, u1],
        2,
        vec![0.0, 0.0, 1.0, 1.0],
        1,
        3,
        2,
        vec![
            [0.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [1.0, 0.0, 1.0],
            [1.0, 1.0, 1.0],
        ],
        vec![1.0; 6],
    )
    .unwrap();
    // The wall meets A exactly at t_w = 1/2 − 2^-26: x_w = 1 − (1 − t_w)² = 3/4 − 2^-26 − 2^-52.
    let t_w = 0.5 - 2f64.powi(-26);
    let x_w = 0.75 - 2f64.powi(-26) - 2f64.powi(-52);
    assert_eq!(
        x_w,
        1.0 - (0.5 + 2f64.powi(-26)) * (0.5 + 2f64.powi(-26)) + 0.0 * t_w
    );
    let b = NurbsSurface::new(
        vec![0.0, 0.0, 1.0, 1.0],
        1,
        vec![0.0, 0.0, 1.0, 1.0],
        1,
        2,
        2,
        vec![
            [x_w, 0.3, -1.0],
            [x_w, 0.3, 1.0],
            [x_w, 0.4, -1.0],
            [x_w, 0.4, 1.0],
        ],
        vec![1.0; 4],
    )
    .unwrap();
    // Face A: right of the edge from (m + ulp, −1) to (m − ulp, 3): u_e(v) = m + ulp (1 − v)/2.
    let face = FaceRegion {
        surface: 0,
        polys: vec![vec![
            [m + ulp, -1.0],
            [m - ulp, 3.0],
            [u1 + 1.0, 3.0],
            [u1 + 1.0, -1.0],
        ]],
        period: [None, None],
        domain: [u0, u1, 0.0, 1.0],
        ambiguous: false,
    };
    // Ground truth, exact (integers in units of 2^-60). The faces' intersection holds
    // {A(t_w, v) : v ∈ [0.3, 0.4]} = {(x_w, v, t_w²)}: it is on the wall (y ∈ [0.3, 0.4],
    // z = t_w² ∈ [−1, 1]) and, with u_w = u0 + t_w (u1 − u0), right of the edge:
    // u_w − u0 ≥ u_e(v) − u0 = (m − u0) + ulp (1 − v)/2, worst at v = 0.3 (×20 below).
    {
        let unit = |x: f64| -> i128 {
            let y = x * 2f64.powi(60);
            assert_eq!(y.fract(), 0.0);
            y as i128
        };
        let span = unit(1.0) - unit(2f64.powi(-22)); // u1 − u0 = 1 − 2^-22
        let tw = unit(t_w);
        let prod = tw * span; // < 2^120
        let uw = prod >> 60; // u_w − u0 in units of 2^-60
        assert_eq!(uw << 60, prod);
        let m_u0 = unit(0.5) - unit(2f64.powi(-22)); // m − u0 = 1/2 − 2^-22
        let ulp80 = unit(ulp);
        assert!(
            20 * uw >= 20 * m_u0 + 7 * ulp80,
            "right of the edge at v = 0.3"
        );
        // And t_w < 1/2: in the exact left half, whose label [u0, m] is outside face A.
        assert!(t_w < 0.5);
    }
    // The left half's label [u0, m] is no longer taken as outside face A: the tests widen it
    // by the labels' rounding (its exact box reaches 2^-23 past m, into the face).
    assert!(!face.box_outside(&[u0, m, 0.0, 0.5], FACE_MARGIN));
    let prm0 = common::coverage_params(1e-6);
    let mut false_certificates = Vec::new();
    for with_outside in [false, true] {
        let (restrict, outside) = restriction(face.clone());
        let mut prm = prm0.clone();
        prm.restrict = Some(restrict);
        if with_outside {
            prm.outside = Some(outside);
        }
        let c = coverage(&a, &b, &[], &[], &prm);
        println!(
            "outside test {with_outside}: no_missed_branches {} uncertified {} transversal {} \
             with_trim_loops {} free {} outside_faces {} crossing_boxes_outside_faces {} \
             trim_edge_searches {} regions {:?}",
            c.no_missed_branches,
            c.uncertified,
            c.transversal,
            c.transversal_with_trim_loops,
            c.free,
            c.outside_faces,
            c.crossing_boxes_outside_faces,
            c.trim_edge_searches,
            c.uncertified_regions
        );
        if c.no_missed_branches {
            false_certificates.push(with_outside);
        }
    }
    assert!(
        false_certificates.is_empty(),
        "FALSE CERTIFICATE (with the pair-level outside test: {false_certificates:?}): the faces \
         meet in a segment of length 0.1, nothing is output, and the run claims no missed branch"
    );
}
