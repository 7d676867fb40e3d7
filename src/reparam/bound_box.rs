//! The per-box forms of the proven deviation bound ([`super::bound`], which states the
//! theorem): on a parameter box `Q` of N, enclosures of `f = N − S∘c∘φ` by
//!
//! * the direct form `N(Q) − S(C)`, `C = c(φ(Q))`;
//! * the mean-value (centred) form `f(q0) + (DN(Q) − DS(C)·K·Dφ(Q))(Q − q0)`, `K` the hull
//!   of the clamp's derivatives on `φ(Q)` (Moore's centred form; valid for the Lipschitz
//!   `f`, one-sided derivatives across knot lines, see [`crate::spline::enclose`]);
//! * the second-order (Taylor) form `f(q0) + Df(q0)(Q − q0) + ½ (Q − q0)ᵀ D²f(Q) (Q − q0)`
//!   where `f` is C² on the box (φ(Q) inside D and within one span rectangle of S);
//!
//! intersected. Every value is enclosed relative to `c`, an `f64` approximation of
//! `S(φ(q0))`, and through centred enclosures of the control nets and their derivative nets
//! ([`crate::spline::enclose_net`]), so the widths follow the variation over the box.

use crate::scalar::Interval;
use crate::spline::NurbsSurface;
use crate::spline::enclose_net::INet;

type I = Interval;

/// The clamp of an interval to `[lo, hi]` and the hull of the clamp's derivative on it.
fn clamp(x: I, lo: f64, hi: f64) -> (I, I) {
    if x.lo >= lo && x.hi <= hi {
        (x, I::point(1.0))
    } else if x.hi < lo {
        (I::point(lo), I::point(0.0))
    } else if x.lo > hi {
        (I::point(hi), I::point(0.0))
    } else {
        (I::new(x.lo.max(lo), x.hi.min(hi)), I::new(0.0, 1.0))
    }
}

fn meet(a: I, b: I) -> I {
    let (lo, hi) = (a.lo.max(b.lo), a.hi.min(b.hi));
    if lo <= hi { I::new(lo, hi) } else { a }
}

/// The nets of N, φ and S's homogeneous form with their first and second derivative nets,
/// enclosed: `[∂s, ∂t, value]` and `[∂ss, ∂st, ∂tt]` (for S: u, v).
pub struct Nets {
    n: [INet<3>; 3],
    f: [INet<2>; 3],
    h: [INet<4>; 3],
    n2: Option<[INet<3>; 3]>,
    f2: Option<[INet<2>; 3]>,
    h2: Option<[INet<4>; 3]>,
}

fn second<const D: usize>(d: &[INet<D>; 3]) -> Option<[INet<D>; 3]> {
    Some([
        d[0].derivative(true)?,
        d[0].derivative(false)?,
        d[1].derivative(false)?,
    ])
}

impl Nets {
    /// `None` when a first derivative net cannot be formed or N, φ are not polynomial
    /// (second derivative nets are optional: degree 1 has none, and the first-order form
    /// is used alone).
    pub fn new(
        s: &NurbsSurface<f64, 3>,
        n: &NurbsSurface<f64, 3>,
        phi: &NurbsSurface<f64, 3>,
    ) -> Option<Nets> {
        let n: INet<3> = INet::polynomial(n)?;
        let n = [n.derivative(true)?, n.derivative(false)?, n];
        let f: INet<2> = INet::polynomial(phi)?;
        let f = [f.derivative(true)?, f.derivative(false)?, f];
        let h = INet::homogeneous(s);
        let h = [h.derivative(true)?, h.derivative(false)?, h];
        Some(Nets {
            n2: second(&n),
            f2: second(&f),
            h2: second(&h),
            n,
            f,
            h,
        })
    }
}

/// `X − c w` and `w` of a homogeneous point (a linear map).
fn shifted(c: [f64; 3]) -> impl Fn(&[I; 4]) -> [I; 4] {
    move |x| {
        let w = x[3];
        [
            x[0] - I::point(c[0]) * w,
            x[1] - I::point(c[1]) * w,
            x[2] - I::point(c[2]) * w,
            w,
        ]
    }
}

/// `sup_{q ∈ Q} |N(q) − S(c(φ(q)))|`, bounded (module documentation); `None` when an
/// enclosure fails. Every value is enclosed relative to `c`, an `f64` approximation of
/// `S(φ(q0))`, so that the intervals' widths follow the variation over the box.
pub fn box_bound(s: &NurbsSurface<f64, 3>, nets: &Nets, d: [f64; 4], qs: I, qt: I) -> Option<f64> {
    let (cs, ct) = (qs.mid().clamp(qs.lo, qs.hi), qt.mid().clamp(qt.lo, qt.hi));
    let (ps, pt) = (I::point(cs), I::point(ct));
    let [ns, nt, n] = &nets.n;
    let [fs, ft, f] = &nets.f;
    let [hu, hv, h] = &nets.h;
    // The reference point c.
    let f0 = f.enclose(ps, pt)?;
    let (a0, _) = clamp(f0[0], d[0], d[1]);
    let (b0, _) = clamp(f0[1], d[2], d[3]);
    let c = s.eval(&a0.mid(), &b0.mid());
    if !c.iter().all(|x| x.is_finite()) {
        return None;
    }
    let shift = |x: &[I; 3]| -> [I; 3] { std::array::from_fn(|k| x[k] - I::point(c[k])) };
    // S − c and its derivatives over a box of S's domain: Y/W with Y = X − c w.
    let s_rel = |u: I, v: I| -> Option<[I; 3]> {
        let y = h.enclose_map(u, v, shifted(c))?;
        let w = y[3];
        Some([
            y[0].checked_div(w)?,
            y[1].checked_div(w)?,
            y[2].checked_div(w)?,
        ])
    };
    // f(q0) − nothing: N(q0) − c − (S(c(φ(q0))) − c).
    let n0 = n.enclose_map(ps, pt, shift)?;
    let s0 = s_rel(a0, b0)?;
    // Over the box.
    let nq = n.enclose_map(qs, qt, shift)?;
    let (dns, dnt) = (ns.enclose(qs, qt)?, nt.enclose(qs, qt)?);
    let mut fq = f.enclose(qs, qt)?;
    let (dfs, dft) = (fs.enclose(qs, qt)?, ft.enclose(qs, qt)?);
    // On a box touching a side, φ's fixed coordinate there is exact (hypothesis 3), so
    // `φ_v(s, t) = v0 + ∫_0^t ∂_t φ_v ∈ v0 + [t]·∂_t φ_v(Q)` (likewise on the other sides):
    // with a positive derivative this keeps φ(Q) inside D, where the clamp is inactive.
    // With `∂_t φ_v ≥ 0` on Q this is exactly `φ_v ≥ v0` (no rounding in the conclusion).
    let one = I::point(1.0);
    let side = |x: &mut I, at: f64, from: I, deriv: I, low: bool| {
        *x = meet(*x, I::point(at) + from * deriv);
        if deriv.lo >= 0.0 {
            if low && x.lo < at {
                *x = I::new(at, x.hi.max(at));
            } else if !low && x.hi > at {
                *x = I::new(x.lo.min(at), at);
            }
        }
    };
    if qt.lo == 0.0 {
        side(&mut fq[1], d[2], qt, dft[1], true);
    }
    if qt.hi == 1.0 {
        side(&mut fq[1], d[3], qt - one, dft[1], false);
    }
    if qs.lo == 0.0 {
        side(&mut fq[0], d[0], qs, dfs[0], true);
    }
    if qs.hi == 1.0 {
        side(&mut fq[0], d[1], qs - one, dfs[0], false);
    }
    let (cu, ku) = clamp(fq[0], d[0], d[1]);
    let (cv, kv) = clamp(fq[1], d[2], d[3]);
    let y = h.enclose_map(cu, cv, shifted(c))?;
    let yu = hu.enclose_map(cu, cv, shifted(c))?;
    let yv = hv.enclose_map(cu, cv, shifted(c))?;
    let w = y[3];
    let sq_rel: [I; 3] = [
        y[0].checked_div(w)?,
        y[1].checked_div(w)?,
        y[2].checked_div(w)?,
    ];
    let mut su = [I::point(0.0); 3];
    let mut sv = [I::point(0.0); 3];
    for k in 0..3 {
        su[k] = (yu[k] - sq_rel[k] * yu[3]).checked_div(w)?;
        sv[k] = (yv[k] - sq_rel[k] * yv[3]).checked_div(w)?;
    }
    let (ds, dt) = (qs - ps, qt - pt);
    let taylor = second_order(nets, d, (ps, pt), (ds, dt), c, (n0, s0), (fq, su, sv, w, y));
    // Clamped Dφ: rows u, v; columns s, t.
    let (us, ut) = (ku * dfs[0], ku * dft[0]);
    let (vs, vt) = (kv * dfs[1], kv * dft[1]);
    let mut sq = I::point(0.0);
    for k in 0..3 {
        let gs = dns[k] - (su[k] * us + sv[k] * vs);
        let gt = dnt[k] - (su[k] * ut + sv[k] * vt);
        let centred = (n0[k] - s0[k]) + gs * ds + gt * dt;
        let direct = nq[k] - sq_rel[k];
        let mut fk = meet(centred, direct);
        if let Some(tk) = taylor {
            fk = meet(fk, tk[k]);
        }
        if !fk.is_finite() {
            return None;
        }
        let m = I::point(fk.mag());
        sq = sq + m * m;
    }
    Some(sq.hi.sqrt().next_up())
}

type Sjet = ([I; 2], [I; 3], [I; 3], I, [I; 4]);

/// The second-order (Taylor) form `f(q0) + Df(q0) d + ½ dᵀ D²f(Q) d`, valid where `f` is C²
/// on the box: φ(Q) inside D (no clamp) and within one span rectangle of S (one rational
/// function), Q within one span of N and φ (boxes are). `None` when not applicable.
/// `D²(S∘φ) = D²S(Dφ·, Dφ·) + DS·D²φ`, and for `S − c = Y/w`, `Y = X − c w`:
/// `S_uu = (Y_uu − 2 S_u w_u − (S − c) w_uu)/w`,
/// `S_uv = (Y_uv − S_u w_v − S_v w_u − (S − c) w_uv)/w` (The NURBS Book eq. 4.20 shifted).
fn second_order(
    nets: &Nets,
    d: [f64; 4],
    (ps, pt): (I, I),
    (ds, dt): (I, I),
    c: [f64; 3],
    (n0, s0): ([I; 3], [I; 3]),
    (fq, su, sv, w, y): Sjet,
) -> Option<[I; 3]> {
    let (n2, f2, h2) = (nets.n2.as_ref()?, nets.f2.as_ref()?, nets.h2.as_ref()?);
    let inside = |x: I, lo: f64, hi: f64| x.lo >= lo && x.hi <= hi;
    if !(inside(fq[0], d[0], d[1]) && inside(fq[1], d[2], d[3])) {
        return None;
    }
    let (cu, cv) = (fq[0], fq[1]);
    if !(nets.h[2].ku.single_span(cu) && nets.h[2].kv.single_span(cv)) {
        return None;
    }
    let sh = shifted(c);
    let (qs, qt) = (ps + ds, pt + dt);
    // Df(q0): at the point.
    let [ns, nt, _] = &nets.n;
    let [fs, ft, f] = &nets.f;
    let [hu, hv, h] = &nets.h;
    let (dn0s, dn0t) = (ns.enclose(ps, pt)?, nt.enclose(ps, pt)?);
    let f0 = f.enclose(ps, pt)?;
    let (df0s, df0t) = (fs.enclose(ps, pt)?, ft.enclose(ps, pt)?);
    let y0 = h.enclose_map(f0[0], f0[1], &sh)?;
    let (y0u, y0v) = (
        hu.enclose_map(f0[0], f0[1], &sh)?,
        hv.enclose_map(f0[0], f0[1], &sh)?,
    );
    let w0 = y0[3];
    let mut g = [[I::point(0.0); 2]; 3];
    for k in 0..3 {
        let rel = y0[k].checked_div(w0)?;
        let s0u = (y0u[k] - rel * y0u[3]).checked_div(w0)?;
        let s0v = (y0v[k] - rel * y0v[3]).checked_div(w0)?;
        g[k][0] = dn0s[k] - (s0u * df0s[0] + s0v * df0s[1]);
        g[k][1] = dn0t[k] - (s0u * df0t[0] + s0v * df0t[1]);
    }
    // D²f(Q).
    let [nss, nst, ntt] = n2;
    let [fss, fst, ftt] = f2;
    let [huu, huv, hvv] = h2;
    let (a_ss, a_st, a_tt) = (
        nss.enclose(qs, qt)?,
        nst.enclose(qs, qt)?,
        ntt.enclose(qs, qt)?,
    );
    let (p_ss, p_st, p_tt) = (
        fss.enclose(qs, qt)?,
        fst.enclose(qs, qt)?,
        ftt.enclose(qs, qt)?,
    );
    let (dfs, dft) = (fs.enclose(qs, qt)?, ft.enclose(qs, qt)?);
    let yu = hu.enclose_map(cu, cv, &sh)?;
    let yv = hv.enclose_map(cu, cv, &sh)?;
    let yuu = huu.enclose_map(cu, cv, &sh)?;
    let yuv = huv.enclose_map(cu, cv, &sh)?;
    let yvv = hvv.enclose_map(cu, cv, &sh)?;
    let half = I::point(0.5);
    let two = I::point(2.0);
    let mut out = [I::point(0.0); 3];
    for k in 0..3 {
        let rel = y[k].checked_div(w)?;
        let suu = (yuu[k] - two * su[k] * yu[3] - rel * yuu[3]).checked_div(w)?;
        let suv = (yuv[k] - su[k] * yv[3] - sv[k] * yu[3] - rel * yuv[3]).checked_div(w)?;
        let svv = (yvv[k] - two * sv[k] * yv[3] - rel * yvv[3]).checked_div(w)?;
        // (S∘φ)_ab = S_uu φu_a φu_b + S_uv (φu_a φv_b + φv_a φu_b) + S_vv φv_a φv_b
        //          + S_u φu_ab + S_v φv_ab.
        let comp = |a: [I; 2], b: [I; 2], ab: [I; 2]| {
            suu * a[0] * b[0]
                + suv * (a[0] * b[1] + a[1] * b[0])
                + svv * a[1] * b[1]
                + su[k] * ab[0]
                + sv[k] * ab[1]
        };
        let hss = a_ss[k] - comp(dfs, dfs, p_ss);
        let hst = a_st[k] - comp(dfs, dft, p_st);
        let htt = a_tt[k] - comp(dft, dft, p_tt);
        let quad = half * (hss * ds.sqr() + two * hst * (ds * dt) + htt * dt.sqr());
        out[k] = (n0[k] - s0[k]) + g[k][0] * ds + g[k][1] * dt + quad;
    }
    let _ = (y, w);
    Some(out)
}
