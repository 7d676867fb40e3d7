//! Composition of a planar Bézier curve `C(t) = (u(t), v(t))` of degree `d` with a Bézier
//! surface `S` of degrees `(p, q)`: the space curve `S(C(t))` is a Bézier curve of degree
//! `(p + q) d`, computed exactly (DeRose, Goldman, Hagen & Mann, "Functional composition
//! algorithms via blossoming", ACM TOG 1993; Renner & Weiß 2004 for its use on surfaces).
//!
//! Two routines, both exact in exact arithmetic and checked against each other in tests:
//! * [`compose_line`] — `d = 1` (a chord in the domain, Yang et al. §4): control point `k`
//!   of the degree-`(p+q)` curve is a weighted sum of surface blossom values,
//!   `R_k = Σ_{i+j=k} C(p,i) C(q,j) / C(p+q,k) · f(a_u^{p-i} b_u^i ; a_v^{q-j} b_v^j)`,
//!   which follows from multi-affinity of the blossom `f` and
//!   `B_i^p B_j^q = C(p,i)C(q,j)/C(p+q,i+j) B_{i+j}^{p+q}`;
//! * [`compose`] — any `d`: the same identity applied to the Bernstein polynomials
//!   `B_a^p(u(t)) B_b^q(v(t))`, built by exact Bernstein multiplication (the blossoming
//!   formula of DeRose et al. evaluated in the Bernstein basis).
//!
//! Works for any control-point type, so rational surfaces (homogeneous points) compose to
//! rational curves exactly as well.

use super::bezier_curve::BezierCurve;
use super::bezier_surface::BezierSurface;
use crate::geom::Point;
use crate::scalar::Scalar;

/// A polynomial in Bernstein form of degree `coef.len() - 1` on `[0, 1]`.
#[derive(Clone, Debug, PartialEq)]
pub struct Bernstein<S: Scalar> {
    pub coef: Vec<S>,
}

impl<S: Scalar> Bernstein<S> {
    pub fn degree(&self) -> usize {
        self.coef.len() - 1
    }
    /// The constant 1 of degree 0.
    pub fn one() -> Self {
        Bernstein {
            coef: vec![S::one()],
        }
    }
    /// `1 - self` (Bernstein polynomials form a partition of unity).
    pub fn one_minus(&self) -> Self {
        Bernstein {
            coef: self.coef.iter().map(|c| S::one() - c.clone()).collect(),
        }
    }
    /// Exact product: `c_k = Σ_{i+j=k} C(m,i) C(n,j) / C(m+n,k) f_i g_j`.
    pub fn mul(&self, o: &Self) -> Self {
        let (m, n) = (self.degree(), o.degree());
        let mut c = vec![S::zero(); m + n + 1];
        for (i, fi) in self.coef.iter().enumerate() {
            let bi = S::binomial(m, i);
            for (j, gj) in o.coef.iter().enumerate() {
                let w = bi.clone() * S::binomial(n, j);
                c[i + j] = c[i + j].clone() + w * fi.clone() * gj.clone();
            }
        }
        for (k, ck) in c.iter_mut().enumerate() {
            *ck = ck.clone() / S::binomial(m + n, k);
        }
        Bernstein { coef: c }
    }
    /// Scale by a constant.
    pub fn scale(&self, s: &S) -> Self {
        Bernstein {
            coef: self.coef.iter().map(|c| c.clone() * s.clone()).collect(),
        }
    }
    /// Value at `t` (de Casteljau).
    pub fn eval(&self, t: &S) -> S {
        let mut b = self.coef.clone();
        let n = b.len();
        for level in 1..n {
            for i in 0..n - level {
                b[i] = b[i].clone() + (b[i + 1].clone() - b[i].clone()) * t.clone();
            }
        }
        b.swap_remove(0)
    }
}

/// `B_a^p(x(t))` for `a = 0..=p`, each a Bernstein polynomial of degree `p · deg x`.
fn basis_of<S: Scalar>(x: &Bernstein<S>, p: usize) -> Vec<Bernstein<S>> {
    let om = x.one_minus();
    let mut pow_x = vec![Bernstein::one()];
    let mut pow_om = vec![Bernstein::one()];
    for k in 1..=p {
        pow_x.push(pow_x[k - 1].mul(x));
        pow_om.push(pow_om[k - 1].mul(&om));
    }
    (0..=p)
        .map(|a| pow_x[a].mul(&pow_om[p - a]).scale(&S::binomial(p, a)))
        .collect()
}

/// The exact space curve `S(C(t))`, degree `(p + q) · d`, with `(p+q)d + 1` control points.
pub fn compose<P: Point>(s: &BezierSurface<P>, c: &BezierCurve<[P::S; 2]>) -> BezierCurve<P> {
    let u = Bernstein {
        coef: c.control.iter().map(|pt| pt[0].clone()).collect(),
    };
    let v = Bernstein {
        coef: c.control.iter().map(|pt| pt[1].clone()).collect(),
    };
    let bu = basis_of(&u, s.p);
    let bv = basis_of(&v, s.q);
    let deg = (s.p + s.q) * c.degree();
    let mut out = vec![P::origin(); deg + 1];
    for (a, ba) in bu.iter().enumerate() {
        for (b, bb) in bv.iter().enumerate() {
            let w = ba.mul(bb);
            let pab = s.at(a, b);
            for (k, wk) in w.coef.iter().enumerate() {
                if !wk.is_zero() {
                    out[k] = out[k].add(&pab.scale(wk));
                }
            }
        }
    }
    BezierCurve { control: out }
}

/// Polar values `c[x^(n-j), y^j]`, `j = 0..=n`, of a Bézier curve of degree `n`.
fn polar_values<P: Point>(c: &BezierCurve<P>, x: &P::S, y: &P::S) -> Vec<P> {
    let n = c.degree();
    (0..=n)
        .map(|j| {
            let mut ts = vec![x.clone(); n - j];
            ts.extend(std::iter::repeat_n(y.clone(), j));
            c.blossom(&ts)
        })
        .collect()
}

/// The exact image `S(a + t (b - a))` of a domain segment: degree `p + q`, control points
/// from the surface blossom (Yang et al. §4, "mapping segments onto the surface"). Each
/// polar value `f(a_u^{p-i} b_u^i; a_v^{q-j} b_v^j)` is computed once: polar values of the
/// rows in v, then of the resulting columns in u (the tensor-product blossom factorizes).
pub fn compose_line<P: Point>(
    s: &BezierSurface<P>,
    a: &[P::S; 2],
    b: &[P::S; 2],
) -> BezierCurve<P> {
    let (p, q) = (s.p, s.q);
    let rows: Vec<Vec<P>> = (0..=p)
        .map(|r| polar_values(&s.row(r), &a[1], &b[1]))
        .collect();
    let mut h = vec![vec![P::origin(); q + 1]; p + 1];
    for j in 0..=q {
        let col = BezierCurve {
            control: (0..=p).map(|r| rows[r][j].clone()).collect(),
        };
        for (i, v) in polar_values(&col, &a[0], &b[0]).into_iter().enumerate() {
            h[i][j] = v;
        }
    }
    let mut out = Vec::with_capacity(p + q + 1);
    for k in 0..=p + q {
        let mut acc = P::origin();
        let den = P::S::binomial(p + q, k);
        for i in k.saturating_sub(q)..=k.min(p) {
            let j = k - i;
            let w = P::S::binomial(p, i) * P::S::binomial(q, j) / den.clone();
            acc = acc.add(&h[i][j].scale(&w));
        }
        out.push(acc);
    }
    BezierCurve { control: out }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::Rational;
    type Q = Rational;
    fn q(x: f64) -> Q {
        crate::scalar::lift(x)
    }

    #[test]
    fn line_composition_equals_general_composition() {
        let mut net = Vec::new();
        for i in 0..4 {
            for j in 0..3 {
                net.push([
                    q(i as f64),
                    q(j as f64 * 1.5),
                    q(((i * 5 + j * 2) % 3) as f64),
                ]);
            }
        }
        let s = BezierSurface::new(3, 2, net).unwrap();
        let (a, b) = ([q(0.125), q(0.75)], [q(0.875), q(0.25)]);
        let line = BezierCurve::new(vec![a.clone(), b.clone()]).unwrap();
        let g = compose(&s, &line);
        let l = compose_line(&s, &a, &b);
        assert_eq!(g, l);
        for i in 0..=10 {
            let t = q(i as f64 / 10.0);
            let uv = line.eval(&t);
            assert_eq!(l.eval(&t), s.eval(&uv[0], &uv[1]));
        }
    }
}
