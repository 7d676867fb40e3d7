//! Enclosures of a NURBS surface and of its partial derivatives up to order two over a
//! parameter box, for the singular-point proof ([`crate::ssi::singular`]) and the tessellation's
//! proven chordal bound ([`crate::tessellate::bound`]): the second-order companion of
//! [`super::enclose`]. Basis functions and their derivatives by the Cox–de Boor
//! recurrence in outward-rounded interval arithmetic (The NURBS Book eq. 2.9, A2.3), the
//! rational quotient rule (eq. 4.20); a box is cut into the spans it meets, grouped where the
//! surface is C² across the knot (multiplicity at most the degree − 2), and in a closed
//! direction the parameter runs on across the seam into a copy of the domain.

use crate::scalar::Interval;
use crate::spline::{KnotVector, NurbsSurface};

mod bezier;
pub use bezier::bezier_jet;

type I = Interval;
type V = [I; 3];

fn pt(x: f64) -> I {
    Interval::point(x)
}

/// Largest order (degree + 1) handled.
pub const MAX_ORDER: usize = 16;
/// Most knot spans a box may meet in one direction.
pub(crate) const MAX_SPANS: usize = 8;

/// Enclosures of `S` and its partial derivatives up to order two over a parameter box.
#[derive(Clone, Copy, Debug)]
pub struct Jet2 {
    pub s: V,
    pub su: V,
    pub sv: V,
    pub suu: V,
    pub suv: V,
    pub svv: V,
}

/// Basis functions `N_{span-p..=span, p}` of span `span` and their first and second
/// derivatives (`[N, N', N'']`), enclosed for every parameter in `x` (the polynomial of the
/// span, also beyond it). Cox–de Boor on the levels `0..=p`, derivatives by
/// `N'_{i,j} = j (N_{i,j-1} / (t_{i+j} − t_i) − N_{i+1,j-1} / (t_{i+j+1} − t_{i+1}))` applied
/// twice (The NURBS Book eq. 2.9, A2.3); every divisor is a positive knot difference (a
/// function active on a non-empty span has a support containing it).
pub fn basis_d2(k: &KnotVector<f64>, span: usize, x: I) -> Option<[[I; MAX_ORDER]; 3]> {
    let p = k.degree();
    let t = k.knots();
    if p >= MAX_ORDER || span < p || span + p >= t.len() {
        return None;
    }
    let z = pt(0.0);
    let mut lev = [[z; MAX_ORDER]; MAX_ORDER];
    lev[0][0] = pt(1.0);
    for j in 1..=p {
        for a in 0..=j {
            let i = span + a - j;
            let mut acc = z;
            if a >= 1 {
                let den = pt(t[i + j]) - pt(t[i]);
                acc = acc + (x - pt(t[i])).checked_div(den)? * lev[j - 1][a - 1];
            }
            if a < j {
                let den = pt(t[i + j + 1]) - pt(t[i + 1]);
                acc = acc + (pt(t[i + j + 1]) - x).checked_div(den)? * lev[j - 1][a];
            }
            lev[j][a] = acc;
        }
    }
    // Derivatives of the level-j functions from `f`, the values (or derivatives) of level j-1.
    let step = |j: usize, f: &[I; MAX_ORDER]| -> Option<[I; MAX_ORDER]> {
        let mut d = [z; MAX_ORDER];
        if j == 0 {
            return Some(d);
        }
        let c = pt(j as f64);
        for (a, da) in d.iter_mut().enumerate().take(j + 1) {
            let i = span + a - j;
            let mut acc = z;
            if a >= 1 {
                acc = acc + f[a - 1].checked_div(pt(t[i + j]) - pt(t[i]))?;
            }
            if a < j {
                acc = acc - f[a].checked_div(pt(t[i + j + 1]) - pt(t[i + 1]))?;
            }
            *da = c * acc;
        }
        Some(d)
    };
    let n1 = if p >= 1 {
        step(p, &lev[p - 1])?
    } else {
        [z; MAX_ORDER]
    };
    let n2 = if p >= 2 {
        step(p, &step(p - 1, &lev[p - 2])?)?
    } else {
        [z; MAX_ORDER]
    };
    Some([lev[p], n1, n2])
}

/// One span rectangle's function (extended beyond it) over `u × v`.
pub(crate) fn piece2(
    s: &NurbsSurface<f64, 3>,
    (su, u): (usize, I),
    (sv, v): (usize, I),
) -> Option<Jet2> {
    let h = &s.hom;
    let bu = basis_d2(&h.ku, su, u)?;
    let bv = basis_d2(&h.kv, sv, v)?;
    let (p, q) = (h.ku.degree(), h.kv.degree());
    let ncols = h.kv.n_ctrl();
    let z4 = [pt(0.0); 4];
    // Homogeneous sums: X, X_u, X_v, X_uu, X_uv, X_vv (4 components each, the last is w).
    let mut a = [z4; 6];
    for i in 0..=p {
        let mut r = [z4; 3];
        for j in 0..=q {
            let c = h.net.get((su - p + i) * ncols + (sv - q + j))?;
            let cw = [pt(c.wp[0]), pt(c.wp[1]), pt(c.wp[2]), pt(c.w)];
            for (d, rd) in r.iter_mut().enumerate() {
                for m in 0..4 {
                    rd[m] = rd[m] + bv[d][j] * cw[m];
                }
            }
        }
        for m in 0..4 {
            a[0][m] = a[0][m] + bu[0][i] * r[0][m];
            a[1][m] = a[1][m] + bu[1][i] * r[0][m];
            a[2][m] = a[2][m] + bu[0][i] * r[1][m];
            a[3][m] = a[3][m] + bu[2][i] * r[0][m];
            a[4][m] = a[4][m] + bu[1][i] * r[1][m];
            a[5][m] = a[5][m] + bu[0][i] * r[2][m];
        }
    }
    let s0: [Option<I>; 3] = std::array::from_fn(|m| a[0][m].checked_div(a[0][3]));
    quotient([s0[0]?, s0[1]?, s0[2]?], &a)
}

/// The Cartesian jet of `S = X / w` from the homogeneous jet `a = [X, X_u, X_v, X_uu, X_uv,
/// X_vv]` (4 components each, the last the weight) and an enclosure `s` of `S` itself (The
/// NURBS Book eq. 4.20); `None` for a weight not proven non-zero or a non-finite result.
pub(crate) fn quotient(s: V, a: &[[I; 4]; 6]) -> Option<Jet2> {
    let w = a[0][3];
    let (wu, wv, wuu, wuv, wvv) = (a[1][3], a[2][3], a[3][3], a[4][3], a[5][3]);
    let two = pt(2.0);
    let mut o = Jet2 {
        s,
        su: [pt(0.0); 3],
        sv: [pt(0.0); 3],
        suu: [pt(0.0); 3],
        suv: [pt(0.0); 3],
        svv: [pt(0.0); 3],
    };
    for m in 0..3 {
        o.su[m] = (a[1][m] - wu * o.s[m]).checked_div(w)?;
        o.sv[m] = (a[2][m] - wv * o.s[m]).checked_div(w)?;
        o.suu[m] = (a[3][m] - two * wu * o.su[m] - wuu * o.s[m]).checked_div(w)?;
        o.suv[m] = (a[4][m] - wu * o.sv[m] - wv * o.su[m] - wuv * o.s[m]).checked_div(w)?;
        o.svv[m] = (a[5][m] - two * wv * o.sv[m] - wvv * o.s[m]).checked_div(w)?;
    }
    let ok = [o.s, o.su, o.sv, o.suu, o.suv, o.svv]
        .iter()
        .flatten()
        .all(|x| x.is_finite());
    ok.then_some(o)
}

/// A span, the part of the parameter interval it covers, and the offset of the copy of the
/// domain it belongs to: the surface at `x` is the span's function at `x − offset` (offsets
/// other than 0 only in closed directions).
pub(crate) type Piece = (usize, I, f64);

/// The spans the interval `x` meets, in groups joined with continuous second derivatives
/// (knots of multiplicity at most the degree − 2 between them); a new group starts at every
/// knot of multiplicity ≥ the degree − 1, and at the seam of a closed direction (`periodic`: the domain
/// repeated one period to either side). Each group's outer pieces are extended to the ends of
/// `x` (the polynomial extension of its outermost spans); in an open direction the outermost
/// spans of the domain extend to infinity. Piece ends are rounded outward, so neighbouring
/// pieces overlap by an ulp rather than leave a gap. `None` beyond [`MAX_SPANS`] spans, for
/// degree 0, or when `x` is not covered.
pub(crate) fn groups(k: &KnotVector<f64>, x: I, periodic: bool) -> Option<Vec<Vec<Piece>>> {
    let t = k.knots();
    let p = k.degree();
    if p == 0 || !(x.is_finite() && x.lo <= x.hi) {
        return None;
    }
    let (d0, d1) = k.domain();
    let (first, last) = (k.find_span(&d0), k.find_span(&d1));
    let per = d1 - d0;
    let offsets: &[f64] = if periodic { &[-per, 0.0, per] } else { &[0.0] };
    let thin = x.lo == x.hi;
    let mut out: Vec<Vec<Piece>> = Vec::new();
    let mut count = 0;
    let mut covered = x.lo;
    for &o in offsets {
        for s in first..=last {
            if t[s] >= t[s + 1] {
                continue;
            }
            let (a, b) = ((pt(t[s]) + pt(o)).lo, (pt(t[s + 1]) + pt(o)).hi);
            let lo = if s == first && !periodic {
                x.lo
            } else {
                x.lo.max(a)
            };
            let hi = if s == last && !periodic {
                x.hi
            } else {
                x.hi.min(b)
            };
            if !(lo < hi || (thin && lo <= hi)) {
                continue;
            }
            if lo > covered {
                return None;
            }
            covered = covered.max(hi);
            count += 1;
            if count > MAX_SPANS {
                return None;
            }
            if out.is_empty() || k.multiplicity(&t[s]) + 1 >= p {
                out.push(Vec::new());
            }
            out.last_mut()?.push((s, I::new(lo, hi), o));
        }
    }
    if covered < x.hi {
        return None;
    }
    for g in &mut out {
        g[0].1.lo = x.lo;
        let n = g.len() - 1;
        g[n].1.hi = x.hi;
    }
    (!out.is_empty()).then_some(out)
}

/// The group's function over `z ⊂ x` (pieces overlapping `z`, cut to it).
pub(crate) fn restrict(g: &[Piece], z: I) -> Vec<Piece> {
    g.iter()
        .filter(|(_, r, _)| r.lo <= z.hi && z.lo <= r.hi)
        .map(|&(s, r, o)| (s, I::new(r.lo.max(z.lo), r.hi.min(z.hi)), o))
        .collect()
}

fn hull_v(a: V, b: V) -> V {
    std::array::from_fn(|k| a[k].hull(b[k]))
}

/// Enclosure of one smooth group's function over the pieces (hull across C² joins).
pub(crate) fn group_jet(s: &NurbsSurface<f64, 3>, gu: &[Piece], gv: &[Piece]) -> Option<Jet2> {
    let mut out: Option<Jet2> = None;
    for &a in gu {
        for &b in gv {
            let j = piece2(s, (a.0, a.1 - pt(a.2)), (b.0, b.1 - pt(b.2)))?;
            out = Some(match out {
                None => j,
                Some(o) => Jet2 {
                    s: hull_v(o.s, j.s),
                    su: hull_v(o.su, j.su),
                    sv: hull_v(o.sv, j.sv),
                    suu: hull_v(o.suu, j.suu),
                    suv: hull_v(o.suv, j.suv),
                    svv: hull_v(o.svv, j.svv),
                },
            });
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spline::closure::exact_seam as closed;
    use crate::spline::construct::{sphere, torus};
    use crate::spline::enclose::tests::frame;

    /// Thin enclosures hold the f64 evaluation and central differences of the first
    /// derivatives (second derivatives), away from knot lines.
    #[test]
    fn second_derivatives_match_differences() {
        for s in [
            torus(&frame(), 2.0, 0.7).unwrap(),
            sphere(&frame(), 1.5).unwrap(),
        ] {
            for (u, v) in [(0.1, 0.3), (0.61, 0.12), (0.4, 0.8)] {
                let g = [
                    groups(&s.hom.ku, pt(u), false).unwrap(),
                    groups(&s.hom.kv, pt(v), false).unwrap(),
                ];
                let j = group_jet(&s, &g[0][0], &g[1][0]).unwrap();
                let (p, su, sv) = crate::spline::project::point_d1(&s, u, v);
                let e = 1e-6;
                let d1 = |u: f64, v: f64| {
                    let (_, a, b) = crate::spline::project::point_d1(&s, u, v);
                    (a, b)
                };
                let (up, um) = (d1(u + e, v), d1(u - e, v));
                let (vp, vm) = (d1(u, v + e), d1(u, v - e));
                for k in 0..3 {
                    let near = |x: f64, i: I, t: f64| i.lo - t <= x && x <= i.hi + t;
                    assert!(near(p[k], j.s[k], 1e-12));
                    assert!(near(su[k], j.su[k], 1e-11));
                    assert!(near(sv[k], j.sv[k], 1e-11));
                    let fd_uu = (up.0[k] - um.0[k]) / (2.0 * e);
                    let fd_uv = (vp.0[k] - vm.0[k]) / (2.0 * e);
                    let fd_vv = (vp.1[k] - vm.1[k]) / (2.0 * e);
                    assert!(near(fd_uu, j.suu[k], 1e-4), "{u} {v} {k}");
                    assert!(near(fd_uv, j.suv[k], 1e-4), "{u} {v} {k}");
                    assert!(near(fd_vv, j.svv[k], 1e-4), "{u} {v} {k}");
                    assert!(j.suu[k].hi - j.suu[k].lo < 1e-9);
                }
            }
        }
    }

    /// Exact rational second derivatives (the same surface lifted to `Rational`, The NURBS
    /// Book A4.4) lie in the enclosures over boxes, across knot lines and the seam too (in the
    /// enclosure of one of the pieces there).
    #[test]
    fn enclosures_hold_exact_derivatives() {
        use crate::geom::{Hom, lift_point};
        use crate::scalar::Rational as Q;
        use crate::scalar::lift;
        let q = |x: f64| Q::try_from(x).unwrap();
        let within = |x: &Q, i: I| q(i.lo) <= *x && *x <= q(i.hi);
        for s in [
            torus(&frame(), 2.0, 0.7).unwrap(),
            sphere(&frame(), 1.5).unwrap(),
        ] {
            let e: NurbsSurface<Q, 3> = NurbsSurface {
                hom: s.hom.map(
                    |k| lift::<Q>(*k),
                    |h| Hom {
                        wp: lift_point(&h.wp),
                        w: lift(h.w),
                    },
                ),
            };
            let per = [closed(&s, 0), closed(&s, 1)];
            for (u0, v0, w) in [
                (0.1, 0.3, 1e-6),
                (0.25 - 1e-7, 0.5 - 2e-7, 4e-7),
                (0.61, 0.12, 1e-3),
                (-3e-7, 0.7, 1e-6),
                (0.37, 0.25, 0.0),
            ] {
                let x = [I::new(u0, u0 + w), I::new(v0, v0 + w)];
                let gu = groups(&s.hom.ku, x[0], per[0]).unwrap();
                let gv = groups(&s.hom.kv, x[1], per[1]).unwrap();
                let jets: Vec<Jet2> = gu
                    .iter()
                    .flat_map(|a| gv.iter().map(move |b| (a, b)))
                    .map(|(a, b)| group_jet(&s, a, b).unwrap())
                    .collect();
                for a in 0..5 {
                    for b in 0..5 {
                        let (mut u, v) = (u0 + w * a as f64 / 4.0, v0 + w * b as f64 / 4.0);
                        if u < 0.0 {
                            u += 1.0; // the seam: the same point one period on
                        }
                        let d = e.derivatives2(&q(u), &q(v));
                        let ok = jets.iter().any(|j| {
                            let all = [j.s, j.su, j.sv, j.suu, j.suv, j.svv];
                            (0..6).all(|m| (0..3).all(|k| within(&d[m][k], all[m][k])))
                        });
                        // At u + 1 (beyond the seam) the exact value is that of the last span.
                        assert!(ok, "{u} {v}");
                    }
                }
            }
        }
    }

    /// Revolved surfaces are closed around the axis; the sphere's profile runs pole to pole.
    #[test]
    fn closed_directions() {
        let t = torus(&frame(), 2.0, 0.7).unwrap();
        assert!(closed(&t, 0) && closed(&t, 1));
        let s = sphere(&frame(), 1.5).unwrap();
        assert!(closed(&s, 0) && !closed(&s, 1));
        // Across the seam: two groups (the copy below the domain, the domain itself).
        let g = groups(&t.hom.ku, I::new(-0.01, 0.01), true).unwrap();
        assert_eq!(g.len(), 2);
        assert_eq!(g[0][0].2, -1.0);
        assert!(groups(&t.hom.ku, I::new(-0.01, 0.01), false).unwrap().len() == 1);
    }

    /// A box across a double knot (the circle's joints) splits into two groups, and so does
    /// one across a simple knot of a quadratic (C¹ only); across a simple knot of a cubic (C²)
    /// it stays one, across a double knot of a cubic it splits.
    #[test]
    fn groups_split_where_not_c2() {
        let k2 = KnotVector::new(vec![0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0], 2, 4).unwrap();
        assert_eq!(groups(&k2, I::new(0.4, 0.6), false).unwrap().len(), 2);
        let k3 = KnotVector::new(vec![0.0, 0.0, 0.0, 0.0, 0.5, 0.5, 1.0, 1.0, 1.0, 1.0], 3, 6);
        assert_eq!(
            groups(&k3.unwrap(), I::new(0.4, 0.6), false).unwrap().len(),
            2
        );
        let s = torus(&frame(), 2.0, 0.7).unwrap();
        assert_eq!(
            groups(&s.hom.kv, I::new(0.49, 0.51), false).unwrap().len(),
            2
        );
        assert_eq!(
            groups(&s.hom.kv, I::new(0.4, 0.45), false).unwrap().len(),
            1
        );
        let k = KnotVector::new(vec![0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0, 1.0], 3, 5).unwrap();
        let g = groups(&k, I::new(0.4, 0.6), false).unwrap();
        assert_eq!(g.len(), 1);
        assert_eq!(g[0].len(), 2);
    }
}
