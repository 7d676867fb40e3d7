//! Interval Bézier tools for the f64 path: every routine is the blossom (de Casteljau /
//! de Boor–Ramshaw recurrence, Ramshaw 1989) evaluated in outward-rounded interval
//! arithmetic ([`Interval`]), so each result *encloses* the exact value for the exact input
//! (f64 input numbers are exact rationals). Exact operations stay points (`0·x`, `1·x`), so
//! clamped end control points come out exact.

use crate::scalar::interval::Interval;
pub use crate::spline::enclosed_bezier::{bspline_blossom, bspline_span_bezier, lerp};
use arrayvec::ArrayVec;

pub type I = Interval;
/// A point with interval coordinates.
pub type IP<const D: usize> = [I; D];

/// Largest degree handled without allocation.
pub const MAX_DEGREE: usize = 31;

/// Control points handled by the fast (midpoint–radius) path; longer lists take the
/// interval recurrence.
const FAST_CAP: usize = 12;

pub fn ip<const D: usize>(p: &[f64; D]) -> IP<D> {
    std::array::from_fn(|i| I::point(p[i]))
}

/// Midpoint–radius form of a list of boxes, for the fast path of the Bézier blossoms:
/// midpoints, the largest radius `r` (every coordinate of every true point lies within `r`
/// of its midpoint), the largest midpoint magnitude `mx`, and an upper bound `dp` of
/// `max_i |P_{i+1} - P_i|_∞` over the true points.
struct MidRad<const D: usize> {
    m: ArrayVec<[f64; D], FAST_CAP>,
    r: f64,
    mx: f64,
    dp: f64,
}

fn mid_rad<const D: usize>(ctrl: &[IP<D>]) -> MidRad<D> {
    let mut m: ArrayVec<[f64; D], FAST_CAP> = ArrayVec::new();
    let (mut r, mut mx) = (0.0f64, 0.0f64);
    for p in ctrl {
        m.push(std::array::from_fn(|c| p[c].mid()));
        for c in p {
            r = r.max(c.radius_about_mid());
            mx = mx.max(c.mid().abs());
        }
    }
    let mut dp = 0.0f64;
    for w in m.windows(2) {
        for c in 0..D {
            dp = dp.max((w[1][c] - w[0][c]).abs());
        }
    }
    // Rounding of the differences (relative u) and the true points' offsets (2r).
    let dp = (dp * (1.0 + 1e-14) + 2.0 * r) * (1.0 + 1e-14);
    MidRad { m, r, mx, dp }
}

/// Error bound of `levels` de Casteljau levels in f64 with parameters in `[0, 1]` whose
/// exact values lie within `sum_dt` (sum over the parameters) of the ones used.
///
/// One level computes `fl(fl(fl(1 - t)·a) + fl(t·b))`; with unit roundoff `u = 2^-53` its
/// distance to `(1 - t) a + t b` is at most `((1 + u)³ - 1) max(|a|, |b|) ≤ 3.0000001 u M`
/// (plus `2^-1073` for underflow), `M` bounding the values of the level; the values are
/// (rounded) convex combinations of the midpoints, so `M ≤ mx (1 + 1e-13)` for up to 32
/// levels. Convex combinations do not grow the input radius `r`. The blossom is affine in
/// each parameter with slope a blossom of the differences `P_{i+1} - P_i` (parameters in
/// `[0, 1]`), so a parameter off by `δ` moves it by at most `δ · dp`. The sum is computed in
/// f64 and enlarged by `1e-14` relatively, which dominates its own rounding (5 operations).
fn mr_error<const D: usize>(mr: &MidRad<D>, levels: usize, sum_dt: f64) -> f64 {
    (mr.r + sum_dt * mr.dp + levels as f64 * (3.4e-16 * mr.mx * (1.0 + 1e-13) + 1e-300))
        * (1.0 + 1e-14)
}

/// Bound added by `levels` de Casteljau levels with exact parameters in `[0, 1]` on values
/// of magnitude at most `mx` (the lerp lemma of `mr_error`), to an input radius `r`.
pub fn mr_levels_error(r: f64, levels: usize, mx: f64) -> f64 {
    (r + levels as f64 * (3.4e-16 * mx * (1.0 + 1e-13) + 1e-300)) * (1.0 + 1e-14)
}

/// The box `m ± r`, rounded outward.
pub fn boxed<const D: usize>(m: &[f64; D], r: f64) -> IP<D> {
    std::array::from_fn(|c| I::new((m[c] - r).next_down(), (m[c] + r).next_up()))
}

/// De Casteljau in f64 on midpoints (any number of control points).
pub(crate) fn mr_blossom<const D: usize>(m: &[[f64; D]], ts: &[f64]) -> [f64; D] {
    fn run<const D: usize>(w: &mut [[f64; D]], ts: &[f64]) -> [f64; D] {
        let n = w.len() - 1;
        for (r, &t) in ts.iter().enumerate() {
            let s = 1.0 - t;
            for i in 0..n - r {
                for c in 0..D {
                    w[i][c] = s * w[i][c] + t * w[i + 1][c];
                }
            }
        }
        w[0]
    }
    if m.len() <= FAST_CAP {
        let mut w: ArrayVec<[f64; D], FAST_CAP> = m.iter().copied().collect();
        run(&mut w, ts)
    } else {
        run(&mut m.to_vec(), ts)
    }
}

/// Parameters for the fast path: midpoints and the sum of radii, when every parameter lies
/// in `[0, 1]`.
fn fast_params(ts: &[I], n_ctrl: usize) -> Option<(ArrayVec<f64, FAST_CAP>, f64)> {
    if n_ctrl <= FAST_CAP && ts.len() <= FAST_CAP && ts.iter().all(|t| t.lo >= 0.0 && t.hi <= 1.0) {
        let mids = ts.iter().map(|t| t.mid().clamp(0.0, 1.0)).collect();
        let dt = ts.iter().map(|t| t.radius_about_mid()).sum::<f64>() * (1.0 + 1e-14);
        Some((mids, dt))
    } else {
        None
    }
}

/// Blossom `b(t_1, …, t_n)` of the Bézier curve with control points `ctrl` (degree
/// `n = ctrl.len() - 1 = ts.len()`), enclosed. Parameters inside `[0, 1]` take the fast
/// path (f64 de Casteljau on midpoints with the error bound of `mr_error`); others the
/// interval recurrence.
pub fn blossom<const D: usize>(ctrl: &[IP<D>], ts: &[I]) -> IP<D> {
    debug_assert_eq!(ts.len(), ctrl.len() - 1);
    if let Some((t, dt)) = fast_params(ts, ctrl.len()) {
        let mr = mid_rad(ctrl);
        return boxed(&mr_blossom(&mr.m, &t), mr_error(&mr, ts.len(), dt));
    }
    blossom_interval(ctrl, ts)
}

/// The interval recurrence (any parameters).
pub fn blossom_interval<const D: usize>(ctrl: &[IP<D>], ts: &[I]) -> IP<D> {
    let mut w: ArrayVec<IP<D>, 32> = ctrl.iter().copied().collect();
    let n = ctrl.len() - 1;
    for (r, t) in ts.iter().enumerate() {
        for i in 0..n - r {
            w[i] = lerp(&w[i], &w[i + 1], *t);
        }
    }
    w[0]
}

/// Polar values `b(x^(n-j), y^j)`, `j = 0..=n`: the control points of the curve restricted
/// to `[x, y]` (reparametrized to `[0, 1]`).
pub fn polar_values<const D: usize>(ctrl: &[IP<D>], x: I, y: I) -> Vec<IP<D>> {
    let n = ctrl.len() - 1;
    if let Some((t, dt)) = fast_params(&[x, y], ctrl.len()) {
        // Each polar value uses `n` parameters, each within `dt` (the larger radius).
        let mr = mid_rad(ctrl);
        let err = mr_error(&mr, n, dt * n as f64);
        let mut vals: Vec<[f64; D]> = Vec::with_capacity(n + 1);
        mr_polar_values(&mr.m, t[0], t[1], &mut vals);
        return vals.iter().map(|v| boxed(v, err)).collect();
    }
    let mut ts: ArrayVec<I, 32> = ArrayVec::new();
    (0..=n)
        .map(|j| {
            ts.clear();
            ts.extend(std::iter::repeat_n(x, n - j));
            ts.extend(std::iter::repeat_n(y, j));
            blossom_interval(ctrl, &ts)
        })
        .collect()
}

/// Enclosure of `C(t)` (for an interval `t`, of `{C(t) : t ∈ t}` by inclusion isotonicity).
pub fn eval<const D: usize>(ctrl: &[IP<D>], t: I) -> IP<D> {
    let n = ctrl.len() - 1;
    let ts: ArrayVec<I, 32> = std::iter::repeat_n(t, n).collect();
    if t.lo == t.hi {
        blossom(ctrl, &ts)
    } else {
        blossom_interval(ctrl, &ts)
    }
}

/// De Casteljau halves at `t = 1/2`.
pub fn halves<const D: usize>(ctrl: &[IP<D>]) -> (Vec<IP<D>>, Vec<IP<D>>) {
    split_at(ctrl, 0.5)
}

/// De Casteljau split at the point parameter `t ∈ [0, 1]`: control points of `[0, t]` and
/// `[t, 1]` (f64 triangle on midpoints; every output is at most `n` levels deep).
pub fn split_at<const D: usize>(ctrl: &[IP<D>], t: f64) -> (Vec<IP<D>>, Vec<IP<D>>) {
    let n = ctrl.len() - 1;
    if ctrl.len() > FAST_CAP {
        let ti = I::point(t);
        let mut w: Vec<IP<D>> = ctrl.to_vec();
        let mut left = Vec::with_capacity(n + 1);
        let mut right = vec![w[n]; n + 1];
        left.push(w[0]);
        for r in 1..=n {
            for i in 0..=n - r {
                w[i] = lerp(&w[i], &w[i + 1], ti);
            }
            left.push(w[0]);
            right[n - r] = w[n - r];
        }
        return (left, right);
    }
    let mr = mid_rad(ctrl);
    let err = mr_error(&mr, n, 0.0);
    let mut w = mr.m;
    let mut left = Vec::with_capacity(n + 1);
    let mut right = vec![boxed(&w[n], err); n + 1];
    left.push(boxed(&w[0], err));
    let s = 1.0 - t;
    for r in 1..=n {
        for i in 0..=n - r {
            for c in 0..D {
                w[i][c] = s * w[i][c] + t * w[i + 1][c];
            }
        }
        left.push(boxed(&w[0], err));
        right[n - r] = boxed(&w[n - r], err);
    }
    (left, right)
}

/// All polar values `b(x^(n-j), y^j)`, `j = 0..=n`, in f64 on midpoints, sharing work: the
/// de Casteljau levels at `y` are kept (level `j` holds the blossoms with `j` arguments `y`),
/// and each polar value applies `x` to its level `n - j` times. Every value is `n` lerp
/// levels deep with parameters in `[0, 1]` (the blossom is symmetric, so the order of the
/// arguments does not matter): the error lemma of [`mr_error`] applies as for one blossom.
/// `out` receives `n + 1` points.
pub(crate) fn mr_polar_values<const D: usize>(
    m: &[[f64; D]],
    x: f64,
    y: f64,
    out: &mut Vec<[f64; D]>,
) {
    let n = m.len() - 1;
    if n >= 16 {
        for j in 0..=n {
            let mut ts = vec![x; n - j];
            ts.extend(std::iter::repeat_n(y, j));
            out.push(mr_blossom(m, &ts));
        }
        return;
    }
    let start = out.len();
    out.resize(start + n + 1, [0.0; D]);
    crate::curve_on_surface::casteljau::polar_values(m, x, y, &mut out[start..]);
}

/// Upper bound of the Euclidean norm of every point of the box `x`.
pub fn norm_hi<const D: usize>(x: &IP<D>) -> f64 {
    I::norm_hi(x)
}

/// Upper bound of the distance from every point of the box `x` to the point `y`.
pub fn dist_hi<const D: usize>(x: &IP<D>, y: &[f64; D]) -> f64 {
    let d: IP<D> = std::array::from_fn(|i| x[i] - I::point(y[i]));
    norm_hi(&d)
}

/// Upper bound of the distance from every point of the box `x` to the segment `[a, b]`:
/// the distance to one chosen point `y` of the segment (the projection of the box's centre,
/// computed in f64 — any point of the segment gives an upper bound). With `c`, `ρ` the
/// box's centre and largest coordinate radius and `ŷ = fl(a + t (b - a))` (within
/// `3.0000001 u max|a|,|b|` per coordinate of `y`, the lerp lemma of `mr_error`), the
/// distance is at most `‖c - ŷ‖ + √2 (ρ + 3.4e-16 max|a|,|b|)`; `‖c - ŷ‖` is computed in f64
/// and enlarged by `1e-15` relatively (a few roundings), the sum likewise.
pub fn dist_to_segment_hi(x: &IP<2>, a: &[f64; 2], b: &[f64; 2]) -> f64 {
    let c = [x[0].mid(), x[1].mid()];
    let rho = x[0].radius_about_mid().max(x[1].radius_about_mid());
    dist_to_segment_mr(&c, rho, a, b)
}

/// [`dist_to_segment_hi`] for the box `c ± rho` (every coordinate).
pub fn dist_to_segment_mr(c: &[f64; 2], rho: f64, a: &[f64; 2], b: &[f64; 2]) -> f64 {
    let ab = [b[0] - a[0], b[1] - a[1]];
    let l2 = ab[0] * ab[0] + ab[1] * ab[1];
    let t = if l2 > 0.0 {
        (((c[0] - a[0]) * ab[0] + (c[1] - a[1]) * ab[1]) / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let s = 1.0 - t;
    let y = [s * a[0] + t * b[0], s * a[1] + t * b[1]];
    let (dx, dy) = (c[0] - y[0], c[1] - y[1]);
    let d = (dx * dx + dy * dy).sqrt() * (1.0 + 1e-15);
    let mag = a[0].abs().max(a[1].abs()).max(b[0].abs()).max(b[1].abs());
    ((d + std::f64::consts::SQRT_2 * 1.000001 * (rho + 3.4e-16 * mag + 1e-300)) * (1.0 + 1e-15))
        .next_up()
}

/// Midpoints (the f64 representative) of a box.
pub fn mid<const D: usize>(x: &IP<D>) -> [f64; D] {
    std::array::from_fn(|i| x[i].mid())
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::curve_on_surface::float::midpatch::IPatch;
    use crate::scalar::Rational;
    use crate::spline::{BSplineCurve, BezierSurface, KnotVector};

    fn q(x: f64) -> Rational {
        crate::scalar::lift(x)
    }
    fn contains(x: &I, e: &Rational) -> bool {
        q(x.lo) <= *e && *e <= q(x.hi)
    }

    #[test]
    fn span_extraction_encloses_exact_bezier_pieces() {
        let knots = vec![0.0, 0.0, 0.0, 0.0, 0.3, 0.35, 0.35, 0.9, 1.0, 1.0, 1.0, 1.0];
        let ctrl: Vec<[f64; 2]> = (0..8)
            .map(|i| [i as f64 * 0.37 - 1.0, ((i * 7) % 5) as f64 * 0.11])
            .collect();
        let c = BSplineCurve::new(knots.clone(), 3, ctrl.clone()).unwrap();
        let cq: BSplineCurve<[Rational; 2]> = c.map(|k| q(*k), crate::geom::lift_point);
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
        let sq = s.map(crate::geom::lift_point::<Rational, 3>);
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

    /// xorshift values with magnitudes over many binades (so rounding is exercised).
    pub(crate) fn rng(seed: u64) -> impl FnMut() -> f64 {
        let mut state = seed | 1;
        move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            let m = (state >> 11) as f64 / (1u64 << 53) as f64 - 0.5;
            m * 2f64.powi(((state >> 3) % 40) as i32 - 20)
        }
    }

    pub(crate) fn q_(x: f64) -> Rational {
        crate::scalar::lift(x)
    }

    #[test]
    fn midpoint_radius_blossoms_enclose_exact_values() {
        let mut r = rng(3);
        for trial in 0..200 {
            let n = 1 + trial % 6;
            let ctrl: Vec<[f64; 2]> = (0..=n).map(|_| [r(), r()]).collect();
            let exact = crate::spline::BezierCurve::new(
                ctrl.iter()
                    .map(crate::geom::lift_point::<Rational, 2>)
                    .collect(),
            )
            .unwrap();
            let ictrl: Vec<IP<2>> = ctrl.iter().map(ip).collect();
            let (x, y) = (r().abs().min(1.0), r().abs().min(1.0));
            let pv = polar_values(&ictrl, I::point(x), I::point(y));
            for (j, v) in pv.iter().enumerate() {
                let mut ts = vec![q_(x); n - j];
                ts.extend(std::iter::repeat_n(q_(y), j));
                let e = exact.blossom(&ts);
                assert!(
                    contains(&v[0], &e[0]) && contains(&v[1], &e[1]),
                    "trial {trial}"
                );
            }
            let (l, rr) = split_at(&ictrl, 0.5 - 1.0 / 2048.0);
            let (el, er) = exact.subdivide(&q_(0.5 - 1.0 / 2048.0));
            for (v, e) in l.iter().zip(&el.control).chain(rr.iter().zip(&er.control)) {
                assert!(
                    contains(&v[0], &e[0]) && contains(&v[1], &e[1]),
                    "trial {trial}"
                );
            }
        }
    }
}
