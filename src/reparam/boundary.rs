//! Step 1 of the RCA parametrization (§2, "Boundary curve approximation"): each of the four
//! boundary iso-curves of S is measured by arc length (adaptive Gauss–Legendre quadrature of
//! the speed, per knot span) and curvature, and interpolation points are chosen "by arc
//! length and curvature distribution": more points where the radius of curvature is small.
//!
//! The points are placed at equal steps of the measure
//! `M(s) = ∫ m(σ) dσ`, `m = n_min / L + κ / θ_max + (κ³ / (76.8 ε))^{1/4}`,
//! with `N = max(n_min, ⌈M(L)⌉)` pieces. Each piece then has `∫ m ≤ 1`, so its length is at
//! most `L / n_min` and its turning angle `∫ κ ds` at most `θ_max` (both exactly, up to the
//! quadrature of `κ`), and the last term asks for pieces no longer than `(76.8 ε / κ³)^{1/4}`,
//! the spacing at which the cubic interpolation error estimate `5/384 h⁴ |C''''|` of a
//! circle of curvature κ is `ε` (an estimate, not a bound: step 4 measures the result).

use super::{Params, ReparamError};
use crate::spline::NurbsSurface;
use crate::spline::closure::Closure;
use crate::spline::project::point_d1;

/// The four borders, in the order used throughout: `v = v0`, `v = v1` (parameter u),
/// `u = u0`, `u = u1` (parameter v).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Side {
    VMin,
    VMax,
    UMin,
    UMax,
}

impl Side {
    pub const ALL: [Side; 4] = [Side::VMin, Side::VMax, Side::UMin, Side::UMax];
    /// Index in [`Closure::degenerate`] (`u_min, u_max, v_min, v_max`).
    fn closure_index(self) -> usize {
        match self {
            Side::UMin => 0,
            Side::UMax => 1,
            Side::VMin => 2,
            Side::VMax => 3,
        }
    }
    /// Whether the curve's parameter is u.
    pub fn along_u(self) -> bool {
        matches!(self, Side::VMin | Side::VMax)
    }
}

/// Nodes of the 5-point Gauss–Legendre rule on `[-1, 1]` and their weights.
const GL_X: [f64; 5] = [
    -0.906_179_845_938_664,
    -0.538_469_310_105_683,
    0.0,
    0.538_469_310_105_683,
    0.906_179_845_938_664,
];
const GL_W: [f64; 5] = [
    0.236_926_885_056_189_1,
    0.478_628_670_499_366_5,
    0.568_888_888_888_888_9,
    0.478_628_670_499_366_5,
    0.236_926_885_056_189_1,
];

fn gauss5(f: &dyn Fn(f64) -> f64, a: f64, b: f64) -> f64 {
    let (c, h) = ((a + b) / 2.0, (b - a) / 2.0);
    h * GL_X
        .iter()
        .zip(&GL_W)
        .map(|(x, w)| w * f(c + h * x))
        .sum::<f64>()
}

/// `∫_a^b f` by adaptive 5-point Gauss–Legendre: an interval is split until the rule on it
/// and on its halves agree within `tol` relative to the estimate or within `abs`, or to
/// depth 16.
pub fn integrate(f: &dyn Fn(f64) -> f64, a: f64, b: f64, tol: f64, abs: f64) -> f64 {
    fn rec(f: &dyn Fn(f64) -> f64, a: f64, b: f64, whole: f64, tol: (f64, f64), depth: u32) -> f64 {
        let m = (a + b) / 2.0;
        let (l, r) = (gauss5(f, a, m), gauss5(f, m, b));
        let diff = (l + r - whole).abs();
        if depth == 0 || !diff.is_finite() || diff <= tol.0 * (l + r).abs() || diff <= tol.1 {
            l + r
        } else {
            rec(f, a, m, l, tol, depth - 1) + rec(f, m, b, r, tol, depth - 1)
        }
    }
    if b <= a {
        return 0.0;
    }
    rec(f, a, b, gauss5(f, a, b), (tol, abs), 16)
}

/// Relative accuracy of the arc-length quadrature.
const QUAD_TOL: f64 = 1e-11;
/// Table nodes per knot span.
const PER_SPAN: usize = 16;

/// One boundary curve of S with its arc-length and curvature table.
#[derive(Clone, Debug)]
pub struct BoundaryCurve {
    pub side: Side,
    /// Parameter range of the curve and the fixed other parameter.
    pub t0: f64,
    pub t1: f64,
    pub fixed: f64,
    /// Table nodes: parameter, arc length from `t0`, curvature.
    pub t: Vec<f64>,
    pub s: Vec<f64>,
    pub kappa: Vec<f64>,
    /// Total arc length.
    pub length: f64,
    /// The border is a single point (a pole): no arc length to measure.
    pub pole: bool,
}

impl BoundaryCurve {
    /// Measure the border `side` of `s`.
    pub fn new(
        s: &NurbsSurface<f64, 3>,
        side: Side,
        closure: &Closure,
    ) -> Result<Self, ReparamError> {
        let (u0, u1, v0, v1) = s.hom.domain();
        let (t0, t1, fixed, knots) = match side {
            Side::VMin => (u0, u1, v0, &s.hom.ku),
            Side::VMax => (u0, u1, v1, &s.hom.ku),
            Side::UMin => (v0, v1, u0, &s.hom.kv),
            Side::UMax => (v0, v1, u1, &s.hom.kv),
        };
        let uv = |t: f64| {
            if side.along_u() {
                (t, fixed)
            } else {
                (fixed, t)
            }
        };
        let speed = |t: f64| {
            let (u, v) = uv(t);
            let (_, su, sv) = point_d1(s, u, v);
            crate::geom::norm(if side.along_u() { &su } else { &sv })
        };
        let mut c = BoundaryCurve {
            side,
            t0,
            t1,
            fixed,
            t: vec![],
            s: vec![],
            kappa: vec![],
            length: 0.0,
            pole: closure.degenerate[side.closure_index()],
        };
        let scale = s
            .points_weights()
            .0
            .iter()
            .flatten()
            .fold(0.0f64, |m, x| m.max(x.abs()));
        let abs = 1e-15 * scale;
        if c.pole {
            // A border collapsed in the control net: no arc length to measure.
            return Ok(c);
        }
        let breaks = knots.breakpoints();
        let mut acc = 0.0;
        for w in breaks.windows(2) {
            for k in 0..PER_SPAN {
                let a = w[0] + (w[1] - w[0]) * k as f64 / PER_SPAN as f64;
                let b = if k + 1 == PER_SPAN {
                    w[1]
                } else {
                    w[0] + (w[1] - w[0]) * (k + 1) as f64 / PER_SPAN as f64
                };
                if c.t.is_empty() {
                    c.push_node(s, side, a, 0.0)?;
                }
                acc += integrate(&speed, a, b, QUAD_TOL, abs);
                c.push_node(s, side, b, acc)?;
            }
        }
        if !acc.is_finite() {
            let (u, v) = uv(t0);
            return Err(ReparamError::NotFinite(u, v));
        }
        c.length = acc;
        if acc <= 1e-12 * scale.max(f64::MIN_POSITIVE) {
            c.pole = true;
        }
        Ok(c)
    }

    fn push_node(
        &mut self,
        s: &NurbsSurface<f64, 3>,
        side: Side,
        t: f64,
        arc: f64,
    ) -> Result<(), ReparamError> {
        let (u, v) = if side.along_u() {
            (t, self.fixed)
        } else {
            (self.fixed, t)
        };
        let d = s.derivatives2(&u, &v);
        let (d1, d2) = if side.along_u() {
            (d[1], d[3])
        } else {
            (d[2], d[5])
        };
        if d.iter().flatten().any(|x| !x.is_finite()) {
            return Err(ReparamError::NotFinite(u, v));
        }
        let sp = crate::geom::norm(&d1);
        // κ = |C' × C''| / |C'|³; at a point of zero speed the curvature is not defined by
        // the parametrization, and the node contributes none.
        let k = if sp > 0.0 {
            crate::geom::norm(&crate::geom::cross(&d1, &d2)) / (sp * sp * sp)
        } else {
            0.0
        };
        self.t.push(t);
        self.s.push(arc);
        self.kappa.push(if k.is_finite() { k } else { 0.0 });
        Ok(())
    }

    /// The point of the domain of S at curve parameter `t`.
    pub fn domain_point(&self, t: f64) -> [f64; 2] {
        if self.side.along_u() {
            [t, self.fixed]
        } else {
            [self.fixed, t]
        }
    }

    /// Interpolation points of step 1 as fractions of the arc length, `0 = f_0 < … < f_N = 1`.
    pub fn interpolation_fractions(&self, p: &Params) -> Vec<f64> {
        let n_min = p.min_pieces as f64;
        let m: Vec<f64> = self
            .kappa
            .iter()
            .map(|&k| {
                n_min / self.length + k / p.max_turn + (k * k * k / (76.8 * p.tol)).powf(0.25)
            })
            .collect();
        let mut cm = vec![0.0];
        for k in 1..self.s.len() {
            let ds = self.s[k] - self.s[k - 1];
            cm.push(cm[k - 1] + ds * (m[k] + m[k - 1]) / 2.0);
        }
        let total = *cm.last().unwrap_or(&0.0);
        let n = ((total - 1e-9).ceil().max(n_min) as usize).clamp(p.min_pieces, p.max_pieces);
        let mut f = vec![0.0];
        let mut k = 0;
        for j in 1..n {
            let target = total * j as f64 / n as f64;
            while k + 2 < cm.len() && cm[k + 1] < target {
                k += 1;
            }
            let (a, b) = (cm[k], cm[k + 1]);
            let r = if b > a {
                ((target - a) / (b - a)).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let arc = self.s[k] + r * (self.s[k + 1] - self.s[k]);
            let fr = arc / self.length;
            if fr > *f.last().unwrap_or(&0.0) && fr < 1.0 {
                f.push(fr);
            }
        }
        f.push(1.0);
        f
    }

    /// The curve parameter at arc-length fraction `f` (`s(t) = f L`): the table bracket, then
    /// safeguarded Newton steps on `s(t) − f L` with `s` integrated by [`integrate`]. On a
    /// pole the parameter is `t0 + f (t1 − t0)` (every parameter gives the same point).
    pub fn param_at_fraction(&self, s: &NurbsSurface<f64, 3>, f: f64) -> f64 {
        if self.pole || f <= 0.0 {
            return if self.pole {
                self.t0 + f.clamp(0.0, 1.0) * (self.t1 - self.t0)
            } else {
                self.t0
            };
        }
        if f >= 1.0 {
            return self.t1;
        }
        let target = f * self.length;
        let k = self
            .s
            .partition_point(|&x| x <= target)
            .clamp(1, self.s.len() - 1)
            - 1;
        let (mut lo, mut hi) = (self.t[k], self.t[k + 1]);
        let base = self.s[k];
        let speed = |t: f64| {
            let [u, v] = self.domain_point(t);
            let (_, su, sv) = point_d1(s, u, v);
            crate::geom::norm(if self.side.along_u() { &su } else { &sv })
        };
        let span = self.s[k + 1] - base;
        let mut t = if span > 0.0 {
            lo + (hi - lo) * ((target - base) / span).clamp(0.0, 1.0)
        } else {
            lo
        };
        for _ in 0..60 {
            let g = base + integrate(&speed, self.t[k], t, QUAD_TOL, 1e-16 * self.length) - target;
            if g.abs() <= 1e-13 * self.length {
                break;
            }
            if g > 0.0 {
                hi = t;
            } else {
                lo = t;
            }
            let sp = speed(t);
            let newton = if sp > 0.0 { t - g / sp } else { f64::NAN };
            t = if newton > lo && newton < hi {
                newton
            } else {
                (lo + hi) / 2.0
            };
            if hi - lo <= 1e-15 * (self.t1 - self.t0).abs() {
                break;
            }
        }
        t
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gauss_legendre_integrates_smooth_and_kinked_functions() {
        let f = |x: f64| x.sin();
        assert!((integrate(&f, 0.0, 3.0, 1e-12, 0.0) - (1.0 - 3f64.cos())).abs() < 1e-12);
        let g = |x: f64| (x - 0.3).abs();
        assert!((integrate(&g, 0.0, 1.0, 1e-12, 0.0) - (0.045 + 0.245)).abs() < 1e-9);
    }

    #[test]
    fn quarter_circle_arc_length_and_fractions() {
        // Cylinder r = 2 about z: the border v = v0 is a full circle of length 4π.
        let s = crate::spline::construct::cylinder(
            &crate::spline::construct::Frame::WORLD,
            2.0,
            0.0,
            1.0,
        )
        .unwrap();
        let c = BoundaryCurve::new(&s, Side::VMin, &Closure::of(&s)).unwrap();
        assert!(
            (c.length - 4.0 * std::f64::consts::PI).abs() < 1e-9,
            "{}",
            c.length
        );
        let p = Params::default();
        let f = c.interpolation_fractions(&p);
        // Constant curvature: equal pieces, each turning at most max_turn.
        let n = f.len() - 1;
        assert!(2.0 * std::f64::consts::PI / n as f64 <= p.max_turn + 1e-9);
        for w in f.windows(2) {
            assert!((w[1] - w[0] - 1.0 / n as f64).abs() < 1e-3);
        }
        // The parameter at a fraction lies at that fraction of the arc length.
        for fr in [0.1, 0.37, 0.8] {
            let t = c.param_at_fraction(&s, fr);
            let p = s.eval(&t, &0.0);
            let ang = p[1].atan2(p[0]).rem_euclid(2.0 * std::f64::consts::PI);
            assert!(
                (ang / (2.0 * std::f64::consts::PI) - fr).abs() < 1e-10,
                "{fr}: {ang}"
            );
        }
    }
}
