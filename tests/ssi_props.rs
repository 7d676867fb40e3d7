//! Property tests of the SSI: loop-topology invariants over random segment soups, and random
//! surface pairs (random bicubic B-spline surfaces against random planes) through the whole
//! pipeline.

use proptest::prelude::*;
use vericad::spline::NurbsSurface;
use vericad::spline::construct::bilinear;
use vericad::ssi::topology::Topology;
use vericad::ssi::trace::{check_invariants, trace};
use vericad::ssi::{SsiParams, intersect_pair_canonical};

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]
    /// Every segment is used exactly once; branches are simple paths or loops; open ends are
    /// exactly the uses at points of use count != 2.
    #[test]
    fn random_soups_trace_consistently(soup in prop::collection::vec((0u32..12, 0u32..12), 0..40)) {
        let mut t = Topology::from_soup(&soup);
        let b = trace(&mut t);
        prop_assert!(check_invariants(&t, &b).is_ok(), "{:?}", check_invariants(&t, &b));
        let ends: usize = t.points.iter().filter(|p| p.uses.len() != 2).map(|p| p.uses.len()).sum();
        prop_assert_eq!(2 * b.iter().filter(|x| !x.closed).count(), ends);
    }
}

fn random_surface(n: usize, z: &[f64]) -> NurbsSurface<f64, 3> {
    let mut pts = Vec::new();
    for i in 0..n {
        for j in 0..n {
            pts.push([
                i as f64 / (n - 1) as f64,
                j as f64 / (n - 1) as f64,
                z[(i * n + j) % z.len()],
            ]);
        }
    }
    let mut k = vec![0.0; 4];
    k.extend((1..n - 3).map(|i| i as f64 / (n - 3) as f64));
    k.extend([1.0; 4]);
    NurbsSurface::new(k.clone(), 3, k, 3, n, n, pts, vec![1.0; n * n]).unwrap()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]
    /// The pipeline completes; every triangle pair is consistent under the perturbation; the
    /// coverage certificate never calls a pair free that holds a branch point; every branch is
    /// within tol of both surfaces unless it reports points where refinement broke down.
    #[test]
    fn random_surface_meets_random_plane(
        n in 4usize..7,
        z in prop::collection::vec(-1.0f64..1.0, 16..49),
        c in -0.5f64..0.5,
        tilt in -0.5f64..0.5,
    ) {
        let s = random_surface(n, &z);
        let p = bilinear([-0.5, -0.5, c - tilt], [1.5, -0.5, c + tilt], [-0.5, 1.5, c - tilt], [1.5, 1.5, c + tilt]).unwrap();
        let tol = 1e-6;
        let r = intersect_pair_canonical(&s, &p, (0, 1), &SsiParams { tol, ..Default::default() }, None);
        prop_assert!(r.is_ok(), "{:?}", r.err());
        let r = r.unwrap();
        prop_assert_eq!(r.stats.inconsistent_triangle_pairs, 0);
        let cov = r.coverage.as_ref().unwrap();
        prop_assert!(cov.free_pairs_with_branch_points.is_none_or(|n| n == 0));
        for b in &r.branches {
            let broke = b.tangential_points + b.unconverged_points > 0;
            prop_assert!(broke || (b.dist_a_max <= tol && b.dist_b_max <= tol), "{} {}", b.dist_a_max, b.dist_b_max);
            // Points on the plane, checked independently of the library.
            for q in &b.points {
                let plane_z = c - tilt + 2.0 * tilt * (q[0] + 0.5) / 2.0;
                prop_assert!(broke || (q[2] - plane_z).abs() <= 2.0 * tol + 1e-12, "{:?} vs {}", q, plane_z);
            }
            if !b.closed {
                prop_assert!(b.ends.iter().all(|e| *e != vericad::ssi::EndKind::Unexplained), "{:?}", b.ends);
            }
        }
    }
}
