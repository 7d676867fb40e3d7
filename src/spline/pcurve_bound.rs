//! A proven bound on how far the curve a pcurve draws on a surface lies from a space curve:
//! the Hausdorff distance between `S(p(f))`, `f ∈ [f₀, f₁]`, and `C(t)`, `t ∈ [c₀, c₁]`
//! (an edge's pcurve on a face against the edge's 3D curve).
//!
//! # The argument
//!
//! Cut both ranges at matched breakpoints `f₀ = φ₀ < … < φ_m = f₁`, `c₀ = τ₀ < … < τ_m = c₁`
//! (the pcurve's knots and the curve's knots, each paired with its image under the linear map
//! between the ranges, then halvings). On piece `l` pair `f = φ_l + s(φ_{l+1} − φ_l)` with
//! `t = τ_l + s(τ_{l+1} − τ_l)`, `s ∈ [0, 1]`. If `|S(p(f(s))) − C(t(s))| ≤ r` on every piece,
//! every point of either curve lies within `r` of the other (each pairing is onto both
//! pieces): the Hausdorff distance is at most `r`. The pairing need not be the curves' true
//! correspondence; it is good when the pcurve was made by projecting `C` at the same
//! fractions of the ranges (as the writers' pcurves are) or shares the edge's parameter.
//!
//! On a piece, `p` is a rational Bézier curve of degree `d` in `s` with homogeneous
//! coefficients `(U_k, V_k, W_k)` (blossoms of `p` at the piece's ends) and `C` one of degree
//! `n` with coefficients `(X_k, w_k)`. With `W_k > 0`, `p(s)` lies in the convex hull of the
//! affine points `(U_k/W_k, V_k/W_k)`, so in the cells (knot rectangles of `S`) that their box
//! meets. On a cell `[u₀, u₁] × [v₀, v₁]` the surface is the rational Bézier patch
//! `S_c(x, y) = Σ P_ij^h B_i^p(x) B_j^q(y)` (homogeneous), `x = (u − u₀)/(u₁ − u₀)`. Writing
//! `x = X̂/W` with `X̂ = (U − u₀W)/(u₁ − u₀)` (and `Ŷ` alike),
//! `B_i^p(x) = C(p,i) X̂^i (W − X̂)^{p−i} / W^p`, so
//!
//! `N(s) := W^{p+q} · S_c^h(p(s)) = Σ_ij P_ij^h C(p,i) C(q,j) X̂^i (W−X̂)^{p−i} Ŷ^j (W−Ŷ)^{q−j}`,
//!
//! a Bézier polynomial of degree `(p+q)d` in `s`, computed by Bernstein products (the
//! composition of DeRose et al., see [`super::compose`]). It is an identity of polynomials,
//! valid for every `s`. With `N = (N_xyz, N_w)` and `C = (C_xyz, C_w)`,
//!
//! `S_c(p(s)) − C(t(s)) = E(s) / (N_w(s) C_w(s))`,  `E = N_xyz C_w − C_xyz N_w`,
//!
//! and by the convex hull property of Bézier polynomials `|E(s)| ≤ max_k |E_k|`,
//! `N_w(s) ≥ min_k N_w,k`, `C_w(s) ≥ min_k C_w,k`; so when both minima are positive,
//! `r_c = max_k |E_k| / (min N_w · min C_w)` bounds `|S_c(p(s)) − C(t(s))|` for every `s`.
//! At each `s`, `p(s)` lies in one of the cells the box meets and `S = S_c` there, so the
//! largest `r_c` over those cells bounds the piece. A piece whose bound exceeds the target
//! is halved (the control polygons converge to the polynomials quadratically).
//!
//! Every number is computed in outward-rounded [`Interval`] arithmetic from the f64 data
//! taken as exact: the pieces by the de Boor–Ramshaw recurrence, the cells by enclosed
//! Bézier extraction ([`super::enclosed_bezier`]).
//!
//! **Hypotheses**, each checked, or the bound is refused with the reason ([`Unproven`]):
//! positive weights of `p`, `C` and the composed `N_w` on every piece; the pcurve's box
//! inside the surface's domain (no extrapolation); the degree of `E` at most
//! [`MAX_ERROR_DEGREE`] (binomials exact in f64). The breakpoints themselves are f64 numbers;
//! any increasing choice is valid, which is why their rounding does not matter.

use super::enclosed_bezier::{EnclosedPatch, bspline_blossom, enclosed_bezier_patches};
use super::scaled_bernstein::{binom, mul, powers, scaled, unscaled};
use super::{NurbsCurve, NurbsSurface};
use crate::scalar::Interval;

type I = Interval;

/// Largest degree of the error polynomial `E` (`C(56, 28) < 2⁵³`: binomials exact in f64).
pub const MAX_ERROR_DEGREE: usize = 56;

/// Halvings of one matched piece.
pub const MAX_DEPTH: u32 = 10;

/// Halving goes on only while the halves' bounds fall below this fraction of the whole's.
pub const CONVERGED: f64 = 0.7;

/// Halvings in one call of [`SurfaceCells::bound`] (each costs two pieces' compositions).
pub const MAX_HALVINGS: usize = 2048;

/// Why no bound was proven.
#[derive(Clone, Debug, PartialEq)]
pub enum Unproven {
    /// The pcurve's control points leave the surface's domain near curve parameter `t`.
    OffDomain { t: f64 },
    /// A weight (of the pcurve, the curve or the composition) not proven positive near `t`.
    Weight { t: f64 },
    /// The error polynomial's degree is above [`MAX_ERROR_DEGREE`].
    Degree(usize),
    /// A knot vector or a range that cannot be enclosed (empty ranges, repeated interior
    /// knots beyond the degree, non-finite data).
    Extraction,
}

impl std::fmt::Display for Unproven {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Unproven::OffDomain { t } => {
                write!(f, "the pcurve leaves the surface's domain near t = {t}")
            }
            Unproven::Weight { t } => write!(f, "a weight is not proven positive near t = {t}"),
            Unproven::Degree(d) => write!(
                f,
                "the composed degree {d} is above {MAX_ERROR_DEGREE}: no bound attempted"
            ),
            Unproven::Extraction => f.write_str("a knot vector or range cannot be enclosed"),
        }
    }
}

/// A surface cut into its Bézier cells, enclosed once for every pcurve checked on it.
pub struct SurfaceCells {
    patches: Vec<EnclosedPatch>,
    ub: Vec<f64>,
    vb: Vec<f64>,
    /// Halvings left in the current call of [`SurfaceCells::bound`].
    halvings: std::cell::Cell<usize>,
}

/// A NURBS curve's knots, degree and homogeneous control points as point intervals.
struct HomCurve<const E: usize> {
    knots: super::KnotVector<f64>,
    ctrl: Vec<[I; E]>,
}

impl<const E: usize> HomCurve<E> {
    /// The enclosed Bézier coefficients of the curve over `[a, b]` (inside one knot span).
    fn piece(&self, a: f64, b: f64) -> Option<Vec<[I; E]>> {
        let p = self.knots.degree();
        let s = self.knots.find_span(&(0.5 * (a + b)));
        let (ia, ib) = (I::point(a), I::point(b));
        let mut xs = Vec::with_capacity(p);
        (0..=p)
            .map(|k| {
                xs.clear();
                xs.extend(std::iter::repeat_n(ia, p - k));
                xs.extend(std::iter::repeat_n(ib, k));
                bspline_blossom(self.knots.knots(), p, &self.ctrl, s, &xs)
            })
            .collect()
    }
}

fn hom2(c: &NurbsCurve<f64, 2>) -> HomCurve<3> {
    let ctrl = c.hom.control.iter();
    HomCurve {
        knots: c.hom.knots.clone(),
        ctrl: ctrl
            .map(|h| [h.wp[0], h.wp[1], h.w].map(I::point))
            .collect(),
    }
}

fn hom3(c: &NurbsCurve<f64, 3>) -> HomCurve<4> {
    let ctrl = c.hom.control.iter();
    HomCurve {
        knots: c.hom.knots.clone(),
        ctrl: ctrl
            .map(|h| [h.wp[0], h.wp[1], h.wp[2], h.w].map(I::point))
            .collect(),
    }
}

/// The cells `first..=last` of breakpoints `br` that `[lo, hi]` meets; `None` outside.
fn cells_meeting(br: &[f64], lo: f64, hi: f64) -> Option<(usize, usize)> {
    let n = br.len().checked_sub(1)?;
    if !(lo >= br[0] && hi <= br[n] && lo <= hi) {
        return None;
    }
    let first = (0..n).find(|&i| br[i + 1] >= lo)?;
    let last = (0..n).rev().find(|&j| br[j] <= hi)?;
    Some((first, last))
}

impl SurfaceCells {
    /// `None` when the surface's Bézier cells cannot be enclosed.
    pub fn new(s: &NurbsSurface<f64, 3>) -> Option<SurfaceCells> {
        let patches = enclosed_bezier_patches(s)?;
        let (ub, vb) = (s.hom.ku.breakpoints(), s.hom.kv.breakpoints());
        (patches.len() == (ub.len() - 1) * (vb.len() - 1)).then_some(SurfaceCells {
            patches,
            ub,
            vb,
            halvings: std::cell::Cell::new(0),
        })
    }

    /// A proven upper bound on the Hausdorff distance between `S ∘ p` over `p`'s domain and
    /// `c` over `range`, pairing the two ranges linearly (module comment); pieces are halved
    /// while their bound exceeds `target` (at most [`MAX_DEPTH`] times, [`MAX_HALVINGS`] in
    /// all), so the bound returned may exceed `target`.
    pub fn bound(
        &self,
        p: &NurbsCurve<f64, 2>,
        c: &NurbsCurve<f64, 3>,
        range: (f64, f64),
        target: f64,
    ) -> Result<f64, Unproven> {
        let (f0, f1) = p.hom.domain();
        let (c0, c1) = range;
        if !(f0 < f1 && c0 < c1 && range.0.is_finite() && range.1.is_finite()) {
            return Err(Unproven::Extraction);
        }
        self.halvings.set(MAX_HALVINGS);
        let (pc, cc) = (hom2(p), hom3(c));
        // A polynomial pcurve whose control points lie in the domain lies in it (convex
        // hull; the comparison is exact): its pieces' boxes, wider by the enclosures'
        // rounding, are then cut back to the domain.
        let d = [
            self.ub[0],
            self.ub[self.ub.len() - 1],
            self.vb[0],
            self.vb[self.vb.len() - 1],
        ];
        let inside = p.hom.control.iter().all(|h| {
            h.w == 1.0 && (d[0]..=d[1]).contains(&h.wp[0]) && (d[2]..=d[3]).contains(&h.wp[1])
        });
        let pc = (pc, inside);
        // Equal ranges (a pcurve on its edge's parameter) pair by the identity, exactly.
        let same = f0 == c0 && f1 == c1;
        let map = |x: f64, (a0, a1): (f64, f64), (b0, b1): (f64, f64)| {
            if same {
                x
            } else {
                b0 + (x - a0) * ((b1 - b0) / (a1 - a0))
            }
        };
        let to_t = |f: f64| map(f, (f0, f1), (c0, c1));
        let to_f = |t: f64| map(t, (c0, c1), (f0, f1));
        // Breakpoints (f, t, f exact, t exact).
        let mut br: Vec<(f64, f64, bool, bool)> = vec![(f0, c0, true, true), (f1, c1, true, true)];
        br.extend(
            p.hom
                .knots
                .interior_breaks()
                .into_iter()
                .map(|f| (f, to_t(f), true, false)),
        );
        br.extend(
            c.hom
                .knots
                .breakpoints()
                .into_iter()
                .filter(|t| *t > c0 && *t < c1)
                .map(|t| (to_f(t), t, false, true)),
        );
        br.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
        // The f values are now in order, the exact t values too (both maps are monotone
        // in rounding); a rounded t below its predecessor is raised to it, and a rounded t
        // above an exact successor lowered to it, so the knots of both curves stay exact
        // breakpoints and both sequences increase (some pieces may be points on one side).
        for i in 1..br.len() {
            if br[i].1 < br[i - 1].1 && !br[i].3 {
                br[i].1 = br[i - 1].1;
            }
        }
        for i in (1..br.len()).rev() {
            if br[i - 1].1 > br[i].1 && !br[i - 1].3 {
                br[i - 1].1 = br[i].1;
            }
        }
        let (fk, ck) = (&p.hom.knots, &c.hom.knots);
        let in_span = |k: &super::KnotVector<f64>, a: f64, b: f64| {
            let s = k.find_span(&(0.5 * (a + b)));
            a == b || (k.knots()[s] <= a && b <= k.knots()[s + 1])
        };
        let pts: Vec<(f64, f64)> = br.iter().map(|b| (b.0, b.1)).collect();
        for w in pts.windows(2) {
            let ok = w[0].0 <= w[1].0 && w[0].1 <= w[1].1;
            if !ok || !in_span(fk, w[0].0, w[1].0) || !in_span(ck, w[0].1, w[1].1) {
                return Err(Unproven::Extraction);
            }
        }
        let mut worst: f64 = 0.0;
        for w in pts.windows(2).filter(|w| w[0] != w[1]) {
            let r = self.piece(&pc, &cc, (w[0].0, w[1].0), (w[0].1, w[1].1), target)?;
            worst = worst.max(r);
        }
        Ok(worst)
    }

    /// The bound on one matched piece, halved while above `target` and while halving pays:
    /// where the halves' bounds are not below [`CONVERGED`] times the whole's, the distance
    /// at paired parameters is itself that large (not the control polygons' overshoot,
    /// which halving divides by about four), and halving stops.
    fn piece(
        &self,
        pc: &(HomCurve<3>, bool),
        cc: &HomCurve<4>,
        f: (f64, f64),
        t: (f64, f64),
        target: f64,
    ) -> Result<f64, Unproven> {
        let r = self.matched(pc, cc, f, t)?;
        Ok(self.refine(pc, cc, f, t, r, target, 0))
    }

    #[allow(clippy::too_many_arguments)]
    fn refine(
        &self,
        pc: &(HomCurve<3>, bool),
        cc: &HomCurve<4>,
        f: (f64, f64),
        t: (f64, f64),
        r: f64,
        target: f64,
        depth: u32,
    ) -> f64 {
        let (fm, tm) = (0.5 * (f.0 + f.1), 0.5 * (t.0 + t.1));
        let left = self.halvings.get();
        if r <= target
            || depth >= MAX_DEPTH
            || left == 0
            || !(f.0 < fm && fm < f.1 && t.0 < tm && tm < t.1)
        {
            return r;
        }
        self.halvings.set(left - 1);
        let (fa, ta, fb, tb) = ((f.0, fm), (t.0, tm), (fm, f.1), (tm, t.1));
        // The halves' boxes lie in the whole's: they fail only where it did not, by
        // rounding; the whole's bound stands then.
        let (Ok(ra), Ok(rb)) = (self.matched(pc, cc, fa, ta), self.matched(pc, cc, fb, tb)) else {
            return r;
        };
        if ra.max(rb) > CONVERGED * r {
            return ra.max(rb).min(r);
        }
        let a = self.refine(pc, cc, fa, ta, ra, target, depth + 1);
        let b = self.refine(pc, cc, fb, tb, rb, target, depth + 1);
        a.max(b)
    }

    /// `max_c r_c` over the cells the pcurve piece's box meets (module comment).
    fn matched(
        &self,
        pc: &(HomCurve<3>, bool),
        cc: &HomCurve<4>,
        f: (f64, f64),
        t: (f64, f64),
    ) -> Result<f64, Unproven> {
        let weight = Unproven::Weight { t: t.0 };
        let pp = pc.0.piece(f.0, f.1).ok_or(Unproven::Extraction)?;
        let cp = cc.piece(t.0, t.1).ok_or(Unproven::Extraction)?;
        if pp.iter().any(|x| !x[2].is_pos()) || cp.iter().any(|x| !x[3].is_pos()) {
            return Err(weight);
        }
        let mut bx = [
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ];
        for x in &pp {
            for d in 0..2 {
                let a = x[d].checked_div(x[2]).ok_or(weight.clone())?;
                bx[2 * d] = bx[2 * d].min(a.lo);
                bx[2 * d + 1] = bx[2 * d + 1].max(a.hi);
            }
        }
        if pc.1 {
            let (u, v) = (&self.ub, &self.vb);
            bx = [
                bx[0].max(u[0]),
                bx[1].min(u[u.len() - 1]),
                bx[2].max(v[0]),
                bx[3].min(v[v.len() - 1]),
            ];
        }
        let off = Unproven::OffDomain { t: t.0 };
        let (iu0, iu1) = cells_meeting(&self.ub, bx[0], bx[1]).ok_or(off.clone())?;
        let (iv0, iv1) = cells_meeting(&self.vb, bx[2], bx[3]).ok_or(off)?;
        let nv = self.vb.len() - 1;
        let mut r: f64 = 0.0;
        for iu in iu0..=iu1 {
            for iv in iv0..=iv1 {
                let rc =
                    cell_bound(&self.patches[iu * nv + iv], &pp, &cp).map_err(|e| match e {
                        Unproven::Weight { .. } => Unproven::Weight { t: t.0 },
                        e => e,
                    })?;
                r = r.max(rc);
            }
        }
        Ok(r)
    }
}

/// `r_c` of the module comment: the bound on `|S_c(p(s)) − C(t(s))|` from the pcurve piece
/// `pp` (homogeneous `(U, V, W)`) on cell `patch` and the curve piece `cp`.
fn cell_bound(patch: &EnclosedPatch, pp: &[[I; 3]], cp: &[[I; 4]]) -> Result<f64, Unproven> {
    let (p, q, d, n) = (patch.p, patch.q, pp.len() - 1, cp.len() - 1);
    let deg = (p + q) * d + n;
    if deg > MAX_ERROR_DEGREE {
        return Err(Unproven::Degree(deg));
    }
    let [u0, u1, v0, v1] = patch.uv.map(I::point);
    let local = |k: usize, lo: I, hi: I| -> Option<(Vec<I>, Vec<I>)> {
        let x: Vec<I> = pp
            .iter()
            .map(|c| (c[k] - lo * c[2]).checked_div(hi - lo))
            .collect::<Option<_>>()?;
        let rest = pp.iter().zip(&x).map(|(c, x)| c[2] - *x).collect();
        Some((x, rest))
    };
    let (xh, aw) = local(0, u0, u1).ok_or(Unproven::Extraction)?;
    let (yh, bw) = local(1, v0, v1).ok_or(Unproven::Extraction)?;
    // Every polynomial from here on is in the scaled form of [`mul`] (products are then
    // convolutions), back to Bernstein coefficients only where a convex hull is read.
    let sc = |v: Vec<I>| scaled(v.into_iter());
    let (xp, ap, yp, bp) = (
        powers(&sc(xh), p),
        powers(&sc(aw), p),
        powers(&sc(yh), q),
        powers(&sc(bw), q),
    );
    let times = |v: Vec<I>, s: f64| -> Vec<I> { v.into_iter().map(|x| x * I::point(s)).collect() };
    let bx: Vec<Vec<I>> = (0..=p)
        .map(|i| times(mul(&xp[i], &ap[p - i]), binom(p, i)))
        .collect();
    let by: Vec<Vec<I>> = (0..=q)
        .map(|j| times(mul(&yp[j], &bp[q - j]), binom(q, j)))
        .collect();
    let mut nsum = vec![[I::point(0.0); 4]; (p + q) * d + 1];
    for (i, bxi) in bx.iter().enumerate() {
        for (j, byj) in by.iter().enumerate() {
            let b = mul(bxi, byj);
            let pij = patch.net[i * (q + 1) + j];
            for (acc, bk) in nsum.iter_mut().zip(&b) {
                for c in 0..4 {
                    acc[c] = acc[c] + pij[c] * *bk;
                }
            }
        }
    }
    let nw: Vec<I> = nsum.iter().map(|x| x[3]).collect();
    let cw = scaled(cp.iter().map(|x| x[3]));
    let min_lo = |v: &[I]| v.iter().map(|x| x.lo).fold(f64::INFINITY, f64::min);
    let (nw_min, cw_min) = (
        min_lo(&unscaled(&nw)),
        min_lo(&cp.iter().map(|x| x[3]).collect::<Vec<_>>()),
    );
    if !(nw_min > 0.0 && cw_min > 0.0) {
        return Err(Unproven::Weight { t: 0.0 });
    }
    let mut sq = vec![I::point(0.0); deg + 1];
    for c in 0..3 {
        let nc: Vec<I> = nsum.iter().map(|x| x[c]).collect();
        let xc = scaled(cp.iter().map(|x| x[c]));
        let e: Vec<I> = mul(&nc, &cw)
            .into_iter()
            .zip(mul(&xc, &nw))
            .map(|(a, b)| a - b)
            .collect();
        for (s, ek) in sq.iter_mut().zip(&unscaled(&e)) {
            *s = *s + ek.sqr();
        }
    }
    let e_max = sq.iter().map(|s| s.hi).fold(0.0, f64::max).sqrt().next_up();
    let den = I::point(nw_min) * I::point(cw_min);
    let r = I::point(e_max)
        .checked_div(den)
        .ok_or(Unproven::Weight { t: 0.0 })?;
    if r.hi.is_finite() {
        Ok(r.hi)
    } else {
        Err(Unproven::Extraction)
    }
}

#[cfg(test)]
mod tests;
