//! Property tests of the repair: random patch grids cut apart and perturbed below u1/u2 are
//! reassembled to the original connectivity; grids of mixed degrees, knots and orientations
//! become watertight bit for bit and merge; a row pulled apart beyond u2 is reported, not
//! merged; duplicates and crowded corners are handled.

mod common;
mod repair_util;

use proptest::prelude::*;
use vericad::repair::features::FeatureOverrides;
use vericad::repair::{RepairParams, repair};
use vericad::spline::NurbsSurface;

/// An `m × n` grid of biquadratic patches on a gently curved sheet, every control point moved
/// by up to `noise` (so shared edges no longer coincide).
fn grid(m: usize, n: usize, noise: &[f64]) -> Vec<NurbsSurface<f64, 3>> {
    let mut k = 0;
    let mut out = Vec::new();
    for a in 0..m {
        for b in 0..n {
            let mut pts = Vec::new();
            for i in 0..3 {
                for j in 0..3 {
                    let (x, y) = (a as f64 + i as f64 / 2.0, b as f64 + j as f64 / 2.0);
                    let e = |d: usize| noise[(k * 3 + d) % noise.len()];
                    pts.push([x + e(0), y + e(1), 0.1 * (0.5 * x).sin() + e(2)]);
                    k += 1;
                }
            }
            let kn = vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0];
            out.push(NurbsSurface::new(kn.clone(), 2, kn, 2, 3, 3, pts, vec![1.0; 9]).unwrap());
        }
    }
    out
}

fn none(_: &str) {}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(32))]
    /// Generated sets whose neighbours differ in degree (2 or 3), control-point count and
    /// knots, gaps of 1e-4, random u/v swaps and reversals (the construction knows the true
    /// adjacency and surface): every shared row bit-identical, every grid vertex one point,
    /// the surface within the perturbation, and one merged patch (one feature-free region).
    #[test]
    fn mixed_grids_become_watertight_and_merge(
        m in 1usize..4,
        n in 1usize..4,
        seed in any::<u64>(),
        turn in any::<bool>(),
    ) {
        let (out, _, _) = repair_util::check_grid(m, n, seed, turn);
        prop_assert_eq!(out, 1);
    }

    #[test]
    fn perturbed_grids_are_reassembled(
        m in 1usize..5,
        n in 1usize..5,
        noise in prop::collection::vec(-1e-4f64..1e-4, 7..40),
    ) {
        let prm = RepairParams { u1: 1e-2, u2: 1e-2, ..Default::default() };
        let r = repair(grid(m, n, &noise), &prm, &FeatureOverrides::default(), &none).unwrap();
        let rep = &r.report;
        // Grid adjacency: (m-1)·n + m·(n-1) shared edges.
        prop_assert_eq!(rep.edges_connected, (m - 1) * n + m * (n - 1));
        prop_assert!(rep.gaps_left.is_empty());
        prop_assert_eq!(rep.shared_edges_identical, rep.edges_connected);
        prop_assert_eq!(rep.free_edges, 2 * (m + n));
        // No feature on a gentle sheet: one merged patch reproducing every piece.
        prop_assert_eq!(rep.patches_out, 1);
        prop_assert!(rep.max_merge_deviation.unwrap() < 1e-3);
    }

    #[test]
    fn gaps_beyond_u2_are_reported_not_merged(
        m in 2usize..4,
        n in 1usize..4,
        pull in 0.03f64..0.2,
    ) {
        let mut ps = grid(m, n, &[0.0]);
        // Move the middle control point of patch 0's east edge away: an interior gap of about
        // pull/2 (the middle Bernstein weight peaks at 1/2), so pulls from 0.03 keep the gap
        // clear of the threshold u2 = 1e-2 (0.02 gave a gap at the threshold itself).
        let h = &mut ps[0].hom;
        let nv = h.nv();
        h.net[2 * nv + 1].wp[2] += pull;
        let prm = RepairParams { u1: 1e-2, u2: 1e-2, ..Default::default() };
        let rep = repair(ps, &prm, &FeatureOverrides::default(), &none).unwrap().report;
        prop_assert_eq!(rep.gaps_left.len(), 1);
        prop_assert!(rep.gaps_left[0].gap >= 1e-2);
        prop_assert_eq!(rep.edges_connected, (m - 1) * n + m * (n - 1) - 1);
    }
}

#[test]
fn duplicates_and_crowded_corners_are_handled() {
    // A duplicate patch: its edges have two partners each — reported as non-manifold, not forced.
    let mut ps = grid(2, 2, &[0.0]);
    ps.push(ps[0].clone());
    let rep = repair(
        ps,
        &RepairParams::default(),
        &FeatureOverrides::default(),
        &none,
    )
    .unwrap()
    .report;
    assert!(!rep.non_manifold.is_empty(), "{rep}");
    assert_eq!(
        rep.patch_origin
            .iter()
            .flatten()
            .collect::<std::collections::BTreeSet<_>>()
            .len(),
        5
    );
    // Six patches around one corner (a fan): no panic, every patch accounted for.
    let mut fan = Vec::new();
    for k in 0..6 {
        let (a0, a1) = (
            k as f64 * std::f64::consts::PI / 3.0,
            (k + 1) as f64 * std::f64::consts::PI / 3.0,
        );
        let p = |a: f64, r: f64| [r * a.cos(), r * a.sin(), 0.0];
        fan.push(
            vericad::spline::construct::bilinear(p(a0, 0.0), p(a0, 1.0), p(a1, 0.0), p(a1, 1.0))
                .unwrap(),
        );
    }
    let rep = repair(
        fan,
        &RepairParams::default(),
        &FeatureOverrides::default(),
        &none,
    )
    .unwrap()
    .report;
    assert_eq!(
        rep.patch_origin
            .iter()
            .flatten()
            .collect::<std::collections::BTreeSet<_>>()
            .len(),
        6
    );
}
