//! [`Exact`] for each backend: the library's own exact `f64` conversion and its
//! by-reference operators.

use crate::Exact;

// ---------------------------------------------------------------------------------------
// num-rational 0.4 over num-bigint 0.4: vericad's `BigRational`.

pub use num_rational::BigRational;

fn sign_of<T: num_traits::Signed>(x: &T) -> i8 {
    if x.is_positive() {
        1
    } else if x.is_negative() {
        -1
    } else {
        0
    }
}

impl Exact for BigRational {
    const NAME: &'static str = "num-rational";
    fn from_f64(x: f64) -> Self {
        BigRational::from_float(x).expect("finite")
    }
    fn from_i64(i: i64) -> Self {
        BigRational::from_integer(i.into())
    }
    fn add(&self, o: &Self) -> Self {
        self + o
    }
    fn sub(&self, o: &Self) -> Self {
        self - o
    }
    fn mul(&self, o: &Self) -> Self {
        self * o
    }
    fn div(&self, o: &Self) -> Self {
        self / o
    }
    fn add_assign(&mut self, o: &Self) {
        *self += o;
    }
    fn sign(&self) -> i8 {
        sign_of(self)
    }
    fn to_num_den(&self) -> (String, String) {
        (self.numer().to_string(), self.denom().to_string())
    }
}

// ---------------------------------------------------------------------------------------
// num-rational 0.4's `Ratio` over num-bigint 0.5 (newest): an extra column.

/// `num_rational::Ratio<num_bigint 0.5 BigInt>`, in a newtype that keeps the two num-bigint
/// versions apart in signatures.
#[derive(Clone, Debug, PartialEq)]
pub struct Ratio05(pub num_rational::Ratio<num_bigint_05::BigInt>);

impl Exact for Ratio05 {
    const NAME: &'static str = "num-rational+bigint0.5";
    /// Exact: `m · 2^e` from the bits (num-rational's `from_float` is only for num-bigint 0.4).
    fn from_f64(x: f64) -> Self {
        use num_bigint_05::BigInt;
        assert!(x.is_finite());
        let bits = x.to_bits();
        let neg = bits >> 63 == 1;
        let exp = ((bits >> 52) & 0x7ff) as i64;
        let frac = bits & ((1u64 << 52) - 1);
        let (m, e) = if exp == 0 {
            (frac, -1074)
        } else {
            (frac | (1u64 << 52), exp - 1075)
        };
        let mut m = BigInt::from(m);
        if neg {
            m = -m;
        }
        let r = if e >= 0 {
            num_rational::Ratio::from_integer(m << e as usize)
        } else {
            num_rational::Ratio::new(m, BigInt::from(1u8) << (-e) as usize)
        };
        Ratio05(r)
    }
    fn from_i64(i: i64) -> Self {
        Ratio05(num_rational::Ratio::from_integer(i.into()))
    }
    fn add(&self, o: &Self) -> Self {
        Ratio05(&self.0 + &o.0)
    }
    fn sub(&self, o: &Self) -> Self {
        Ratio05(&self.0 - &o.0)
    }
    fn mul(&self, o: &Self) -> Self {
        Ratio05(&self.0 * &o.0)
    }
    fn div(&self, o: &Self) -> Self {
        Ratio05(&self.0 / &o.0)
    }
    fn add_assign(&mut self, o: &Self) {
        self.0 += &o.0;
    }
    fn sign(&self) -> i8 {
        sign_of(&self.0)
    }
    fn to_num_den(&self) -> (String, String) {
        (self.0.numer().to_string(), self.0.denom().to_string())
    }
}

// ---------------------------------------------------------------------------------------
// rug (GMP mpq_t).

pub use rug::Rational as RugRational;

impl Exact for rug::Rational {
    const NAME: &'static str = "rug";
    fn from_f64(x: f64) -> Self {
        rug::Rational::from_f64(x).expect("finite")
    }
    fn from_i64(i: i64) -> Self {
        rug::Rational::from(i)
    }
    fn add(&self, o: &Self) -> Self {
        rug::Rational::from(self + o)
    }
    fn sub(&self, o: &Self) -> Self {
        rug::Rational::from(self - o)
    }
    fn mul(&self, o: &Self) -> Self {
        rug::Rational::from(self * o)
    }
    fn div(&self, o: &Self) -> Self {
        rug::Rational::from(self / o)
    }
    fn add_assign(&mut self, o: &Self) {
        *self += o;
    }
    fn sign(&self) -> i8 {
        self.cmp0() as i8
    }
    fn to_num_den(&self) -> (String, String) {
        (self.numer().to_string(), self.denom().to_string())
    }
}

// ---------------------------------------------------------------------------------------
// dashu (RBig: always reduced).

pub use dashu_ratio::RBig;

impl Exact for RBig {
    const NAME: &'static str = "dashu";
    fn from_f64(x: f64) -> Self {
        RBig::try_from(x).expect("finite")
    }
    fn from_i64(i: i64) -> Self {
        RBig::from(i)
    }
    fn add(&self, o: &Self) -> Self {
        self + o
    }
    fn sub(&self, o: &Self) -> Self {
        self - o
    }
    fn mul(&self, o: &Self) -> Self {
        self * o
    }
    fn div(&self, o: &Self) -> Self {
        self / o
    }
    fn add_assign(&mut self, o: &Self) {
        *self += o;
    }
    fn sign(&self) -> i8 {
        if self.is_zero() {
            0
        } else if self.sign() == dashu_base::Sign::Negative {
            -1
        } else {
            1
        }
    }
    fn to_num_den(&self) -> (String, String) {
        (self.numerator().to_string(), self.denominator().to_string())
    }
}

// ---------------------------------------------------------------------------------------
// malachite (malachite-q `Rational`).

pub use malachite_q::Rational as MalachiteRational;

impl Exact for malachite_q::Rational {
    const NAME: &'static str = "malachite";
    fn from_f64(x: f64) -> Self {
        malachite_q::Rational::try_from(x).expect("finite")
    }
    fn from_i64(i: i64) -> Self {
        malachite_q::Rational::from(i)
    }
    fn add(&self, o: &Self) -> Self {
        self + o
    }
    fn sub(&self, o: &Self) -> Self {
        self - o
    }
    fn mul(&self, o: &Self) -> Self {
        self * o
    }
    fn div(&self, o: &Self) -> Self {
        self / o
    }
    fn add_assign(&mut self, o: &Self) {
        *self += o;
    }
    fn sign(&self) -> i8 {
        use malachite_base::num::arithmetic::traits::Sign;
        Sign::sign(self) as i8
    }
    fn to_num_den(&self) -> (String, String) {
        let num = self.numerator_ref().to_string();
        let num = if Exact::sign(self) < 0 {
            format!("-{num}")
        } else {
            num
        };
        (num, self.denominator_ref().to_string())
    }
}
