//! Rational patches in the f64 path: a NURBS surface's Bézier patch `S = X / W` (homogeneous
//! numerator `X`, weight `W > 0`, both polynomial patches) reduced to the polynomial
//! machinery of steps 3 and 6.
//!
//! **Centring.** With a point `c` (any constant), `S − c = Q / W` where `Q = X − c W` is a
//! polynomial patch whose control points are `W_ij (P_ij − c)`. With positive weights each
//! `S(x)` is a convex combination of the control points `P_ij = X_ij / W_ij`, so
//! `|S(x) − c| ≤ ρ := max_ij |P_ij − c|`, and `W(x) ≥ w_lo := min_ij W_ij`.
//!
//! **Lipschitz bound (step 3).** For `x, y` in a convex region `R` of the patch,
//! `S(x) − S(y) = (Q(x) − Q(y)) / W(x) − (S(y) − c) (W(x) − W(y)) / W(x)`, hence
//! `|S(x) − S(y)| ≤ (K_Q + ρ K_W) |x − y| / w_lo`
//! with `K_Q`, `K_W` any Lipschitz bounds of the polynomial patches `Q` and `W` on `R` —
//! eq. (12) or the local hodograph bound of [`super::cells`], applied to each. This is the
//! bound eq. (12) stands for when S is rational (the paper treats polynomial S only);
//! its hypotheses: positive weights (checked: `w_lo > 0` from the enclosures), `R` convex.
//!
//! **Mapping (step 6).** The blossom of `Q` and of `W` on a chord gives the homogeneous
//! Bézier curve of degree `p + q` exactly on S; its control points are `c + Q_k / W_k` with
//! weights `W_k` (a rational Bézier curve). The enclosures of `Q_k` and `W_k` bound both the
//! printed points and the printed weights; [`RationalCell::compose_line`] turns them into a
//! bound on the distance between the printed curve and the exact one.

use super::ibez::{I, IP, norm_hi};
use super::midpatch::{IPatch, MidPatch};
use crate::curve_on_surface::g1::F64Patch;

/// The rational part of a cell (see the module doc): the weight patch, the centre `c`, `ρ`
/// and `w_lo`.
#[derive(Clone, Debug)]
pub struct RationalCell {
    /// The weight patch `W` in coordinate 0 (coordinates 1, 2 are zero).
    pub w: MidPatch,
    pub w_hodo_u: Option<MidPatch>,
    pub w_hodo_v: Option<MidPatch>,
    /// The midpoints of `Q` and of the weights, with their hodographs (for tangents,
    /// computed in f64).
    pub q_f64: F64Patch,
    pub w_f64: F64Patch,
    pub center: [f64; 3],
    /// Upper bound of `max_ij |P_ij − c|`.
    pub rho: f64,
    /// Lower bound (positive) of `min_ij W_ij`.
    pub w_lo: f64,
}

/// Why a rational patch cannot be used.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NonPositiveWeight;

impl RationalCell {
    /// From the enclosed homogeneous patch `x` and weight patch `w` (coordinate 0): the
    /// centred numerator `Q = X − c W` (enclosed) and the rational part.
    pub fn new(x: &IPatch, w: &IPatch) -> Result<(IPatch, RationalCell), NonPositiveWeight> {
        if w.net.iter().chain(&x.net).flatten().any(|c| !c.is_finite()) {
            return Err(NonPositiveWeight);
        }
        let w_lo = w.net.iter().map(|c| c[0].lo).fold(f64::INFINITY, f64::min);
        if !(w_lo > 0.0 && w_lo.is_finite()) {
            return Err(NonPositiveWeight);
        }
        let pts: Vec<IP<3>> = x
            .net
            .iter()
            .zip(&w.net)
            .map(|(xp, wp)| std::array::from_fn(|c| div(xp[c], wp[0])))
            .collect();
        let center: [f64; 3] = std::array::from_fn(|c| {
            let lo = pts.iter().map(|p| p[c].lo).fold(f64::INFINITY, f64::min);
            let hi = pts
                .iter()
                .map(|p| p[c].hi)
                .fold(f64::NEG_INFINITY, f64::max);
            0.5 * lo + 0.5 * hi
        });
        let ic: IP<3> = std::array::from_fn(|c| I::point(center[c]));
        let rho = pts
            .iter()
            .map(|p| norm_hi(&std::array::from_fn::<I, 3, _>(|c| p[c] - ic[c])))
            .fold(0.0, f64::max);
        let q = IPatch {
            p: x.p,
            q: x.q,
            net: x
                .net
                .iter()
                .zip(&w.net)
                .map(|(xp, wp)| std::array::from_fn(|c| xp[c] - ic[c] * wp[0]))
                .collect(),
        };
        let wm = MidPatch::new(w);
        let q_f64 = f64_patch(&MidPatch::new(&q));
        Ok((
            q,
            RationalCell {
                w_hodo_u: wm.hodograph(true),
                w_hodo_v: wm.hodograph(false),
                q_f64,
                w_f64: f64_patch(&wm),
                w: wm,
                center,
                rho,
                w_lo,
            },
        ))
    }

    /// The Lipschitz bound of S from bounds `k_q` of `Q` and `k_w` of `W` on the same convex
    /// region: `(K_Q + ρ K_W) / w_lo`, rounded up.
    pub fn lipschitz(&self, k_q: f64, k_w: f64) -> f64 {
        crate::curve_on_surface::tolerance::rational_lipschitz(k_q, k_w, self.rho, self.w_lo)
    }

    /// The image of the local chord `a → b` (exact local coordinates within `dt` of these):
    /// the printed control points `c + Q_k / W_k` and weights `W_k` of the rational Bézier
    /// curve of degree `p + q`, and a proven bound on the distance between the curve they
    /// define and the exact image. With `|Q̂_k − Q_k|, |Ŵ_k − W_k|` bounded by the blossoms'
    /// error bounds, the interval quotients enclose the exact points, whose printed
    /// midpoints are within `δ` (per coordinate) of them; the printed weights are within a
    /// relative `ε` of the exact ones (plus `2u` for the B-spline form's joint rescaling).
    /// A rational Bézier curve is `Σ λ_k P_k` with `λ_k = B_k W_k / Σ B_j W_j`; relative
    /// weight errors `≤ ε` change each `λ_k` by at most `λ_k · 2ε / (1 − ε)`, and `Σ λ_k = 1`,
    /// so the printed curve is within `√3 δ + 2ε / (1 − ε) · max_k |P_k − c|` of the exact one.
    pub fn compose_line(
        &self,
        q: &MidPatch,
        a: [f64; 2],
        b: [f64; 2],
        dt: f64,
    ) -> Option<(Vec<[f64; 3]>, Vec<f64>, f64)> {
        let (xq, eq) = q.compose_line(a, b, dt);
        let (xw, ew) = self.w.compose_line(a, b, dt);
        let ic: IP<3> = std::array::from_fn(|c| I::point(self.center[c]));
        let (mut delta, mut eps, mut reach) = (0.0f64, 0.0f64, 0.0f64);
        let mut pts = Vec::with_capacity(xq.len());
        let mut ws = Vec::with_capacity(xq.len());
        for (x, w) in xq.iter().zip(&xw) {
            let wi = I::new((w[0] - ew).next_down(), (w[0] + ew).next_up());
            if wi.lo.is_nan() || wi.lo <= 0.0 {
                return None;
            }
            let rel: IP<3> = std::array::from_fn(|c| {
                div(I::new((x[c] - eq).next_down(), (x[c] + eq).next_up()), wi)
            });
            let p: IP<3> = std::array::from_fn(|c| rel[c] + ic[c]);
            let m: [f64; 3] = std::array::from_fn(|c| p[c].mid());
            for c in 0..3 {
                delta = delta.max((p[c].hi - m[c]).max(m[c] - p[c].lo));
            }
            reach = reach.max(norm_hi(&rel));
            eps = eps.max((ew / wi.lo).next_up());
            pts.push(m);
            ws.push(w[0]);
        }
        let bound = crate::curve_on_surface::tolerance::rational_rounding(delta, eps, reach);
        if !bound.is_finite() {
            return None;
        }
        Some((pts, ws, bound))
    }
}

/// A midpoint patch as an f64 patch with its hodographs.
fn f64_patch(m: &MidPatch) -> F64Patch {
    F64Patch::new(crate::spline::BezierSurface {
        p: m.p,
        q: m.q,
        net: m.m.clone(),
    })
}

/// `a / b`, or the whole line when `b` may be zero (never here: both callers check `b > 0`).
fn div(a: I, b: I) -> I {
    a.checked_div(b)
        .unwrap_or(I::new(f64::NEG_INFINITY, f64::INFINITY))
}
