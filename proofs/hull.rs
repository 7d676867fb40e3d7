//! The convex-hull and "near the output" decisions of the SSI coverage certificate
//! (`vericad::ssi::coverage::{patch, near}`): halving encloses the exact de Casteljau halves,
//! the control-point box encloses the exact piece, `separated_along` proves disjoint
//! projections, and `dist_upper`, `Near::box_within`, `Near::net_within` never say "near"
//! wrongly. Oracle: exact rationals.

use crate::common::*;
use vericad::scalar::Interval;
use vericad::ssi::coverage::near::{Near, dist_upper};
use vericad::ssi::coverage::patch::{Box3, ICurve, IPatch, V, hull_box, separated_along};

// ---------------------------------------------------------------- dist_upper

/// `dist_upper(c, p, q)` is at least the exact distance from `c` to the segment `[p, q]`
/// (compared squared, exactly), is never NaN and never negative.
pub fn prop_dist_upper(c: [f64; 3], p: [f64; 3], qq: [f64; 3]) {
    let u = dist_upper(&c, &p, &qq);
    assert!(u >= 0.0, "dist_upper({c:?}, {p:?}, {qq:?}) = {u}");
    if u == f64::INFINITY {
        return;
    }
    let exact = dist2_seg(&q3(&c), &q3(&p), &q3(&qq));
    assert!(
        q(u) * q(u) >= exact,
        "dist_upper({c:?}, {p:?}, {qq:?}) = {u} is below the exact distance {}",
        exact.to_string().chars().take(60).collect::<String>()
    );
}

fn pt(rng: &mut Rng, kind: u64) -> [f64; 3] {
    std::array::from_fn(|_| match kind {
        0 => rng.int(-6, 6) as f64,
        1 => rng.range(-4.0, 4.0),
        2 => rng.scaled(20),
        3 => rng.scaled(170) * 1e-150,
        4 => rng.scaled(10) * 1e150,
        _ => rng.int(-3, 3) as f64 * 0.1 + rng.int(-2, 2) as f64 * 2f64.powi(-40),
    })
}

#[test]
fn dist_upper_bounds_the_exact_distance() {
    let n = cases(10_000, 1_000_000);
    let mut rng = Rng::new(3);
    for i in 0..n {
        let kind = i % 6;
        let (p, qq) = (pt(&mut rng, kind), pt(&mut rng, kind));
        let c = match rng.below(4) {
            // On the segment at a rounded parameter, at an end, or anywhere.
            0 => {
                let t = rng.unit();
                std::array::from_fn(|k| p[k] + t * (qq[k] - p[k]))
            }
            1 => p,
            _ => pt(&mut rng, kind),
        };
        prop_dist_upper(c, p, qq);
        prop_dist_upper(c, p, p);
    }
}

// ---------------------------------------------------------------- box_within / net_within

/// Exact squared distance from `x` to the nearest of `segs`.
fn dist2_to(x: &Q3, segs: &[([f64; 3], [f64; 3])]) -> Q {
    segs.iter()
        .map(|(p, qq)| dist2_seg(x, &q3(p), &q3(qq)))
        .min()
        .expect("segments")
}

/// If `Near::box_within(b, d)` holds, every point of the box (its 8 corners and random
/// interior rationals) lies within `d` of the output segments, exactly. Returns the answer.
pub fn prop_box_within(
    segs: &[([f64; 3], [f64; 3])],
    near: &Near,
    b: &Box3,
    d: f64,
    rng: &mut Rng,
) -> bool {
    if !near.box_within(b, d) {
        return false;
    }
    let d2 = q(d) * q(d);
    let mut pts: Vec<Q3> = (0..8)
        .map(|m| std::array::from_fn(|k| q(if m >> k & 1 == 0 { b.0[k] } else { b.1[k] })))
        .collect();
    for _ in 0..4 {
        pts.push(std::array::from_fn(|k| rng.in_interval(b.0[k], b.1[k])));
    }
    for x in &pts {
        assert!(
            dist2_to(x, segs) <= d2,
            "box_within({b:?}, {d}) said yes, but a point is farther (segments {segs:?})"
        );
    }
    true
}

/// If `Near::net_within(pts, d)` holds — or `Near::net_within_hinted` with a hint naming an
/// arbitrary entry, which is tried first — every point of the convex hull of the enclosed
/// points (exact points chosen inside the interval boxes, and random convex combinations of
/// them) lies within `d` of the output segments, exactly. Returns the answer.
pub fn prop_net_within(
    segs: &[([f64; 3], [f64; 3])],
    near: &Near,
    pts: &[V],
    d: f64,
    rng: &mut Rng,
) -> bool {
    let hint = vericad::ssi::coverage::near::Hint::at(rng.below(64) as u32);
    if !(near.net_within(pts, d) || near.net_within_hinted(pts, d, &hint)) {
        return false;
    }
    let d2 = q(d) * q(d);
    let mut xs: Vec<Q3> = Vec::new();
    for p in pts {
        // All corners of the box, and one interior point.
        for m in 0..8 {
            xs.push(std::array::from_fn(|k| {
                q(if m >> k & 1 == 0 { p[k].lo } else { p[k].hi })
            }));
        }
        xs.push(std::array::from_fn(|k| rng.in_interval(p[k].lo, p[k].hi)));
    }
    for _ in 0..4 {
        let mut acc: Q3 = [zero(), zero(), zero()];
        let mut total = zero();
        for p in pts {
            let w = rng.unit_q();
            let x: Q3 = std::array::from_fn(|k| rng.in_interval(p[k].lo, p[k].hi));
            acc = add3(&acc, &scale3(&x, &w));
            total += w;
        }
        if !total.is_zero() {
            xs.push(scale3(&acc, &(one() / total)));
        }
    }
    for x in &xs {
        assert!(
            dist2_to(x, segs) <= d2,
            "net_within({pts:?}, {d}) said yes, but a hull point is farther"
        );
    }
    true
}

fn random_segments(rng: &mut Rng, ints: bool) -> Vec<([f64; 3], [f64; 3])> {
    let n = 1 + rng.below(6) as usize;
    let mut v = Vec::new();
    let mut a = pt(rng, if ints { 0 } else { 1 });
    for _ in 0..n {
        let step: [f64; 3] = if ints {
            std::array::from_fn(|_| rng.int(-2, 2) as f64)
        } else {
            std::array::from_fn(|_| rng.range(-1.0, 1.0))
        };
        let b = std::array::from_fn(|k| a[k] + step[k]);
        v.push((a, b));
        a = b;
    }
    if rng.below(4) == 0 {
        v.push((a, a)); // a touching point
    }
    v
}

/// Boxes and nets placed at and around random polylines, with match distances around the
/// decision threshold: integer coordinates (exact ties: the corner distance equal to `d`),
/// real coordinates, degenerate boxes, interval control points of positive width.
#[test]
fn near_decisions_are_sound() {
    let n = cases(500, 100_000);
    let mut rng = Rng::new(11);
    let (mut yes_box, mut yes_net) = (0, 0);
    for i in 0..n {
        let ints = i % 2 == 0;
        let segs = random_segments(&mut rng, ints);
        let (p, qq) = segs[rng.below(segs.len() as u64) as usize];
        let t = rng.unit();
        let base: [f64; 3] = std::array::from_fn(|k| p[k] + t * (qq[k] - p[k]));
        let r = [0.5, 0.1, 1e-3, 1e-9][rng.below(4) as usize];
        let off: [f64; 3] = std::array::from_fn(|_| rng.range(-r, r));
        let half: [f64; 3] =
            std::array::from_fn(|_| if rng.coin() { 0.0 } else { rng.range(0.0, r) });
        let b: Box3 = if ints {
            let c: [f64; 3] = std::array::from_fn(|k| (base[k]).round());
            let h: [f64; 3] = std::array::from_fn(|_| rng.int(0, 1) as f64);
            (
                std::array::from_fn(|k| c[k] - h[k]),
                std::array::from_fn(|k| c[k] + h[k]),
            )
        } else {
            (
                std::array::from_fn(|k| base[k] + off[k] - half[k]),
                std::array::from_fn(|k| base[k] + off[k] + half[k]),
            )
        };
        let d = if ints {
            // Integer and square-root distances: ties with corner distances.
            let s = rng.int(0, 12) as f64;
            match rng.below(3) {
                0 => s.sqrt(),
                1 => s.sqrt().next_down(),
                _ => s,
            }
        } else {
            rng.range(0.0, 4.0 * r)
        };
        let near = Near::new(segs.clone());
        yes_box += usize::from(prop_box_within(&segs, &near, &b, d, &mut rng));
        let net: Vec<V> = (0..1 + rng.below(6))
            .map(|_| {
                std::array::from_fn(|k| {
                    let x = base[k] + rng.range(-r, r);
                    if rng.coin() {
                        Interval::point(x)
                    } else {
                        Interval::new(x, x + rng.range(0.0, r))
                    }
                })
            })
            .collect();
        yes_net += usize::from(prop_net_within(&segs, &near, &net, d, &mut rng));
    }
    // The harness is not vacuous: both tests said "near" often.
    assert!(yes_box > n / 10 && yes_net > n / 10, "{yes_box} {yes_net}");
}

/// Chords ([`Near::with_chords`]): polylines sampling a circular arc or a gently wandering
/// curve with short segments (the output of a traced branch), boxes and nets straddling their
/// vertices, match distances around the chords' slack. Every "near" must hold exactly
/// against the output segments themselves (the chords are not part of the output); the
/// harness asserts that chords decided cases single segments could not.
#[test]
fn chord_decisions_are_sound() {
    let n = cases(400, 50_000);
    let mut rng = Rng::new(17);
    let (mut yes, mut by_chord) = (0, 0);
    for i in 0..n {
        let m = 3 + rng.below(40) as usize;
        let radius = [2.0, 1.0, 1e3, 1e-3][rng.below(4) as usize];
        let step = radius * rng.range(1e-4, 2e-2);
        let wander = i % 3 == 0;
        let c: [f64; 3] = std::array::from_fn(|_| rng.range(-1.0, 1.0));
        let pts: Vec<[f64; 3]> = (0..=m)
            .map(|k| {
                let a = k as f64 * step / radius;
                let z = if wander {
                    rng.range(-1.0, 1.0) * step * 1e-3
                } else {
                    0.0
                };
                [c[0] + radius * a.cos(), c[1] + radius * a.sin(), c[2] + z]
            })
            .collect();
        let segs: Vec<_> = pts.windows(2).map(|w| (w[0], w[1])).collect();
        let sag = step * step / (8.0 * radius);
        let d = sag * [0.5, 1.0, 4.0, 16.0, 64.0][rng.below(5) as usize];
        let near = Near::with_chords(segs.clone(), d);
        let single = Near::new(segs.clone());
        // A curve piece along the polyline: points on the arc between two parameters
        // straddling a vertex, as a net of point and interval control points.
        let k = rng.below(m as u64) as f64;
        let (a0, a1) = (
            (k + rng.range(-1.5, 0.5)) * step / radius,
            (k + rng.range(0.5, 2.5)) * step / radius,
        );
        let net: Vec<V> = (0..2 + rng.below(4))
            .map(|j| {
                let a = a0 + (a1 - a0) * rng.unit() * f64::from(j as u8 > 0);
                let r = radius * (1.0 + rng.range(-1.0, 1.0) * sag / radius);
                let x = [c[0] + r * a.cos(), c[1] + r * a.sin(), c[2]];
                std::array::from_fn(|q| {
                    if rng.coin() {
                        Interval::point(x[q])
                    } else {
                        Interval::new(x[q], x[q] + rng.range(0.0, sag))
                    }
                })
            })
            .collect();
        let nb = prop_net_within(&segs, &near, &net, d, &mut rng);
        let lo: [f64; 3] =
            std::array::from_fn(|q| net.iter().map(|p| p[q].lo).fold(f64::INFINITY, f64::min));
        let hi: [f64; 3] = std::array::from_fn(|q| {
            net.iter()
                .map(|p| p[q].hi)
                .fold(f64::NEG_INFINITY, f64::max)
        });
        let bb = prop_box_within(&segs, &near, &(lo, hi), d, &mut rng);
        yes += usize::from(nb) + usize::from(bb);
        by_chord += usize::from(nb && !single.net_within(&net, d))
            + usize::from(bb && !single.box_within(&(lo, hi), d));
    }
    assert!(
        yes > n / 10 && by_chord > n / 20,
        "{yes} near, {by_chord} by a chord"
    );
}

// ---------------------------------------------------------------- separated_along

/// If `separated_along(a, b, n)` holds, the exact projections onto `n` of every point of
/// the boxes of `a` (its corners: the extremes of a linear function) lie strictly on one
/// side of those of `b`: the convex hulls are disjoint. Returns the answer.
pub fn prop_separated_along(a: &[V], b: &[V], n: &[f64; 3]) -> bool {
    if !separated_along(a, b, n) {
        return false;
    }
    let nq = q3(n);
    let proj = |pts: &[V]| -> (Q, Q) {
        let mut v: Vec<Q> = Vec::new();
        for p in pts {
            for m in 0..8 {
                let c: Q3 =
                    std::array::from_fn(|k| q(if m >> k & 1 == 0 { p[k].lo } else { p[k].hi }));
                v.push(dot3(&c, &nq));
            }
        }
        (
            v.iter().min().unwrap().clone(),
            v.iter().max().unwrap().clone(),
        )
    };
    let (ra, rb) = (proj(a), proj(b));
    assert!(
        ra.1 < rb.0 || rb.1 < ra.0,
        "separated_along({a:?}, {b:?}, {n:?}) but the exact projections overlap"
    );
    true
}

#[test]
fn separated_along_is_sound() {
    let n = cases(2_500, 200_000);
    let mut rng = Rng::new(5);
    let mut yes = 0;
    for i in 0..n {
        let ints = i % 3 == 0;
        let dir: [f64; 3] = if ints {
            std::array::from_fn(|_| rng.int(-2, 2) as f64)
        } else {
            std::array::from_fn(|_| rng.range(-1.0, 1.0))
        };
        let gap = [0.0, 1e-17, 1e-12, 0.1][rng.below(4) as usize];
        let mk = |rng: &mut Rng, shift: f64| -> Vec<V> {
            (0..1 + rng.below(5))
                .map(|_| {
                    std::array::from_fn(|k| {
                        let x = if ints {
                            rng.int(-3, 3) as f64
                        } else {
                            rng.range(-1.0, 1.0)
                        } + shift * dir[k];
                        if rng.coin() {
                            Interval::point(x)
                        } else {
                            Interval::new(x, x.next_up())
                        }
                    })
                })
                .collect()
        };
        // Two clouds pushed apart along the direction (by a gap that is sometimes below
        // rounding), or touching.
        let a = mk(&mut rng, 0.0);
        let shift = if ints {
            rng.int(0, 8) as f64
        } else {
            2.0 + gap
        };
        let b = mk(&mut rng, shift);
        yes += usize::from(prop_separated_along(&a, &b, &dir));
    }
    assert!(yes > n / 10, "{yes}");
}

// ---------------------------------------------------------------- halving and hulls

/// Exact de Casteljau halves at 1/2 of a row of exact values.
fn halve_exact(row: &[Q]) -> (Vec<Q>, Vec<Q>) {
    let n = row.len() - 1;
    let mut x = row.to_vec();
    let (mut l, mut r) = (vec![x[0].clone(); n + 1], vec![x[n].clone(); n + 1]);
    let half = ratio(1, 2);
    for level in 1..=n {
        for k in 0..=n - level {
            x[k] = (&x[k] + &x[k + 1]) * &half;
        }
        l[level] = x[0].clone();
        r[n - level] = x[n - level].clone();
    }
    (l, r)
}

/// A patch's exact homogeneous net: `(x, y, z, w)` per control point, row-major.
type Net = Vec<[Q; 4]>;

fn pick_net(h: &IPatch, rng: &mut Rng) -> Net {
    h.x.iter()
        .zip(&h.w)
        .map(|(x, w)| {
            [
                rng.in_interval(x[0].lo, x[0].hi),
                rng.in_interval(x[1].lo, x[1].hi),
                rng.in_interval(x[2].lo, x[2].hi),
                rng.in_interval(w.lo, w.hi),
            ]
        })
        .collect()
}

fn inside(h: &IPatch, net: &Net) -> bool {
    h.x.iter().zip(&h.w).zip(net).all(|((x, w), e)| {
        (0..3).all(|c| in_ext(&e[c], x[c].lo, x[c].hi)) && in_ext(&e[3], w.lo, w.hi)
    })
}

/// For exact control values anywhere inside the enclosures of `h` (positive weights):
/// * `h.halve(along_u)` encloses the exact de Casteljau halves of that exact net;
/// * `hull_box` of `h` (when it gives one) holds every exact Cartesian control point and
///   every exact point of the rational patch at random rational parameters (convex hull
///   property);
/// * `ICurve::halve` on a border row encloses the exact halves of that row.
#[allow(clippy::needless_range_loop)]
pub fn prop_halve_and_hull(h: &IPatch, rng: &mut Rng) {
    let net = pick_net(h, rng);
    for along_u in [true, false] {
        let (l, r) = h.halve(along_u);
        let (n, m) = if along_u { (h.p, h.q) } else { (h.q, h.p) };
        let (mut el, mut er) = (net.clone(), net.clone());
        for line in 0..=m {
            let idx = |k: usize| {
                if along_u {
                    h.at(k, line)
                } else {
                    h.at(line, k)
                }
            };
            for c in 0..4 {
                let row: Vec<Q> = (0..=n).map(|k| net[idx(k)][c].clone()).collect();
                let (lr, rr) = halve_exact(&row);
                for k in 0..=n {
                    el[idx(k)][c] = lr[k].clone();
                    er[idx(k)][c] = rr[k].clone();
                }
            }
        }
        assert!(
            inside(&l, &el),
            "left half (along_u {along_u}) misses the exact half of {h:?}"
        );
        assert!(
            inside(&r, &er),
            "right half (along_u {along_u}) misses the exact half of {h:?}"
        );
    }
    let row = ICurve {
        x: (0..=h.q).map(|j| h.x[h.at(0, j)]).collect(),
        w: (0..=h.q).map(|j| h.w[h.at(0, j)]).collect(),
    };
    let (cl, cr) = row.halve();
    for c in 0..4 {
        let ex: Vec<Q> = (0..=h.q).map(|j| net[h.at(0, j)][c].clone()).collect();
        let (lr, rr) = halve_exact(&ex);
        for (half, exact) in [(&cl, &lr), (&cr, &rr)] {
            for k in 0..=h.q {
                let iv = if c < 3 { half.x[k][c] } else { half.w[k] };
                assert!(
                    in_ext(&exact[k], iv.lo, iv.hi),
                    "ICurve::halve misses the exact half"
                );
            }
        }
    }
    let Some(b) = hull_box(&h.x, &h.w) else {
        return;
    };
    let in_box = |x: &[Q; 4]| (0..3).all(|c| in_ext(&(&x[c] / &x[3]), b.0[c], b.1[c]));
    for e in &net {
        assert!(in_box(e), "hull_box {b:?} misses a control point of {h:?}");
    }
    for _ in 0..3 {
        let (u, v) = (rng.unit_q(), rng.unit_q());
        let x = eval_exact(h.p, h.q, &net, &u, &v);
        assert!(
            in_box(&x),
            "hull_box {b:?} misses a point of the patch {h:?}"
        );
    }
}

/// For any exact values in the enclosures with positive weights, `hull_box` holds `x/w` at
/// all corners of each control point's box (the extremes of `x/w` over a box with `w > 0`).
#[allow(clippy::needless_range_loop)]
pub fn prop_hull_box_corners(x: &[V], w: &[Interval]) {
    let Some(b) = hull_box(x, w) else {
        return;
    };
    for (p, wi) in x.iter().zip(w) {
        assert!(wi.lo > 0.0, "hull_box accepted a weight {wi:?}");
        for c in 0..3 {
            for xv in [p[c].lo, p[c].hi] {
                for wv in [wi.lo, wi.hi] {
                    let e = q(xv) / q(wv);
                    assert!(
                        in_ext(&e, b.0[c], b.1[c]),
                        "hull_box {b:?} misses {xv}/{wv}"
                    );
                }
            }
        }
    }
}

fn random_patch(rng: &mut Rng) -> IPatch {
    let (p, q_) = (1 + rng.below(3) as usize, 1 + rng.below(3) as usize);
    let kind = rng.below(4);
    let rational = rng.coin();
    let n = (p + 1) * (q_ + 1);
    let iv = |rng: &mut Rng, x: f64| match rng.below(3) {
        0 => Interval::point(x),
        1 => Interval::new(x, x.next_up().next_up()),
        _ => Interval::new(x - x.abs() * 1e-9, x + x.abs() * 1e-9),
    };
    let x = (0..n)
        .map(|_| {
            std::array::from_fn(|_| {
                let v = match kind {
                    0 => rng.int(-8, 8) as f64,
                    1 => rng.range(-1.0, 1.0),
                    2 => rng.scaled(30),
                    _ => rng.range(-1.0, 1.0) * 1e-300,
                };
                iv(rng, v)
            })
        })
        .collect();
    let w = (0..n)
        .map(|_| {
            if rational {
                let v = rng.range(0.05, 8.0);
                iv(rng, v)
            } else {
                Interval::point(1.0)
            }
        })
        .collect();
    IPatch { p, q: q_, x, w }
}

/// Random patches of degree 1–3 in each direction, polynomial or rational, with point,
/// ulp-wide and relatively wide interval control points; small integer, real, wide-range
/// and tiny (near-underflow) coordinates.
#[test]
fn halving_and_hulls_enclose_the_exact_pieces() {
    let n = cases(400, 50_000);
    let mut rng = Rng::new(9);
    for _ in 0..n {
        let h = random_patch(&mut rng);
        prop_halve_and_hull(&h, &mut rng);
        // Halving repeatedly compounds roundings: the grandchildren still enclose.
        let (l, _) = h.halve(true);
        let (_, lr) = l.halve(false);
        prop_halve_and_hull(&lr, &mut rng);
        prop_hull_box_corners(&h.x, &h.w);
    }
}

#[test]
fn hull_box_refuses_what_it_cannot_enclose() {
    let p = [Interval::point(1.0); 3];
    for w in [
        Interval::new(-1e-300, 1.0),
        Interval::new(0.0, 1.0),
        Interval::new(-0.0, 1.0),
        Interval::point(f64::NAN),
    ] {
        assert!(hull_box(&[p], &[w]).is_none(), "{w:?}");
    }
    assert!(hull_box(&[[Interval::point(f64::MAX); 3]], &[Interval::point(0.5)]).is_none());
}
