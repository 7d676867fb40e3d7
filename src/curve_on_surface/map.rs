//! Step 6 — map each final chord to a Bézier curve of degree `p + q` lying exactly on S, by
//! blossoming (`spline::compose::compose_line`, DeRose): computed in exact arithmetic from
//! the exact patch, then rounded to f64 for output with the rounding error measured exactly.

use super::CosError;
use super::cells::Cells;
use super::segments::Seg;
use crate::curve_on_surface::CosInternal;
use crate::geom::{Point, to_f64_point};
use crate::scalar::{Rational, Scalar};
use crate::spline::BezierCurve;
use crate::spline::compose::compose_line;

type Q = Rational;

/// A mapped segment.
#[derive(Clone, Debug)]
pub struct MappedSegment {
    /// Exact control points (Rational): the image of the chord, exactly.
    pub exact: BezierCurve<[Q; 3]>,
    /// The same, rounded to f64.
    pub control_points: Vec<[f64; 3]>,
    /// For a rational surface: the weights, rounded to f64 (the exact curve's control
    /// points are then `exact`'s, its weights the exact blossoms of `W`).
    pub weights: Option<Vec<f64>>,
    /// Chord end points in the domain.
    pub domain: [[f64; 2]; 2],
    pub cell: usize,
}

/// Map every segment; also returns the largest coordinate rounding error of the f64 output.
pub fn map_segments(segs: &[Seg], cells: &Cells) -> Result<(Vec<MappedSegment>, f64), CosError> {
    let zero = Q::ZERO;
    let one = Q::ONE;
    let mut out = Vec::with_capacity(segs.len());
    let mut rounding = 0.0f64;
    for s in segs {
        let (a, b) = (cells.local(s.cell, &s.a), cells.local(s.cell, &s.b));
        // The chord must lie in its patch: then its image is on S exactly.
        for x in a.iter().chain(b.iter()) {
            if *x < zero || *x > one {
                return Err(CosInternal::ChordLeavesPatch { a: s.a, b: s.b }.into());
            }
        }
        let (exact, hom_w) = match &cells.cells[s.cell].rational {
            None => (compose_line(&cells.cells[s.cell].patch, &a, &b), None),
            Some(r) => {
                let h = compose_line(&r.hom, &a, &b);
                let pts = h.map(|x| std::array::from_fn(|c| x[c].clone() / x[3].clone()));
                (
                    pts,
                    Some(
                        h.control
                            .into_iter()
                            .map(|x| x[3].clone())
                            .collect::<Vec<Q>>(),
                    ),
                )
            }
        };
        let cps: Vec<[f64; 3]> = exact.control.iter().map(to_f64_point).collect();
        let mut delta = 0.0f64;
        for (r, e) in cps.iter().zip(&exact.control) {
            for i in 0..3 {
                let d = Scalar::to_f64(&(crate::scalar::lift::<Q>(r[i]) - e[i].clone()).abs())
                    .next_up();
                delta = delta.max(d);
            }
        }
        let weights = hom_w
            .as_ref()
            .map(|w| w.iter().map(Scalar::to_f64).collect::<Vec<f64>>());
        let bound = match (&hom_w, &weights) {
            (Some(w), Some(wf)) => rational_rounding(&exact.control, w, wf, delta),
            _ => delta,
        };
        rounding = rounding.max(bound);
        out.push(MappedSegment {
            exact,
            control_points: cps,
            weights,
            domain: [s.a, s.b],
            cell: s.cell,
        });
    }
    Ok((out, rounding))
}

/// The distance between the rational curve of the printed points and weights and the exact
/// one (the argument of `float::rational`'s `compose_line`): `√3 δ + 2ε / (1 − ε) · max_k
/// |P_k − P_0|`, with `δ` the points' coordinate rounding and `ε` the weights' relative
/// rounding (plus `2u` for the B-spline form's joint rescaling); infinite when `ε ≥ 1/2`.
fn rational_rounding(pts: &[[Q; 3]], w: &[Q], wf: &[f64], delta: f64) -> f64 {
    let mut eps = 0.0f64;
    for (e, r) in w.iter().zip(wf) {
        let rel = ((crate::scalar::lift::<Q>(*r) - e.clone()) / e.clone()).abs();
        eps = eps.max(Scalar::to_f64(&rel).next_up());
    }
    let reach = pts
        .iter()
        .map(|p| super::tolerance::sqrt_up(&crate::geom::norm2(&p.sub(&pts[0]))))
        .fold(0.0, f64::max);
    super::tolerance::rational_rounding(delta, eps, reach)
}
