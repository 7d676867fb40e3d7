//! The curve certificate at and next to a proven branch point, where Krawczyk's test on the
//! plane ([`super::krawczyk`]) cannot succeed: the two surfaces are tangent at the branch point
//! (the Jacobian of `S_A − S_B` is singular there), and a plane through a nearby point meets
//! both crossing branches, so no zero is unique. The argument here proves *existence* of a
//! true intersection point without uniqueness, by the intermediate value theorem.
//!
//! **The function.** One surface `S` (parameters `x = (u, v)`) carries a segment, the other
//! `F` (parameters `y = (s, t)`) the foot. Fix two `f64` vectors `e1`, `e2` (an orthonormal
//! pair across the approximate common normal `n0`; any vectors with `e1 × e2 ≠ 0` will do)
//! and `N = e1 × e2` (enclosed). For `x` in a parameter box `X` and `y` in a box `Y` let
//!
//! `G(x, y) = ((S(x) − F(y))·e1, (S(x) − F(y))·e2)`,  `H(x, y) = (S(x) − F(y))·N`.
//!
//! `G = 0` says that `F(y)` lies on the line through `S(x)` along `N` (the foot of `S(x)` on
//! `F` along a fixed direction); `G = 0` and `H = 0` say `S(x) − F(y)` is orthogonal to the
//! basis `e1, e2, N`, i.e. `S(x) = F(y)`: a true common point.
//!
//! **Theorem (the foot).** Let `K(Y) = y0 − Y0 G(X, y0) + (I − Y0 J(Y)) (Y − y0)` with `y0 ∈ Y`,
//! any real 2 × 2 matrix `Y0`, `G(X, y0)` an enclosure of `{G(x, y0) : x ∈ X}` and `J(Y)` the
//! enclosure of `∂G/∂y = −[F_s·e_i, F_t·e_i]` over `Y` (one-sided across knot lines: the
//! mean-value form of [`super::enclose`]). If `K(Y) ⊂ int Y`, then for every `x ∈ X` the map
//! `G(x, ·)` has exactly one zero `y(x)` in `Y` (Krawczyk's theorem for the fixed `x`, whose
//! operator lies inside `K(Y)`), and `x ↦ y(x)` is continuous on `X`: for `x_k → x`, every
//! limit point `y'` of `y(x_k)` in the compact `Y` has `G(x, y') = 0` by continuity of `G`,
//! so `y' = y(x)` by uniqueness.
//!
//! **Theorem (the crossing).** Then `h(x) = H(x, y(x))` is continuous on `X`. If `a, b ∈ X`
//! have `h(a) > 0 > h(b)` (proven: `h` enclosed at the `f64` points `a`, `b` with `y(a)`,
//! `y(b)` enclosed by iterating `Z ← K(Z) ∩ Z` from `Z = Y`, which keeps every zero in `Z`),
//! the segment `[a, b] ⊂ X` (boxes are convex) holds an `x*` with `h(x*) = 0` (intermediate
//! value theorem on `τ ↦ h(a + τ (b − a))`), and `q = S(x*) = F(y(x*))` is a true common
//! point. It is a point of both *faces* when `X` and `Y` lie in the closed parameter domains
//! (checked). Bisection keeps a sub-segment with proven opposite signs at its ends, so `x*`
//! lies in its bounding box `X*`, and `||p − q|| ≤ sup ||p − S(X*)||`, bounded from an
//! enclosure of `S` over `X*` with upward rounding: the radius.
//!
//! **Where the signs come from.** At a branch point the signed distance `h` has a
//! non-degenerate saddle (proven by [`super::singular`]) with value near 0, so on a small
//! circle of parameters around the point it takes both signs; along a branch next to it, a
//! segment across the branch changes sign. The segments tried are the diameters and chords of
//! such circles (radius `ε` in model units, `ε` doubling from `1e-9` of the scale), and radial
//! pairs between consecutive circles (a sample's sign carries over when its foot box lies
//! in the new `Y`: the foot is then the same, the only one in `Y`); the first
//! `ε` with a proven sign change gives the radius, about `ε` — at a branch point about
//! `sqrt(δ / κ)` for the enclosure width `δ` of `h` and the curvature difference `κ`, which is
//! what any argument from signs of `h` can reach.
//!
//! **Hypotheses.** Continuous surfaces, weights not vanishing on the boxes (refused by the
//! interval quotients otherwise). Nothing about the branch point itself is used in the proof:
//! the singular proof only decides where this certificate is tried (points near a proven
//! branch point, where Krawczyk's test fails). The full statement: docs/ssi-branch-points.md.

mod circles;

use super::certify::ExactSurface;
use super::enclose::{enclose_jet, enclose_point};
use super::refine::point_d1;
use crate::geom::dot;
use crate::scalar::Interval;
use crate::spline::NurbsSurface;
use circles::with_roles;

type I = Interval;
type M2 = [[f64; 2]; 2];

fn pt(x: f64) -> I {
    Interval::point(x)
}

/// A proven true intersection point near `p`, found by a sign change.
#[derive(Clone, Copy, Debug)]
pub struct SignChangeCert {
    /// Upper bound on `||p − q||`, `q` a true common point of both faces.
    pub radius: f64,
    /// The surface carrying the segment (`'a'` or `'b'`) and the box of its parameters
    /// holding the zero `x*`.
    pub on: char,
    pub params: [I; 2],
    /// Radius (model units) of the circle of parameters whose samples changed sign.
    pub eps: f64,
}

/// Why no certificate came out.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SignChangeFail {
    /// No proven sign change on any circle tried.
    NoSignChange,
    /// A sign change was proven, but the radius exceeds the run's tolerance.
    AboveTol(f64),
}

/// Samples per circle.
const SAMPLES: usize = 8;
/// Growth of the circle radius per step.
const GROWTH: f64 = 2.0;
/// Smallest and largest circle radius, relative to the point's scale `1 + max |p_k|`.
const EPS_MIN: f64 = 1e-9;
const EPS_MAX: f64 = 1e-5;
/// Bisection steps on a segment, and sign-changing pairs tried per circle.
const BISECT: usize = 80;
const PAIRS: usize = 4;

fn inv2(m: &M2) -> Option<M2> {
    let d = m[0][0] * m[1][1] - m[0][1] * m[1][0];
    let r = [[m[1][1] / d, -m[0][1] / d], [-m[1][0] / d, m[0][0] / d]];
    (d != 0.0 && r.iter().flatten().all(|x| x.is_finite())).then_some(r)
}

/// The foot system for one assignment of roles (see the module comment).
struct Foot<'a> {
    s: &'a NurbsSurface<f64, 3>,
    f: &'a NurbsSurface<f64, 3>,
    es: &'a ExactSurface,
    ef: &'a ExactSurface,
    e: [[f64; 3]; 2],
    /// Enclosure of `e1 × e2`.
    n: [I; 3],
    dom_s: [f64; 4],
    dom_f: [f64; 4],
}

/// A box `Y` proven to hold, for every `x` of the segment box, exactly one foot `y(x)`.
struct FootBox {
    y: [I; 2],
    y0: [f64; 2],
    yinv: M2,
}

impl Foot<'_> {
    fn g_f64(&self, x: &[f64; 2], y: &[f64; 2]) -> ([f64; 2], M2) {
        let a = self.s.eval(&x[0], &x[1]);
        let (b, bs, bt) = point_d1(self.f, y[0], y[1]);
        let d = [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
        let g = [dot(&d, &self.e[0]), dot(&d, &self.e[1])];
        let j = [
            [-dot(&bs, &self.e[0]), -dot(&bt, &self.e[0])],
            [-dot(&bs, &self.e[1]), -dot(&bt, &self.e[1])],
        ];
        (g, j)
    }

    /// `f64` Newton for the foot of `S(x)` from `y`.
    fn newton(&self, x: &[f64; 2], mut y: [f64; 2]) -> Option<[f64; 2]> {
        for _ in 0..8 {
            let (g, j) = self.g_f64(x, &y);
            let ji = inv2(&j)?;
            let d = [
                ji[0][0] * g[0] + ji[0][1] * g[1],
                ji[1][0] * g[0] + ji[1][1] * g[1],
            ];
            y = [y[0] - d[0], y[1] - d[1]];
            if !(y[0].is_finite() && y[1].is_finite()) {
                return None;
            }
            if d[0].abs() + d[1].abs() <= 1e-17 * (1.0 + y[0].abs() + y[1].abs()) {
                break;
            }
        }
        Some(y)
    }

    /// `K(Z)` for the enclosure `sx` of `S(x)` (a point or a box of `x`), centre `c ∈ Z`.
    fn krawczyk(&self, sx: &[I; 3], c: &[f64; 2], yinv: &M2, z: &[I; 2]) -> Option<[I; 2]> {
        let fc = enclose_point(self.f, pt(c[0]), pt(c[1]))?;
        let jet = enclose_jet(self.f, z[0], z[1])?;
        let de: [I; 3] = std::array::from_fn(|k| sx[k] - fc[k]);
        let e: [[I; 3]; 2] = self.e.map(|v| v.map(pt));
        let d3 = |a: &[I; 3], b: &[I; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        let g = [d3(&de, &e[0]), d3(&de, &e[1])];
        let j = [
            [pt(0.0) - d3(&jet.su, &e[0]), pt(0.0) - d3(&jet.sv, &e[0])],
            [pt(0.0) - d3(&jet.su, &e[1]), pt(0.0) - d3(&jet.sv, &e[1])],
        ];
        let mut k = [pt(0.0); 2];
        for i in 0..2 {
            let mut acc = pt(c[i]) - (pt(yinv[i][0]) * g[0] + pt(yinv[i][1]) * g[1]);
            for col in 0..2 {
                let cij = pt(if i == col { 1.0 } else { 0.0 })
                    - (pt(yinv[i][0]) * j[0][col] + pt(yinv[i][1]) * j[1][col]);
                acc = acc + cij * (z[col] - pt(c[col]));
            }
            k[i] = acc;
        }
        k.iter().all(|v| v.is_finite()).then_some(k)
    }

    /// The foot box over the parameter box `x` (the first theorem of the module comment).
    fn foot_box(&self, x: &[I; 2], y_seed: [f64; 2]) -> Option<FootBox> {
        let xc = [x[0].mid(), x[1].mid()];
        let y0 = self.newton(&xc, y_seed)?;
        let (_, j) = self.g_f64(&xc, &y0);
        let yinv = inv2(&j)?;
        let sx = enclose_point(self.s, x[0], x[1])?;
        // Radius: twice the reach of the operator over a point box, then inflated.
        let k0 = self.krawczyk(&sx, &y0, &yinv, &y0.map(pt))?;
        let mut rad: [f64; 2] = std::array::from_fn(|i| {
            2.0 * (k0[i].lo - y0[i]).abs().max((k0[i].hi - y0[i]).abs())
                + 64.0 * f64::EPSILON * (y0[i].abs() + self.dom_f[2 * i + 1] - self.dom_f[2 * i])
        });
        for _ in 0..8 {
            let y: [I; 2] = std::array::from_fn(|i| {
                I::new((pt(y0[i]) - pt(rad[i])).lo, (pt(y0[i]) + pt(rad[i])).hi)
            });
            let k = self.krawczyk(&sx, &y0, &yinv, &y)?;
            if (0..2).all(|i| k[i].lo > y[i].lo && k[i].hi < y[i].hi) {
                let inside = (0..2)
                    .all(|i| y[i].lo >= self.dom_f[2 * i] && y[i].hi <= self.dom_f[2 * i + 1]);
                return inside.then_some(FootBox { y, y0, yinv });
            }
            for i in 0..2 {
                let reach = (k[i].lo - y0[i]).abs().max((k[i].hi - y0[i]).abs());
                rad[i] = (2.0 * rad[i]).max(1.25 * reach);
            }
        }
        None
    }

    /// Proven sign of `h(x) = H(x, y(x))` at the `f64` point `x` of the foot box's segment
    /// box, with the box `Z ⊂ Y` holding `y(x)`; `None` when undecided.
    fn sign_at(&self, x: &[f64; 2], fb: &FootBox) -> Option<(bool, [I; 2])> {
        let sx = enclose_point(self.s, pt(x[0]), pt(x[1]))?;
        let yc = self.newton(x, fb.y0)?;
        let yc = [
            yc[0].clamp(fb.y[0].lo, fb.y[0].hi),
            yc[1].clamp(fb.y[1].lo, fb.y[1].hi),
        ];
        // Z ← K(Z) ∩ Z keeps y(x), the only zero in Y.
        let mut z = fb.y;
        for it in 0..3 {
            let c = if it == 0 {
                yc
            } else {
                [z[0].mid(), z[1].mid()]
            };
            if !(0..2).all(|i| z[i].lo <= c[i] && c[i] <= z[i].hi) {
                break;
            }
            let k = self.krawczyk(&sx, &c, &fb.yinv, &z)?;
            let n: [I; 2] =
                std::array::from_fn(|i| I::new(k[i].lo.max(z[i].lo), k[i].hi.min(z[i].hi)));
            if !(0..2).all(|i| n[i].lo <= n[i].hi) {
                return None;
            }
            z = n;
        }
        // F(y(x)) ∈ F(yc) + F_s(Z')(Z_s − yc_s) + F_t(Z')(Z_t − yc_t), Z' = hull(Z, yc).
        let zh: [I; 2] = std::array::from_fn(|i| z[i].hull(pt(yc[i])));
        let fc = enclose_point(self.f, pt(yc[0]), pt(yc[1]))?;
        let jet = enclose_jet(self.f, zh[0], zh[1])?;
        let (ds, dt) = (z[0] - pt(yc[0]), z[1] - pt(yc[1]));
        // Dotted with N first: F's tangents are nearly orthogonal to N, so the terms of the
        // foot's enclosure width nearly vanish.
        let d3 = |a: &[I; 3], b: &[I; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        let dc: [I; 3] = std::array::from_fn(|k| sx[k] - fc[k]);
        let rest = d3(&jet.su, &self.n) * ds + d3(&jet.sv, &self.n) * dt;
        let mut h = d3(&dc, &self.n) - rest;
        if h.contains_zero() {
            // Undecided in intervals: S(x) − F(yc) exactly (both points are f64 parameters),
            // rounded outward per component.
            let (a, b) = (self.es.exact_point(x)?, self.ef.exact_point(&yc)?);
            let d = a.minus_enclosed(&b)?;
            h = d3(&d, &self.n) - rest;
        }
        if h.is_pos() {
            Some((true, z))
        } else if h.is_neg() {
            Some((false, z))
        } else {
            None
        }
    }

    /// Bisection of `[a, b]` (signs `true` at `a`, `false` at `b`): a sub-segment with proven
    /// opposite signs at its ends, as its bounding box.
    ///
    /// Stops once the segment's length in model units (`w`: the lengths of `S_u`, `S_v`) is
    /// below `stop` (the radius is then set by the distance to `p`, not by the segment).
    fn bisect(
        &self,
        mut a: [f64; 2],
        mut b: [f64; 2],
        fb: &FootBox,
        w: &[f64; 2],
        stop: f64,
    ) -> [I; 2] {
        'outer: for _ in 0..BISECT {
            let len = ((b[0] - a[0]) * w[0]).hypot((b[1] - a[1]) * w[1]);
            if len <= stop {
                break;
            }
            // A split point of undecided sign (near the zero) is replaced by another one.
            for t in [0.5, 0.375, 0.625, 0.25, 0.75] {
                // The rounded point lies in the segment's box, where y(x) is continuous.
                let m: [f64; 2] = std::array::from_fn(|i| {
                    (a[i] + t * (b[i] - a[i])).clamp(a[i].min(b[i]), a[i].max(b[i]))
                });
                if m == a || m == b {
                    break 'outer;
                }
                match self.sign_at(&m, fb).map(|s| s.0) {
                    Some(true) => {
                        a = m;
                        continue 'outer;
                    }
                    Some(false) => {
                        b = m;
                        continue 'outer;
                    }
                    None => {}
                }
            }
            break;
        }
        std::array::from_fn(|i| I::new(a[i].min(b[i]), a[i].max(b[i])))
    }
}

/// The sign-change certificate of the point `p` with parameters `uv_a` on `sa`, `uv_b` on
/// `sb` (see the module comment): segments on `sa` with feet on `sb` first, then the other
/// way round. A radius above `tol` is reported as such, never as a certificate.
#[allow(clippy::too_many_arguments)]
pub fn certify_by_sign_change(
    sa: &NurbsSurface<f64, 3>,
    sb: &NurbsSurface<f64, 3>,
    ea: &ExactSurface,
    eb: &ExactSurface,
    p: &[f64; 3],
    uv_a: &[f64; 2],
    uv_b: &[f64; 2],
    tol: f64,
) -> Result<SignChangeCert, SignChangeFail> {
    if !p.iter().chain(uv_a).chain(uv_b).all(|c| c.is_finite()) {
        return Err(SignChangeFail::NoSignChange);
    }
    let c = with_roles(sa, sb, ea, eb, p, uv_a, uv_b, 'a', tol)
        .or_else(|| with_roles(sb, sa, eb, ea, p, uv_b, uv_a, 'b', tol));
    match c {
        Some(c) if c.radius <= tol => Ok(c),
        Some(c) => Err(SignChangeFail::AboveTol(c.radius)),
        None => Err(SignChangeFail::NoSignChange),
    }
}
