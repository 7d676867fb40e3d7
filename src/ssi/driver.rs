//! The many-surface driver (paper §4: "the driver calls the intersection operator with
//! successive pairs of surfaces until all possible surface pairs are processed").
//!
//! Pairs are culled by the bounding boxes of their control nets (a NURBS surface with positive
//! weights lies in the convex hull of its control points, so disjoint boxes prove the faces
//! disjoint), then run in parallel; results are collected in pair order, and every pair is
//! computed in a canonical surface order, so the output is the same for every thread count
//! and for `(A, B)` and `(B, A)`.

use super::mesh::intersect_meshes;
use super::pair::intersect_surfaces;
use super::report::{PairOut, SsiResult, Summary};
use super::trims::{SAMPLES_PER_CURVE, TrimRegion, clip};
use super::{SsiError, SsiParams};
use crate::geom::Aabb;
use crate::model::{Model, Triangulation};
use crate::spline::NurbsSurface;
use rayon::prelude::*;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::{Duration, Instant};

/// A total order on surfaces by the bits of their knots, weights and control points.
fn canonical_key(s: &NurbsSurface<f64, 3>) -> Vec<u64> {
    let h = &s.hom;
    let mut k: Vec<u64> = vec![
        h.ku.degree() as u64,
        h.kv.degree() as u64,
        h.ku.n_ctrl() as u64,
        h.kv.n_ctrl() as u64,
    ];
    k.extend(h.ku.knots().iter().chain(h.kv.knots()).map(|x| x.to_bits()));
    for p in &h.net {
        k.extend(p.wp.iter().map(|x| x.to_bits()));
        k.push(p.w.to_bits());
    }
    k
}

fn swap_sides(mut p: PairOut) -> PairOut {
    std::mem::swap(&mut p.a, &mut p.b);
    for b in &mut p.branches {
        std::mem::swap(&mut b.uv_a, &mut b.uv_b);
        std::mem::swap(&mut b.dist_a_max, &mut b.dist_b_max);
        if let Some(f) = &mut b.fit {
            std::mem::swap(&mut f.control_points_uv_a, &mut f.control_points_uv_b);
        }
    }
    for t in &mut p.touch_points {
        std::mem::swap(&mut t.uv_a, &mut t.uv_b);
        std::mem::swap(&mut t.dist_a, &mut t.dist_b);
    }
    if let Some(c) = &mut p.coverage {
        std::mem::swap(&mut c.boxes_a, &mut c.boxes_b);
        for r in &mut c.uncertified_regions {
            std::mem::swap(&mut r.uv_a, &mut r.uv_b);
        }
    }
    for c in &mut p.contacts {
        std::mem::swap(&mut c.triangle_a, &mut c.triangle_b);
    }
    let s = &mut p.stats;
    std::mem::swap(&mut s.triangles_a, &mut s.triangles_b);
    std::mem::swap(&mut s.unresolved_cells_a, &mut s.unresolved_cells_b);
    p
}

/// Intersect two surfaces in their canonical order, reporting in the caller's order.
pub fn intersect_pair_canonical(
    sa: &NurbsSurface<f64, 3>,
    sb: &NurbsSurface<f64, 3>,
    ids: (usize, usize),
    prm: &SsiParams,
    deadline: Option<Instant>,
) -> Result<PairOut, SsiError> {
    if canonical_key(sa) <= canonical_key(sb) {
        intersect_surfaces(sa, sb, ids, prm, deadline)
    } else {
        intersect_surfaces(sb, sa, (ids.1, ids.0), prm, deadline).map(swap_sides)
    }
}

fn net_box(s: &NurbsSurface<f64, 3>) -> Option<Aabb<f64, 3>> {
    let pts = s.points_weights().0;
    Aabb::of_points(pts.iter())
}

enum Work<'a> {
    Surfaces(&'a NurbsSurface<f64, 3>, &'a NurbsSurface<f64, 3>),
    Meshes(&'a Triangulation, &'a Triangulation),
}

/// Intersect all pairs of faces of `a` (when `b` is `None`) or every face of `a` with every
/// face of `b`. Models without faces are intersected as triangulations (mesh-only mode).
/// `progress(done, total)` is called as pairs finish (from worker threads).
pub fn intersect_models(
    a: &Model,
    b: Option<&Model>,
    prm: &SsiParams,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<SsiResult, SsiError> {
    prm.validate()?;
    let t0 = Instant::now();
    let deadline = prm.time_limit.map(|s| t0 + Duration::from_secs_f64(s));
    let meshes = a.surfaces.is_empty() && b.is_none_or(|m| m.surfaces.is_empty());
    let (na, nb) = if meshes {
        (
            a.triangulations.len(),
            b.map_or(0, |m| m.triangulations.len()),
        )
    } else {
        (a.surfaces.len(), b.map_or(0, |m| m.surfaces.len()))
    };
    if na == 0 || (b.is_some() && nb == 0) {
        return Err(SsiError::Empty);
    }
    let mut jobs: Vec<(usize, usize)> = Vec::new();
    match b {
        None => (0..na).for_each(|i| (i + 1..na).for_each(|j| jobs.push((i, j)))),
        Some(_) => (0..na).for_each(|i| (0..nb).for_each(|j| jobs.push((i, j)))),
    }
    let considered = jobs.len();
    let other = b.unwrap_or(a);
    let work = |(i, j): (usize, usize)| -> Work {
        if meshes {
            Work::Meshes(&a.triangulations[i], &other.triangulations[j])
        } else {
            Work::Surfaces(&a.surfaces[i].nurbs, &other.surfaces[j].nurbs)
        }
    };
    let bounds_overlap = |w: &Work| match w {
        Work::Surfaces(x, y) => match (net_box(x), net_box(y)) {
            (Some(p), Some(q)) => p.overlaps(&q),
            _ => true,
        },
        Work::Meshes(x, y) => match (
            Aabb::of_points(x.vertices.iter()),
            Aabb::of_points(y.vertices.iter()),
        ) {
            (Some(p), Some(q)) => p.overlaps(&q),
            _ => false,
        },
    };
    jobs.retain(|&j| bounds_overlap(&work(j)));
    let culled = considered - jobs.len();
    let done = AtomicUsize::new(0);
    let total = jobs.len();
    let results: Vec<Option<Result<PairOut, SsiError>>> = jobs
        .par_iter()
        .map(|&(i, j)| {
            if deadline.is_some_and(|d| Instant::now() > d) {
                return None;
            }
            let r = match work((i, j)) {
                Work::Surfaces(x, y) => intersect_pair_canonical(x, y, (i, j), prm, deadline),
                Work::Meshes(x, y) => intersect_meshes(x, y, (i, j)),
            };
            progress(done.fetch_add(1, Ordering::Relaxed) + 1, total);
            Some(r)
        })
        .collect();
    let mut pairs = Vec::new();
    let mut not_run = 0;
    for r in results {
        match r {
            None => not_run += 1,
            Some(r) => pairs.push(r?),
        }
    }
    let mut trimmed_faces = 0;
    if prm.respect_trims && !meshes {
        let ra: Vec<_> = a.surfaces.iter().map(TrimRegion::of).collect();
        let rb: Vec<_> = other.surfaces.iter().map(TrimRegion::of).collect();
        trimmed_faces = ra.iter().filter(|r| r.is_some()).count();
        for p in &mut pairs {
            let (x, y) = (ra[p.a].as_ref(), rb[p.b].as_ref());
            if x.is_some() || y.is_some() {
                p.branches = p.branches.iter().flat_map(|b| clip(b, x, y)).collect();
            }
        }
    }
    let partial = not_run > 0 || pairs.iter().any(|p| !p.complete);
    let branches: Vec<_> = pairs.iter().flat_map(|p| &p.branches).collect();
    let dist_max = branches
        .iter()
        .map(|b| b.dist_a_max.max(b.dist_b_max))
        .fold(0.0, f64::max);
    let points = branches.iter().map(|b| b.points.len()).sum();
    let points_curve_uncertified: usize = branches.iter().map(|b| b.curve_uncertified_points).sum();
    let dist_curve_max = (points_curve_uncertified == 0).then(|| {
        branches
            .iter()
            .filter_map(|b| b.dist_curve_max)
            .fold(0.0, f64::max)
    });
    let all_points_within_tol = dist_curve_max.is_some_and(|d| d <= prm.tol);
    let uncertified: usize = pairs
        .iter()
        .filter_map(|p| p.coverage.as_ref())
        .map(|c| c.uncertified)
        .sum();
    let no_missed_branches = !meshes
        && pairs.iter().all(|p| {
            p.coincident.is_none() && p.coverage.as_ref().is_some_and(|c| c.no_missed_branches)
        });
    let coincident_pairs = pairs.iter().filter(|p| p.coincident.is_some()).count();
    let matched = pairs
        .iter()
        .filter_map(|p| p.coverage.as_ref())
        .map(|c| c.match_distance)
        .fold(0.0, f64::max);
    let mut certificate = vec![
        if meshes {
            "every point lies within the stated distance of both triangulations (rigorous bound on the constructed crossing point)".to_string()
        } else {
            "every point's distance to each surface at its own parameters is bounded rigorously (outward-rounded interval evaluation, exact rational fallback): dist_a_max, dist_b_max, dist_max".to_string()
        },
        if meshes {
            "distance to the curve (mesh mode): the same bound, to the exact crossing of the triangulations".to_string()
        } else if points_curve_uncertified == 0 {
            "every point's distance to the intersection curve is bounded rigorously: a true common point of both faces (parameters in both domains) lies within curve_radius, the unique zero in its parameter box (Krawczyk's test on S_A(u,v) = S_B(s,t) plus a plane across the curve, interval enclosures over the box; hypotheses: continuous surfaces, weights not vanishing, both proven or refused)".to_string()
        } else {
            format!("distance to the intersection curve: proven for every point but {points_curve_uncertified}, which are uncertified (listed per branch with the reason: tangency, singular points, no contraction of the Krawczyk box); dist_curve_max is null")
        },
        "branch topology comes from exact signs with symbolic perturbation; every segment is used once (checked)".to_string(),
        if meshes {
            "mesh mode: the curves are the exact intersection of the triangulations; no coverage certificate".to_string()
        } else if no_missed_branches {
            format!("coverage: every branch of the true intersection (closed loop, open arc, touching point) comes within {matched:.3e} of the output, proven: every parameter-box pair is free (disjoint control-point boxes), within that distance of the output, or transversal (separated normal cones) with every border crossing within that distance of the output")
        } else if uncertified == 0 && coincident_pairs > 0 {
            "coverage: not applicable to coincident face pairs (below); every other pair is certified".to_string()
        } else {
            format!("coverage: NOT certified: {uncertified} parameter-box pairs undecided (listed per pair with the reason): a branch could be missing there")
        },
        "chord midpoints within tol of the true curve are measured after refinement (evidence, not proof)".to_string(),
    ];
    if prm.respect_trims {
        certificate.push(format!(
            "branches clipped to trim loops ({trimmed_faces} trimmed faces), polygonized with {SAMPLES_PER_CURVE} samples per trim curve: exact decisions against the polygon, evidence against the true trim curves"
        ));
    }
    if coincident_pairs > 0 {
        certificate.push(format!(
            "COINCIDENT: {coincident_pairs} face pairs are proven to coincide (identical, or all control points in one plane, exact): their intersection is a region, not curves; listed per pair, not certified as curves"
        ));
    }
    if partial {
        certificate.push(format!(
            "PARTIAL: stopped by the time limit; {not_run} pairs not run"
        ));
    }
    let summary = Summary {
        tol: prm.tol,
        faces_a: na,
        faces_b: nb,
        pairs_considered: considered,
        pairs_culled_by_bounds: culled,
        pairs_intersected: pairs.len(),
        pairs_with_branches: pairs.iter().filter(|p| !p.branches.is_empty()).count(),
        branches: branches.len(),
        closed_branches: branches.iter().filter(|b| b.closed).count(),
        points,
        dist_max,
        dist_curve_max,
        points_curve_uncertified,
        all_points_within_tol,
        pairs_not_run: not_run,
        no_missed_branches,
        uncertified_box_pairs: uncertified,
        coincident_pairs,
        partial,
        certified: all_points_within_tol && !partial && (meshes || no_missed_branches),
        seconds: t0.elapsed().as_secs_f64(),
        certificate,
    };
    Ok(SsiResult { pairs, summary })
}
