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
use crate::spline::BezierCurve;
use num_rational::BigRational;

type Q = BigRational;

/// Smallest parameter length (relative to the piece) a segment is split down to for ε_T.
const MIN_PARAM_LEN: f64 = 1e-10;

fn tangent(cells: &Cells, s: &Seg, at_end: bool) -> [f64; 3] {
    let c = &cells.cells[s.cell];
    let p = if at_end { s.b } else { s.a };
    let (lu, lv) = ((p[0] - c.u0) / (c.u1 - c.u0), (p[1] - c.v0) / (c.v1 - c.v0));
    let su = c
        .patch_f64
        .hodograph_u()
        .map(|h| h.eval(&lu, &lv))
        .unwrap_or([0.0; 3]);
    let sv = c
        .patch_f64
        .hodograph_v()
        .map(|h| h.eval(&lu, &lv))
        .unwrap_or([0.0; 3]);
    let du = (s.b[0] - s.a[0]) / (c.u1 - c.u0);
    let dv = (s.b[1] - s.a[1]) / (c.v1 - c.v0);
    std::array::from_fn(|i| du * su[i] + dv * sv[i])
}

/// Angle in degrees between the end tangent of `x` and the start tangent of `y`.
pub fn junction_angle(cells: &Cells, x: &Seg, y: &Seg) -> Option<f64> {
    let (t0, t1) = (tangent(cells, x, true), tangent(cells, y, false));
    let (n0, n1) = (norm(&t0), norm(&t1));
    if n0 == 0.0 || n1 == 0.0 {
        return None;
    }
    Some(
        (dot(&t0, &t1) / (n0 * n1))
            .clamp(-1.0, 1.0)
            .acos()
            .to_degrees(),
    )
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
    mut segs: Vec<Seg>,
    pieces: &[BezierCurve<[Q; 2]>],
    cells: &Cells,
    eps_t_deg: f64,
    closed: bool,
    max_segments: usize,
) -> (Vec<Seg>, G1Stats) {
    let mut stats = G1Stats::default();
    let plen = |s: &Seg| crate::Scalar::to_f64(&(s.t1.clone() - s.t0.clone()));
    loop {
        let n = segs.len();
        let mut split = vec![false; n];
        let mut unresolved = 0;
        let pairs = if closed && n > 1 {
            n
        } else {
            n.saturating_sub(1)
        };
        for i in 0..pairs {
            let j = (i + 1) % n;
            if let Some(a) = junction_angle(cells, &segs[i], &segs[j])
                && a > eps_t_deg
            {
                let k = if segs[i].h >= segs[j].h { i } else { j };
                let other = if k == i { j } else { i };
                if plen(&segs[k]) > MIN_PARAM_LEN {
                    split[k] = true;
                } else if plen(&segs[other]) > MIN_PARAM_LEN {
                    split[other] = true;
                } else {
                    unresolved += 1;
                }
            }
        }
        if !split.contains(&true) || n >= max_segments {
            stats.unresolved_junctions = unresolved;
            break;
        }
        let mut out = Vec::with_capacity(n * 2);
        for (s, sp) in segs.into_iter().zip(split) {
            if sp {
                stats.splits += 1;
                let c = s.curve(pieces);
                let (mut l, mut r) = s.split(&farthest_parameter(&c), pieces, cells);
                // Theorem 1: sub-pieces of a single-sided piece stay within d; recompute anyway.
                l.h = f64::INFINITY;
                r.h = f64::INFINITY;
                l.k = f64::INFINITY;
                r.k = f64::INFINITY;
                out.push(l);
                out.push(r);
            } else {
                out.push(s);
            }
        }
        segs = out;
    }
    let n = segs.len();
    let pairs = if closed && n > 1 {
        n
    } else {
        n.saturating_sub(1)
    };
    stats.max_angle_deg = (0..pairs)
        .filter_map(|i| junction_angle(cells, &segs[i], &segs[(i + 1) % n]))
        .fold(0.0, f64::max);
    (segs, stats)
}
