//! The region of a proven branch point, against a construction whose critical points and
//! intersection components are known: the graph of `f(x, y) = y² − x² r(x)`, with
//! `r(x) = −(x − a)(x − b)(x − c) / (a b c)` (`0 < a < b < c`), cut by the plane `z = 0`.
//!
//! `f = 0` is `y² = x² r(x)`: two arcs crossing at the origin (a saddle of `f`, the branch
//! point: `f ≈ y² − x²`), whose right halves close into a lobe at `x = a`, their left halves
//! leaving the patch; and a separate oval over `b ≤ x ≤ c`, where `r > 0` again. The plane's
//! normal is constant, so the collinear-normal points are the critical points of `f`: the
//! origin and the extrema of `x² r(x)` on `(0, a)`, `(a, b)` and `(b, c)` (on `y = 0`). A
//! region around the origin must keep out the nearest of them, and the coverage certificate
//! must refuse when the oval is left out of the output.

mod common;
use vericad::spline::NurbsSurface;
use vericad::spline::construct::bilinear;
use vericad::ssi::coverage::{CoverageParams, coverage};
use vericad::ssi::report::{BranchOut, SingularKind, TouchOut};
use vericad::ssi::singular::branch_region;
use vericad::ssi::singular::classify;

const A: f64 = 0.002;
const B: f64 = 0.004;
const C: f64 = 0.006;
/// The patch spans `[−H, H]²`.
const H: f64 = 0.05;

fn r(x: f64) -> f64 {
    -(x - A) * (x - B) * (x - C) / (A * B * C)
}

/// Bernstein coefficients of degree `n` on `[0, 1]` of the polynomial with power
/// coefficients `p` (in `u`): `b_i = Σ_{k ≤ i} C(i, k) / C(n, k) p_k`.
fn bernstein(p: &[f64], n: usize) -> Vec<f64> {
    let binom =
        |n: usize, k: usize| (0..k).fold(1.0, |acc, j| acc * (n - j) as f64 / (j + 1) as f64);
    (0..=n)
        .map(|i| {
            (0..=i.min(p.len() - 1))
                .map(|k| binom(i, k) / binom(n, k) * p[k])
                .sum()
        })
        .collect()
}

/// Power coefficients in `u` of `g(x(u))`, `x = −H + 2H u`, for `g` with power coefficients
/// `q` in `x`.
fn in_u(q: &[f64]) -> Vec<f64> {
    let mut out = vec![0.0; q.len()];
    // (−H + 2H u)^k expanded.
    for (k, &qk) in q.iter().enumerate() {
        let mut term = vec![1.0];
        for _ in 0..k {
            let mut next = vec![0.0; term.len() + 1];
            for (j, t) in term.iter().enumerate() {
                next[j] += -H * t;
                next[j + 1] += 2.0 * H * t;
            }
            term = next;
        }
        for (j, t) in term.iter().enumerate() {
            out[j] += qk * t;
        }
    }
    out
}

/// The graph of `f` over `[−H, H]²`, a polynomial patch of degree (5, 2).
fn saddle_and_oval() -> NurbsSurface<f64, 3> {
    // x² r(x) = −x² (x³ − (a+b+c) x² + (ab+bc+ca) x − abc) / abc.
    let s = A * B * C;
    let xr = [
        0.0,
        0.0,
        1.0,
        -(A * B + B * C + C * A) / s,
        (A + B + C) / s,
        -1.0 / s,
    ];
    let gx = bernstein(&in_u(&xr), 5);
    let gy = bernstein(&in_u(&[0.0, 0.0, 1.0]), 2);
    let mut pts = Vec::new();
    for (i, gi) in gx.iter().enumerate() {
        for (j, gj) in gy.iter().enumerate() {
            let x = -H + 2.0 * H * i as f64 / 5.0;
            let y = -H + 2.0 * H * j as f64 / 2.0;
            pts.push([x, y, gj - gi]);
        }
    }
    let ku = vec![0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0];
    let kv = vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0];
    NurbsSurface::new(ku, 5, kv, 2, 6, 3, pts, vec![1.0; 18]).unwrap()
}

fn plane() -> NurbsSurface<f64, 3> {
    let h = 2.0 * H;
    bilinear([-h, -h, 0.0], [h, -h, 0.0], [-h, h, 0.0], [h, h, 0.0]).unwrap()
}

/// The extremum of `x² r(x)` in `(lo, hi)`: a root of its derivative, by bisection.
fn critical(lo: f64, hi: f64) -> f64 {
    let d = |x: f64| {
        let e = 1e-7;
        (((x + e) * (x + e)) * r(x + e) - ((x - e) * (x - e)) * r(x - e)) / (2.0 * e)
    };
    let (mut l, mut h) = (lo, hi);
    assert!(d(l).signum() != d(h).signum());
    for _ in 0..100 {
        let m = 0.5 * (l + h);
        if d(m).signum() == d(l).signum() {
            l = m;
        } else {
            h = m;
        }
    }
    0.5 * (l + h)
}

/// The surface's `x` at parameter `u`.
fn x_of(u: f64) -> f64 {
    -H + 2.0 * H * u
}

/// `f(x, y)` from its definition (not from the patch).
fn f(x: f64, y: f64) -> f64 {
    y * y - x * x * r(x)
}

/// The zero of `f` on the ray from `(cx, 0)` at angle `t`, between radii `lo` and `hi`
/// (where `f` changes sign), by bisection.
fn on_ray(cx: f64, t: f64, lo: f64, hi: f64) -> [f64; 3] {
    let p = |rho: f64| (cx + rho * t.cos(), rho * t.sin());
    let g = |rho: f64| {
        let (x, y) = p(rho);
        f(x, y)
    };
    let (mut l, mut h) = (lo, hi);
    assert!(g(l).signum() != g(h).signum(), "ray {t}");
    for _ in 0..200 {
        let m = 0.5 * (l + h);
        if g(m).signum() == g(l).signum() {
            l = m;
        } else {
            h = m;
        }
    }
    let (x, y) = p(0.5 * (l + h));
    [x, y, 0.0]
}

fn polyline(points: Vec<[f64; 3]>, closed: bool) -> BranchOut {
    BranchOut {
        closed,
        points,
        ..Default::default()
    }
}

/// The true intersection, from the construction: the left arms `y = ±|x| √r(x)` from the
/// patch border through the origin, the lobe over `0 ≤ x ≤ a` and the oval over
/// `b ≤ x ≤ c` (by rays from their centres), as polylines far finer than the match distance
/// needs (sagitta below 1e-8).
fn truth() -> (BranchOut, BranchOut, BranchOut) {
    // The arms leave the patch where |x| √r(x) = H.
    let x0 = {
        let (mut l, mut h) = (-H, 0.0);
        for _ in 0..200 {
            let m = 0.5 * (l + h);
            if m.abs() * r(m).sqrt() > H {
                l = m;
            } else {
                h = m;
            }
        }
        h
    };
    let n = 40_000;
    let mut arms = Vec::new();
    for k in 0..=n {
        let x = x0 * (1.0 - k as f64 / n as f64);
        arms.push([x, -x.abs() * r(x).sqrt(), 0.0]);
    }
    for k in (0..n).rev() {
        let x = x0 * (1.0 - k as f64 / n as f64);
        arms.push([x, x.abs() * r(x).sqrt(), 0.0]);
    }
    let m = 40_000;
    let angle = |k: usize| std::f64::consts::TAU * k as f64 / m as f64;
    // The lobe passes through the origin (the ray at angle π from its centre ends there);
    // a ray pointing left is searched up to the line x = 0, where f = y² > 0.
    let lobe = (0..m)
        .map(|k| {
            let t = angle(k);
            if k == m / 2 {
                [0.0; 3]
            } else if t.cos() < 0.0 {
                on_ray(0.5 * A, t, 0.0, 0.5 * A / -t.cos())
            } else {
                on_ray(0.5 * A, t, 0.0, 0.5 * A + 1e-9)
            }
        })
        .collect();
    let oval = (0..m)
        .map(|k| on_ray(0.5 * (B + C), angle(k), 0.0, 0.5 * (C - B) + 0.5 * B))
        .collect();
    (
        polyline(arms, false),
        polyline(lobe, true),
        polyline(oval, true),
    )
}

fn params(d: f64) -> CoverageParams {
    common::coverage_params(d)
}

#[test]
fn a_region_keeps_out_every_other_critical_point_and_a_missing_oval_is_refused() {
    let (a, b) = (saddle_and_oval(), plane());
    // The patch is the construction: f at a few points.
    for (u, v) in [(0.3, 0.7), (0.55, 0.5), (0.9, 0.1)] {
        let p = a.eval(&u, &v);
        assert!((p[2] - f(x_of(u), x_of(v))).abs() < 1e-12, "{p:?}");
    }
    // The branch point at the origin (u = v = ½ on both), proven.
    let s = classify(&a, &b, &[0.5, 0.5], &[0.5, 0.5], 1e-7);
    assert_eq!(s.kind, SingularKind::BranchPoint, "{s:?}");
    let touch = TouchOut {
        point: [0.0; 3],
        uv_a: Some([0.5, 0.5]),
        uv_b: Some([0.5, 0.5]),
        status: None,
        dist_a: None,
        dist_b: None,
        branch_ends: 4,
        singular: Some(s.clone()),
    };

    // The region: around the origin, keeping out the extremum of x² r on (0, a) — the
    // nearest other collinear-normal point.
    let reg = branch_region(&a, &b, &s).expect("a region around the branch point");
    let x1 = critical(1e-6, A - 1e-6);
    let wa = reg.w_a;
    eprintln!(
        "region {:?} {:?} x1 {x1} crit {:?}",
        reg.w_a, reg.w_b, s.critical_on
    );
    assert!(x_of(wa[0]) < 0.0 && 0.0 < x_of(wa[1]), "{wa:?}");
    assert!(
        x_of(wa[1]) < x1,
        "region reaches x = {} past the critical point {x1}",
        x_of(wa[1])
    );

    // The whole truth as the output: certified, with pairs decided by the region.
    let (arms, lobe, oval) = truth();
    let d = 1e-6;
    let all = coverage(
        &a,
        &b,
        &[arms.clone(), lobe.clone(), oval.clone()],
        std::slice::from_ref(&touch),
        &params(d),
    );
    assert!(all.no_missed_branches, "{all:?}");
    assert!(all.branch_point_regions > 0, "{all:?}");

    // Without the oval, refused, with a listed region at the oval.
    let without = coverage(
        &a,
        &b,
        &[arms, lobe],
        std::slice::from_ref(&touch),
        &params(d),
    );
    assert!(!without.no_missed_branches, "{without:?}");
    assert!(
        without
            .uncertified_regions
            .iter()
            .any(|g| g.point.is_some_and(|q| q[0] > B - 1e-3 && q[0] < C + 1e-3)),
        "{:?}",
        without.uncertified_regions
    );
}
