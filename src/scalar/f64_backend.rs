//! `f64`: the fast path. Predicates are Shewchuk's adaptive exact ones (crate `robust`):
//! a floating-point filter answers when the sign is clear, exact expansions when not.

use super::{NotFinite, Rational, RealScalar, Scalar, Sign};

/// Shewchuk's predicates are exact only when no intermediate product overflows or
/// underflows. With every non-zero coordinate magnitude in `[2^-200, 2^200]`, coordinate
/// differences lie in `[2^-253, 2^201]` (differences of such numbers are multiples of the
/// smaller one's ulp), triple products and their expansion tails in `[2^-900, 2^604]`: far
/// inside the normal range. Outside it the predicates fall back to exact rationals.
const SAFE_LO: f64 = 6.223015277861142e-61; // 2^-200
const SAFE_HI: f64 = 1.6069380442589903e60; // 2^200

#[inline(always)]
fn safe(xs: &[f64]) -> bool {
    xs.iter().all(|x| {
        let a = x.abs();
        a == 0.0 || (SAFE_LO..=SAFE_HI).contains(&a)
    })
}

fn exact<const D: usize>(p: &[f64; D]) -> [Rational; D] {
    std::array::from_fn(|i| p[i].to_rational())
}

impl Scalar for f64 {
    const EXACT: bool = false;
    const NAME: &'static str = "f64";

    #[inline(always)]
    fn zero() -> Self {
        0.0
    }
    #[inline(always)]
    fn one() -> Self {
        1.0
    }
    #[inline(always)]
    fn from_i64(i: i64) -> Self {
        i as f64
    }
    #[inline(always)]
    fn from_f64(x: f64) -> Result<Self, NotFinite> {
        if x.is_finite() {
            Ok(x)
        } else {
            Err(NotFinite(x))
        }
    }
    #[inline(always)]
    fn to_f64(&self) -> f64 {
        *self
    }
    #[inline(always)]
    fn sign(&self) -> Sign {
        if *self > 0.0 {
            Sign::Positive
        } else if *self < 0.0 {
            Sign::Negative
        } else {
            Sign::Zero
        }
    }
    fn to_rational(&self) -> Rational {
        // Finite by construction of every f64 the kernel accepts; NaN/inf map to 0 here and
        // are rejected at the input boundary (model validation).
        Rational::try_from(*self).unwrap_or_default()
    }
    #[inline(always)]
    fn abs(&self) -> Self {
        f64::abs(*self)
    }

    /// Adaptive exact orientation (Shewchuk's `orient2d`); exact rationals outside the
    /// safe exponent range.
    #[inline]
    fn orient2d(a: &[f64; 2], b: &[f64; 2], c: &[f64; 2]) -> Sign {
        if !safe(&[a[0], a[1], b[0], b[1], c[0], c[1]]) {
            return Rational::orient2d(&exact(a), &exact(b), &exact(c));
        }
        let c2 = |p: &[f64; 2]| robust::Coord { x: p[0], y: p[1] };
        robust::orient2d(c2(a), c2(b), c2(c)).sign()
    }

    /// Adaptive exact orientation. Shewchuk's `orient3d(a,b,c,d)` is
    /// `det[a-d, b-d, c-d] = -det[b-a, c-a, d-a]`, hence the negation.
    #[inline]
    fn orient3d(a: &[f64; 3], b: &[f64; 3], c: &[f64; 3], d: &[f64; 3]) -> Sign {
        if !safe(&[
            a[0], a[1], a[2], b[0], b[1], b[2], c[0], c[1], c[2], d[0], d[1], d[2],
        ]) {
            return Rational::orient3d(&exact(a), &exact(b), &exact(c), &exact(d));
        }
        let c3 = |p: &[f64; 3]| robust::Coord3D {
            x: p[0],
            y: p[1],
            z: p[2],
        };
        robust::orient3d(c3(a), c3(b), c3(c), c3(d)).sign().flip()
    }
}

impl RealScalar for f64 {
    #[inline(always)]
    fn sqrt(&self) -> Self {
        f64::sqrt(*self)
    }
}
