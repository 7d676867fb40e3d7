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
        let bound =
            |pc: &NurbsCurve<f64, 2>| self.check(pc, arc, fit.aim).ok().filter(|r| *r <= fit.off);
        // `one` is the projection itself where its control points lie exactly at the end
        // already (snapped there): its proven bound holds. On a surface closed exactly in
        // direction `d` (identical border rows) the twin has the same image as `one`
        // (`S(lo, ·) = S(hi, ·)`), so the same bound.
        let one_bound = match p.bound.filter(|r| *r <= fit.off) {
            Some(r) if one == p.curve => r,
            _ => bound(&one)?,
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
    use crate::spline::closure::{Closure, exact_seam};
    use crate::spline::construct::{Frame, cylinder};
    use crate::spline::{NurbsCurve, NurbsSurface};

    /// The cylinder of radius 1 about the axis through `(x0, 0, 0)` along z for `z ∈ [0, 2]`,
    /// with the border row of its closed direction at the far end (`hi`) moved outward by
    /// `delta`.
    fn cylinder_moved(x0: f64, delta: f64) -> (NurbsSurface<f64, 3>, usize) {
        let f = Frame {
            o: [x0, 0.0, 0.0],
            ..Frame::WORLD
        };
        let s = cylinder(&f, 1.0, 0.0, 2.0).unwrap();
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
                    let (x, y) = (p[0] - x0, p[1]);
                    let r = (x * x + y * y).sqrt();
                    p[0] = x0 + x * (1.0 + delta / r);
                    p[1] = y * (1.0 + delta / r);
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
        for x0 in [0.0, 1e4] {
            // The seam line of the exact cylinder (the start of its circle).
            let (s, d) = cylinder_moved(x0, 0.0);
            assert!(exact_seam(&s, d));
            let seam_point = |v: f64| {
                if d == 0 {
                    s.eval(&0.0, &v)
                } else {
                    s.eval(&v, &0.0)
                }
            };
            let (a, b) = (seam_point(0.0), seam_point(1.0));
            let line =
                NurbsCurve::new(vec![0.0, 0.0, 1.0, 1.0], 1, vec![a, b], vec![1.0; 2]).unwrap();
            let (sides, r) = Projector::new(&s).seam_sides(&line, fit).unwrap();
            assert!(r < 1e-9, "exact cylinder at {x0}: {r}");
            let ends: Vec<f64> = sides.iter().map(|c| c.points_weights().0[0][d]).collect();
            assert!(ends.contains(&0.0) && ends.contains(&1.0), "{ends:?}");
            // One side moved by 5e-9: within the search's closure (1e-7) and, 1e4 from the
            // origin, within `Closure::of`'s rounding allowance too (it calls the cylinder
            // closed there), but not exactly closed: the moved side lies 5e-9 off the line,
            // and the bound must see it on whichever side the projection lands.
            let delta = 5e-9;
            let (m, _) = cylinder_moved(x0, delta);
            assert!(!exact_seam(&m, d));
            if x0 > 0.0 {
                let c = Closure::of(&m);
                assert!(c.seam_u || c.seam_v, "Closure::of allows the rounding");
            }
            let (_, r) = Projector::new(&m).seam_sides(&line, fit).unwrap();
            assert!(
                r >= 0.99 * delta && r < 3.0 * delta,
                "moved cylinder at {x0}: {r}"
            );
        }
    }
}
