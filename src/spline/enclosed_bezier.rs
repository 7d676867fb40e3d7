//! Bézier extraction in interval arithmetic: the control points of a B-spline's polynomial
//! pieces, *enclosed*. The de Boor–Ramshaw recurrence (the blossom, Ramshaw 1989; The NURBS
//! Book §5.2) is evaluated in outward-rounded [`Interval`] arithmetic on the f64 knots and
//! control points taken as exact rationals, so each result contains the exact Bézier control
//! point — what exact rational knot insertion would give — at f64 cost.
//!
//! For a surface the extraction runs along u on every column of the net, then along v on
//! every row of the result (the tensor-product blossom is the u-blossom of the v-blossoms), on
//! homogeneous points `(wP, w)`, so rational surfaces are extracted without division.

use super::NurbsSurface;
use crate::scalar::Interval;
use arrayvec::ArrayVec;

type I = Interval;

/// `(1 - t) a + t b`, enclosed.
#[inline]
pub fn lerp<const D: usize>(a: &[I; D], b: &[I; D], t: I) -> [I; D] {
    let s = I::point(1.0) - t;
    std::array::from_fn(|i| s * a[i] + t * b[i])
}

/// De Casteljau's algorithm at the point parameter `t` on a row of enclosed points (`1 − t`
/// enclosed): the rows of `[0, t]` and `[t, 1]`, each holding the exact parts of every row
/// the enclosures hold.
pub fn split_row<const D: usize>(row: &[[I; D]], t: f64) -> (Vec<[I; D]>, Vec<[I; D]>) {
    let n = row.len() - 1;
    let t = I::point(t);
    let mut d = row.to_vec();
    let (mut left, mut right) = (vec![d[0]; n + 1], vec![d[n]; n + 1]);
    for level in 1..=n {
        for k in 0..=n - level {
            d[k] = lerp(&d[k], &d[k + 1], t);
        }
        left[level] = d[0];
        right[n - level] = d[n - level];
    }
    (left, right)
}

/// The part of a row (parameter `[0, 1]`) covering at least `[a, b]`, `0 ≤ a ≤ b ≤ 1`: cut at
/// `b`, then the left part at `s = a / b` rounded down, so the part kept is exactly
/// `[s b, b] ⊇ [a, b]`. Returns the part and `s` (0 when `a = 0`); `None` for ends out of order.
pub fn cut_row<const D: usize>(row: &[[I; D]], (a, b): (f64, f64)) -> Option<(Vec<[I; D]>, f64)> {
    if !(0.0 <= a && a <= b && b <= 1.0) || row.is_empty() {
        return None;
    }
    let left = if b < 1.0 {
        split_row(row, b).0
    } else {
        row.to_vec()
    };
    if a == 0.0 {
        return Some((left, 0.0));
    }
    let s = (a / b).next_down().max(0.0);
    Some((split_row(&left, s).1, s))
}

/// Blossom of a B-spline curve of degree `p` (knots `knots`, control points `ctrl`) on span
/// `s` (`knots[s] < knots[s + 1]`), at arguments `xs` (de Boor–Ramshaw recurrence).
/// `None` when a knot difference is not certified positive (invalid knot vector) or the
/// degree exceeds [`super::MAX_DEGREE`].
pub fn bspline_blossom<const D: usize>(
    knots: &[f64],
    p: usize,
    ctrl: &[[I; D]],
    s: usize,
    xs: &[I],
) -> Option<[I; D]> {
    if p > super::MAX_DEGREE || s < p || s >= ctrl.len() || knots.len() < s + p + 2 {
        return None;
    }
    let mut d: ArrayVec<[I; D], 32> = (s - p..=s).map(|j| ctrl[j]).collect();
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

/// The blossom's interpolation factors on span `s` for the Bézier points' arguments
/// `(u_s^(p−k), u_{s+1}^k)`, `k = 0..=p`: every `alpha` [`bspline_blossom`] computes, in its
/// order (k, then the recurrence's `r` and `j`). They depend on the knots only, so one table
/// serves every row of a net; [`span_bezier_with`] applies it with the operations of the
/// recurrence, so the enclosures are the blossom's, bit for bit.
fn span_alphas(knots: &[f64], p: usize, s: usize) -> Option<Vec<I>> {
    if p > super::MAX_DEGREE || s < p || knots.len() < s + p + 2 {
        return None;
    }
    let (a, b) = (I::point(knots[s]), I::point(knots[s + 1]));
    let mut out = Vec::with_capacity((p + 1) * p * (p + 1) / 2);
    for k in 0..=p {
        for r in 1..=p {
            let x = if r <= p - k { a } else { b };
            for j in (s - p + r..=s).rev() {
                let (uj, ue) = (knots[j], knots[j + p + 1 - r]);
                out.push((x - I::point(uj)).checked_div(I::point(ue) - I::point(uj))?);
            }
        }
    }
    Some(out)
}

/// The Bézier control points of a span from its `p + 1` B-spline control points `window`
/// (`ctrl[s − p..=s]`) and its [`span_alphas`] table, into `out`.
fn span_bezier_with<const D: usize>(
    alphas: &[I],
    p: usize,
    window: &[[I; D]],
    out: &mut Vec<[I; D]>,
) {
    out.clear();
    let mut at = alphas.iter();
    for _ in 0..=p {
        let mut d: ArrayVec<[I; D], 32> = window.iter().copied().collect();
        for r in 1..=p {
            for k in (r..=p).rev() {
                // The table holds one factor per step, in this order.
                let alpha = at.next().copied().unwrap_or(I::point(f64::NAN));
                d[k] = lerp(&d[k - 1], &d[k], alpha);
            }
        }
        out.push(d[p]);
    }
}

/// The Bézier control points of span `s` of a B-spline curve: blossoms at
/// `(u_s^(p-k), u_{s+1}^k)`, `k = 0..=p` (the recurrence of [`bspline_blossom`], its factors
/// tabled once for the span).
pub fn bspline_span_bezier<const D: usize>(
    knots: &[f64],
    p: usize,
    ctrl: &[[I; D]],
    s: usize,
) -> Option<Vec<[I; D]>> {
    if s >= ctrl.len() {
        return None;
    }
    let alphas = span_alphas(knots, p, s)?;
    let mut out = Vec::with_capacity(p + 1);
    span_bezier_with(&alphas, p, &ctrl[s - p..=s], &mut out);
    Some(out)
}

/// One Bézier piece of a surface with enclosed homogeneous control points.
#[derive(Clone, Debug)]
pub struct EnclosedPatch {
    /// The knot span rectangle `[u0, u1, v0, v1]` (knot values, exact).
    pub uv: [f64; 4],
    pub p: usize,
    pub q: usize,
    /// Homogeneous control points `(wP, w)`, row-major (`i` along u, `j` along v).
    pub net: Vec<[I; 4]>,
}

/// Indices `s` of the non-empty spans `[t_s, t_{s+1})` of a clamped knot vector inside the
/// domain `[t_p, t_{n}]`.
fn spans(knots: &[f64], p: usize, n: usize) -> Vec<usize> {
    (p..n).filter(|&s| knots[s] < knots[s + 1]).collect()
}

/// Every Bézier piece of `s` (one per pair of non-empty knot spans, u-major), enclosed; `None`
/// when a knot difference cannot be certified positive.
pub fn enclosed_bezier_patches(s: &NurbsSurface<f64, 3>) -> Option<Vec<EnclosedPatch>> {
    let h = &s.hom;
    let (p, q) = h.degrees();
    let (ku, kv) = (h.ku.knots(), h.kv.knots());
    let (nu, nv) = (ku.len() - p - 1, kv.len() - q - 1);
    if nu * nv != h.net.len() {
        return None;
    }
    let hom = |i: usize, j: usize| -> [I; 4] {
        let c = &h.net[i * nv + j];
        [c.wp[0], c.wp[1], c.wp[2], c.w].map(I::point)
    };
    let (su, sv) = (spans(ku, p, nu), spans(kv, q, nv));
    let alphas_v: Vec<Vec<I>> = sv
        .iter()
        .map(|&b| span_alphas(kv, q, b))
        .collect::<Option<_>>()?;
    let mut out = Vec::with_capacity(su.len() * sv.len());
    let mut window: Vec<[I; 4]> = Vec::with_capacity(p.max(q) + 1);
    let mut bz: Vec<[I; 4]> = Vec::with_capacity(p.max(q) + 1);
    for &a in &su {
        let alphas_u = span_alphas(ku, p, a)?;
        // Along u on every column j: the u-Bézier points of this span, (p + 1) per column.
        let mut cols: Vec<[I; 4]> = Vec::with_capacity(nv * (p + 1));
        for j in 0..nv {
            window.clear();
            window.extend((a - p..=a).map(|i| hom(i, j)));
            span_bezier_with(&alphas_u, p, &window, &mut bz);
            cols.extend_from_slice(&bz);
        }
        for (&b, alphas) in sv.iter().zip(&alphas_v) {
            let mut net = vec![[I::point(0.0); 4]; (p + 1) * (q + 1)];
            for i in 0..=p {
                window.clear();
                window.extend((b - q..=b).map(|j| cols[j * (p + 1) + i]));
                span_bezier_with(alphas, q, &window, &mut bz);
                net[i * (q + 1)..(i + 1) * (q + 1)].copy_from_slice(&bz);
            }
            out.push(EnclosedPatch {
                uv: [ku[a], ku[a + 1], kv[b], kv[b + 1]],
                p,
                q,
                net,
            });
        }
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::lift_point;
    use crate::scalar::Rational;
    use crate::scalar::lift;

    /// The enclosures contain the exact rational extraction (knot insertion in Rational,
    /// an independent algorithm), for a rational surface with non-uniform, repeated knots.
    #[test]
    fn enclosures_contain_the_exact_extraction() {
        use crate::geom::Hom;
        use crate::spline::{BSplineSurface, KnotVector};
        let ku = KnotVector::new(vec![0.0, 0.0, 0.0, 0.3, 0.3, 0.7, 1.0, 1.0, 1.0], 2, 6).unwrap();
        let kv =
            KnotVector::new(vec![-1.0, -1.0, -1.0, -1.0, 0.1, 2.0, 2.0, 2.0, 2.0], 3, 5).unwrap();
        let (nu, nv) = (6, 5);
        let mut net = Vec::new();
        for i in 0..nu {
            for j in 0..nv {
                let w = 0.5 + ((i * 7 + j * 3) % 5) as f64 * 0.37;
                let pnt = [
                    i as f64 * 0.9 + 0.1 * j as f64,
                    j as f64 * 1.1 - 0.3 * (i as f64).sin(),
                    ((i * j) as f64).cos() / 3.0,
                ];
                net.push(Hom::from_point(&pnt, &w));
            }
        }
        let s = NurbsSurface {
            hom: BSplineSurface { ku, kv, net },
        };
        let enc = enclosed_bezier_patches(&s).unwrap();
        type Q = Rational;
        let exact = s.hom.map(
            |k| lift::<Q>(*k),
            |h| Hom {
                wp: lift_point(&h.wp),
                w: lift(h.w),
            },
        );
        let ex = exact.bezier_patches();
        assert_eq!(enc.len(), ex.len());
        assert_eq!(enc.len(), 3 * 2);
        let inside = |x: &I, q: &Q| lift::<Q>(x.lo) <= *q && *q <= lift::<Q>(x.hi);
        for (e, x) in enc.iter().zip(&ex) {
            assert_eq!(lift::<Q>(e.uv[0]), x.u0);
            assert_eq!(lift::<Q>(e.uv[3]), x.v1);
            assert_eq!(e.net.len(), x.patch.net.len());
            for (a, b) in e.net.iter().zip(&x.patch.net) {
                for c in 0..3 {
                    assert!(inside(&a[c], &b.wp[c]), "{a:?} vs {b:?}");
                    assert!(a[c].hi - a[c].lo <= 1e-12 * (1.0 + a[c].lo.abs()));
                }
                assert!(inside(&a[3], &b.w));
            }
        }
    }
}
