//! Tensor-product B-spline surfaces: evaluation, partial derivative surfaces, knot
//! insertion, Bézier patch extraction, sub-patches (The NURBS Book, ch. 3, 5).

use super::basis::{Buf, basis_funs_d1_into, basis_funs_into, ders_basis_funs};
use super::bezier_surface::BezierSurface;
use super::bspline_curve::BSplineCurve;
use super::knots::KnotVector;
use super::{MAX_DEGREE, SplineError};
use crate::geom::Point;
use crate::scalar::Scalar;

/// A B-spline surface. The net is row-major: `net[i * nv + j] = P_{i,j}`, `i` along u
/// (`nu` rows), `j` along v (`nv` columns).
#[derive(Clone, Debug, PartialEq)]
pub struct BSplineSurface<P: Point> {
    pub ku: KnotVector<P::S>,
    pub kv: KnotVector<P::S>,
    pub net: Vec<P>,
}

/// A Bézier patch of a surface with the parameter rectangle it covers.
#[derive(Clone, Debug, PartialEq)]
pub struct BezierPatch<P: Point> {
    pub u0: P::S,
    pub u1: P::S,
    pub v0: P::S,
    pub v1: P::S,
    pub patch: BezierSurface<P>,
}

impl<P: Point> BSplineSurface<P> {
    /// Validate and build from a row-major `nu × nv` net.
    pub fn new(
        knots_u: Vec<P::S>,
        deg_u: usize,
        knots_v: Vec<P::S>,
        deg_v: usize,
        nu: usize,
        nv: usize,
        net: Vec<P>,
    ) -> Result<Self, SplineError> {
        for d in [deg_u, deg_v] {
            if d == 0 || d > MAX_DEGREE {
                return Err(SplineError::Degree(d));
            }
        }
        if net.len() != nu * nv {
            return Err(SplineError::NetSize {
                got: net.len(),
                expected: nu * nv,
                what: "nu * nv",
            });
        }
        let ku = KnotVector::new(knots_u, deg_u, nu)?;
        let kv = KnotVector::new(knots_v, deg_v, nv)?;
        Ok(BSplineSurface { ku, kv, net })
    }
    /// A Bézier patch as a B-spline surface on `[0,1]²`.
    pub fn from_bezier(b: &BezierSurface<P>) -> Result<Self, SplineError> {
        Ok(BSplineSurface {
            ku: KnotVector::bezier(b.p)?,
            kv: KnotVector::bezier(b.q)?,
            net: b.net.clone(),
        })
    }
    pub fn nu(&self) -> usize {
        self.ku.n_ctrl()
    }
    pub fn nv(&self) -> usize {
        self.kv.n_ctrl()
    }
    pub fn degrees(&self) -> (usize, usize) {
        (self.ku.degree(), self.kv.degree())
    }
    /// `P_{i,j}`.
    pub fn at(&self, i: usize, j: usize) -> &P {
        &self.net[i * self.nv() + j]
    }
    /// `(u0, u1, v0, v1)`.
    pub fn domain(&self) -> (P::S, P::S, P::S, P::S) {
        let (a, b) = self.ku.domain();
        let (c, d) = self.kv.domain();
        (a, b, c, d)
    }

    /// Point at `(u, v)` (A3.5): basis functions in each direction, no allocation.
    #[inline]
    pub fn eval(&self, u: &P::S, v: &P::S) -> P {
        let (p, q) = self.degrees();
        let nv = self.nv();
        let su = self.ku.find_span(u);
        let sv = self.kv.find_span(v);
        let (mut nu_, mut nv_) = (Buf::new(), Buf::new());
        basis_funs_into(&self.ku, su, u, &mut nu_);
        basis_funs_into(&self.kv, sv, v, &mut nv_);
        let mut acc = P::origin();
        for (a, na) in nu_.iter().enumerate() {
            let row = (su - p + a) * nv + sv - q;
            let mut tmp = P::origin();
            for (b, nb) in nv_.iter().enumerate() {
                tmp = tmp.add(&self.net[row + b].scale(nb));
            }
            acc = acc.add(&tmp.scale(na));
        }
        acc
    }

    /// Point at `(u, v)`, or an error outside the domain.
    pub fn eval_checked(&self, u: &P::S, v: &P::S) -> Result<P, SplineError> {
        for (t, k) in [(u, &self.ku), (v, &self.kv)] {
            if !k.contains(t) {
                let (a, b) = k.domain();
                return Err(SplineError::OutOfDomain(t.to_f64(), a.to_f64(), b.to_f64()));
            }
        }
        Ok(self.eval(u, v))
    }

    /// `(S, S_u, S_v)` at `(u, v)`, allocation-free (the hot path of SSI refinement and
    /// tangent checks).
    #[inline]
    pub fn eval_d1(&self, u: &P::S, v: &P::S) -> (P, P, P) {
        let (p, q) = self.degrees();
        let nv = self.nv();
        let su = self.ku.find_span(u);
        let sv = self.kv.find_span(v);
        let (mut nu_, mut du_, mut nv_, mut dv_) = (Buf::new(), Buf::new(), Buf::new(), Buf::new());
        basis_funs_d1_into(&self.ku, su, u, &mut nu_, &mut du_);
        basis_funs_d1_into(&self.kv, sv, v, &mut nv_, &mut dv_);
        let (mut s, mut s_u, mut s_v) = (P::origin(), P::origin(), P::origin());
        for a in 0..=p {
            let row = (su - p + a) * nv + sv - q;
            let (mut t0, mut t1) = (P::origin(), P::origin());
            for b in 0..=q {
                let pt = &self.net[row + b];
                t0 = t0.add(&pt.scale(&nv_[b]));
                t1 = t1.add(&pt.scale(&dv_[b]));
            }
            s = s.add(&t0.scale(&nu_[a]));
            s_u = s_u.add(&t0.scale(&du_[a]));
            s_v = s_v.add(&t1.scale(&nu_[a]));
        }
        (s, s_u, s_v)
    }

    /// All partial derivatives `∂^{k+l} S / ∂u^k ∂v^l` for `k + l <= d` (A3.6):
    /// `out[k][l]`.
    pub fn derivatives(&self, u: &P::S, v: &P::S, d: usize) -> Vec<Vec<P>> {
        let (p, q) = self.degrees();
        let nv = self.nv();
        let su = self.ku.find_span(u);
        let sv = self.kv.find_span(v);
        let du = ders_basis_funs(&self.ku, su, u, d);
        let dv = ders_basis_funs(&self.kv, sv, v, d);
        let mut out = vec![vec![P::origin(); d + 1]; d + 1];
        for k in 0..=d {
            for l in 0..=d - k {
                let mut acc = P::origin();
                for a in 0..=p {
                    let mut tmp = P::origin();
                    for b in 0..=q {
                        tmp = tmp.add(&self.net[(su - p + a) * nv + sv - q + b].scale(&dv[l][b]));
                    }
                    acc = acc.add(&tmp.scale(&du[k][a]));
                }
                out[k][l] = acc;
            }
        }
        out
    }

    /// Row `i` as a curve in v.
    pub fn row(&self, i: usize) -> BSplineCurve<P> {
        let nv = self.nv();
        BSplineCurve {
            knots: self.kv.clone(),
            control: self.net[i * nv..(i + 1) * nv].to_vec(),
        }
    }
    /// Column `j` as a curve in u.
    pub fn column(&self, j: usize) -> BSplineCurve<P> {
        BSplineCurve {
            knots: self.ku.clone(),
            control: (0..self.nu()).map(|i| self.at(i, j).clone()).collect(),
        }
    }
    fn from_rows(ku: KnotVector<P::S>, rows: Vec<BSplineCurve<P>>) -> Self {
        let kv = rows[0].knots.clone();
        BSplineSurface {
            ku,
            kv,
            net: rows.into_iter().flat_map(|r| r.control).collect(),
        }
    }
    fn from_columns(kv: KnotVector<P::S>, cols: Vec<BSplineCurve<P>>) -> Self {
        let ku = cols[0].knots.clone();
        let nu = cols[0].control.len();
        let mut net = Vec::with_capacity(nu * cols.len());
        for i in 0..nu {
            for c in &cols {
                net.push(c.control[i].clone());
            }
        }
        BSplineSurface { ku, kv, net }
    }

    /// The same surface with its u-parametrization starting at `t` instead of `u_min`, for a
    /// surface closed in u: the parts over `[t, u_max]` and `[u_min, t]` joined at the old
    /// seam, the second shifted by the period and its control points mapped by `second`
    /// (for homogeneous points of a rational surface whose seam rows differ by a common
    /// weight factor `r = w(u_max) / w(u_min)`: scaled by `r`, the same rational surface), so
    /// the domain is `[t, t + u_max − u_min]` and the seam lies at `t`. The control points at
    /// the old seam are the first part's.
    pub fn reseamed_u(&self, t: &P::S, second: impl Fn(&P) -> P) -> Result<Self, SplineError> {
        let (u0, u1, _, _) = self.domain();
        let p = self.ku.degree();
        let period = u1.clone() - u0.clone();
        let cols: Result<Vec<_>, SplineError> = (0..self.nv())
            .map(|j| {
                let c = self.column(j);
                let a = c.sub_curve(t, &u1)?;
                let b = c.sub_curve(&u0, t)?;
                let ka = a.knots.knots();
                let kb = b.knots.knots();
                let mut knots: Vec<P::S> = ka[..ka.len() - 1].to_vec();
                knots.extend(kb[p + 1..].iter().map(|k| k.clone() + period.clone()));
                let mut control = a.control.clone();
                control.extend(b.control[1..].iter().map(&second));
                BSplineCurve::new(knots, p, control)
            })
            .collect();
        Ok(Self::from_columns(self.kv.clone(), cols?))
    }

    /// Insert the u-knot `t` `r` times (Boehm on every column); shape unchanged.
    pub fn insert_knot_u(&self, t: &P::S, r: usize) -> Self {
        let cols = (0..self.nv())
            .map(|j| self.column(j).insert_knot(t, r))
            .collect();
        Self::from_columns(self.kv.clone(), cols)
    }
    /// Insert the v-knot `t` `r` times (Boehm on every row); shape unchanged.
    pub fn insert_knot_v(&self, t: &P::S, r: usize) -> Self {
        let rows = (0..self.nu())
            .map(|i| self.row(i).insert_knot(t, r))
            .collect();
        Self::from_rows(self.ku.clone(), rows)
    }

    /// ∂S/∂u as a B-spline surface of degrees `(p-1, q)`; `None` when `p < 2`.
    pub fn derivative_u(&self) -> Option<Self> {
        let cols: Option<Vec<_>> = (0..self.nv())
            .map(|j| self.column(j).derivative())
            .collect();
        Some(Self::from_columns(self.kv.clone(), cols?))
    }
    /// ∂S/∂v as a B-spline surface of degrees `(p, q-1)`; `None` when `q < 2`.
    pub fn derivative_v(&self) -> Option<Self> {
        let rows: Option<Vec<_>> = (0..self.nu()).map(|i| self.row(i).derivative()).collect();
        Some(Self::from_rows(self.ku.clone(), rows?))
    }

    /// Split into Bézier patches, one per non-empty knot rectangle, by knot insertion
    /// (each patch keeps the global parameter rectangle it covers).
    pub fn bezier_patches(&self) -> Vec<BezierPatch<P>> {
        let (p, q) = self.degrees();
        // Rows → Bézier pieces in v; then columns of those → pieces in u.
        let mut s = self.clone();
        for b in self.ku.breakpoints() {
            let m = s.ku.multiplicity(&b);
            if m < p {
                s = s.insert_knot_u(&b, p - m);
            }
        }
        for b in self.kv.breakpoints() {
            let m = s.kv.multiplicity(&b);
            if m < q {
                s = s.insert_knot_v(&b, q - m);
            }
        }
        let bu = s.ku.breakpoints();
        let bv = s.kv.breakpoints();
        let mut out = Vec::new();
        for wu in bu.windows(2) {
            let su = s.ku.find_span(&wu[0]);
            for wv in bv.windows(2) {
                let sv = s.kv.find_span(&wv[0]);
                let mut net = Vec::with_capacity((p + 1) * (q + 1));
                for i in su - p..=su {
                    for j in sv - q..=sv {
                        net.push(s.at(i, j).clone());
                    }
                }
                out.push(BezierPatch {
                    u0: wu[0].clone(),
                    u1: wu[1].clone(),
                    v0: wv[0].clone(),
                    v1: wv[1].clone(),
                    patch: BezierSurface { p, q, net },
                });
            }
        }
        out
    }

    /// The part over `[u0,u1]×[v0,v1]` as a clamped B-spline surface.
    pub fn sub_patch(
        &self,
        u0: &P::S,
        u1: &P::S,
        v0: &P::S,
        v1: &P::S,
    ) -> Result<Self, SplineError> {
        let cols: Result<Vec<_>, _> = (0..self.nv())
            .map(|j| self.column(j).sub_curve(u0, u1))
            .collect();
        let s = Self::from_columns(self.kv.clone(), cols?);
        let rows: Result<Vec<_>, _> = (0..s.nu()).map(|i| s.row(i).sub_curve(v0, v1)).collect();
        Ok(Self::from_rows(s.ku.clone(), rows?))
    }

    /// Map control points and knots (e.g. to convert backends).
    pub fn map<Q: Point>(
        &self,
        kmap: impl Fn(&P::S) -> Q::S,
        f: impl Fn(&P) -> Q,
    ) -> BSplineSurface<Q> {
        BSplineSurface {
            ku: KnotVector::new_unchecked(
                self.ku.knots().iter().map(&kmap).collect(),
                self.ku.degree(),
            ),
            kv: KnotVector::new_unchecked(
                self.kv.knots().iter().map(&kmap).collect(),
                self.kv.degree(),
            ),
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
    pub(crate) fn surface() -> BSplineSurface<[Q; 3]> {
        let ku = [0., 0., 0., 0., 0.3, 0.6, 1., 1., 1., 1.];
        let kv = [0., 0., 0., 0.5, 1., 1., 1.];
        let (nu, nv) = (6, 4);
        let net = (0..nu * nv)
            .map(|k| {
                let (i, j) = (k / nv, k % nv);
                [
                    q(i as f64),
                    q(j as f64),
                    q(((i * 3 + j * 5) % 7) as f64 * 0.25),
                ]
            })
            .collect();
        BSplineSurface::new(
            ku.iter().map(|&x| q(x)).collect(),
            3,
            kv.iter().map(|&x| q(x)).collect(),
            2,
            nu,
            nv,
            net,
        )
        .unwrap()
    }

    #[test]
    fn insertion_patches_subpatch_exact() {
        let s = surface();
        let s2 = s.insert_knot_u(&q(0.45), 2).insert_knot_v(&q(0.25), 1);
        let patches = s.bezier_patches();
        assert_eq!(patches.len(), 3 * 2);
        let sub = s.sub_patch(&q(0.1), &q(0.7), &q(0.2), &q(0.9)).unwrap();
        let du = s.derivative_u().unwrap();
        let dv = s.derivative_v().unwrap();
        for i in 0..=10 {
            for j in 0..=10 {
                let (u, v) = (q(i as f64 / 10.0), q(j as f64 / 10.0));
                let p = s.eval(&u, &v);
                assert_eq!(s2.eval(&u, &v), p);
                let bp = patches
                    .iter()
                    .find(|b| b.u0 <= u && u <= b.u1 && b.v0 <= v && v <= b.v1)
                    .unwrap();
                let lu = (u.clone() - bp.u0.clone()) / (bp.u1.clone() - bp.u0.clone());
                let lv = (v.clone() - bp.v0.clone()) / (bp.v1.clone() - bp.v0.clone());
                assert_eq!(bp.patch.eval(&lu, &lv), p);
                if u >= q(0.1) && u <= q(0.7) && v >= q(0.2) && v <= q(0.9) {
                    assert_eq!(sub.eval(&u, &v), p);
                }
                let d = s.derivatives(&u, &v, 2);
                assert_eq!(d[0][0], p);
                assert_eq!(
                    s.eval_d1(&u, &v),
                    (d[0][0].clone(), d[1][0].clone(), d[0][1].clone())
                );
                assert_eq!(d[1][0], du.eval(&u, &v));
                assert_eq!(d[0][1], dv.eval(&u, &v));
                assert_eq!(d[1][1], du.derivative_v().unwrap().eval(&u, &v));
            }
        }
    }
}
