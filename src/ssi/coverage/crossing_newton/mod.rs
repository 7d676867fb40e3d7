//! Krawczyk's enclosure of the border crossings of one curve piece with one surface piece.
//!
//! The border search ([`super::crossings`]) halves a border curve `C` of one surface and a
//! piece `S` of the other until every part is empty or within the match distance of the
//! output; a transversal crossing then costs about two boxes per halving, down to parts the
//! size of the match distance. This test encloses every crossing of the current parts at
//! once, so the search can stop while the parts are still large.
//!
//! **The enclosure.** Let `C(t) = X(t) / w(t)`, `t ∈ [0, 1]`, and `S(u, v) = Y(u, v) /
//! ω(u, v)` be rational Bézier pieces whose homogeneous control points lie in the given
//! interval boxes, with weights enclosed positive, and `F(t, u, v) = C(t) − S(u, v)` on
//! `X = [0, 1]³`, centre `y = (½, ½, ½)`. `F` is smooth on `X`. Let `J` be an interval matrix
//! holding `F′(ξ)` for every `ξ ∈ X`: `C′ = (X′ w − X w′) / w²` and the partial derivatives
//! of `S` alike, each factor enclosed by the hull of its control points (convex hull
//! property: a Bézier function takes its values in the hull of its coefficients; the
//! derivative's coefficients are the hodograph's). For any real matrix `Λ` and any zero
//! `x* ∈ X` of `F`, the mean-value theorem applied to each component gives
//! `F(x*) − F(y) = M (x* − y)` with the rows of `M` in those of `J` (their points lie on the
//! segment `[y, x*] ⊂ X`, which is convex), so
//! `x* = y − Λ F(y) + (I − Λ M)(x* − y) ∈ K = y − Λ F(y) + (I − Λ J)(X − y)`
//! (Krawczyk 1969; Neumaier, *Interval methods for systems of equations*, 1990, §5.1).
//! Hence every zero in `X` lies in `K ∩ X`: none when that is empty, and otherwise every
//! crossing point is `C(t*)` with `t* ∈ T = (K ∩ X)_t`, inside
//! `C(½) + C′([0, 1]) (T − ½)` (mean-value form). `F(y)` is enclosed by de Casteljau's
//! algorithm at `½` on the interval control points (halving is exact; sums round outward).
//! No claim of uniqueness is made or needed.

use super::patch::{Box3, ICurve, IPatch, V, cross, derivative_numerator};
use crate::scalar::Interval;
use crate::spline::enclosed_bezier::cut_row;

type M3 = [[Interval; 3]; 3];

/// What the test established for a curve piece against a surface piece.
#[derive(Debug, PartialEq)]
pub(crate) enum Crossings {
    /// No point of the curve piece lies on the surface piece.
    None,
    /// Every common point lies in this model-space box.
    Within(Box3),
    /// Nothing shown (an enclosure failed, or `K` did not shrink).
    Undecided,
}

/// What the test needs of a surface piece: `S(½, ½)` and `S_u`, `S_v` over the whole piece,
/// enclosed (computed once per piece while the search splits only the curve).
#[derive(Debug)]
pub(crate) struct PatchJet {
    mid: V,
    su: V,
    sv: V,
    /// `S_u × S_v` enclosed over the piece.
    normal: V,
}

/// The enclosures of [`PatchJet`]; `None` where one fails (weights not enclosed positive,
/// degree 0, overflow).
pub(crate) fn patch_jet(s: &IPatch) -> Option<PatchJet> {
    let ds = |along_u: bool| -> Option<V> {
        let h = s.hodograph(along_u)?;
        derivative(&s.x, &s.w, &h.x, &h.w)
    };
    let (su, sv) = (ds(true)?, ds(false)?);
    Some(PatchJet {
        su,
        sv,
        normal: cross(&su, &sv),
        mid: cartesian(patch_at_half(s))?,
    })
}

/// Most Krawczyk steps in one call of [`crossings`].
const MAX_STEPS: usize = 6;

/// Every crossing of `c` with the piece `s` (whose [`patch_jet`] is `jet`) enclosed (see the
/// module comment). Where `K ∩ X` shrinks, the parts are cut down to it (de Casteljau at the
/// ends, in intervals: the cut parts hold every crossing) and the step repeated, so the box
/// shrinks about quadratically, as Newton's method converges, until its diagonal is at most
/// `target`. A part is not cut narrower than [`MIN_CUT`] of its parameter range (narrower
/// parts have derivative enclosures made of rounding alone).
pub(crate) fn crossings(c: &ICurve, s: &IPatch, jet: &PatchJet, target: f64) -> Crossings {
    let mut best = Crossings::Undecided;
    let (mut c, mut s) = (c.clone(), std::borrow::Cow::Borrowed(s));
    let mut own: Option<PatchJet> = None;
    for _ in 0..MAX_STEPS {
        let j = own.as_ref().unwrap_or(jet);
        match step(&c, j) {
            None => return best,
            Some(Step::Empty) => return Crossings::None,
            Some(Step::Shrunk(r, b)) => {
                best = Crossings::Within(b);
                if r[0].1 - r[0].0 >= 0.5 || super::patch::diagonal(&b) <= target {
                    return best;
                }
                let r = r.map(widen);
                let Some(cut) = sub_row(&c.x, &c.w, r[0]) else {
                    return best;
                };
                c = ICurve { x: cut.0, w: cut.1 };
                if r[1] != (0.0, 1.0) || r[2] != (0.0, 1.0) {
                    let Some(p) = sub_patch(&s, r[1], r[2]) else {
                        return best;
                    };
                    let Some(pj) = patch_jet(&p) else {
                        return best;
                    };
                    s = std::borrow::Cow::Owned(p);
                    own = Some(pj);
                }
            }
        }
    }
    best
}

/// Narrowest range a part is cut to.
const MIN_CUT: f64 = 1.0 / 1024.0 / 1024.0;

/// `[a, b]` grown about its middle to about [`MIN_CUT`], inside `[0, 1]`; always holding
/// `[a, b]` (the `min`/`max` keep it whatever the rounding).
fn widen((a, b): (f64, f64)) -> (f64, f64) {
    if b - a >= MIN_CUT {
        return (a, b);
    }
    let (m, h) = (0.5 * (a + b), 0.5 * MIN_CUT);
    let (mut lo, mut hi) = ((m - h).max(0.0).min(a), (m + h).min(1.0).max(b));
    if lo == 0.0 {
        hi = hi.max(MIN_CUT);
    }
    if hi == 1.0 {
        lo = lo.min(1.0 - MIN_CUT);
    }
    (lo, hi)
}

type Row = (Vec<V>, Vec<Interval>);

/// The row of a part covering at least `[a, b] ⊂ [0, 1]`
/// ([`crate::spline::enclosed_bezier::cut_row`] on the homogeneous points).
fn sub_row(xs: &[V], ws: &[Interval], ab: (f64, f64)) -> Option<Row> {
    let row: Vec<[Interval; 4]> = xs
        .iter()
        .zip(ws)
        .map(|(x, w)| [x[0], x[1], x[2], *w])
        .collect();
    let (cut, _) = cut_row(&row, ab)?;
    Some(cut.iter().map(|h| ([h[0], h[1], h[2]], h[3])).unzip())
}

/// The part of `s` covering at least `[u0, u1] × [v0, v1]`.
fn sub_patch(s: &IPatch, u: (f64, f64), v: (f64, f64)) -> Option<IPatch> {
    let mut out = s.clone();
    for (along_u, range) in [(true, u), (false, v)] {
        if range == (0.0, 1.0) {
            continue;
        }
        let (n, m) = if along_u { (s.p, s.q) } else { (s.q, s.p) };
        for line in 0..=m {
            let idx = |k: usize| {
                if along_u {
                    s.at(k, line)
                } else {
                    s.at(line, k)
                }
            };
            let xs: Vec<V> = (0..=n).map(|k| out.x[idx(k)]).collect();
            let ws: Vec<Interval> = (0..=n).map(|k| out.w[idx(k)]).collect();
            let (cx, cw) = sub_row(&xs, &ws, range)?;
            for k in 0..=n {
                out.x[idx(k)] = cx[k];
                out.w[idx(k)] = cw[k];
            }
        }
    }
    Some(out)
}

/// Enclosure of the derivative `(X′ w − X w′) / w²` of the rational piece with homogeneous
/// net `(x, w)` and hodograph `(dx, dw)` over its whole parameter domain.
fn derivative(x: &[V], w: &[Interval], dx: &[V], dw: &[Interval]) -> Option<V> {
    let (n, wr) = derivative_numerator(x, w, dx, dw)?;
    if !wr.is_pos() {
        return None;
    }
    let w2 = wr * wr;
    let out = [
        n[0].checked_div(w2)?,
        n[1].checked_div(w2)?,
        n[2].checked_div(w2)?,
    ];
    out.iter().all(Interval::is_finite).then_some(out)
}

/// de Casteljau at `½` on a row of homogeneous interval points.
fn at_half(xs: &[V], ws: &[Interval]) -> (V, Interval) {
    let half = Interval::point(0.5);
    let (mut x, mut w) = (xs.to_vec(), ws.to_vec());
    for level in 1..x.len() {
        for k in 0..x.len() - level {
            x[k] = std::array::from_fn(|c| (x[k][c] + x[k + 1][c]) * half);
            w[k] = (w[k] + w[k + 1]) * half;
        }
    }
    (x[0], w[0])
}

fn cartesian((x, w): (V, Interval)) -> Option<V> {
    if !w.is_pos() {
        return None;
    }
    let p = [
        x[0].checked_div(w)?,
        x[1].checked_div(w)?,
        x[2].checked_div(w)?,
    ];
    p.iter().all(Interval::is_finite).then_some(p)
}

/// `S(½, ½)`: each row along v at `½`, then the column of results at `½`.
fn patch_at_half(s: &IPatch) -> (V, Interval) {
    let (mut xs, mut ws) = (Vec::with_capacity(s.p + 1), Vec::with_capacity(s.p + 1));
    for i in 0..=s.p {
        let r = (0..=s.q).map(|j| s.at(i, j));
        let (x, w) = at_half(
            &r.clone().map(|k| s.x[k]).collect::<Vec<_>>(),
            &r.map(|k| s.w[k]).collect::<Vec<_>>(),
        );
        xs.push(x);
        ws.push(w);
    }
    at_half(&xs, &ws)
}

/// Inverse of a real 3 × 3 matrix (Cramer's rule; any real matrix serves as `Λ`).
fn inverse3(m: &[[f64; 3]; 3]) -> Option<[[f64; 3]; 3]> {
    let c = |i: usize, j: usize| {
        let (i1, i2) = ((i + 1) % 3, (i + 2) % 3);
        let (j1, j2) = ((j + 1) % 3, (j + 2) % 3);
        m[i1][j1] * m[i2][j2] - m[i1][j2] * m[i2][j1]
    };
    let det = m[0][0] * c(0, 0) + m[0][1] * c(0, 1) + m[0][2] * c(0, 2);
    if det == 0.0 || !det.is_finite() {
        return None;
    }
    let inv: [[f64; 3]; 3] = std::array::from_fn(|i| std::array::from_fn(|j| c(j, i) / det));
    inv.iter().flatten().all(|x| x.is_finite()).then_some(inv)
}

/// One Krawczyk step on the whole parts.
enum Step {
    /// `K ∩ X` is empty: no crossing.
    Empty,
    /// `K ∩ X` (its `t`, `u`, `v` ranges) and a box holding every crossing point.
    Shrunk([(f64, f64); 3], Box3),
}

fn step(c: &ICurve, s: &PatchJet) -> Option<Step> {
    // Derivative enclosures over the whole pieces.
    let h = c.hodograph()?;
    let dc = derivative(&c.x, &c.w, &h.x, &h.w)?;
    let (su, sv) = (s.su, s.sv);
    // Where the curve's tangents may lie in a tangent plane of the surface (C′ · (S_u × S_v)
    // not proven of one sign), the crossings need not be isolated (a border lying in the
    // other surface) and K would not shrink: left to the search, at the cost of one dot
    // product. A scheduling choice: the theorem needs no such condition.
    if (0..3)
        .map(|k| dc[k] * s.normal[k])
        .fold(Interval::point(0.0), |a, b| a + b)
        .contains_zero()
    {
        return None;
    }
    // J = [C′ | −S_u | −S_v], F(y) = C(½) − S(½, ½).
    let j: M3 = std::array::from_fn(|r| [dc[r], -su[r], -sv[r]]);
    let c_mid = cartesian(at_half(&c.x, &c.w))?;
    let s_mid = s.mid;
    let f: V = std::array::from_fn(|r| c_mid[r] - s_mid[r]);
    let l = inverse3(&std::array::from_fn(|r| {
        std::array::from_fn(|k| j[r][k].mid())
    }))?;
    let half = Interval::point(0.5);
    let dev = Interval::new(-0.5, 0.5);
    let mut k_box = [Interval::point(0.0); 3];
    for (r, kr) in k_box.iter_mut().enumerate() {
        let mut acc = half;
        for m in 0..3 {
            acc = acc - Interval::point(l[r][m]) * f[m];
        }
        for col in 0..3 {
            // (I − Λ J)[r][col]
            let mut e = Interval::point(if r == col { 1.0 } else { 0.0 });
            for m in 0..3 {
                e = e - Interval::point(l[r][m]) * j[m][col];
            }
            acc = acc + e * dev;
        }
        if !acc.is_finite() {
            return None;
        }
        *kr = acc;
    }
    // K ∩ X.
    let meet: [(f64, f64); 3] = k_box.map(|k| (k.lo.max(0.0), k.hi.min(1.0)));
    if meet.iter().any(|&(a, b)| a > b) {
        return Some(Step::Empty);
    }
    let (t0, t1) = meet[0];
    let dt = Interval::new(t0, t1) - half;
    let mut b: Box3 = ([0.0; 3], [0.0; 3]);
    for k in 0..3 {
        let p = c_mid[k] + dc[k] * dt;
        if !p.is_finite() {
            return None;
        }
        (b.0[k], b.1[k]) = (p.lo, p.hi);
    }
    Some(Step::Shrunk(meet, b))
}

#[cfg(test)]
mod tests;
