//! *Centred* enclosures of a tensor-product B-spline with interval control points over a
//! parameter box, and its derivative splines with enclosed control points: the tight
//! companion of [`super::enclose`] for mean-value forms.
//!
//! **Why centred.** Interval Cox–de Boor (The NURBS Book A2.2 with an interval parameter)
//! encloses each basis function `N_a(U)` with a width of order `w/h` (box width over span
//! width) that does not shrink with the spread of the control points: `Σ N_a(U) P_a` then has
//! a width of order `|P| w/h` — the distance of the points from the origin, not their spread,
//! and a derivative enclosure of order `|P'| w/h` instead of `|P''| w`. On each span the basis
//! is a partition of unity as a polynomial identity (`Σ_a N_a ≡ 1`, beyond the span too), so
//! `Σ N_a P_a = m + Σ N_a (P_a − m)` for any `m`; with `m` the centre of the span's control
//! points the width is of order `spread · w/h`, which for the derivative splines (control
//! points `p (P_{a+1} − P_a)/(t_{a+p+1} − t_{a+1})`, The NURBS Book eq. 3.8, computed here in
//! interval arithmetic, so they enclose the exact derivative's control points) is of order
//! `|P''| w`: the true variation.
//!
//! A linear map `L` commutes with the sum (`Σ N_a L(P_a) = L(Σ N_a P_a)`); [`INet::enclose_map`]
//! applies it to the control points before centring, so that, e.g., `X − c w` of a rational
//! surface's homogeneous net is enclosed without the dependency of `X` and `w`.
//! A box meeting several spans is cut at the knot lines and the results are joined by the
//! hull; at a knot where the box touches two spans both one-sided values are in the hull (a
//! derivative net may be discontinuous there: its knot vector allows degree 0 and interior
//! multiplicity `degree + 1`, which [`super::KnotVector`] refuses, hence [`Knots`]).

use super::NurbsSurface;
use super::enclose::MAX_ORDER;
use crate::scalar::Interval;

type I = Interval;

/// Most spans a box may meet in one direction.
pub const MAX_PIECES: usize = 8;

/// A knot vector for enclosures: non-decreasing finite knots, degree `p < MAX_ORDER`, any
/// multiplicity up to `p + 1`.
#[derive(Clone, Debug)]
pub struct Knots {
    pub t: Vec<f64>,
    pub p: usize,
}

impl Knots {
    fn n_ctrl(&self) -> usize {
        self.t.len() - self.p - 1
    }

    /// Whether the interval lies in one closed non-empty span (one polynomial piece).
    pub fn single_span(&self, x: I) -> bool {
        let k = self.find_span(x.lo);
        x.lo >= self.t[k] && x.hi <= self.t[k + 1]
    }

    /// The span `k` with `t[k] ≤ x < t[k+1]`, `p ≤ k < n`, clamped to the end spans (The
    /// NURBS Book A2.1).
    fn find_span(&self, x: f64) -> usize {
        let (n, p, t) = (self.n_ctrl(), self.p, &self.t);
        if x >= t[n] {
            let mut k = n - 1;
            while k > p && t[k] == t[k + 1] {
                k -= 1;
            }
            return k;
        }
        if x <= t[p] {
            let mut k = p;
            while k + 1 < n && t[k + 1] == t[p] {
                k += 1;
            }
            return k;
        }
        let (mut lo, mut hi) = (p, n);
        while hi - lo > 1 {
            let mid = (lo + hi) / 2;
            if x < t[mid] {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        lo
    }

    /// The non-empty spans an interval meets, each with the part it covers (the outermost
    /// spans extended: polynomial extension beyond the domain); `None` beyond
    /// [`MAX_PIECES`].
    fn pieces(&self, x: I) -> Option<arrayvec::ArrayVec<(usize, I), MAX_PIECES>> {
        let t = &self.t;
        let (s0, s1) = (self.find_span(x.lo), self.find_span(x.hi));
        let mut out = arrayvec::ArrayVec::new();
        if s0 == s1 {
            out.push((s0, x));
            return Some(out);
        }
        let (first, last) = (self.find_span(t[self.p]), self.find_span(t[self.n_ctrl()]));
        for s in s0..=s1 {
            if t[s] >= t[s + 1] {
                continue;
            }
            let lo = if s == first { x.lo } else { x.lo.max(t[s]) };
            let hi = if s == last { x.hi } else { x.hi.min(t[s + 1]) };
            if lo <= hi {
                out.try_push((s, I::new(lo, hi))).ok()?;
            }
        }
        Some(out)
    }

    /// The basis functions `N_{span-p..=span}` of span `span` over `x` (Cox–de Boor, The
    /// NURBS Book A2.2, in interval arithmetic).
    fn basis(&self, span: usize, x: I) -> Option<[I; MAX_ORDER]> {
        let (p, t) = (self.p, &self.t);
        let zero = I::point(0.0);
        let mut n = [zero; MAX_ORDER];
        if p >= MAX_ORDER {
            return None;
        }
        let (mut left, mut right) = ([zero; MAX_ORDER], [zero; MAX_ORDER]);
        n[0] = I::point(1.0);
        for j in 1..=p {
            left[j] = x - I::point(t[span + 1 - j]);
            right[j] = I::point(t[span + j]) - x;
            let mut saved = zero;
            for r in 0..j {
                let den = I::point(t[span + r + 1]) - I::point(t[span + 1 + r - j]);
                let temp = n[r].checked_div(den)?;
                n[r] = saved + right[r + 1] * temp;
                saved = left[j - r] * temp;
            }
            n[j] = saved;
        }
        Some(n)
    }
}

/// A tensor-product B-spline with exact `f64` knots and enclosed control points (row-major,
/// `i` along u).
#[derive(Clone, Debug)]
pub struct INet<const D: usize> {
    pub ku: Knots,
    pub kv: Knots,
    pub ctrl: Vec<[I; D]>,
}

fn knots(k: &super::KnotVector<f64>) -> Knots {
    Knots {
        t: k.knots().to_vec(),
        p: k.degree(),
    }
}

impl INet<4> {
    /// The homogeneous net `(w x, w y, w z, w)` of a NURBS surface, exactly.
    pub fn homogeneous(s: &NurbsSurface<f64, 3>) -> INet<4> {
        let h = &s.hom;
        INet {
            ku: knots(&h.ku),
            kv: knots(&h.kv),
            ctrl: h
                .net
                .iter()
                .map(|c| [c.wp[0], c.wp[1], c.wp[2], c.w].map(I::point))
                .collect(),
        }
    }
}

impl<const D: usize> INet<D> {
    /// The net of a polynomial surface's first `D` coordinates (`None` when a weight is not
    /// 1, i.e. the surface is rational).
    pub fn polynomial(s: &NurbsSurface<f64, 3>) -> Option<INet<D>> {
        let h = &s.hom;
        if D > 3 || h.net.iter().any(|c| c.w != 1.0) {
            return None;
        }
        Some(INet {
            ku: knots(&h.ku),
            kv: knots(&h.kv),
            ctrl: h
                .net
                .iter()
                .map(|c| std::array::from_fn(|k| I::point(c.wp[k])))
                .collect(),
        })
    }

    fn nv(&self) -> usize {
        self.kv.n_ctrl()
    }

    /// The derivative spline in u (`du = true`) or v (degree one less, knots without the
    /// first and last), control points enclosed. In a direction of degree 0 the derivative
    /// is zero on every span (the one-sided derivatives of the pieces): the same net with
    /// zero control points.
    pub fn derivative(&self, du: bool) -> Option<INet<D>> {
        let k = if du { &self.ku } else { &self.kv };
        let p = k.p;
        if p == 0 {
            return Some(INet {
                ku: self.ku.clone(),
                kv: self.kv.clone(),
                ctrl: vec![[I::point(0.0); D]; self.ctrl.len()],
            });
        }
        if k.n_ctrl() < 2 {
            return None;
        }
        let t = &k.t;
        let dk = Knots {
            t: t[1..t.len() - 1].to_vec(),
            p: p - 1,
        };
        let (nu, nv) = (self.ku.n_ctrl(), self.nv());
        let (mu, mv) = if du { (nu - 1, nv) } else { (nu, nv - 1) };
        let deg = I::point(p as f64);
        let mut ctrl = Vec::with_capacity(mu * mv);
        for i in 0..mu {
            for j in 0..mv {
                let (a, b, idx) = if du {
                    (self.ctrl[i * nv + j], self.ctrl[(i + 1) * nv + j], i)
                } else {
                    (self.ctrl[i * nv + j], self.ctrl[i * nv + j + 1], j)
                };
                let den = I::point(t[idx + p + 1]) - I::point(t[idx + 1]);
                let q: [I; D] = if den.hi <= 0.0 {
                    // An empty support: that basis function of the derivative is zero.
                    [I::point(0.0); D]
                } else {
                    let mut q = [I::point(0.0); D];
                    for c in 0..D {
                        q[c] = (deg * (b[c] - a[c])).checked_div(den)?;
                    }
                    q
                };
                ctrl.push(q);
            }
        }
        let (ku, kv) = if du {
            (dk, self.kv.clone())
        } else {
            (self.ku.clone(), dk)
        };
        Some(INet { ku, kv, ctrl })
    }

    /// `{Σ N_a(u) N_b(v) L(P_ab) : u ∈ U, v ∈ V}` enclosed, centred per span (module
    /// documentation); `L` must be linear (or affine: the basis sums to 1). `None` when the
    /// box meets too many spans, an input is not finite, or a knot difference is not positive.
    pub fn enclose_map<const E: usize>(
        &self,
        u: I,
        v: I,
        map: impl Fn(&[I; D]) -> [I; E],
    ) -> Option<[I; E]> {
        if !(u.is_finite() && v.is_finite() && u.lo <= u.hi && v.lo <= v.hi) {
            return None;
        }
        let (pu, pv) = (self.ku.pieces(u)?, self.kv.pieces(v)?);
        let (p, q) = (self.ku.p, self.kv.p);
        let nv = self.nv();
        let mut out: Option<[I; E]> = None;
        let mut local: Vec<[I; E]> = Vec::with_capacity((p + 1) * (q + 1));
        for &(su, uu) in &pu {
            let bu = self.ku.basis(su, uu)?;
            for &(sv, vv) in &pv {
                let bv = self.kv.basis(sv, vv)?;
                local.clear();
                for a in 0..=p {
                    for b in 0..=q {
                        local.push(map(&self.ctrl[(su - p + a) * nv + (sv - q + b)]));
                    }
                }
                // The centre of the local control points (any real number works).
                let mut m = [0.0; E];
                for (c, mc) in m.iter_mut().enumerate() {
                    let lo = local.iter().map(|x| x[c].lo).fold(f64::INFINITY, f64::min);
                    let hi = local
                        .iter()
                        .map(|x| x[c].hi)
                        .fold(f64::NEG_INFINITY, f64::max);
                    *mc = if lo.is_finite() && hi.is_finite() {
                        lo * 0.5 + hi * 0.5
                    } else {
                        0.0
                    };
                }
                let mut acc = [I::point(0.0); E];
                for a in 0..=p {
                    let mut row = [I::point(0.0); E];
                    for b in 0..=q {
                        let x = &local[a * (q + 1) + b];
                        for c in 0..E {
                            row[c] = row[c] + bv[b] * (x[c] - I::point(m[c]));
                        }
                    }
                    for c in 0..E {
                        acc[c] = acc[c] + bu[a] * row[c];
                    }
                }
                let val: [I; E] = std::array::from_fn(|c| acc[c] + I::point(m[c]));
                if val.iter().any(|x| !x.is_finite()) {
                    return None;
                }
                out = Some(match out {
                    None => val,
                    Some(o) => std::array::from_fn(|c| o[c].hull(val[c])),
                });
            }
        }
        out
    }

    /// [`INet::enclose_map`] with the identity.
    pub fn enclose(&self, u: I, v: I) -> Option<[I; D]> {
        self.enclose_map(u, v, |x| *x)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spline::construct::{Frame, sphere};

    /// Samples of a rational surface's homogeneous net, its derivative nets and a polynomial
    /// surface lie in the centred box enclosures, which are narrow (of the order of the
    /// variation over the box, not of the coordinates).
    #[test]
    fn centred_enclosures_hold_samples_and_are_narrow() {
        let s = sphere(&Frame::WORLD, 100.0).unwrap();
        let h = INet::homogeneous(&s);
        let (hu, hv) = (h.derivative(true).unwrap(), h.derivative(false).unwrap());
        for (u0, v0, w) in [
            (0.1, 0.3, 1e-3),
            (0.25 - 1e-4, 0.5 - 2e-4, 4e-4),
            (0.6, 0.1, 0.0),
        ] {
            let (u, v) = (I::new(u0, u0 + w), I::new(v0, v0 + w));
            let x = h.enclose(u, v).unwrap();
            let xu = hu.enclose(u, v).unwrap();
            let xv = hv.enclose(u, v).unwrap();
            for a in 0..5 {
                for b in 0..5 {
                    let (uu, vv) = (u0 + w * a as f64 / 4.0, v0 + w * b as f64 / 4.0);
                    let (p, pu, pv) = s.hom.eval_d1(&uu, &vv);
                    let e = 1e-9;
                    let inside = |x: f64, i: I| i.lo - e <= x && x <= i.hi + e;
                    for c in 0..3 {
                        assert!(inside(p.wp[c], x[c]), "{uu} {vv} {c}");
                        assert!(inside(pu.wp[c], xu[c]), "{uu} {vv} {c} {:?}", xu[c]);
                        assert!(inside(pv.wp[c], xv[c]), "{uu} {vv} {c}");
                    }
                    assert!(inside(p.w, x[3]) && inside(pu.w, xu[3]) && inside(pv.w, xv[3]));
                }
            }
            // Narrow: a few times the variation (|S_uu| ~ 100 · 40 on this sphere); the box
            // across the knot lines holds both one-sided derivatives and is not.
            if u0 == 0.25 - 1e-4 {
                continue;
            }
            for c in 0..4 {
                assert!(x[c].hi - x[c].lo <= 1e-10 + 2e3 * w, "{:?}", x[c]);
                assert!(xu[c].hi - xu[c].lo <= 1e-9 + 1e5 * w, "{:?}", xu[c]);
            }
        }
    }
}
