//! Exact points of a NURBS surface at `f64` parameters, fraction-free.
//!
//! Every finite `f64` is a dyadic rational `m · 2^e` (`m` an integer of at most 53 bits), so
//! `S(u, v) = Σ N_i(u) N_j(v) w_ij P_ij / Σ N_i(u) N_j(v) w_ij` (The NURBS Book eq. 4.9, the
//! homogeneous form of the net: `wp_ij = w_ij P_ij` and `w_ij` as stored, taken as the exact
//! values they are) is a rational number computed exactly here:
//!
//! * the `p + 1` non-zero basis functions at `u` (Cox–de Boor, A2.2) over one common
//!   denominator `D_u`, computed fraction-free in integers: `N_i(u) = a_i / D_u` with
//!   integers `a_i` (see `basis_numerators`); the same in `v`;
//! * the net's values as integers on one power of two: `wp_ijk = M_ijk · 2^{e_p}`,
//!   `w_ij = m_ij · 2^{e_w}` (`e_p`, `e_w` the smallest exponents present);
//! * `X_k = Σ a_i b_j M_ijk` and `W = Σ a_i b_j m_ij` in integers, so that
//!   `S_k = X_k 2^{e_p} / (W 2^{e_w})` — the factor `1 / (D_u D_v)` cancels.
//!
//! No fraction is reduced on the way (the rational backend reduces at every operation, about
//! ten times the cost). A difference of two such points is again a quotient of integers
//! times a power of two, rounded outward to an `f64` interval at the end
//! ([`ExactPoint::minus_enclosed`]): its width is a few ulps *of the difference*, however
//! much cancels.

use super::knots::KnotVector;
use super::nurbs::NurbsSurface;
use crate::scalar::{BigInt, Interval, Rational, pow2, ratio};
use dashu_int::ops::{BitTest, UnsignedAbs};

/// A surface point `S_k = x_k · 2^shift / w` exactly (`w ≠ 0`).
#[derive(Clone, Debug, PartialEq)]
pub struct ExactPoint {
    pub x: [BigInt; 3],
    pub w: BigInt,
    pub shift: i64,
}

/// `x = m · 2^e` exactly, for finite `x` (`m = 0` for zero).
pub fn decode(x: f64) -> (i64, i64) {
    let bits = x.to_bits();
    let sign = if bits >> 63 == 0 { 1 } else { -1 };
    let exp = ((bits >> 52) & 0x7ff) as i64;
    let frac = (bits & ((1u64 << 52) - 1)) as i64;
    let (m, e) = if exp == 0 {
        (frac, -1074)
    } else {
        (frac | (1i64 << 52), exp - 1075)
    };
    (sign * m, e)
}

/// Evaluator of one surface.
#[derive(Clone, Debug)]
pub struct ExactEvaluator {
    f: NurbsSurface<f64, 3>,
}

/// The `p + 1` basis functions of span `span` at `t` over one common denominator: their
/// numerators, fraction-free.
///
/// The recurrence is A2.2's (The NURBS Book), `N_r ← saved + right_{r+1} · N_r / d_r`,
/// `saved ← left_{j−r} · N_r / d_r` with `d_r = right_{r+1} + left_{j−r}` (a knot difference,
/// positive inside a non-empty span), in integers: every knot and `t` is `m · 2^e`, so on the
/// smallest exponent `e0` present they are integers and so are `left`, `right` and `d_r`
/// (the common factor `2^e0` cancels in `right · N / d`). Level `j` keeps its values over
/// `D_j = D_{j−1} · Π_r d_r` and multiplies `N_r` by `Π_{s≠r} d_s` instead of dividing by
/// `d_r`: no fraction is formed or reduced. The numerators' ratios are the basis values'.
fn basis_numerators(knots: &[f64], p: usize, span: usize, t: f64) -> Vec<BigInt> {
    let used = || {
        knots[span + 1 - p..=span + p]
            .iter()
            .chain(std::iter::once(&t))
    };
    let e0 = used()
        .map(|x| decode(*x))
        .filter(|(m, _)| *m != 0)
        .map(|(_, e)| e)
        .min()
        .unwrap_or(0);
    let int = |x: f64| {
        let (m, e) = decode(x);
        BigInt::from(m) << ((e - e0).max(0) as usize)
    };
    let ti = int(t);
    let mut left = vec![BigInt::ZERO; p + 1];
    let mut right = vec![BigInt::ZERO; p + 1];
    for j in 1..=p {
        left[j] = &ti - int(knots[span + 1 - j]);
        right[j] = int(knots[span + j]) - &ti;
    }
    let mut n = vec![BigInt::ONE];
    for j in 1..=p {
        let d: Vec<BigInt> = (0..j).map(|r| &right[r + 1] + &left[j - r]).collect();
        // `Π_{s≠r} d_s` from prefix and suffix products.
        let mut suffix = vec![BigInt::ONE; j + 1];
        for r in (0..j).rev() {
            suffix[r] = &suffix[r + 1] * &d[r];
        }
        let mut prefix = BigInt::ONE;
        let mut saved = BigInt::ZERO;
        for r in 0..j {
            let temp = &n[r] * (&prefix * &suffix[r + 1]);
            n[r] = saved + &right[r + 1] * &temp;
            saved = &left[j - r] * temp;
            prefix *= &d[r];
        }
        n.push(saved);
    }
    n
}

impl ExactEvaluator {
    /// `None` when a knot is not finite.
    pub fn new(s: &NurbsSurface<f64, 3>) -> Option<ExactEvaluator> {
        let finite = |k: &KnotVector<f64>| k.knots().iter().all(|x| x.is_finite());
        (finite(&s.hom.ku) && finite(&s.hom.kv)).then(|| ExactEvaluator { f: s.clone() })
    }

    /// `S(u, v)` exactly; `None` for parameters not finite or outside the domain, or a weight
    /// sum of zero.
    pub fn point(&self, u: f64, v: f64) -> Option<ExactPoint> {
        let h = &self.f.hom;
        if !(h.ku.contains(&u) && h.kv.contains(&v)) {
            return None;
        }
        let (p, q) = (h.ku.degree(), h.kv.degree());
        // The spans of the exact values equal those of the f64 values (same comparisons).
        let (su, sv) = (h.ku.find_span(&u), h.kv.find_span(&v));
        let a = basis_numerators(h.ku.knots(), p, su, u);
        let b = basis_numerators(h.kv.knots(), q, sv, v);
        let nv = h.kv.n_ctrl();
        let idx = |i: usize, j: usize| (su - p + i) * nv + sv - q + j;
        let (mut ep, mut ew) = (i64::MAX, i64::MAX);
        for i in 0..=p {
            for j in 0..=q {
                let c = &h.net[idx(i, j)];
                for x in c.wp.iter().chain(std::iter::once(&c.w)) {
                    if !x.is_finite() {
                        return None;
                    }
                }
                for x in c.wp {
                    let (m, e) = decode(x);
                    if m != 0 {
                        ep = ep.min(e);
                    }
                }
                let (m, e) = decode(c.w);
                if m != 0 {
                    ew = ew.min(e);
                }
            }
        }
        if ew == i64::MAX {
            return None;
        }
        let ep = if ep == i64::MAX { 0 } else { ep };
        let int = |x: f64, e0: i64| {
            let (m, e) = decode(x);
            BigInt::from(m) << ((e - e0) as usize)
        };
        let mut xs: [BigInt; 3] = Default::default();
        let mut w = BigInt::ZERO;
        for i in 0..=p {
            if a[i].is_zero() {
                continue;
            }
            let mut row: [BigInt; 3] = Default::default();
            let mut roww = BigInt::ZERO;
            for j in 0..=q {
                if b[j].is_zero() {
                    continue;
                }
                let c = &h.net[idx(i, j)];
                for k in 0..3 {
                    if c.wp[k] != 0.0 {
                        row[k] += &b[j] * int(c.wp[k], ep);
                    }
                }
                if c.w != 0.0 {
                    roww += &b[j] * int(c.w, ew);
                }
            }
            for k in 0..3 {
                xs[k] += &a[i] * &row[k];
            }
            w += &a[i] * roww;
        }
        if w.is_zero() {
            return None;
        }
        Some(ExactPoint {
            x: xs,
            w,
            shift: ep - ew,
        })
    }
}

impl ExactPoint {
    /// The coordinates as exact rationals (reference answers).
    pub fn rational(&self) -> [Rational; 3] {
        let scale = pow2(self.shift);
        std::array::from_fn(|k| ratio(self.x[k].clone(), self.w.clone()) * &scale)
    }

    /// The coordinates of `self − other`, each rounded outward to an `f64` interval (`None`
    /// when a coordinate is beyond the `f64` range).
    pub fn minus_enclosed(&self, other: &ExactPoint) -> Option<[Interval; 3]> {
        let m = self.shift.min(other.shift);
        let (sa, sb) = ((self.shift - m) as usize, (other.shift - m) as usize);
        let den = &self.w * &other.w;
        let mut out = [Interval::point(0.0); 3];
        for k in 0..3 {
            let num = ((&self.x[k] * &other.w) << sa) - ((&other.x[k] * &self.w) << sb);
            out[k] = ratio_enclosed(&num, &den, m)?;
        }
        Some(out)
    }

    /// The coordinates, each rounded outward to an `f64` interval.
    pub fn enclosed(&self) -> Option<[Interval; 3]> {
        let mut out = [Interval::point(0.0); 3];
        for k in 0..3 {
            out[k] = ratio_enclosed(&self.x[k], &self.w, self.shift)?;
        }
        Some(out)
    }
}

/// `[lo, hi] · 2^e` outward, for `0 ≤ lo ≤ hi` normal numbers: products by powers of two
/// are exact while the results stay normal; a lower end at or below `2^-1022` (possibly
/// rounded up to it from the subnormal range) is replaced by `0`, an upper end below it by
/// `2 · 2^-1022` (an upper bound of anything that rounded below `2^-1022`). `None` on
/// overflow.
fn scale_outward(lo: f64, hi: f64, e: i64) -> Option<(f64, f64)> {
    let (mut l, mut h, mut e) = (lo, hi, e);
    while e != 0 {
        let s = e.clamp(-600, 600);
        let f = 2f64.powi(s as i32);
        l *= f;
        h *= f;
        e -= s;
    }
    if !(l.is_finite() && h.is_finite()) {
        return None;
    }
    if l <= f64::MIN_POSITIVE {
        l = 0.0;
    }
    if h < f64::MIN_POSITIVE {
        h = 2.0 * f64::MIN_POSITIVE;
    }
    Some((l, h))
}

/// An `f64` interval holding `n · 2^e / d` (`d ≠ 0`).
pub fn ratio_enclosed(n: &BigInt, d: &BigInt, e: i64) -> Option<Interval> {
    if d.is_zero() {
        return None;
    }
    if n.is_zero() {
        return Some(Interval::point(0.0));
    }
    let neg = (*n < BigInt::ZERO) != (*d < BigInt::ZERO);
    let (na, da) = (n.unsigned_abs(), d.unsigned_abs());
    // q = ⌊na · 2^k / da⌋ with at least 64 significant bits: na 2^k / da ∈ [q, q + 1).
    let k = 66 + da.bit_len() as i64 - na.bit_len() as i64;
    let q = if k >= 0 {
        (na << (k as usize)) / da
    } else {
        na / (da << ((-k) as usize))
    };
    // q has 65–67 bits: q and q + 1 round to f64 within one ulp (and above 2^64, so
    // `to_f64` is finite); one more ulp outward for safety.
    let lo = q.to_f64().value().next_down().next_down();
    let hi = (q + 1u32).to_f64().value().next_up().next_up();
    let (lo, hi) = scale_outward(lo, hi, e - k)?;
    Some(if neg {
        Interval::new(-hi, -lo)
    } else {
        Interval::new(lo, hi)
    })
}

#[cfg(test)]
mod tests;
