//! Normal cones of Bézier pieces and the Sederberg–Meyers separation test.
//!
//! The normal `S_u × S_v` of a piece is a non-negative combination of the cross products
//! `A_k × B_l` of the Bernstein coefficients of `A ∝ S_u` and `B ∝ S_v` (`A = w X_u − w_u X`,
//! `B = w X_v − w_v X` for homogeneous `(X, w)`, in Bernstein form of reduced degree,
//! [`super::numerator`]; the hodographs themselves for polynomial pieces; the positive
//! factor `1/w²` does not change directions). These cross products, enclosed in intervals, are the cone's *generators*.
//!
//! **Separation lemma.** If vectors `m`, `m'` satisfy `m·a > 0 > m·b` and `m'·a > 0`,
//! `m'·b > 0` for every generator `a` of cone A and `b` of cone B, then for every non-zero
//! `a ∈ A`, `b ∈ B`, with `w = m × m'`: `(a × b)·w = (a·m)(b·m') − (a·m')(b·m) > 0`. Hence
//! (i) no normal of A is parallel or antiparallel to a normal of B, (ii) both pieces are
//! regular (`m·n_A > 0` so `n_A ≠ 0`), and (iii) along any intersection curve of the two
//! pieces, whose tangent is parallel to `n_A × n_B`, the height `w·x` is strictly monotone:
//! the curve cannot close (Sederberg & Meyers 1988). Every sign is taken on an interval
//! enclosure and counts only when the whole interval has it.

use super::numerator::derivative_numerator_net;
use super::patch::{IPatch, V, cross, derivative_numerator, hull_finite_v};
use crate::scalar::Interval;

/// Normal-cone generators of a piece; empty when one may vanish or overflow (no cone is then
/// claimed, and no separation can be shown).
pub fn normal_generators(h: &IPatch, polynomial: bool) -> Vec<V> {
    let (a, b) = if polynomial {
        let (Some(hu), Some(hv)) = (h.hodograph(true), h.hodograph(false)) else {
            return Vec::new();
        };
        (hu.x, hv.x)
    } else {
        // `w X_u − w_u X` and `w X_v − w_v X` in Bernstein form of reduced degree.
        match (
            derivative_numerator_net(h, true),
            derivative_numerator_net(h, false),
        ) {
            (Some(a), Some(b)) => (a.2, b.2),
            _ => return Vec::new(),
        }
    };
    let mut out = Vec::with_capacity(a.len() * b.len());
    for x in &a {
        for y in &b {
            let c = cross(x, y);
            if c.iter().all(|v| v.contains_zero()) || !c.iter().all(|v| v.is_finite()) {
                return Vec::new();
            }
            out.push(c);
        }
    }
    out
}

/// One interval vector holding every normal `A × B` of a piece — a cone of one generator:
/// `A = w X_u − w_u X` (the hodograph `X_u` alone for polynomial pieces) and `B` alike, each
/// factor enclosed by the hull of its Bernstein coefficients (a Bézier function takes its
/// values in the hull of its coefficients), and interval products and cross product
/// enclose the rest. Every normal is this box's element, so the separation lemma holds with
/// it as the only generator. Far coarser than [`normal_generators`] on large pieces and far
/// cheaper (no Bernstein products): tried first. `None` when an enclosure fails or holds 0.
pub fn normal_box(h: &IPatch, polynomial: bool) -> Option<V> {
    let (hu, hv) = (h.hodograph(true)?, h.hodograph(false)?);
    let side = |d: &IPatch| -> Option<V> {
        if polynomial {
            return hull_finite_v(&d.x);
        }
        derivative_numerator(&h.x, &h.w, &d.x, &d.w).map(|(n, _)| n)
    };
    let n = cross(&side(&hu)?, &side(&hv)?);
    (n.iter().all(Interval::is_finite) && !n.iter().all(Interval::contains_zero)).then_some(n)
}

/// Whether `m · x > 0` for every `x` in the box `v`, proven. The least value over the box
/// is `Σ_k m_k e_k` with `e_k` the end of `v_k` on the side of `−sign(m_k)` (the terms are
/// independent); its rounded sum `t` of rounded products is within `γ_3 Σ |m_k e_k|` of it
/// (Higham §3.1, an inner product of length 3), plus `3 · 2⁻¹⁰⁷⁵` for products below the
/// normal range. With `S` the rounded sum of the `|fl(m_k e_k)|`, the bound is below
/// `3.01 u S + 2⁻¹⁰⁷²`, so `t > 3.02 u S` (the right side's own roundings inside the margin)
/// together with `t > 10⁻³⁰⁰` (then `0.01 u S ≥ 0.0099 u t` exceeds the underflow term)
/// proves the least value positive. Not finite: not proven.
fn positive(m: &[f64; 3], v: &V) -> bool {
    let e = |k: usize| if m[k] >= 0.0 { v[k].lo } else { v[k].hi };
    let p = [m[0] * e(0), m[1] * e(1), m[2] * e(2)];
    let t = p[0] + p[1] + p[2];
    let s = p[0].abs() + p[1].abs() + p[2].abs();
    t > 3.02 * f64::EPSILON / 2.0 * s && t > 1e-300
}

fn unit_mean(v: &[V]) -> Option<[f64; 3]> {
    let mut s = [0.0; 3];
    for x in v {
        let f: [f64; 3] = std::array::from_fn(|k| x[k].mid());
        let l = (f[0] * f[0] + f[1] * f[1] + f[2] * f[2]).sqrt();
        if l > 0.0 && l.is_finite() {
            for k in 0..3 {
                s[k] += f[k] / l;
            }
        }
    }
    let n = (s[0] * s[0] + s[1] * s[1] + s[2] * s[2]).sqrt();
    (n > 0.0 && n.is_finite()).then(|| s.map(|c| c / n))
}

/// Whether the two cones are proven to hold no parallel vectors (the separation lemma, with
/// `m`, `m'` the difference and sum of the generators' unit means; the lemma holds for any
/// choice, the choice only decides how often it succeeds).
pub fn cones_separated(a: &[V], b: &[V]) -> bool {
    separation(a, b).is_some()
}

/// The directions `(m, m')` of the separation lemma when the test succeeds: `m·a > 0`,
/// `m'·a > 0`, `m·b < 0`, `m'·b > 0` proven for every generator `a` of A and `b` of B.
pub fn separation(a: &[V], b: &[V]) -> Option<([f64; 3], [f64; 3])> {
    if a.is_empty() || b.is_empty() {
        return None;
    }
    let (Some(ua), Some(ub)) = (unit_mean(a), unit_mean(b)) else {
        return None;
    };
    let m: [f64; 3] = std::array::from_fn(|k| ua[k] - ub[k]);
    let m2: [f64; 3] = std::array::from_fn(|k| ua[k] + ub[k]);
    let neg_m = m.map(|c| -c);
    let ok = a.iter().all(|x| positive(&m, x) && positive(&m2, x))
        && b.iter().all(|y| positive(&neg_m, y) && positive(&m2, y));
    ok.then_some((m, m2))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn v(x: f64, y: f64, z: f64) -> V {
        [x, y, z].map(Interval::point)
    }

    /// The paraboloid `z = u² + v²` over the unit square as a biquadratic patch (x = u,
    /// y = v): its normal `S_u × S_v = (−2u, −2v, 1)` lies in the one-box cone at every
    /// sample, and as a rational patch (all weights 2, the same surface) `A × B` is `w⁴` times
    /// it; a plane tilted away is separated from it by the boxes alone, one whose normal is
    /// the paraboloid's at a corner is not.
    #[test]
    fn the_normal_box_holds_every_normal() {
        let a = [0.0, 0.0, 1.0];
        let xy = [0.0, 0.5, 1.0];
        for w in [1.0, 2.0] {
            let patch = IPatch {
                p: 2,
                q: 2,
                x: (0..9)
                    .map(|k| {
                        let (i, j) = (k / 3, k % 3);
                        v(w * xy[i], w * xy[j], w * (a[i] + a[j]))
                    })
                    .collect(),
                w: vec![Interval::point(w); 9],
            };
            let n = normal_box(&patch, w == 1.0).unwrap();
            let w4 = w.powi(4);
            for i in 0..=10 {
                for j in 0..=10 {
                    let (u, t) = (i as f64 / 10.0, j as f64 / 10.0);
                    let exact = [-2.0 * u * w4, -2.0 * t * w4, w4];
                    for k in 0..3 {
                        assert!(
                            n[k].lo <= exact[k] && exact[k] <= n[k].hi,
                            "{w} {u} {t} {n:?}"
                        );
                    }
                }
            }
            // A plane with normal (1, 1, 0.5): never parallel to any (−2u, −2v, 1).
            let apart = [v(1.0, 1.0, 0.5)];
            assert!(cones_separated(&[n], &apart));
            let corner = [v(-2.0, -2.0, 1.0)];
            assert!(!cones_separated(&[n], &corner));
        }
    }

    /// `positive` never claims a sign the exact least value over the box does not have:
    /// checked in rationals at every corner, on boxes whose dot product with `m` cancels to
    /// within a few ulps of zero, at magnitudes 1e-320 … 1e300; and it is not vacuous.
    #[test]
    fn positive_is_proven() {
        use crate::scalar::Rational;
        let q = |x: f64| Rational::try_from(x).unwrap();
        let mut r = crate::spline::test_params::rng(0x9e37_79b9_7f4a_7c15);
        let mut next = || r() - 0.5;
        let mut claimed = 0;
        for k in 0..20_000 {
            let scale = 10f64.powi((k % 63) * 10 - 320);
            let m = [next(), next(), next()];
            let mut v: V = std::array::from_fn(|_| {
                let c = next() * scale;
                Interval::new(c, c + next().abs() * scale * 1e-12)
            });
            // Make m · lo nearly cancel: v_2 from the other two, then nudged a few ulps.
            if m[2] != 0.0 && k % 2 == 0 {
                let c = -(m[0] * v[0].lo + m[1] * v[1].lo) / m[2];
                let c = match k % 6 {
                    0 => c,
                    2 => c.next_up().next_up(),
                    _ => c.next_down().next_down(),
                };
                v[2] = Interval::point(c);
            }
            if !positive(&m, &v) {
                continue;
            }
            claimed += 1;
            for corner in 0..8 {
                let e: Vec<f64> = (0..3)
                    .map(|i| {
                        if corner >> i & 1 == 0 {
                            v[i].lo
                        } else {
                            v[i].hi
                        }
                    })
                    .collect();
                let dot = (0..3).fold(Rational::ZERO, |s, i| s + q(m[i]) * q(e[i]));
                assert!(dot > q(0.0), "{m:?} {v:?}: corner {corner} gives {dot}");
            }
        }
        assert!(claimed > 3000, "{claimed}");
    }

    #[test]
    fn separation_needs_every_generator() {
        let a = vec![v(0.1, 0.0, 1.0), v(-0.1, 0.0, 1.0)];
        let b = vec![v(1.0, 0.0, 0.1), v(1.0, 0.1, 0.0)];
        assert!(cones_separated(&a, &b));
        // A generator of B parallel to one of A: never separated.
        let b2 = vec![v(1.0, 0.0, 0.1), v(0.2, 0.0, 2.0)];
        assert!(!cones_separated(&a, &b2));
        // Antiparallel also counts as parallel.
        let b3 = vec![v(1.0, 0.0, 0.1), v(-0.1, 0.0, -1.0)];
        assert!(!cones_separated(&a, &b3));
        // A cone surrounding the other's direction (the dome over a plane).
        let ring: Vec<V> = (0..8)
            .map(|k| {
                let t = k as f64 * std::f64::consts::FRAC_PI_4;
                v(0.3 * t.cos(), 0.3 * t.sin(), 1.0)
            })
            .collect();
        assert!(!cones_separated(&ring, &[v(0.0, 0.0, 1.0)]));
        assert!(!cones_separated(&[], &b));
    }
}
