//! The coverage decision (`vericad::ssi::coverage::coverage`) end to end, against ground
//! truth from the construction. Its claim: when `no_missed_branches` is true, every
//! connected component of the true intersection comes within the match distance `d` of the
//! output. Contrapositive checked here: when the true intersection has a point (proven
//! exactly) and the output is empty or far from both surfaces, the certificate must be
//! refused. This exercises every class of the leaf-pair classification — a pair wrongly
//! called free (boxes or a normal direction), near the output, or transversal (cones, border
//! crossings) would let such a run through.

use crate::common::*;
use vericad::scalar::Scalar;
use vericad::spline::NurbsSurface;
use vericad::ssi::coverage::{CoverageParams, coverage};
use vericad::ssi::report::TouchOut;

fn params() -> CoverageParams {
    CoverageParams {
        match_distance: 1e-3,
        max_pair_depth: 10,
        max_crossing_depth: 24,
        max_boxes: 4_000,
        deadline: None,
        cancel: None,
        outside: None,
        tubes: Default::default(),
        borders: Default::default(),
        restrict: None,
    }
}

/// A Bézier patch of degree `(p, q)` as a NURBS surface (row-major net, `i` along u).
fn bezier(p: usize, q_: usize, pts: Vec<[f64; 3]>, w: Vec<f64>) -> NurbsSurface<f64, 3> {
    let kn = |d: usize| {
        let mut k = vec![0.0; d + 1];
        k.extend(vec![1.0; d + 1]);
        k
    };
    NurbsSurface::new(kn(p), p, kn(q_), q_, p + 1, q_ + 1, pts, w).expect("valid patch")
}

/// Exact homogeneous point of the (single-piece) surface at `(u, v)`, from its own exact
/// homogeneous net.
fn eval_surface_exact(s: &NurbsSurface<f64, 3>, u: &Q, v: &Q) -> [Q; 4] {
    let net: Vec<[Q; 4]> = s
        .hom
        .net
        .iter()
        .map(|h| [q(h.wp[0]), q(h.wp[1]), q(h.wp[2]), q(h.w)])
        .collect();
    eval_exact(s.hom.nu() - 1, s.hom.nv() - 1, &net, u, v)
}

/// Output far from both surfaces (or nothing).
fn far_output(far: bool) -> Vec<TouchOut> {
    if !far {
        return Vec::new();
    }
    vec![TouchOut {
        point: [1e3, -1e3, 1e3],
        uv_a: None,
        uv_b: None,
        status: None,
        dist_a: None,
        dist_b: None,
        branch_ends: 0,
        singular: None,
    }]
}

/// Ground truth and claim: `a` meets `b` (proven by the caller), the output is empty or far
/// from both, so the certificate must be refused. Returns the number of uncertified pairs.
pub fn prop_missing_branch_is_never_certified(
    a: &NurbsSurface<f64, 3>,
    b: &NurbsSurface<f64, 3>,
    far: bool,
) -> usize {
    let touches = far_output(far);
    for (x, y) in [(a, b), (b, a)] {
        let cov = coverage(x, y, &[], &touches, &params());
        assert!(
            !cov.no_missed_branches && cov.uncertified > 0,
            "certified with a branch missing: {cov:?}\nA = {:?}\nB = {:?}",
            x.hom,
            y.hom
        );
        assert_eq!(
            cov.pairs,
            cov.free + cov.near_output + cov.transversal + cov.uncertified
        );
    }
    1
}

fn plane() -> NurbsSurface<f64, 3> {
    bezier(
        1,
        1,
        vec![
            [-50.0, -50.0, 0.0],
            [-50.0, 50.0, 0.0],
            [50.0, -50.0, 0.0],
            [50.0, 50.0, 0.0],
        ],
        vec![1.0; 4],
    )
}

/// Whether the exact z of surface `s` changes sign (or vanishes) on a 9 × 9 parameter grid:
/// then `s` meets the plane `z = 0` (a continuous function on a connected domain), given its
/// x, y stay inside the plane patch (checked on the control points: convex hull).
fn meets_plane(s: &NurbsSurface<f64, 3>) -> bool {
    assert!(
        s.hom
            .net
            .iter()
            .all(|h| (0..2).all(|k| (h.wp[k] / h.w).abs() < 40.0))
    );
    let (mut pos, mut neg) = (false, false);
    for i in 0..=8 {
        for j in 0..=8 {
            let (u, v) = (ratio(i, 8), ratio(j, 8));
            let z = eval_surface_exact(s, &u, &v)[2].clone(); // w > 0: the sign of z is that of w z
            if z.is_zero() {
                return true;
            }
            pos |= z > Q::ZERO;
            neg |= z < Q::ZERO;
        }
    }
    pos && neg
}

fn random_graph_patch(rng: &mut Rng, kind: u64) -> NurbsSurface<f64, 3> {
    let (p, q_) = (1 + rng.below(3) as usize, 1 + rng.below(3) as usize);
    let rational = rng.coin();
    let (c, k) = (rng.range(1e-4, 0.05), rng.range(0.5, 2.0));
    let mut pts = Vec::new();
    for i in 0..=p {
        for j in 0..=q_ {
            let (x, y) = (
                i as f64 / p as f64 + rng.range(-0.1, 0.1),
                j as f64 / q_ as f64 + rng.range(-0.1, 0.1),
            );
            let z = match kind {
                // A dome: positive inside, negative on the border (a closed loop inside).
                0 => {
                    let border = i == 0 || i == p || j == 0 || j == q_;
                    if border {
                        -k * rng.range(0.2, 1.0)
                    } else {
                        c * rng.range(1.0, 4.0) * (p * q_) as f64
                    }
                }
                // Touching the plane at a corner from below.
                1 => {
                    if i == 0 && j == 0 {
                        0.0
                    } else {
                        -rng.range(1e-9, 1.0)
                    }
                }
                // Any: crossing or not.
                _ => rng.range(-1.0, 1.0),
            };
            pts.push([x, y, z]);
        }
    }
    let n = pts.len();
    let w = (0..n)
        .map(|_| if rational { rng.range(0.5, 2.0) } else { 1.0 })
        .collect();
    bezier(p, q_, pts, w)
}

/// Random graphs over the unit square crossing the plane `z = 0` (dome loops strictly
/// inside a piece, corner touching from one side, arbitrary crossings), polynomial and
/// rational, with the output empty or far away.
#[test]
fn missing_branches_against_a_plane() {
    let n = cases(90, 2_000);
    let mut rng = Rng::new(41);
    let pl = plane();
    let mut checked = 0usize;
    for i in 0..n {
        let a = random_graph_patch(&mut rng, i % 3);
        if meets_plane(&a) {
            checked += prop_missing_branch_is_never_certified(&a, &pl, i % 2 == 0);
        }
    }
    assert!(checked as u64 > n / 2, "{checked}");
}

/// Random pairs of dyadic patches translated so that they share an exact point
/// (`A(½, ½) = B(s, t)` exactly, all values dyadic so the translation is exact in f64).
#[test]
fn missing_branches_between_random_patches() {
    let n = cases(40, 1_000);
    let mut rng = Rng::new(43);
    for i in 0..n {
        let mk = |rng: &mut Rng| {
            let (p, q_) = (1 + rng.below(2) as usize, 1 + rng.below(2) as usize);
            let pts: Vec<[f64; 3]> = (0..(p + 1) * (q_ + 1))
                .map(|k| {
                    let (ii, jj) = (k / (q_ + 1), k % (q_ + 1));
                    [
                        ii as f64 + rng.int(-2, 2) as f64 / 8.0,
                        jj as f64 + rng.int(-2, 2) as f64 / 8.0,
                        rng.int(-8, 8) as f64 / 8.0,
                    ]
                })
                .collect();
            (p, q_, pts)
        };
        let (pa, qa, ptsa) = mk(&mut rng);
        let (pb, qb, mut ptsb) = mk(&mut rng);
        // Rotate B's net a quarter turn about x so that the pieces cross.
        for x in ptsb.iter_mut() {
            *x = [x[0], x[2], x[1]];
        }
        let a = bezier(pa, qa, ptsa, vec![1.0; (pa + 1) * (qa + 1)]);
        let (s, t) = (ratio(rng.int(0, 4), 4), ratio(rng.int(0, 4), 4));
        let half = ratio(1, 2);
        let pa_ = eval_surface_exact(&a, &half, &half);
        let b0 = bezier(pb, qb, ptsb.clone(), vec![1.0; ptsb.len()]);
        let pb_ = eval_surface_exact(&b0, &s, &t);
        let shift: Vec<f64> = (0..3)
            .map(|k| {
                let d = &pa_[k] - &pb_[k];
                let f = Scalar::to_f64(&d);
                assert_eq!(q(f), d, "the shift is dyadic and small: exact in f64");
                f
            })
            .collect();
        for x in ptsb.iter_mut() {
            for k in 0..3 {
                x[k] += shift[k]; // exact: dyadic values with small denominators
            }
        }
        let b = bezier(pb, qb, ptsb.clone(), vec![1.0; ptsb.len()]);
        let pb2 = eval_surface_exact(&b, &s, &t);
        assert_eq!(pa_, pb2, "constructed common point");
        prop_missing_branch_is_never_certified(&a, &b, i % 2 == 0);
    }
}
