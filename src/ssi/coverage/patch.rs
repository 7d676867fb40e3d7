//! Bézier pieces with *enclosed* control points: every coordinate and weight is an
//! outward-rounded [`Interval`] holding the exact value, so a piece obtained by halving stands
//! for the exact sub-patch (or sub-curve) of the exact surface, and its control-point box
//! encloses that exact piece (convex hull property, positive weights).

use crate::scalar::Interval;

pub type V = [Interval; 3];

fn iv0() -> Interval {
    Interval::point(0.0)
}

/// Cross product of enclosed vectors.
pub fn cross(a: &V, b: &V) -> V {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// The hull of enclosures, each of them finite (`Interval::hull` passes a NaN end over);
/// `None` for none or a non-finite one. A Bézier function takes its values in the hull of its
/// coefficients, so this encloses its range.
pub fn hull_finite(mut xs: impl Iterator<Item = Interval>) -> Option<Interval> {
    let mut h = xs.next().filter(Interval::is_finite)?;
    for x in xs {
        if !x.is_finite() {
            return None;
        }
        h = h.hull(x);
    }
    Some(h)
}

/// [`hull_finite`] per coordinate of vector coefficients.
pub fn hull_finite_v(xs: &[V]) -> Option<V> {
    Some([
        hull_finite(xs.iter().map(|x| x[0]))?,
        hull_finite(xs.iter().map(|x| x[1]))?,
        hull_finite(xs.iter().map(|x| x[2]))?,
    ])
}

/// The range of `w X′ − w′ X` (∝ the derivative of the rational piece `X / w`, by the
/// positive factor `1 / w²`) over the piece with homogeneous net `(x, w)` and hodograph
/// `(dx, dw)`: each factor enclosed by the hull of its coefficients. Also returns the hull
/// of `w` (for the quotient).
pub fn derivative_numerator(
    x: &[V],
    w: &[Interval],
    dx: &[V],
    dw: &[Interval],
) -> Option<(V, Interval)> {
    let (xr, wr) = (hull_finite_v(x)?, hull_finite(w.iter().copied())?);
    let (dxr, dwr) = (hull_finite_v(dx)?, hull_finite(dw.iter().copied())?);
    let n: V = std::array::from_fn(|k| wr * dxr[k] - dwr * xr[k]);
    n.iter().all(Interval::is_finite).then_some((n, wr))
}

/// Axis-aligned box `[lo, hi]` in model space.
pub type Box3 = ([f64; 3], [f64; 3]);

/// The box of the Cartesian control points `x/w` of homogeneous interval control points, or
/// `None` when a weight interval is not strictly positive or anything is not finite (no
/// convex-hull claim is then possible).
pub fn hull_box(x: &[V], w: &[Interval]) -> Option<Box3> {
    cartesian(x, w).map(|p| box_of(&p))
}

/// The Cartesian control points `x/w`, enclosed, or `None` when a weight interval is not
/// strictly positive or anything is not finite.
pub fn cartesian(x: &[V], w: &[Interval]) -> Option<Vec<V>> {
    let mut out = Vec::with_capacity(x.len());
    for (p, wi) in x.iter().zip(w) {
        if wi.lo.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) || !wi.is_finite() {
            return None;
        }
        let mut c = [Interval::point(0.0); 3];
        // Weight exactly 1 (polynomial pieces stay so under halving): the point itself.
        let unit = wi.lo == 1.0 && wi.hi == 1.0;
        for k in 0..3 {
            if !(p[k].is_finite() && p[k].lo <= p[k].hi) {
                return None;
            }
            c[k] = if unit { p[k] } else { p[k].checked_div(*wi)? };
            if !(c[k].is_finite() && c[k].lo <= c[k].hi) {
                return None;
            }
        }
        out.push(c);
    }
    Some(out)
}

/// The box of enclosed points.
pub fn box_of(pts: &[V]) -> Box3 {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in pts {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k].lo);
            hi[k] = hi[k].max(p[k].hi);
        }
    }
    (lo, hi)
}

/// Whether the convex hulls of two sets of enclosed points are proven disjoint along
/// direction `n` (any direction: the projections of the hulls are the hulls of the
/// projections).
pub fn separated_along(a: &[V], b: &[V], n: &[f64; 3]) -> bool {
    match (range_along(a, n), range_along(b, n)) {
        (Some(ra), Some(rb)) => apart(ra, rb),
        _ => false,
    }
}

/// Enclosure of the projections of the points onto `n` (`None` for a direction that is zero
/// or not finite: no separation is claimed along it).
pub fn range_along(pts: &[V], n: &[f64; 3]) -> Option<(f64, f64)> {
    if !n.iter().all(|x| x.is_finite()) || n.iter().all(|x| *x == 0.0) {
        return None;
    }
    let nn = n.map(Interval::point);
    Some(
        pts.iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
                let t = p[0] * nn[0] + p[1] * nn[1] + p[2] * nn[2];
                (lo.min(t.lo), hi.max(t.hi))
            }),
    )
}

/// Whether two enclosed ranges are disjoint (a strict gap).
pub fn apart(a: (f64, f64), b: (f64, f64)) -> bool {
    a.1 < b.0 || b.1 < a.0
}

/// Whether two boxes are disjoint (a strict gap on some axis).
pub fn disjoint(a: &Box3, b: &Box3) -> bool {
    (0..3).any(|k| a.1[k] < b.0[k] || b.1[k] < a.0[k])
}

/// The common part of two overlapping boxes.
pub fn meet(a: &Box3, b: &Box3) -> Box3 {
    (
        std::array::from_fn(|k| a.0[k].max(b.0[k])),
        std::array::from_fn(|k| a.1[k].min(b.1[k])),
    )
}

/// Length of the box diagonal (rounded; used only to choose what to split).
pub(crate) fn diagonal(b: &Box3) -> f64 {
    (0..3)
        .map(|k| (b.1[k] - b.0[k]).powi(2))
        .sum::<f64>()
        .sqrt()
}

/// One de Casteljau halving at `t = 1/2` of a row of homogeneous interval points; returns
/// the control points of the left and right halves. Multiplication by 1/2 is exact, so each
/// step adds only the rounding of one sum.
/// Homogeneous control points of a curve: coordinates and weights.
type Row = (Vec<V>, Vec<Interval>);

fn halve_row(xs: &[V], ws: &[Interval]) -> (Row, Row) {
    let n = xs.len() - 1;
    let half = Interval::point(0.5);
    let mut x = xs.to_vec();
    let mut w = ws.to_vec();
    let (mut lx, mut lw) = (vec![x[0]; n + 1], vec![w[0]; n + 1]);
    let (mut rx, mut rw) = (vec![x[n]; n + 1], vec![w[n]; n + 1]);
    for level in 1..=n {
        for k in 0..=n - level {
            x[k] = std::array::from_fn(|c| (x[k][c] + x[k + 1][c]) * half);
            w[k] = (w[k] + w[k + 1]) * half;
        }
        lx[level] = x[0];
        lw[level] = w[0];
        rx[n - level] = x[n - level];
        rw[n - level] = w[n - level];
    }
    ((lx, lw), (rx, rw))
}

/// A Bézier curve with interval homogeneous control points.
#[derive(Clone, Debug)]
pub struct ICurve {
    pub x: Vec<V>,
    pub w: Vec<Interval>,
}

impl ICurve {
    pub fn halve(&self) -> (ICurve, ICurve) {
        let ((lx, lw), (rx, rw)) = halve_row(&self.x, &self.w);
        (ICurve { x: lx, w: lw }, ICurve { x: rx, w: rw })
    }
    pub fn cartesian(&self) -> Option<Vec<V>> {
        cartesian(&self.x, &self.w)
    }
    /// Hodograph (degree one less), homogeneous `(X', w')`; `None` at degree 0.
    pub fn hodograph(&self) -> Option<ICurve> {
        let n = self.x.len().checked_sub(1).filter(|&n| n > 0)?;
        let deg = Interval::point(n as f64);
        Some(ICurve {
            x: (0..n)
                .map(|k| std::array::from_fn(|c| (self.x[k + 1][c] - self.x[k][c]) * deg))
                .collect(),
            w: (0..n).map(|k| (self.w[k + 1] - self.w[k]) * deg).collect(),
        })
    }
}

/// Which border of a patch's parameter rectangle.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Side {
    U0,
    U1,
    V0,
    V1,
}

pub(crate) const SIDES: [Side; 4] = [Side::U0, Side::U1, Side::V0, Side::V1];

/// A tensor-product Bézier patch with interval homogeneous control points, row-major
/// (`i` along u, degree `p`; `j` along v, degree `q`).
#[derive(Clone, Debug)]
pub struct IPatch {
    pub p: usize,
    pub q: usize,
    pub x: Vec<V>,
    pub w: Vec<Interval>,
}

impl IPatch {
    pub fn at(&self, i: usize, j: usize) -> usize {
        i * (self.q + 1) + j
    }
    pub fn cartesian(&self) -> Option<Vec<V>> {
        cartesian(&self.x, &self.w)
    }
    /// A rough unit normal from the corner control points (midpoints; chooses a separating
    /// direction, proves nothing by itself). Zero when degenerate.
    pub fn rough_normal(&self) -> [f64; 3] {
        let pt = |k: usize| -> [f64; 3] {
            let w = self.w[k].mid();
            std::array::from_fn(|c| self.x[k][c].mid() / w)
        };
        let (a, b, c, d) = (
            pt(self.at(0, 0)),
            pt(self.at(self.p, 0)),
            pt(self.at(0, self.q)),
            pt(self.at(self.p, self.q)),
        );
        let e: [f64; 3] = std::array::from_fn(|k| d[k] - a[k]);
        let f: [f64; 3] = std::array::from_fn(|k| c[k] - b[k]);
        let n = [
            e[1] * f[2] - e[2] * f[1],
            e[2] * f[0] - e[0] * f[2],
            e[0] * f[1] - e[1] * f[0],
        ];
        let l = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        if l > 0.0 && l.is_finite() {
            n.map(|x| x / l)
        } else {
            [0.0; 3]
        }
    }
    /// de Casteljau at 1/2 along u (`along_u`) or v; the two halves.
    pub fn halve(&self, along_u: bool) -> (IPatch, IPatch) {
        let (n, m) = if along_u {
            (self.p, self.q)
        } else {
            (self.q, self.p)
        };
        let mut l = self.clone();
        let mut r = self.clone();
        for line in 0..=m {
            let idx = |k: usize| {
                if along_u {
                    self.at(k, line)
                } else {
                    self.at(line, k)
                }
            };
            let xs: Vec<V> = (0..=n).map(|k| self.x[idx(k)]).collect();
            let ws: Vec<Interval> = (0..=n).map(|k| self.w[idx(k)]).collect();
            let ((lx, lw), (rx, rw)) = halve_row(&xs, &ws);
            for k in 0..=n {
                l.x[idx(k)] = lx[k];
                l.w[idx(k)] = lw[k];
                r.x[idx(k)] = rx[k];
                r.w[idx(k)] = rw[k];
            }
        }
        (l, r)
    }
    /// The four quarters `[u-low v-low, u-low v-high, u-high v-low, u-high v-high]`.
    pub fn quarters(&self) -> [IPatch; 4] {
        let (l, r) = self.halve(true);
        let (a, b) = l.halve(false);
        let (c, d) = r.halve(false);
        [a, b, c, d]
    }
    /// The border curve on `side` (exactly the patch restricted to that border).
    pub fn edge(&self, side: Side) -> ICurve {
        let idx: Vec<usize> = match side {
            Side::U0 => (0..=self.q).map(|j| self.at(0, j)).collect(),
            Side::U1 => (0..=self.q).map(|j| self.at(self.p, j)).collect(),
            Side::V0 => (0..=self.p).map(|i| self.at(i, 0)).collect(),
            Side::V1 => (0..=self.p).map(|i| self.at(i, self.q)).collect(),
        };
        ICurve {
            x: idx.iter().map(|&k| self.x[k]).collect(),
            w: idx.iter().map(|&k| self.w[k]).collect(),
        }
    }
    /// Whether the net is longer along u than along v (by the midpoints of its border rows;
    /// a heuristic that only chooses which way to split).
    pub fn longer_in_u(&self) -> bool {
        let (lu, lv) = self.border_lengths();
        lv.partial_cmp(&lu) != Some(std::cmp::Ordering::Greater)
    }
    /// Squared lengths of the net along u and along v, each the sum over its two border
    /// rows of the squared distance between the row's end points (midpoints of the
    /// enclosures, rounded to nearest: a scheduling figure only).
    pub fn border_lengths(&self) -> (f64, f64) {
        let pt = |k: usize| -> [f64; 3] {
            let w = self.w[k].mid();
            std::array::from_fn(|c| self.x[k][c].mid() / w)
        };
        let d = |a: usize, b: usize| {
            let (x, y) = (pt(a), pt(b));
            (0..3).map(|c| (x[c] - y[c]).powi(2)).sum::<f64>()
        };
        let lu =
            d(self.at(0, 0), self.at(self.p, 0)) + d(self.at(0, self.q), self.at(self.p, self.q));
        let lv =
            d(self.at(0, 0), self.at(0, self.q)) + d(self.at(self.p, 0), self.at(self.p, self.q));
        (lu, lv)
    }
    /// Hodograph in u or v (degree one less), homogeneous `(X', w')`; `None` at degree 0.
    pub fn hodograph(&self, along_u: bool) -> Option<IPatch> {
        let (p, q) = if along_u {
            (self.p.checked_sub(1)?, self.q)
        } else {
            (self.p, self.q.checked_sub(1)?)
        };
        let deg = Interval::point(if along_u { self.p } else { self.q } as f64);
        let mut h = IPatch {
            p,
            q,
            x: Vec::with_capacity((p + 1) * (q + 1)),
            w: Vec::with_capacity((p + 1) * (q + 1)),
        };
        for i in 0..=p {
            for j in 0..=q {
                let (a, b) = if along_u {
                    (self.at(i + 1, j), self.at(i, j))
                } else {
                    (self.at(i, j + 1), self.at(i, j))
                };
                h.x.push(std::array::from_fn(|c| (self.x[a][c] - self.x[b][c]) * deg));
                h.w.push((self.w[a] - self.w[b]) * deg);
            }
        }
        Some(h)
    }
}

/// Zero net of the given size.
pub(crate) fn zero_net(n: usize) -> Vec<V> {
    vec![[iv0(); 3]; n]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pt(x: f64, y: f64, z: f64) -> V {
        [x, y, z].map(Interval::point)
    }

    #[test]
    fn halves_enclose_exact_de_casteljau() {
        // Quadratic row with weights: halving at 1/2 of (0, 1, 3) with weights (1, 2, 1):
        // left = (0, 1, 7/4·...) checked through the homogeneous values, exact in binary.
        let c = ICurve {
            x: vec![pt(0.0, 0.0, 0.0), pt(2.0, 4.0, 0.0), pt(3.0, 0.0, 0.0)],
            w: [1.0, 2.0, 1.0].map(Interval::point).to_vec(),
        };
        let (l, r) = c.halve();
        // Homogeneous midpoint at level 2: ((0+2)/2 + (2+3)/2)/2 = 1.75 in x, weight 1.5.
        assert_eq!(l.x[2][0], Interval::point(1.75));
        assert_eq!(l.w[2], Interval::point(1.5));
        assert_eq!(r.x[0], l.x[2]);
        assert_eq!(l.x[1][1], Interval::point(2.0));
        assert_eq!(r.w[1], Interval::point(1.5));
    }

    #[test]
    fn hull_refuses_non_positive_weights() {
        let x = vec![pt(0.0, 0.0, 0.0), pt(1.0, 0.0, 0.0)];
        assert!(hull_box(&x, &[Interval::point(1.0), Interval::new(-1e-300, 1.0)]).is_none());
        assert!(hull_box(&x, &[Interval::point(1.0), Interval::point(0.0)]).is_none());
        let b = hull_box(&x, &[Interval::point(1.0), Interval::point(2.0)]).unwrap();
        assert_eq!(b, ([0.0, 0.0, 0.0], [0.5, 0.0, 0.0]));
        let nan = vec![pt(f64::NAN, 0.0, 0.0)];
        assert!(hull_box(&nan, &[Interval::point(1.0)]).is_none());
    }
}
