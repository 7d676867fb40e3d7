//! General averaging (paper §4 (i)–(v)): neighbours that differ in degree (2 or 3), number of
//! control points and knots, with gaps of 1e-4 and random u/v swaps and reversals. The truth
//! comes from the construction: every patch is an exact piece of the parabolic cylinder
//! `z = C x²` (or of a plane, for the corner fans) before the perturbation, and the test knows
//! which patch edges meet. After repair every shared edge is the same control points bit for
//! bit (checked here on the nets, independently of the library's own check), every shared
//! corner is one point, and the surface stays within a few perturbations of the truth.

mod common;
use common::Rng;
use vericad::repair::features::FeatureOverrides;
use vericad::repair::{RepairParams, repair};
use vericad::spline::NurbsSurface;

const C: f64 = 0.3;
const NOISE: f64 = 1e-4;

fn none(_: &str) {}

/// Random clamped knots on `[0, 1]` for degree `p` with 0..=2 interior knots.
fn knots(p: usize, r: &mut Rng) -> Vec<f64> {
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
fn parabolic_patch(
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
fn swap_uv(s: &mut NurbsSurface<f64, 3>, side: &mut [usize; 4]) {
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
fn reverse_u(s: &mut NurbsSurface<f64, 3>, side: &mut [usize; 4]) {
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
fn row(s: &NurbsSurface<f64, 3>, e: usize) -> Vec<([f64; 3], f64)> {
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
fn assert_identical(a: &NurbsSurface<f64, 3>, ea: usize, b: &NurbsSurface<f64, 3>, eb: usize) {
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
fn grid(m: usize, n: usize, seed: u64, turn: bool) -> (Vec<NurbsSurface<f64, 3>>, Vec<[usize; 4]>) {
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
fn check_grid(m: usize, n: usize, seed: u64, turn: bool) -> (usize, usize, usize) {
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

#[test]
fn mixed_degrees_and_knots_share_identical_edges() {
    let (mut fitted, mut averaged) = (0, 0);
    for seed in 0..12 {
        let (out, f, a) = check_grid(3, 3, 1000 + seed, false);
        // No feature line on the cylinder: one region, one merged patch.
        assert_eq!(out, 1, "seed {seed}");
        fitted += f;
        averaged += a;
    }
    // Both methods were exercised.
    assert!(fitted > 0 && averaged > 0, "{fitted} {averaged}");
}

#[test]
fn swapped_and_reversed_neighbours_share_identical_edges() {
    let mut fitted = 0;
    for seed in 0..12 {
        let (out, f, _) = check_grid(3, 2, 2000 + seed, true);
        // Turned neighbours join their group: one region, one merged patch.
        assert_eq!(out, 1, "seed {seed}");
        fitted += f;
    }
    assert!(fitted > 0);
}

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

/// A roof: `z = max(0, x - 2)` over `[0, 4] × [0, 2]`, cut into 4 × 2 patches of random
/// degrees and knots (exact: the function is linear on each patch, so the Greville abscissae
/// give its control points), perturbed, some turned. The crease at `x = 2` (45°) is a feature
/// line: two feature-bounded regions, so two merged patches.
#[test]
fn merged_patches_are_the_feature_bounded_regions() {
    for seed in 0..6 {
        let mut r = Rng(3000 + seed);
        let mut ps = Vec::new();
        for a in 0..4 {
            for b in 0..2 {
                let (p, q) = (2 + r.below(2), 2 + r.below(2));
                let (ku, kv) = (knots(p, &mut r), knots(q, &mut r));
                let (nu, nv) = (ku.len() - p - 1, kv.len() - q - 1);
                let mut pts = Vec::new();
                for i in 0..nu {
                    let x = a as f64 + ku[i + 1..=i + p].iter().sum::<f64>() / p as f64;
                    for j in 0..nv {
                        let y = b as f64 + kv[j + 1..=j + q].iter().sum::<f64>() / q as f64;
                        let z = if a >= 2 { x - 2.0 } else { 0.0 };
                        pts.push([x, y, z].map(|c| c + NOISE * (2.0 * r.unit() - 1.0)));
                    }
                }
                let mut s =
                    NurbsSurface::new(ku, p, kv, q, nu, nv, pts, vec![1.0; nu * nv]).unwrap();
                let mut side = [0, 1, 2, 3];
                if r.below(2) == 1 {
                    swap_uv(&mut s, &mut side);
                }
                if r.below(2) == 1 {
                    reverse_u(&mut s, &mut side);
                }
                ps.push(s);
            }
        }
        let prm = RepairParams {
            u1: 1e-2,
            u2: 1e-2,
            ..Default::default()
        };
        let res = repair(ps, &prm, &FeatureOverrides::default(), &none).unwrap();
        let rep = &res.report;
        assert_eq!(rep.feature_edges, 2, "seed {seed}: {rep}");
        assert!(rep.averaging.left.is_empty());
        assert_eq!(rep.patches_out, 2, "seed {seed}: {rep}");
    }
}

/// A cylinder of radius 1 from exact rational quadratic quarter arcs (weights 1, √2/2, 1),
/// four sectors around and two levels up; each arc gets a random knot inserted (so stacked
/// neighbours hold the same arc with different knots: rational, incompatible rows) and the
/// height direction degree 1 or 2. Perturbed by `NOISE`. After repair: shared rows identical,
/// every point within a few perturbations of the cylinder.
#[test]
fn rational_rows_with_different_knots_share_identical_edges() {
    use vericad::geom::Hom;
    use vericad::spline::BSplineCurve;
    let s2 = std::f64::consts::FRAC_1_SQRT_2;
    let mut r = Rng(4242);
    let mut ps = Vec::new();
    for k in 0..4 {
        for level in 0..2 {
            let rot = |x: f64, y: f64| -> [f64; 2] {
                let (c, s) = match k {
                    0 => (1.0, 0.0),
                    1 => (0.0, 1.0),
                    2 => (-1.0, 0.0),
                    _ => (0.0, -1.0),
                };
                [c * x - s * y, s * x + c * y]
            };
            let arc = BSplineCurve::new(
                vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
                2,
                [(1.0, 0.0, 1.0), (1.0, 1.0, s2), (0.0, 1.0, 1.0)]
                    .iter()
                    .map(|&(x, y, w)| {
                        let p = rot(x, y);
                        Hom::from_point(&[p[0], p[1], 0.0], &w)
                    })
                    .collect(),
            )
            .unwrap();
            let arc = arc.insert_knot(&r.range(0.2, 0.8), 1);
            let q = 1 + r.below(2);
            let zs: Vec<f64> = (0..=q)
                .map(|j| level as f64 + j as f64 / q as f64)
                .collect();
            let kv: Vec<f64> = [vec![0.0; q + 1], vec![1.0; q + 1]].concat();
            let mut pts = Vec::new();
            let mut w = Vec::new();
            for h in &arc.control {
                for z in &zs {
                    let p = [h.wp[0] / h.w, h.wp[1] / h.w, *z];
                    pts.push(p.map(|c| c + NOISE * (2.0 * r.unit() - 1.0)));
                    w.push(h.w);
                }
            }
            let nu = arc.control.len();
            ps.push(
                NurbsSurface::new(arc.knots.knots().to_vec(), 2, kv, q, nu, q + 1, pts, w).unwrap(),
            );
        }
    }
    let prm = RepairParams {
        u1: 1e-2,
        u2: 1e-2,
        ..Default::default()
    };
    let res = repair(ps, &prm, &FeatureOverrides::default(), &none).unwrap();
    let rep = &res.report;
    // 4 vertical seams per level, 4 arcs between the levels.
    assert_eq!(rep.edges_connected, 12, "{rep}");
    assert!(rep.averaging.left.is_empty(), "{:?}", rep.averaging.left);
    assert!(rep.averaging.edges_fitted >= 4, "{rep}");
    let out = &res.connected_patches;
    let id = |k: usize, level: usize| 2 * k + level;
    for k in 0..4 {
        // Sector k's end (u = max, east) meets sector k+1's start (west); level 0's top
        // (north) meets level 1's bottom (south).
        for level in 0..2 {
            assert_identical(&out[id(k, level)], 1, &out[id((k + 1) % 4, level)], 3);
        }
        assert_identical(&out[id(k, 0)], 2, &out[id(k, 1)], 0);
    }
    for s in out {
        let (u0, u1, v0, v1) = s.hom.domain();
        for i in 0..=16 {
            for j in 0..=8 {
                let x = s.eval(
                    &(u0 + (u1 - u0) * i as f64 / 16.0),
                    &(v0 + (v1 - v0) * j as f64 / 8.0),
                );
                let off = ((x[0] * x[0] + x[1] * x[1]).sqrt() - 1.0).abs();
                assert!(off < 6.0 * NOISE, "{off} off the cylinder at {x:?}");
            }
        }
    }
}

/// Every public STEP and IGES file (untrimmed faces): every connected manifold pair is made
/// identical or left with its reason; the deviations reported are finite.
#[test]
fn real_models_leave_no_unexplained_incompatible_rows() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/public");
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| {
            p.extension()
                .is_some_and(|x| ["step", "stp", "igs"].contains(&x.to_str().unwrap_or("")))
        })
        .collect();
    files.sort();
    let mut ran = 0;
    for f in files {
        let rep = match vericad::repair::job::run(
            &f,
            &RepairParams::default(),
            None,
            vericad::repair::job::Outputs::default(),
        ) {
            Ok(r) => r,
            // Files that are not patch sets (a faulty header): a typed error.
            Err(e) => {
                assert!(e.is_bad_input(), "{}: {e}", f.display());
                continue;
            }
        };
        ran += 1;
        let a = &rep.averaging;
        assert_eq!(
            rep.shared_edges_identical,
            a.edges_averaged + a.edges_fitted,
            "{}: {rep}",
            f.display()
        );
        assert_eq!(a.edges.len(), a.edges_averaged + a.edges_fitted);
        assert_eq!(a.incompatible_before, a.edges_fitted + a.left.len());
        for l in &a.left {
            assert!(!l.reason.is_empty());
        }
        assert!(a.max_deviation_measured_evidence.is_finite());
        for p in &a.patches {
            if let Some(b) = p.deviation_bound_proven {
                // The measured distance starts from the corresponding parameter and only
                // improves, so it cannot exceed the bound at equal parameters.
                assert!(
                    p.deviation_measured_evidence <= b * (1.0 + 1e-9) + 1e-12,
                    "{}: patch {} measured {} above the bound {b}",
                    f.display(),
                    p.patch,
                    p.deviation_measured_evidence
                );
            }
        }
    }
    assert!(ran >= 5);
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
