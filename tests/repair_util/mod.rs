//! Shared constructions of the repair tests: exact patches (polar forms, Greville abscissae), the
//! symmetries of a patch's parameter square, and an independent bit-for-bit check of shared
//! rows read from the nets.
#![allow(dead_code)]

use crate::common::Rng;
use vericad::repair::features::FeatureOverrides;
use vericad::repair::{RepairParams, repair};
use vericad::spline::NurbsSurface;

pub const C: f64 = 0.3;
pub const NOISE: f64 = 1e-4;

pub fn none(_: &str) {}

/// Random clamped knots on `[0, 1]` for degree `p` with 0..=2 interior knots.
pub fn knots(p: usize, r: &mut Rng) -> Vec<f64> {
    let k = r.below(3);
    let mut inner: Vec<f64> = (0..k).map(|_| r.range(0.15, 0.85)).collect();
    inner.sort_by(f64::total_cmp);
    inner.dedup_by(|a, b| (*a - *b).abs() < 0.1);
    let mut v = vec![0.0; p + 1];
    v.extend(inner);
    v.extend(std::iter::repeat_n(1.0, p + 1));
    v
}

/// A patch of `z = C x²` over `[x0, x1] × [y0, y1]` with degrees and knots as given: control
/// points from the polar forms (blossoms) of `x`, `y` and `x²` at the knots, so the patch is the
/// surface exactly; every control point then moved by up to `NOISE`.
#[allow(clippy::too_many_arguments)]
pub fn parabolic_patch(
    x0: f64,
    x1: f64,
    y0: f64,
    y1: f64,
    p: usize,
    q: usize,
    ku: &[f64],
    kv: &[f64],
    r: &mut Rng,
) -> NurbsSurface<f64, 3> {
    let (nu, nv) = (ku.len() - p - 1, kv.len() - q - 1);
    let mut pts = Vec::new();
    for i in 0..nu {
        let xs: Vec<f64> = ku[i + 1..=i + p]
            .iter()
            .map(|t| x0 + t * (x1 - x0))
            .collect();
        let gx = xs.iter().sum::<f64>() / p as f64;
        let mut pairs = 0.0;
        for a in 0..p {
            for b in a + 1..p {
                pairs += xs[a] * xs[b];
            }
        }
        let x2 = pairs / (p * (p - 1) / 2) as f64;
        for j in 0..nv {
            let gy = kv[j + 1..=j + q]
                .iter()
                .map(|t| y0 + t * (y1 - y0))
                .sum::<f64>()
                / q as f64;
            pts.push([
                gx + NOISE * (2.0 * r.unit() - 1.0),
                gy + NOISE * (2.0 * r.unit() - 1.0),
                C * x2 + NOISE * (2.0 * r.unit() - 1.0),
            ]);
        }
    }
    NurbsSurface::new(
        ku.to_vec(),
        p,
        kv.to_vec(),
        q,
        nu,
        nv,
        pts,
        vec![1.0; nu * nv],
    )
    .unwrap()
}

/// Swap u and v; `side` maps true sides (0 S, 1 E, 2 N, 3 W) to edge indices and follows.
pub fn swap_uv(s: &mut NurbsSurface<f64, 3>, side: &mut [usize; 4]) {
    let h = &s.hom;
    let (nu, nv) = (h.nu(), h.nv());
    let mut net = Vec::with_capacity(nu * nv);
    for j in 0..nv {
        for i in 0..nu {
            net.push(h.at(i, j).clone());
        }
    }
    let (p, q) = h.degrees();
    let (pts, w): (Vec<[f64; 3]>, Vec<f64>) =
        net.iter().map(|x| (x.wp.map(|c| c / x.w), x.w)).unzip();
    *s = NurbsSurface::new(
        h.kv.knots().to_vec(),
        q,
        h.ku.knots().to_vec(),
        p,
        nv,
        nu,
        pts,
        w,
    )
    .unwrap();
    for e in side.iter_mut() {
        *e = [3, 2, 1, 0][*e];
    }
}

/// Reverse u; `side` follows.
pub fn reverse_u(s: &mut NurbsSurface<f64, 3>, side: &mut [usize; 4]) {
    let h = &s.hom;
    let (nu, nv) = (h.nu(), h.nv());
    let (a, b) = h.ku.domain();
    let ku: Vec<f64> = h.ku.knots().iter().rev().map(|x| a + b - x).collect();
    let mut pts = Vec::new();
    let mut w = Vec::new();
    for i in 0..nu {
        for j in 0..nv {
            let x = h.at(nu - 1 - i, j);
            pts.push(x.wp.map(|c| c / x.w));
            w.push(x.w);
        }
    }
    let (p, q) = h.degrees();
    *s = NurbsSurface::new(ku, p, h.kv.knots().to_vec(), q, nu, nv, pts, w).unwrap();
    for e in side.iter_mut() {
        *e = [0, 3, 2, 1][*e];
    }
}

/// Control points and weights of edge `e` in its traversal order (corner e to e+1), read from
/// the net directly.
pub fn row(s: &NurbsSurface<f64, 3>, e: usize) -> Vec<([f64; 3], f64)> {
    let h = &s.hom;
    let (nu, nv) = (h.nu(), h.nv());
    let idx: Vec<(usize, usize)> = match e {
        0 => (0..nu).map(|i| (i, 0)).collect(),
        1 => (0..nv).map(|j| (nu - 1, j)).collect(),
        2 => (0..nu).rev().map(|i| (i, nv - 1)).collect(),
        _ => (0..nv).rev().map(|j| (0, j)).collect(),
    };
    idx.iter()
        .map(|&(i, j)| {
            let x = h.at(i, j);
            (x.wp.map(|c| c / x.w), x.w)
        })
        .collect()
}

/// The two rows are the same control points and weights, bit for bit, in one of the two
/// orders, and both patches' knots along the edge agree after normalization.
pub fn assert_identical(a: &NurbsSurface<f64, 3>, ea: usize, b: &NurbsSurface<f64, 3>, eb: usize) {
    let (ra, mut rb) = (row(a, ea), row(b, eb));
    assert_eq!(ra.len(), rb.len(), "rows of different lengths");
    if ra.first() != rb.first() {
        rb.reverse();
    }
    assert!(ra == rb, "shared rows differ:\n{ra:?}\n{rb:?}");
    let norm = |s: &NurbsSurface<f64, 3>, e: usize| -> Vec<f64> {
        let kv = if e.is_multiple_of(2) {
            &s.hom.ku
        } else {
            &s.hom.kv
        };
        let (lo, hi) = kv.domain();
        kv.knots().iter().map(|x| (x - lo) / (hi - lo)).collect()
    };
    let (ka, kb) = (norm(a, ea), norm(b, eb));
    let mirrored: Vec<f64> = kb.iter().rev().map(|x| 1.0 - x).collect();
    let close = |x: &[f64], y: &[f64]| {
        x.len() == y.len() && x.iter().zip(y).all(|(s, t)| (s - t).abs() <= 1e-12)
    };
    assert!(close(&ka, &kb) || close(&ka, &mirrored), "knots differ");
}

/// An `m × n` grid of parabolic-cylinder patches over `[0, m] × [0, n]`, random degrees 2/3
/// and knots, optionally random u/v swaps and reversals. Returns the patches and each one's
/// true-side → edge map.
pub fn grid(
    m: usize,
    n: usize,
    seed: u64,
    turn: bool,
) -> (Vec<NurbsSurface<f64, 3>>, Vec<[usize; 4]>) {
    let mut r = Rng(seed);
    let mut ps = Vec::new();
    let mut sides = Vec::new();
    for a in 0..m {
        for b in 0..n {
            let (p, q) = (2 + r.below(2), 2 + r.below(2));
            let (ku, kv) = (knots(p, &mut r), knots(q, &mut r));
            let (x0, y0) = (a as f64, b as f64);
            let mut s = parabolic_patch(x0, x0 + 1.0, y0, y0 + 1.0, p, q, &ku, &kv, &mut r);
            let mut side = [0, 1, 2, 3];
            if turn {
                if r.below(2) == 1 {
                    swap_uv(&mut s, &mut side);
                }
                if r.below(2) == 1 {
                    reverse_u(&mut s, &mut side);
                }
            }
            ps.push(s);
            sides.push(side);
        }
    }
    (ps, sides)
}

/// Repair the grid and check it; returns (patches out, pairs fitted, pairs given
/// control-point averaging).
pub fn check_grid(m: usize, n: usize, seed: u64, turn: bool) -> (usize, usize, usize) {
    let (ps, sides) = grid(m, n, seed, turn);
    let incompatible_in = {
        // Pairs whose rows differ in degree, count or knots (from the construction).
        let mut k = 0;
        let id = |a: usize, b: usize| a * n + b;
        for a in 0..m {
            for b in 0..n {
                for (c, d, sa, sb) in [(a + 1, b, 1, 3), (a, b + 1, 2, 0)] {
                    if c < m && d < n {
                        let (x, y) = (&ps[id(a, b)], &ps[id(c, d)]);
                        if row(x, sides[id(a, b)][sa]).len() != row(y, sides[id(c, d)][sb]).len() {
                            k += 1;
                        }
                    }
                }
            }
        }
        k
    };
    let prm = RepairParams {
        u1: 1e-2,
        u2: 1e-2,
        ..Default::default()
    };
    let res = repair(ps, &prm, &FeatureOverrides::default(), &none).unwrap();
    let rep = &res.report;
    assert_eq!(rep.t_junctions, 0, "{rep}");
    assert_eq!(rep.edges_connected, (m - 1) * n + m * (n - 1), "{rep}");
    assert!(rep.gaps_left.is_empty());
    assert!(rep.averaging.left.is_empty(), "{:?}", rep.averaging.left);
    assert!(rep.averaging.edges_fitted >= incompatible_in.min(1));
    let out = &res.connected_patches;
    let id = |a: usize, b: usize| a * n + b;
    // Every true shared edge: the same control points on both sides, bit for bit.
    for a in 0..m {
        for b in 0..n {
            if a + 1 < m {
                assert_identical(
                    &out[id(a, b)],
                    sides[id(a, b)][1],
                    &out[id(a + 1, b)],
                    sides[id(a + 1, b)][3],
                );
            }
            if b + 1 < n {
                assert_identical(
                    &out[id(a, b)],
                    sides[id(a, b)][2],
                    &out[id(a, b + 1)],
                    sides[id(a, b + 1)][0],
                );
            }
        }
    }
    // Every interior grid vertex: one point for its four patches.
    for a in 1..m {
        for b in 1..n {
            let around = [
                (id(a - 1, b - 1), 2),
                (id(a, b - 1), 3),
                (id(a, b), 0),
                (id(a - 1, b), 1),
            ];
            let pts: Vec<([f64; 3], f64)> = around
                .iter()
                .map(|&(k, true_corner)| {
                    // The corner at the start of the true side `true_corner` (S starts at
                    // SW, E at SE, N at NE, W at NW): the shared endpoint of two true sides.
                    let s = &out[k];
                    let e1 = sides[k][true_corner];
                    let e0 = sides[k][(true_corner + 3) % 4];
                    let (r1, r0) = (row(s, e1), row(s, e0));
                    [r1[0], r1[r1.len() - 1]]
                        .into_iter()
                        .find(|x| *x == r0[0] || *x == r0[r0.len() - 1])
                        .expect("two sides of a patch share a corner")
                })
                .collect();
            assert!(
                pts.iter().all(|x| *x == pts[0]),
                "corner ({a}, {b}): {pts:?}"
            );
        }
    }
    // The truth: every repaired patch stays on z = C x² within a few perturbations.
    for s in out {
        let (u0, u1, v0, v1) = s.hom.domain();
        for i in 0..=10 {
            for j in 0..=10 {
                let x = s.eval(
                    &(u0 + (u1 - u0) * i as f64 / 10.0),
                    &(v0 + (v1 - v0) * j as f64 / 10.0),
                );
                let off = (x[2] - C * x[0] * x[0]).abs();
                assert!(
                    off < 6.0 * NOISE,
                    "{off} off the parabolic cylinder at {x:?}"
                );
            }
        }
    }
    // The merged output too.
    for s in &res.patches {
        let (u0, u1, v0, v1) = s.hom.domain();
        for i in 0..=20 {
            for j in 0..=20 {
                let x = s.eval(
                    &(u0 + (u1 - u0) * i as f64 / 20.0),
                    &(v0 + (v1 - v0) * j as f64 / 20.0),
                );
                assert!((x[2] - C * x[0] * x[0]).abs() < 6.0 * NOISE, "{x:?}");
            }
        }
    }
    (
        rep.patches_out,
        rep.averaging.edges_fitted,
        rep.averaging.edges_averaged,
    )
}
