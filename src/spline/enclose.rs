//! Rigorous enclosures of a NURBS surface and of its first partial derivatives over a
//! parameter *box* `U × V` (intervals), in outward-rounded interval arithmetic
//! ([`Interval`]). Kernel code shared by the pipelines: the intersection's point certificate
//! and Krawczyk test (`ssi`, boxes of zero width and small boxes) and the proven deviation
//! bound of the reparametrization (`reparam::bound`, a mean-value form over parameter boxes).
//!
//! **Method.** On one knot span the surface is one rational function: the basis functions
//! `N_{span-p..=span}` of that span are polynomials, evaluated by the Cox–de Boor recurrence
//! (The NURBS Book A2.2) with the interval parameter, and their derivatives by
//! `N'_{i,p} = p (N_{i,p-1} / (t_{i+p} - t_i) - N_{i+1,p-1} / (t_{i+p+1} - t_{i+1}))` (A2.3).
//! The knots and the homogeneous control points `(w P, w)` are `f64` numbers taken exactly,
//! so every interval operation encloses the exact result for every parameter in the box
//! (inclusion monotonicity), and
//!
//! * `S = X / w`, `S_u = (X_u - S w_u) / w`, `S_v = (X_v - S w_v) / w`
//!
//! with `X = Σ N_i N_j w_ij P_ij`, `w = Σ N_i N_j w_ij`; the quotients are refused (`None`)
//! when the enclosure of `w` contains 0. A box that meets several spans is cut at the knot
//! lines; each piece (box ∩ closed span rectangle) is enclosed with its span's function and
//! the results are joined by the hull (boxes meeting more than [`MAX_PIECES`] spans in one
//! direction are refused). Parts of the box beyond the parameter domain are
//! enclosed with the *polynomial extension* of the outermost span (callers that need points
//! of the true face check that their parameters lie in the domain).
//!
//! **What the hull means for derivatives.** Across a knot line of multiplicity equal to the
//! degree the surface is only C0, and the hull of the one-sided derivative enclosures is then
//! not an enclosure of a derivative (there is none on the line). It is still what the
//! mean-value argument of the Krawczyk test needs: the segment between two parameter points
//! of the box splits into finitely many pieces, each in one closed span rectangle, on which the
//! (continuous) surface equals that span's smooth function; summing the fundamental theorem of
//! calculus over the pieces gives `S(b) - S(a) = ∫ ∇S_k · (b - a)`, an average of one-sided
//! gradients, each in the hull. Continuity holds because interior knot multiplicity above the
//! degree is refused when a surface is built ([`crate::spline`]).

mod point;

use crate::scalar::Interval;
use crate::spline::{KnotVector, NurbsSurface};
pub use point::enclose_point_f64;

/// Enclosures of `S`, `∂S/∂u`, `∂S/∂v` over a parameter box.
#[derive(Clone, Copy, Debug)]
pub struct Jet {
    pub s: [Interval; 3],
    pub su: [Interval; 3],
    pub sv: [Interval; 3],
}

fn pt(x: f64) -> Interval {
    Interval::point(x)
}

/// Largest order (degree + 1) handled; higher degrees are refused (`None`).
pub const MAX_ORDER: usize = 16;

/// Most spans a box may meet in one direction; wider boxes are refused (`None`).
pub const MAX_PIECES: usize = 8;

/// Basis functions `N_{span-p..=span}` of the polynomial piece of span `span` written to
/// `n[..=p]` (and, when `d` is given, their first derivatives to `d[..=p]`), enclosed for every
/// parameter in `x`. `None` only if a knot difference of the span is not positive (never for a
/// non-empty span), or the degree is [`MAX_ORDER`] or more.
pub fn basis_d1(
    k: &KnotVector<f64>,
    span: usize,
    x: Interval,
    n: &mut [Interval; MAX_ORDER],
    d: Option<&mut [Interval; MAX_ORDER]>,
) -> Option<()> {
    let p = k.degree();
    if p >= MAX_ORDER {
        return None;
    }
    let t = k.knots();
    let zero = pt(0.0);
    let (mut left, mut right, mut prev) = ([zero; MAX_ORDER], [zero; MAX_ORDER], [zero; MAX_ORDER]);
    n[0] = pt(1.0);
    for j in 1..=p {
        if d.is_some() && j == p {
            prev[..p].copy_from_slice(&n[..p]);
        }
        left[j] = x - pt(t[span + 1 - j]);
        right[j] = pt(t[span + j]) - x;
        let mut saved = zero;
        for r in 0..j {
            // right[r+1] + left[j-r] with the parameter cancelled: a positive knot difference.
            let den = pt(t[span + r + 1]) - pt(t[span + 1 + r - j]);
            let temp = n[r].checked_div(den)?;
            n[r] = saved + right[r + 1] * temp;
            saved = left[j - r] * temp;
        }
        n[j] = saved;
    }
    if let Some(d) = d {
        if p == 0 {
            d[0] = zero;
            return Some(());
        }
        let deg = pt(p as f64);
        for (a, da) in d.iter_mut().enumerate().take(p + 1) {
            let i = span - p + a;
            let t1 = if a >= 1 {
                prev[a - 1].checked_div(pt(t[i + p]) - pt(t[i]))?
            } else {
                zero
            };
            let t2 = if a < p {
                prev[a].checked_div(pt(t[i + p + 1]) - pt(t[i + 1]))?
            } else {
                zero
            };
            *da = deg * (t1 - t2);
        }
    }
    Some(())
}

type Pieces = arrayvec::ArrayVec<(usize, Interval), MAX_PIECES>;

/// The spans an interval meets, each with the part of the interval it covers (the outermost
/// spans extended to infinity: polynomial extension beyond the domain); `None` beyond
/// [`MAX_PIECES`].
fn pieces(k: &KnotVector<f64>, x: Interval) -> Option<Pieces> {
    let t = k.knots();
    let (s0, s1) = (k.find_span(&x.lo), k.find_span(&x.hi));
    let mut out = Pieces::new();
    if s0 == s1 {
        out.push((s0, x));
        return Some(out);
    }
    let (d0, d1) = k.domain();
    let (first, last) = (k.find_span(&d0), k.find_span(&d1));
    for s in s0..=s1 {
        if t[s] >= t[s + 1] {
            continue;
        }
        let lo = if s == first { x.lo } else { x.lo.max(t[s]) };
        let hi = if s == last { x.hi } else { x.hi.min(t[s + 1]) };
        if lo <= hi {
            out.try_push((s, Interval::new(lo, hi))).ok()?;
        }
    }
    Some(out)
}

fn hull3(a: [Interval; 3], b: [Interval; 3]) -> [Interval; 3] {
    std::array::from_fn(|k| a[k].hull(b[k]))
}

/// One span rectangle: `(S, S_u, S_v)` (derivatives only when `deriv`).
fn piece(
    s: &NurbsSurface<f64, 3>,
    (su, u): (usize, Interval),
    (sv, v): (usize, Interval),
    deriv: bool,
) -> Option<Jet> {
    let h = &s.hom;
    let zero = [pt(0.0); MAX_ORDER];
    let (mut nu, mut du, mut nv, mut dv) = (zero, zero, zero, zero);
    basis_d1(&h.ku, su, u, &mut nu, deriv.then_some(&mut du))?;
    basis_d1(&h.kv, sv, v, &mut nv, deriv.then_some(&mut dv))?;
    let (p, q) = (h.ku.degree(), h.kv.degree());
    let ncols = h.kv.n_ctrl();
    let z = [pt(0.0); 4];
    let (mut a, mut au, mut av) = (z, z, z);
    for i in 0..=p {
        // Row sums over v first (fewer interval operations).
        let (mut r, mut rv) = (z, z);
        for j in 0..=q {
            let c = &h.net[(su - p + i) * ncols + (sv - q + j)];
            let cw = [pt(c.wp[0]), pt(c.wp[1]), pt(c.wp[2]), pt(c.w)];
            for m in 0..4 {
                r[m] = r[m] + nv[j] * cw[m];
                if deriv {
                    rv[m] = rv[m] + dv[j] * cw[m];
                }
            }
        }
        for m in 0..4 {
            a[m] = a[m] + nu[i] * r[m];
            if deriv {
                au[m] = au[m] + du[i] * r[m];
                av[m] = av[m] + nu[i] * rv[m];
            }
        }
    }
    let w = a[3];
    let mut out = Jet {
        s: [pt(0.0); 3],
        su: [pt(0.0); 3],
        sv: [pt(0.0); 3],
    };
    for m in 0..3 {
        out.s[m] = a[m].checked_div(w)?;
        if deriv {
            out.su[m] = (au[m] - out.s[m] * au[3]).checked_div(w)?;
            out.sv[m] = (av[m] - out.s[m] * av[3]).checked_div(w)?;
        }
    }
    let ok = |v: &[Interval; 3]| v.iter().all(|x| x.is_finite());
    (ok(&out.s) && ok(&out.su) && ok(&out.sv)).then_some(out)
}

fn enclose(s: &NurbsSurface<f64, 3>, u: Interval, v: Interval, deriv: bool) -> Option<Jet> {
    if !(u.is_finite() && v.is_finite() && u.lo <= u.hi && v.lo <= v.hi) {
        return None;
    }
    let (pu, pv) = (pieces(&s.hom.ku, u)?, pieces(&s.hom.kv, v)?);
    let mut out: Option<Jet> = None;
    for &a in &pu {
        for &b in &pv {
            let j = piece(s, a, b, deriv)?;
            out = Some(match out {
                None => j,
                Some(o) => Jet {
                    s: hull3(o.s, j.s),
                    su: hull3(o.su, j.su),
                    sv: hull3(o.sv, j.sv),
                },
            });
        }
    }
    out
}

/// Enclosure of `{S(u, v) : u ∈ U, v ∈ V}` (see the module comment); `None` when a weight
/// enclosure contains 0 or an input is not finite.
/// At a point (`u`, `v` of zero width) the homogeneous sum is taken in `f64` with a forward
/// error bound ([`enclose_point_f64`]), the interval sum where that refuses.
pub fn enclose_point(s: &NurbsSurface<f64, 3>, u: Interval, v: Interval) -> Option<[Interval; 3]> {
    if u.lo == u.hi
        && v.lo == v.hi
        && let Some(p) = point::enclose_point_f64(s, u.lo, v.lo)
    {
        return Some(p);
    }
    enclose(s, u, v, false).map(|j| j.s)
}

/// Enclosures of `S`, `S_u`, `S_v` over `U × V` (one-sided across knot lines, joined by the
/// hull: see the module comment for what that is valid for).
pub fn enclose_jet(s: &NurbsSurface<f64, 3>, u: Interval, v: Interval) -> Option<Jet> {
    enclose(s, u, v, true)
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;
    use crate::spline::construct::{Frame, sphere, torus};

    /// A rotated frame off the origin (shared with [`super::super::enclose2`]'s tests).
    pub(in crate::spline) fn frame() -> Frame {
        Frame {
            o: [0.1, -0.2, 0.3],
            x: [1.0, 0.0, 0.0],
            y: [0.0, 0.6, 0.8],
            z: [0.0, -0.8, 0.6],
        }
    }

    fn inside(x: f64, i: Interval) -> bool {
        i.lo <= x && x <= i.hi
    }

    /// Sampled values and derivatives (f64, a few ulps off the exact ones) lie in the box
    /// enclosures, which are narrow; across knot lines too.
    #[test]
    fn box_enclosures_hold_samples() {
        for s in [
            torus(&frame(), 2.0, 0.7).unwrap(),
            sphere(&frame(), 1.5).unwrap(),
        ] {
            for (u0, v0, w) in [
                (0.1, 0.3, 1e-6),
                (0.25 - 1e-7, 0.5 - 2e-7, 4e-7),
                (0.61, 0.12, 1e-3),
                (0.0, 0.5, 0.0),
            ] {
                let (u, v) = (Interval::new(u0, u0 + w), Interval::new(v0, v0 + w));
                let j = enclose_jet(&s, u, v).unwrap();
                for a in 0..5 {
                    for b in 0..5 {
                        let (x, y) = (u0 + w * a as f64 / 4.0, v0 + w * b as f64 / 4.0);
                        let (p, su, sv) = crate::spline::project::point_d1(&s, x, y);
                        for k in 0..3 {
                            let e = 1e-13;
                            let grow = |i: Interval| Interval::new(i.lo - e, i.hi + e);
                            assert!(inside(p[k], grow(j.s[k])), "{x} {y} {k}");
                            assert!(inside(su[k], grow(j.su[k])), "{x} {y} {k}");
                            assert!(inside(sv[k], grow(j.sv[k])), "{x} {y} {k}");
                        }
                    }
                }
                for k in 0..3 {
                    let width = |i: Interval| i.hi - i.lo;
                    assert!(width(j.s[k]) <= 1e-12 + 200.0 * w, "{:?}", j.s[k]);
                    assert!(width(j.su[k]) <= 1e-11 + 2000.0 * w, "{:?}", j.su[k]);
                }
            }
        }
    }
}
