//! Outward-rounded interval arithmetic on `f64`.
//!
//! Operations on two points compute the round-to-nearest result together with its exact
//! rounding error (TwoSum; Dekker's TwoProduct) and move each end point one ulp outward only
//! when the error points outward: an exact result stays a point (so `0 · x`, `1 · x`, `x + 0`
//! and sums of representable values are not widened). Multiplying by a point that is 0 or
//! ± a power of two is exact. Everything else is rounded to nearest and widened one ulp each
//! way. Where the error-free transformations are not valid (overflow, near underflow)
//! the end points are widened by one ulp, which round-to-nearest always justifies. Quotients
//! are widened by one ulp. An end point that is an exact zero is never widened (a product
//! with a zero factor, a sum that rounds to zero — exact under gradual underflow — or a
//! quotient whose every value has one sign): `next_up(0)` is subnormal, and subnormal
//! operands make every later product slow. The result contains the exact result of the operation applied to
//! any reals inside the operands: a rigorous enclosure, used for the error bounds that
//! accompany constructed points (triangle–triangle crossings, curve-on-surface certificates).

use std::ops::{Add, Mul, Neg, Sub};

/// A closed interval `[lo, hi]` of reals, `lo <= hi`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Interval {
    pub lo: f64,
    pub hi: f64,
}

impl Interval {
    /// The degenerate interval holding exactly `x`.
    #[inline]
    pub fn point(x: f64) -> Interval {
        Interval { lo: x, hi: x }
    }
    #[inline]
    fn widen(lo: f64, hi: f64) -> Interval {
        Interval {
            lo: lo.next_down(),
            hi: hi.next_up(),
        }
    }
    /// [`Interval::widen`] for a rounded sum or difference: an end that is zero stays zero.
    /// With gradual underflow (IEEE 754) a sum or difference that rounds to zero is exact
    /// (`x ⊕ y = 0` only when `x = −y`: results in the subnormal range are exact; Hauser,
    /// *Handling floating-point exceptions in numeric programs*, TOPLAS 1996, Thm 3.4.1).
    /// Not widening it keeps subnormal end points (`next_up(0)`) out of later products,
    /// which cost a microcode assist per operation on common processors.
    #[inline]
    fn widen_sum(lo: f64, hi: f64) -> Interval {
        Interval {
            lo: if lo == 0.0 { 0.0 } else { lo.next_down() },
            hi: if hi == 0.0 { 0.0 } else { hi.next_up() },
        }
    }
    /// Whether 0 lies in the interval.
    #[inline]
    pub fn contains_zero(&self) -> bool {
        self.lo <= 0.0 && self.hi >= 0.0
    }
    /// Midpoint (rounded) — the representative value.
    pub fn mid(&self) -> f64 {
        self.lo * 0.5 + self.hi * 0.5
    }
    /// A rigorous bound on `|x - self.mid()|` for every `x` in the interval.
    pub fn radius_about_mid(&self) -> f64 {
        let m = self.mid();
        ((m - self.lo).max(self.hi - m)).next_up()
    }
    /// Whether the enclosure is finite (no overflow happened).
    #[inline]
    pub fn is_finite(&self) -> bool {
        self.lo.is_finite() && self.hi.is_finite()
    }
    /// The interval `[lo, hi]` (caller guarantees `lo <= hi`).
    #[inline]
    pub fn new(lo: f64, hi: f64) -> Interval {
        Interval { lo, hi }
    }
    /// The smallest interval holding both.
    #[inline]
    pub fn hull(self, o: Interval) -> Interval {
        Interval {
            lo: self.lo.min(o.lo),
            hi: self.hi.max(o.hi),
        }
    }
    /// `max |x|` over the interval.
    #[inline]
    pub fn mag(&self) -> f64 {
        self.lo.abs().max(self.hi.abs())
    }
    /// Upper bound of the Euclidean norm of every point of the box `x` (one interval a
    /// coordinate).
    pub fn norm_hi(x: &[Interval]) -> f64 {
        let s = x.iter().fold(Interval::point(0.0), |s, c| s + c.sqr());
        s.hi.sqrt().next_up()
    }
    /// Enclosure of `x²` (non-negative even when the interval holds 0).
    pub fn sqr(self) -> Interval {
        let m = self * self;
        if self.contains_zero() {
            Interval { lo: 0.0, hi: m.hi }
        } else {
            Interval {
                lo: m.lo.max(0.0),
                hi: m.hi,
            }
        }
    }
    /// Whether every point is strictly positive / strictly negative.
    pub fn is_pos(&self) -> bool {
        self.lo > 0.0
    }
    pub fn is_neg(&self) -> bool {
        self.hi < 0.0
    }
    /// Quotient; `None` when the divisor interval contains zero.
    #[inline]
    pub fn checked_div(self, o: Interval) -> Option<Interval> {
        if o.contains_zero() {
            return None;
        }
        if self.lo == 0.0 && self.hi == 0.0 {
            return Some(Interval::point(0.0));
        }
        if self.lo == self.hi && o.lo == o.hi {
            // Exact when the residual a - q·b vanishes (a, b, q in the normal range).
            let q = self.lo / o.lo;
            // Dekker's error term is exact only away from underflow: every operand and the
            // quotient must be in the normal range well above the subnormals.
            if q.is_finite()
                && q.abs() >= 1e-280
                && self.lo.abs() >= 1e-280
                && o.lo.abs() >= 1e-280
                && o.lo.abs() < 1e290
                && q.abs() < 1e290
            {
                let (p, e) = two_product(q, o.lo);
                if p == self.lo && e == 0.0 {
                    return Some(Interval::point(q));
                }
            }
        }
        let c = [
            self.lo / o.lo,
            self.lo / o.hi,
            self.hi / o.lo,
            self.hi / o.hi,
        ];
        let lo = c.iter().cloned().fold(f64::INFINITY, f64::min);
        let hi = c.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
        // Where every quotient is ≥ 0 (≤ 0), zero is a valid lower (upper) bound: a zero end
        // is kept rather than widened to a subnormal (see `widen_sum`).
        let nonneg = (self.lo >= 0.0 && o.lo > 0.0) || (self.hi <= 0.0 && o.hi < 0.0);
        let nonpos = (self.hi <= 0.0 && o.lo > 0.0) || (self.lo >= 0.0 && o.hi < 0.0);
        Some(Interval {
            lo: if nonneg && lo == 0.0 {
                0.0
            } else {
                lo.next_down()
            },
            hi: if nonpos && hi == 0.0 {
                0.0
            } else {
                hi.next_up()
            },
        })
    }
}

/// Knuth's TwoSum: `a + b = s + e` exactly, `s` the rounded sum.
#[inline]
fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    let e = (a - (s - bb)) + (b - bb);
    (s, e)
}

/// Dekker's TwoProduct (Veltkamp splitting): `a · b = p + e` exactly, `p` the rounded
/// product (valid without overflow/underflow; callers widen when that may have happened).
#[inline]
fn two_product(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    let split = |x: f64| {
        let c = 134217729.0 * x; // 2^27 + 1
        let hi = c - (c - x);
        (hi, x - hi)
    };
    let (ah, al) = split(a);
    let (bh, bl) = split(b);
    let e = al * bl - (((p - ah * bh) - al * bh) - ah * bl);
    (p, e)
}

/// Lower and upper bound of a rounded result `r` whose exact value is `r + e`, with `e`
/// from an error-free transformation: exact results stay points. When the transformation
/// is not trustworthy (non-finite, or magnitudes where underflow may spoil it), one ulp
/// each way, as round-to-nearest guarantees.
#[inline]
fn bounds(r: f64, e: f64) -> (f64, f64) {
    if !r.is_finite() || !e.is_finite() || (r != 0.0 && r.abs() < 1e-280) {
        return (r.next_down(), r.next_up());
    }
    if e > 0.0 {
        (r, r.next_up())
    } else if e < 0.0 {
        (r.next_down(), r)
    } else {
        (r, r)
    }
}

#[inline]
fn lo_sum(a: f64, b: f64) -> f64 {
    let (s, e) = two_sum(a, b);
    bounds(s, e).0
}
#[inline]
fn hi_sum(a: f64, b: f64) -> f64 {
    let (s, e) = two_sum(a, b);
    bounds(s, e).1
}

impl Add for Interval {
    type Output = Interval;
    #[inline]
    fn add(self, o: Interval) -> Interval {
        if self.lo != self.hi || o.lo != o.hi {
            // Not points: one ulp outward (round-to-nearest is within half an ulp).
            return Interval::widen_sum(self.lo + o.lo, self.hi + o.hi);
        }
        Interval {
            lo: lo_sum(self.lo, o.lo),
            hi: hi_sum(self.hi, o.hi),
        }
    }
}
impl Sub for Interval {
    type Output = Interval;
    #[inline]
    fn sub(self, o: Interval) -> Interval {
        if self.lo != self.hi || o.lo != o.hi {
            return Interval::widen_sum(self.lo - o.hi, self.hi - o.lo);
        }
        Interval {
            lo: lo_sum(self.lo, -o.hi),
            hi: hi_sum(self.hi, -o.lo),
        }
    }
}
impl Neg for Interval {
    type Output = Interval;
    #[inline]
    fn neg(self) -> Interval {
        Interval {
            lo: -self.hi,
            hi: -self.lo,
        }
    }
}
/// Lower bound of the exact product `a · b` from the rounded one: one ulp down, except
/// that a product with a zero factor is exactly zero (kept, not widened to a subnormal).
#[inline]
fn prod_lo(a: f64, b: f64) -> f64 {
    let p = a * b;
    if p == 0.0 && (a == 0.0 || b == 0.0) {
        0.0
    } else {
        p.next_down()
    }
}
/// Upper bound of the exact product `a · b` (see [`prod_lo`]).
#[inline]
fn prod_hi(a: f64, b: f64) -> f64 {
    let p = a * b;
    if p == 0.0 && (a == 0.0 || b == 0.0) {
        0.0
    } else {
        p.next_up()
    }
}

/// Bounds of the exact product `a · b`.
#[inline]
fn product_bounds(a: f64, b: f64) -> (f64, f64) {
    if a == 0.0 || b == 0.0 {
        return (0.0, 0.0);
    }
    let (p, e) = two_product(a, b);
    if !(a.abs() < 1e290 && b.abs() < 1e290) || p.abs() < 1e-280 {
        // Outside the range where the splitting is error-free (or underflow).
        return (p.next_down(), p.next_up());
    }
    bounds(p, e)
}

/// Whether multiplying by `x` is exact for every finite operand away from the extremes of
/// the exponent range: a point that is 0, or ± a power of two.
#[inline]
fn exact_multiplier(x: Interval) -> bool {
    x.lo == x.hi && (x.lo == 0.0 || (x.lo.abs().to_bits() & ((1u64 << 52) - 1)) == 0)
}

impl Mul for Interval {
    type Output = Interval;
    #[inline]
    fn mul(self, o: Interval) -> Interval {
        if self.lo == self.hi && o.lo == o.hi {
            let (lo, hi) = product_bounds(self.lo, o.lo);
            return Interval { lo, hi };
        }
        let (x, y) = if self.lo == self.hi {
            (o, self)
        } else {
            (self, o)
        };
        if exact_multiplier(y) {
            let c = y.lo;
            if c == 0.0 {
                return Interval::point(0.0);
            }
            let (a, b) = (x.lo * c, x.hi * c);
            let (lo, hi) = if c > 0.0 { (a, b) } else { (b, a) };
            // Exact unless the result is tiny (underflow) or not finite; a zero factor
            // gives an exact zero.
            let exact = |r: f64, f: f64| f == 0.0 || (r.abs() >= 1e-290 && r.is_finite());
            if exact(a, x.lo) && exact(b, x.hi) {
                return Interval { lo, hi };
            }
            return Interval::widen(lo, hi);
        }
        if y.lo == y.hi {
            let c = y.lo;
            return if c >= 0.0 {
                Interval::new(prod_lo(x.lo, c), prod_hi(x.hi, c))
            } else if c < 0.0 {
                Interval::new(prod_lo(x.hi, c), prod_hi(x.lo, c))
            } else {
                // NaN: as before (the comparisons below are false, NaN propagates).
                let (a, b) = (x.lo * c, x.hi * c);
                Interval::widen(a.min(b), a.max(b))
            };
        }
        // Round-to-nearest products, one ulp outward (rigorous; cheaper than the error-free
        // transformation for intervals that are not points anyway). With the signs of both
        // operands fixed, the extreme products are known (the classical case table); the
        // comparisons are false for NaN, which falls through to the general case.
        if x.lo >= 0.0 && y.lo >= 0.0 {
            return Interval::new(prod_lo(x.lo, y.lo), prod_hi(x.hi, y.hi));
        }
        if x.hi <= 0.0 && y.hi <= 0.0 {
            return Interval::new(prod_lo(x.hi, y.hi), prod_hi(x.lo, y.lo));
        }
        if x.lo >= 0.0 && y.hi <= 0.0 {
            return Interval::new(prod_lo(x.hi, y.lo), prod_hi(x.lo, y.hi));
        }
        if x.hi <= 0.0 && y.lo >= 0.0 {
            return Interval::new(prod_lo(x.lo, y.hi), prod_hi(x.hi, y.lo));
        }
        let c = [x.lo * y.lo, x.lo * y.hi, x.hi * y.lo, x.hi * y.hi];
        let lo = c[0].min(c[1]).min(c[2].min(c[3]));
        let hi = c[0].max(c[1]).max(c[2].max(c[3]));
        Interval::widen(lo, hi)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::Rational;

    fn r(x: f64) -> Rational {
        Rational::try_from(x).unwrap()
    }

    #[test]
    fn enclosures_contain_the_exact_result() {
        let xs = [0.1, 1.0 / 3.0, -7.25e-3, 1e300, 3.0e-310, -2.5];
        for &a in &xs {
            for &b in &xs {
                let (ia, ib) = (Interval::point(a), Interval::point(b));
                let exact = [
                    (ia + ib, r(a) + r(b)),
                    (ia - ib, r(a) - r(b)),
                    (ia * ib, r(a) * r(b)),
                ];
                for (iv, ex) in exact {
                    if iv.is_finite() {
                        assert!(r(iv.lo) <= ex && ex <= r(iv.hi), "{a} {b} {iv:?}");
                    }
                }
                let q = ia.checked_div(ib).unwrap();
                if q.is_finite() {
                    let ex = r(a) / r(b);
                    assert!(r(q.lo) <= ex && ex <= r(q.hi));
                }
            }
        }
    }

    #[test]
    fn random_operands_are_enclosed_and_exact_results_stay_points() {
        // xorshift, so the test needs no dependency and is reproducible.
        let mut state = 0x9e3779b97f4a7c15u64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            let m = (state >> 11) as f64 / (1u64 << 53) as f64;
            let e = ((state & 63) as i32) - 40;
            (m - 0.5) * 2f64.powi(e)
        };
        for _ in 0..20_000 {
            let (a, b, c, d) = (next(), next(), next(), next());
            let x = Interval::new(a.min(b), a.max(b));
            let y = Interval::new(c.min(d), c.max(d));
            for (iv, xs) in [
                (x + y, [r(x.lo) + r(y.lo), r(x.hi) + r(y.hi)]),
                (x - y, [r(x.lo) - r(y.hi), r(x.hi) - r(y.lo)]),
            ] {
                assert!(r(iv.lo) <= xs[0] && xs[1] <= r(iv.hi), "{x:?} {y:?} {iv:?}");
            }
            let m = x * y;
            for (p, q) in [(x.lo, y.lo), (x.lo, y.hi), (x.hi, y.lo), (x.hi, y.hi)] {
                let e = r(p) * r(q);
                assert!(r(m.lo) <= e && e <= r(m.hi), "{x:?} {y:?} {m:?}");
            }
            // Exact operations give points.
            let p = Interval::point(a);
            assert_eq!(p * Interval::point(1.0), p);
            assert_eq!(p * Interval::point(0.0), Interval::point(0.0));
            assert_eq!(p + Interval::point(0.0), p);
            assert_eq!(p * Interval::point(2.0), Interval::point(2.0 * a));
        }
        let third = Interval::point(1.0)
            .checked_div(Interval::point(3.0))
            .unwrap();
        assert!(third.lo < third.hi);
        assert_eq!(
            Interval::point(0.5) + Interval::point(0.25),
            Interval::point(0.75)
        );
    }
}
