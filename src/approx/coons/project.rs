//! Step 3 (§3.3): projecting the Coons points onto the original surfaces.
//!
//! * Culling: a surface is considered when the box of its control net (which holds the
//!   surface, convex-hull property, positive weights) meets the box of all `a`, `b`.
//! * Its triangulation: a uniform grid of its parameter domain (`triangles_per_span` per
//!   knot span and direction, 8 to 256), every vertex with its `(u, v)`; triangles whose
//!   box misses the hull box are dropped (the paper clips them; whole triangles are kept).
//! * Each segment `a–b` against the triangles: decided by exact `orient3d` signs (the
//!   segment crosses the triangle's plane, and the line through `a`, `b` passes the three
//!   edges on one side); segments in a triangle's plane are not hits. Of several hits the
//!   one nearest `x` (`t` nearest ½) is kept. Where no triangle is hit, an edge within
//!   rounding (1e-10 of the coordinates' scale) of the segment counts: a segment through an
//!   edge exactly (the model's outer border) is otherwise decided by the rounding of the
//!   edge's end points.
//! * Eq. (8)/(9): the hit's barycentric coordinates give `(u, v)`; Newton on
//!   `S(u, v) = a + t (b − a)` (with `(u, v)` clamped to the domain) then puts the point on
//!   the exact surface (`y = S(u, v)`). Newton starts from the nearest hit, then from the
//!   other hits at the same place, then on every other surface with triangles around the
//!   hit (near a seam the root may lie on the neighbouring patch); where none converges,
//!   the barycentric `(u, v)` is kept (`refined = false`).
//!
//! Trimmed faces ([`super::trim`]): triangles that may meet the face's region are kept, and
//! a hit counts only if its final `(u, v)` lies in the region, so segments meet the faces,
//! not their surfaces' extensions.

use super::discrete::Grid;
use crate::geom::bvh::Bvh;
use crate::geom::{Point, cross, dot, norm};
use crate::model::Model;
use crate::predicates::orient3d;
use crate::scalar::Sign;
use crate::spline::NurbsSurface;
use crate::spline::project::point_d1;
use rayon::prelude::*;

/// The triangulated, culled original surfaces.
#[derive(Clone, Debug, Default)]
pub struct OriginalMesh {
    pub vertices: Vec<[f64; 3]>,
    pub uv: Vec<[f64; 2]>,
    /// Triangles: vertex indices and the surface (index into the model).
    pub triangles: Vec<([u32; 3], usize)>,
    /// Surfaces whose net box met the hull box.
    pub surfaces: Vec<usize>,
    /// The faces' trimmed regions.
    pub regions: super::trim::Regions,
    pub bvh: Bvh,
}

/// A projection found on an original surface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    pub surface: usize,
    pub uv: [f64; 2],
    /// Eq. (10): the point is `(1 − t) a + t b`.
    pub t: f64,
    /// `y = S(u, v)`.
    pub point: [f64; 3],
    /// Newton converged onto the exact surface (otherwise the barycentric `(u, v)`).
    pub refined: bool,
    /// `‖S(u, v) − ((1 − t) a + t b)‖` at the end.
    pub residual: f64,
}

fn net_box(s: &NurbsSurface<f64, 3>) -> Option<([f64; 3], [f64; 3])> {
    let (pts, _) = s.points_weights();
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in &pts {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    (lo.iter().chain(&hi).all(|c| c.is_finite())).then_some((lo, hi))
}

fn meets(a: &([f64; 3], [f64; 3]), b: &([f64; 3], [f64; 3])) -> bool {
    (0..3).all(|k| a.0[k] <= b.1[k] && b.0[k] <= a.1[k])
}

/// Cull the model's surfaces against `hull` and triangulate the rest (inside their faces'
/// trimmed regions).
pub fn triangulate(model: &Model, hull: ([f64; 3], [f64; 3]), per_span: usize) -> OriginalMesh {
    let mut m = OriginalMesh {
        regions: super::trim::regions(model),
        ..Default::default()
    };
    let mut boxes = Vec::new();
    for (si, surf) in model.surfaces.iter().enumerate() {
        let s = &surf.nurbs;
        if !net_box(s).is_some_and(|b| meets(&b, &hull)) {
            continue;
        }
        m.surfaces.push(si);
        let (u0, u1, v0, v1) = s.hom.domain();
        let su = s.hom.ku.interior_breaks().len() + 1;
        let sv = s.hom.kv.interior_breaks().len() + 1;
        let nu = (su * per_span).clamp(8, 256);
        let nv = (sv * per_span).clamp(8, 256);
        let base = m.vertices.len();
        for i in 0..=nu {
            let u = u0 + (u1 - u0) * i as f64 / nu as f64;
            for j in 0..=nv {
                let v = v0 + (v1 - v0) * j as f64 / nv as f64;
                m.vertices.push(s.eval(&u, &v));
                m.uv.push([u, v]);
            }
        }
        let id = |i: usize, j: usize| (base + i * (nv + 1) + j) as u32;
        for i in 0..nu {
            for j in 0..nv {
                for t in [
                    [id(i, j), id(i + 1, j), id(i + 1, j + 1)],
                    [id(i, j), id(i + 1, j + 1), id(i, j + 1)],
                ] {
                    let b = tri_box(&m.vertices, &t);
                    if b.0.iter().chain(&b.1).all(|c| c.is_finite())
                        && meets(&b, &hull)
                        && m.regions.touches(si, &t.map(|k| m.uv[k as usize]))
                    {
                        m.triangles.push((t, si));
                        boxes.push(b);
                    }
                }
            }
        }
    }
    m.bvh = Bvh::build(boxes);
    m
}

fn tri_box(v: &[[f64; 3]], t: &[u32; 3]) -> ([f64; 3], [f64; 3]) {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for &i in t {
        for k in 0..3 {
            lo[k] = lo[k].min(v[i as usize][k]);
            hi[k] = hi[k].max(v[i as usize][k]);
        }
    }
    (lo, hi)
}

fn det3(a: &[f64; 3], b: &[f64; 3], c: &[f64; 3]) -> f64 {
    dot(a, &cross(b, c))
}

/// Whether segment `ab` meets triangle `pqr` (exact signs), with `t` along `ab` and the
/// barycentric coordinates of the meeting point (computed in `f64` from the signed volumes).
pub fn segment_triangle(
    a: &[f64; 3],
    b: &[f64; 3],
    p: &[f64; 3],
    q: &[f64; 3],
    r: &[f64; 3],
) -> Option<(f64, [f64; 3])> {
    let sa = orient3d(p, q, r, a);
    let sb = orient3d(p, q, r, b);
    if sa == sb {
        return None; // both on one side, or the segment lies in the plane
    }
    let s_pq = orient3d(a, b, p, q);
    let s_qr = orient3d(a, b, q, r);
    let s_rp = orient3d(a, b, r, p);
    let signs = [s_pq, s_qr, s_rp];
    let pos = signs.contains(&Sign::Positive);
    let neg = signs.contains(&Sign::Negative);
    if pos == neg {
        return None; // edges on both sides, or all zero (degenerate)
    }
    let vol = |s: Sign, x: &[f64; 3], y: &[f64; 3]| {
        if s == Sign::Zero {
            0.0
        } else {
            det3(&b.sub(a), &x.sub(a), &y.sub(a)).abs()
        }
    };
    let (wr, wp, wq) = (vol(s_pq, p, q), vol(s_qr, q, r), vol(s_rp, r, p));
    let sum = wr + wp + wq;
    let bary = if sum > 0.0 {
        [wp / sum, wq / sum, wr / sum]
    } else {
        [1.0 / 3.0; 3]
    };
    let va = if sa == Sign::Zero {
        0.0
    } else {
        det3(&q.sub(p), &r.sub(p), &a.sub(p))
    };
    let vb = if sb == Sign::Zero {
        0.0
    } else {
        det3(&q.sub(p), &r.sub(p), &b.sub(p))
    };
    let t = if va == vb {
        0.5
    } else {
        (va / (va - vb)).clamp(0.0, 1.0)
    };
    Some((t, bary))
}

/// The closest points of segments `a b` and `p q`: their distance, the parameter along
/// `a b` and the parameter along `p q` (clamped, Ericson's method).
fn segment_segment(a: &[f64; 3], b: &[f64; 3], p: &[f64; 3], q: &[f64; 3]) -> (f64, f64, f64) {
    let (d1, d2, r) = (b.sub(a), q.sub(p), a.sub(p));
    let (aa, ee, f) = (dot(&d1, &d1), dot(&d2, &d2), dot(&d2, &r));
    let (mut s, mut t);
    if aa <= 0.0 && ee <= 0.0 {
        return (norm(&r), 0.0, 0.0);
    }
    if aa <= 0.0 {
        s = 0.0;
        t = (f / ee).clamp(0.0, 1.0);
    } else {
        let c = dot(&d1, &r);
        if ee <= 0.0 {
            t = 0.0;
            s = (-c / aa).clamp(0.0, 1.0);
        } else {
            let bb = dot(&d1, &d2);
            let den = aa * ee - bb * bb;
            s = if den > 0.0 {
                ((bb * f - c * ee) / den).clamp(0.0, 1.0)
            } else {
                0.0
            };
            t = (bb * s + f) / ee;
            if t < 0.0 {
                t = 0.0;
                s = (-c / aa).clamp(0.0, 1.0);
            } else if t > 1.0 {
                t = 1.0;
                s = ((bb - c) / aa).clamp(0.0, 1.0);
            }
        }
    }
    let x = a.lerp(b, &s);
    let y = p.lerp(q, &t);
    (norm(&x.sub(&y)), s, t)
}

/// Newton on `S(u, v) − (a + t (b − a)) = 0` from `(uv, t)`, `(u, v)` clamped to the
/// domain; `None` when it does not converge to a point of the segment.
pub fn refine(
    s: &NurbsSurface<f64, 3>,
    a: &[f64; 3],
    b: &[f64; 3],
    uv: [f64; 2],
    t: f64,
) -> Option<([f64; 2], f64, [f64; 3], f64)> {
    let (u0, u1, v0, v1) = s.hom.domain();
    let dir = b.sub(a);
    let scale = norm(&dir).max(norm(a)).max(1.0);
    let (mut u, mut v, mut t) = (uv[0], uv[1], t);
    for _ in 0..30 {
        let (p, su, sv) = point_d1(s, u, v);
        let f = p.sub(&a.add(&dir.scale(&t)));
        let res = norm(&f);
        if !res.is_finite() {
            return None;
        }
        if res <= 1e-13 * scale {
            return (-1e-9..=1.0 + 1e-9)
                .contains(&t)
                .then_some(([u, v], t, p, res));
        }
        let nd = dir.scale(&-1.0);
        let det = det3(&su, &sv, &nd);
        if det == 0.0 || !det.is_finite() {
            return None;
        }
        // Cramer: [su sv nd] δ = −f.
        let g = f.scale(&-1.0);
        let du = det3(&g, &sv, &nd) / det;
        let dv = det3(&su, &g, &nd) / det;
        let dt = det3(&su, &sv, &g) / det;
        // Clamped to the domain: a root on its border (a seam between patches) is still
        // reached; a root beyond it leaves a residual and is refused below.
        let (un, vn) = ((u + du).clamp(u0, u1), (v + dv).clamp(v0, v1));
        if !(un.is_finite() && vn.is_finite() && dt.is_finite()) {
            return None;
        }
        let moved = (un - u).abs() + (vn - v).abs();
        (u, v, t) = (un, vn, t + dt);
        if moved <= 1e-15 * ((u1 - u0) + (v1 - v0)) {
            let p = s.eval(&u, &v);
            let res = norm(&p.sub(&a.add(&dir.scale(&t))));
            let on_segment = (-1e-9..=1.0 + 1e-9).contains(&t);
            return (res <= 1e-9 * scale && on_segment).then_some(([u, v], t, p, res));
        }
    }
    None
}

/// Project every point of the grid: the hit nearest `x` on segment `a–b`, or `None`.
pub fn project_grid(
    model: &Model,
    mesh: &OriginalMesh,
    a: &Grid<[f64; 3]>,
    b: &Grid<[f64; 3]>,
) -> Grid<Option<Hit>> {
    let data: Vec<Option<Hit>> = (0..a.data.len())
        .into_par_iter()
        .map(|k| project_one(model, mesh, &a.data[k], &b.data[k]))
        .collect();
    Grid {
        m: a.m,
        n: a.n,
        data,
    }
}

fn project_one(model: &Model, mesh: &OriginalMesh, a: &[f64; 3], b: &[f64; 3]) -> Option<Hit> {
    let lo = std::array::from_fn(|k| a[k].min(b[k]));
    let hi = std::array::from_fn(|k| a[k].max(b[k]));
    let mut found: Vec<(f64, usize, [f64; 3])> = Vec::new();
    mesh.bvh.query(&lo, &hi, &mut |ti| {
        let (t, _) = mesh.triangles[ti];
        let [p, q, r] = t.map(|i| &mesh.vertices[i as usize]);
        if let Some((tt, bary)) = segment_triangle(a, b, p, q, r) {
            found.push((tt, ti, bary));
        }
    });
    if found.is_empty() {
        // A segment through a triangle edge exactly (the model's outer border, a patch
        // border) is decided by the rounding of the edge's end points: take the edges within
        // rounding of the segment as hits; Newton below must still put the point on the
        // surface and on the segment.
        let graze = 1e-10 * (norm(a) + norm(b) + norm(&b.sub(a))).max(1e-300);
        let (glo, ghi) = (lo.map(|x: f64| x - graze), hi.map(|x: f64| x + graze));
        mesh.bvh.query(&glo, &ghi, &mut |ti| {
            let (t, _) = mesh.triangles[ti];
            let v = t.map(|i| mesh.vertices[i as usize]);
            for e in 0..3 {
                let (p, q) = (&v[e], &v[(e + 1) % 3]);
                let (d, s, w) = segment_segment(a, b, p, q);
                if d <= graze {
                    let mut bary = [0.0; 3];
                    bary[e] = 1.0 - w;
                    bary[(e + 1) % 3] = w;
                    found.push((s, ti, bary));
                    break;
                }
            }
        });
    }
    found.sort_by(|x, y| {
        (x.0 - 0.5)
            .abs()
            .total_cmp(&(y.0 - 0.5).abs())
            .then(x.1.cmp(&y.1))
    });
    let uv_of = |ti: usize, bary: &[f64; 3]| {
        let uvs = mesh.triangles[ti].0.map(|i| mesh.uv[i as usize]);
        [
            bary[0] * uvs[0][0] + bary[1] * uvs[1][0] + bary[2] * uvs[2][0],
            bary[0] * uvs[0][1] + bary[1] * uvs[1][1] + bary[2] * uvs[2][1],
        ]
    };
    // Hits outside their face's trimmed region do not count.
    found.retain(|(_, ti, bary)| {
        mesh.regions
            .contains(mesh.triangles[*ti].1, &uv_of(*ti, bary))
    });
    let &(t_best, _, _) = found.first()?;
    // Newton converged, but outside the face: the segment meets the surface only where the
    // face is trimmed away.
    let mut outside = false;
    // Newton from the nearest hit; where it leaves its surface's domain (a seam between
    // patches), from the hits at (almost) the same place on the other triangles.
    for (t, ti, bary) in found
        .iter()
        .take_while(|h| (h.0 - t_best).abs() <= 1e-3)
        .take(8)
    {
        let si = mesh.triangles[*ti].1;
        let s = &model.surfaces[si].nurbs;
        if let Some((uv, t, point, residual)) = refine(s, a, b, uv_of(*ti, bary), *t) {
            if !mesh.regions.contains(si, &uv) {
                outside = true;
                continue;
            }
            return Some(Hit {
                surface: si,
                uv,
                t,
                point,
                refined: true,
                residual,
            });
        }
    }
    let (t, ti, bary) = found[0];
    let si = mesh.triangles[ti].1;
    let uv = uv_of(ti, &bary);
    // The triangulation's chord put the hit on one patch, the surface's own root may lie on
    // a neighbour: Newton on every other surface with triangles around the hit, from the
    // nearest vertex.
    let tri = mesh.triangles[ti].0.map(|i| mesh.vertices[i as usize]);
    let hit = a.lerp(b, &t);
    let reach = tri
        .iter()
        .map(|q| crate::geom::dist(q, &hit))
        .fold(0.0, f64::max);
    let mut near: Vec<(f64, usize, [f64; 2])> = Vec::new();
    let lo = hit.map(|c| c - reach);
    let hi = hit.map(|c| c + reach);
    mesh.bvh.query(&lo, &hi, &mut |tj| {
        let (tv, sj) = mesh.triangles[tj];
        if sj == si {
            return;
        }
        for &k in &tv {
            let d = crate::geom::dist(&mesh.vertices[k as usize], &hit);
            match near.iter_mut().find(|n| n.1 == sj) {
                Some(n) if d < n.0 => *n = (d, sj, mesh.uv[k as usize]),
                Some(_) => {}
                None => near.push((d, sj, mesh.uv[k as usize])),
            }
        }
    });
    near.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
    for (_, sj, uv0) in near {
        if let Some((uv, t, point, residual)) = refine(&model.surfaces[sj].nurbs, a, b, uv0, t) {
            if !mesh.regions.contains(sj, &uv) {
                outside = true;
                continue;
            }
            return Some(Hit {
                surface: sj,
                uv,
                t,
                point,
                refined: true,
                residual,
            });
        }
    }
    if outside {
        return None;
    }
    let point = model.surfaces[si].nurbs.eval(&uv[0], &uv[1]);
    let residual = norm(&point.sub(&a.lerp(b, &t)));
    Some(Hit {
        surface: si,
        uv,
        t,
        point,
        refined: false,
        residual,
    })
}
