//! Step 3, completion — the interior of a patch follows its new boundary rows (paper §6,
//! matrix (2): "the rows (columns) related to the boundary of each original patch are
//! blended"), and the deviation of the repaired patch from the original is measured.
//!
//! Blending: the boundary control points moved by `Δ` (averaged rows, fitted rows, averaged
//! corners); every interior control point moves by the discrete Coons patch of those moves,
//! `D(s, t) = (1-t) Δ_S(s) + t Δ_N(s) + (1-s) Δ_W(t) + s Δ_E(t) − (bilinear corner term)`, at
//! its Greville abscissae `(s, t)` normalized to `[0, 1]`. A rigid shift of all four rows
//! shifts the whole net; moves along one edge fade across the patch. Weight changes of the
//! boundary rows (a fitted rational row) are blended the same way.
//!
//! Deviation: the repaired patch's control points against those of the original refined to the
//! same knots (before any move) give, when both have the same weights, a *proven* bound on
//! `|S_new(u, v) − S_old(u, v)|`: the maximum control-point move (the rational basis functions
//! are non-negative and sum to one; hypotheses: equal weights, the refinement exact — on `f64`
//! it carries rounding of relative size ~1e-16). With changed weights (a fitted row has
//! weights 1) only the measured figure is given: the largest distance from samples of the
//! repaired patch to their closest points on the original (Gauss–Newton from the
//! corresponding parameter): evidence.

use crate::geom::dist;
use crate::spline::NurbsSurface;
use crate::spline::project::descend;

fn cart(s: &NurbsSurface<f64, 3>, i: usize, j: usize) -> [f64; 3] {
    let h = s.hom.at(i, j);
    [h.wp[0] / h.w, h.wp[1] / h.w, h.wp[2] / h.w]
}

/// Greville abscissae of a knot vector, normalized to `[0, 1]`.
pub(super) fn greville(k: &[f64], p: usize) -> Vec<f64> {
    let n = k.len() - p - 1;
    let (a, b) = (k[p], k[n]);
    (0..n)
        .map(|i| {
            let g = k[i + 1..=i + p].iter().sum::<f64>() / p as f64;
            ((g - a) / (b - a)).clamp(0.0, 1.0)
        })
        .collect()
}

/// Move the interior of `after` (whose boundary rows are final) by the Coons blend of the
/// boundary moves from `before` (same net size): the Cartesian moves, and the weight changes
/// (a row given other weights passes them on gradually instead of as a jump between the
/// boundary row and the next; a blended weight that would not be positive is left as it was).
/// Returns the largest interior move.
pub fn blend_interior(before: &NurbsSurface<f64, 3>, after: &mut NurbsSurface<f64, 3>) -> f64 {
    let (nu, nv) = (after.hom.nu(), after.hom.nv());
    if nu < 3 || nv < 3 {
        return 0.0;
    }
    let delta = |i: usize, j: usize| -> [f64; 4] {
        let (a, b) = (cart(after, i, j), cart(before, i, j));
        [
            a[0] - b[0],
            a[1] - b[1],
            a[2] - b[2],
            after.hom.at(i, j).w - before.hom.at(i, j).w,
        ]
    };
    let gs = greville(after.hom.ku.knots(), after.hom.ku.degree());
    let gt = greville(after.hom.kv.knots(), after.hom.kv.degree());
    let (d00, d10, d01, d11) = (
        delta(0, 0),
        delta(nu - 1, 0),
        delta(0, nv - 1),
        delta(nu - 1, nv - 1),
    );
    let south: Vec<[f64; 4]> = (0..nu).map(|i| delta(i, 0)).collect();
    let north: Vec<[f64; 4]> = (0..nu).map(|i| delta(i, nv - 1)).collect();
    let west: Vec<[f64; 4]> = (0..nv).map(|j| delta(0, j)).collect();
    let east: Vec<[f64; 4]> = (0..nv).map(|j| delta(nu - 1, j)).collect();
    let mut worst: f64 = 0.0;
    for i in 1..nu - 1 {
        for j in 1..nv - 1 {
            let (s, t) = (gs[i], gt[j]);
            let d: [f64; 4] = std::array::from_fn(|k| {
                (1.0 - t) * south[i][k] + t * north[i][k] + (1.0 - s) * west[j][k] + s * east[j][k]
                    - ((1.0 - s) * (1.0 - t) * d00[k]
                        + s * (1.0 - t) * d10[k]
                        + (1.0 - s) * t * d01[k]
                        + s * t * d11[k])
            });
            if d == [0.0; 4] {
                continue;
            }
            let x = cart(before, i, j);
            let y: [f64; 3] = std::array::from_fn(|k| x[k] + d[k]);
            worst = worst.max(dist(&x, &y));
            let w0 = before.hom.at(i, j).w;
            let w = if w0 + d[3] > 0.0 && (w0 + d[3]).is_finite() {
                w0 + d[3]
            } else {
                w0
            };
            let nvv = after.hom.nv();
            after.hom.net[i * nvv + j] = crate::geom::Hom::from_point(&y, &w);
        }
    }
    worst
}

/// Largest control-point move from `before` to `after` (same net), and whether their weights
/// are equal (then the move bounds the surfaces' distance at equal parameters).
pub fn control_move(before: &NurbsSurface<f64, 3>, after: &NurbsSurface<f64, 3>) -> (f64, bool) {
    let same_w = before
        .hom
        .net
        .iter()
        .zip(&after.hom.net)
        .all(|(a, b)| a.w == b.w);
    let (nu, nv) = (after.hom.nu(), after.hom.nv());
    let mut m: f64 = 0.0;
    for i in 0..nu {
        for j in 0..nv {
            m = m.max(dist(&cart(before, i, j), &cart(after, i, j)));
        }
    }
    (m, same_w)
}

/// Largest distance from `n × n` samples of `repaired` to their closest points on
/// `original` (Gauss–Newton started at the corresponding normalized parameter): evidence.
pub fn measured_deviation(
    original: &NurbsSurface<f64, 3>,
    repaired: &NurbsSurface<f64, 3>,
    n: usize,
) -> f64 {
    let (a0, a1, b0, b1) = original.hom.domain();
    let (c0, c1, d0, d1) = repaired.hom.domain();
    let dom = [a0, a1, b0, b1];
    let mut worst: f64 = 0.0;
    for i in 0..n {
        for j in 0..n {
            let (s, t) = (i as f64 / (n - 1) as f64, j as f64 / (n - 1) as f64);
            let x = repaired.eval(&(c0 + s * (c1 - c0)), &(d0 + t * (d1 - d0)));
            let start = [a0 + s * (a1 - a0), b0 + t * (b1 - b0)];
            let (uv, _) = descend(original, &x, start, &dom);
            worst = worst.max(dist(&original.eval(&uv[0], &uv[1]), &x));
        }
    }
    worst
}
