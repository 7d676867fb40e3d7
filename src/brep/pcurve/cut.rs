//! Edges whose projection crosses a closed surface's seam: no one pcurve in the surface's
//! domain can carry them, so the edge is cut where its projection crosses the seam and each
//! part is projected on its own ([`Projector::project`]).

use super::chart::unwrap;
use super::project::{Fit, Projected, Projector};
use crate::spline::NurbsCurve;
use crate::spline::project::project as project_point;

/// Samples scanned for seam crossings.
const SCAN: usize = 256;
/// Bisections narrowing a crossing.
const BISECTIONS: usize = 60;

impl Projector<'_> {
    /// The pcurves of `arc`'s parts between the crossings of its projection with the seams
    /// of the surface's closed directions, each with the part of the arc it stands for; the
    /// whole arc alone when it needs no cut. `None` where a part cannot be projected.
    pub fn project_cut(
        &self,
        arc: &NurbsCurve<f64, 3>,
        fit: Fit,
    ) -> Option<Vec<(NurbsCurve<f64, 3>, Projected)>> {
        if let Some(p) = self.project(arc, None, None, fit) {
            return Some(vec![(arc.clone(), p)]);
        }
        let c = &self.chart;
        let (t0, t1) = arc.hom.domain();
        let ts: Vec<f64> = (0..SCAN)
            .map(|i| t0 + (t1 - t0) * i as f64 / (SCAN - 1) as f64)
            .collect();
        let mut scan = vec![project_point(c.s, &arc.eval(&t0))];
        for t in &ts[1..] {
            let last = scan[scan.len() - 1];
            scan.push(c.foot(arc, *t, last));
        }
        let mut cuts = Vec::new();
        for d in (0..2).filter(|d| c.closed[*d]) {
            let p = c.period(d);
            // Which copy of the domain a parameter is in.
            let sheet = |x: f64| ((x - c.lo[d]) / p).floor();
            for (i, w) in scan.windows(2).enumerate() {
                if sheet(w[0][d]) == sheet(w[1][d]) {
                    continue;
                }
                let s0 = sheet(w[0][d]);
                let (mut a, mut b) = (ts[i], ts[i + 1]);
                for _ in 0..BISECTIONS {
                    let m = 0.5 * (a + b);
                    if m <= a || m >= b {
                        break;
                    }
                    let x = unwrap(c.foot(arc, m, w[0])[d], w[0][d], p);
                    if sheet(x) == s0 { a = m } else { b = m }
                }
                cuts.push(0.5 * (a + b));
            }
        }
        let tiny = 1e-9 * (t1 - t0);
        cuts.retain(|t| *t > t0 + tiny && *t < t1 - tiny);
        cuts.sort_by(f64::total_cmp);
        cuts.dedup_by(|x, y| (*x - *y).abs() <= tiny);
        if cuts.is_empty() {
            return None;
        }
        let mut bounds = vec![t0];
        bounds.extend(cuts);
        bounds.push(t1);
        bounds
            .windows(2)
            .map(|w| {
                let part = NurbsCurve {
                    hom: arc.hom.sub_curve(&w[0], &w[1]).ok()?,
                };
                // The part is the arc's knot insertion in f64 (rounded): its bounds are
                // proven against the arc itself over the part's range.
                let p = self.project_against(&part, arc, None, None, fit)?;
                Some((part, p))
            })
            .collect()
    }
}
