//! Edges along a closed surface's seam: one pcurve per side of it, both with a proven bound.

use super::project::{Fit, Projector};
use crate::spline::NurbsCurve;

impl Projector<'_> {
    /// The pcurves of `arc`, an edge along the seam of a closed direction, on both sides of
    /// it (the projection with that parameter set to the end of the domain it lies at, and
    /// the same curve at the other end), with the larger of their proven bounds. `None` when
    /// the projection does not lie along a border, or either side is not proven within
    /// `fit.off` of the edge (the other side: the surface is not closed there).
    pub fn seam_sides(
        &self,
        arc: &NurbsCurve<f64, 3>,
        fit: Fit,
    ) -> Option<([NurbsCurve<f64, 2>; 2], f64)> {
        let c = &self.chart;
        let p = self.project(arc, None, None, fit)?;
        // The direction whose parameter stays at one end of the domain (within 1e-6 of its
        // length, as in `place_in_domain`), and that end; both sides are checked.
        let (pts, w) = p.curve.points_weights();
        let at_end = |d: usize, x: f64| pts.iter().all(|q| (q[d] - x).abs() <= 1e-6 * c.period(d));
        // The chart's closure is a search aid (borders within 1e-7): where the surface is not
        // closed exactly, the other side is accepted only with a proven bound of its own.
        let (d, here, other) = (0..2).find_map(|d| {
            if at_end(d, c.lo[d]) {
                Some((d, c.lo[d], c.hi[d]))
            } else if at_end(d, c.hi[d]) {
                Some((d, c.hi[d], c.lo[d]))
            } else {
                None
            }
        })?;
        let put = |x: f64| -> Vec<[f64; 2]> {
            pts.iter()
                .map(|q| if d == 0 { [x, q[1]] } else { [q[0], x] })
                .collect()
        };
        let knots = p.curve.hom.knots.knots().to_vec();
        let deg = p.curve.hom.degree();
        let one = NurbsCurve::new(knots.clone(), deg, put(here), w.clone()).ok()?;
        let twin = NurbsCurve::new(knots, deg, put(other), w).ok()?;
        let (t0, t1) = arc.hom.domain();
        let bound = |pc: &NurbsCurve<f64, 2>| {
            self.cells
                .as_ref()
                .and_then(|x| x.bound(pc, arc, (t0, t1), fit.aim).ok())
                .filter(|r| *r <= fit.off)
        };
        // `one` is the projection itself where its control points lie exactly at the end
        // already (snapped there): its proven bound holds. On a surface closed exactly in
        // direction `d` the twin has the same image as `one` (`S(lo, ·) = S(hi, ·)`), so the
        // same bound.
        let here_bound = if one == p.curve {
            p.bound.filter(|r| *r <= fit.off)
        } else {
            None
        };
        let one_bound = match here_bound {
            Some(r) => r,
            None => bound(&one)?,
        };
        let twin_bound = if self.exact_seam[d] {
            one_bound
        } else {
            bound(&twin)?
        };
        Some(([one, twin], one_bound.max(twin_bound)))
    }
}

#[cfg(test)]
mod tests {
    use super::super::project::{Fit, Projector};
    use crate::spline::closure::Closure;
    use crate::spline::construct::{Frame, cylinder};
    use crate::spline::{NurbsCurve, NurbsSurface};

    /// The cylinder of radius 1 about z for `z ∈ [0, 2]`, with the border row of its closed
    /// direction at the far end (`hi`) moved outward by `delta`.
    fn cylinder_moved(delta: f64) -> (NurbsSurface<f64, 3>, usize) {
        let s = cylinder(&Frame::WORLD, 1.0, 0.0, 2.0).unwrap();
        let c = Closure::of(&s);
        assert!(c.seam_u != c.seam_v, "closed in one direction");
        let d = if c.seam_u { 0 } else { 1 };
        let (mut pts, w) = s.points_weights();
        let (nu, nv) = (s.hom.nu(), s.hom.nv());
        for i in 0..nu {
            for j in 0..nv {
                let last = if d == 0 { i == nu - 1 } else { j == nv - 1 };
                if last {
                    let p = &mut pts[i * nv + j];
                    let r = (p[0] * p[0] + p[1] * p[1]).sqrt();
                    p[0] *= 1.0 + delta / r;
                    p[1] *= 1.0 + delta / r;
                }
            }
        }
        let k = |kv: &crate::spline::KnotVector<f64>| kv.knots().to_vec();
        let (p, q) = (s.hom.ku.degree(), s.hom.kv.degree());
        let moved = NurbsSurface::new(k(&s.hom.ku), p, k(&s.hom.kv), q, nu, nv, pts, w).unwrap();
        (moved, d)
    }

    #[test]
    fn the_twin_shares_the_bound_only_on_an_exactly_closed_surface() {
        let fit = Fit {
            aim: 1e-9,
            off: 1e-3,
        };
        // The seam line of the exact cylinder (its start of the circle, at x = 1).
        let (s, d) = cylinder_moved(0.0);
        let seam_point = |v: f64| {
            if d == 0 {
                s.eval(&0.0, &v)
            } else {
                s.eval(&v, &0.0)
            }
        };
        let (a, b) = (seam_point(0.0), seam_point(1.0));
        let line = NurbsCurve::new(vec![0.0, 0.0, 1.0, 1.0], 1, vec![a, b], vec![1.0; 2]).unwrap();
        let (sides, r) = Projector::new(&s).seam_sides(&line, fit).unwrap();
        assert!(r < 1e-12, "exact cylinder: {r}");
        let ends: Vec<f64> = sides.iter().map(|c| c.points_weights().0[0][d]).collect();
        assert!(ends.contains(&0.0) && ends.contains(&1.0), "{ends:?}");
        // Moved by 1e-8 on one side: within the chart's 1e-7, so the projection still finds
        // the seam, but the moved side lies 1e-8 off the line: the bound must see it on
        // whichever side the projection lands (the twin bounded on its own).
        let delta = 1e-8;
        let (m, _) = cylinder_moved(delta);
        assert!(!Closure::of(&m).seam_u && !Closure::of(&m).seam_v);
        let (_, r) = Projector::new(&m).seam_sides(&line, fit).unwrap();
        assert!(r >= 0.99 * delta && r < 2.0 * delta, "moved cylinder: {r}");
    }
}
