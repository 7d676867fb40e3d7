//! [`Rational`] (dashu's `RBig`, always in lowest terms): the exact reference backend, and
//! the few helpers the exact code shares.

use super::{BigInt, BigUint, NotFinite, Rational, Scalar, Sign};
use dashu_int::Sign as IntSign;

impl Scalar for Rational {
    const EXACT: bool = true;
    const NAME: &'static str = "Rational (dashu)";

    fn zero() -> Self {
        Rational::ZERO
    }
    fn one() -> Self {
        Rational::ONE
    }
    fn from_i64(i: i64) -> Self {
        Rational::from(i)
    }
    /// Exact: every finite f64 is a dyadic rational (`m · 2^e` from its bits).
    fn from_f64(x: f64) -> Result<Self, NotFinite> {
        Rational::try_from(x).map_err(|_| NotFinite(x))
    }
    /// Correctly rounded (to nearest, ties to even); saturates to ±inf beyond range.
    fn to_f64(&self) -> f64 {
        Rational::to_f64(self).value()
    }
    fn sign(&self) -> Sign {
        int_sign(self.numerator())
    }
    fn to_rational(&self) -> Rational {
        self.clone()
    }
    fn is_zero(&self) -> bool {
        Rational::is_zero(self)
    }
}

/// The sign of an integer.
pub fn int_sign(x: &BigInt) -> Sign {
    if x.is_zero() {
        Sign::Zero
    } else if x.sign() == IntSign::Negative {
        Sign::Negative
    } else {
        Sign::Positive
    }
}

/// `numer / denom` in lowest terms. A zero denominator is a logic error (it panics, as a
/// division by zero does); callers pass non-zero denominators.
pub fn ratio(numer: impl Into<BigInt>, denom: impl Into<BigInt>) -> Rational {
    Rational::from_parts_signed(numer.into(), denom.into())
}

/// `2^e`, exactly.
pub fn pow2(e: i64) -> Rational {
    let p = BigUint::ONE << e.unsigned_abs() as usize;
    if e >= 0 {
        Rational::from(p)
    } else {
        Rational::from_parts(BigInt::ONE, p)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// f64 → Rational is exact: 0.1 is the dyadic 3602879701896397 / 2^55, not 1/10.
    #[test]
    fn f64_converts_exactly() {
        let q = <Rational as Scalar>::from_f64(0.1).unwrap();
        assert_eq!(
            q,
            ratio(3_602_879_701_896_397i64, 36_028_797_018_963_968i64)
        );
        assert_eq!(q.denominator(), &(BigUint::ONE << 55));
        for x in [
            0.0,
            -0.0,
            1.0,
            -2.5,
            1.0 / 3.0,
            f64::MAX,
            -f64::MAX,
            f64::MIN_POSITIVE,
            5e-324,
            -5e-324,
            1e300,
            1e-300,
        ] {
            let q = <Rational as Scalar>::from_f64(x).unwrap();
            assert_eq!(Scalar::to_f64(&q).to_bits(), (x + 0.0).to_bits(), "{x:e}");
        }
        for x in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            assert!(<Rational as Scalar>::from_f64(x).is_err());
        }
        assert_eq!(pow2(-1074), <Rational as Scalar>::from_f64(5e-324).unwrap());
        assert_eq!(pow2(3), Rational::from(8));
    }

    /// The rounding back to f64 is to nearest, ties to even, and saturates.
    #[test]
    fn to_f64_rounds_to_nearest() {
        assert_eq!(Scalar::to_f64(&ratio(1, 3)), 1.0 / 3.0);
        assert_eq!(Scalar::to_f64(&ratio(-2, 3)), -2.0 / 3.0);
        // 1 + 2^-53 is the tie between 1 and 1 + 2^-52: even is 1.
        let one = Rational::ONE;
        assert_eq!(Scalar::to_f64(&(one.clone() + pow2(-53))), 1.0);
        assert_eq!(
            Scalar::to_f64(&(one.clone() + pow2(-53) + pow2(-200))),
            1.0 + f64::EPSILON
        );
        assert_eq!(
            Scalar::to_f64(&(one + pow2(-52) + pow2(-53))),
            1.0 + 2.0 * f64::EPSILON
        );
        assert_eq!(Scalar::to_f64(&pow2(1100)), f64::INFINITY);
        assert_eq!(Scalar::to_f64(&-pow2(1100)), f64::NEG_INFINITY);
        assert_eq!(Scalar::to_f64(&pow2(-1100)), 0.0);
        // Subnormals: 3 · 2^-1076 rounds to 2^-1074 (nearest of 0, 2^-1074).
        assert_eq!(Scalar::to_f64(&(pow2(-1076) * Rational::from(3))), 5e-324);
        // Small integer quotients agree with f64 division (correctly rounded).
        for n in -50i64..50 {
            for d in 1i64..50 {
                assert_eq!(Scalar::to_f64(&ratio(n, d)), n as f64 / d as f64);
            }
        }
        assert_eq!(Scalar::sign(&ratio(-1, 7)), Sign::Negative);
        assert_eq!(Scalar::sign(&Rational::ZERO), Sign::Zero);
        assert_eq!(Scalar::sign(&ratio(1, -7)), Sign::Negative);
    }
}
