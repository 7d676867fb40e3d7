//! Exact univariate polynomials over `Rational`: Bernstein→power conversion, square-free
//! decomposition (Yun), Sturm sequences, and root isolation on an interval. Used where a
//! *sign* of a polynomial on an interval must be decided exactly (the single-sided test of
//! Yang et al. §3) and where its sign changes must be located (splitting a double-sided
//! piece at the roots of `(C(t)-P0)×(Pn-P0)`).

use crate::scalar::{BigInt, Rational, Scalar, ratio};

pub use super::descartes::*;

/// Power-basis polynomial `Σ c_i t^i` with exact rational coefficients; no trailing zeros.
#[derive(Clone, Debug, PartialEq)]
pub struct Poly {
    pub c: Vec<Rational>,
}

fn binom(n: usize, k: usize) -> Rational {
    Rational::from(crate::scalar::binomial_i64(n, k))
}

impl Poly {
    /// Normalize (strip trailing zero coefficients).
    pub fn new(mut c: Vec<Rational>) -> Poly {
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
    pub fn from_bernstein(b: &[Rational]) -> Poly {
        let n = b.len().saturating_sub(1);
        let mut c = vec![Rational::ZERO; n + 1];
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
    pub fn eval(&self, t: &Rational) -> Rational {
        let mut acc = Rational::ZERO;
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
                .map(|(i, ci)| ci * Rational::from(i))
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
        let mut q = vec![Rational::ZERO; n - dd];
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
            return Poly::new(vec![Rational::ONE]);
        }
        let f = self.monic();
        let fp = f.derivative();
        let mut a = f.gcd(&fp);
        let mut b = f.div_rem(&a).0;
        let mut c = fp.div_rem(&a).0;
        let mut d = c_minus(&c, &b.derivative());
        let mut k = 1usize;
        let mut odd = Poly::new(vec![Rational::ONE]);
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
        let mut c = vec![Rational::ZERO; self.c.len() + o.c.len() - 1];
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

fn sign_changes(seq: &[Poly], t: &Rational) -> usize {
    let mut last = 0i8;
    let mut n = 0;
    for p in seq {
        let v = p.eval(t);
        let s = Scalar::sign(&v).as_i8();
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
    a: &Rational,
    b: &Rational,
    width: &Rational,
) -> Vec<(Rational, Rational)> {
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
        let mid = (&lo + &hi) / Rational::from(2);
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
pub fn count_roots(p: &Poly, a: &Rational, b: &Rational) -> usize {
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

/// Whether the polynomial with Bernstein coefficients `b` on `[0, 1]` is negative anywhere
/// on `[0, 1]`, decided exactly: `None` when it is `>= 0` on the whole interval (a touch
/// of zero included), otherwise a parameter where it is negative — or, when every candidate
/// point happens to be a root, a parameter of a sign change.
///
/// All coefficients `>= 0` decide at once (convex hull). Otherwise the polynomial `g` is
/// negative somewhere iff its odd-multiplicity part (square-free, with the sign changes of
/// `g` as its roots) has a root in `(0, 1)`, or `g` is negative at an end; without sign
/// changes `g` keeps one sign on `(0, 1)` away from its even roots, read at one of `n + 1`
/// distinct points (a non-zero polynomial of degree `n` has at most `n` roots). A double
/// root — a curve touching a line from one side — is therefore no sign change but is still
/// classified by the side it lies on.
pub fn negative_on_unit_interval(b: &[Rational]) -> Option<Rational> {
    let zero = Rational::ZERO;
    if b.iter().all(|x| *x >= zero) {
        return None;
    }
    let n = b.len() - 1;
    if b[0] < zero {
        return Some(zero);
    }
    if b[n] < zero {
        return Some(Rational::ONE);
    }
    let g = Poly::from_bernstein(b);
    if g.is_zero() {
        return None;
    }
    let (lo, hi) = (zero.clone(), Rational::ONE);
    let odd = g.odd_multiplicity_part();
    if count_roots(&odd, &lo, &hi) > 0 {
        let width = crate::scalar::pow2(-32);
        let roots = isolate_roots(&odd, &lo, &hi, &width);
        for (a, c) in &roots {
            for t in [a, c] {
                if g.eval(t) < zero {
                    return Some(t.clone());
                }
            }
        }
        let two = Rational::from(2);
        return Some(roots.first().map_or(ratio(1, 2), |(a, c)| (a + c) / two));
    }
    let den = BigInt::from(n as u64 + 2);
    for j in 1..=n as u64 + 1 {
        let t = ratio(BigInt::from(j), den.clone());
        let v = g.eval(&t);
        if !v.is_zero() {
            return (v < zero).then_some(t);
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    fn r(n: i64, d: i64) -> Rational {
        ratio(n, d)
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

    #[test]
    fn negative_on_unit_interval_sees_touches_and_interior_dips() {
        let q = |v: &[i64]| -> Vec<Rational> { v.iter().map(|x| Rational::from(*x)).collect() };
        let neg = |v: &[i64]| negative_on_unit_interval(&q(v));
        // (1 - 2t)^2: touches zero at 1/2 from above.
        assert_eq!(neg(&[1, -1, 1]), None);
        // -(1 - 2t)^2: below zero except at 1/2 (negative at the ends).
        assert_eq!(neg(&[-1, 1, -1]), Some(Rational::ZERO));
        // -2t(1 - t): zero at both ends, negative inside, no sign change in (0, 1).
        let t = neg(&[0, -1, 0]).unwrap();
        assert!(Poly::from_bernstein(&q(&[0, -1, 0])).eval(&t) < Rational::ZERO);
        // 6t^2 - 6t + 1: two sign changes.
        let t = neg(&[1, -2, 1]).unwrap();
        assert!(Poly::from_bernstein(&q(&[1, -2, 1])).eval(&t) < Rational::ZERO);
        assert_eq!(neg(&[0, 0, 0]), None);
        assert_eq!(neg(&[0, 1, 0]), None);
    }
}
