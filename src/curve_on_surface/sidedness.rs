//! Step 2 — classify each planar Bézier piece single-/double-sided with the exact predicate
//! and split double-sided pieces at every crossing with their chord (roots of
//! `(C(t) - P_0) × (P_n - P_0)` in `(0, 1)`, isolated exactly; the paper's `t_1` for cubics).
//! A closed piece (`P_0 = P_n`) is first split at `t = 1/2`.

use super::cells::Cells;
use super::segments::Seg;
use crate::predicates::single_sided;
use crate::predicates::single_sided::{Sidedness, split_parameters};
use crate::scalar::{Rational, ratio};
use crate::spline::BezierCurve;

type Q = Rational;

/// Counts for the report.
#[derive(Clone, Copy, Debug, Default, serde::Serialize)]
pub struct SidednessStats {
    pub single_sided: usize,
    pub double_sided_split: usize,
    pub closed_split: usize,
    /// Pieces still double-sided after splitting at approximations of irrational crossings
    /// (sub-ulp excursions; the Hausdorff bound does not rely on single-sidedness).
    pub residual_double_sided: usize,
}

/// Split every segment until its piece is single-sided (bounded number of rounds).
pub fn make_single_sided(
    segs: Vec<Seg>,
    pieces: &[BezierCurve<[Q; 2]>],
    cells: &Cells,
) -> (Vec<Seg>, SidednessStats) {
    let mut stats = SidednessStats::default();
    let mut work = segs;
    for round in 0..4 {
        let mut out = Vec::with_capacity(work.len());
        let mut changed = false;
        for s in work {
            let c = s.curve(pieces);
            match single_sided(&c.control) {
                Sidedness::SingleSided { .. } => {
                    if round == 0 {
                        stats.single_sided += 1;
                    }
                    out.push(s);
                }
                Sidedness::DegenerateChord => {
                    stats.closed_split += 1;
                    changed = true;
                    let (l, r) = s.split(&ratio(1, 2), pieces, cells);
                    out.push(l);
                    out.push(r);
                }
                Sidedness::DoubleSided { .. } => {
                    if round == 3 {
                        stats.residual_double_sided += 1;
                        out.push(s);
                        continue;
                    }
                    stats.double_sided_split += 1;
                    changed = true;
                    let roots: Vec<Q> = split_parameters(&c.control, 2f64.powi(-40))
                        .into_iter()
                        .map(|(lo, hi)| (lo + hi) / Q::from(2))
                        .collect();
                    // Split at each root, left to right (re-expressing later roots locally).
                    let mut rest = s;
                    let mut consumed = Q::ZERO;
                    for r in roots {
                        let local = (r.clone() - consumed.clone()) / (Q::ONE - consumed.clone());
                        let (l, rr) = rest.split(&local, pieces, cells);
                        out.push(l);
                        rest = rr;
                        consumed = r;
                    }
                    out.push(rest);
                }
            }
        }
        work = out;
        if !changed {
            break;
        }
    }
    (work, stats)
}
