//! A local closest point of a surface (and of a curve, [`CurveFoot`]) to a point: grid starts
//! refined by damped Gauss–Newton (Newton on a curve). It finds *a* nearby foot, not the global closest point, and proves nothing:
//! callers use it for measured distances (evidence) and as a start for certified searches.

use super::closure::Closure;
use super::{NurbsCurve, NurbsSurface};
use crate::geom::{Point, dot};

/// `S(u, v)`, `S_u`, `S_v` of a rational surface (quotient rule on the homogeneous
/// derivatives).
pub fn point_d1(s: &NurbsSurface<f64, 3>, u: f64, v: f64) -> ([f64; 3], [f64; 3], [f64; 3]) {
    let (h, hu, hv) = s.hom.eval_d1(&u, &v);
    let p = h.wp.scale(&(1.0 / h.w));
    let su = hu.wp.sub(&p.scale(&hu.w)).scale(&(1.0 / h.w));
    let sv = hv.wp.sub(&p.scale(&hv.w)).scale(&(1.0 / h.w));
    (p, su, sv)
}

fn sub(a: &[f64; 3], b: &[f64; 3]) -> [f64; 3] {
    a.sub(b)
}

/// Damped Gauss–Newton from `uv` towards the closest point of `s` to `x`.
pub fn descend(
    s: &NurbsSurface<f64, 3>,
    x: &[f64; 3],
    mut uv: [f64; 2],
    d: &[f64; 4],
) -> ([f64; 2], f64) {
    let err = |uv: &[f64; 2]| {
        let p = s.eval(&uv[0], &uv[1]);
        dot(&sub(&p, x), &sub(&p, x))
    };
    let mut e = err(&uv);
    for _ in 0..40 {
        let (p, su, sv) = point_d1(s, uv[0], uv[1]);
        let r = sub(&p, x);
        let (a, b, c) = (dot(&su, &su), dot(&su, &sv), dot(&sv, &sv));
        let (g0, g1) = (dot(&r, &su), dot(&r, &sv));
        // At a pole (a degenerate border) one derivative vanishes and the normal equations
        // are singular: a Levenberg–Marquardt shift moves along the other direction.
        let mut det = a * c - b * b;
        let lm = if det > 1e-12 * a * c {
            0.0
        } else {
            1e-6 * (a + c)
        };
        let (a, c) = (a + lm, c + lm);
        if lm > 0.0 {
            det = a * c - b * b;
        }
        if det.is_nan() || det <= 0.0 {
            break;
        }
        let step = [-(c * g0 - b * g1) / det, -(a * g1 - b * g0) / det];
        let mut t = 1.0;
        let mut moved = false;
        for _ in 0..12 {
            let next = [
                (uv[0] + t * step[0]).clamp(d[0], d[1]),
                (uv[1] + t * step[1]).clamp(d[2], d[3]),
            ];
            let en = err(&next);
            if en < e {
                (uv, e, moved) = (next, en, true);
                break;
            }
            t *= 0.5;
        }
        if !moved {
            break;
        }
    }
    (uv, e)
}

/// Grid steps per parameter of a surface's closest-point starts.
const GRID: usize = 16;

/// Parameters of (a local) closest point of `s` to `x`: [`SurfaceFoot::closest`] with the
/// grid made for this one query.
pub fn project(s: &NurbsSurface<f64, 3>, x: &[f64; 3]) -> [f64; 2] {
    SurfaceFoot::new(s).closest(x)
}

/// Closest points on one surface to many points: the 17 × 17 grid of starts (16 equal steps
/// per parameter) is evaluated once, and the seam test once.
pub struct SurfaceFoot<'a> {
    s: &'a NurbsSurface<f64, 3>,
    d: [f64; 4],
    /// Grid points in row order (`u` outer), with their parameters.
    grid: Vec<([f64; 2], [f64; 3])>,
    closure: Option<Closure>,
}

impl<'a> SurfaceFoot<'a> {
    pub fn new(s: &'a NurbsSurface<f64, 3>) -> Self {
        let (u0, u1, v0, v1) = s.hom.domain();
        let d = [u0, u1, v0, v1];
        let n = GRID as f64;
        let mut grid = Vec::with_capacity((GRID + 1) * (GRID + 1));
        for i in 0..=GRID {
            for j in 0..=GRID {
                let uv = [
                    d[0] + (d[1] - d[0]) * i as f64 / n,
                    d[2] + (d[3] - d[2]) * j as f64 / n,
                ];
                grid.push((uv, s.eval(&uv[0], &uv[1])));
            }
        }
        SurfaceFoot {
            s,
            d,
            grid,
            closure: None,
        }
    }

    /// Parameters of (a local) closest point of the surface to `x`: the best of four grid
    /// starts at distinct distances from `x` (so not four copies of one pole), each refined by
    /// damped Gauss–Newton; on a closed surface, a result on the seam is refined again from
    /// the other end of that parameter's domain (the grid's start there is the same point,
    /// dropped as a copy, and a descent stops at the domain's border).
    pub fn closest(&mut self, x: &[f64; 3]) -> [f64; 2] {
        let (s, d) = (self.s, self.d);
        // The four nearest grid points at distinct distances (a pole row is one point many
        // times), the first in grid order among equal ones: kept in order as the grid is
        // scanned (the same four a stable sort of the whole grid would give first).
        let mut chosen: Vec<(f64, [f64; 2])> = Vec::with_capacity(5);
        for (uv, p) in &self.grid {
            let st = (dot(&sub(p, x), &sub(p, x)), *uv);
            if chosen.iter().any(|c| c.0 == st.0) {
                continue;
            }
            let at = chosen.partition_point(|c| c.0.total_cmp(&st.0).is_le());
            if at < 4 {
                chosen.insert(at, st);
                chosen.truncate(4);
            }
        }
        let Some(mut best) = chosen
            .iter()
            .map(|(_, uv)| descend(s, x, *uv, &d))
            .min_by(|a, b| a.1.total_cmp(&b.1))
        else {
            return [d[0], d[2]];
        };
        // On a closed surface a descent that stopped on the seam may want to go on past it:
        // start again from the same point at the other end of that parameter's domain.
        let on_border = |uv: &[f64; 2], k: usize| uv[k] == d[2 * k] || uv[k] == d[2 * k + 1];
        if !(on_border(&best.0, 0) || on_border(&best.0, 1)) {
            return best.0;
        }
        let c = *self.closure.get_or_insert_with(|| Closure::of(s));
        for (k, closed) in [(0, c.seam_u), (1, c.seam_v)] {
            let (lo, hi) = (d[2 * k], d[2 * k + 1]);
            if closed && on_border(&best.0, k) {
                let mut uv = best.0;
                uv[k] = if best.0[k] == lo { hi } else { lo };
                let other = descend(s, x, uv, &d);
                if other.1 < best.1 {
                    best = other;
                }
            }
        }
        best.0
    }
}

/// Samples per closest-point search (plus one): the curve's domain in 32 equal steps.
const FOOT_SAMPLES: usize = 33;

/// Closest points on one curve to many points: the curve's 33 samples (32 equal parameter
/// steps) are evaluated once; each query takes the best three (by distance, ties by
/// parameter order), refines each by Newton on `(C - x)·C' = 0` (accepting only improving
/// steps) and returns the best result.
pub struct CurveFoot<'a> {
    c: &'a NurbsCurve<f64, 3>,
    samples: [(f64, [f64; 3]); FOOT_SAMPLES],
}

impl<'a> CurveFoot<'a> {
    pub fn new(c: &'a NurbsCurve<f64, 3>) -> Self {
        let (t0, t1) = c.hom.domain();
        let n = (FOOT_SAMPLES - 1) as f64;
        CurveFoot {
            c,
            samples: std::array::from_fn(|i| {
                let t = t0 + (t1 - t0) * i as f64 / n;
                (t, c.eval(&t))
            }),
        }
    }

    /// `(t, C(t), |C(t) - x|)` of the closest point found.
    pub fn closest(&self, x: &[f64; 3]) -> (f64, [f64; 3], f64) {
        let c = self.c;
        let (t0, t1) = c.hom.domain();
        let d2 =
            |p: &[f64; 3]| (p[0] - x[0]).powi(2) + (p[1] - x[1]).powi(2) + (p[2] - x[2]).powi(2);
        let mut order: [(f64, usize); FOOT_SAMPLES] =
            std::array::from_fn(|i| (d2(&self.samples[i].1), i));
        order.sort_unstable_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        let newton = |(mut t, mut p): (f64, [f64; 3])| -> (f64, [f64; 3]) {
            for _ in 0..20 {
                let (q, d1, dd) = c.derivatives2_f64(t);
                let r = [q[0] - x[0], q[1] - x[1], q[2] - x[2]];
                let f = r[0] * d1[0] + r[1] * d1[1] + r[2] * d1[2];
                let fp = d1[0] * d1[0]
                    + d1[1] * d1[1]
                    + d1[2] * d1[2]
                    + r[0] * dd[0]
                    + r[1] * dd[1]
                    + r[2] * dd[2];
                if fp.is_nan() || fp <= 0.0 {
                    break;
                }
                let tn = (t - f / fp).clamp(t0, t1);
                let pn = c.eval(&tn);
                if d2(&pn) >= d2(&p) {
                    break;
                }
                (t, p) = (tn, pn);
            }
            (t, p)
        };
        let (t, p) = order
            .iter()
            .take(3)
            .map(|(_, i)| newton(self.samples[*i]))
            .min_by(|a, b| d2(&a.1).total_cmp(&d2(&b.1)))
            .unwrap_or((t0, c.eval(&t0)));
        (t, p, d2(&p).sqrt())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spline::construct::{Frame, cylinder, sphere};

    /// Points just either side of the seam of closed surfaces (in a tilted frame) project to
    /// their own feet, not to the seam: the grid start on the far side of the seam is the
    /// same point as the near one, and a descent from it stops at the domain's border.
    #[test]
    fn feet_next_to_a_seam() {
        let f = Frame {
            o: [1.0, -2.0, 0.5],
            x: [0.6, 0.8, 0.0],
            y: [0.0, 0.0, 1.0],
            z: [0.8, -0.6, 0.0],
        };
        for s in [
            cylinder(&f, 2.0, 0.0, 3.0).unwrap(),
            sphere(&f, 2.0).unwrap(),
        ] {
            let (u0, u1, v0, v1) = s.hom.domain();
            let v = v0 + 0.4 * (v1 - v0);
            for du in [1e-3, 1e-6, -1e-3, -1e-6] {
                let u = if du > 0.0 { u0 + du } else { u1 + du };
                let q = s.eval(&u, &v);
                // 0.1 out along the normal.
                let n = s.unit_normal(&u, &v).unwrap();
                let x: [f64; 3] = std::array::from_fn(|k| q[k] + 0.1 * n[k]);
                let p = project(&s, &x);
                let foot = s.eval(&p[0], &p[1]);
                let d = (0..3).map(|k| (foot[k] - q[k]).powi(2)).sum::<f64>().sqrt();
                assert!(d < 1e-7, "du {du}: foot {p:?} is {d} from the true foot");
            }
        }
    }
}
