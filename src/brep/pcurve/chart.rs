//! A surface's parameter chart for projecting curves onto it: its domain, the directions in
//! which it closes (a seam) and its poles (borders that are one point), with the searches
//! and the parameter bookkeeping that need them.

use crate::spline::closure::Closure;
use crate::spline::project::{descend, project};
use crate::spline::{NurbsCurve, NurbsSurface};

/// The straight segment from `a` to `b` (degree 1 over `[0, 1]`).
pub(crate) fn segment<const D: usize>(a: [f64; D], b: [f64; D]) -> Option<NurbsCurve<f64, D>> {
    NurbsCurve::new(vec![0.0, 0.0, 1.0, 1.0], 1, vec![a, b], vec![1.0, 1.0]).ok()
}

/// `x` moved by whole periods to the value nearest `near`.
pub(crate) fn unwrap(x: f64, near: f64, period: f64) -> f64 {
    x - period * ((x - near) / period).round()
}

/// A surface with its domain and closed directions (found once, not per search).
pub(crate) struct Chart<'a> {
    pub s: &'a NurbsSurface<f64, 3>,
    pub lo: [f64; 2],
    pub hi: [f64; 2],
    pub closed: [bool; 2],
    /// Borders `u = lo`, `u = hi`, `v = lo`, `v = hi` that are a point (a pole).
    pub poles: [bool; 4],
}

impl<'a> Chart<'a> {
    pub fn new(s: &'a NurbsSurface<f64, 3>, closure: &Closure) -> Chart<'a> {
        let (u0, u1, v0, v1) = s.hom.domain();
        Chart {
            s,
            lo: [u0, v0],
            hi: [u1, v1],
            closed: [closure.seam_u, closure.seam_v],
            poles: closure.degenerate,
        }
    }
    /// The first and last of `pts` lying on a pole take the other parameter of their
    /// neighbour (at a pole that parameter is arbitrary; the pcurve must arrive along it).
    pub fn at_poles(&self, pts: &mut [[f64; 2]]) {
        let n = pts.len();
        if n >= 2 {
            pts[0] = self.at_pole(pts[0], pts[1]);
            pts[n - 1] = self.at_pole(pts[n - 1], pts[n - 2]);
        }
    }
    /// Whether `a` and `b` lie on one pole (one degenerate border: the same point of space),
    /// apart.
    pub fn on_one_pole(&self, a: [f64; 2], b: [f64; 2]) -> bool {
        (0..4).any(|side| {
            let (d, end) = (side / 2, if side % 2 == 0 { self.lo } else { self.hi });
            let near = |x: f64| (x - end[d]).abs() <= 1e-9 * self.period(d);
            self.poles[side] && near(a[d]) && near(b[d]) && a[1 - d] != b[1 - d]
        })
    }
    /// `p`, with the other parameter of `next` where `p` lies on a pole.
    pub fn at_pole(&self, mut p: [f64; 2], next: [f64; 2]) -> [f64; 2] {
        for side in 0..4 {
            let (d, end) = (side / 2, if side % 2 == 0 { self.lo } else { self.hi });
            if self.poles[side] && (p[d] - end[d]).abs() <= 1e-9 * self.period(d) {
                p[1 - d] = next[1 - d];
            }
        }
        p
    }
    pub fn period(&self, d: usize) -> f64 {
        self.hi[d] - self.lo[d]
    }
    /// The parameters of a closest point of the surface to `x` near `seed` (its closed
    /// parameters taken modulo their periods): damped Gauss–Newton from the seed, or the
    /// global search ([`project`]) where the descent stops on a border of a closed direction
    /// or moves more than a quarter of the domain (a search figure: the pcurves made from
    /// these points are checked against the edges themselves).
    pub fn seeded(&self, x: &[f64; 3], seed: [f64; 2]) -> [f64; 2] {
        let (lo, hi) = (self.lo, self.hi);
        let start: [f64; 2] = std::array::from_fn(|j| {
            if self.closed[j] {
                lo[j] + (seed[j] - lo[j]).rem_euclid(hi[j] - lo[j])
            } else {
                seed[j].clamp(lo[j], hi[j])
            }
        });
        let (uv, _) = descend(self.s, x, start, &[lo[0], hi[0], lo[1], hi[1]]);
        let on_seam = |j: usize| self.closed[j] && (uv[j] == lo[j] || uv[j] == hi[j]);
        let far = (0..2).any(|j| (uv[j] - start[j]).abs() > 0.25 * (hi[j] - lo[j]));
        if on_seam(0) || on_seam(1) || far || !uv.iter().all(|v| v.is_finite()) {
            project(self.s, x)
        } else {
            uv
        }
    }
    /// The parameters of `arc`'s point at `t`, each closed one unwrapped to the value nearest
    /// `near`'s (which also seeds the search).
    pub fn foot(&self, arc: &NurbsCurve<f64, 3>, t: f64, near: [f64; 2]) -> [f64; 2] {
        let p = self.seeded(&arc.eval(&t), near);
        std::array::from_fn(|d| {
            if self.closed[d] {
                unwrap(p[d], near[d], self.period(d))
            } else {
                p[d]
            }
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spline::construct::{Frame, sphere};

    /// A sphere's NURBS form has its poles at `v = 0` and `v = 1` and its seam at `u = 0, 1`:
    /// points on one pole are one point of space, whatever their `u`.
    #[test]
    fn poles_and_seams_of_a_sphere() {
        let s = sphere(&Frame::WORLD, 2.0).unwrap();
        let c = Chart::new(&s, &Closure::within(&s, 1e-7));
        assert_eq!(c.closed, [true, false]);
        assert!(c.on_one_pole([0.2, 0.0], [0.7, 0.0]));
        assert!(c.on_one_pole([0.2, 1.0], [0.9, 1.0]));
        assert!(!c.on_one_pole([0.2, 0.0], [0.7, 1.0]));
        assert!(!c.on_one_pole([0.2, 0.5], [0.7, 0.5]));
        assert!(!c.on_one_pole([0.2, 0.0], [0.2, 0.0]));
        // A sample at a pole takes its neighbour's free parameter.
        let mut pts = [[0.9, 0.0], [0.3, 0.1], [0.35, 0.2]];
        c.at_poles(&mut pts);
        assert_eq!(pts[0], [0.3, 0.0]);
        // Unwrapping moves by whole periods only.
        assert_eq!(unwrap(0.05, 0.98, 1.0), 1.05);
        let p = s.eval(&0.3, &0.4);
        let q = c.foot(&segment([0.0f64; 3], p).unwrap(), 1.0, [1.29, 0.4]);
        assert!(
            (q[0] - 1.3).abs() < 1e-9 && (q[1] - 0.4).abs() < 1e-9,
            "{q:?}"
        );
    }
}
