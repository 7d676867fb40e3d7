//! Outward-rounded interval arithmetic on `f64`.
//!
//! Every operation computes the round-to-nearest result and then widens it by one ulp in
//! each direction (`next_down` / `next_up`). Round-to-nearest is within half an ulp of the
//! exact value, so the widened interval contains the exact result of the operation applied
//! to any reals inside the operands: a rigorous enclosure, used for the error bounds that
//! accompany constructed points (e.g. triangle–triangle crossing endpoints).

use std::ops::{Add, Mul, Neg, Sub};

/// A closed interval `[lo, hi]` of reals, `lo <= hi`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Interval {
    pub lo: f64,
    pub hi: f64,
}

impl Interval {
    /// The degenerate interval holding exactly `x`.
    pub fn point(x: f64) -> Interval {
        Interval { lo: x, hi: x }
    }
    fn widen(lo: f64, hi: f64) -> Interval {
        Interval {
            lo: lo.next_down(),
            hi: hi.next_up(),
        }
    }
    /// Whether 0 lies in the interval.
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
    pub fn is_finite(&self) -> bool {
        self.lo.is_finite() && self.hi.is_finite()
    }
    /// Quotient; `None` when the divisor interval contains zero.
    pub fn checked_div(self, o: Interval) -> Option<Interval> {
        if o.contains_zero() {
            return None;
        }
        let c = [
            self.lo / o.lo,
            self.lo / o.hi,
            self.hi / o.lo,
            self.hi / o.hi,
        ];
        let lo = c.iter().cloned().fold(f64::INFINITY, f64::min);
        let hi = c.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
        Some(Interval::widen(lo, hi))
    }
}

impl Add for Interval {
    type Output = Interval;
    fn add(self, o: Interval) -> Interval {
        Interval::widen(self.lo + o.lo, self.hi + o.hi)
    }
}
impl Sub for Interval {
    type Output = Interval;
    fn sub(self, o: Interval) -> Interval {
        Interval::widen(self.lo - o.hi, self.hi - o.lo)
    }
}
impl Neg for Interval {
    type Output = Interval;
    fn neg(self) -> Interval {
        Interval {
            lo: -self.hi,
            hi: -self.lo,
        }
    }
}
impl Mul for Interval {
    type Output = Interval;
    fn mul(self, o: Interval) -> Interval {
        let c = [
            self.lo * o.lo,
            self.lo * o.hi,
            self.hi * o.lo,
            self.hi * o.hi,
        ];
        let lo = c.iter().cloned().fold(f64::INFINITY, f64::min);
        let hi = c.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
        Interval::widen(lo, hi)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_rational::BigRational;

    fn r(x: f64) -> BigRational {
        BigRational::from_float(x).unwrap()
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
}
