//! Trim-loop crossings: the image on a piece of a loop polygon's edge, for case 3 of the
//! coverage theorem on trimmed faces.
//!
//! On a pair `α × β` a trim loop runs through, a component of the *faces'* intersection may
//! end at the loop inside the pair, where no border crossing of `α × β` sees it. Such an end
//! is a point where the loop meets the other surface: `S_A(z_a) = S_B(z_b)` with `z_a` on an
//! edge of face A's loop polygon (or `z_b` on one of B's). The edge is a segment in the
//! parameter plane; its part in the Bézier piece `α` of degrees `(p, q)` maps to the space
//! curve `S_A(a + t (b − a))`, a rational Bézier curve of degree `p + q` whose control
//! points are weighted sums of the piece's blossom values (Yang et al. §4, "mapping segments
//! onto the surface"; [`crate::spline::compose::compose_line`] computes it exactly):
//!
//! `R_k = Σ_{i+j=k} C(p,i) C(q,j) / C(p+q,k) · f(a_u^{p−i} b_u^i ; a_v^{q−j} b_v^j)`.
//!
//! Here it is evaluated in outward-rounded interval arithmetic on the piece's enclosed
//! homogeneous control points, with the segment's ends in the piece's own coordinates
//! enclosed from the exact knot span and dyadic part the piece is ([`Cell::span`],
//! [`Cell::frac`]): by inclusion monotonicity each control point's enclosure contains the
//! exact control point of the image of the exact segment. The crossings of that curve with
//! the other piece are then searched like a border curve's ([`super::crossings::search`]).
//!
//! Which part of the edge: the segment is clipped to the piece's label box widened by
//! [`MARGIN`] of its width plus 512 ulps of the larger of its coordinates and the edge's. A
//! label differs from the exact box by the rounding of the midpoints that made it (half an
//! ulp per halving, fewer than 512 halvings), and the clip's own rounding moves its ends by a
//! few ulps of the edge's coordinates: the clipped segment holds the edge's whole part in the
//! exact piece. A longer segment only adds
//! crossings to examine (of the piece's polynomial continued a little beyond it), never hides
//! one.

use super::patch::{ICurve, IPatch};
use super::pieces::Cell;
use crate::scalar::Interval;
use crate::tessellate::region::{LoopEdge, clip_segment};

/// Relative widening of a piece's label box before an edge is clipped to it.
pub(crate) const MARGIN: f64 = 1e-9;

/// Homogeneous interval point: three coordinates and the weight.
type H = [Interval; 4];

/// The image on `cell`'s piece of the part inside the piece of the loop edge `e` (on the
/// piece's surface, with its shift by whole periods): a curve of degree `p + q` whose every crossing with a piece of
/// the other surface is a crossing of the edge's part in the piece (or of its continuation a
/// little past the piece). `None` when the segment misses the piece. Where the piece's place
/// cannot be enclosed (a knot span not certified positive, more than 52 halvings a way) the
/// image is a curve with unbounded control points, which no search can decide.
pub(crate) fn edge_image(cell: &Cell, e: &LoopEdge) -> Option<ICurve> {
    let [u0, u1, v0, v1] = cell.uv;
    let (a, b, sh) = (e.0, e.1, e.2);
    // The edge in the piece's frame, rounded (only to clip: the image is of the exact one).
    let seg = ([a[0] - sh[0], a[1] - sh[1]], [b[0] - sh[0], b[1] - sh[1]]);
    // The clip's own rounding moves its ends by a few ulps of the edge's coordinates.
    let big = [
        a[0], a[1], b[0], b[1], seg.0[0], seg.0[1], seg.1[0], seg.1[1],
    ]
    .iter()
    .fold(0.0f64, |m, x| m.max(x.abs()));
    let pad = |a: f64, b: f64| {
        MARGIN * (b - a).abs() + 512.0 * f64::EPSILON * a.abs().max(b.abs()).max(big)
    };
    let (pu, pv) = (pad(u0, u1), pad(v0, v1));
    let (t0, t1) = clip_segment(&seg.0, &seg.1, &[u0 - pu, v0 - pv], &[u1 + pu, v1 + pv])?;
    // The exact point `a + t (b − a) − s`, enclosed, in the piece's own coordinates.
    let at = |t: f64| -> Option<[Interval; 2]> {
        let t = Interval::point(t);
        let g = |k: usize| {
            let (ak, bk) = (Interval::point(a[k]), Interval::point(b[k]));
            ak + t * (bk - ak) - Interval::point(sh[k])
        };
        Some([local(cell, 0, g(0))?, local(cell, 1, g(1))?])
    };
    Some(match (at(t0), at(t1)) {
        (Some(x), Some(y)) => compose_line(&cell.patch, x, y),
        _ => {
            let all = Interval::new(f64::NEG_INFINITY, f64::INFINITY);
            let n = cell.patch.p + cell.patch.q + 1;
            ICurve {
                x: vec![[all; 3]; n],
                w: vec![all; n],
            }
        }
    })
}

/// The piece's own coordinate in direction `k` (0: u, 1: v) of a surface parameter `x`,
/// enclosed: `((x − k₀) / (k₁ − k₀) − f₀) / (f₁ − f₀)` for the knot span `[k₀, k₁]` and the
/// dyadic part `[f₀, f₁]`.
fn local(cell: &Cell, k: usize, x: Interval) -> Option<Interval> {
    let (k0, k1) = (cell.span[2 * k], cell.span[2 * k + 1]);
    let (f0, f1) = (cell.frac[2 * k], cell.frac[2 * k + 1]);
    // Fewer than 53 halvings: f₀, f₁ and their difference are exact.
    if f1 - f0 < f64::EPSILON * 4.0 || (f1 - f0).is_nan() {
        return None;
    }
    let span = Interval::point(k1) - Interval::point(k0);
    let s = (x - Interval::point(k0)).checked_div(span)?;
    (s - Interval::point(f0)).checked_div(Interval::point(f1) - Interval::point(f0))
}

/// Blossom of a row of homogeneous points (degree `n = row.len() − 1`) at `ts` (`n` values):
/// de Casteljau with the `l`-th parameter at level `l`, in interval arithmetic.
fn blossom(row: &[H], ts: &[Interval]) -> H {
    let mut b = row.to_vec();
    for (level, t) in ts.iter().enumerate() {
        for i in 0..b.len() - 1 - level {
            b[i] = std::array::from_fn(|c| b[i][c] + *t * (b[i + 1][c] - b[i][c]));
        }
    }
    b[0]
}

/// Polar values `f[x^(n−j), y^j]`, `j = 0..=n`, of a row.
fn polar_values(row: &[H], x: Interval, y: Interval) -> Vec<H> {
    let n = row.len() - 1;
    (0..=n)
        .map(|j| {
            let mut ts = vec![x; n - j];
            ts.extend(std::iter::repeat_n(y, j));
            blossom(row, &ts)
        })
        .collect()
}

/// `S(a + t (b − a))` for the piece `s` and the segment from `a` to `b` in its own
/// coordinates: the control points `R_k` of the module comment, in intervals.
fn compose_line(s: &IPatch, a: [Interval; 2], b: [Interval; 2]) -> ICurve {
    let (p, q) = (s.p, s.q);
    let h = |k: usize| -> H { [s.x[k][0], s.x[k][1], s.x[k][2], s.w[k]] };
    // Rows in v (fixed i), then the columns of their polar values in u.
    let rows: Vec<Vec<H>> = (0..=p)
        .map(|i| {
            let row: Vec<H> = (0..=q).map(|j| h(s.at(i, j))).collect();
            polar_values(&row, a[1], b[1])
        })
        .collect();
    let mut f = vec![vec![[Interval::point(0.0); 4]; q + 1]; p + 1];
    for j in 0..=q {
        let col: Vec<H> = (0..=p).map(|i| rows[i][j]).collect();
        for (i, v) in polar_values(&col, a[0], b[0]).into_iter().enumerate() {
            f[i][j] = v;
        }
    }
    let binom = |n: usize, k: usize| -> f64 {
        (0..k).fold(1.0, |acc, i| acc * (n - i) as f64 / (i + 1) as f64)
    };
    let mut x = Vec::with_capacity(p + q + 1);
    let mut w = Vec::with_capacity(p + q + 1);
    for k in 0..=p + q {
        let mut acc = [Interval::point(0.0); 4];
        for i in k.saturating_sub(q)..=k.min(p) {
            let j = k - i;
            // C(p,i) C(q,j) / C(p+q,k): integers up to 2^53 are exact; the quotient enclosed.
            let num = Interval::point(binom(p, i)) * Interval::point(binom(q, j));
            let c = num
                .checked_div(Interval::point(binom(p + q, k)))
                .unwrap_or(Interval::new(f64::NEG_INFINITY, f64::INFINITY));
            acc = std::array::from_fn(|m| acc[m] + c * f[i][j][m]);
        }
        x.push([acc[0], acc[1], acc[2]]);
        w.push(acc[3]);
    }
    ICurve { x, w }
}

#[cfg(test)]
mod tests;
