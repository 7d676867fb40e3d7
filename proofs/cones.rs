//! The Sederberg–Meyers separation lemma as implemented by
//! `vericad::ssi::coverage::cones::{separation, cones_separated, normal_generators}`, on which
//! the "transversal" class of the coverage certificate rests.

use crate::common::*;
use vericad::scalar::Interval;
use vericad::ssi::coverage::cones::{cones_separated, normal_generators, separation};
use vericad::ssi::coverage::patch::{IPatch, V};

fn corners(v: &V) -> Vec<Q3> {
    (0..8)
        .map(|m| std::array::from_fn(|k| q(if m >> k & 1 == 0 { v[k].lo } else { v[k].hi })))
        .collect()
}

fn pick(v: &V, rng: &mut Rng) -> Q3 {
    std::array::from_fn(|k| rng.in_interval(v[k].lo, v[k].hi))
}

/// A random non-negative combination (not all zero) of exact vectors chosen in the boxes.
fn combination(g: &[V], rng: &mut Rng) -> Q3 {
    loop {
        let mut acc: Q3 = [zero(), zero(), zero()];
        let mut any = false;
        for v in g {
            let c = if rng.below(3) == 0 {
                zero()
            } else {
                rng.unit_q()
            };
            any |= !c.is_zero();
            acc = add3(&acc, &scale3(&pick(v, rng), &c));
        }
        if any {
            return acc;
        }
    }
}

/// If the test separates generator boxes `a` and `b` with directions `(m, m')`:
/// * exactly, `m·x > 0`, `m'·x > 0` at every corner of every box of `a` and `m·y < 0`,
///   `m'·y > 0` at every corner of every box of `b` (so for every exact generator in the
///   boxes, these being linear);
/// * for single generators and for random non-negative combinations `x` of exact vectors
///   in `a`'s boxes and `y` in `b`'s: `x × y ≠ 0` and `(x × y)·(m × m') > 0` — no parallel
///   or antiparallel normals, and the height along `m × m'` strictly monotone on any
///   intersection curve.
///
/// Returns whether the test separated the cones.
pub fn prop_separation_lemma(a: &[V], b: &[V], rng: &mut Rng) -> bool {
    let Some((m, m2)) = separation(a, b) else {
        assert!(!cones_separated(a, b));
        return false;
    };
    assert!(cones_separated(a, b));
    let (mq, m2q) = (q3(&m), q3(&m2));
    for v in a {
        for c in corners(v) {
            assert!(
                dot3(&c, &mq) > zero() && dot3(&c, &m2q) > zero(),
                "generator box {v:?} of A not on the positive side of m={m:?}, m'={m2:?}"
            );
        }
    }
    for v in b {
        for c in corners(v) {
            assert!(
                dot3(&c, &mq) < zero() && dot3(&c, &m2q) > zero(),
                "generator box {v:?} of B not on the right side of m={m:?}, m'={m2:?}"
            );
        }
    }
    let w = cross3(&mq, &m2q);
    let mut pairs: Vec<(Q3, Q3)> = Vec::new();
    for x in a.iter().take(4) {
        for y in b.iter().take(4) {
            pairs.push((pick(x, rng), pick(y, rng)));
        }
    }
    for _ in 0..6 {
        pairs.push((combination(a, rng), combination(b, rng)));
    }
    for (x, y) in &pairs {
        let c = cross3(x, y);
        assert!(
            c.iter().any(|t| !t.is_zero()),
            "parallel vectors in separated cones {a:?} {b:?}"
        );
        assert!(
            dot3(&c, &w) > zero(),
            "(a × b)·(m × m') <= 0 in separated cones {a:?} {b:?}"
        );
    }
    true
}

/// Unit vector at polar angle `th` from the axis `(0,0,1)` rotated to `axis`, azimuth `ph`
/// (an orthonormal frame around `axis`).
fn around(axis: [f64; 3], th: f64, ph: f64) -> [f64; 3] {
    let l = (axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]).sqrt();
    let n = axis.map(|x| x / l);
    let t = if n[0].abs() < 0.9 {
        [1.0, 0.0, 0.0]
    } else {
        [0.0, 1.0, 0.0]
    };
    let e1 = {
        let c = [
            n[1] * t[2] - n[2] * t[1],
            n[2] * t[0] - n[0] * t[2],
            n[0] * t[1] - n[1] * t[0],
        ];
        let l = (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt();
        c.map(|x| x / l)
    };
    let e2 = [
        n[1] * e1[2] - n[2] * e1[1],
        n[2] * e1[0] - n[0] * e1[2],
        n[0] * e1[1] - n[1] * e1[0],
    ];
    std::array::from_fn(|k| th.cos() * n[k] + th.sin() * (ph.cos() * e1[k] + ph.sin() * e2[k]))
}

/// A cone of `k` generators within angle `spread` of `axis`, lengths varied, as point or
/// interval boxes.
fn cone(rng: &mut Rng, axis: [f64; 3], spread: f64, k: usize, width: f64) -> Vec<V> {
    (0..k)
        .map(|_| {
            let d = around(axis, rng.range(0.0, spread), rng.range(0.0, 6.3));
            let len = [1.0, 1e-3, 1e3, 1e-150][rng.below(4) as usize] * rng.range(0.5, 2.0);
            std::array::from_fn(|c| {
                let x = d[c] * len;
                if width == 0.0 {
                    Interval::point(x)
                } else {
                    let r = width * len * rng.unit();
                    Interval::new(x - r, x + r)
                }
            })
        })
        .collect()
}

/// Random and adversarial cone pairs: narrow and wide cones at angles from nearly parallel
/// (1e-13 rad) through right angles to nearly antiparallel, generators of very different
/// lengths, point and interval generators (boxes that may straddle a separating plane),
/// one cone surrounding the other's axis (the dome over a plane), and generators in exactly
/// orthogonal integer directions.
#[test]
fn separation_lemma_random_and_adversarial() {
    let n = cases(1_500, 200_000);
    let mut rng = Rng::new(21);
    let (mut yes, mut no) = (0, 0);
    for i in 0..n {
        let axis_a = [
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
        ];
        if axis_a.iter().all(|x| x.abs() < 1e-3) {
            continue;
        }
        let angle = match i % 5 {
            0 => 10f64.powi(-(rng.int(1, 13) as i32)),
            1 => std::f64::consts::PI - 10f64.powi(-(rng.int(1, 13) as i32)),
            2 => rng.range(0.0, std::f64::consts::PI),
            3 => std::f64::consts::FRAC_PI_2 + rng.range(-1e-3, 1e-3),
            _ => rng.range(0.0, 0.3),
        };
        let axis_b = around(axis_a, angle, rng.range(0.0, 6.3));
        let spread_a = [0.0, 1e-12, 1e-6, 1e-2, 0.3, 1.2][rng.below(6) as usize];
        let spread_b = [0.0, 1e-12, 1e-6, 1e-2, 0.3, 1.2][rng.below(6) as usize];
        let width = [0.0, 0.0, 1e-15, 1e-9, 1e-3][rng.below(5) as usize];
        let ka = 1 + rng.below(9) as usize;
        let a = cone(&mut rng, axis_a, spread_a, ka, width);
        let b = if i % 7 == 0 {
            // B surrounds A's axis in a ring: never separable when A's axis is inside.
            (0..8)
                .map(|k| {
                    around(axis_a, 0.3, k as f64 * std::f64::consts::FRAC_PI_4).map(Interval::point)
                })
                .collect()
        } else {
            let kb = 1 + rng.below(9) as usize;
            cone(&mut rng, axis_b, spread_b, kb, width)
        };
        if prop_separation_lemma(&a, &b, &mut rng) {
            yes += 1;
        } else {
            no += 1;
        }
    }
    // Exactly orthogonal and exactly parallel integer generators.
    let iv = |x: [i64; 3]| x.map(|c| Interval::point(c as f64));
    for a in -1..=1i64 {
        for b in -1..=1i64 {
            for c in -1..=1i64 {
                let ga = vec![iv([a, b, c]), iv([1, 0, 0])];
                let gb = vec![iv([0, 1, 0]), iv([c, a, b])];
                prop_separation_lemma(&ga, &gb, &mut rng);
                prop_separation_lemma(&gb, &ga, &mut rng);
            }
        }
    }
    assert!(yes > n / 10 && no > n / 10, "separated {yes}, not {no}");
}

// ---------------------------------------------------------------- normals in the cone

/// Exact homogeneous point and first partial derivatives of a Bézier patch at `(u, v)`.
fn eval_d1(p: usize, q_: usize, net: &[[Q; 4]], u: &Q, v: &Q) -> ([Q; 4], [Q; 4], [Q; 4]) {
    // Bernstein basis and its derivative.
    let bern = |n: usize, t: &Q| -> (Vec<Q>, Vec<Q>) {
        let s = one() - t;
        let binom = |n: usize, k: usize| -> Q { qi(vericad::scalar::binomial_i64(n, k)) };
        let pw = |x: &Q, e: usize| -> Q { (0..e).fold(one(), |acc, _| acc * x) };
        let b: Vec<Q> = (0..=n)
            .map(|k| binom(n, k) * pw(t, k) * pw(&s, n - k))
            .collect();
        let d: Vec<Q> = (0..=n)
            .map(|k| {
                let mut r = zero();
                if k >= 1 {
                    r += binom(n, k) * qi(k as i64) * pw(t, k - 1) * pw(&s, n - k);
                }
                if k < n {
                    r -= binom(n, k) * qi((n - k) as i64) * pw(t, k) * pw(&s, n - k - 1);
                }
                r
            })
            .collect();
        (b, d)
    };
    let (bu, du) = bern(p, u);
    let (bv, dv) = bern(q_, v);
    let mut f: [Q; 4] = std::array::from_fn(|_| zero());
    let (mut fu, mut fv) = (f.clone(), f.clone());
    for i in 0..=p {
        for j in 0..=q_ {
            let c = &net[i * (q_ + 1) + j];
            for k in 0..4 {
                f[k] += &bu[i] * &bv[j] * &c[k];
                fu[k] += &du[i] * &bv[j] * &c[k];
                fv[k] += &bu[i] * &dv[j] * &c[k];
            }
        }
    }
    (f, fu, fv)
}

/// For a patch whose normal generators separate from a single direction `t` chosen across
/// the patch's normal, with `(m, m')` the directions found: the exact normal of the exact
/// patch (any exact net inside the enclosures) at random rational parameters, `n ∝
/// (w X_u − w_u X) × (w X_v − w_v X)`, satisfies `m·n > 0` and `m'·n > 0` — the normals of
/// the piece lie where the lemma needs them. Returns whether separation succeeded.
pub fn prop_normals_in_cone(h: &IPatch, polynomial: bool, t: [f64; 3], rng: &mut Rng) -> bool {
    let gens = normal_generators(h, polynomial);
    let Some((m, m2)) = separation(&gens, &[t.map(Interval::point)]) else {
        return false;
    };
    let (mq, m2q) = (q3(&m), q3(&m2));
    let net: Vec<[Q; 4]> =
        h.x.iter()
            .zip(&h.w)
            .map(|(x, w)| {
                [
                    rng.in_interval(x[0].lo, x[0].hi),
                    rng.in_interval(x[1].lo, x[1].hi),
                    rng.in_interval(x[2].lo, x[2].hi),
                    if polynomial {
                        one()
                    } else {
                        rng.in_interval(w.lo, w.hi)
                    },
                ]
            })
            .collect();
    for _ in 0..4 {
        let (u, v) = (rng.unit_q(), rng.unit_q());
        let (f, fu, fv) = eval_d1(h.p, h.q, &net, &u, &v);
        let tu: Q3 = std::array::from_fn(|k| &f[3] * &fu[k] - &fu[3] * &f[k]);
        let tv: Q3 = std::array::from_fn(|k| &f[3] * &fv[k] - &fv[3] * &f[k]);
        let n = cross3(&tu, &tv);
        assert!(
            dot3(&n, &mq) > zero() && dot3(&n, &m2q) > zero(),
            "the exact normal at ({u}, {v}) is outside the separated cone of {h:?}"
        );
    }
    true
}

/// Nearly flat random patches of degree 1–3 (polynomial and rational), bent by a random
/// amount, tested against a direction across their mean normal.
#[test]
fn normals_lie_in_the_separated_cone() {
    let n = cases(600, 20_000);
    let mut rng = Rng::new(31);
    let mut yes = 0;
    for i in 0..n {
        let (p, q_) = (1 + rng.below(3) as usize, 1 + rng.below(3) as usize);
        let polynomial = i % 2 == 0;
        let bend = [0.0, 0.05, 0.3, 1.0][rng.below(4) as usize];
        let mut x = Vec::new();
        let mut w = Vec::new();
        for a in 0..=p {
            for b in 0..=q_ {
                let z = bend * rng.range(-1.0, 1.0);
                let pt = [a as f64 / p as f64, b as f64 / q_ as f64, z];
                let width = [0.0, 1e-12][rng.below(2) as usize];
                x.push(pt.map(|c| Interval::new(c - width, c + width)));
                w.push(if polynomial {
                    Interval::point(1.0)
                } else {
                    Interval::point(rng.range(0.5, 2.0))
                });
            }
        }
        let h = IPatch { p, q: q_, x, w };
        // A direction across the normal (0, 0, 1), tilted by a random angle.
        let th = rng.range(0.3, 1.5);
        let ph = rng.range(0.0, 6.3);
        let t = [th.sin() * ph.cos(), th.sin() * ph.sin(), th.cos()];
        yes += usize::from(prop_normals_in_cone(&h, polynomial, t, &mut rng));
    }
    assert!(yes > n / 10, "{yes}");
}
