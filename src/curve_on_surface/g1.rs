//! Step 5 — the ε_T–G1 pass (eqs. 18–22). The mapped segment `S(P_0 + t (P_n - P_0))` has end
//! derivatives `(u_n - u_0) S_u + (v_n - v_0) S_v` (eq. 20, with `S_u`, `S_v` from the patch
//! hodographs, eqs. 21–22, scaled to global parameters). Where adjacent mapped segments meet
//! at an angle above ε_T, the segment with the greater deviation is split at its farthest
//! point; Theorem 1 keeps the distance bound (and the bound is recomputed anyway).
//!
//! Angles are computed in f64 from the rounded patch control points (reported as such).
//! A junction where even tiny segments keep the angle above ε_T (a corner of D or of S) is
//! left, counted and reported.

use super::cells::Cells;
use super::hausdorff::farthest_parameter;
use super::segments::Seg;
use crate::geom::{dot, norm};
use crate::scalar::Rational;
use crate::spline::{BezierCurve, BezierSurface};

type Q = Rational;

/// Smallest parameter length (relative to the piece) a segment is split down to for ε_T.
const MIN_PARAM_LEN: f64 = 1e-10;
/// Most ε_T splits in the line of descent of one segment. A junction still above ε_T after
/// this many splits on either side is a corner (of D, of S, or a cusp where D doubles back
/// with zero speed): splitting cannot remove it, and without the cap the splits at such a
/// point grow the segment count by thousands before `MIN_PARAM_LEN` stops them.
pub const MAX_SPLIT_DEPTH: u32 = 24;

/// End tangent (`at_end`) or start tangent of the image of the chord `a → b` on a patch
/// over `rect = [u0, u1, v0, v1]`: `(Δu / (u1 - u0)) S_s + (Δv / (v1 - v0)) S_r` (eq. 20).
pub fn mapped_tangent(
    patch: &BezierSurface<[f64; 3]>,
    rect: [f64; 4],
    a: &[f64; 2],
    b: &[f64; 2],
    at_end: bool,
) -> [f64; 3] {
    let hodographs = (patch.hodograph_u(), patch.hodograph_v());
    mapped_tangent_with(&hodographs, rect, a, b, at_end)
}

/// [`mapped_tangent`] with the patch's hodographs `(S_s, S_r)` given.
pub fn mapped_tangent_with(
    hodographs: &Hodographs,
    rect: [f64; 4],
    a: &[f64; 2],
    b: &[f64; 2],
    at_end: bool,
) -> [f64; 3] {
    let ([lu, lv], [du, dv]) = chord_local(rect, a, b, at_end);
    let su = hodographs
        .0
        .as_ref()
        .map(|h| eval_tensor(h, lu, lv))
        .unwrap_or([0.0; 3]);
    let sv = hodographs
        .1
        .as_ref()
        .map(|h| eval_tensor(h, lu, lv))
        .unwrap_or([0.0; 3]);
    std::array::from_fn(|i| du * su[i] + dv * sv[i])
}

/// The chord `a → b`'s start (or end, `at_end`) and its step in the local coordinates of the
/// patch over `rect`.
fn chord_local(rect: [f64; 4], a: &[f64; 2], b: &[f64; 2], at_end: bool) -> ([f64; 2], [f64; 2]) {
    let p = if at_end { b } else { a };
    let (wu, wv) = (rect[1] - rect[0], rect[3] - rect[2]);
    (
        [(p[0] - rect[0]) / wu, (p[1] - rect[2]) / wv],
        [(b[0] - a[0]) / wu, (b[1] - a[1]) / wv],
    )
}

/// Tensor-product de Casteljau in f64 without allocation (degrees below 16; larger ones use
/// the general evaluator).
pub(crate) fn eval_tensor(s: &BezierSurface<[f64; 3]>, u: f64, v: f64) -> [f64; 3] {
    if let Some(x) = super::casteljau::eval_tensor(&s.net, s.p + 1, s.q + 1, u, v) {
        return x;
    }
    if s.p >= 16 || s.q >= 16 {
        return s.eval(&u, &v);
    }
    let casteljau = |w: &mut arrayvec::ArrayVec<[f64; 3], 16>, t: f64| {
        let n = w.len() - 1;
        for r in 1..=n {
            for i in 0..=n - r {
                for c in 0..3 {
                    w[i][c] = (1.0 - t) * w[i][c] + t * w[i + 1][c];
                }
            }
        }
        w[0]
    };
    let mut col: arrayvec::ArrayVec<[f64; 3], 16> = arrayvec::ArrayVec::new();
    for i in 0..=s.p {
        let mut row: arrayvec::ArrayVec<[f64; 3], 16> = s.net[i * (s.q + 1)..(i + 1) * (s.q + 1)]
            .iter()
            .copied()
            .collect();
        col.push(casteljau(&mut row, v));
    }
    casteljau(&mut col, u)
}

/// The hodographs `(S_s, S_r)` of a patch in local coordinates (`None`: degree 0).
pub type Hodographs = (
    Option<BezierSurface<[f64; 3]>>,
    Option<BezierSurface<[f64; 3]>>,
);

/// Angle in degrees between two tangents; `None` when one vanishes.
pub fn angle_deg(t0: &[f64; 3], t1: &[f64; 3]) -> Option<f64> {
    let (n0, n1) = (norm(t0), norm(t1));
    if n0 == 0.0 || n1 == 0.0 {
        return None;
    }
    Some(
        (dot(t0, t1) / (n0 * n1))
            .clamp(-1.0, 1.0)
            .acos()
            .to_degrees(),
    )
}

fn tangent(cells: &Cells, s: &Seg, at_end: bool) -> [f64; 3] {
    let c = &cells.cells[s.cell];
    let rect = [c.u0, c.u1, c.v0, c.v1];
    match &c.rational {
        None => mapped_tangent(&c.patch_f64, rect, &s.a, &s.b, at_end),
        Some(r) => rational_tangent(&r.q_f64, &r.w_f64, rect, &s.a, &s.b, at_end),
    }
}

/// A patch in f64 with its hodographs, made once per cell for the tangents of the ε_T pass.
#[derive(Clone, Debug)]
pub struct F64Patch {
    pub patch: BezierSurface<[f64; 3]>,
    pub hodographs: Hodographs,
}

impl F64Patch {
    pub fn new(patch: BezierSurface<[f64; 3]>) -> F64Patch {
        F64Patch {
            hodographs: (patch.hodograph_u(), patch.hodograph_v()),
            patch,
        }
    }
}

/// [`mapped_tangent`] on a rational patch `S = c + Q / W` (`q` the centred numerator, `w`
/// the weights in coordinate 0): by the quotient rule `S_s ∝ Q_s W − Q W_s` (`W > 0` only
/// scales), combined as in eq. (20).
pub fn rational_tangent(
    q: &F64Patch,
    w: &F64Patch,
    rect: [f64; 4],
    a: &[f64; 2],
    b: &[f64; 2],
    at_end: bool,
) -> [f64; 3] {
    let ([lu, lv], [du, dv]) = chord_local(rect, a, b, at_end);
    let at = |s: &Option<BezierSurface<[f64; 3]>>| {
        s.as_ref()
            .map(|s| eval_tensor(s, lu, lv))
            .unwrap_or([0.0; 3])
    };
    let (qv, wv) = (
        eval_tensor(&q.patch, lu, lv),
        eval_tensor(&w.patch, lu, lv)[0],
    );
    let (qu, qr) = (at(&q.hodographs.0), at(&q.hodographs.1));
    let (wu, wr) = (at(&w.hodographs.0)[0], at(&w.hodographs.1)[0]);
    std::array::from_fn(|i| du * (qu[i] * wv - qv[i] * wu) + dv * (qr[i] * wv - qv[i] * wr))
}

/// Angle in degrees between the end tangent of `x` and the start tangent of `y`.
pub fn junction_angle(cells: &Cells, x: &Seg, y: &Seg) -> Option<f64> {
    angle_deg(&tangent(cells, x, true), &tangent(cells, y, false))
}

/// Result of the pass.
#[derive(Clone, Copy, Debug, Default, serde::Serialize)]
pub struct G1Stats {
    pub splits: usize,
    /// Junctions left above ε_T (corners of the curve or the surface).
    pub unresolved_junctions: usize,
    pub max_angle_deg: f64,
}

/// Split until every junction is within `eps_t_deg` (or cannot be improved). `closed`: the
/// polyline is a loop and the last segment joins the first.
pub fn enforce_g1(
    segs: Vec<Seg>,
    pieces: &[BezierCurve<[Q; 2]>],
    cells: &Cells,
    eps_t_deg: f64,
    closed: bool,
    max_segments: usize,
) -> (Vec<Seg>, G1Stats) {
    enforce_g1_with(
        segs,
        eps_t_deg,
        closed,
        max_segments,
        &G1Ops {
            tangents: |x: &Seg| Some((tangent(cells, x, false), tangent(cells, x, true))),
            deviation: |s: &Seg| s.h,
            param_len: |s: &Seg| crate::Scalar::to_f64(&(s.t1.clone() - s.t0.clone())),
            split: |s: &Seg| {
                let c = s.curve(pieces);
                // Theorem 1: sub-pieces of a single-sided piece stay within d; the bound is
                // recomputed anyway (split resets it).
                Some(s.split(&farthest_parameter(&c), pieces, cells))
            },
        },
    )
}

/// What the ε_T pass needs of a segment type.
pub struct G1Ops<A, D, L, P> {
    /// Start and end tangents of a segment's image (`None`: not available).
    pub tangents: A,
    /// The segment's current 2D deviation `h` (the one with the greater is split).
    pub deviation: D,
    /// Parameter length relative to its piece.
    pub param_len: L,
    /// Split at the farthest point (`None`: cannot).
    pub split: P,
}

/// The ε_T pass over any segment type.
pub fn enforce_g1_with<S, A, D, L, P>(
    mut segs: Vec<S>,
    eps_t_deg: f64,
    closed: bool,
    max_segments: usize,
    ops: &G1Ops<A, D, L, P>,
) -> (Vec<S>, G1Stats)
where
    A: Fn(&S) -> Option<([f64; 3], [f64; 3])>,
    D: Fn(&S) -> f64,
    L: Fn(&S) -> f64,
    P: Fn(&S) -> Option<(S, S)>,
{
    let mut stats = G1Stats::default();
    let pairs = |n: usize| {
        if closed && n > 1 {
            n
        } else {
            n.saturating_sub(1)
        }
    };
    // Tangents per segment, computed once per segment (splits replace them), and the number
    // of ε_T splits each segment descends from.
    let mut tan: Vec<Option<([f64; 3], [f64; 3])>> = segs.iter().map(&ops.tangents).collect();
    let mut depth: Vec<u32> = vec![0; segs.len()];
    let splittable = |s: &S, d: u32| d < MAX_SPLIT_DEPTH && (ops.param_len)(s) > MIN_PARAM_LEN;
    loop {
        let n = segs.len();
        let mut split = vec![false; n];
        let mut unresolved = 0;
        let mut pass_max = 0.0f64;
        for i in 0..pairs(n) {
            let j = (i + 1) % n;
            let angle = match (&tan[i], &tan[j]) {
                (Some(a), Some(b)) => angle_deg(&a.1, &b.0),
                _ => None,
            };
            pass_max = pass_max.max(angle.unwrap_or(0.0));
            if let Some(a) = angle
                && a > eps_t_deg
            {
                let k = if (ops.deviation)(&segs[i]) >= (ops.deviation)(&segs[j]) {
                    i
                } else {
                    j
                };
                let other = if k == i { j } else { i };
                if splittable(&segs[k], depth[k]) {
                    split[k] = true;
                } else if splittable(&segs[other], depth[other]) {
                    split[other] = true;
                } else {
                    unresolved += 1;
                }
            }
        }
        // Every exit below leaves the segments as this pass measured them.
        stats.max_angle_deg = pass_max;
        if !split.contains(&true) || n >= max_segments {
            stats.unresolved_junctions = unresolved;
            break;
        }
        let mut out = Vec::with_capacity(n * 2);
        let mut out_tan = Vec::with_capacity(n * 2);
        let mut out_depth = Vec::with_capacity(n * 2);
        let mut failed = 0;
        for (((s, sp), t), d) in segs.into_iter().zip(split).zip(tan).zip(depth) {
            match if sp { (ops.split)(&s) } else { None } {
                Some((l, r)) => {
                    stats.splits += 1;
                    out_tan.push((ops.tangents)(&l));
                    out_tan.push((ops.tangents)(&r));
                    out_depth.extend([d + 1, d + 1]);
                    out.push(l);
                    out.push(r);
                }
                None => {
                    failed += usize::from(sp);
                    out_tan.push(t);
                    out_depth.push(d);
                    out.push(s);
                }
            }
        }
        segs = out;
        tan = out_tan;
        depth = out_depth;
        if segs.len() == n {
            // No split was possible: those junctions stay.
            stats.unresolved_junctions = unresolved + failed;
            break;
        }
    }
    (segs, stats)
}
