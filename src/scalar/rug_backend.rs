//! GMP/MPFR backends (feature `rug`): `rug::Rational` (exact) and [`BigFloat<P>`]
//! (MPFR binary floating point with `P` bits of precision, round-to-nearest).

use super::{NotFinite, RealScalar, Scalar, Sign};
use rug::{Float, Rational};
use std::cmp::Ordering;
use std::ops::{Add, Div, Mul, Neg, Sub};

fn sign_of(o: Option<Ordering>) -> Sign {
    match o {
        Some(Ordering::Less) => Sign::Negative,
        Some(Ordering::Greater) => Sign::Positive,
        _ => Sign::Zero,
    }
}

fn rug_to_big(r: &Rational) -> super::Rational {
    let conv = |i: &rug::Integer| {
        super::BigInt::from_str_radix(&i.to_string_radix(16), 16).unwrap_or_default()
    };
    // The denominator is positive (rug keeps it so); a failed parse, which cannot happen,
    // would give a zero denominator: fall back to zero rather than divide by it.
    let (n, d) = (conv(r.numer()), conv(r.denom()));
    if d.is_zero() {
        return super::Rational::ZERO;
    }
    super::Rational::from_parts_signed(n, d)
}

impl Scalar for Rational {
    const EXACT: bool = true;
    const NAME: &'static str = "rug::Rational";

    fn zero() -> Self {
        Rational::new()
    }
    fn one() -> Self {
        Rational::from(1)
    }
    fn from_i64(i: i64) -> Self {
        Rational::from(i)
    }
    fn from_f64(x: f64) -> Result<Self, NotFinite> {
        Rational::from_f64(x).ok_or(NotFinite(x))
    }
    fn to_f64(&self) -> f64 {
        Rational::to_f64(self)
    }
    fn sign(&self) -> Sign {
        Sign::of_ordering(self.cmp0())
    }
    fn to_rational(&self) -> super::Rational {
        rug_to_big(self)
    }
}

/// MPFR float with `P` bits of significand (`P >= 53`, so every f64 converts exactly).
/// The arithmetic rounds to nearest at `P` bits; its orientation predicates are exact
/// (the operands are converted exactly to `rug::Rational`).
#[derive(Clone, Debug, PartialEq, PartialOrd)]
pub struct BigFloat<const P: u32>(pub Float);

impl<const P: u32> BigFloat<P> {
    const CHECK: () = assert!(P >= 53, "BigFloat needs at least 53 bits");
    fn new(f: Float) -> Self {
        #[allow(clippy::let_unit_value)]
        let _ = Self::CHECK;
        BigFloat(f)
    }
    fn to_rug_rational(&self) -> Rational {
        self.0.to_rational().unwrap_or_default()
    }
}

macro_rules! binop {
    ($tr:ident, $f:ident) => {
        impl<const P: u32> $tr for BigFloat<P> {
            type Output = Self;
            fn $f(self, o: Self) -> Self {
                BigFloat::new(Float::with_val(P, (self.0).$f(&o.0)))
            }
        }
    };
}
binop!(Add, add);
binop!(Sub, sub);
binop!(Mul, mul);
binop!(Div, div);

impl<const P: u32> Neg for BigFloat<P> {
    type Output = Self;
    fn neg(self) -> Self {
        BigFloat::new(-self.0)
    }
}

fn rat_pt<const P: u32, const D: usize>(p: &[BigFloat<P>; D]) -> [Rational; D] {
    std::array::from_fn(|i| p[i].to_rug_rational())
}

impl<const P: u32> Scalar for BigFloat<P> {
    const EXACT: bool = false;
    const NAME: &'static str = "rug::Float";

    fn zero() -> Self {
        BigFloat::new(Float::new(P))
    }
    fn one() -> Self {
        BigFloat::new(Float::with_val(P, 1))
    }
    fn from_i64(i: i64) -> Self {
        BigFloat::new(Float::with_val(P, i))
    }
    fn from_f64(x: f64) -> Result<Self, NotFinite> {
        if x.is_finite() {
            Ok(BigFloat::new(Float::with_val(P, x)))
        } else {
            Err(NotFinite(x))
        }
    }
    fn to_f64(&self) -> f64 {
        self.0.to_f64()
    }
    fn sign(&self) -> Sign {
        sign_of(self.0.cmp0())
    }
    fn to_rational(&self) -> super::Rational {
        rug_to_big(&self.to_rug_rational())
    }
    /// Exact: the operands are converted to rationals without rounding.
    fn orient2d(a: &[Self; 2], b: &[Self; 2], c: &[Self; 2]) -> Sign {
        Rational::orient2d(&rat_pt(a), &rat_pt(b), &rat_pt(c))
    }
    /// Exact: the operands are converted to rationals without rounding.
    fn orient3d(a: &[Self; 3], b: &[Self; 3], c: &[Self; 3], d: &[Self; 3]) -> Sign {
        Rational::orient3d(&rat_pt(a), &rat_pt(b), &rat_pt(c), &rat_pt(d))
    }
}

impl<const P: u32> RealScalar for BigFloat<P> {
    fn sqrt(&self) -> Self {
        BigFloat::new(Float::with_val(P, self.0.sqrt_ref()))
    }
}
