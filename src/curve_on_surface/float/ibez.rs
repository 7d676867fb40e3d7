//! Interval Bézier tools for the f64 path: every routine is the blossom (de Casteljau /
//! de Boor–Ramshaw recurrence, Ramshaw 1989) evaluated in outward-rounded interval
//! arithmetic ([`Interval`]), so each result *encloses* the exact value for the exact input
//! (f64 input numbers are exact rationals). Exact operations stay points (`0·x`, `1·x`), so
//! clamped end control points come out exact.

use crate::scalar::interval::Interval;
use arrayvec::ArrayVec;

pub type I = Interval;
/// A point with interval coordinates.
pub type IP<const D: usize> = [I; D];

/// Largest degree handled without allocation.
pub const MAX_DEGREE: usize = 31;

pub fn ip<const D: usize>(p: &[f64; D]) -> IP<D> {
    std::array::from_fn(|i| I::point(p[i]))
}

/// `(1 - t) a + t b`, enclosed.
#[inline]
pub fn lerp<const D: usize>(a: &IP<D>, b: &IP<D>, t: I) -> IP<D> {
    let s = I::point(1.0) - t;
    std::array::from_fn(|i| s * a[i] + t * b[i])
}

/// Blossom `b(t_1, …, t_n)` of the Bézier curve with control points `ctrl` (degree
/// `n = ctrl.len() - 1 = ts.len()`).
pub fn blossom<const D: usize>(ctrl: &[IP<D>], ts: &[I]) -> IP<D> {
    let mut w: ArrayVec<IP<D>, 32> = ctrl.iter().copied().collect();
    let n = ctrl.len() - 1;
    debug_assert_eq!(ts.len(), n);
    for (r, t) in ts.iter().enumerate() {
        for i in 0..n - r {
            w[i] = lerp(&w[i], &w[i + 1], *t);
        }
    }
    w[0]
}

/// Polar values `b(x^(n-j), y^j)`, `j = 0..=n`: the control points of the curve restricted
/// to `[x, y]` (reparametrized to `[0, 1]`).
pub fn polar_values<const D: usize>(ctrl: &[IP<D>], x: I, y: I) -> ArrayVec<IP<D>, 32> {
    let n = ctrl.len() - 1;
    let mut ts: ArrayVec<I, 32> = ArrayVec::new();
    (0..=n)
        .map(|j| {
            ts.clear();
            ts.extend(std::iter::repeat_n(x, n - j));
            ts.extend(std::iter::repeat_n(y, j));
            blossom(ctrl, &ts)
        })
        .collect()
}

/// Enclosure of `C(t)` (for an interval `t`, of `{C(t) : t ∈ t}` by inclusion isotonicity).
pub fn eval<const D: usize>(ctrl: &[IP<D>], t: I) -> IP<D> {
    let n = ctrl.len() - 1;
    let ts: ArrayVec<I, 32> = std::iter::repeat_n(t, n).collect();
    blossom(ctrl, &ts)
}

/// De Casteljau halves at `t = 1/2`.
pub fn halves<const D: usize>(ctrl: &[IP<D>]) -> (Vec<IP<D>>, Vec<IP<D>>) {
    split_at(ctrl, 0.5)
}

/// De Casteljau split at the point parameter `t`: control points of `[0, t]` and `[t, 1]`.
pub fn split_at<const D: usize>(ctrl: &[IP<D>], t: f64) -> (Vec<IP<D>>, Vec<IP<D>>) {
    let n = ctrl.len() - 1;
    let t = I::point(t);
    let mut w: Vec<IP<D>> = ctrl.to_vec();
    let mut left = Vec::with_capacity(n + 1);
    let mut right = vec![w[n]; n + 1];
    left.push(w[0]);
    for r in 1..=n {
        for i in 0..=n - r {
            w[i] = lerp(&w[i], &w[i + 1], t);
        }
        left.push(w[0]);
        right[n - r] = w[n - r];
    }
    (left, right)
}

/// Blossom of a B-spline curve of degree `p` (knots `knots`, control points `ctrl`) on span
/// `s` (`knots[s] < knots[s + 1]`), at arguments `xs` (de Boor–Ramshaw recurrence).
/// `None` when a knot difference is not certified positive (invalid knot vector).
pub fn bspline_blossom<const D: usize>(
    knots: &[f64],
    p: usize,
    ctrl: &[IP<D>],
    s: usize,
    xs: &[I],
) -> Option<IP<D>> {
    let mut d: ArrayVec<IP<D>, 32> = (s - p..=s).map(|j| ctrl[j]).collect();
    for (r, x) in (1..=p).zip(xs) {
        for j in (s - p + r..=s).rev() {
            let (uj, ue) = (knots[j], knots[j + p + 1 - r]);
            let alpha = (*x - I::point(uj)).checked_div(I::point(ue) - I::point(uj))?;
            let k = j - (s - p);
            d[k] = lerp(&d[k - 1], &d[k], alpha);
        }
    }
    Some(d[p])
}

/// The Bézier control points of span `s` of a B-spline curve: blossoms at
/// `(u_s^(p-k), u_{s+1}^k)`.
pub fn bspline_span_bezier<const D: usize>(
    knots: &[f64],
    p: usize,
    ctrl: &[IP<D>],
    s: usize,
) -> Option<Vec<IP<D>>> {
    let (a, b) = (I::point(knots[s]), I::point(knots[s + 1]));
    let mut xs: ArrayVec<I, 32> = ArrayVec::new();
    (0..=p)
        .map(|k| {
            xs.clear();
            xs.extend(std::iter::repeat_n(a, p - k));
            xs.extend(std::iter::repeat_n(b, k));
            bspline_blossom(knots, p, ctrl, s, &xs)
        })
        .collect()
}

/// A tensor-product Bézier patch with interval control points, `net[i * (q + 1) + j]`
/// (`i` along u).
#[derive(Clone, Debug)]
pub struct IPatch {
    pub p: usize,
    pub q: usize,
    pub net: Vec<IP<3>>,
}

impl IPatch {
    pub fn at(&self, i: usize, j: usize) -> &IP<3> {
        &self.net[i * (self.q + 1) + j]
    }

    /// `∂/∂s` in local coordinates: degree `(p - 1, q)`, control points `p (P_{i+1,j} - P_{i,j})`.
    pub fn hodograph_u(&self) -> Option<IPatch> {
        if self.p == 0 {
            return None;
        }
        let m = I::point(self.p as f64);
        let mut net = Vec::with_capacity(self.p * (self.q + 1));
        for i in 0..self.p {
            for j in 0..=self.q {
                let (a, b) = (self.at(i, j), self.at(i + 1, j));
                net.push(std::array::from_fn(|c| m * (b[c] - a[c])));
            }
        }
        Some(IPatch {
            p: self.p - 1,
            q: self.q,
            net,
        })
    }

    /// `∂/∂r` in local coordinates: degree `(p, q - 1)`.
    pub fn hodograph_v(&self) -> Option<IPatch> {
        if self.q == 0 {
            return None;
        }
        let n = I::point(self.q as f64);
        let mut net = Vec::with_capacity((self.p + 1) * self.q);
        for i in 0..=self.p {
            for j in 0..self.q {
                let (a, b) = (self.at(i, j), self.at(i, j + 1));
                net.push(std::array::from_fn(|c| n * (b[c] - a[c])));
            }
        }
        Some(IPatch {
            p: self.p,
            q: self.q - 1,
            net,
        })
    }

    /// Polar values `f(x_u^(p-i) y_u^i ; x_v^(q-j) y_v^j)` for all `i, j`, row-major: the
    /// patch restricted to `[x_u, y_u] × [x_v, y_v]` (tensor-product blossom, rows first).
    pub fn polar_net(&self, xu: I, yu: I, xv: I, yv: I) -> Vec<IP<3>> {
        let (p, q) = (self.p, self.q);
        let rows: Vec<ArrayVec<IP<3>, 32>> = (0..=p)
            .map(|i| polar_values(&self.net[i * (q + 1)..(i + 1) * (q + 1)], xv, yv))
            .collect();
        let mut out = vec![[I::point(0.0); 3]; (p + 1) * (q + 1)];
        let mut col: ArrayVec<IP<3>, 32> = ArrayVec::new();
        for j in 0..=q {
            col.clear();
            col.extend(rows.iter().map(|r| r[j]));
            for (i, v) in polar_values(&col, xu, yu).into_iter().enumerate() {
                out[i * (q + 1) + j] = v;
            }
        }
        out
    }

    /// Enclosure of the image `S(a + t (b - a))` of a local segment: the Bézier curve of
    /// degree `p + q` from the blossom (the interval counterpart of
    /// `spline::compose::compose_line`).
    pub fn compose_line(&self, a: &IP<2>, b: &IP<2>) -> Vec<IP<3>> {
        let (p, q) = (self.p, self.q);
        let h = self.polar_net(a[0], b[0], a[1], b[1]);
        let binom = |n: usize, k: usize| crate::scalar::binomial_i64(n, k) as f64;
        (0..=p + q)
            .map(|k| {
                let den = I::point(binom(p + q, k));
                let mut acc = [I::point(0.0); 3];
                for i in k.saturating_sub(q)..=k.min(p) {
                    let j = k - i;
                    let w = I::point(binom(p, i) * binom(q, j))
                        .checked_div(den)
                        .expect("binomial coefficients are positive");
                    let v = &h[i * (q + 1) + j];
                    for c in 0..3 {
                        acc[c] = acc[c] + w * v[c];
                    }
                }
                acc
            })
            .collect()
    }
}

/// Upper bound of the Euclidean norm of every point of the box `x`.
pub fn norm_hi<const D: usize>(x: &IP<D>) -> f64 {
    let mut s = I::point(0.0);
    for c in x {
        s = s + c.sqr();
    }
    s.hi.sqrt().next_up()
}

/// Upper bound of the distance from every point of the box `x` to the point `y`.
pub fn dist_hi<const D: usize>(x: &IP<D>, y: &[f64; D]) -> f64 {
    let d: IP<D> = std::array::from_fn(|i| x[i] - I::point(y[i]));
    norm_hi(&d)
}

/// Upper bound of the distance from every point of the box `x` to the segment `[a, b]`:
/// the distance to one chosen point of the segment (the projection of the box's centre,
/// computed in f64 — any point of the segment gives an upper bound), enclosed.
pub fn dist_to_segment_hi(x: &IP<2>, a: &[f64; 2], b: &[f64; 2]) -> f64 {
    let c = [x[0].mid(), x[1].mid()];
    let ab = [b[0] - a[0], b[1] - a[1]];
    let l2 = ab[0] * ab[0] + ab[1] * ab[1];
    let t = if l2 > 0.0 {
        (((c[0] - a[0]) * ab[0] + (c[1] - a[1]) * ab[1]) / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    // The chosen segment point a + t (b - a), enclosed.
    let ti = I::point(t);
    let y: IP<2> = lerp(&ip(a), &ip(b), ti);
    let d: IP<2> = std::array::from_fn(|i| x[i] - y[i]);
    norm_hi(&d)
}

/// Midpoints (the f64 representative) of a box.
pub fn mid<const D: usize>(x: &IP<D>) -> [f64; D] {
    std::array::from_fn(|i| x[i].mid())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spline::{BSplineCurve, BezierSurface, KnotVector};
    use num_rational::BigRational;

    fn q(x: f64) -> BigRational {
        crate::scalar::lift(x)
    }
    fn contains(x: &I, e: &BigRational) -> bool {
        q(x.lo) <= *e && *e <= q(x.hi)
    }

    #[test]
    fn span_extraction_encloses_exact_bezier_pieces() {
        let knots = vec![0.0, 0.0, 0.0, 0.0, 0.3, 0.35, 0.35, 0.9, 1.0, 1.0, 1.0, 1.0];
        let ctrl: Vec<[f64; 2]> = (0..8)
            .map(|i| [i as f64 * 0.37 - 1.0, ((i * 7) % 5) as f64 * 0.11])
            .collect();
        let c = BSplineCurve::new(knots.clone(), 3, ctrl.clone()).unwrap();
        let cq: BSplineCurve<[BigRational; 2]> = c.map(|k| q(*k), crate::geom::lift_point);
        let exact = cq.bezier_pieces();
        let kv = KnotVector::new(knots.clone(), 3, 8).unwrap();
        let ictrl: Vec<IP<2>> = ctrl.iter().map(ip).collect();
        let spans: Vec<usize> = kv
            .breakpoints()
            .windows(2)
            .map(|w| kv.find_span(&w[0]))
            .collect();
        assert_eq!(spans.len(), exact.len());
        for (s, e) in spans.iter().zip(&exact) {
            let bz = bspline_span_bezier(&knots, 3, &ictrl, *s).unwrap();
            for (b, x) in bz.iter().zip(&e.curve.control) {
                assert!(contains(&b[0], &x[0]) && contains(&b[1], &x[1]));
                assert!(b[0].hi - b[0].lo < 1e-14);
            }
        }
        // Clamped end points come out exact.
        let first = bspline_span_bezier(&knots, 3, &ictrl, spans[0]).unwrap()[0];
        assert_eq!(first, ip(&ctrl[0]));
    }

    #[test]
    fn compose_line_encloses_the_exact_composition() {
        let net: Vec<[f64; 3]> = (0..12)
            .map(|k| {
                [
                    k as f64 * 0.3,
                    ((k * 5) % 7) as f64 * 0.2,
                    ((k * 3) % 4) as f64,
                ]
            })
            .collect();
        let s = BezierSurface::new(3, 2, net.clone()).unwrap();
        let sq = s.map(crate::geom::lift_point::<BigRational, 3>);
        let (a, b) = ([0.1, 0.7], [0.9, 0.2]);
        let exact = crate::spline::compose::compose_line(
            &sq,
            &crate::geom::lift_point(&a),
            &crate::geom::lift_point(&b),
        );
        let ipatch = IPatch {
            p: 3,
            q: 2,
            net: net.iter().map(ip).collect(),
        };
        let enc = ipatch.compose_line(&ip(&a), &ip(&b));
        for (x, e) in enc.iter().zip(&exact.control) {
            for c in 0..3 {
                assert!(contains(&x[c], &e[c]), "{x:?}");
                assert!(x[c].hi - x[c].lo < 1e-13);
            }
        }
    }

    #[test]
    fn interval_evaluation_encloses_the_range() {
        let ctrl: Vec<IP<2>> = [[0.0, 0.0], [1.0, 2.0], [2.0, -1.0], [3.0, 0.5]]
            .iter()
            .map(ip)
            .collect();
        let box_ = eval(&ctrl, I::new(0.25, 0.5));
        for k in 0..=100 {
            let t = 0.25 + 0.25 * k as f64 / 100.0;
            let p = eval(&ctrl, I::point(t));
            for c in 0..2 {
                assert!(box_[c].lo <= p[c].lo && p[c].hi <= box_[c].hi);
            }
        }
    }
}
