//! The arithmetic the kernel is written against.
//!
//! Every kernel routine is generic over [`Scalar`] and is instantiated for
//! * `f64` — the fast path: `Copy` values, no allocation, static dispatch, and
//!   adaptive exact predicates (Shewchuk's filters via the `robust` crate);
//! * [`Rational`] — the exact reference: an arbitrary-precision rational in lowest terms
//!   (dashu's `RBig`, pure Rust);
//! * `rug::Rational` and [`BigFloat<P>`](self::rug_backend::BigFloat) — GMP/MPFR backends
//!   behind the non-default feature `rug`.
//!
//! An `f64` converts *exactly* into the exact types ([`Scalar::from_f64`]), so the same
//! input can be run through the f64 kernel and through the exact kernel and the two answers
//! compared: that is how the tests certify the f64 path.
//!
//! The trait is bounded on `Clone`, not `Copy`, so that arbitrary-precision types qualify.
//! Sign questions (orientation of points) are associated functions, so each backend picks
//! its own implementation: the f64 one is filtered and adaptive, the exact ones evaluate the
//! plain determinant exactly.
//!
//! The exact types are named in this module only: [`Rational`], and the integers
//! [`BigInt`] (its numerators) and [`BigUint`] (its denominators). The rest of the crate
//! uses these names, so the exact backend is chosen here. [`Rational`]'s conversion from
//! `f64` is exact and its conversion to `f64` correctly rounded (to nearest, ties to even).
//! `Rational` also has inherent `sign` and `to_f64` methods (dashu's, returning dashu's
//! types), which method-call syntax prefers to the trait's: on a concrete `Rational` write
//! `Scalar::sign(&x)` and `Scalar::to_f64(&x)`. Generic code (`S: Scalar`) is unaffected.

mod dashu_backend;
mod f64_backend;
pub mod interval;
#[cfg(feature = "rug")]
pub mod rug_backend;

use std::fmt::Debug;
use std::ops::{Add, Div, Mul, Neg, Sub};

pub use dashu_backend::{int_sign, pow2, ratio};
pub use interval::Interval;

/// The exact rational type of the crate (dashu's `RBig`): every value is kept in lowest
/// terms with a positive denominator. Division by zero panics (a logic error: kernel code
/// checks its denominators first).
pub type Rational = dashu_ratio::RBig;
/// Arbitrary-precision signed integer: the numerators of [`Rational`].
pub type BigInt = dashu_int::IBig;
/// Arbitrary-precision non-negative integer: the denominators of [`Rational`].
pub type BigUint = dashu_int::UBig;

/// The sign of an exactly decided quantity.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, serde::Serialize)]
pub enum Sign {
    Negative,
    Zero,
    Positive,
}

impl Sign {
    /// Sign of an `i32`-like comparison result.
    pub fn of_ordering(o: std::cmp::Ordering) -> Sign {
        match o {
            std::cmp::Ordering::Less => Sign::Negative,
            std::cmp::Ordering::Equal => Sign::Zero,
            std::cmp::Ordering::Greater => Sign::Positive,
        }
    }
    /// The opposite sign.
    pub fn flip(self) -> Sign {
        match self {
            Sign::Negative => Sign::Positive,
            Sign::Zero => Sign::Zero,
            Sign::Positive => Sign::Negative,
        }
    }
    /// Product of two signs.
    pub fn times(self, o: Sign) -> Sign {
        match (self, o) {
            (Sign::Zero, _) | (_, Sign::Zero) => Sign::Zero,
            (a, b) if a == b => Sign::Positive,
            _ => Sign::Negative,
        }
    }
    /// -1, 0 or 1.
    pub fn as_i8(self) -> i8 {
        match self {
            Sign::Negative => -1,
            Sign::Zero => 0,
            Sign::Positive => 1,
        }
    }
}

/// A value that is not a finite real number (NaN or ±inf) was given where one is required.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
#[error("not a finite number: {0}")]
pub struct NotFinite(pub f64);

/// The arithmetic every kernel routine needs.
///
/// Division by zero is a logic error for exact types (they panic); kernel code checks
/// every denominator it forms (knot-span widths, weights) before dividing, and reports a
/// typed error where the input could make one zero.
pub trait Scalar:
    Clone
    + Debug
    + PartialEq
    + PartialOrd
    + Send
    + Sync
    + 'static
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    /// `true` when `+ - * /` are exact (rationals); `false` for rounded types.
    const EXACT: bool;
    /// Human-readable backend name for reports.
    const NAME: &'static str;

    fn zero() -> Self;
    fn one() -> Self;
    /// Exact conversion of a small integer.
    fn from_i64(i: i64) -> Self;
    /// Conversion of a finite `f64`. Exact for every backend that can hold 53-bit
    /// significands (all of them here).
    fn from_f64(x: f64) -> Result<Self, NotFinite>;
    /// Nearest `f64` (correctly rounded for the rational backends).
    fn to_f64(&self) -> f64;
    /// Exact sign.
    fn sign(&self) -> Sign;
    /// The exact value as a [`Rational`] (every backend holds rationals; none rounds here).
    fn to_rational(&self) -> Rational;

    fn is_zero(&self) -> bool {
        self.sign() == Sign::Zero
    }
    fn abs(&self) -> Self {
        if self.sign() == Sign::Negative {
            -self.clone()
        } else {
            self.clone()
        }
    }
    /// `self / rhs`, or `None` when `rhs` is zero.
    fn checked_div(&self, rhs: &Self) -> Option<Self> {
        if rhs.is_zero() {
            None
        } else {
            Some(self.clone() / rhs.clone())
        }
    }
    /// Binomial coefficient `C(n, k)` as a scalar (exact for n ≤ 60).
    fn binomial(n: usize, k: usize) -> Self {
        Self::from_i64(binomial_i64(n, k))
    }

    /// Sign of `det[b-a, c-a]`: positive when `a, b, c` turn counter-clockwise.
    /// Default: the plain determinant, exact for exact types. f64 overrides it with the
    /// adaptive exact predicate.
    fn orient2d(a: &[Self; 2], b: &[Self; 2], c: &[Self; 2]) -> Sign {
        let d = (b[0].clone() - a[0].clone()) * (c[1].clone() - a[1].clone())
            - (b[1].clone() - a[1].clone()) * (c[0].clone() - a[0].clone());
        d.sign()
    }

    /// Sign of `det[b-a, c-a, d-a]`: positive when `d` lies on the side of the plane
    /// `abc` into which the normal `(b-a)×(c-a)` points.
    fn orient3d(a: &[Self; 3], b: &[Self; 3], c: &[Self; 3], d: &[Self; 3]) -> Sign {
        let u = sub3(b, a);
        let v = sub3(c, a);
        let w = sub3(d, a);
        det3(&u, &v, &w).sign()
    }
}

/// Scalars with a (rounded) square root: the kernel routines that need lengths
/// (chord-length parameters, unit normals) are bounded on this.
pub trait RealScalar: Scalar {
    fn sqrt(&self) -> Self;
}

fn sub3<S: Scalar>(a: &[S; 3], b: &[S; 3]) -> [S; 3] {
    [
        a[0].clone() - b[0].clone(),
        a[1].clone() - b[1].clone(),
        a[2].clone() - b[2].clone(),
    ]
}

fn det3<S: Scalar>(u: &[S; 3], v: &[S; 3], w: &[S; 3]) -> S {
    u[0].clone() * (v[1].clone() * w[2].clone() - v[2].clone() * w[1].clone())
        - u[1].clone() * (v[0].clone() * w[2].clone() - v[2].clone() * w[0].clone())
        + u[2].clone() * (v[0].clone() * w[1].clone() - v[1].clone() * w[0].clone())
}

/// `C(n, k)` in `i64` (exact for n ≤ 60, saturating beyond — far above any spline degree).
/// Pascal's triangle `C(n, k)` for `n < 64` (all below `2^63`), built at compile time.
pub static BINOMIAL: [[u64; 64]; 64] = {
    let mut t = [[0u64; 64]; 64];
    let mut n = 0;
    while n < 64 {
        t[n][0] = 1;
        let mut k = 1;
        while k <= n {
            t[n][k] = t[n - 1][k - 1] + t[n - 1][k];
            k += 1;
        }
        n += 1;
    }
    t
};

pub fn binomial_i64(n: usize, k: usize) -> i64 {
    if k > n {
        return 0;
    }
    let k = k.min(n - k);
    let mut r: i128 = 1;
    for i in 0..k {
        r = r * (n - i) as i128 / (i + 1) as i128;
        if r > i64::MAX as i128 {
            return i64::MAX;
        }
    }
    r as i64
}

/// Convert between backends through `f64` when the source is rounded, exactly otherwise.
/// Used to lift f64 input into an exact backend: `lift::<Rational>(x)` is exact.
pub fn lift<S: Scalar>(x: f64) -> S {
    S::from_f64(x).expect("lift: caller guarantees a finite value")
}

/// Smallest `f64` `r` tried with `r² >= q` (proven in rationals).
pub fn sqrt_upper(q: &Rational) -> f64 {
    if q.is_zero() {
        return 0.0;
    }
    let approx = Scalar::to_f64(&Scalar::abs(q)).sqrt();
    let mut r = if approx > 0.0 {
        approx
    } else {
        f64::MIN_POSITIVE
    };
    for _ in 0..64 {
        let rq: Rational = lift(r);
        if rq.clone() * rq >= *q {
            return r;
        }
        r = r.next_up().max(r * (1.0 + 1e-15));
    }
    f64::INFINITY
}

#[cfg(test)]
mod binomial_tests {
    use super::{BINOMIAL, binomial_i64};

    /// The compile-time triangle equals the multiplicative formula (exact in i128) and
    /// the symmetry and row-sum identities.
    #[test]
    fn pascal_triangle_matches_the_formula() {
        for n in 0..64usize {
            let mut row_sum: u128 = 0;
            for k in 0..=n {
                assert_eq!(BINOMIAL[n][k] as i64, binomial_i64(n, k), "C({n},{k})");
                assert_eq!(BINOMIAL[n][k], BINOMIAL[n][n - k]);
                row_sum += BINOMIAL[n][k] as u128;
            }
            assert_eq!(row_sum, 1u128 << n);
        }
    }
}
