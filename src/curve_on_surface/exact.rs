//! The exact path of the curve-on-surface computation (Yang et al., CAD 2008): steps 1–6 run
//! in Rational throughout — Bézier patches and splitting, single-sided pieces, the
//! distance bound, the ε_T pass and the exact mapping by blossoming (rational surfaces by the
//! centring of `float::rational`, in exact arithmetic) — the reference against
//! which the f64 path ([`super::float`]) is checked, and its fallback when an enclosure
//! cannot decide.

use super::{Chain, ChainSegment, CosError, Params, cells, distance, g1, map, sidedness, split};
use crate::spline::{BSplineCurve, BSplineSurface};

/// The steps in exact arithmetic (Rational throughout).
pub(super) fn exact_chain(
    s: &BSplineSurface<[f64; 3]>,
    weights: Option<&[f64]>,
    d: &BSplineCurve<[f64; 2]>,
    params: &Params,
    progress: &mut dyn FnMut(&str, usize),
) -> Result<Chain, CosError> {
    if let Some(w) = weights.filter(|w| w.len() != s.net.len()) {
        return Err(
            super::CosInternal::Curve(crate::spline::SplineError::NetSize {
                got: w.len(),
                expected: s.net.len(),
                what: "weights",
            })
            .into(),
        );
    }
    let cells =
        cells::Cells::new(s, weights, params.eps_d).map_err(|cell| CosError::Weight { cell })?;
    let (pieces, segs) = split::split(d, &cells)?;
    progress("split at knots and knot lines", segs.len());
    let n_pieces = pieces.len();
    let after_split = segs.len();
    let (segs, side) = sidedness::make_single_sided(segs, &pieces, &cells);
    let distance = |segs| {
        distance::enforce_distance(
            segs,
            &pieces,
            &cells,
            params.eps_d,
            params.bound,
            params.max_segments,
        )
    };
    let segs = distance(segs)?;
    let after_distance = segs.len();
    progress("distance bound", segs.len());
    let closed = segs.first().map(|f| f.a) == segs.last().map(|l| l.b)
        && segs.len() > 1
        && d.eval(&d.domain().0) == d.eval(&d.domain().1);
    let (segs, g1s) = g1::enforce_g1(
        segs,
        &pieces,
        &cells,
        params.eps_t_deg,
        closed,
        params.max_segments,
    );
    let segs = distance(segs)?;
    progress("eps_T pass", segs.len());
    let (mapped, rounding) = map::map_segments(&segs, &cells)?;
    progress("mapped exactly", mapped.len());
    let joints_exact = mapped
        .windows(2)
        .all(|w| w[0].exact.control.last() == w[1].exact.control.first());
    Ok(Chain {
        segments: mapped
            .into_iter()
            .zip(&segs)
            .map(|(m, x)| ChainSegment {
                control_points: m.control_points,
                weights: m.weights,
                domain: m.domain,
                bound: (x.k * x.h).next_up(),
                domain_curve: (params.evidence_samples > 0)
                    .then(|| x.curve(&pieces).map(crate::geom::to_f64_point)),
            })
            .collect(),
        rounding,
        joints_exact,
        side,
        g1: g1s,
        bezier_patches: cells.cells.len(),
        patches_built: cells.cells.len(),
        domain_bezier_pieces: n_pieces,
        after_split,
        after_distance,
        min_2d_tolerance: cells
            .cells
            .iter()
            .map(|c| c.d)
            .fold(f64::INFINITY, f64::min),
        arithmetic: "exact (Rational)".into(),
    })
}
