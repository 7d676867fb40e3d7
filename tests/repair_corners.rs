//! Corners and limits of the general averaging (paper §4 (iv)): fans of quads and of
//! triangular patches (degenerate quads) around a corner of valence 3, 5 and 6, every patch of
//! random degree and knots and perturbed by 1e-4 — after repair the shared spokes are the same
//! control points bit for bit and the centre is one point; and a knot class too large to refine
//! is left with its reason.

mod common;
mod repair_util;
use common::Rng;
use repair_util::*;
use vericad::repair::features::FeatureOverrides;
use vericad::repair::{RepairParams, repair};
use vericad::spline::NurbsSurface;

/// A fan of `k` planar quads around the origin (valence `k` at the centre), each with random
/// degrees and knots and perturbed by `NOISE`; quad `i` has corners O, A_i, M_i, A_{i+1}.
fn fan(k: usize, seed: u64) -> Vec<NurbsSurface<f64, 3>> {
    let mut r = Rng(seed);
    let tau = std::f64::consts::TAU;
    let at = |a: f64, rad: f64| [rad * a.cos(), rad * a.sin(), 0.0];
    (0..k)
        .map(|i| {
            let (a0, a1) = (tau * i as f64 / k as f64, tau * (i + 1) as f64 / k as f64);
            let c = [
                [0.0, 0.0, 0.0],
                at(a0, 1.0),
                at(0.5 * (a0 + a1), 1.2),
                at(a1, 1.0),
            ];
            let (p, q) = (2 + r.below(2), 2 + r.below(2));
            let (ku, kv) = (knots(p, &mut r), knots(q, &mut r));
            let (nu, nv) = (ku.len() - p - 1, kv.len() - q - 1);
            let mut pts = Vec::new();
            for i in 0..nu {
                let s = ku[i + 1..=i + p].iter().sum::<f64>() / p as f64;
                for j in 0..nv {
                    let t = kv[j + 1..=j + q].iter().sum::<f64>() / q as f64;
                    // Bilinear in the Greville abscissae: the bilinear quad exactly.
                    let b: [f64; 3] = std::array::from_fn(|d| {
                        (1.0 - s) * (1.0 - t) * c[0][d]
                            + s * (1.0 - t) * c[1][d]
                            + s * t * c[2][d]
                            + (1.0 - s) * t * c[3][d]
                    });
                    pts.push(b.map(|x| x + NOISE * (2.0 * r.unit() - 1.0)));
                }
            }
            NurbsSurface::new(ku, p, kv, q, nu, nv, pts, vec![1.0; nu * nv]).unwrap()
        })
        .collect()
}

#[test]
fn corners_of_valence_3_5_6_are_one_point() {
    for k in [3, 5, 6] {
        for seed in 0..4 {
            let prm = RepairParams {
                u1: 1e-2,
                u2: 1e-2,
                ..Default::default()
            };
            let res = repair(fan(k, 77 + seed), &prm, &FeatureOverrides::default(), &none).unwrap();
            let rep = &res.report;
            assert_eq!(rep.edges_connected, k, "valence {k}: {rep}");
            assert!(rep.averaging.left.is_empty());
            let out = &res.connected_patches;
            // Quad i's west edge (A_{i+1} → O) is quad i+1's south edge (O → A_{i+1}).
            for i in 0..k {
                assert_identical(&out[i], 3, &out[(i + 1) % k], 0);
            }
            // The centre: corner 0 of every quad, one point and weight.
            let centre: Vec<([f64; 3], f64)> = out.iter().map(|s| row(s, 0)[0]).collect();
            assert!(
                centre.iter().all(|x| *x == centre[0]),
                "valence {k}: {centre:?}"
            );
            // Within the perturbation of the plane z = 0.
            for s in out {
                for x in s.points_weights().0 {
                    assert!(x[2].abs() < 4.0 * NOISE, "{x:?}");
                }
            }
        }
    }
}

/// Triangular patches (degenerate quads: the west edge collapsed to the apex) in a fan of `k`
/// around the origin, random degrees and knots, perturbed (the collapsed row moved as one
/// point). After repair every apex row is still one point, the same for all triangles.
#[test]
fn collapsed_apexes_stay_one_point() {
    for k in [3, 5, 6] {
        let mut r = Rng(500 + k as u64);
        let tau = std::f64::consts::TAU;
        let at = |a: f64| [a.cos(), a.sin(), 0.0];
        let ps: Vec<NurbsSurface<f64, 3>> = (0..k)
            .map(|i| {
                let (a0, a1) = (tau * i as f64 / k as f64, tau * (i + 1) as f64 / k as f64);
                let c = [[0.0, 0.0, 0.0], at(a0), at(a1), [0.0, 0.0, 0.0]];
                let (p, q) = (2 + r.below(2), 2 + r.below(2));
                let (ku, kv) = (knots(p, &mut r), knots(q, &mut r));
                let (nu, nv) = (ku.len() - p - 1, kv.len() - q - 1);
                let apex_noise = [0, 1, 2].map(|_| NOISE * (2.0 * r.unit() - 1.0));
                let mut pts = Vec::new();
                for i in 0..nu {
                    let s = ku[i + 1..=i + p].iter().sum::<f64>() / p as f64;
                    for j in 0..nv {
                        let t = kv[j + 1..=j + q].iter().sum::<f64>() / q as f64;
                        let b: [f64; 3] = std::array::from_fn(|d| {
                            (1.0 - s) * (1.0 - t) * c[0][d]
                                + s * (1.0 - t) * c[1][d]
                                + s * t * c[2][d]
                                + (1.0 - s) * t * c[3][d]
                        });
                        let e: [f64; 3] = if i == 0 {
                            apex_noise
                        } else {
                            [0, 1, 2].map(|_| NOISE * (2.0 * r.unit() - 1.0))
                        };
                        pts.push(std::array::from_fn(|d| b[d] + e[d]));
                    }
                }
                NurbsSurface::new(ku, p, kv, q, nu, nv, pts, vec![1.0; nu * nv]).unwrap()
            })
            .collect();
        let prm = RepairParams {
            u1: 1e-2,
            u2: 1e-2,
            ..Default::default()
        };
        let res = repair(ps, &prm, &FeatureOverrides::default(), &none).unwrap();
        let rep = &res.report;
        assert_eq!(rep.collapsed_edges, k, "{rep}");
        assert_eq!(rep.edges_connected, k, "{rep}");
        let out = &res.connected_patches;
        for i in 0..k {
            // Triangle i's north edge (A_{i+1} → O) is triangle i+1's south edge (O → A_{i+1}).
            assert_identical(&out[i], 2, &out[(i + 1) % k], 0);
        }
        let apex = row(&out[0], 3)[0];
        for s in out {
            assert!(row(s, 3).iter().all(|x| *x == apex), "valence {k}");
        }
    }
}

/// A strip of 100 patches side by side, each with its own three interior v-knots: the v
/// directions form one knot class whose union would need far more control points per row than
/// the limit; its incompatible pairs are left, each with the reason, and nothing panics.
#[test]
fn oversized_knot_classes_are_left_with_their_reason() {
    let mut r = Rng(9);
    let ps: Vec<NurbsSurface<f64, 3>> = (0..100)
        .map(|a| {
            let mut kv = vec![0.0; 4];
            let mut inner: Vec<f64> = (0..3)
                .map(|k| r.range(0.05, 0.3) + 0.3 * k as f64)
                .collect();
            inner.sort_by(f64::total_cmp);
            kv.extend(inner);
            kv.extend([1.0; 4]);
            let ku = [0.0, 0.0, 0.0, 1.0, 1.0, 1.0];
            parabolic_patch(
                a as f64 * 0.1,
                (a + 1) as f64 * 0.1,
                0.0,
                1.0,
                2,
                3,
                &ku,
                &kv,
                &mut r,
            )
        })
        .collect();
    let prm = RepairParams {
        u1: 1e-2,
        u2: 1e-2,
        ..Default::default()
    };
    let rep = repair(ps, &prm, &FeatureOverrides::default(), &none)
        .unwrap()
        .report;
    assert_eq!(rep.edges_connected, 99);
    let a = &rep.averaging;
    assert_eq!(a.left.len(), a.incompatible_before, "{:?}", a.left.first());
    assert!(a.left.iter().all(|l| l.reason.contains("limit")));
    assert_eq!(rep.shared_edges_identical, a.edges_averaged);
}
