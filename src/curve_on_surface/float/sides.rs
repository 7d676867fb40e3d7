//! Step 2, f64 path — classify each segment's piece single-/double-sided with the exact
//! predicate ([`crate::predicates::single_sided`]) applied to the f64 control points of the
//! piece (the midpoints of its enclosures, i.e. the piece as rounded to f64), and split a
//! double-sided one at every crossing with its chord (isolated exactly for those control
//! points). The certificate does not rest on this step — every final segment's bound is
//! computed from the enclosures — it is the paper's step that keeps Theorem 1 applicable.

use super::cells::FCells;
use super::distance::{split_at, sub_curve};
use super::ibez::mid;
use super::{FSeg, Piece};
use crate::curve_on_surface::sidedness::SidednessStats;
use crate::predicates::single_sided::{Sidedness, single_sided, split_parameters};
use crate::scalar::Scalar;

/// Split every segment until its (rounded) piece is single-sided (bounded rounds).
pub fn make_single_sided(
    segs: Vec<FSeg>,
    pieces: &[Piece],
    cells: &FCells,
) -> (Vec<FSeg>, SidednessStats) {
    let mut stats = SidednessStats::default();
    let mut work = segs;
    for round in 0..4 {
        let mut out = Vec::with_capacity(work.len());
        let mut changed = false;
        for s in work {
            let c: Vec<[f64; 2]> = sub_curve(&s, pieces).iter().map(mid).collect();
            let roots: Vec<f64> = match single_sided(&c) {
                Sidedness::SingleSided { .. } => {
                    if round == 0 {
                        stats.single_sided += 1;
                    }
                    out.push(s);
                    continue;
                }
                Sidedness::DegenerateChord => {
                    stats.closed_split += 1;
                    vec![0.5]
                }
                Sidedness::DoubleSided { .. } if round == 3 => {
                    stats.residual_double_sided += 1;
                    out.push(s);
                    continue;
                }
                Sidedness::DoubleSided { .. } => {
                    stats.double_sided_split += 1;
                    split_parameters(&c, 2f64.powi(-40))
                        .into_iter()
                        .map(|(lo, hi)| (lo.to_f64() + hi.to_f64()) / 2.0)
                        .collect()
                }
            };
            // Split at each root, left to right (later roots re-expressed locally).
            let mut rest = s;
            for r in roots {
                let local = (s.t0 + (s.t1 - s.t0) * r - rest.t0) / (rest.t1 - rest.t0);
                match split_at(&rest, local, pieces, cells) {
                    Some((l, rr)) => {
                        changed = true;
                        out.push(l);
                        rest = rr;
                    }
                    None => break,
                }
            }
            out.push(rest);
        }
        work = out;
        if !changed {
            break;
        }
    }
    (work, stats)
}
