//! Step 1b, f64 path — split D at its own knots (Bézier pieces enclosed in interval
//! arithmetic) and wherever it crosses a knot line of S or the domain's boundary. A crossing
//! of `u(t) = u_k` is isolated rigorously on the Bernstein coefficients of `u(t) - u_k`
//! (enclosed): a sub-interval is discarded when the coefficients are certified of one sign,
//! and accepted as holding exactly one simple crossing when its end values have certified
//! opposite signs and the derivative's coefficients one certified sign (monotone); it is then
//! narrowed by bisection to `2^-44`. A crossing within `2^-40` of a piece's end (the curve
//! passing through a knot line exactly at one of its own knots) is assigned to that end's
//! vertex on interior knot lines. Anything else the enclosures cannot decide within
//! `2^-40` (a tangency to a knot line; an end zone on the domain's boundary, where the
//! curve must be proven inside) is reported as undecided, and the caller reruns in exact
//! arithmetic. The certificate does not depend on where the cuts fall (see
//! [`super::distance`]): they only keep each chord in one patch.

use super::cells::FCells;
use super::ibez::{I, IP, bspline_span_bezier, dist_hi, eval, ip, mid, mr_levels_error, split_at};
use super::{FSeg, FloatError, Piece, Undecided};
use crate::curve_on_surface::CosError;
use crate::curve_on_surface::casteljau;
use crate::spline::BSplineCurve;

const MAX_DEPTH: u32 = 40;
const ROOT_WIDTH: f64 = 1.0 / (1u64 << 44) as f64;

/// Sign of the polynomial with these Bernstein coefficients on the open interval, when
/// certified: `Some(1)`, `Some(-1)`, `Some(0)` (identically zero), `None` undecided.
fn open_sign(b: &[IP<1>]) -> Option<i8> {
    if b.iter().all(|x| x[0].lo >= 0.0) && b.iter().any(|x| x[0].lo > 0.0) {
        return Some(1);
    }
    if b.iter().all(|x| x[0].hi <= 0.0) && b.iter().any(|x| x[0].hi < 0.0) {
        return Some(-1);
    }
    if b.iter().all(|x| x[0].lo == 0.0 && x[0].hi == 0.0) {
        return Some(0);
    }
    None
}

fn strict_sign(x: &I) -> i8 {
    if x.is_pos() {
        1
    } else if x.is_neg() {
        -1
    } else {
        0
    }
}

/// Exactly one simple root inside: certified opposite end values, monotone.
fn simple_root(b: &[IP<1>]) -> bool {
    let n = b.len() - 1;
    let (s0, s1) = (strict_sign(&b[0][0]), strict_sign(&b[n][0]));
    if s0 == 0 || s1 == 0 || s0 == s1 {
        return false;
    }
    let d: Vec<I> = b.windows(2).map(|w| w[1][0] - w[0][0]).collect();
    d.iter().all(|x| x.is_pos()) || d.iter().all(|x| x.is_neg())
}

/// Where a sub-interval is split: off the centre, so that crossings at "round" parameters
/// (1/2, 1/4, … — common for symmetric data) fall inside a sub-interval, not on its end.
const SPLIT: f64 = 0.5 - 1.0 / 2048.0;

/// Isolate the sign changes of the polynomial with Bernstein coefficients `b` on `[lo, hi]`
/// (`end_zones`: a sub-interval of width `2^-MAX_DEPTH` at the piece's start or end that
/// stays undecided is accepted — any crossing there is within that width of the piece's end
/// vertex, which is already a cut).
fn isolate(
    b: Vec<IP<1>>,
    lo: f64,
    hi: f64,
    depth: u32,
    end_zones: bool,
    out: &mut Vec<f64>,
) -> Result<(), ()> {
    if open_sign(&b).is_some() {
        return Ok(());
    }
    if simple_root(&b) {
        // Narrowing on the local parameter of this sub-interval (Illinois regula falsi, with
        // a bisection step after any step that did not halve the bracket): the sign of the
        // enclosed value at the trial point decides the side; a trial point whose sign is
        // undecided lies within the enclosure's width of the root and is taken as it.
        let s0 = strict_sign(&b[0][0]);
        let n = b.len() - 1;
        let mids: Vec<f64> = b.iter().map(|x| x[0].mid()).collect();
        let r = b.iter().fold(0.0f64, |m, x| m.max(x[0].radius_about_mid()));
        let mx = mids.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        // The value at a point parameter is within `err` of the f64 de Casteljau value.
        let err = mr_levels_error(r, n, mx);
        let (mut a, mut z) = (0.0f64, 1.0f64);
        let (mut fa, mut fz) = (mids[0], mids[n]);
        let (mut last_side, mut bisect) = (0i8, false);
        let mut found = None;
        while (z - a) * (hi - lo) > ROOT_WIDTH {
            let width = z - a;
            let mut c = if bisect || fa == fz {
                a + width / 2.0
            } else {
                (a * fz - z * fa) / (fz - fa)
            };
            if !(c > a && c < z) {
                c = a + width / 2.0;
            }
            let v = casteljau::eval_1d(&mids, c);
            let m = if v > err {
                1
            } else if v < -err {
                -1
            } else {
                0
            };
            if m == s0 {
                a = c;
                fa = v;
                if last_side == 1 {
                    fz /= 2.0;
                }
                last_side = 1;
            } else if m == -s0 {
                z = c;
                fz = v;
                if last_side == -1 {
                    fa /= 2.0;
                }
                last_side = -1;
            } else {
                found = Some(c);
                break;
            }
            bisect = z - a > width / 2.0;
        }
        let t = found.unwrap_or(a + (z - a) / 2.0);
        out.push(lo + (hi - lo) * t);
        return Ok(());
    }
    if depth >= MAX_DEPTH {
        return if end_zones && (lo == 0.0 || hi == 1.0) {
            Ok(())
        } else {
            Err(())
        };
    }
    let (l, r) = split_at(&b, SPLIT);
    let c = lo + (hi - lo) * SPLIT;
    isolate(l, lo, c, depth + 1, end_zones, out)?;
    isolate(r, c, hi, depth + 1, end_zones, out)
}

/// Crossing parameters in `(0, 1)` of the piece with line `x_dim = k` (`interior`: a knot
/// line inside the domain, where end zones may be accepted; on the domain's boundary they
/// may not, since the curve must be proven inside).
fn crossings(ctrl: &[IP<2>], dim: usize, k: f64, interior: bool) -> Result<Vec<f64>, ()> {
    // A line outside the range of the enclosed control points: the exact curve lies in
    // their convex hull, strictly on one side, so it does not cross.
    let one_side = |c: &[IP<2>]| c.iter().all(|p| p[dim].lo > k) || c.iter().all(|p| p[dim].hi < k);
    if one_side(ctrl) {
        return Ok(Vec::new());
    }
    // A piece along the line (every coefficient exactly on it) needs no cut: it lies in the
    // closed cells on both sides. A piece with an end exactly on the line and its other
    // coefficients strictly on one side has `Σ b_i B_i(t)` of one sign on `(0, 1)` (the
    // Bernstein basis is positive there): no crossing but at that end, already a vertex.
    let on = |p: &IP<2>| p[dim].lo == k && p[dim].hi == k;
    let n = ctrl.len() - 1;
    if ctrl.iter().all(on)
        || (n >= 2 && on(&ctrl[0]) && on(&ctrl[n]) && one_side(&ctrl[1..n]))
        || (n >= 1 && on(&ctrl[0]) && !on(&ctrl[n]) && one_side(&ctrl[1..]))
        || (n >= 1 && on(&ctrl[n]) && !on(&ctrl[0]) && one_side(&ctrl[..n]))
    {
        return Ok(Vec::new());
    }
    let b: Vec<IP<1>> = ctrl.iter().map(|p| [p[dim] - I::point(k)]).collect();
    let mut out = Vec::new();
    isolate(b, 0.0, 1.0, 0, interior, &mut out)?;
    Ok(out)
}

#[derive(Clone, Copy)]
enum Snap {
    None,
    U(f64),
    V(f64),
}

/// The Bézier pieces of D (enclosed) and the initial segments.
pub fn split(
    curve: &BSplineCurve<[f64; 2]>,
    cells: &FCells,
) -> Result<(Vec<Piece>, Vec<FSeg>), FloatError> {
    let p = curve.degree();
    let knots = curve.knots.knots();
    let ctrl: Vec<IP<2>> = curve.control.iter().map(ip).collect();
    let dom = cells.domain();
    // Control points inside the domain (exact comparisons): the curve is inside (convex
    // hull). A coordinate equal in every control point is that value all along the curve
    // (a convex combination of equal values): its enclosures are made exact.
    let all_in = curve
        .control
        .iter()
        .all(|p| dom[0] <= p[0] && p[0] <= dom[1] && dom[2] <= p[1] && p[1] <= dom[3]);
    let constant: [Option<f64>; 2] = std::array::from_fn(|d| {
        let x = curve.control.first()?[d];
        curve.control.iter().all(|p| p[d] == x).then_some(x)
    });
    let mut pieces = Vec::new();
    let mut segs: Vec<FSeg> = Vec::new();
    for w in curve.knots.breakpoints().windows(2) {
        let s = curve.knots.find_span(&w[0]);
        let mut bz = bspline_span_bezier(knots, p, &ctrl, s)
            .ok_or(FloatError::Undecided(Undecided::DomainKnots))?;
        for (d, x) in constant.iter().enumerate() {
            if let Some(x) = x {
                bz.iter_mut().for_each(|c| c[d] = I::point(*x));
            }
        }
        let mut cuts: Vec<(f64, Snap)> = Vec::new();
        for (dim, breaks) in [(0usize, &cells.u_breaks), (1usize, &cells.v_breaks)] {
            for (bi, &k) in breaks.iter().enumerate() {
                let interior = bi > 0 && bi + 1 < breaks.len();
                let ts = crossings(&bz, dim, k, interior).map_err(|_| {
                    FloatError::Undecided(Undecided::KnotLineCrossing {
                        t: [w[0], w[1]],
                        along_u: dim == 0,
                        knot: k,
                    })
                })?;
                cuts.extend(
                    ts.into_iter()
                        .map(|t| (t, if dim == 0 { Snap::U(k) } else { Snap::V(k) })),
                );
            }
        }
        cuts.sort_by(|x, y| x.0.total_cmp(&y.0));
        let mut ts: Vec<(f64, Snap)> = vec![(0.0, Snap::None)];
        ts.extend(cuts.into_iter().filter(|c| c.0 > 0.0 && c.0 < 1.0));
        ts.push((1.0, Snap::None));
        ts.dedup_by(|x, y| x.0 == y.0);
        let global = |t: f64| w[0] + (w[1] - w[0]) * t;
        let encl: Vec<IP<2>> = ts
            .iter()
            .map(|(t, _)| {
                let mut e = eval(&bz, I::point(*t));
                for (d, x) in constant.iter().enumerate() {
                    if let Some(x) = x {
                        e[d] = I::point(*x);
                    }
                }
                e
            })
            .collect();
        let mut verts: Vec<[f64; 2]> = ts
            .iter()
            .zip(&encl)
            .map(|((_, s), e)| {
                let mut v = mid(e);
                match s {
                    Snap::U(u) => v[0] = *u,
                    Snap::V(x) => v[1] = *x,
                    Snap::None => {}
                }
                v
            })
            .collect();
        // The cell of each stretch, from an enclosure of its midpoint.
        let mut cell_of = Vec::with_capacity(ts.len() - 1);
        for k in 0..ts.len() - 1 {
            let (t0, t1) = (ts[k].0, ts[k + 1].0);
            let mut m = eval(&bz, I::point(t0 + (t1 - t0) / 2.0));
            for (d, x) in constant.iter().enumerate() {
                if let Some(x) = x {
                    m[d] = I::point(*x);
                }
            }
            let inside = all_in
                || (m[0].lo >= dom[0]
                    && m[0].hi <= dom[1]
                    && m[1].lo >= dom[2]
                    && m[1].hi <= dom[3]);
            let outside = !all_in
                && (m[0].hi < dom[0] || m[0].lo > dom[1] || m[1].hi < dom[2] || m[1].lo > dom[3]);
            if outside {
                return Err(FloatError::Cos(CosError::OutOfDomain {
                    t0: global(t0),
                    t1: global(t1),
                    at: mid(&m),
                }));
            }
            if !inside {
                return Err(FloatError::Undecided(Undecided::InsideDomain {
                    t: global(t0 + (t1 - t0) / 2.0),
                }));
            }
            // The exact test says inside; a cell the f64 lookup cannot find is left to the
            // exact rerun.
            // Inside, so the midpoint clamped to the domain is as good a witness as the
            // midpoint of its enclosure.
            let c = mid(&m);
            let c = [c[0].clamp(dom[0], dom[1]), c[1].clamp(dom[2], dom[3])];
            match cells.locate(&c) {
                Some(c) => cell_of.push(c),
                None => {
                    return Err(FloatError::Undecided(Undecided::Cell {
                        t: global(t0 + (t1 - t0) / 2.0),
                    }));
                }
            }
        }
        for (idx, v) in verts.iter_mut().enumerate() {
            for k in [idx.wrapping_sub(1), idx] {
                if let Some(&c) = cell_of.get(k) {
                    *v = cells.clamp(c, v);
                }
            }
        }
        let pidx = pieces.len();
        for k in 0..ts.len() - 1 {
            segs.push(FSeg {
                piece: pidx,
                t0: ts[k].0,
                t1: ts[k + 1].0,
                a: verts[k],
                b: verts[k + 1],
                ea: dist_hi(&encl[k], &verts[k]),
                eb: dist_hi(&encl[k + 1], &verts[k + 1]),
                cell: cell_of[k],
                h: f64::INFINITY,
                k: f64::INFINITY,
                k_region: [0.0; 4],
                k_own: false,
            });
        }
        pieces.push(Piece {
            t_lo: w[0],
            t_hi: w[1],
            ctrl_f64: bz.iter().map(mid).collect(),
            ctrl_r: bz
                .iter()
                .flatten()
                .fold(0.0f64, |m, x| m.max(x.radius_about_mid())),
            ctrl_mx: bz
                .iter()
                .flatten()
                .fold(0.0f64, |m, x| m.max(x.mid().abs())),
            ctrl: bz,
        });
    }
    // Consecutive segments share their vertex exactly (a clamp in one may have moved it);
    // the offset is recomputed from the enclosure of the curve point it stands for.
    for i in 1..segs.len() {
        if segs[i].a != segs[i - 1].b {
            let keep_left = segs[i - 1].eb <= segs[i].ea;
            let v = if keep_left { segs[i - 1].b } else { segs[i].a };
            let v = cells.clamp(segs[i].cell, &cells.clamp(segs[i - 1].cell, &v));
            let e_left = dist_hi(
                &eval(&pieces[segs[i - 1].piece].ctrl, I::point(segs[i - 1].t1)),
                &v,
            );
            let e_right = dist_hi(&eval(&pieces[segs[i].piece].ctrl, I::point(segs[i].t0)), &v);
            segs[i - 1].b = v;
            segs[i - 1].eb = e_left;
            segs[i].a = v;
            segs[i].ea = e_right;
        }
    }
    Ok((pieces, segs))
}
