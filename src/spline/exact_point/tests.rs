use super::*;
use crate::scalar::Scalar;
use crate::spline::construct::{Frame, sphere, torus};
use crate::spline::test_params::rng;

fn q(x: f64) -> Rational {
    Rational::try_from(x).unwrap()
}

/// `N_{i,p}(t)` by the Cox–de Boor recursion (triangular definition, not A2.2).
fn basis(knots: &[f64], p: usize, i: usize, t: &Rational) -> Rational {
    let k = |j: usize| q(knots[j]);
    if p == 0 {
        // Half-open spans; the last non-empty span closed at the domain's end.
        let n = knots.len();
        let end = knots[n - 1];
        let inside = (k(i) <= *t && *t < k(i + 1))
            || (*t == q(end) && knots[i + 1] == end && knots[i] < end);
        return if inside {
            Rational::ONE
        } else {
            Rational::ZERO
        };
    }
    let mut r = Rational::ZERO;
    if knots[i + p] != knots[i] {
        r += (t - k(i)) / (k(i + p) - k(i)) * basis(knots, p - 1, i, t);
    }
    if knots[i + p + 1] != knots[i + 1] {
        r += (k(i + p + 1) - t) / (k(i + p + 1) - k(i + 1)) * basis(knots, p - 1, i + 1, t);
    }
    r
}

/// The oracle: the same formula (eq. 4.9) summed term by term in reduced rationals, every
/// basis function by the Cox–de Boor recursion written out here (not the crate's A2.2).
fn oracle(s: &NurbsSurface<f64, 3>, u: f64, v: f64) -> [Rational; 3] {
    let h = &s.hom;
    let (ku, kv) = (h.ku.knots(), h.kv.knots());
    let (nu, nv) = (h.ku.n_ctrl(), h.kv.n_ctrl());
    let (tu, tv) = (q(u), q(v));
    let mut num: [Rational; 3] = Default::default();
    let mut den = Rational::ZERO;
    for i in 0..nu {
        let a = basis(ku, h.ku.degree(), i, &tu);
        if a.is_zero() {
            continue;
        }
        for j in 0..nv {
            let b = basis(kv, h.kv.degree(), j, &tv);
            let c = &h.net[i * nv + j];
            let ab = &a * &b;
            for k in 0..3 {
                num[k] += &ab * q(c.wp[k]);
            }
            den += &ab * q(c.w);
        }
    }
    std::array::from_fn(|k| &num[k] / &den)
}

/// Exact points of a rational sphere and torus in rotated, shifted frames equal the
/// term-by-term rational sum, at random parameters, knots and domain ends included.
#[test]
fn exact_points_equal_the_rational_sum() {
    let mut r = rng(0x9e37_79b9_7f4a_7c15);
    let frame = Frame {
        o: [1.25, -3.5, 1e3],
        x: [0.6, 0.8, 0.0],
        y: [-0.8, 0.6, 0.0],
        z: [0.0, 0.0, 1.0],
    };
    for s in [
        sphere(&frame, 2.0).unwrap(),
        torus(&frame, 3.0, 0.7).unwrap(),
    ] {
        let ev = ExactEvaluator::new(&s).unwrap();
        let (_, u1, v0, _) = s.hom.domain();
        for k in 0..60 {
            let (u, v) = crate::spline::test_params::params(&s, k, &mut r);
            let p = ev.point(u, v).unwrap();
            let want = oracle(&s, u, v);
            for c in 0..3 {
                assert_eq!(
                    p.rational()[c].clone(),
                    want[c],
                    "({u}, {v}) coordinate {c}"
                );
            }
            // The enclosure holds the value and is a few ulps wide.
            let e = p.enclosed().unwrap();
            for c in 0..3 {
                assert!(q(e[c].lo) <= want[c] && want[c] <= q(e[c].hi));
                let f = Scalar::to_f64(&want[c]);
                assert!(e[c].hi - e[c].lo <= 1e-15 * f.abs().max(1e-300));
            }
        }
        assert!(ev.point(u1 + 1.0, v0).is_none());
        assert!(ev.point(f64::NAN, v0).is_none());
    }
}

/// The difference of two points is enclosed to a few ulps of the difference itself, down to
/// points one ulp of `u` apart (a difference about 1e-16 of the coordinates, where an f64
/// enclosure of each point would be as wide as the difference).
#[test]
fn differences_are_enclosed_relative_to_themselves() {
    let s = sphere(&Frame::WORLD, 2.0).unwrap();
    let ev = ExactEvaluator::new(&s).unwrap();
    let (u0, u1, v0, v1) = s.hom.domain();
    let (u, v) = (u0 + 0.3 * (u1 - u0), v0 + 0.6 * (v1 - v0));
    let a = ev.point(u, v).unwrap();
    for du in [0.0, u.next_up() - u, f64::EPSILON * u, 1e-12, 1e-3] {
        let b = ev.point(u + du, v).unwrap();
        let d = a.minus_enclosed(&b).unwrap();
        let (wa, wb) = (oracle(&s, u, v), oracle(&s, u + du, v));
        for c in 0..3 {
            let exact = &wa[c] - &wb[c];
            assert!(q(d[c].lo) <= exact && exact <= q(d[c].hi), "{du} {c}");
            let f = Scalar::to_f64(&exact).abs();
            assert!(
                d[c].hi - d[c].lo <= 1e-15 * f + 4.0 * f64::MIN_POSITIVE,
                "{du} {c}"
            );
        }
    }
}

/// `ratio_enclosed` holds `n 2^e / d` for random integers of 1–300 bits, signs and
/// exponents from -1200 to 1200 (underflow to the subnormal range and overflow included).
#[test]
fn ratios_are_enclosed() {
    let mut r = rng(0x2545_f491_4f6c_dd1d);
    let mut big = |bits: usize| {
        let mut x = BigInt::ZERO;
        for _ in 0..bits.div_ceil(50) {
            x = (x << 50usize) + BigInt::from((r() * (1u64 << 50) as f64) as u64);
        }
        x >> (bits.div_ceil(50) * 50 - bits)
    };
    for k in 0..2000usize {
        let mut n = big(1 + k % 300) + 1u32;
        let mut d = big(1 + (k * 7) % 300) + 1u32;
        if k % 3 == 0 {
            n = -n;
        }
        if k % 5 == 0 {
            d = -d;
        }
        let e = (k as i64 * 37) % 2400 - 1200;
        let exact = ratio(n.clone(), d.clone()) * pow2(e);
        match ratio_enclosed(&n, &d, e) {
            Some(i) => {
                assert!(q(i.lo) <= exact && exact <= q(i.hi), "{n} {d} {e}: {i:?}");
                if i.lo.abs() > 1e-300 && i.hi.abs() < 1e300 {
                    assert!(i.hi - i.lo <= 1e-15 * i.lo.abs().max(i.hi.abs()));
                }
            }
            None => assert!(exact.abs() > q(1e300), "{n} {d} {e}"),
        }
    }
    assert_eq!(
        ratio_enclosed(&BigInt::ZERO, &BigInt::ONE, 5),
        Some(Interval::point(0.0))
    );
    assert_eq!(ratio_enclosed(&BigInt::ONE, &BigInt::ZERO, 5), None);
}

#[test]
fn decode_is_exact() {
    for x in [
        0.0,
        -0.0,
        1.0,
        -1.5,
        1e-310,
        f64::MIN_POSITIVE,
        f64::MAX,
        0.1,
    ] {
        let (m, e) = decode(x);
        assert_eq!(Rational::from(m) * pow2(e), q(x), "{x}");
    }
}

/// The fraction-free numerators are the basis values over one common denominator: `a_i / Σ a`
/// (the basis sums to one) equals the Cox–de Boor value exactly, on random clamped knot
/// vectors of degrees 0–7 (repeated and 1e-12-close knots) at magnitudes 1e-300 … 1e300,
/// parameters inside spans, at knots, one ulp past them and at the domain's end.
#[test]
fn basis_numerators_are_the_basis_over_one_denominator() {
    let mut r = rng(0x0ba5_e0ff_1e1d);
    let mut checked = 0;
    for case in 0..300 {
        let p = case % 8;
        let scale = 10f64.powi((case as i32 % 61) * 10 - 300);
        let inner = 1 + (r() * 5.0) as usize;
        let knots = crate::spline::test_params::clamped_knots(&mut r, p, inner, scale);
        let Ok(kv) = KnotVector::new(knots.clone(), p, knots.len() - p - 1) else {
            continue;
        };
        for trial in 0..4 {
            let (a, b) = (knots[p], knots[knots.len() - 1 - p]);
            let mut pick = || knots[p + 1 + (r() * inner as f64) as usize % inner];
            let x = match trial {
                0 => a + r() * (b - a),
                1 => pick(),
                2 => pick().next_up().min(b),
                _ => b,
            };
            let span = kv.find_span(&x);
            let a = basis_numerators(&knots, p, span, x);
            assert_eq!(a.len(), p + 1);
            let sum: BigInt = a.iter().sum();
            assert!(!sum.is_zero(), "case {case}: zero denominator");
            for (i, ai) in a.iter().enumerate() {
                let want = basis(&knots, p, span - p + i, &q(x));
                let got = ratio(ai.clone(), sum.clone());
                assert_eq!(got, want, "case {case} p {p} x {x:e} i {i}");
            }
            checked += 1;
        }
    }
    assert!(checked > 900, "only {checked} parameters checked");
}
