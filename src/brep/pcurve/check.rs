//! Proving a pcurve against its edge on the projector's surface, and putting projected
//! pcurves exactly on the knot lines they run along.

use super::project::Projector;
use crate::spline::NurbsCurve;

impl Projector<'_> {
    /// A proven bound on the Hausdorff distance between `S ∘ pc` and `arc` (ranges paired
    /// linearly, [`crate::spline::pcurve_bound::SurfaceCells::bound`]), halving while above `target`; why not otherwise.
    pub fn check(
        &self,
        pc: &NurbsCurve<f64, 2>,
        arc: &NurbsCurve<f64, 3>,
        target: f64,
    ) -> Result<f64, String> {
        self.check_on(pc, arc, arc.hom.domain(), target)
    }

    /// [`Projector::check`] against `arc` over `range` only.
    pub fn check_on(
        &self,
        pc: &NurbsCurve<f64, 2>,
        arc: &NurbsCurve<f64, 3>,
        range: (f64, f64),
        target: f64,
    ) -> Result<f64, String> {
        let cells = self
            .cells
            .as_ref()
            .ok_or("the surface's Bézier cells cannot be enclosed")?;
        cells
            .bound(pc, arc, range, target)
            .map_err(|e| e.to_string())
    }

    /// Puts every control point coordinate within `1e-12` of the domain's width of one of
    /// the surface's knot lines (its domain's ends included) exactly on it. Projected samples
    /// along a knot line or the domain's border come out a few ulps off it, which leaves it
    /// undecided whether the curve crosses the line or leaves the domain; exactly on it, both
    /// are decided. (The piece's bound is proven after.)
    pub(super) fn snap_to_lines(&self, ctrl: &mut [[f64; 2]]) {
        let c = &self.chart;
        let lines = [c.s.hom.ku.breakpoints(), c.s.hom.kv.breakpoints()];
        for p in ctrl {
            for d in 0..2 {
                let near = 1e-12 * (c.hi[d] - c.lo[d]);
                if let Some(k) = lines[d].iter().find(|k| (p[d] - **k).abs() <= near) {
                    p[d] = *k;
                }
            }
        }
    }
}
