//! The search for a proven sign change of the sign-change certificate (the "Where the signs
//! come from" paragraph of the parent module): samples on circles of parameters around the
//! point, their signs of `h` proven over a foot box, pairs of opposite signs nearest to the
//! point bisected, and the radius of the certificate from an enclosure of `S` over the
//! bisected box.

use super::{EPS_MAX, EPS_MIN, Foot, GROWTH, I, PAIRS, SAMPLES, SignChangeCert, inv2, pt};
use crate::geom::{cross, dot, norm};
use crate::spline::NurbsSurface;
use crate::ssi::certify::{ExactSurface, distance_upper};
use crate::ssi::enclose::enclose_point;
use crate::ssi::refine::{domain, point_d1};
use rayon::prelude::*;

/// Two unit vectors orthogonal to the unit vector `d` and to each other.
fn across(d: &[f64; 3]) -> [[f64; 3]; 2] {
    let a = if d[0].abs() < 0.6 {
        [1.0, 0.0, 0.0]
    } else {
        [0.0, 1.0, 0.0]
    };
    let e1 = cross(d, &a);
    let l = norm(&e1);
    let e1 = e1.map(|c| c / l);
    [e1, cross(d, &e1)]
}

/// Parameter directions `d_k` of `S` at `x` whose images `S_u d_u + S_v d_v` are unit
/// vectors in `SAMPLES` evenly spread directions of the tangent plane (approximately).
fn directions(s: &NurbsSurface<f64, 3>, x: &[f64; 2]) -> Option<Vec<[f64; 2]>> {
    let (_, su, sv) = point_d1(s, x[0], x[1]);
    let lu = norm(&su);
    if !(lu > 0.0 && lu.is_finite()) {
        return None;
    }
    let a1 = su.map(|c| c / lu);
    let w: [f64; 3] = std::array::from_fn(|k| sv[k] - dot(&sv, &a1) * a1[k]);
    let lw = norm(&w);
    if !(lw > 1e-12 * norm(&sv) && lw.is_finite()) {
        return None;
    }
    let a2 = w.map(|c| c / lw);
    let g = [
        [dot(&su, &su), dot(&su, &sv)],
        [dot(&su, &sv), dot(&sv, &sv)],
    ];
    let gi = inv2(&g)?;
    Some(
        (0..SAMPLES)
            .map(|k| {
                let th = std::f64::consts::TAU * k as f64 / SAMPLES as f64;
                let t: [f64; 3] = std::array::from_fn(|c| th.cos() * a1[c] + th.sin() * a2[c]);
                let r = [dot(&su, &t), dot(&sv, &t)];
                [
                    gi[0][0] * r[0] + gi[0][1] * r[1],
                    gi[1][0] * r[0] + gi[1][1] * r[1],
                ]
            })
            .collect(),
    )
}

/// Distance (in the parameter plane, scaled by `w`) from `x` to the segment `[a, b]`.
fn seg_dist(x: &[f64; 2], a: &[f64; 2], b: &[f64; 2], w: &[f64; 2]) -> f64 {
    let d = [(b[0] - a[0]) * w[0], (b[1] - a[1]) * w[1]];
    let r = [(x[0] - a[0]) * w[0], (x[1] - a[1]) * w[1]];
    let l2 = d[0] * d[0] + d[1] * d[1];
    let t = if l2 > 0.0 {
        ((r[0] * d[0] + r[1] * d[1]) / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    ((r[0] - t * d[0]).powi(2) + (r[1] - t * d[1]).powi(2)).sqrt()
}

/// The certificate for one assignment of roles: segments in `s`'s parameters around `x`,
/// feet on `f` near `y`.
#[allow(clippy::too_many_arguments)]
pub(super) fn with_roles(
    s: &NurbsSurface<f64, 3>,
    f: &NurbsSurface<f64, 3>,
    es: &ExactSurface,
    ef: &ExactSurface,
    p: &[f64; 3],
    x: &[f64; 2],
    y: &[f64; 2],
    on: char,
    tol: f64,
) -> Option<SignChangeCert> {
    let (_, fs, ft) = point_d1(f, y[0], y[1]);
    let n0 = cross(&fs, &ft);
    let ln = norm(&n0);
    if !(ln > 0.0 && ln.is_finite()) {
        return None;
    }
    let e = across(&n0.map(|c| c / ln));
    let ei = e.map(|v| v.map(pt));
    let n = [
        ei[0][1] * ei[1][2] - ei[0][2] * ei[1][1],
        ei[0][2] * ei[1][0] - ei[0][0] * ei[1][2],
        ei[0][0] * ei[1][1] - ei[0][1] * ei[1][0],
    ];
    // e1, e2, N a basis: |N|² > 0 proven.
    if !(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).is_pos() {
        return None;
    }
    let foot = Foot {
        s,
        f,
        es,
        ef,
        e,
        n,
        dom_s: domain(s),
        dom_f: domain(f),
    };
    let dirs = directions(s, x)?;
    let ds = foot.dom_s;
    let inside = |z: &[f64; 2]| z[0] >= ds[0] && z[0] <= ds[1] && z[1] >= ds[2] && z[1] <= ds[3];
    let scale = 1.0 + p.iter().fold(0.0f64, |m, c| m.max(c.abs()));
    let (_, su, sv) = point_d1(s, x[0], x[1]);
    let w = [norm(&su), norm(&sv)];
    let mut eps = EPS_MIN * scale;
    // The previous circle's decided samples: point, sign, box of its foot.
    let mut prev: Vec<([f64; 2], bool, [I; 2])> = Vec::new();
    while eps <= EPS_MAX * scale {
        let samples: Vec<Option<[f64; 2]>> = dirs
            .iter()
            .map(|d| {
                let z = [x[0] + eps * d[0], x[1] + eps * d[1]];
                inside(&z).then_some(z)
            })
            .collect();
        let pts: Vec<[f64; 2]> = samples.iter().flatten().copied().collect();
        if pts.len() >= 2 {
            let bx: [I; 2] = std::array::from_fn(|i| {
                let lo = pts.iter().map(|z| z[i]).fold(f64::INFINITY, f64::min);
                let hi = pts.iter().map(|z| z[i]).fold(f64::NEG_INFINITY, f64::max);
                I::new(lo, hi)
            });
            if let Some(fb) = foot.foot_box(&bx, *y) {
                let signs: Vec<Option<(bool, [I; 2])>> = samples
                    .par_iter()
                    .map(|z| z.and_then(|z| foot.sign_at(&z, &fb)))
                    .collect();
                let mut decided: Vec<([f64; 2], bool)> = Vec::new();
                let mut next = Vec::new();
                for (z, sg) in samples.iter().zip(&signs) {
                    if let (Some(z), Some((sg, zb))) = (z, sg) {
                        decided.push((*z, *sg));
                        next.push((*z, *sg, *zb));
                    }
                }
                // A previous sample whose foot box lies in Y has the same foot here (the only
                // zero in Y), so its sign holds for this h: pairs across the two circles catch
                // a curve between them.
                let within = |v: f64, i: I| i.lo <= v && v <= i.hi;
                let sub = |a: &[I; 2], b: &[I; 2]| {
                    (0..2).all(|i| b[i].lo <= a[i].lo && a[i].hi <= b[i].hi)
                };
                for (z, sg, zb) in &prev {
                    if within(z[0], bx[0]) && within(z[1], bx[1]) && sub(zb, &fb.y) {
                        decided.push((*z, *sg));
                    }
                }
                prev = next;
                // Pairs with proven opposite signs, nearest to x first.
                let mut pairs = Vec::new();
                for (i, (a, sa)) in decided.iter().enumerate() {
                    for (b, sb) in &decided[i + 1..] {
                        if sa != sb {
                            let (a, b) = if *sa { (*a, *b) } else { (*b, *a) };
                            pairs.push((seg_dist(x, &a, &b, &w), a, b));
                        }
                    }
                }
                pairs.sort_by(|u, v| u.0.total_cmp(&v.0));
                let mut best: Option<SignChangeCert> = None;
                for (_, a, b) in pairs.into_iter().take(PAIRS) {
                    // Bisection to 1/100 of the distance from p (or of tol).
                    let pa = s.eval(&a[0], &a[1]);
                    let d = (0..3).map(|k| (pa[k] - p[k]).powi(2)).sum::<f64>().sqrt();
                    let xs = foot.bisect(a, b, &fb, &w, 1e-2 * d.min(tol));
                    let Some(q) = enclose_point(s, xs[0], xs[1]) else {
                        continue;
                    };
                    if let Some(r) = distance_upper(p, &q)
                        && best.is_none_or(|c| r < c.radius)
                    {
                        best = Some(SignChangeCert {
                            radius: r,
                            on,
                            params: xs,
                            eps,
                        });
                    }
                }
                if best.is_some() {
                    return best;
                }
            }
        }
        eps *= GROWTH;
    }
    None
}
