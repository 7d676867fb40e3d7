//! Step 1b — split the domain curve D at its own knots (exact Bézier extraction) and wherever
//! it crosses a knot line of S (or the domain's boundary): crossing parameters are roots of
//! `u(t) - u_k` isolated exactly (Bernstein–Descartes with a square-free certificate, Sturm
//! otherwise), never by sampling. The vertex at a crossing is *snapped* onto the knot line,
//! so each chord lies in one patch; its offset from the curve is carried as a proven bound.
//! A piece outside the surface's domain is an error naming its parameter range.

use super::CosError;
use super::cells::Cells;
use super::segments::{Seg, offset, round};
use crate::geom::lift_point;
use crate::predicates::poly::{
    Poly, certify_squarefree, deflate_ends, descartes_isolate, integer_bernstein,
    integer_power_from_bernstein, isolate_roots, negative_on_unit_interval,
};
use crate::scalar::{Rational, Scalar, lift, pow2};
use crate::spline::{BSplineCurve, BezierCurve};
use dashu_int::ops::BitTest;

type Q = Rational;

/// Depth of crossing isolation: crossings are located within `2^-CROSSING_DEPTH` in `t`.
const CROSSING_DEPTH: u32 = 48;

/// Parameters in `(0,1)` where the polynomial with Bernstein coefficients `b` changes sign.
fn sign_changes(b: &[Q]) -> Vec<Q> {
    if b.iter().all(|x| Scalar::sign(x) == crate::Sign::Positive)
        || b.iter().all(|x| Scalar::sign(x) == crate::Sign::Negative)
    {
        return vec![];
    }
    if b.iter().all(|x| x.is_zero()) {
        return vec![];
    }
    let two = Q::from(2);
    let ib = integer_bernstein(b);
    let g = deflate_ends(integer_power_from_bernstein(&ib));
    if g.len() <= 1 {
        return vec![];
    }
    let roots: Vec<(Q, Q)> = if certify_squarefree(&g) {
        let bits = ib.iter().map(|x| x.bit_len()).max().unwrap_or(0) as u32;
        let cap = 64 + (ib.len() as u32) * (bits + 2 * ib.len() as u32);
        match descartes_isolate(&ib, cap, CROSSING_DEPTH) {
            Some(r) => r.into_iter().map(|x| (x.lo, x.hi)).collect(),
            None => vec![],
        }
    } else {
        let odd = Poly::from_bernstein(b).odd_multiplicity_part();
        let w = pow2(-i64::from(CROSSING_DEPTH));
        isolate_roots(&odd, &Q::ZERO, &Q::ONE, &w)
    };
    roots
        .into_iter()
        .map(|(lo, hi)| (lo + hi) / two.clone())
        .collect()
}

/// What a crossing vertex is snapped onto.
#[derive(Clone, Copy)]
enum Snap {
    None,
    U(f64),
    V(f64),
    /// A patch corner: both lines crossed at the same parameter.
    UV(f64, f64),
}

/// The exact Bézier pieces of D and the initial segments.
pub type Split = (Vec<BezierCurve<[Q; 2]>>, Vec<Seg>);

/// Split D into its exact Bézier pieces and the initial segments (one per stretch between
/// consecutive knot-line crossings).
pub fn split(curve: &BSplineCurve<[f64; 2]>, cells: &Cells) -> Result<Split, CosError> {
    let cq: BSplineCurve<[Q; 2]> = curve.map(|k| lift(*k), lift_point);
    let bz = cq.bezier_pieces();
    let mut pieces = Vec::with_capacity(bz.len());
    let mut segs = Vec::new();
    let dom = [
        cells.u_breaks[0],
        cells.u_breaks[cells.u_breaks.len() - 1],
        cells.v_breaks[0],
        cells.v_breaks[cells.v_breaks.len() - 1],
    ];
    for bp in bz {
        let c = bp.curve;
        let g =
            |t: &Q| Scalar::to_f64(&(bp.t0.clone() + (bp.t1.clone() - bp.t0.clone()) * t.clone()));
        // Inside the domain, exactly: each edge function (u - u0, u1 - u, v - v0, v1 - v)
        // is >= 0 on the whole piece. Crossing parameters alone miss a piece that touches an
        // edge from outside (a double root, no sign change).
        for (dim, edge, sign) in [
            (0, dom[0], 1),
            (0, dom[1], -1),
            (1, dom[2], 1),
            (1, dom[3], -1),
        ] {
            let e: Q = lift(edge);
            let b: Vec<Q> = c
                .control
                .iter()
                .map(|p| {
                    let d = p[dim].clone() - e.clone();
                    if sign > 0 { d } else { -d }
                })
                .collect();
            if let Some(t) = negative_on_unit_interval(&b) {
                return Err(CosError::OutOfDomain {
                    t0: g(&t),
                    t1: g(&t),
                    at: round(&c.eval(&t)),
                });
            }
        }
        let mut cuts: Vec<(Q, Snap)> = Vec::new();
        for (dim, breaks) in [(0usize, &cells.u_breaks), (1usize, &cells.v_breaks)] {
            for &k in breaks.iter() {
                let kq: Q = lift(k);
                let b: Vec<Q> = c
                    .control
                    .iter()
                    .map(|p| p[dim].clone() - kq.clone())
                    .collect();
                for t in sign_changes(&b) {
                    cuts.push((t, if dim == 0 { Snap::U(k) } else { Snap::V(k) }));
                }
            }
        }
        cuts.sort_by(|x, y| x.0.cmp(&y.0));
        // Vertices: the piece's end points and every crossing.
        let mut ts: Vec<(Q, Snap)> = vec![(Q::ZERO, Snap::None)];
        for (t, s) in cuts {
            let last = ts.len() - 1;
            if ts[last].0 == t {
                ts[last].1 = match (ts[last].1, s) {
                    (Snap::U(u), Snap::V(v)) | (Snap::V(v), Snap::U(u)) => Snap::UV(u, v),
                    (old, _) => old,
                };
            } else {
                ts.push((t, s));
            }
        }
        if ts.last().is_some_and(|x| x.0 == Q::ONE) {
            ts.pop();
        }
        ts.push((Q::ONE, Snap::None));
        let exact: Vec<[Q; 2]> = ts.iter().map(|(t, _)| c.eval(t)).collect();
        let mut verts: Vec<[f64; 2]> = ts
            .iter()
            .zip(&exact)
            .map(|((_, s), e)| {
                let mut v = round(e);
                match s {
                    Snap::U(u) => v[0] = *u,
                    Snap::V(w) => v[1] = *w,
                    Snap::UV(u, w) => v = [*u, *w],
                    Snap::None => {}
                }
                v
            })
            .collect();
        // The cell of each stretch, from its exact midpoint.
        let mut cell_of = Vec::with_capacity(ts.len() - 1);
        for w in 0..ts.len() - 1 {
            let (t0, t1) = (&ts[w].0, &ts[w + 1].0);
            let mid = c.eval(&((t0.clone() + t1.clone()) / Q::from(2)));
            let cell = cells.locate(&mid).ok_or_else(|| {
                let g = |t: &Q| {
                    Scalar::to_f64(&(bp.t0.clone() + (bp.t1.clone() - bp.t0.clone()) * t.clone()))
                };
                CosError::OutOfDomain {
                    t0: g(t0),
                    t1: g(t1),
                    at: round(&mid),
                }
            })?;
            cell_of.push(cell);
        }
        // Keep every vertex inside the cells of the stretches it joins (only rounding can
        // move it out; two adjacent cells meet on an edge, where the clamps agree).
        for (idx, v) in verts.iter_mut().enumerate() {
            for w in [idx.wrapping_sub(1), idx] {
                if let Some(&cell) = cell_of.get(w) {
                    *v = cells.clamp(cell, v);
                }
            }
        }
        let pidx = pieces.len();
        for w in 0..ts.len() - 1 {
            segs.push(Seg {
                piece: pidx,
                t0: ts[w].0.clone(),
                t1: ts[w + 1].0.clone(),
                a: verts[w],
                b: verts[w + 1],
                ea: offset(&verts[w], &exact[w]),
                eb: offset(&verts[w + 1], &exact[w + 1]),
                cell: cell_of[w],
                h: f64::INFINITY,
                k: f64::INFINITY,
            });
        }
        pieces.push(c);
    }
    // Consecutive segments must share their vertex exactly (a clamp in one may have moved
    // it): keep the nearer one, clamped into both cells (adjacent cells meet on an edge, where
    // the clamps agree), with its exact offsets from both curve points it stands for.
    for i in 1..segs.len() {
        if segs[i].a != segs[i - 1].b {
            let v = if segs[i - 1].eb <= segs[i].ea {
                segs[i - 1].b
            } else {
                segs[i].a
            };
            let v = cells.clamp(segs[i].cell, &cells.clamp(segs[i - 1].cell, &v));
            let end = pieces[segs[i - 1].piece].eval(&segs[i - 1].t1);
            let start = pieces[segs[i].piece].eval(&segs[i].t0);
            segs[i - 1].b = v;
            segs[i - 1].eb = offset(&v, &end);
            segs[i].a = v;
            segs[i].ea = offset(&v, &start);
        }
    }
    Ok((pieces, segs))
}
