//! Exact root isolation on (0, 1) in the Bernstein basis: Bernstein–Descartes bisection on
//! integer-scaled coefficients (additions and shifts only), and the modular certificate of
//! square-freeness that guarantees its termination.

use crate::scalar::{BigInt, BigUint, Rational, Scalar, int_sign, ratio};
use dashu_int::ops::Gcd;

/// Exact integer Bernstein coefficients proportional (by one positive factor) to `b`.
pub fn integer_bernstein(b: &[Rational]) -> Vec<BigInt> {
    // The least common multiple of the (positive) denominators.
    let l = b.iter().fold(BigUint::ONE, |acc, x| {
        let d = x.denominator();
        let g = (&acc).gcd(d);
        acc / g * d
    });
    b.iter()
        .map(|x| x.numerator() * BigInt::from(&l / x.denominator()))
        .collect()
}

fn variations(c: &[BigInt]) -> usize {
    let mut last = 0i8;
    let mut v = 0;
    for x in c {
        let s = int_sign(x).as_i8();
        if s != 0 {
            if last != 0 && s != last {
                v += 1;
            }
            last = s;
        }
    }
    v
}

/// Split integer Bernstein coefficients at `t = 1/2`; both halves scaled by `2^m` (a positive
/// factor, irrelevant to signs). Additions only.
fn halve(c: &[BigInt]) -> (Vec<BigInt>, Vec<BigInt>) {
    let m = c.len() - 1;
    let mut level = c.to_vec();
    let mut left = Vec::with_capacity(m + 1);
    let mut right = Vec::with_capacity(m + 1);
    left.push(&level[0] << m);
    right.push(&level[m] << m);
    for r in 1..=m {
        for i in 0..=m - r {
            level[i] = &level[i] + &level[i + 1];
        }
        left.push(&level[0] << (m - r));
        right.push(&level[m - r] << (m - r));
    }
    right.reverse();
    (left, right)
}

/// A root isolated in `[lo, hi]` (`lo == hi` when the root is exactly a dyadic point).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RootInterval {
    pub lo: Rational,
    pub hi: Rational,
}

fn dyadic(k: &BigInt, d: u32) -> Rational {
    ratio(k.clone(), BigInt::ONE << d as usize)
}

/// Roots in the open interval `(0, 1)` of the polynomial with integer Bernstein coefficients
/// `c`, isolated by exact Bernstein–Descartes bisection (variation diminishing: no sign
/// variation ⇒ no root in the open interval; one ⇒ exactly one simple root). A root that
/// lands exactly on a bisection point is recorded as a point. Intervals holding one root are
/// halved further until they are at least `min_depth` levels deep (width `2^-min_depth`).
///
/// Terminates for square-free polynomials (root separation); returns `None` when
/// `max_depth` is reached first (a repeated root): the caller then uses Sturm sequences.
/// Exact: integer additions and shifts only.
pub fn descartes_isolate(
    c: &[BigInt],
    max_depth: u32,
    min_depth: u32,
) -> Option<Vec<RootInterval>> {
    let mut out = Vec::new();
    let mut stack = vec![(c.to_vec(), BigInt::ZERO, 0u32)];
    while let Some((cc, k, d)) = stack.pop() {
        let v = variations(&cc);
        if v == 0 || (v == 1 && d >= min_depth) {
            if v == 1 {
                out.push(RootInterval {
                    lo: dyadic(&k, d),
                    hi: dyadic(&(&k + 1), d),
                });
            }
            continue;
        }
        if d >= max_depth {
            return None;
        }
        let (l, r) = halve(&cc);
        let k2 = &k << 1;
        // The shared coefficient is the (scaled) value at the midpoint.
        if l[l.len() - 1].is_zero() {
            let m = dyadic(&(&k2 + 1), d + 1);
            out.push(RootInterval {
                lo: m.clone(),
                hi: m,
            });
        }
        stack.push((r, &k2 + 1, d + 1));
        stack.push((l, k2, d + 1));
    }
    out.sort_by(|a, b| a.lo.cmp(&b.lo));
    Some(out)
}

/// Power-basis integer coefficients of the polynomial with integer Bernstein coefficients
/// `b` (exact: `a_k = Σ_{i<=k} b_i C(n,i) C(n-i,k-i) (-1)^{k-i}`).
pub fn integer_power_from_bernstein(b: &[BigInt]) -> Vec<BigInt> {
    let n = b.len().saturating_sub(1);
    let mut a = vec![BigInt::ZERO; n + 1];
    for (i, bi) in b.iter().enumerate() {
        for k in i..=n {
            let w = BigInt::from(crate::scalar::binomial_i64(n, i))
                * BigInt::from(crate::scalar::binomial_i64(n - i, k - i));
            if (k - i) % 2 == 0 {
                a[k] += bi * w;
            } else {
                a[k] -= bi * w;
            }
        }
    }
    while a.last().is_some_and(|x| x.is_zero()) {
        a.pop();
    }
    a
}

/// Remove the factors `t` and `t - 1` (roots at the interval ends) from integer power
/// coefficients; exact (synthetic division by a monic factor).
pub fn deflate_ends(mut a: Vec<BigInt>) -> Vec<BigInt> {
    while a.len() > 1 && a[0].is_zero() {
        a.remove(0);
    }
    while a.len() > 1 && a.iter().fold(BigInt::ZERO, |s, x| s + x).is_zero() {
        // a(t) = (t - 1) q(t): q_{n-1} = a_n, q_{k-1} = a_k + q_k.
        let n = a.len() - 1;
        let mut q = vec![BigInt::ZERO; n];
        q[n - 1] = a[n].clone();
        for k in (1..n).rev() {
            q[k - 1] = &a[k] + &q[k];
        }
        a = q;
    }
    a
}

fn inv_mod(x: u128, p: u128) -> u128 {
    // Fermat: x^(p-2) mod p.
    let (mut base, mut e, mut r) = (x % p, p - 2, 1u128);
    while e > 0 {
        if e & 1 == 1 {
            r = r * base % p;
        }
        base = base * base % p;
        e >>= 1;
    }
    r
}

fn poly_gcd_degree_mod(mut f: Vec<u128>, mut g: Vec<u128>, p: u128) -> usize {
    let trim = |v: &mut Vec<u128>| {
        while v.last() == Some(&0) {
            v.pop();
        }
    };
    trim(&mut f);
    trim(&mut g);
    while !g.is_empty() {
        // f mod g
        let lg = inv_mod(*g.last().unwrap_or(&1), p);
        while f.len() >= g.len() {
            let shift = f.len() - g.len();
            let c = f[f.len() - 1] * lg % p;
            for (j, gj) in g.iter().enumerate() {
                f[shift + j] = (f[shift + j] + p - c * gj % p) % p;
            }
            trim(&mut f);
            if f.is_empty() {
                break;
            }
        }
        std::mem::swap(&mut f, &mut g);
    }
    f.len().saturating_sub(1)
}

/// A certificate that the integer polynomial `a` (power basis) is square-free: for a prime
/// `p` not dividing its leading coefficient, `gcd(a mod p, a' mod p) = 1` implies
/// `gcd(a, a') = 1` over ℚ (a repeated factor of `a` would survive reduction mod `p` with
/// its degree). `false` means "not certified" (repeated root, or unlucky primes).
pub fn certify_squarefree(a: &[BigInt]) -> bool {
    if a.len() <= 2 {
        return true;
    }
    const PRIMES: [u64; 3] = [
        2_305_843_009_213_693_951,
        4_611_686_018_427_387_847,
        1_000_000_007,
    ];
    for p in PRIMES {
        let pb = BigInt::from(p);
        let red: Vec<u128> = a
            .iter()
            .map(|x| {
                let r = ((x % &pb) + &pb) % &pb;
                u128::try_from(r).unwrap_or(0)
            })
            .collect();
        let p = p as u128;
        if red.last() == Some(&0) {
            continue;
        }
        let der: Vec<u128> = red
            .iter()
            .enumerate()
            .skip(1)
            .map(|(k, x)| (k as u128 % p) * x % p)
            .collect();
        if poly_gcd_degree_mod(red, der, p) == 0 {
            return true;
        }
    }
    false
}

/// Sign of the polynomial with Bernstein coefficients `b` at the rational `t` (exact).
pub fn bernstein_sign_at(b: &[Rational], t: &Rational) -> i8 {
    let mut v = b.to_vec();
    let n = v.len();
    for level in 1..n {
        for i in 0..n - level {
            v[i] = &v[i] + (&v[i + 1] - &v[i]) * t;
        }
    }
    Scalar::sign(&v[0]).as_i8()
}

#[cfg(test)]
mod descartes_tests {
    use super::*;
    use crate::predicates::poly::{Poly, count_roots};

    /// The Descartes fast path and Sturm's theorem count the same sign changes, and the
    /// square-free certificate never certifies a polynomial with a repeated root.
    #[test]
    fn descartes_agrees_with_sturm() {
        let mut seed = 7u64;
        let mut next = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((seed >> 33) % 21) as i64 - 10
        };
        let mut decided = 0;
        for _ in 0..3000 {
            let n = 3 + (next().unsigned_abs() as usize % 5);
            let b: Vec<Rational> = (0..=n).map(|_| Rational::from(next())).collect();
            let p = Poly::from_bernstein(&b);
            if p.is_zero() {
                continue;
            }
            let sturm = count_roots(&p.odd_multiplicity_part(), &Rational::ZERO, &Rational::ONE);
            let ib = integer_bernstein(&b);
            let sqf = certify_squarefree(&integer_power_from_bernstein(&ib));
            if sqf {
                assert_eq!(p.gcd(&p.derivative()).degree(), Some(0), "{b:?}");
            }
            if let Some(r) = descartes_isolate(&ib, 64, 0) {
                assert_eq!(r.len(), sturm, "{b:?}");
                for iv in &r {
                    assert!(bernstein_sign_at(&b, &iv.lo) * bernstein_sign_at(&b, &iv.hi) <= 0);
                }
                decided += 1;
            } else {
                assert!(!sqf, "square-free but Descartes did not terminate: {b:?}");
            }
        }
        assert!(decided > 2000, "{decided}");
    }

    #[test]
    fn repeated_roots_are_not_certified_square_free() {
        // (t - 1/2)^2 (t - 1/3) scaled to integers: 36 t^3 - 48 t^2 + 21 t - 3.
        let a: Vec<BigInt> = [-3, 21, -48, 36].iter().map(|&x| BigInt::from(x)).collect();
        assert!(!certify_squarefree(&a));
        let b: Vec<BigInt> = [-1, 0, 2].iter().map(|&x| BigInt::from(x)).collect();
        assert!(certify_squarefree(&b));
        // Ends deflate: t (t - 1) (2t - 1) → 2t - 1.
        let c: Vec<BigInt> = [0, 1, -3, 2].iter().map(|&x| BigInt::from(x)).collect();
        assert_eq!(deflate_ends(c), vec![BigInt::from(-1), BigInt::from(2)]);
    }
}
