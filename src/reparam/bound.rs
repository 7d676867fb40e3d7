//! A **proven** bound on the deviation `E_max` of §2 (docs/papers.md §A: "the largest distance
//! between the given surface and its chord-length-parametrized replacement"): an upper bound
//! of the Hausdorff distance between the two surfaces as point sets, or the reason why the
//! argument does not apply (then only the sampled evidence of [`super::error`] is left).
//!
//! **The map φ.** `N(s, t)` interpolates `x_ij = S(u_ij, v_ij)` at `(ξ_i, η_j)`
//! ([`super::surface`]). φ is the *same* interpolation (same knots and degrees, the tensor
//! product of the same clamped cubic interpolants) of the domain points `(u_ij, v_ij)`:
//! `N` and `S∘φ` agree at the grid points, so `f = N − S∘φ` is an interpolation error and
//! small between them. The control points of φ's boundary rows are then set to the fixed
//! coordinate of their side (`v = v0` on `t = 0`, …), which they equal up to the rounding of
//! the interpolation solve, because the grid's boundary points lie on those sides exactly;
//! the bound below holds for this φ, whatever it is (no interpolation property is used in
//! the proof, only in making the bound small). Let `c` clamp a point of the plane to S's
//! domain `D = [u0, u1] × [v0, v1]` (componentwise) and `Φ = c∘φ`.
//!
//! **Theorem.** Let `B ≥ |N(q) − S(Φ(q))|` for every `q ∈ [0,1]²`. Then every point of N is
//! within `B` of S, and every point of S is within `B` of N: `d_H(N([0,1]²), S(D)) ≤ B`.
//!
//! *Proof.* `S(Φ(q))` is a point of S (Φ maps into D), so `d(N(q), S) ≤ B`. For the other
//! direction Φ is onto D: the knots of φ are clamped, so on the side `t = 0` only the control
//! row `j = 0` contributes, `φ(s, 0) = Σ_i B_i(s) P_i0` with every `P_i0` having `v = v0`
//! exactly, hence `φ_v(s, 0) = v0` (partition of unity); likewise on the three other sides,
//! and the corners `φ(0,0) = P_00 = (u0, v0)`, …. The clamp keeps the fixed coordinate and
//! moves the running one into its interval, so Φ maps each side of `[0,1]²` into the
//! corresponding side of D with corners to corners. Each side's path is then homotopic in
//! that side, with its ends fixed, to the straight one, so `Φ|∂[0,1]²` has degree 1 about
//! every interior point `p` of D; if `p` were not in `Φ([0,1]²)`, Φ would contract that loop
//! in `D ∖ {p}`, a contradiction. Points of `∂D` are reached by the side paths themselves
//! (intermediate values). So every `p ∈ D` is some `Φ(q)`, and `d(S(p), N) ≤ |S(Φ(q)) − N(q)|
//! ≤ B`. ∎ (Monotonicity of φ along the sides is not needed, nor is φ injective.)
//!
//! **Bounding `sup |f|`, `f = N − S∘Φ`** (a mean-value form, Moore's centred form, on
//! parameter boxes `Q ⊂ [0,1]²` with centre `q0`): `f` is Lipschitz, and along the segment
//! from `q0` to `q ∈ Q` its derivative exists almost everywhere and is
//! `DN·d − DS(Φ)·K·Dφ·d`, `d = q − q0`, where `K = diag(κ_u, κ_v)`, `κ ∈ [0, 1]` the derivative
//! of the clamp (1 while φ is inside, 0 outside, and `h' = 0` a.e. where `φ_u` sits on the
//! bound) and `DS` a one-sided derivative of the span rectangle of S the point lies in (the
//! piecewise argument of [`crate::spline::enclose`]). Integrating,
//! `f(Q) ⊆ f(q0) + (DN(Q) − DS(C)·K(Q)·Dφ(Q)) (Q − q0)` with `C = c(φ(Q)) = φ(Q) ∩ D` and
//! `K(Q)` the hull of the clamp's derivatives on `φ(Q)`, each factor enclosed in
//! outward-rounded interval arithmetic ([`crate::spline::enclose`]: Cox–de Boor with interval
//! parameters, the quotient rule for rational S); `f(q0)` is enclosed at the point the same
//! way (`N(q0)`, `φ(q0)`, then S over `c(φ(q0))`). The direct enclosure `N(Q) − S(C)` is
//! intersected with it. `|f| ≤ sqrt(Σ_k mag(F_k)²)`, rounded up. Boxes start as the knot
//! spans of N and are quartered while their bound exceeds the target, within a budget; the
//! bound is the largest over the final boxes.
//!
//! **Hypotheses checked** (each failure gives no bound and its reason): the grid's boundary
//! points lie exactly on their sides of D and its corners are D's corners; N and φ have
//! clamped knots on `[0,1]`; φ's boundary control points are within rounding of their sides
//! before being set on them; every enclosure exists (S's weights certified non-zero over the
//! boxes, finite values). A box budget reached is not a failure: the bound is still proven,
//! only perhaps above ε.

use super::bound_box::{Nets, box_bound};
use super::interior::{Grid, Line, locate};
use super::{ReparamError, surface};
use crate::scalar::Interval;
use crate::spline::NurbsSurface;
use rayon::prelude::*;
use serde::Serialize;

type I = Interval;

/// The proven deviation bound of one surface, or why there is none.
#[derive(Clone, Debug, Default, Serialize)]
pub struct ProvenBound {
    /// `e_max_proven`: an upper bound of the Hausdorff distance between N and S (see the
    /// module documentation); `None` when a hypothesis failed (`reason`).
    pub e_max_proven: Option<f64>,
    /// The hypotheses of the theorem, each checked for this surface.
    pub hypotheses: Vec<String>,
    /// Why there is no bound.
    pub reason: Option<String>,
    /// Parameter boxes evaluated, and in the final cover.
    pub boxes: usize,
    pub final_boxes: usize,
    /// The box budget was reached before every box met the target.
    pub budget_reached: bool,
    /// The refinement target: boxes are quartered while their bound exceeds it.
    pub target: f64,
    /// `(s, t)` centre of the box with the largest bound.
    pub worst: [f64; 2],
    pub seconds: f64,
    /// The final boxes' bounds and centres, worst first (at most 256): where lines go when
    /// the proven bound exceeds ε.
    #[serde(skip)]
    pub worst_boxes: Vec<(f64, [f64; 2])>,
}

/// The hypotheses (module documentation), in the order they are checked.
pub const HYPOTHESES: [&str; 4] = [
    "grid boundary points lie exactly on their sides of S's domain D, corners on D's corners",
    "N and φ (the same interpolation of the domain points) have clamped knots on [0,1]",
    "φ's boundary control points lie on their sides within rounding (then set on them): clamp∘φ maps sides into sides, corners to corners, so it is onto D (degree argument)",
    "every box enclosure of N, φ, S and first derivatives exists (S's weights certified non-zero)",
];

/// A box `[s] × [t]` with its bound (`None`: an enclosure failed).
#[derive(Clone, Copy, Debug)]
struct Box2 {
    s: I,
    t: I,
    bound: Option<f64>,
}

/// φ: the interpolation of the grid's domain points with N's knots, boundary control points
/// set on their sides. `Err(reason)` when a hypothesis fails.
pub fn phi(s: &NurbsSurface<f64, 3>, g: &Grid) -> Result<NurbsSurface<f64, 3>, String> {
    let (u0, u1, v0, v1) = s.hom.domain();
    let (n, m) = (g.xi.len(), g.eta.len());
    // Hypothesis 1: the grid's boundary on the sides of D.
    for i in 0..n {
        for (j, want) in [(0, v0), (m - 1, v1)] {
            if g.uv[i][j][1] != want {
                return Err(format!(
                    "grid point ({i}, {j}) has v = {:e}, not the side's {want:e}",
                    g.uv[i][j][1]
                ));
            }
        }
    }
    for j in 0..m {
        for (i, want) in [(0, u0), (n - 1, u1)] {
            if g.uv[i][j][0] != want {
                return Err(format!(
                    "grid point ({i}, {j}) has u = {:e}, not the side's {want:e}",
                    g.uv[i][j][0]
                ));
            }
        }
    }
    let vals: Vec<Vec<[f64; 3]>> =
        g.uv.iter()
            .map(|row| row.iter().map(|p| [p[0], p[1], 0.0]).collect())
            .collect();
    let mut f = surface::interpolate_values(&g.xi, &g.eta, &vals)
        .map_err(|e: ReparamError| format!("φ: {e}"))?;
    // Hypothesis 2: clamped knots on [0, 1].
    for k in [&f.hom.ku, &f.hom.kv] {
        let (p, t) = (k.degree(), k.knots());
        let clamped = t.len() >= 2 * p + 2
            && t[..=p].iter().all(|&x| x == 0.0)
            && t[t.len() - p - 1..].iter().all(|&x| x == 1.0);
        if !clamped {
            return Err("φ's knot vector is not clamped on [0, 1]".into());
        }
    }
    // Hypothesis 3: boundary control rows on their sides within rounding, then exactly.
    let (nu, nv) = (f.hom.nu(), f.hom.nv());
    let scale = (u1 - u0)
        .abs()
        .max((v1 - v0).abs())
        .max(u0.abs())
        .max(u1.abs());
    let scale = scale.max(v0.abs()).max(v1.abs());
    let mut set = |k: usize, c: usize, want: f64| -> Result<(), String> {
        let h = &mut f.hom.net[k];
        let off = (h.wp[c] - want).abs();
        if off > 1e-9 * scale {
            return Err(format!(
                "φ's boundary control point {k} is {off:e} off its side (coordinate {c})"
            ));
        }
        h.wp[c] = want;
        Ok(())
    };
    for i in 0..nu {
        set(i * nv, 1, v0)?;
        set(i * nv + nv - 1, 1, v1)?;
    }
    for j in 0..nv {
        set(j, 0, u0)?;
        set((nu - 1) * nv + j, 0, u1)?;
    }
    Ok(f)
}

/// The distinct knot values of a knot vector inside `[0, 1]`.
fn breaks(t: &[f64]) -> Vec<f64> {
    let mut b: Vec<f64> = t
        .iter()
        .copied()
        .filter(|x| (0.0..=1.0).contains(x))
        .collect();
    b.dedup();
    b
}

/// The proven bound of `n` against `s` for the grid `g` that `n` interpolates: boxes quartered
/// while their bound exceeds `target`, at most `max_boxes` evaluated.
pub fn prove(
    s: &NurbsSurface<f64, 3>,
    n: &NurbsSurface<f64, 3>,
    g: &Grid,
    target: f64,
    max_boxes: usize,
) -> ProvenBound {
    let t0 = std::time::Instant::now();
    let mut out = ProvenBound {
        target,
        ..Default::default()
    };
    let f = match phi(s, g) {
        Ok(f) => f,
        Err(why) => {
            out.reason = Some(why);
            out.seconds = t0.elapsed().as_secs_f64();
            return out;
        }
    };
    let (u0, u1, v0, v1) = s.hom.domain();
    let d = [u0, u1, v0, v1];
    let Some(nets) = Nets::new(s, n, &f) else {
        out.reason = Some("the derivative nets of N, φ or S cannot be formed".into());
        out.seconds = t0.elapsed().as_secs_f64();
        return out;
    };
    let (bs, bt) = (breaks(n.hom.ku.knots()), breaks(n.hom.kv.knots()));
    let mut level: Vec<Box2> = bs
        .windows(2)
        .flat_map(|a| {
            bt.windows(2).map(move |b| Box2 {
                s: I::new(a[0], a[1]),
                t: I::new(b[0], b[1]),
                bound: None,
            })
        })
        .collect();
    // Worst first: the boxes with the largest bound (an enclosure failure counts as ∞) are
    // quartered, a batch at a time (evaluated in parallel), until the largest is at most the
    // target or the budget is spent.
    let key = |b: &Box2| b.bound.unwrap_or(f64::INFINITY).to_bits();
    let splittable = |x: I| {
        let m = x.mid();
        x.lo < m && m < x.hi
    };
    level.par_iter_mut().for_each(|b| {
        b.bound = box_bound(s, &nets, d, b.s, b.t);
    });
    out.boxes += level.len();
    let mut heap: std::collections::BinaryHeap<(u64, usize)> = std::collections::BinaryHeap::new();
    let mut all: Vec<Box2> = level;
    for (k, b) in all.iter().enumerate() {
        heap.push((key(b), k));
    }
    let mut done: Vec<Box2> = vec![];
    while let Some(&(top, _)) = heap.peek() {
        if f64::from_bits(top) <= target {
            break;
        }
        if out.boxes + 4 > max_boxes {
            out.budget_reached = true;
            break;
        }
        let batch_len = ((max_boxes - out.boxes) / 4).clamp(1, 64);
        let mut batch: Vec<Box2> = vec![];
        while batch.len() < batch_len * 4 {
            let Some(&(k, i)) = heap.peek() else { break };
            if f64::from_bits(k) <= target {
                break;
            }
            heap.pop();
            let b = all[i];
            if !(splittable(b.s) && splittable(b.t)) {
                done.push(b);
                continue;
            }
            let (ms, mt) = (b.s.mid(), b.t.mid());
            for a in [I::new(b.s.lo, ms), I::new(ms, b.s.hi)] {
                for c in [I::new(b.t.lo, mt), I::new(mt, b.t.hi)] {
                    batch.push(Box2 {
                        s: a,
                        t: c,
                        bound: None,
                    });
                }
            }
        }
        if batch.is_empty() {
            break;
        }
        batch.par_iter_mut().for_each(|b| {
            b.bound = box_bound(s, &nets, d, b.s, b.t);
        });
        out.boxes += batch.len();
        for b in batch {
            all.push(b);
            heap.push((key(&b), all.len() - 1));
        }
    }
    done.extend(heap.into_iter().map(|(_, i)| all[i]));
    out.final_boxes = done.len();
    out.hypotheses = HYPOTHESES.iter().map(|h| h.to_string()).collect();
    let mut worst = -1.0;
    for b in &done {
        match b.bound {
            None => {
                out.reason = Some(format!(
                    "an enclosure failed on the box s ∈ [{:e}, {:e}], t ∈ [{:e}, {:e}] (a weight \
                     interval of S containing 0, a non-finite value, or too many spans of S)",
                    b.s.lo, b.s.hi, b.t.lo, b.t.hi
                ));
                out.e_max_proven = None;
                out.seconds = t0.elapsed().as_secs_f64();
                return out;
            }
            Some(x) if x > worst => {
                worst = x;
                out.worst = [b.s.mid(), b.t.mid()];
            }
            _ => {}
        }
    }
    let mut ranked: Vec<(f64, [f64; 2])> = done
        .iter()
        .filter_map(|b| b.bound.map(|x| (x, [b.s.mid(), b.t.mid()])))
        .collect();
    ranked.sort_by(|a, b| b.0.total_cmp(&a.0));
    ranked.truncate(256);
    out.worst_boxes = ranked;
    out.e_max_proven = (worst >= 0.0).then_some(worst);
    if out.e_max_proven.is_none() {
        out.reason = Some("no box".into());
    }
    out.seconds = t0.elapsed().as_secs_f64();
    out
}

/// The refinement target for an evidence figure `e` and tolerance `tol`: `ratio · e`, at
/// least `10⁻³ ε`, at most ε while the evidence is within ε (so the proof can decide ε).
pub fn target(e: f64, tol: f64, ratio: f64) -> f64 {
    let t = (ratio * e).max(1e-3 * tol);
    if e <= tol { t.min(tol) } else { t }
}

/// Lines where the proven bound exceeds ε: per span of ξ (η), one line through the centre of
/// its worst box above ε, kept in the span's middle half (as [`super::error::measure`]).
pub fn lines_over(pb: &ProvenBound, g: &Grid, tol: f64) -> Vec<Line> {
    let mut span_xi: Vec<Option<f64>> = vec![None; g.xi.len() - 1];
    let mut span_eta: Vec<Option<f64>> = vec![None; g.eta.len() - 1];
    for &(_, [s, t]) in pb.worst_boxes.iter().filter(|w| w.0 > tol) {
        let (i, _) = locate(&g.xi, s);
        let (j, _) = locate(&g.eta, t);
        span_xi[i].get_or_insert(s);
        span_eta[j].get_or_insert(t);
    }
    let middle = |t: &[f64], k: usize, x: f64| {
        let q = (t[k + 1] - t[k]) / 4.0;
        x.clamp(t[k] + q, t[k + 1] - q)
    };
    let mut out = vec![];
    for (i, w) in span_xi.iter().enumerate() {
        if let Some(x) = w {
            out.push(Line::Xi(middle(&g.xi, i, *x)));
        }
    }
    for (j, w) in span_eta.iter().enumerate() {
        if let Some(x) = w {
            out.push(Line::Eta(middle(&g.eta, j, *x)));
        }
    }
    out
}
