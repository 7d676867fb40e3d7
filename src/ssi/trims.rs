//! Clipping intersection curves to the faces' trimming loops (`--respect-trims`, issue step 7).
//!
//! Each trim loop is polygonized in the parameter plane (every curve sampled at
//! [`SAMPLES_PER_CURVE`] + 1 parameters, the curves' end points exactly); a parameter point is
//! inside the face when the even-odd rule over all loops says so, decided with exact
//! orientation signs against the polygon edges. The polygon is an approximation of the trim
//! curves (evidence-level near the trim boundary, said in the report); the decision for the
//! polygon is exact. A branch is cut where it leaves either face; the cut ends are marked
//! [`EndKind::TrimBoundary`].

use super::fit::fit_branch;
use super::krawczyk::Uncertified;
use super::report::{BranchOut, EndKind};
use crate::model::Surface;
use crate::predicates::orient2d;
use crate::scalar::Sign;

pub const SAMPLES_PER_CURVE: usize = 64;

/// A face's trimmed region as polygons in its parameter plane.
pub struct TrimRegion {
    loops: Vec<Vec<[f64; 2]>>,
}

impl TrimRegion {
    /// `None` when the face has no trim loops (the whole domain is the face).
    pub fn of(s: &Surface) -> Option<TrimRegion> {
        if s.trim_loops.is_empty() {
            return None;
        }
        let loops = s
            .trim_loops
            .iter()
            .map(|l| {
                let mut poly = Vec::new();
                for c in &l.curves {
                    let (t0, t1) = c.hom.domain();
                    for k in 0..SAMPLES_PER_CURVE {
                        poly.push(c.eval(&(t0 + (t1 - t0) * k as f64 / SAMPLES_PER_CURVE as f64)));
                    }
                }
                poly
            })
            .filter(|p| p.len() >= 3)
            .collect();
        Some(TrimRegion { loops })
    }

    /// Even-odd rule over all loops; a point on a polygon edge counts as inside.
    pub fn inside(&self, p: &[f64; 2]) -> bool {
        let mut odd = false;
        for poly in &self.loops {
            for k in 0..poly.len() {
                let (a, b) = (&poly[k], &poly[(k + 1) % poly.len()]);
                // Ray to +u: edges crossing the horizontal line through p, half-open in v.
                if (a[1] > p[1]) != (b[1] > p[1]) {
                    let o = orient2d(a, b, p);
                    if o == Sign::Zero {
                        return true;
                    }
                    // p is left of the upward edge (or right of a downward one) => crossing.
                    let upward = b[1] > a[1];
                    if (o == Sign::Positive) == upward {
                        odd = !odd;
                    }
                }
            }
        }
        odd
    }
}

fn refit(b: &mut BranchOut) {
    b.fit = fit_branch(&b.points, &b.uv_a, &b.uv_b, b.closed);
}

/// The parts of `b` inside both trimmed faces (`None`: untrimmed face).
pub fn clip(b: &BranchOut, ra: Option<&TrimRegion>, rb: Option<&TrimRegion>) -> Vec<BranchOut> {
    let n = b.points.len();
    let keep: Vec<bool> = (0..n)
        .map(|i| ra.is_none_or(|r| r.inside(&b.uv_a[i])) && rb.is_none_or(|r| r.inside(&b.uv_b[i])))
        .collect();
    if keep.iter().all(|k| *k) {
        return vec![b.clone()];
    }
    // Runs of kept points; for a closed branch, start after a dropped point so a run may wrap.
    let start = if b.closed {
        keep.iter().position(|k| !k).unwrap_or(0)
    } else {
        0
    };
    let mut runs: Vec<Vec<usize>> = Vec::new();
    let mut cur: Vec<usize> = Vec::new();
    for s in 0..n {
        let i = (start + s) % n;
        if keep[i] {
            cur.push(i);
        } else if !cur.is_empty() {
            runs.push(std::mem::take(&mut cur));
        }
    }
    if !cur.is_empty() {
        runs.push(cur);
    }
    runs.into_iter()
        .filter(|r| r.len() >= 2)
        .map(|r| {
            let end_kind = |i: usize, first: bool| -> EndKind {
                let orig_end = !b.closed && ((first && i == 0) || (!first && i == n - 1));
                if orig_end {
                    b.ends[if first { 0 } else { 1 }]
                } else {
                    EndKind::TrimBoundary
                }
            };
            let curve = b.curve_results();
            let mut out = BranchOut {
                closed: false,
                points: r.iter().map(|&i| b.points[i]).collect(),
                uv_a: r.iter().map(|&i| b.uv_a[i]).collect(),
                uv_b: r.iter().map(|&i| b.uv_b[i]).collect(),
                ends: vec![end_kind(r[0], true), end_kind(r[r.len() - 1], false)],
                fit: None,
                ..b.clone()
            };
            out.set_curve_radii(
                r.iter()
                    .map(|&i| curve.get(i).copied().unwrap_or(Err(Uncertified::NotFinite)))
                    .collect(),
            );
            refit(&mut out);
            out
        })
        .collect()
}
