//! [`Jet2`] over a parameter box inside one Bézier piece, from the Bernstein form: the piece's
//! enclosed homogeneous net ([`crate::spline::enclosed_bezier`]) is cut to the box by de
//! Casteljau's algorithm (The NURBS Book §1.3, A1.5), its derivative nets are differences of
//! control points (hodographs, eq. 1.10 and its tensor-product form), and every polynomial is
//! enclosed by the hull of its Bernstein coefficients (convex hull property, eq. 1.8). The
//! rational quotient rule (eq. 4.20) then gives the Cartesian jet; the point itself is the
//! hull of the Cartesian control points (rational convex hull property, weights positive).
//!
//! Over a box of width `h` these enclosures exceed the true ranges by `O(h²)`, where the
//! Cox–de Boor ones of the parent module exceed them by `O(h)`: the difference between a
//! box of a few parameter units in 10⁻⁴ and one in 10⁻² when the ranges decide a proof.
//!
//! Soundness: every step is outward-rounded interval arithmetic. The cut uses point
//! parameters rounded so that the cut-out part covers the box (`a′ ≤ a`, `b′ ≥ b`, the second
//! cut at `s ≤ a′ / b′`: [`cut_row`], shared with the coverage's crossing test), and the
//! derivative scale uses that part's exact width, enclosed.

use super::{I, Jet2, V, pt};
use crate::spline::enclosed_bezier::{EnclosedPatch, cut_row};

type H = [I; 4];

/// The part of a row (local parameter `[0, 1]`) covering `[a, b]` ([`cut_row`]), with its
/// exact local width `b (1 − s)` enclosed. `None` unless `0 ≤ a < b ≤ 1`.
fn cut(row: &[H], a: f64, b: f64) -> Option<(Vec<H>, I)> {
    if !(0.0 <= a && a < b && b <= 1.0) {
        return None;
    }
    let (part, s) = cut_row(row, (a, b))?;
    Some((part, pt(b) * (pt(1.0) - pt(s))))
}

/// The local parameter interval `[a′, b′] ⊇` the image of `[lo, hi]` in the span `[t0, t1]`.
fn local(lo: f64, hi: f64, t0: f64, t1: f64) -> Option<(f64, f64)> {
    let w = pt(t1) - pt(t0);
    let a = (pt(lo) - pt(t0)).checked_div(w)?.lo.max(0.0);
    let b = (pt(hi) - pt(t0)).checked_div(w)?.hi.min(1.0);
    Some((a, b))
}

/// Hull of a net's points, one component.
fn hull(net: &[H], m: usize) -> Option<I> {
    let mut it = net.iter().map(|h| h[m]);
    let first = it.next()?;
    let out = it.fold(first, |acc, x| acc.hull(x));
    out.is_finite().then_some(out)
}

/// The derivative net along u (`along_u`) or v of a `(p + 1) × (q + 1)` net, unscaled
/// (degree times differences): `(net, p, q)` of the result.
fn diff(net: &[H], p: usize, q: usize, along_u: bool) -> (Vec<H>, usize, usize) {
    if along_u {
        if p == 0 {
            return (vec![[pt(0.0); 4]], 0, q);
        }
        let k = pt(p as f64);
        let mut out = Vec::with_capacity(p * (q + 1));
        for i in 0..p {
            for j in 0..=q {
                let (a, b) = (net[i * (q + 1) + j], net[(i + 1) * (q + 1) + j]);
                out.push(std::array::from_fn(|m| k * (b[m] - a[m])));
            }
        }
        (out, p - 1, q)
    } else {
        if q == 0 {
            return (vec![[pt(0.0); 4]], p, 0);
        }
        let k = pt(q as f64);
        let mut out = Vec::with_capacity((p + 1) * q);
        for i in 0..=p {
            for j in 0..q {
                let (a, b) = (net[i * (q + 1) + j], net[i * (q + 1) + j + 1]);
                out.push(std::array::from_fn(|m| k * (b[m] - a[m])));
            }
        }
        (out, p, q - 1)
    }
}

/// The jet of the piece `e` over the box `[u0, u1] × [v0, v1]` (inside the piece's span
/// rectangle `e.uv`); `None` outside it, for weights not proven positive, or on overflow.
pub fn bezier_jet(e: &EnclosedPatch, u: I, v: I) -> Option<Jet2> {
    let [t0, t1, s0, s1] = e.uv;
    if !(t0 <= u.lo && u.hi <= t1 && s0 <= v.lo && v.hi <= s1 && u.lo < u.hi && v.lo < v.hi) {
        return None;
    }
    let (p, q) = (e.p, e.q);
    let (au, bu) = local(u.lo, u.hi, t0, t1)?;
    let (av, bv) = local(v.lo, v.hi, s0, s1)?;
    // Cut every u-column (fixed j), then every v-row of the result.
    let mut cols: Vec<Vec<H>> = Vec::with_capacity(q + 1);
    let mut fu = pt(1.0);
    for j in 0..=q {
        let col: Vec<H> = (0..=p).map(|i| e.net[i * (q + 1) + j]).collect();
        let (c, f) = cut(&col, au, bu)?;
        cols.push(c);
        fu = f;
    }
    let mut net = vec![[pt(0.0); 4]; (p + 1) * (q + 1)];
    let mut fv = pt(1.0);
    for i in 0..=p {
        let row: Vec<H> = (0..=q).map(|j| cols[j][i]).collect();
        let (r, f) = cut(&row, av, bv)?;
        fv = f;
        net[i * (q + 1)..(i + 1) * (q + 1)].copy_from_slice(&r);
    }
    // d/du = d/dσ / (width of the part in u): local width times the span's.
    let du = fu * (pt(t1) - pt(t0));
    let dv = fv * (pt(s1) - pt(s0));
    let (nu, pu, qu) = diff(&net, p, q, true);
    let (nv, pv, qv) = diff(&net, p, q, false);
    let (nuu, _, _) = diff(&nu, pu, qu, true);
    let (nuv, _, _) = diff(&nu, pu, qu, false);
    let (nvv, _, _) = diff(&nv, pv, qv, false);
    let comp = |n: &[H], scale: I| -> Option<H> {
        let mut o = [pt(0.0); 4];
        for (m, om) in o.iter_mut().enumerate() {
            *om = hull(n, m)?.checked_div(scale)?;
        }
        Some(o)
    };
    let xu = comp(&nu, du)?;
    let xv = comp(&nv, dv)?;
    let xuu = comp(&nuu, du * du)?;
    let xuv = comp(&nuv, du * dv)?;
    let xvv = comp(&nvv, dv * dv)?;
    let w = hull(&net, 3)?;
    if !w.is_pos() {
        return None;
    }
    // The point: hull of the Cartesian control points.
    let mut s: V = [pt(0.0); 3];
    for (m, sm) in s.iter_mut().enumerate() {
        let mut acc: Option<I> = None;
        for h in &net {
            let c = h[m].checked_div(h[3])?;
            acc = Some(acc.map_or(c, |a| a.hull(c)));
        }
        *sm = acc?;
    }
    let mut x0 = [pt(0.0); 4];
    x0[3] = w;
    super::quotient(s, &[x0, xu, xv, xuu, xuv, xvv])
}

#[cfg(test)]
mod tests;
