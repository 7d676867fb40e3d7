//! Knot vectors: validation, spans, multiplicities (The NURBS Book, §2.2).

use crate::scalar::Scalar;

/// Why a knot vector was refused.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum KnotError {
    #[error("{got} knots for degree {degree} and {n_ctrl} control points; expected {expected}")]
    Count {
        got: usize,
        expected: usize,
        degree: usize,
        n_ctrl: usize,
    },
    #[error("knots decrease at index {0}")]
    Unsorted(usize),
    #[error("knot {index} has multiplicity {mult} > degree + 1 = {max}")]
    Multiplicity {
        index: usize,
        mult: usize,
        max: usize,
    },
    #[error(
        "interior knot {index} has multiplicity {mult} > degree {degree}: the spline would be discontinuous"
    )]
    InteriorMultiplicity {
        index: usize,
        mult: usize,
        degree: usize,
    },
    #[error("empty parameter domain: knot[{lo}] == knot[{hi}]")]
    EmptyDomain { lo: usize, hi: usize },
    #[error("degree must be at least 1")]
    ZeroDegree,
    #[error("need at least degree + 1 = {need} control points, got {got}")]
    TooFewControlPoints { need: usize, got: usize },
    #[error("knot {0} is not finite")]
    NotFinite(usize),
    #[error(
        "knot span [{lo:e}, {hi:e}] is wider than the f64 range: basis functions would divide by infinity"
    )]
    SpanNotFinite { lo: f64, hi: f64 },
}

/// A validated knot vector for a spline of degree `degree` with `n_ctrl` control points:
/// `knots.len() == n_ctrl + degree + 1`, non-decreasing, interior multiplicities ≤ degree,
/// a non-empty domain `[knots[degree], knots[n_ctrl]]`.
#[derive(Clone, Debug, PartialEq)]
pub struct KnotVector<S: Scalar> {
    knots: Vec<S>,
    degree: usize,
}

impl<S: Scalar> KnotVector<S> {
    /// Validate and wrap.
    pub fn new(knots: Vec<S>, degree: usize, n_ctrl: usize) -> Result<Self, KnotError> {
        if degree == 0 {
            return Err(KnotError::ZeroDegree);
        }
        if n_ctrl < degree + 1 {
            return Err(KnotError::TooFewControlPoints {
                need: degree + 1,
                got: n_ctrl,
            });
        }
        let expected = n_ctrl + degree + 1;
        if knots.len() != expected {
            return Err(KnotError::Count {
                got: knots.len(),
                expected,
                degree,
                n_ctrl,
            });
        }
        for (i, k) in knots.iter().enumerate() {
            if !k.to_f64().is_finite() {
                return Err(KnotError::NotFinite(i));
            }
        }
        for i in 1..knots.len() {
            if knots[i] < knots[i - 1] {
                return Err(KnotError::Unsorted(i));
            }
        }
        // Every difference of knots (the denominators of the basis recurrence) is at most
        // the whole span: it must be a finite f64 too.
        let (lo, hi) = (&knots[0], &knots[knots.len() - 1]);
        if !(hi.clone() - lo.clone()).to_f64().is_finite() {
            return Err(KnotError::SpanNotFinite {
                lo: lo.to_f64(),
                hi: hi.to_f64(),
            });
        }
        // Multiplicities.
        let mut i = 0;
        while i < knots.len() {
            let mut j = i + 1;
            while j < knots.len() && knots[j] == knots[i] {
                j += 1;
            }
            let mult = j - i;
            if mult > degree + 1 {
                return Err(KnotError::Multiplicity {
                    index: i,
                    mult,
                    max: degree + 1,
                });
            }
            // Interior: strictly inside the domain.
            if knots[i] > knots[degree] && knots[i] < knots[n_ctrl] && mult > degree {
                return Err(KnotError::InteriorMultiplicity {
                    index: i,
                    mult,
                    degree,
                });
            }
            i = j;
        }
        if knots[degree] >= knots[n_ctrl] {
            return Err(KnotError::EmptyDomain {
                lo: degree,
                hi: n_ctrl,
            });
        }
        // End knots of multiplicity `degree` at the domain's ends with one more knot beyond
        // (`t_0 < t_1 = … = t_p`, as systems that store closed surfaces periodically write
        // them): the outermost knot does not enter any basis function on the domain (in the
        // recurrence it only multiplies `N_{0,p-1}`, which vanishes on `[t_p, t_n]`), so it
        // is set to the domain end — the same spline, clamped.
        let mut knots = knots;
        let last = knots.len() - 1;
        if degree >= 2 && knots[1..=degree].iter().all(|t| *t == knots[degree]) {
            knots[0] = knots[degree].clone();
        }
        if degree >= 2 && knots[n_ctrl..last].iter().all(|t| *t == knots[n_ctrl]) {
            knots[last] = knots[n_ctrl].clone();
        }
        Ok(KnotVector { knots, degree })
    }

    /// Clamped uniform knot vector on `[0, 1]` (exact rationals `i / spans`).
    pub fn clamped_uniform(degree: usize, n_ctrl: usize) -> Result<Self, KnotError> {
        if degree == 0 {
            return Err(KnotError::ZeroDegree);
        }
        if n_ctrl < degree + 1 {
            return Err(KnotError::TooFewControlPoints {
                need: degree + 1,
                got: n_ctrl,
            });
        }
        let spans = n_ctrl - degree;
        let mut k = vec![S::zero(); degree + 1];
        for i in 1..spans {
            k.push(S::from_i64(i as i64) / S::from_i64(spans as i64));
        }
        k.extend(std::iter::repeat_n(S::one(), degree + 1));
        KnotVector::new(k, degree, n_ctrl)
    }

    /// Bézier knot vector `[0^(p+1), 1^(p+1)]`.
    pub fn bezier(degree: usize) -> Result<Self, KnotError> {
        Self::clamped_uniform(degree, degree + 1)
    }

    /// Wrap without validation — for knot vectors produced by kernel operations that
    /// preserve validity (knot insertion, derivative splines).
    pub(crate) fn new_unchecked(knots: Vec<S>, degree: usize) -> Self {
        KnotVector { knots, degree }
    }

    pub fn degree(&self) -> usize {
        self.degree
    }
    pub fn knots(&self) -> &[S] {
        &self.knots
    }
    pub fn len(&self) -> usize {
        self.knots.len()
    }
    pub fn is_empty(&self) -> bool {
        self.knots.is_empty()
    }
    /// Number of control points this knot vector serves.
    pub fn n_ctrl(&self) -> usize {
        self.knots.len() - self.degree - 1
    }
    /// Parameter domain `[knots[p], knots[n]]`.
    pub fn domain(&self) -> (S, S) {
        (
            self.knots[self.degree].clone(),
            self.knots[self.n_ctrl()].clone(),
        )
    }
    /// Whether `t` lies in the closed domain.
    pub fn contains(&self, t: &S) -> bool {
        let (a, b) = self.domain();
        *t >= a && *t <= b
    }

    /// Span index `k` with `knots[k] <= t < knots[k+1]`, `p <= k < n`; the last non-empty
    /// span for `t` at the domain's end (The NURBS Book A2.1). The caller ensures `t` is in
    /// the domain; values outside are clamped to the end spans.
    pub fn find_span(&self, t: &S) -> usize {
        let n = self.n_ctrl();
        let p = self.degree;
        if *t >= self.knots[n] {
            // Last non-empty span.
            let mut k = n - 1;
            while k > p && self.knots[k] == self.knots[k + 1] {
                k -= 1;
            }
            return k;
        }
        if *t <= self.knots[p] {
            let mut k = p;
            while k + 1 < n && self.knots[k + 1] == self.knots[p] {
                k += 1;
            }
            return k;
        }
        let (mut lo, mut hi) = (p, n);
        while hi - lo > 1 {
            let mid = (lo + hi) / 2;
            if *t < self.knots[mid] {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        lo
    }

    /// Multiplicity of the value `t` in the knot vector.
    pub fn multiplicity(&self, t: &S) -> usize {
        self.knots.iter().filter(|k| *k == t).count()
    }

    /// Distinct interior knot values strictly inside the domain, ascending.
    pub fn interior_breaks(&self) -> Vec<S> {
        let (a, b) = self.domain();
        let mut out: Vec<S> = Vec::new();
        for k in &self.knots {
            if *k > a && *k < b && out.last() != Some(k) {
                out.push(k.clone());
            }
        }
        out
    }

    /// Distinct breakpoints including the domain ends, ascending.
    pub fn breakpoints(&self) -> Vec<S> {
        let (a, b) = self.domain();
        let mut v = vec![a];
        v.extend(self.interior_breaks());
        v.push(b);
        v
    }

    /// Knot vector of the derivative spline: the first and last knot removed.
    pub fn derivative(&self) -> Option<Self> {
        if self.degree == 0 {
            return None;
        }
        Some(KnotVector::new_unchecked(
            self.knots[1..self.knots.len() - 1].to_vec(),
            self.degree - 1,
        ))
    }

    /// Convert to `f64` knots.
    pub fn to_f64(&self) -> KnotVector<f64> {
        KnotVector::new_unchecked(self.knots.iter().map(|k| k.to_f64()).collect(), self.degree)
    }

    /// Lift `f64` knots exactly into another backend.
    pub fn lift<T: Scalar>(&self) -> KnotVector<T> {
        KnotVector::new_unchecked(
            self.knots
                .iter()
                .map(|k| crate::scalar::lift(k.to_f64()))
                .collect(),
            self.degree,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn validation_catches_each_fault() {
        let ok = KnotVector::<f64>::new(vec![0., 0., 0., 0.5, 1., 1., 1.], 2, 4);
        assert!(ok.is_ok());
        assert!(matches!(
            KnotVector::<f64>::new(vec![0., 0., 0., 1., 1.], 2, 4),
            Err(KnotError::Count { .. })
        ));
        assert!(matches!(
            KnotVector::<f64>::new(vec![0., 0., 0., 0.5, 0.4, 1., 1.], 2, 4),
            Err(KnotError::Unsorted(4))
        ));
        assert!(matches!(
            KnotVector::<f64>::new(vec![0., 0., 0., 0., 1., 1., 1.], 2, 4),
            Err(KnotError::Multiplicity { .. })
        ));
        assert!(matches!(
            KnotVector::<f64>::new(vec![0., 0., 0., f64::NAN, 1., 1., 1.], 2, 4),
            Err(KnotError::NotFinite(3))
        ));
        assert!(matches!(
            KnotVector::<f64>::new(vec![0., 0., 0., 0.5, 0.5, 0.5, 1., 1., 1.], 2, 6),
            Err(KnotError::InteriorMultiplicity { .. })
        ));
        assert!(matches!(
            KnotVector::<f64>::new(vec![1., 1., 1., 1., 1., 1.], 2, 3),
            Err(KnotError::Multiplicity { .. }) | Err(KnotError::EmptyDomain { .. })
        ));
    }

    #[test]
    fn spans() {
        let k = KnotVector::<f64>::new(vec![0., 0., 0., 0.5, 0.5, 1., 1., 1.], 2, 5).unwrap();
        assert_eq!(k.find_span(&0.0), 2);
        assert_eq!(k.find_span(&0.25), 2);
        assert_eq!(k.find_span(&0.5), 4);
        assert_eq!(k.find_span(&1.0), 4);
        assert_eq!(k.interior_breaks(), vec![0.5]);
    }
}
