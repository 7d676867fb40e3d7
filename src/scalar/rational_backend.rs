//! `BigRational` (num-rational): the exact reference backend.

use super::{NotFinite, Scalar, Sign};
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, ToPrimitive, Zero};

impl Scalar for BigRational {
    const EXACT: bool = true;
    const NAME: &'static str = "BigRational";

    fn zero() -> Self {
        <BigRational as Zero>::zero()
    }
    fn one() -> Self {
        <BigRational as One>::one()
    }
    fn from_i64(i: i64) -> Self {
        BigRational::from_integer(BigInt::from(i))
    }
    /// Exact: every finite f64 is a dyadic rational.
    fn from_f64(x: f64) -> Result<Self, NotFinite> {
        BigRational::from_float(x).ok_or(NotFinite(x))
    }
    /// Correctly rounded (num-rational's `ToPrimitive`); saturates to ±inf beyond range.
    fn to_f64(&self) -> f64 {
        ToPrimitive::to_f64(self).unwrap_or(if self.is_negative() {
            f64::NEG_INFINITY
        } else {
            f64::INFINITY
        })
    }
    fn sign(&self) -> Sign {
        if self.is_positive() {
            Sign::Positive
        } else if self.is_negative() {
            Sign::Negative
        } else {
            Sign::Zero
        }
    }
    fn to_big_rational(&self) -> BigRational {
        self.clone()
    }
    fn is_zero(&self) -> bool {
        Zero::is_zero(self)
    }
}
