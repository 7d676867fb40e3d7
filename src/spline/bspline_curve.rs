//! B-spline curves: de Boor evaluation, derivative splines, Boehm knot insertion, Bézier
//! extraction, sub-curves (The NURBS Book, ch. 2–5).

use super::basis::{Buf, basis_funs_into};
use super::bezier_curve::BezierCurve;
use super::knots::KnotVector;
use super::{MAX_DEGREE, SplineError};
use crate::geom::Point;
use crate::scalar::Scalar;

/// A B-spline curve: validated knots and `n_ctrl` control points.
#[derive(Clone, Debug, PartialEq)]
pub struct BSplineCurve<P: Point> {
    pub knots: KnotVector<P::S>,
    pub control: Vec<P>,
}

/// A Bézier piece of a spline together with the parameter interval it covers.
#[derive(Clone, Debug, PartialEq)]
pub struct BezierPiece<P: Point> {
    pub t0: P::S,
    pub t1: P::S,
    pub curve: BezierCurve<P>,
}

impl<P: Point> BSplineCurve<P> {
    /// Validate and build.
    pub fn new(knots: Vec<P::S>, degree: usize, control: Vec<P>) -> Result<Self, SplineError> {
        if degree == 0 || degree > MAX_DEGREE {
            return Err(SplineError::Degree(degree));
        }
        let kv = KnotVector::new(knots, degree, control.len())?;
        Ok(BSplineCurve { knots: kv, control })
    }
    /// The Bézier curve as a B-spline on `[0, 1]`.
    pub fn from_bezier(b: &BezierCurve<P>) -> Result<Self, SplineError> {
        let kv = KnotVector::bezier(b.degree())?;
        Ok(BSplineCurve {
            knots: kv,
            control: b.control.clone(),
        })
    }
    /// The Bézier curve as a B-spline on `[t0, t1]` (knots `t0` and `t1`, each `degree + 1`
    /// times): the same points, the parameter mapped affinely.
    pub fn from_bezier_on(b: &BezierCurve<P>, t0: P::S, t1: P::S) -> Result<Self, SplineError> {
        let d = b.degree();
        let mut knots = vec![t0; d + 1];
        knots.extend(std::iter::repeat_n(t1, d + 1));
        Self::new(knots, d, b.control.clone())
    }
    pub fn degree(&self) -> usize {
        self.knots.degree()
    }
    pub fn domain(&self) -> (P::S, P::S) {
        self.knots.domain()
    }

    /// Point at `t` (basis functions, A3.1). Outside the domain the end polynomial pieces
    /// are extended; use [`Self::eval_checked`] to refuse such parameters.
    pub fn eval(&self, t: &P::S) -> P {
        let p = self.degree();
        let span = self.knots.find_span(t);
        let mut n = Buf::new();
        basis_funs_into(&self.knots, span, t, &mut n);
        let mut acc = P::origin();
        for (j, nj) in n.iter().enumerate() {
            acc = acc.add(&self.control[span - p + j].scale(nj));
        }
        acc
    }

    /// Point at `t` by de Boor's algorithm (The NURBS Book eq. 5.x, the triangular scheme of
    /// affine combinations); equals [`Self::eval`] exactly in exact arithmetic.
    pub fn eval_de_boor(&self, t: &P::S) -> P {
        let p = self.degree();
        let k = self.knots.find_span(t);
        let u = self.knots.knots();
        let mut d: Vec<P> = self.control[k - p..=k].to_vec();
        for r in 1..=p {
            for j in (r..=p).rev() {
                let i = k - p + j;
                let a0 = u[i].clone();
                let a1 = u[i + p + 1 - r].clone();
                d[j] = d[j - 1].lerp_on(&d[j], &a0, &a1, t);
            }
        }
        d.swap_remove(p)
    }

    /// Point at `t`, or an error for a parameter outside the domain.
    pub fn eval_checked(&self, t: &P::S) -> Result<P, SplineError> {
        if !self.knots.contains(t) {
            let (a, b) = self.domain();
            return Err(SplineError::OutOfDomain(t.to_f64(), a.to_f64(), b.to_f64()));
        }
        Ok(self.eval(t))
    }

    /// The derivative curve `C'(t)`, degree `p - 1`, control points
    /// `p (P_{i+1} - P_i) / (u_{i+p+1} - u_{i+1})` (zero where the knot difference is zero:
    /// the corresponding basis function vanishes identically). `None` for degree 1 (the
    /// derivative is piecewise constant, degree 0, which this kernel does not represent).
    pub fn derivative(&self) -> Option<Self> {
        let p = self.degree();
        if p < 2 {
            return None;
        }
        let u = self.knots.knots();
        let pp = P::S::from_i64(p as i64);
        let control = (0..self.control.len() - 1)
            .map(|i| {
                let den = u[i + p + 1].clone() - u[i + 1].clone();
                if den.is_zero() {
                    P::origin()
                } else {
                    self.control[i + 1]
                        .sub(&self.control[i])
                        .scale(&(pp.clone() / den))
                }
            })
            .collect();
        Some(BSplineCurve {
            knots: self.knots.derivative()?,
            control,
        })
    }

    /// First derivative at `t`, valid for every degree ≥ 1.
    pub fn derivative_at(&self, t: &P::S) -> P {
        let ders = super::basis::ders_basis_funs(&self.knots, self.knots.find_span(t), t, 1);
        let span = self.knots.find_span(t);
        let p = self.degree();
        let mut acc = P::origin();
        for j in 0..=p {
            acc = acc.add(&self.control[span - p + j].scale(&ders[1][j]));
        }
        acc
    }

    /// Insert the knot `t` `r` times (Boehm's algorithm, The NURBS Book A5.1). The curve is
    /// unchanged: exactly so in exact arithmetic. Insertion stops at multiplicity `p`
    /// (further copies would not change the control polygon meaningfully).
    pub fn insert_knot(&self, t: &P::S, r: usize) -> Self {
        let mut c = self.clone();
        for _ in 0..r {
            if c.knots.multiplicity(t) >= c.degree() {
                break;
            }
            c = c.insert_once(t);
        }
        c
    }

    fn insert_once(&self, t: &P::S) -> Self {
        let p = self.degree();
        let u = self.knots.knots();
        let k = self.knots.find_span(t);
        // Knot vector: t inserted after position k.
        let mut nk = Vec::with_capacity(u.len() + 1);
        nk.extend_from_slice(&u[..=k]);
        nk.push(t.clone());
        nk.extend_from_slice(&u[k + 1..]);
        let mut q = Vec::with_capacity(self.control.len() + 1);
        for i in 0..=self.control.len() {
            if i + p <= k {
                q.push(self.control[i].clone());
            } else if i > k {
                q.push(self.control[i - 1].clone());
            } else {
                // k - p + 1 <= i <= k
                let a = (t.clone() - u[i].clone()) / (u[i + p].clone() - u[i].clone());
                q.push(self.control[i - 1].lerp(&self.control[i], &a));
            }
        }
        BSplineCurve {
            knots: KnotVector::new_unchecked(nk, p),
            control: q,
        }
    }

    /// Make every breakpoint (domain ends included) of multiplicity ≥ p.
    fn saturated(&self) -> Self {
        let p = self.degree();
        let mut c = self.clone();
        for b in self.knots.breakpoints() {
            let m = c.knots.multiplicity(&b);
            if m < p {
                c = c.insert_knot(&b, p - m);
            }
        }
        c
    }

    /// Split into Bézier pieces, one per non-empty knot span, by knot insertion.
    pub fn bezier_pieces(&self) -> Vec<BezierPiece<P>> {
        let p = self.degree();
        let c = self.saturated();
        let br = c.knots.breakpoints();
        let mut out = Vec::with_capacity(br.len() - 1);
        for w in br.windows(2) {
            // Last index with knot == w[0] below the next break.
            let span = c.knots.find_span(&w[0]);
            out.push(BezierPiece {
                t0: w[0].clone(),
                t1: w[1].clone(),
                curve: BezierCurve {
                    control: c.control[span - p..=span].to_vec(),
                },
            });
        }
        out
    }

    /// The part over `[a, b]` (inside the domain, `a < b`) as a clamped B-spline.
    pub fn sub_curve(&self, a: &P::S, b: &P::S) -> Result<Self, SplineError> {
        let (d0, d1) = self.domain();
        if *a < d0 || *b > d1 || *a >= *b {
            return Err(SplineError::OutOfDomain(
                a.to_f64(),
                d0.to_f64(),
                d1.to_f64(),
            ));
        }
        let p = self.degree();
        let mut c = self.clone();
        for x in [a, b] {
            let m = c.knots.multiplicity(x);
            if m < p {
                c = c.insert_knot(x, p - m);
            }
        }
        let k = c.knots.knots();
        let idx: Vec<usize> = (0..c.control.len())
            .filter(|&i| k[i] < *b && k[i + p + 1] > *a)
            .collect();
        let (i0, i1) = (idx[0], *idx.last().unwrap_or(&idx[0]));
        let mut nk: Vec<P::S> = k[i0..=i1 + p + 1].to_vec();
        for kk in nk.iter_mut().take(p + 1) {
            *kk = a.clone();
        }
        let len = nk.len();
        for kk in nk.iter_mut().skip(len - p - 1) {
            *kk = b.clone();
        }
        Ok(BSplineCurve {
            knots: KnotVector::new_unchecked(nk, p),
            control: c.control[i0..=i1].to_vec(),
        })
    }

    /// The same curve traversed the other way over the same domain: `C'(t) = C(a + b − t)`
    /// (knots mirrored, control points reversed). Exact for exact scalars; in f64 each
    /// mirrored knot `a + b − t` is rounded once (exact when the knots are small dyadic
    /// numbers, as in the constructions of this crate).
    pub fn reversed(&self) -> Self {
        let (a, b) = self.domain();
        let ab = a + b;
        let k: Vec<P::S> = self
            .knots
            .knots()
            .iter()
            .rev()
            .map(|t| ab.clone() - t.clone())
            .collect();
        let mut control = self.control.clone();
        control.reverse();
        BSplineCurve {
            knots: KnotVector::new_unchecked(k, self.degree()),
            control,
        }
    }

    /// Map every control point (e.g. to convert backends).
    pub fn map<Q: Point>(
        &self,
        kmap: impl Fn(&P::S) -> Q::S,
        f: impl Fn(&P) -> Q,
    ) -> BSplineCurve<Q> {
        BSplineCurve {
            knots: KnotVector::new_unchecked(
                self.knots.knots().iter().map(kmap).collect(),
                self.degree(),
            ),
            control: self.control.iter().map(f).collect(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::Rational;
    type Q = Rational;
    fn q(x: f64) -> Q {
        crate::scalar::lift(x)
    }
    fn curve() -> BSplineCurve<[Q; 3]> {
        let knots = [0., 0., 0., 0., 0.2, 0.45, 0.45, 0.8, 1., 1., 1., 1.];
        let pts: Vec<[Q; 3]> = (0..8)
            .map(|i| {
                [
                    q(i as f64),
                    q(((i * 5) % 7) as f64),
                    q(((i * 3) % 4) as f64 * 0.5),
                ]
            })
            .collect();
        BSplineCurve::new(knots.iter().map(|&x| q(x)).collect(), 3, pts).unwrap()
    }

    #[test]
    fn insertion_extraction_subcurve_exact() {
        let c = curve();
        let c2 = c.insert_knot(&q(0.3), 2).insert_knot(&q(0.8), 1);
        let pieces = c.bezier_pieces();
        assert_eq!(pieces.len(), 4);
        let sub = c.sub_curve(&q(0.1), &q(0.7)).unwrap();
        for i in 0..=40 {
            let t = q(i as f64 / 40.0);
            assert_eq!(c2.eval(&t), c.eval(&t));
            let pc = pieces.iter().find(|p| p.t0 <= t && t <= p.t1).unwrap();
            let s = (t.clone() - pc.t0.clone()) / (pc.t1.clone() - pc.t0.clone());
            assert_eq!(pc.curve.eval(&s), c.eval(&t));
            if t >= q(0.1) && t <= q(0.7) {
                assert_eq!(sub.eval(&t), c.eval(&t));
            }
        }
    }

    #[test]
    fn derivative_spline_equals_basis_derivative() {
        let c = curve();
        let d = c.derivative().unwrap();
        for i in 0..=20 {
            let t = q(i as f64 / 20.0);
            assert_eq!(d.eval(&t), c.derivative_at(&t));
            assert_eq!(c.eval_de_boor(&t), c.eval(&t));
        }
    }
}
