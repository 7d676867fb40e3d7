//! Seams placed outside the faces. An analytic surface closed around an axis (cylinder, cone,
//! sphere, torus, surface of revolution) is converted to a NURBS form whose parameter starts
//! at the placement's x direction; a face that spans that direction (a cylinder face from
//! −60° to +60°) then crosses the seam of its own surface, and its loops do not bound one
//! region of the parameter rectangle (vericad finds no region for it; Open CASCADE's area of
//! such a face written as IGES was 14 % off). Where the surface is used by that face alone,
//! the NURBS form is re-parametrized to start in the widest angular gap of the face's
//! boundary ([`BSplineSurface::reseamed_u`]): the same surface, point for point.
//!
//! The face's boundary is sampled at 65 points per edge (ends included) and projected onto
//! the surface; points on the seam itself are left out. The seam is moved when boundary points
//! lie on both sides of it, their two distances from it adding up to at most 2 % of the
//! period, and a gap of at least 10 % of the period lies elsewhere. Not detected: a face that
//! spans the seam with no boundary near it (a sphere lune bounded by two meridians 30° either
//! side of the seam); surfaces carrying parameter-space trim loops (IGES) are left alone. Every
//! surface moved is named in the model's warnings.

use super::{Brep, LoopKind};
use crate::geom::Point;
use crate::geom::dist;
use crate::geom::dot;
use crate::model::Model;
use crate::spline::closure::Closure;
use crate::spline::project::{SurfaceFoot, point_d1};
use crate::spline::{BSplineSurface, NurbsSurface};
use std::collections::BTreeMap;

/// Move the seams of surfaces out of the faces that span them (see the module comment);
/// returns the model surfaces re-parametrized.
pub fn place_seams(m: &mut Model) -> Vec<usize> {
    let Some(b) = m.brep.as_ref() else {
        return vec![];
    };
    let mut users: BTreeMap<usize, Vec<usize>> = BTreeMap::new();
    for (fi, f) in b.faces.iter().enumerate() {
        if let Some(si) = f.surface.filter(|s| *s < m.surfaces.len()) {
            users.entry(si).or_default().push(fi);
        }
    }
    let mut changed = Vec::new();
    for (si, faces) in users {
        let surf = &m.surfaces[si];
        if faces.len() != 1 || !surf.kind.is_analytic() || !surf.trim_loops.is_empty() {
            continue;
        }
        let pts = boundary(b, faces[0]);
        if pts.is_empty() {
            continue;
        }
        let closure = Closure::of(&surf.nurbs);
        // Distance under which a boundary point counts as on the surface: the model's
        // tolerance (the readers make it at least 1e-9 of the model's size).
        let near = b.tolerance;
        let mut s = surf.nurbs.clone();
        let mut moved = false;
        // Feet of the boundary samples on `s`, made again only after `s` is re-parametrized.
        let mut feet: Option<Vec<[f64; 2]>> = None;
        for d in 0..2 {
            let closed = if d == 0 {
                closure.seam_u
            } else {
                closure.seam_v
            };
            if !closed {
                continue;
            }
            let (u0, u1, v0, v1) = s.hom.domain();
            let (lo, hi) = if d == 0 { (u0, u1) } else { (v0, v1) };
            let f = feet.get_or_insert_with(|| feet_of(&s, &pts, near, &closure));
            let params: Vec<f64> = pts
                .iter()
                .zip(f.iter())
                .map(|(x, q)| parameter(&s, x, *q, d))
                .collect();
            if let Some(t) = new_seam(params, lo, hi)
                && let Some(r) = reseamed(&s, d, t)
            {
                s = r;
                moved = true;
                feet = None;
            }
        }
        if moved {
            m.surfaces[si].nurbs = s;
            changed.push(si);
        }
    }
    changed
}

/// [`place_seams`], with a warning naming the surfaces moved.
pub fn warn(m: &mut Model) {
    let moved = place_seams(m);
    if !moved.is_empty() {
        let ids: Vec<String> = moved
            .iter()
            .map(|&i| {
                let s = &m.surfaces[i];
                s.source.clone().unwrap_or_else(|| s.name.clone())
            })
            .collect();
        m.warnings.push(format!(
            "{} closed surface(s) re-parametrized so that their seam lies outside their face (the same surface; its parameters start elsewhere): {}",
            ids.len(),
            crate::model::list_ids(ids)
        ));
    }
}

/// Samples per edge of a face's boundary, ends included.
const EDGE_SAMPLES: usize = 65;

/// Points along the edges of face `fi`'s loops, [`EDGE_SAMPLES`] per edge, ends included.
fn boundary(b: &Brep, fi: usize) -> Vec<[f64; 3]> {
    let mut out = Vec::new();
    for l in &b.faces[fi].loops {
        if let LoopKind::Edges(oes) = &l.kind {
            for o in oes {
                let Some(c) = b.edges.get(o.edge).and_then(|e| e.curve.as_ref()) else {
                    continue;
                };
                let (t0, t1) = c.nurbs.hom.domain();
                let n = (EDGE_SAMPLES - 1) as f64;
                out.extend(
                    (0..EDGE_SAMPLES).map(|k| c.nurbs.eval(&(t0 + (t1 - t0) * k as f64 / n))),
                );
            }
        }
    }
    out
}

/// Feet (parameters) on `s` of the boundary samples `pts`, edge after edge, [`EDGE_SAMPLES`]
/// each, by local searches.
///
/// Each sample starts from a neighbour's foot ([`newton`]): the previous sample's along the
/// edge; an edge's first sample from the foot of whichever end of the previous edge lies
/// nearest to it (the loop's edges meet there). That search is taken when it ends within
/// `near` of the sample and not on or next to a collapsed border (a pole, where a parameter
/// gives the same point whatever its value; next to it, it moves the point very little):
/// there a surface of revolution is one-to-one, a sample that close to it has one foot
/// nearby, and both searches converge to it (to rounding). A foot on a seam is taken too: the
/// sample is then the seam's point, which both ends of the closed parameter give, and
/// [`parameter`] looks across the seam for either search's result alike. Otherwise the grid
/// search decides.
fn feet_of(
    s: &NurbsSurface<f64, 3>,
    pts: &[[f64; 3]],
    near: f64,
    closure: &Closure,
) -> Vec<[f64; 2]> {
    let (u0, u1, v0, v1) = s.hom.domain();
    let dom = [u0, u1, v0, v1];
    let pole = |q: &[f64; 2]| {
        (0..4).any(|k| {
            closure.degenerate[k] && (q[k / 2] - dom[k]).abs() <= 1e-6 * (dom[k | 1] - dom[k & 2])
        })
    };
    let mut foot = SurfaceFoot::new(s);
    let mut out: Vec<[f64; 2]> = Vec::with_capacity(pts.len());
    for (e, edge) in pts.chunks(EDGE_SAMPLES).enumerate() {
        // The previous edge's end (first or last sample) nearest to this edge's first sample.
        let mut warm = (e > 0).then(|| {
            let (a, b) = ((e - 1) * EDGE_SAMPLES, e * EDGE_SAMPLES - 1);
            let x = &edge[0];
            if dist(&pts[b], x) <= dist(&pts[a], x) {
                out[b]
            } else {
                out[a]
            }
        });
        for x in edge {
            let q = match warm.and_then(|w| newton(s, x, w, &dom)) {
                Some((q, e)) if e <= near && !pole(&q) => q,
                _ => foot.closest(x),
            };
            warm = Some(q);
            out.push(q);
        }
    }
    out
}

/// Gauss–Newton with full steps from `uv` towards the foot of `x` on `s` (kept in the domain
/// `dom`): at most 8 steps, stopped once a step moves less than 1e-14 of the domain; the result
/// and its distance to `x`, `None` where the normal equations are singular. Made for starts
/// next to the foot (the previous sample's), where it converges in a few steps; callers check
/// the distance.
fn newton(
    s: &NurbsSurface<f64, 3>,
    x: &[f64; 3],
    mut uv: [f64; 2],
    dom: &[f64; 4],
) -> Option<([f64; 2], f64)> {
    let tiny = 1e-14 * (dom[1] - dom[0]).max(dom[3] - dom[2]);
    for _ in 0..8 {
        let (p, su, sv) = point_d1(s, uv[0], uv[1]);
        let r = p.sub(x);
        let (a, b, c) = (dot(&su, &su), dot(&su, &sv), dot(&sv, &sv));
        let det = a * c - b * b;
        if det.is_nan() || det <= 1e-12 * a * c {
            return None;
        }
        let (g0, g1) = (dot(&r, &su), dot(&r, &sv));
        let step = [-(c * g0 - b * g1) / det, -(a * g1 - b * g0) / det];
        uv = [
            (uv[0] + step[0]).clamp(dom[0], dom[1]),
            (uv[1] + step[1]).clamp(dom[2], dom[3]),
        ];
        if step[0].abs().max(step[1].abs()) <= tiny {
            break;
        }
    }
    Some((uv, dist(&s.eval(&uv[0], &uv[1]), x)))
}

/// Parameter `d` of the foot `q` of `x` on `s`, closed in `d`: a local search stopped at one
/// end of the domain (the other side of the seam is the same curve) is tried again from the
/// other ([`newton`]), and its result taken where it lies nearer to `x`.
fn parameter(s: &NurbsSurface<f64, 3>, x: &[f64; 3], q: [f64; 2], d: usize) -> f64 {
    let (u0, u1, v0, v1) = s.hom.domain();
    let dom = [u0, u1, v0, v1];
    let (lo, hi) = (dom[2 * d], dom[2 * d + 1]);
    let w = 1e-9 * (hi - lo);
    let other = if (q[d] - lo).abs() <= w {
        hi
    } else if (hi - q[d]).abs() <= w {
        lo
    } else {
        return q[d];
    };
    let e = dist(&s.eval(&q[0], &q[1]), x);
    let mut start = q;
    start[d] = other;
    match newton(s, x, start, &dom) {
        Some((r, e2)) if e2 < e => r[d],
        _ => q[d],
    }
}

/// The parameter to start at, when the boundary's parameters `params` (in `[lo, hi]`) come
/// close to the seam from both sides and leave a gap of a tenth of the period elsewhere: the
/// middle of the widest gap.
fn new_seam(mut params: Vec<f64>, lo: f64, hi: f64) -> Option<f64> {
    let per = hi - lo;
    let on_seam = 1e-9 * per;
    params.retain(|x| x.is_finite() && *x - lo > on_seam && hi - *x > on_seam);
    params.sort_by(f64::total_cmp);
    let (first, last) = (*params.first()?, *params.last()?);
    let wrap = (first - lo) + (hi - last);
    if wrap > 0.02 * per {
        return None;
    }
    let (gap, at) = params
        .windows(2)
        .map(|w| (w[1] - w[0], 0.5 * (w[0] + w[1])))
        .max_by(|a, b| a.0.total_cmp(&b.0))?;
    (gap >= 0.1 * per).then_some(at)
}

/// `s` re-parametrized to start at `t` in direction `d`; `None` unless the weights of the two
/// seam rows differ by one common factor (then the second part is scaled by it: the same
/// rational surface).
fn reseamed(s: &NurbsSurface<f64, 3>, d: usize, t: f64) -> Option<NurbsSurface<f64, 3>> {
    let h = if d == 0 {
        s.hom.clone()
    } else {
        transposed(&s.hom)
    };
    let (nu, nv) = (h.nu(), h.nv());
    let ratios: Vec<f64> = (0..nv).map(|j| h.at(nu - 1, j).w / h.at(0, j).w).collect();
    let r = *ratios.first()?;
    if !(r > 0.0 && r.is_finite()) || ratios.iter().any(|x| (x - r).abs() > 1e-12 * r) {
        return None;
    }
    let moved = h.reseamed_u(&t, |p| p.scale(&r)).ok()?;
    let hom = if d == 0 { moved } else { transposed(&moved) };
    Some(NurbsSurface { hom })
}

/// The surface with `u` and `v` swapped.
fn transposed<P: crate::geom::Point>(s: &BSplineSurface<P>) -> BSplineSurface<P> {
    let (nu, nv) = (s.nu(), s.nv());
    BSplineSurface {
        ku: s.kv.clone(),
        kv: s.ku.clone(),
        net: (0..nv)
            .flat_map(|j| (0..nu).map(move |i| s.at(i, j).clone()))
            .collect(),
    }
}

#[cfg(test)]
mod tests;
