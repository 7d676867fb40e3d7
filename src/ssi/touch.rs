//! Tangential contacts: where the two surfaces touch without crossing, the triangulations may
//! miss each other entirely (a convex surface's chords lie off the surface). Triangle pairs
//! whose boxes, grown by the flatness tolerance, overlap and whose normals are within the
//! tangent angle seed a search for tangential points on the true surfaces
//! ([`tangential_point_until`]): touching points, and the singular points where intersection curves
//! cross (the Steinmetz curve's branch points). Triangles around such a point form its
//! *singular region*: every mesh crossing point named by a feature of a region triangle is
//! merged into one Point for it, so the tracer ends curves there (a branch point when more
//! than two curve ends meet) instead of following the perturbed mesh topology through it.
//! Each tangential point's kind is then proven or left uncertified by [`classify`]
//! ([`super::singular`]): the search itself decides nothing.

use super::branch::PairGeometry;
use super::coverage::Suspects;
use super::pair::tri;
use super::pair_meshes::unit_normals;
use super::refine::{RefineParams, RefineStatus, Refined, point_d1, tangential_point_until};
use super::report::TouchOut;
use super::singular::classify;
use super::triangulate::SurfaceMesh;
use crate::geom::tri_tree::{TriTree, triangle_box};
use crate::geom::{cross, dist, norm};
use crate::spline::NurbsSurface;
use rustc_hash::FxHashSet as HashSet;

/// Most seeds tried per pair.
pub const MAX_SEEDS: usize = 256;

fn grown_tree(m: &SurfaceMesh, d: f64) -> TriTree {
    let boxes: Vec<_> = (0..m.triangles.len() as u32)
        .map(|t| {
            let (lo, hi) = triangle_box(&tri(m, t));
            let g = |x: f32, s: f64| {
                let y = (x as f64 + s) as f32;
                if s < 0.0 { y.next_down() } else { y.next_up() }
            };
            (lo.map(|x| g(x, -d)), hi.map(|x| g(x, d)))
        })
        .collect();
    TriTree::build(&boxes)
}

fn centroid_uv(m: &SurfaceMesh, t: u32) -> [f64; 2] {
    let v = m.triangles[t as usize];
    std::array::from_fn(|c| {
        (m.uv[v[0] as usize][c] + m.uv[v[1] as usize][c] + m.uv[v[2] as usize][c]) / 3.0
    })
}

/// Tangential points of the pair (touching points and singular points of the intersection),
/// one per `flatness` neighbourhood, found from every seed (up to [`MAX_SEEDS`], spread
/// evenly) by [`tangential_point_until`].
pub fn tangential_points(
    g: &PairGeometry,
    flatness: f64,
    tangent_angle_deg: f64,
    prm: &RefineParams,
) -> Vec<Refined> {
    tangential_points_in(g, flatness, tangent_angle_deg, prm, None)
}

/// [`tangential_points`] seeded only from triangle pairs meeting the `suspects` (the
/// parameter boxes where a tangential point may lie, `coverage::apart`) when those are known:
/// a scheduling choice, the search proposes points and decides nothing.
pub(crate) fn tangential_points_in(
    g: &PairGeometry,
    flatness: f64,
    tangent_angle_deg: f64,
    prm: &RefineParams,
    suspects: Option<&Suspects>,
) -> Vec<Refined> {
    let cos_t = tangent_angle_deg.to_radians().cos();
    let mut pairs = grown_tree(g.ma, flatness).overlapping_pairs(&grown_tree(g.mb, flatness));
    if let Some(s) = suspects {
        pairs.retain(|&(ta, tb)| s.meets(&g.ma.uv_box(ta), &g.mb.uv_box(tb)));
    }
    let mut seeds: HashSet<(u32, u32)> = HashSet::default();
    let mut seed_tris = Vec::new();
    let (ua, ub) = (unit_normals(g.ma), unit_normals(g.mb));
    for &(ta, tb) in &pairs {
        if let (Some(x), Some(y)) = (ua[ta as usize], ub[tb as usize])
            && (x[0] * y[0] + x[1] * y[1] + x[2] * y[2]).abs() > cos_t
        {
            let key = (g.ma.tri_cell[ta as usize], g.mb.tri_cell[tb as usize]);
            if seeds.insert(key) {
                seed_tris.push((ta, tb));
            }
        }
    }
    let step = seed_tris.len().div_ceil(MAX_SEEDS).max(1);
    let mut out: Vec<Refined> = Vec::new();
    // A run whose iterate comes within half the merge distance of a point already found, or
    // of where an earlier run stalled short of a root, is stopped: it would end as a
    // duplicate of that point or stall there too (near a pole every seed of the
    // neighbourhood runs to the pole, a local minimum of the residual where the surfaces do
    // not touch).
    let mut stalled: Vec<[f64; 3]> = Vec::new();
    let mut try_seed = |uv_a: [f64; 2], uv_b: [f64; 2], out: &mut Vec<Refined>| {
        let known = |m: &[f64; 3]| {
            out.iter()
                .map(|t| &t.xyz)
                .chain(&stalled)
                .any(|x| dist(x, m) <= 0.5 * flatness)
        };
        let (r, stuck) = tangential_point_until(g.sa, g.sb, (uv_a, uv_b), prm, known);
        if r.status == RefineStatus::Tangential {
            if !out.iter().any(|t| dist(&t.xyz, &r.xyz) <= flatness) {
                out.push(r);
            }
        } else if stuck {
            stalled.push(r.xyz);
        }
    };
    for &(ta, tb) in seed_tris.iter().step_by(step) {
        try_seed(centroid_uv(g.ma, ta), centroid_uv(g.mb, tb), &mut out);
    }
    // Where a tangential point is a mesh vertex (on knot lines, as at a circle's joints, or the
    // apex of a dome meshed by a few facets), the facets around it can all lean by far more
    // than the angle while the surface normal at the vertex is exactly parallel: pairs whose
    // *vertex* normals (true surface normals) are within the angle seed the search too, from
    // those vertices (a budget of their own). Vertex normals are computed on demand, once
    // each; no facet angle filters them (a coarse facet says nothing of its vertices).
    let (mut na, mut nb) = (vec![None; g.ma.uv.len()], vec![None; g.mb.uv.len()]);
    let mut vseeds: HashSet<(u32, u32)> = HashSet::default();
    let mut vertex_pairs = Vec::new();
    for &(ta, tb) in &pairs {
        let key = (g.ma.tri_cell[ta as usize], g.mb.tri_cell[tb as usize]);
        if seeds.contains(&key) || vseeds.contains(&key) {
            continue;
        }
        let (va, vb) = (g.ma.triangles[ta as usize], g.mb.triangles[tb as usize]);
        // The most nearly parallel vertex pair; of equally parallel ones (a plane's
        // vertices), the closest.
        let mut best: Option<(f64, f64, u32, u32)> = None;
        for &i in &va {
            let p = *na[i as usize].get_or_insert_with(|| vertex_normal(g.sa, g.ma.uv[i as usize]));
            for &j in &vb {
                let q =
                    *nb[j as usize].get_or_insert_with(|| vertex_normal(g.sb, g.mb.uv[j as usize]));
                if let (Some(p), Some(q)) = (p, q) {
                    let c = (p[0] * q[0] + p[1] * q[1] + p[2] * q[2]).abs();
                    if best.is_some_and(|b| c < b.0) {
                        continue;
                    }
                    let d = dist(&g.ma.vertices[i as usize], &g.mb.vertices[j as usize]);
                    if best.is_none_or(|b| c > b.0 || d < b.1) {
                        best = Some((c, d, i, j));
                    }
                }
            }
        }
        if let Some((c, _, i, j)) = best
            && c > cos_t
        {
            vseeds.insert(key);
            vertex_pairs.push((g.ma.uv[i as usize], g.mb.uv[j as usize]));
        }
    }
    let step = vertex_pairs.len().div_ceil(MAX_SEEDS).max(1);
    for &(uv_a, uv_b) in vertex_pairs.iter().step_by(step) {
        try_seed(uv_a, uv_b, &mut out);
    }
    out
}

/// Unit surface normal at `uv` (`None` where the parametrisation degenerates).
fn vertex_normal(s: &NurbsSurface<f64, 3>, uv: [f64; 2]) -> Option<[f64; 3]> {
    let (_, su, sv) = point_d1(s, uv[0], uv[1]);
    let n = cross(&su, &sv);
    let l = norm(&n);
    (l > 0.0 && l.is_finite()).then(|| n.map(|c| c / l))
}

/// Triangles of `m` whose box, grown by `r`, holds `x`: the singular region around a
/// tangential point.
pub fn region(m: &SurfaceMesh, x: &[f64; 3], r: f64) -> Vec<u32> {
    (0..m.triangles.len() as u32)
        .filter(|&t| {
            let p = tri(m, t);
            (0..3).all(|k| {
                let lo = p.iter().map(|q| q[k]).fold(f64::INFINITY, f64::min);
                let hi = p.iter().map(|q| q[k]).fold(f64::NEG_INFINITY, f64::max);
                lo - r <= x[k] && x[k] <= hi + r
            })
        })
        .collect()
}

/// The touching point record of a tangential point, with the proof of its kind
/// ([`classify`]: a contact is claimed only within `tol`).
pub fn touch_out(g: &PairGeometry, r: &Refined, branch_ends: usize, tol: f64) -> TouchOut {
    TouchOut {
        singular: Some(classify(g.sa, g.sb, &r.uv_a, &r.uv_b, tol)),
        point: r.xyz,
        uv_a: Some(r.uv_a),
        uv_b: Some(r.uv_b),
        status: Some(r.status),
        dist_a: g.ea.distance_bound(&r.xyz, &r.uv_a),
        dist_b: g.eb.distance_bound(&r.xyz, &r.uv_b),
        branch_ends,
    }
}
