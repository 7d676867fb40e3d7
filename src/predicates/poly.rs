//! Exact univariate polynomials over `BigRational`: Bernstein→power conversion, square-free
//! decomposition (Yun), Sturm sequences, and root isolation on an interval. Used where a
//! *sign* of a polynomial on an interval must be decided exactly (the single-sided test of
//! Yang et al. §3) and where its sign changes must be located (splitting a double-sided
//! piece at the roots of `(C(t)-P0)×(Pn-P0)`).

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};

/// Power-basis polynomial `Σ c_i t^i` with exact rational coefficients; no trailing zeros.
#[derive(Clone, Debug, PartialEq)]
pub struct Poly {
    pub c: Vec<BigRational>,
}

fn binom(n: usize, k: usize) -> BigRational {
    BigRational::from_integer(BigInt::from(crate::scalar::binomial_i64(n, k)))
}

impl Poly {
    /// Normalize (strip trailing zero coefficients).
    pub fn new(mut c: Vec<BigRational>) -> Poly {
        while c.last().is_some_and(|x| x.is_zero()) {
            c.pop();
        }
        Poly { c }
    }
    pub fn is_zero(&self) -> bool {
        self.c.is_empty()
    }
    /// Degree; `None` for the zero polynomial.
    pub fn degree(&self) -> Option<usize> {
        self.c.len().checked_sub(1)
    }
    /// From Bernstein coefficients on `[0,1]`:
    /// `Σ_i b_i C(n,i) t^i (1-t)^{n-i} = Σ_k t^k Σ_{i<=k} b_i C(n,i) C(n-i,k-i) (-1)^{k-i}`.
    pub fn from_bernstein(b: &[BigRational]) -> Poly {
        let n = b.len().saturating_sub(1);
        let mut c = vec![BigRational::zero(); n + 1];
        for (i, bi) in b.iter().enumerate() {
            if bi.is_zero() {
                continue;
            }
            let w = bi * binom(n, i);
            for k in i..=n {
                let term = &w * binom(n - i, k - i);
                if (k - i) % 2 == 0 {
                    c[k] += term;
                } else {
                    c[k] -= term;
                }
            }
        }
        Poly::new(c)
    }
    /// Value at `t` (Horner).
    pub fn eval(&self, t: &BigRational) -> BigRational {
        let mut acc = BigRational::zero();
        for ci in self.c.iter().rev() {
            acc = acc * t + ci;
        }
        acc
    }
    /// Derivative.
    pub fn derivative(&self) -> Poly {
        Poly::new(
            self.c
                .iter()
                .enumerate()
                .skip(1)
                .map(|(i, ci)| ci * BigRational::from_integer(BigInt::from(i)))
                .collect(),
        )
    }
    /// Quotient and remainder; `d` must be non-zero.
    pub fn div_rem(&self, d: &Poly) -> (Poly, Poly) {
        let dd = d.degree().expect("division by the zero polynomial");
        let lead = d.c[dd].clone();
        let mut r = self.c.clone();
        let n = self.c.len();
        if n <= dd {
            return (Poly::new(vec![]), self.clone());
        }
        let mut q = vec![BigRational::zero(); n - dd];
        for k in (0..n - dd).rev() {
            let coef = &r[k + dd] / &lead;
            if !coef.is_zero() {
                for (j, dj) in d.c.iter().enumerate() {
                    r[k + j] -= &coef * dj;
                }
            }
            q[k] = coef;
        }
        r.truncate(dd);
        (Poly::new(q), Poly::new(r))
    }
    /// Monic greatest common divisor.
    pub fn gcd(&self, o: &Poly) -> Poly {
        let (mut a, mut b) = (self.clone(), o.clone());
        while !b.is_zero() {
            let r = a.div_rem(&b).1;
            a = b;
            b = r;
        }
        a.monic()
    }
    fn monic(&self) -> Poly {
        match self.c.last() {
            Some(l) if !l.is_zero() => Poly::new(self.c.iter().map(|x| x / l).collect()),
            _ => self.clone(),
        }
    }
    /// The product of the square-free factors of odd multiplicity (Yun's algorithm): a
    /// polynomial whose real roots are exactly the roots at which `self` changes sign.
    pub fn odd_multiplicity_part(&self) -> Poly {
        if self.degree().unwrap_or(0) == 0 {
            return Poly::new(vec![BigRational::one()]);
        }
        let f = self.monic();
        let fp = f.derivative();
        let mut a = f.gcd(&fp);
        let mut b = f.div_rem(&a).0;
        let mut c = fp.div_rem(&a).0;
        let mut d = c_minus(&c, &b.derivative());
        let mut k = 1usize;
        let mut odd = Poly::new(vec![BigRational::one()]);
        loop {
            let ak = b.gcd(&d);
            if k % 2 == 1 {
                odd = odd.mul(&ak);
            }
            b = b.div_rem(&ak).0;
            if b.degree().unwrap_or(0) == 0 {
                break;
            }
            c = d.div_rem(&ak).0;
            d = c_minus(&c, &b.derivative());
            k += 1;
            a = ak;
        }
        let _ = a;
        odd
    }
    /// Product.
    pub fn mul(&self, o: &Poly) -> Poly {
        if self.is_zero() || o.is_zero() {
            return Poly::new(vec![]);
        }
        let mut c = vec![BigRational::zero(); self.c.len() + o.c.len() - 1];
        for (i, a) in self.c.iter().enumerate() {
            for (j, b) in o.c.iter().enumerate() {
                c[i + j] += a * b;
            }
        }
        Poly::new(c)
    }
    /// Sturm sequence `p, p', -rem(p, p'), …`.
    pub fn sturm(&self) -> Vec<Poly> {
        let mut s = vec![self.clone(), self.derivative()];
        while !s[s.len() - 1].is_zero() {
            let n = s.len();
            let r = s[n - 2].div_rem(&s[n - 1]).1;
            if r.is_zero() {
                break;
            }
            s.push(Poly::new(r.c.iter().map(|x| -x).collect()));
        }
        s
    }
}

fn c_minus(a: &Poly, b: &Poly) -> Poly {
    let n = a.c.len().max(b.c.len());
    Poly::new(
        (0..n)
            .map(|i| {
                a.c.get(i).cloned().unwrap_or_default() - b.c.get(i).cloned().unwrap_or_default()
            })
            .collect(),
    )
}

fn sign_changes(seq: &[Poly], t: &BigRational) -> usize {
    let mut last = 0i8;
    let mut n = 0;
    for p in seq {
        let v = p.eval(t);
        let s = if v.is_positive() {
            1
        } else if v.is_negative() {
            -1
        } else {
            0
        };
        if s != 0 {
            if last != 0 && s != last {
                n += 1;
            }
            last = s;
        }
    }
    n
}

/// Distinct real roots of the square-free polynomial `p` in the open interval `(a, b)`,
/// each isolated in an interval `[lo, hi]` (a single point when a bisection midpoint hit the
/// root exactly) of width at most `width`. Exact (Sturm's theorem).
pub fn isolate_roots(
    p: &Poly,
    a: &BigRational,
    b: &BigRational,
    width: &BigRational,
) -> Vec<(BigRational, BigRational)> {
    if p.degree().unwrap_or(0) == 0 {
        return vec![];
    }
    let seq = p.sturm();
    let mut out = Vec::new();
    // Exclude roots exactly at the ends: count on (a, b] then drop b if it is a root.
    let mut stack = vec![(a.clone(), b.clone())];
    while let Some((lo, hi)) = stack.pop() {
        // Roots in (lo, hi): Sturm counts (lo, hi] when lo is not a root; endpoints that are
        // roots are reported as exact points by the caller of the split below.
        let mut n = sign_changes(&seq, &lo) as isize - sign_changes(&seq, &hi) as isize;
        if p.eval(&hi).is_zero() {
            n -= 1;
        }
        if n <= 0 {
            continue;
        }
        if n == 1 && &hi - &lo <= *width {
            out.push((lo, hi));
            continue;
        }
        let mid = (&lo + &hi) / BigRational::from_integer(BigInt::from(2));
        if p.eval(&mid).is_zero() {
            out.push((mid.clone(), mid.clone()));
        }
        stack.push((mid.clone(), hi));
        stack.push((lo, mid));
    }
    out.sort_by(|x, y| x.0.cmp(&y.0));
    out
}

/// Number of distinct real roots of the square-free `p` in the open interval `(a, b)`.
pub fn count_roots(p: &Poly, a: &BigRational, b: &BigRational) -> usize {
    if p.degree().unwrap_or(0) == 0 {
        return 0;
    }
    let seq = p.sturm();
    let mut n = sign_changes(&seq, a) as isize - sign_changes(&seq, b) as isize;
    if p.eval(b).is_zero() {
        n -= 1;
    }
    n.max(0) as usize
}

#[cfg(test)]
mod tests {
    use super::*;
    fn r(n: i64, d: i64) -> BigRational {
        BigRational::new(n.into(), d.into())
    }
    fn p(c: &[i64]) -> Poly {
        Poly::new(c.iter().map(|&x| r(x, 1)).collect())
    }

    #[test]
    fn odd_part_and_sturm() {
        // (t - 1/2)^2 (t - 1/4) (t - 3/4)^3: sign changes at 1/4 and 3/4 only.
        let f = Poly::new(vec![r(-1, 2), r(1, 1)])
            .mul(&Poly::new(vec![r(-1, 2), r(1, 1)]))
            .mul(&Poly::new(vec![r(-1, 4), r(1, 1)]))
            .mul(
                &Poly::new(vec![r(-3, 4), r(1, 1)])
                    .mul(&Poly::new(vec![r(-3, 4), r(1, 1)]))
                    .mul(&Poly::new(vec![r(-3, 4), r(1, 1)])),
            );
        let odd = f.odd_multiplicity_part();
        assert_eq!(odd.degree(), Some(2));
        assert_eq!(count_roots(&odd, &r(0, 1), &r(1, 1)), 2);
        let iso = isolate_roots(&odd, &r(0, 1), &r(1, 1), &r(1, 1000));
        assert_eq!(iso.len(), 2);
        assert!(iso[0].0 <= r(1, 4) && r(1, 4) <= iso[0].1);
        assert!(iso[1].0 <= r(3, 4) && r(3, 4) <= iso[1].1);
        // t^2 - 2 on (0, 2): one root, irrational.
        let g = p(&[-2, 0, 1]);
        let iso = isolate_roots(&g, &r(0, 1), &r(2, 1), &r(1, 1 << 20));
        assert_eq!(iso.len(), 1);
        let (lo, hi) = &iso[0];
        assert!(lo * lo < r(2, 1) && hi * hi > r(2, 1));
    }

    #[test]
    fn bernstein_conversion() {
        let b = [r(0, 1), r(3, 1), r(-1, 2), r(0, 1)];
        let pw = Poly::from_bernstein(&b);
        for i in 0..=10 {
            let t = r(i, 10);
            let om = r(1, 1) - &t;
            let direct = &b[1] * r(3, 1) * &t * &om * &om + &b[2] * r(3, 1) * &t * &t * &om;
            assert_eq!(pw.eval(&t), direct);
        }
    }
}

/// Exact integer Bernstein coefficients proportional (by one positive factor) to `b`.
pub fn integer_bernstein(b: &[BigRational]) -> Vec<BigInt> {
    use num_integer::Integer;
    let l = b.iter().fold(BigInt::one(), |acc, x| acc.lcm(x.denom()));
    b.iter().map(|x| x.numer() * (&l / x.denom())).collect()
}

fn variations(c: &[BigInt]) -> usize {
    let mut last = 0i8;
    let mut v = 0;
    for x in c {
        let s = if x.is_positive() {
            1
        } else if x.is_negative() {
            -1
        } else {
            0
        };
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
    pub lo: BigRational,
    pub hi: BigRational,
}

fn dyadic(k: &BigInt, d: u32) -> BigRational {
    BigRational::new(k.clone(), BigInt::one() << d)
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
    let mut stack = vec![(c.to_vec(), BigInt::zero(), 0u32)];
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
    let mut a = vec![BigInt::zero(); n + 1];
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
    while a.len() > 1 && a.iter().fold(BigInt::zero(), |s, x| s + x).is_zero() {
        // a(t) = (t - 1) q(t): q_{n-1} = a_n, q_{k-1} = a_k + q_k.
        let n = a.len() - 1;
        let mut q = vec![BigInt::zero(); n];
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
pub fn bernstein_sign_at(b: &[BigRational], t: &BigRational) -> i8 {
    let mut v = b.to_vec();
    let n = v.len();
    for level in 1..n {
        for i in 0..n - level {
            v[i] = &v[i] + (&v[i + 1] - &v[i]) * t;
        }
    }
    if v[0].is_positive() {
        1
    } else if v[0].is_negative() {
        -1
    } else {
        0
    }
}

#[cfg(test)]
mod descartes_tests {
    use super::*;

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
            let b: Vec<BigRational> = (0..=n)
                .map(|_| BigRational::from_integer(next().into()))
                .collect();
            let p = Poly::from_bernstein(&b);
            if p.is_zero() {
                continue;
            }
            let sturm = count_roots(
                &p.odd_multiplicity_part(),
                &BigRational::zero(),
                &BigRational::one(),
            );
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
