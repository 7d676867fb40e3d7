//! Bézier curves: de Casteljau evaluation, blossoms, subdivision, degree elevation,
//! hodographs (Farin, *Curves and Surfaces for CAGD*, ch. 3–5).

use crate::geom::Point;
use crate::scalar::Scalar;

/// A Bézier curve of degree `control.len() - 1` over `[0, 1]`.
#[derive(Clone, Debug, PartialEq)]
pub struct BezierCurve<P: Point> {
    pub control: Vec<P>,
}

impl<P: Point> BezierCurve<P> {
    /// Curve from at least one control point.
    pub fn new(control: Vec<P>) -> Option<Self> {
        if control.is_empty() {
            None
        } else {
            Some(BezierCurve { control })
        }
    }
    pub fn degree(&self) -> usize {
        self.control.len() - 1
    }

    /// Blossom `b[t_1, …, t_n]`: de Casteljau with a different parameter at each level.
    /// `ts.len()` must equal the degree. Symmetric and multi-affine in its arguments; on the
    /// diagonal it is the curve point.
    pub fn blossom(&self, ts: &[P::S]) -> P {
        assert_eq!(
            ts.len(),
            self.degree(),
            "blossom needs degree-many arguments"
        );
        let mut b = self.control.clone();
        for (level, t) in ts.iter().enumerate() {
            for i in 0..b.len() - 1 - level {
                b[i] = b[i].lerp(&b[i + 1], t);
            }
        }
        b.swap_remove(0)
    }

    /// Point at `t` (de Casteljau).
    pub fn eval(&self, t: &P::S) -> P {
        let mut b = self.control.clone();
        let n = b.len();
        for level in 1..n {
            for i in 0..n - level {
                b[i] = b[i].lerp(&b[i + 1], t);
            }
        }
        b.swap_remove(0)
    }

    /// Split at `t` into the pieces over `[0, t]` and `[t, 1]`, each reparametrized to
    /// `[0, 1]`. Exact in exact arithmetic.
    pub fn subdivide(&self, t: &P::S) -> (Self, Self) {
        let n = self.control.len();
        let mut b = self.control.clone();
        let mut left = Vec::with_capacity(n);
        let mut right = Vec::with_capacity(n);
        left.push(b[0].clone());
        right.push(b[n - 1].clone());
        for level in 1..n {
            for i in 0..n - level {
                b[i] = b[i].lerp(&b[i + 1], t);
            }
            left.push(b[0].clone());
            right.push(b[n - 1 - level].clone());
        }
        right.reverse();
        (
            BezierCurve { control: left },
            BezierCurve { control: right },
        )
    }

    /// The piece over `[a, b]` reparametrized to `[0, 1]` (blossom: control point `i` is
    /// `b[a^(n-i), b^i]`).
    pub fn segment(&self, a: &P::S, b: &P::S) -> Self {
        let n = self.degree();
        let control = (0..=n)
            .map(|i| {
                let mut ts = vec![a.clone(); n - i];
                ts.extend(std::iter::repeat_n(b.clone(), i));
                self.blossom(&ts)
            })
            .collect();
        BezierCurve { control }
    }

    /// Same curve as degree `n + 1`: `Q_i = i/(n+1) P_{i-1} + (1 - i/(n+1)) P_i`.
    pub fn elevate(&self) -> Self {
        let n = self.degree();
        let n1 = P::S::from_i64((n + 1) as i64);
        let mut q = Vec::with_capacity(n + 2);
        q.push(self.control[0].clone());
        for i in 1..=n {
            let a = P::S::from_i64(i as i64) / n1.clone();
            q.push(self.control[i].lerp(&self.control[i - 1], &a));
        }
        q.push(self.control[n].clone());
        BezierCurve { control: q }
    }

    /// Hodograph (first derivative curve), degree `n - 1`: `n (P_{i+1} - P_i)`.
    /// `None` for a degree-0 curve.
    pub fn hodograph(&self) -> Option<Self> {
        let n = self.degree();
        if n == 0 {
            return None;
        }
        let nn = P::S::from_i64(n as i64);
        Some(BezierCurve {
            control: (0..n)
                .map(|i| self.control[i + 1].sub(&self.control[i]).scale(&nn))
                .collect(),
        })
    }

    /// Reverse the parameter direction.
    pub fn reversed(&self) -> Self {
        let mut c = self.control.clone();
        c.reverse();
        BezierCurve { control: c }
    }

    /// Map every control point.
    pub fn map<Q: Point>(&self, f: impl Fn(&P) -> Q) -> BezierCurve<Q> {
        BezierCurve {
            control: self.control.iter().map(f).collect(),
        }
    }
}

/// Bernstein polynomial `B_i^n(t)`.
pub fn bernstein<S: Scalar>(n: usize, i: usize, t: &S) -> S {
    let mut r = S::binomial(n, i);
    let one_t = S::one() - t.clone();
    for _ in 0..i {
        r = r * t.clone();
    }
    for _ in 0..n - i {
        r = r * one_t.clone();
    }
    r
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::Rational;
    type Q = Rational;
    fn q(x: f64) -> Q {
        crate::scalar::lift(x)
    }
    fn curve() -> BezierCurve<[Q; 2]> {
        BezierCurve::new(vec![
            [q(0.), q(0.)],
            [q(1.), q(2.)],
            [q(3.), q(-1.)],
            [q(4.), q(0.5)],
        ])
        .unwrap()
    }

    #[test]
    fn subdivision_and_elevation_are_exact() {
        let c = curve();
        let t = q(0.375);
        let (l, r) = c.subdivide(&t);
        for i in 0..=8 {
            let s = q(i as f64 / 8.0);
            assert_eq!(l.eval(&s), c.eval(&(t.clone() * s.clone())));
            assert_eq!(
                r.eval(&s),
                c.eval(&(t.clone() + (q(1.) - t.clone()) * s.clone()))
            );
            assert_eq!(c.elevate().eval(&s), c.eval(&s));
        }
        assert_eq!(c.segment(&q(0.), &t), l);
        assert_eq!(c.segment(&t, &q(1.)), r);
    }

    #[test]
    fn blossom_diagonal_and_bernstein_sum() {
        let c = curve();
        let t = q(0.3);
        assert_eq!(c.blossom(&[t.clone(), t.clone(), t.clone()]), c.eval(&t));
        let mut p = <[Q; 2] as Point>::origin();
        for i in 0..=3 {
            p = p.add(&c.control[i].scale(&bernstein(3, i, &t)));
        }
        assert_eq!(p, c.eval(&t));
    }

    #[test]
    fn hodograph_matches_difference_quotient_limit() {
        // Derivative of a cubic via exact symmetric difference of the polynomial:
        // for cubics, (c(t+h) - c(t-h)) / 2h = c'(t) + c'''(t) h^2 / 6 — check with the
        // third hodograph.
        let c = curve();
        let h1 = c.hodograph().unwrap();
        let h3 = h1.hodograph().unwrap().hodograph().unwrap();
        let (t, h) = (q(0.4), q(0.125));
        let num = c
            .eval(&(t.clone() + h.clone()))
            .sub(&c.eval(&(t.clone() - h.clone())));
        let lhs = num.scale(&(q(1.) / (q(2.) * h.clone())));
        let rhs = h1
            .eval(&t)
            .add(&h3.control[0].scale(&(h.clone() * h.clone() / q(6.))));
        assert_eq!(lhs, rhs);
    }
}
