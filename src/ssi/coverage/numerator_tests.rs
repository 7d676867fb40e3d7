use super::*;
use crate::scalar::Rational;

fn q(x: f64) -> Rational {
    Rational::try_from(x).unwrap()
}

fn binom(n: usize, k: usize) -> Rational {
    q(binomial_i64(n, k) as f64)
}

/// `B_i^n(t)` in rationals.
fn bern(n: usize, i: usize, t: &Rational) -> Rational {
    let one = q(1.0);
    let mut b = binom(n, i);
    for _ in 0..i {
        b = b * t.clone();
    }
    for _ in i..n {
        b = b * (one.clone() - t.clone());
    }
    b
}

/// `d/dt B_i^n(t) = n (B_{i−1}^{n−1} − B_i^{n−1})`, the textbook rule, in rationals.
fn dbern(n: usize, i: usize, t: &Rational) -> Rational {
    let left = if i > 0 { bern(n - 1, i - 1, t) } else { q(0.0) };
    let right = if i < n { bern(n - 1, i, t) } else { q(0.0) };
    q(n as f64) * (left - right)
}

/// `w X_u − w_u X` (or along v) at `(u, v)` by direct differentiation of the tensor-product
/// sums, exactly: an oracle that shares nothing with the reduced-degree identity.
fn direct(h: &IPatch, along_u: bool, u: &Rational, v: &Rational) -> [Rational; 3] {
    let (mut w, mut dw) = (q(0.0), q(0.0));
    let mut x: [Rational; 3] = std::array::from_fn(|_| q(0.0));
    let mut dx: [Rational; 3] = std::array::from_fn(|_| q(0.0));
    for i in 0..=h.p {
        for j in 0..=h.q {
            let b = bern(h.p, i, u) * bern(h.q, j, v);
            let db = if along_u {
                dbern(h.p, i, u) * bern(h.q, j, v)
            } else {
                bern(h.p, i, u) * dbern(h.q, j, v)
            };
            let k = h.at(i, j);
            let wk = q(h.w[k].lo);
            w = w + b.clone() * wk.clone();
            dw = dw + db.clone() * wk;
            for c in 0..3 {
                let xk = q(h.x[k][c].lo);
                x[c] = x[c].clone() + b.clone() * xk.clone();
                dx[c] = dx[c].clone() + db.clone() * xk;
            }
        }
    }
    std::array::from_fn(|c| w.clone() * dx[c].clone() - dw.clone() * x[c].clone())
}

/// The reduced-degree coefficients enclose the exact numerator: at random parameters of
/// random rational patches (degrees 1…4 each way, weights in [0.5, 2], point data), the
/// Bernstein sum of the coefficients' lower (upper) ends bounds the exact value from below
/// (above) — the Bernstein basis is non-negative — and the enclosure is tight.
#[test]
fn reduced_numerator_encloses_the_exact_derivative() {
    let mut r = crate::spline::test_params::rng(0x5eed_0f_da7a);
    for case in 0..60 {
        let (p, qd) = (1 + case % 4, 1 + (case / 4) % 4);
        let n = (p + 1) * (qd + 1);
        let h = IPatch {
            p,
            q: qd,
            x: (0..n)
                .map(|_| std::array::from_fn(|_| Interval::point(4.0 * r() - 2.0)))
                .collect(),
            w: (0..n).map(|_| Interval::point(0.5 + 1.5 * r())).collect(),
        };
        for along_u in [true, false] {
            let (rows, cols, net) = derivative_numerator_net(&h, along_u).unwrap();
            let (er, ec) = if along_u {
                (2 * p - 2, 2 * qd)
            } else {
                (2 * p, 2 * qd - 2)
            };
            assert_eq!((rows, cols), (er, ec));
            for _ in 0..4 {
                let (u, v) = (q(r()), q(r()));
                let exact = direct(&h, along_u, &u, &v);
                for c in 0..3 {
                    let (mut lo, mut hi) = (q(0.0), q(0.0));
                    for k in 0..=rows {
                        for s in 0..=cols {
                            let b = bern(rows, k, &u) * bern(cols, s, &v);
                            let d = net[k * (cols + 1) + s][c];
                            lo = lo + b.clone() * q(d.lo);
                            hi = hi + b * q(d.hi);
                        }
                    }
                    assert!(
                        lo <= exact[c] && exact[c] <= hi,
                        "case {case} u-dir {along_u}"
                    );
                    let width: f64 = crate::scalar::Scalar::to_f64(&(hi - lo));
                    assert!(width <= 1e-12, "case {case}: width {width}");
                }
            }
        }
    }
}

/// A hand-computed case: homogeneous `X = (2u, 0, 0)`, `w = 1 + u` (degree 1 in u, 0 in v)
/// give `w X_u − w_u X = 2(1 + u) − 2u = 2`: one coefficient `(2, 0, 0)`, exactly. No
/// derivative across a direction of degree 0.
#[test]
fn linear_rational_numerator_is_exact() {
    let h = IPatch {
        p: 1,
        q: 0,
        x: vec![
            [0.0, 0.0, 0.0].map(Interval::point),
            [2.0, 0.0, 0.0].map(Interval::point),
        ],
        w: vec![Interval::point(1.0), Interval::point(2.0)],
    };
    let (rows, cols, net) = derivative_numerator_net(&h, true).unwrap();
    assert_eq!((rows, cols), (0, 0));
    assert_eq!(net[0][0], Interval::point(2.0));
    assert_eq!(net[0][1], Interval::point(0.0));
    assert!(derivative_numerator_net(&h, false).is_none());
}
