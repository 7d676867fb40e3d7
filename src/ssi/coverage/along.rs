//! Curve parts lying along the output's cubic pieces (`--pieces cubic`). A border curve that
//! runs along a branch — a border lying in the other surface, as the equator of a sphere's
//! net lies in a plane through its centre — can only be decided near the output
//! ([`super::near`]) in parts short enough to lie within `d` of one straight segment or
//! chord: on a circle of radius `R` about `√(8 R d)` long, thousands per border. Against the
//! output's own cubic pieces a part is decided whole when it follows one of them.
//!
//! # The test
//!
//! Let `C(s) = X(s) / w(s)`, `s ∈ [0, 1]`, be a part of a border curve: a rational Bézier curve
//! of degree `n` whose homogeneous control points `(X_k, w_k)` are enclosed in intervals; and
//! `H(τ) = Σ_i h_i B_i³(τ)`, `τ ∈ [0, 1]`, an output cubic piece ([`crate::ssi::hermite`]: its
//! Bernstein points `h_0 = p`, `h_1 = p + ṗ/3`, `h_2 = q − q̇/3`, `h_3 = q`, enclosed from the
//! piece's f64 data). For any cubic `σ(s) = Σ_k b_k B_k³(s)` with every `b_k ∈ [0, 1]`,
//! `σ(s) ∈ [0, 1]` (convex hull), so `H(σ(s))` is a point of the output, and
//!
//! `‖C(s) − H(σ(s))‖ = ‖E(s)‖ / w(s)`,  `E = X − w · (H ∘ σ)`,
//!
//! a polynomial of degree `n + 9`, computed by Bernstein products
//! ([`crate::spline::scaled_bernstein`]; `B_i³(σ) = C(3, i) σ^i (1 − σ)^{3−i}`). By the convex
//! hull property of Bézier polynomials `‖E(s)‖ ≤ max_k ‖E_k‖` (where that is above the target,
//! the larger of the same bound on the two halves of `E`, split by de Casteljau at `1/2`, up to
//! three halvings deep) and `w(s) ≥ min_k w_k`; so when `min_k w_k > 0`,
//! `r = max_k ‖E_k‖ / min_k w_k` bounds the distance from every point of the part to the
//! output, and the part lies within `d` of it when `r ≤ d`. Every number is an
//! outward-rounded interval. `σ` interpolates the parameters of the closest points on `H` of
//! `C(0)`, `C(1/3)`, `C(2/3)`, `C(1)` (f64): the fit decides only how small `r` comes out
//! (the two parametrizations differ by terms of fourth order in the part's length), never
//! whether it bounds.

use super::patch::{Box3, ICurve};
use crate::scalar::Interval;
use crate::spline::scaled_bernstein::{binom, mul, powers, scaled, unscaled};
use crate::ssi::hermite::Piece;

type I = Interval;

/// Parts smaller than this many match distances are left to the segment and chord tests,
/// which decide them as well (a scheduling choice).
const MIN_PART: f64 = 16.0;

/// The output's cubic pieces, each with its enclosed Bernstein points and their box.
#[derive(Default)]
pub(crate) struct Along {
    /// Sorted by their boxes' lower x.
    pieces: Vec<(Piece, [[I; 3]; 4], Box3)>,
    /// The largest x extent of a piece's box.
    wide: f64,
}

impl Along {
    /// The cubic pieces among `pieces` (chords are left to [`super::near`], which decides
    /// against them exactly); pieces with data that is not finite are left out.
    pub fn new(pieces: impl IntoIterator<Item = Piece>) -> Along {
        let third = I::point(3.0);
        let pieces = pieces
            .into_iter()
            .filter(|h| h.dp != h.dq)
            .filter_map(|h| {
                let pt = |v: &[f64; 7]| -> [I; 3] { std::array::from_fn(|k| I::point(v[k])) };
                let (p, q, dp, dq) = (pt(&h.p), pt(&h.q), pt(&h.dp), pt(&h.dq));
                let mut b = [p, p, q, q];
                for k in 0..3 {
                    b[1][k] = p[k] + dp[k].checked_div(third)?;
                    b[2][k] = q[k] - dq[k].checked_div(third)?;
                }
                let mut bx = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
                for x in &b {
                    for k in 0..3 {
                        bx.0[k] = bx.0[k].min(x[k].lo);
                        bx.1[k] = bx.1[k].max(x[k].hi);
                    }
                }
                b.iter()
                    .all(|x| x.iter().all(|c| c.is_finite()))
                    .then_some((h, b, bx))
            })
            .collect::<Vec<_>>();
        let mut pieces = pieces;
        pieces.sort_by(|a, b| a.2.0[0].total_cmp(&b.2.0[0]));
        let wide = pieces
            .iter()
            .map(|p| p.2.1[0] - p.2.0[0])
            .fold(0.0, f64::max);
        Along { pieces, wide }
    }

    /// Whether every point of the curve part `c` (its control points' box `cbox`, with a
    /// diagonal of `diag`) is proven within `d` of one output cubic piece (module comment).
    pub fn curve_within(&self, c: &ICurve, cbox: &Box3, diag: f64, d: f64) -> bool {
        if self.pieces.is_empty()
            || diag.partial_cmp(&(MIN_PART * d)) != Some(std::cmp::Ordering::Greater)
        {
            return false;
        }
        // A piece whose box, grown by `d`, holds the part's starts in x at or after
        // `cbox.1[0] − d − wide` and at or before `cbox.0[0] + d` (sorted: a range).
        let from = self
            .pieces
            .partition_point(|p| p.2.0[0] < cbox.1[0] - d - self.wide);
        let to = self.pieces.partition_point(|p| p.2.0[0] <= cbox.0[0] + d);
        self.pieces[from..to.max(from)].iter().any(|(h, b, hb)| {
            (0..3).all(|k| hb.0[k] - d <= cbox.0[k] && cbox.1[k] <= hb.1[k] + d)
                && bound(h, b, c, d).is_some_and(|r| r <= d)
        })
    }
}

/// `r` of the module comment for the part `c` against the one piece `h` (`None` where no
/// bound follows or the part is measured farther than `2d` from the piece): what
/// the crossing search compares with `d`, for the proof harnesses.
pub fn piece_bound(h: &Piece, c: &ICurve, d: f64) -> Option<f64> {
    let a = Along::new([*h]);
    let (h, b, _) = a.pieces.first()?;
    bound(h, b, c, d)
}

/// The part's point at `s` from its control points' midpoints (de Casteljau in f64, for the
/// fit of `σ` only).
fn point_at(c: &ICurve, s: f64) -> Option<[f64; 3]> {
    let mut h: Vec<[f64; 4]> =
        c.x.iter()
            .zip(&c.w)
            .map(|(x, w)| [x[0].mid(), x[1].mid(), x[2].mid(), w.mid()])
            .collect();
    for r in 1..h.len() {
        for k in 0..h.len() - r {
            h[k] = std::array::from_fn(|j| (1.0 - s) * h[k][j] + s * h[k + 1][j]);
        }
    }
    let p = h.first()?;
    let x = [p[0] / p[3], p[1] / p[3], p[2] / p[3]];
    x.iter().all(|v| v.is_finite()).then_some(x)
}

/// `r` of the module comment for the part `c` against the piece `h` (Bernstein points `b`);
/// `None` where no bound follows (a weight not proven positive, data not finite) or where the
/// part is measured farther than `2d` from the piece.
fn bound(h: &Piece, b: &[[I; 3]; 4], c: &ICurve, d: f64) -> Option<f64> {
    let n = c.x.len().checked_sub(1)?;
    // A part with a point farther than `2d` from the piece (measured) cannot
    // come out within `d` (`r` bounds those distances): no bound is computed for it.
    let foot = |s: f64| {
        point_at(c, s)
            .map(|x| h.foot(&x))
            .filter(|(dist, _)| *dist <= 2.0 * d)
            .map(|f| f.1)
    };
    let (t0, t3) = (foot(0.0)?, foot(1.0)?);
    let (t1, t2) = (foot(1.0 / 3.0)?, foot(2.0 / 3.0)?);
    // The cubic through the four feet at s = 0, 1/3, 2/3, 1, in Bernstein form.
    let (f1, f2) = (27.0 * t1 - 8.0 * t0 - t3, 27.0 * t2 - t0 - 8.0 * t3);
    let sigma = [t0, (2.0 * f1 - f2) / 18.0, (2.0 * f2 - f1) / 18.0, t3].map(|x| x.clamp(0.0, 1.0));
    if !sigma.iter().all(|x| x.is_finite()) {
        return None;
    }
    let one = I::point(1.0);
    let sp = powers(&scaled(sigma.iter().map(|x| I::point(*x))), 3);
    let rp = powers(&scaled(sigma.iter().map(|x| one - I::point(*x))), 3);
    // `C(3, i) σ^i (1 − σ)^{3−i}`, degree 9, scaled.
    let basis: Vec<Vec<I>> = (0..=3)
        .map(|i| {
            mul(&sp[i], &rp[3 - i])
                .into_iter()
                .map(|x| x * I::point(binom(3, i)))
                .collect()
        })
        .collect();
    let w = scaled(c.w.iter().copied());
    let ones = scaled([one; 10].into_iter());
    let mut e: [Vec<I>; 3] = Default::default();
    for (k, ek) in e.iter_mut().enumerate() {
        let g: Vec<I> = (0..=9)
            .map(|j| (0..4).fold(I::point(0.0), |acc, i| acc + basis[i][j] * b[i][k]))
            .collect();
        let x = scaled(c.x.iter().map(|p| p[k]));
        let diff: Vec<I> = mul(&x, &ones)
            .into_iter()
            .zip(mul(&w, &g))
            .map(|(a, b)| a - b)
            .collect();
        *ek = unscaled(&diff);
    }
    debug_assert!(e.iter().all(|x| x.len() == n + 10));
    let w_min = c.w.iter().map(|x| x.lo).fold(f64::INFINITY, f64::min);
    if w_min.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
        return None;
    }
    let e_max = hull_norm(&e, w_min * d, HALVINGS);
    let r = I::point(e_max).checked_div(I::point(w_min))?.hi;
    r.is_finite().then_some(r)
}

/// Halvings of the error polynomial `E` while its hull bound is above the target.
const HALVINGS: u32 = 3;

/// An upper bound on `max_s ‖E(s)‖` over `[0, 1]` from the Bernstein coefficients of the
/// three components: the largest coefficient norm (convex hull), or, while that is above
/// `target`, the larger of the two halves' bounds (de Casteljau at `1/2` in intervals; the
/// halves' control polygons lie closer to the polynomial), at most `depth` halvings deep.
fn hull_norm(e: &[Vec<I>; 3], target: f64, depth: u32) -> f64 {
    let n = e[0].len();
    let norm = (0..n)
        .map(|k| {
            let s = e[0][k].sqr() + e[1][k].sqr() + e[2][k].sqr();
            s.hi
        })
        .fold(0.0, f64::max)
        .sqrt()
        .next_up();
    if norm <= target || depth == 0 || n < 2 {
        return norm;
    }
    let half = I::point(0.5);
    let mut left: [Vec<I>; 3] = Default::default();
    let mut right: [Vec<I>; 3] = Default::default();
    for c in 0..3 {
        let mut x = e[c].clone();
        let (mut l, mut r) = (vec![x[0]; n], vec![x[n - 1]; n]);
        for level in 1..n {
            for k in 0..n - level {
                x[k] = (x[k] + x[k + 1]) * half;
            }
            l[level] = x[0];
            r[n - 1 - level] = x[n - 1 - level];
        }
        (left[c], right[c]) = (l, r);
    }
    let a = hull_norm(&left, target, depth - 1);
    let b = hull_norm(&right, target, depth - 1);
    a.max(b).min(norm)
}

#[cfg(test)]
mod tests;
