//! Step 3 — the 2D tolerance `d` of eq. (12), per Bézier patch, scaled to the patch's knot
//! spans.
//!
//! Eq. (12) (Yang et al.) for a patch of degrees `m × n` on `[0,1]²`:
//! `d = ε_D / (n · max_{i,h,k} |P_{h,i+1} - P_{k,i}| + m · max_{i,h,k} |P_{i+1,h} - P_{i,k}|)`.
//! It rests on `|S(a) - S(b)| ≤ sup|S_u|·|Δu| + sup|S_v|·|Δv|` with the hodograph bounds
//! `|S_u| ≤ m · max|P_{i+1,h} - P_{i,k}|`, `|S_v| ≤ n · max|P_{h,i+1} - P_{k,i}|`.
//!
//! **Scaling.** A patch of a B-spline surface covers `[a,b] × [c,e]` in the global parameters
//! in which the domain curve is given. With local `s = (u - a)/(b - a)`, the chain rule gives
//! `∂S/∂u = (1/(b-a)) ∂S/∂s`, so in global coordinates
//! `d = ε_D / (n · A_v / (e - c) + m · A_u / (b - a))`,
//! where `A_u`, `A_v` are the two maxima above. (Test: `tests/curve_on_surface.rs` checks the
//! bound against measured Lipschitz quotients on patches of very unequal spans.)
//!
//! All quantities are upper bounds computed with outward rounding from the *exact* patch
//! control points (the patches come from exact knot insertion), so `d` is a lower bound of
//! the true tolerance: never optimistic.

use crate::geom::Point;
use crate::scalar::{Rational, Scalar};
use crate::spline::BezierSurface;

/// Upper bound (f64) of `sqrt(x)` for an exact non-negative rational `x`.
pub fn sqrt_up(x: &Rational) -> f64 {
    let f = Scalar::to_f64(x);
    let f = if f.is_finite() { f.next_up() } else { f };
    f.max(0.0).sqrt().next_up()
}

/// `max_{i,h,k} |P_{i+1,h} - P_{i,k}|` (first index is u): an upper bound, rounded up.
fn a_u(s: &BezierSurface<[Rational; 3]>) -> f64 {
    let mut best = 0.0f64;
    for i in 0..s.p {
        for h in 0..=s.q {
            for k in 0..=s.q {
                let d = s.at(i + 1, h).sub(s.at(i, k));
                best = best.max(sqrt_up(&crate::geom::norm2(&d)));
            }
        }
    }
    best
}

/// `max_{i,h,k} |P_{h,i+1} - P_{k,i}|` (second index is v).
fn a_v(s: &BezierSurface<[Rational; 3]>) -> f64 {
    let mut best = 0.0f64;
    for i in 0..s.q {
        for h in 0..=s.p {
            for k in 0..=s.p {
                let d = s.at(h, i + 1).sub(s.at(k, i));
                best = best.max(sqrt_up(&crate::geom::norm2(&d)));
            }
        }
    }
    best
}

/// Upper bound on `n·A_v/(e-c) + m·A_u/(b-a)`: the constant `K` with
/// `|S(x) - S(y)| ≤ K |x - y|` on the patch (global parameters).
pub fn lipschitz_bound(s: &BezierSurface<[Rational; 3]>, du: f64, dv: f64) -> f64 {
    let m = s.p as f64;
    let n = s.q as f64;
    // du, dv are exact span widths (differences of f64 knots may round: bound below).
    let du_lo = du.next_down();
    let dv_lo = dv.next_down();
    let ku = (m * a_u(s)).next_up() / du_lo;
    let kv = (n * a_v(s)).next_up() / dv_lo;
    (ku.next_up() + kv.next_up()).next_up()
}

/// The 2D tolerance `d = ε_D / K`, rounded down.
pub fn tolerance_2d(eps_d: f64, lipschitz: f64) -> f64 {
    if lipschitz <= 0.0 {
        return f64::INFINITY;
    }
    (eps_d / lipschitz).next_down()
}

/// Local Lipschitz bound on a sub-rectangle of a patch (a refinement of eq. (12), still
/// proven): with `L_u = sup_R |S_u|`, `L_v = sup_R |S_v|` over the rectangle `R` that holds a
/// segment's curve piece and chord, Cauchy–Schwarz gives
/// `|S(x) - S(y)| ≤ |S_u||Δu| + |S_v||Δv| ≤ sqrt(L_u² + L_v²) |x - y|` for `x, y ∈ R` (R is
/// convex). The sups are bounded by the control points of the exact hodograph patches
/// restricted to `R` (blossoming; convex hull property), scaled by `1 / span` to global
/// parameters (the chain rule, as in [`lipschitz_bound`]).
pub fn local_lipschitz(
    hodo_u: Option<&BezierSurface<[Rational; 3]>>,
    hodo_v: Option<&BezierSurface<[Rational; 3]>>,
    r: [Rational; 4],
    du: f64,
    dv: f64,
) -> f64 {
    let sup = |h: Option<&BezierSurface<[Rational; 3]>>| -> f64 {
        match h {
            None => 0.0,
            Some(h) => h
                .sub_patch(&r[0], &r[1], &r[2], &r[3])
                .net
                .iter()
                .map(|p| sqrt_up(&crate::geom::norm2(p)))
                .fold(0.0, f64::max),
        }
    };
    let lu = (sup(hodo_u) / du.next_down()).next_up();
    let lv = (sup(hodo_v) / dv.next_down()).next_up();
    (lu * lu + lv * lv).next_up().sqrt().next_up()
}

/// The Lipschitz bound of a rational patch `S = c + Q / W` from bounds `k_q` of `Q` and `k_w`
/// of `W` on one convex region: `(K_Q + ρ K_W) / w_lo` (`float::rational`), rounded up.
pub fn rational_lipschitz(k_q: f64, k_w: f64, rho: f64, w_lo: f64) -> f64 {
    ((k_q + (rho * k_w).next_up()).next_up() / w_lo).next_up()
}

/// The distance between a rational Bézier curve given by printed points (within `delta` of
/// the exact ones in every coordinate) and printed weights (within a relative `eps` of the
/// exact ones) and the exact curve: `√3 δ + 2ε / (1 − ε) · reach`, `reach` bounding
/// `|P_k − c|` for some point `c` (`float::rational`'s `compose_line` has the argument);
/// `2u` is added to `eps` for the B-spline form's joint rescaling. Infinite when `ε ≥ 1/2`.
pub fn rational_rounding(delta: f64, eps: f64, reach: f64) -> f64 {
    let eps = ((eps + 4.5e-16) * (1.0 + 1e-15)).next_up();
    if eps.is_nan() || eps >= 0.5 {
        return f64::INFINITY;
    }
    ((3f64.sqrt() * 1.000001 * delta).next_up()
        + ((2.0 * eps / (1.0 - eps)).next_up() * reach).next_up())
    .next_up()
}
