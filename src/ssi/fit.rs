//! Step 9b — spline fitting of the refined sample points (paper §4, step 9: "Interpolate the
//! sample points with a spline curve in 3D physical space, 2D parameter space, or both").
//!
//! Local C1 cubic interpolation (Bessel tangents, chord-length parameters): each span is the
//! cubic Hermite piece between consecutive points, written as a cubic B-spline with
//! interior knots (triple, so each span is its own Bézier piece; C1 because the Hermite
//! tangents agree). It passes through every refined point (so it lies within the refinement
//! tolerance of them), costs O(n) without a linear system, and a change to one point moves
//! only the neighbouring spans.

use super::report::FitOut;
use crate::spline::{BSplineCurve, KnotVector};

/// A fitted curve and the points it interpolates, in parameter order.
pub type Fitted<const D: usize> = (BSplineCurve<[f64; D]>, Vec<[f64; D]>);

/// Cubic C1 B-spline through `pts` (consecutive duplicates removed), with the points it
/// interpolates in parameter order. `None` for fewer than two distinct points.
///
/// Chord lengths are measured on the first `metric` coordinates only, so 3D points carrying
/// their `(u, v)` parameters as extra coordinates get one parametrization for all of them.
pub fn fit_cubic<const D: usize>(
    pts: &[[f64; D]],
    closed: bool,
    metric: usize,
) -> Option<Fitted<D>> {
    let m = metric.min(D);
    let d = |a: &[f64; D], b: &[f64; D]| (0..m).map(|k| (a[k] - b[k]).powi(2)).sum::<f64>().sqrt();
    // Points closer than 1e-12 of the polyline's length to the previous kept one would make
    // two knots coincide after normalization: keep the first of them.
    let total: f64 = pts.windows(2).map(|w| d(&w[0], &w[1])).sum();
    let eps = total * 1e-12;
    let mut p: Vec<[f64; D]> = Vec::with_capacity(pts.len());
    for q in pts {
        if p.last().is_none_or(|l| d(l, q) > eps) {
            p.push(*q);
        }
    }
    if closed && p.len() > 2 && d(&p[0], &p[p.len() - 1]) <= eps {
        p.pop();
    }
    if p.len() < 2 {
        return None;
    }
    let n = p.len();
    // Chord lengths of the spans (closed: the closing span too).
    let spans = if closed && n > 2 { n } else { n - 1 };
    let h: Vec<f64> = (0..spans).map(|i| d(&p[i], &p[(i + 1) % n])).collect();
    if h.iter().any(|x| x.is_nan() || *x <= 0.0 || !x.is_finite()) {
        return None;
    }
    // Bessel tangent at i from the parabola through i-1, i, i+1.
    let tangent = |i: usize| -> [f64; D] {
        let diff = |a: usize, b: usize, l: f64| -> [f64; D] {
            std::array::from_fn(|k| (p[b][k] - p[a][k]) / l)
        };
        let (prev, next) = if closed && n > 2 {
            (Some((i + n - 1) % n), Some((i + 1) % n))
        } else {
            ((i > 0).then(|| i - 1), (i + 1 < n).then_some(i + 1))
        };
        match (prev, next) {
            (Some(a), Some(b)) => {
                let (h0, h1) = (h[if closed && n > 2 { a } else { i - 1 }], h[i % spans]);
                let (d0, d1) = (diff(a, i, h0), diff(i, b, h1));
                std::array::from_fn(|k| (h1 * d0[k] + h0 * d1[k]) / (h0 + h1))
            }
            (None, Some(b)) => {
                if n == 2 {
                    diff(i, b, h[0])
                } else {
                    let (d0, d1) = (diff(0, 1, h[0]), diff(1, 2, h[1]));
                    std::array::from_fn(|k| d0[k] + (d0[k] - d1[k]) * h[0] / (h[0] + h[1]))
                }
            }
            (Some(a), None) => {
                if n == 2 {
                    diff(a, i, h[0])
                } else {
                    let (d0, d1) = (diff(n - 3, n - 2, h[n - 3]), diff(n - 2, n - 1, h[n - 2]));
                    std::array::from_fn(|k| {
                        d1[k] + (d1[k] - d0[k]) * h[n - 2] / (h[n - 3] + h[n - 2])
                    })
                }
            }
            (None, None) => [0.0; D],
        }
    };
    let tan: Vec<[f64; D]> = (0..n).map(tangent).collect();
    let mut knots = vec![0.0; 4];
    let mut ctrl = vec![p[0]];
    let mut t = 0.0;
    for i in 0..spans {
        let j = (i + 1) % n;
        let hi = h[i];
        ctrl.push(std::array::from_fn(|k| p[i][k] + hi / 3.0 * tan[i][k]));
        ctrl.push(std::array::from_fn(|k| p[j][k] - hi / 3.0 * tan[j][k]));
        ctrl.push(p[j]);
        t += hi;
        if i + 1 < spans {
            knots.extend([t; 3]);
        }
    }
    knots.extend([t; 4]);
    let kv = KnotVector::new(knots.iter().map(|k| k / t).collect(), 3, ctrl.len()).ok()?;
    if closed && n > 2 {
        p.push(p[0]);
    }
    Some((
        BSplineCurve {
            knots: kv,
            control: ctrl,
        },
        p,
    ))
}

/// The fit of a branch: 3D points with their parameters on both surfaces, one
/// parametrization (3D chord length) for all three curves.
pub fn fit_branch(
    points: &[[f64; 3]],
    uv_a: &[[f64; 2]],
    uv_b: &[[f64; 2]],
    closed: bool,
) -> Option<FitOut> {
    let packed = super::hermite::pack(points, uv_a, uv_b);
    fit_cubic(&packed, closed, 3).map(|(c, used)| fit_out(&c, &used))
}

/// The report of a packed `(x, y, z, u_A, v_A, s_B, t_B)` cubic through `pts` at its knots.
fn fit_out(c: &BSplineCurve<[f64; 7]>, pts: &[[f64; 7]]) -> FitOut {
    FitOut {
        degree: 3,
        knots: c.knots.knots().to_vec(),
        control_points: c.control.iter().map(|p| [p[0], p[1], p[2]]).collect(),
        control_points_uv_a: c.control.iter().map(|p| [p[3], p[4]]).collect(),
        control_points_uv_b: c.control.iter().map(|p| [p[5], p[6]]).collect(),
        max_deviation_at_points: max_deviation_at_points(c, pts, 3),
    }
}

/// The cubic pieces of a branch ([`super::hermite`]) as one cubic B-spline in 3D and in both
/// domains: the pieces' own Bézier control points `p, p + H'(0)/3, q − H'(1)/3, q`, interior
/// knots triple at the cumulative chord lengths (normalized to `[0, 1]`), so each span is
/// exactly its piece (G1 at the points, C1 where consecutive pieces' derivatives match the
/// chord lengths). Pieces shorter than 1e-12 of the whole are skipped. `None` without a piece.
pub fn fit_pieces(pieces: &[super::hermite::Piece]) -> Option<FitOut> {
    let len = |h: &super::hermite::Piece| {
        (0..3)
            .map(|k| (h.q[k] - h.p[k]).powi(2))
            .sum::<f64>()
            .sqrt()
    };
    // Pieces shorter than 1e-12 of the whole would make knots coincide once normalized.
    let eps = 1e-12 * pieces.iter().map(len).sum::<f64>();
    let used: Vec<&super::hermite::Piece> = pieces.iter().filter(|h| len(h) > eps).collect();
    let first = used.first()?;
    let mut ctrl: Vec<[f64; 7]> = vec![first.p];
    let mut knots = vec![0.0; 4];
    let mut pts = vec![first.p];
    let mut t = 0.0;
    for (i, h) in used.iter().enumerate() {
        ctrl.push(std::array::from_fn(|k| h.p[k] + h.dp[k] / 3.0));
        ctrl.push(std::array::from_fn(|k| h.q[k] - h.dq[k] / 3.0));
        ctrl.push(h.q);
        pts.push(h.q);
        t += len(h);
        if i + 1 < used.len() {
            knots.extend([t; 3]);
        }
    }
    knots.extend([t; 4]);
    let kv = KnotVector::new(knots.iter().map(|k| k / t).collect(), 3, ctrl.len()).ok()?;
    let c = BSplineCurve {
        knots: kv,
        control: ctrl,
    };
    Some(fit_out(&c, &pts))
}

/// Largest distance between the fit and the points at the fit's own knots (evidence of the
/// interpolation property, measured, not assumed).
pub fn max_deviation_at_points<const D: usize>(
    c: &BSplineCurve<[f64; D]>,
    pts: &[[f64; D]],
    metric: usize,
) -> f64 {
    let mut ks: Vec<f64> = c.knots.knots().to_vec();
    ks.dedup();
    let mut worst = 0.0f64;
    for (k, t) in ks.iter().enumerate() {
        if let Some(p) = pts.get(k) {
            let q = c.eval(t);
            let d = (0..metric.min(D))
                .map(|i| (q[i] - p[i]).powi(2))
                .sum::<f64>()
                .sqrt();
            worst = worst.max(d);
        }
    }
    worst
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The fit exists, interpolates, and is C1 at the joints (tangent directions agree).
    #[test]
    fn fit_interpolates_and_is_c1() {
        let pts: Vec<[f64; 3]> = (0..12)
            .map(|k| {
                let t = k as f64 * 0.5;
                [t.cos(), t.sin(), 0.1 * t]
            })
            .collect();
        for closed in [false, true] {
            let (c, used) = fit_cubic(&pts, closed, 3).expect("fit");
            assert!(max_deviation_at_points(&c, &used, 3) < 1e-14);
            let mut ks: Vec<f64> = c.knots.knots().to_vec();
            ks.dedup();
            for t in &ks[1..ks.len() - 1] {
                let (a, b) = (c.eval(&(t - 1e-7)), c.eval(&(t + 1e-7)));
                let (a2, b2) = (c.eval(&(t - 2e-7)), c.eval(&(t + 2e-7)));
                let d1: [f64; 3] = std::array::from_fn(|k| a[k] - a2[k]);
                let d2: [f64; 3] = std::array::from_fn(|k| b2[k] - b[k]);
                let n1 = (d1[0] * d1[0] + d1[1] * d1[1] + d1[2] * d1[2]).sqrt();
                let n2 = (d2[0] * d2[0] + d2[1] * d2[1] + d2[2] * d2[2]).sqrt();
                let cos = (d1[0] * d2[0] + d1[1] * d2[1] + d1[2] * d2[2]) / (n1 * n2);
                assert!(cos > 1.0 - 1e-6, "kink at {t}: cos {cos}");
            }
        }
    }
}
