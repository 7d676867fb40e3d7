//! Tensor-product Bézier surfaces: evaluation, blossoms, subdivision, degree elevation and
//! partial hodographs.

use super::bezier_curve::BezierCurve;
use crate::geom::Point;

/// A tensor-product Bézier patch of degrees `(p, q)` over `[0,1]²`. The net is row-major:
/// `net[i * (q + 1) + j] = P_{i,j}`, `i` along u, `j` along v.
#[derive(Clone, Debug, PartialEq)]
pub struct BezierSurface<P: Point> {
    pub p: usize,
    pub q: usize,
    pub net: Vec<P>,
}

impl<P: Point> BezierSurface<P> {
    /// Patch from a net of `(p+1)(q+1)` points; `None` when the size does not match.
    pub fn new(p: usize, q: usize, net: Vec<P>) -> Option<Self> {
        if net.len() != (p + 1) * (q + 1) {
            return None;
        }
        Some(BezierSurface { p, q, net })
    }
    /// `P_{i,j}`.
    pub fn at(&self, i: usize, j: usize) -> &P {
        &self.net[i * (self.q + 1) + j]
    }
    /// Row `i` (fixed u-index) as a curve in v.
    pub fn row(&self, i: usize) -> BezierCurve<P> {
        BezierCurve {
            control: (0..=self.q).map(|j| self.at(i, j).clone()).collect(),
        }
    }
    /// Column `j` (fixed v-index) as a curve in u.
    pub fn column(&self, j: usize) -> BezierCurve<P> {
        BezierCurve {
            control: (0..=self.p).map(|i| self.at(i, j).clone()).collect(),
        }
    }
    fn from_columns(cols: Vec<BezierCurve<P>>) -> Self {
        let q = cols.len() - 1;
        let p = cols[0].degree();
        let mut net = Vec::with_capacity((p + 1) * (q + 1));
        for i in 0..=p {
            for c in &cols {
                net.push(c.control[i].clone());
            }
        }
        BezierSurface { p, q, net }
    }
    fn from_rows(rows: Vec<BezierCurve<P>>) -> Self {
        let p = rows.len() - 1;
        let q = rows[0].degree();
        let net = rows.into_iter().flat_map(|r| r.control).collect();
        BezierSurface { p, q, net }
    }

    /// Tensor-product blossom `f(u_1..u_p; v_1..v_q)`: blossom each row in v, then the
    /// resulting curve in u.
    pub fn blossom(&self, us: &[P::S], vs: &[P::S]) -> P {
        let col = BezierCurve {
            control: (0..=self.p).map(|i| self.row(i).blossom(vs)).collect(),
        };
        col.blossom(us)
    }

    /// Point at `(u, v)`.
    pub fn eval(&self, u: &P::S, v: &P::S) -> P {
        let col = BezierCurve {
            control: (0..=self.p).map(|i| self.row(i).eval(v)).collect(),
        };
        col.eval(u)
    }

    /// Split at `u = t` into two patches over `[0,t]` and `[t,1]` in u.
    pub fn subdivide_u(&self, t: &P::S) -> (Self, Self) {
        let (l, r): (Vec<_>, Vec<_>) = (0..=self.q).map(|j| self.column(j).subdivide(t)).unzip();
        (Self::from_columns(l), Self::from_columns(r))
    }
    /// Split at `v = t`.
    pub fn subdivide_v(&self, t: &P::S) -> (Self, Self) {
        let (l, r): (Vec<_>, Vec<_>) = (0..=self.p).map(|i| self.row(i).subdivide(t)).unzip();
        (Self::from_rows(l), Self::from_rows(r))
    }
    /// Sub-patch over `[u0,u1]×[v0,v1]`, reparametrized to `[0,1]²`.
    pub fn sub_patch(&self, u0: &P::S, u1: &P::S, v0: &P::S, v1: &P::S) -> Self {
        let rows: Vec<_> = (0..=self.p).map(|i| self.row(i).segment(v0, v1)).collect();
        let s = Self::from_rows(rows);
        let cols: Vec<_> = (0..=s.q).map(|j| s.column(j).segment(u0, u1)).collect();
        Self::from_columns(cols)
    }
    /// Elevate the degree in u by one.
    pub fn elevate_u(&self) -> Self {
        Self::from_columns((0..=self.q).map(|j| self.column(j).elevate()).collect())
    }
    /// Elevate the degree in v by one.
    pub fn elevate_v(&self) -> Self {
        Self::from_rows((0..=self.p).map(|i| self.row(i).elevate()).collect())
    }
    /// ∂/∂u patch, degrees `(p-1, q)`; `None` when `p == 0`.
    pub fn hodograph_u(&self) -> Option<Self> {
        let cols: Option<Vec<_>> = (0..=self.q).map(|j| self.column(j).hodograph()).collect();
        Some(Self::from_columns(cols?))
    }
    /// ∂/∂v patch, degrees `(p, q-1)`; `None` when `q == 0`.
    pub fn hodograph_v(&self) -> Option<Self> {
        let rows: Option<Vec<_>> = (0..=self.p).map(|i| self.row(i).hodograph()).collect();
        Some(Self::from_rows(rows?))
    }
    /// Map every control point.
    pub fn map<Q: Point>(&self, f: impl Fn(&P) -> Q) -> BezierSurface<Q> {
        BezierSurface {
            p: self.p,
            q: self.q,
            net: self.net.iter().map(f).collect(),
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
    pub(crate) fn patch() -> BezierSurface<[Q; 3]> {
        let mut net = Vec::new();
        for i in 0..3 {
            for j in 0..4 {
                net.push([
                    q(i as f64),
                    q(j as f64),
                    q(((i * 7 + j * 3) % 5) as f64 - 2.0),
                ]);
            }
        }
        BezierSurface::new(2, 3, net).unwrap()
    }

    #[test]
    fn subdivision_subpatch_elevation_exact() {
        let s = patch();
        let t = q(0.25);
        let (a, b) = s.subdivide_u(&t);
        let (c, _) = s.subdivide_v(&t);
        let sub = s.sub_patch(&q(0.25), &q(0.75), &q(0.5), &q(1.0));
        for i in 0..=4 {
            for j in 0..=4 {
                let (u, v) = (q(i as f64 / 4.0), q(j as f64 / 4.0));
                assert_eq!(a.eval(&u, &v), s.eval(&(t.clone() * u.clone()), &v));
                assert_eq!(
                    b.eval(&u, &v),
                    s.eval(&(t.clone() + (q(1.) - t.clone()) * u.clone()), &v)
                );
                assert_eq!(c.eval(&u, &v), s.eval(&u, &(t.clone() * v.clone())));
                assert_eq!(
                    sub.eval(&u, &v),
                    s.eval(
                        &(q(0.25) + q(0.5) * u.clone()),
                        &(q(0.5) + q(0.5) * v.clone())
                    )
                );
                assert_eq!(s.elevate_u().elevate_v().eval(&u, &v), s.eval(&u, &v));
            }
        }
    }

    #[test]
    fn blossom_diagonal() {
        let s = patch();
        let (u, v) = (q(0.3), q(0.7));
        assert_eq!(
            s.blossom(&[u.clone(), u.clone()], &[v.clone(), v.clone(), v.clone()]),
            s.eval(&u, &v)
        );
        assert!(s.hodograph_u().is_some() && s.hodograph_v().is_some());
    }
}
