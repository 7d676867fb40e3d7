//! The many-surface driver (paper §4: "the driver calls the intersection operator with
//! successive pairs of surfaces until all possible surface pairs are processed").
//!
//! Pairs are culled by the bounding boxes of their control nets (a NURBS surface with positive
//! weights lies in the convex hull of its control points, so disjoint boxes prove the faces
//! disjoint), then run in parallel; results are collected in pair order, and every pair is
//! computed in a canonical surface order, so the output is the same for every thread count
//! and for `(A, B)` and `(B, A)`.

mod canonical;
mod cull;

pub use canonical::intersect_pair_canonical;

use super::brep_faces::Faces;
use super::coincide::CoincidenceKind;
use super::mesh::intersect_meshes;
use super::report::{PairOut, SingularKind, SsiResult, Summary};
use super::trims::SAMPLES_PER_CURVE;
use super::{SsiError, SsiParams};
use crate::geom::Aabb;
use crate::model::{Model, Triangulation};
use crate::spline::NurbsSurface;
use canonical::pair_canonical;
use cull::{net_box, overlapping_pairs};
use rayon::prelude::*;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::{Duration, Instant};

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
    for m in std::iter::once(a).chain(b) {
        m.validate().map_err(SsiError::Input)?;
        m.check_coordinate_range()
            .map_err(|e| SsiError::Input(e.to_string()))?;
    }
    let other = b.unwrap_or(a);
    let work = |(i, j): (usize, usize)| -> Work {
        if meshes {
            Work::Meshes(&a.triangulations[i], &other.triangulations[j])
        } else {
            Work::Surfaces(&a.surfaces[i].nurbs, &other.surfaces[j].nurbs)
        }
    };
    // Boxes once per face (control nets: convex hull; meshes: vertices), then a sweep along x
    // lists the pairs whose boxes overlap, without the O(n²) list of all pairs.
    let boxes = |m: &Model, n: usize| -> Vec<Option<Aabb<f64, 3>>> {
        (0..n)
            .map(|i| {
                if meshes {
                    Aabb::of_points(m.triangulations[i].vertices.iter())
                } else {
                    net_box(&m.surfaces[i].nurbs)
                }
            })
            .collect()
    };
    let ba = boxes(a, na);
    let bb = match b {
        Some(m) => boxes(m, nb),
        None => Vec::new(),
    };
    let considered = match b {
        None => na * na.saturating_sub(1) / 2,
        Some(_) => na * nb,
    };
    let mut jobs = overlapping_pairs(&ba, b.map(|_| bb.as_slice()), meshes);
    jobs.sort_unstable();
    let culled = considered - jobs.len();
    let faces = (prm.respect_trims && !meshes).then(|| Faces::new(a, b, prm.tol));
    let done = AtomicUsize::new(0);
    let total = jobs.len();
    type Tubes = Option<std::sync::Arc<super::shared_tubes::SharedTubes>>;
    let results: Vec<Option<(Result<PairOut, SsiError>, Tubes)>> = jobs
        .par_iter()
        .map(|&(i, j)| {
            if prm.control.stop(deadline) {
                return None;
            }
            let mut tubes = None;
            let r = match work((i, j)) {
                Work::Surfaces(x, y) => {
                    let outside = faces.as_ref().and_then(|f| f.outside_for(i, j));
                    tubes = faces.as_ref().and_then(|f| f.tubes_for(i, j));
                    let restrict = faces
                        .as_ref()
                        .and_then(|f| f.restrict_for(i, j, tubes.clone()));
                    if outside.is_some() || tubes.is_some() {
                        let mut p = prm.clone();
                        // Trimmed faces: branches are cut at their last point inside, which
                        // with cubic pieces could leave a whole piece short of the trim
                        // boundary; such pairs are output in chords.
                        if outside.is_some() {
                            p.pieces = super::Pieces::Chords;
                        }
                        p.coverage_outside = outside;
                        p.coverage_restrict = restrict;
                        p.shared_tubes = tubes.clone();
                        pair_canonical(x, y, (i, j), &p, deadline)
                    } else {
                        pair_canonical(x, y, (i, j), prm, deadline)
                    }
                }
                Work::Meshes(x, y) => intersect_meshes(x, y, (i, j)),
            };
            progress(done.fetch_add(1, Ordering::Relaxed) + 1, total);
            Some((r, tubes))
        })
        .collect();
    let mut pairs = Vec::new();
    let mut pair_tubes = Vec::new();
    let mut not_run = 0;
    for r in results {
        match r {
            None => not_run += 1,
            Some((r, t)) => {
                pairs.push(r?);
                pair_tubes.push(t);
            }
        }
    }
    let mut trimmed_faces = 0;
    let mut faces_not_outlined = Vec::new();
    let mut faces_ambiguous = Vec::new();
    if let Some(faces) = faces {
        trimmed_faces = faces.trimmed;
        for (p, t) in pairs.iter_mut().zip(&pair_tubes) {
            faces.apply(p, t.as_deref());
        }
        faces_not_outlined = faces.failed;
        faces_ambiguous = faces.ambiguous;
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
    let points_sign_change: usize = branches.iter().map(|b| b.curve_cert.len()).sum();
    let sign_change_note = if points_sign_change > 0 {
        format!(
            "; at {points_sign_change} points next to proven branch points, where that test cannot succeed, by a proven sign change instead: the signed distance along a fixed direction changes sign between the ends of a parameter segment on which the foot point is unique and continuous (Krawczyk's test for the 2 x 2 foot system over the segment's box), so a true common point lies on the segment (intermediate value theorem; existence, not uniqueness; listed per branch as curve_cert)"
        )
    } else {
        String::new()
    };
    let uncertified: usize = pairs
        .iter()
        .filter_map(|p| p.coverage.as_ref())
        .map(|c| c.uncertified)
        .sum();
    let (tube_pairs, tube_boxes) =
        pairs
            .iter()
            .filter_map(|p| p.coverage.as_ref())
            .fold((0, 0), |a, c| {
                (
                    a.0 + c.near_shared_edges,
                    a.1 + c.crossing_boxes_near_shared_edges,
                )
            });
    let tube_note = if tube_pairs + tube_boxes > 0 {
        format!(
            "; or, {tube_pairs} pairs and {tube_boxes} crossing boxes, proven inside the tube around an edge or vertex the two faces share (within its reach, listed per shared edge as `within`, of the edge's 513-sample polyline): the claim excludes every branch with a point in such a tube — also where it runs on outside the tube, since a border crossing in a tube decides its pair — there the faces meet by construction"
        )
    } else {
        String::new()
    };
    let no_missed_branches = !meshes
        && pairs.iter().all(|p| {
            p.coincident.is_none() && p.coverage.as_ref().is_some_and(|c| c.no_missed_branches)
        });
    let coincident_pairs = pairs.iter().filter(|p| p.coincident.is_some()).count();
    let overlap_pairs = pairs
        .iter()
        .filter(|p| {
            p.coincident
                .as_ref()
                .is_some_and(|c| c.kind == CoincidenceKind::Overlap)
        })
        .count();
    let singular: Vec<_> = pairs
        .iter()
        .flat_map(|p| &p.touch_points)
        .filter_map(|t| t.singular.as_ref())
        .collect();
    let singular_points_uncertified = singular
        .iter()
        .filter(|s| s.kind == SingularKind::Uncertified)
        .count();
    let singular_points_proven = singular.len() - singular_points_uncertified;
    let matched = pairs
        .iter()
        .filter_map(|p| p.coverage.as_ref())
        .map(|c| c.match_distance)
        .fold(0.0, f64::max);
    let mut certificate = vec![
        if meshes {
            "every point lies within the stated distance of both triangulations (rigorous bound on the constructed crossing point)".to_string()
        } else {
            "every point's distance to each surface at its own parameters is bounded rigorously (basis functions in f64 with a relative error bound or in outward-rounded intervals, the homogeneous sum in f64 with a forward error bound or in intervals, exact rational fallback): dist_a_max, dist_b_max, dist_max".to_string()
        },
        if meshes {
            "distance to the curve (mesh mode): the same bound, to the exact crossing of the triangulations".to_string()
        } else if !prm.certify {
            "distance to the intersection curve: NOT computed (certificates switched off: --no-certify); every point is listed as not_requested and dist_curve_max is null".to_string()
        } else if points_curve_uncertified == 0 {
            format!("every point's distance to the intersection curve is bounded rigorously: a true common point of both faces (parameters in both domains) lies within curve_radius, the unique zero in its parameter box (Krawczyk's test on S_A(u,v) = S_B(s,t) plus a plane across the curve, interval enclosures over the box; hypotheses: continuous surfaces, weights not vanishing, both proven or refused){sign_change_note}")
        } else {
            format!("distance to the intersection curve: proven for every point but {points_curve_uncertified}, which are uncertified (listed per branch with the reason: tangency, singular points, no contraction of the Krawczyk box, a sign-change radius above tol){sign_change_note}; dist_curve_max is null")
        },
        "branch topology comes from exact signs with symbolic perturbation; every segment is used once (checked)".to_string(),
        if meshes {
            "mesh mode: the curves are the exact intersection of the triangulations; no coverage certificate".to_string()
        } else if !prm.certify {
            "coverage: NOT computed (certificates switched off: --no-certify): a branch could be missing".to_string()
        } else if no_missed_branches {
            format!("coverage: every branch of the true intersection (closed loop, open arc, touching point) comes within {matched:.3e} of the output, proven: every parameter-box pair is free (disjoint control-point boxes), within that distance of the output, or transversal (separated normal cones) with every border crossing within that distance of the output, or inside the proven region of a branch point (one zero of the tangency system, one foot per point: no closed loop there but through the branch point){tube_note}")
        } else if uncertified == 0 && coincident_pairs > 0 {
            "coverage: not applicable to coincident face pairs (below); every other pair is certified".to_string()
        } else {
            format!("coverage: NOT certified: {uncertified} parameter-box pairs undecided (listed per pair with the reason): a branch could be missing there")
        },
        if prm.pieces == super::Pieces::Cubic {
            "cubic pieces (each rebuilt from its end points and their tangents in `tangents`): within tol of the true curve at a quarter, half and three quarters of each piece, measured after refinement (evidence, not proof); where a tangent is missing (surfaces meeting at a small angle) the piece is the chord, its midpoint measured; pairs of trimmed faces are output in chords (no `tangents`); the coverage claim is about the pieces (each replaced by a polyline within a proven distance of it)".to_string()
        } else {
            "chord midpoints within tol of the true curve are measured after refinement (evidence, not proof)".to_string()
        },
    ];
    if !singular.is_empty() {
        certificate.push(if singular_points_uncertified == 0 {
            format!("singular points: all {singular_points_proven} proven (touching point or branch point): a unique non-degenerate critical point of the normal distance in the isolating box (Krawczyk's test on the tangency system), its type from the sign of the Hessian determinant, the distance between the surfaces there enclosed within tol")
        } else {
            format!("singular points: {singular_points_proven} proven, {singular_points_uncertified} NOT certified (listed per touch point with the reason): their kind is not known")
        });
    }
    if prm.respect_trims && trimmed_faces > 0 {
        let clip = |f: fn(&super::brep_faces::FaceClipOut) -> usize| -> usize {
            pairs.iter().filter_map(|p| p.faces.as_ref()).map(f).sum()
        };
        let shared = clip(|c| c.shared_edges.len());
        let on_shared: usize = clip(|c| c.shared_edges.iter().map(|e| e.points).sum::<usize>());
        certificate.push(format!(
            "curves, touch points, common borders and uncertified regions restricted to the faces ({trimmed_faces} trimmed; trim loops polygonized with {SAMPLES_PER_CURVE} samples per curve, B-rep loops from their edges sampled at 1/150 of the model size and 3 degrees of turn): exact decisions against the polygons, evidence against the true loop curves; the coverage claim is made about the output so restricted; removed: {} branch points, {} touch points, {} common border points and {} uncertified regions outside the faces",
            clip(|c| c.points_outside),
            clip(|c| c.touch_points_outside),
            clip(|c| c.border_points_outside),
            clip(|c| c.regions_outside),
        ));
        if a.brep.is_some() && b.is_none() {
            certificate.push(format!(
                "shared edges: the intersection along {shared} edges and vertices the faces share ({on_shared} points, {} touch points within the reach of the edge's tube, listed per edge as `within`, by local search: evidence) is listed per pair as shared_edges, not as branches; it is where the faces meet by construction",
                clip(|c| c.touch_points_on_shared_edges)
            ));
        }
    }
    // Said whether or not another face clips: a run whose only face could not be outlined
    // once said nothing of it.
    if prm.respect_trims && !faces_not_outlined.is_empty() {
        certificate.push(format!(
            "NOT restricted, NOT certified: {} faces could not be outlined in their parameter plane, their whole surfaces were intersected: {}",
            faces_not_outlined.len(),
            faces_not_outlined.join("; ")
        ));
    }
    if prm.respect_trims && !faces_ambiguous.is_empty() {
        certificate.push(format!(
            "NOT certified: {} faces are outlined against what their files declare: {}",
            faces_ambiguous.len(),
            faces_ambiguous.join("; ")
        ));
    }
    if !prm.respect_trims && (a.brep.is_some() || b.is_some_and(|m| m.brep.is_some())) {
        certificate.push("untrimmed: the faces' whole surfaces were intersected (the B-rep's loops and shared edges ignored, --untrimmed)".to_string());
    }
    if coincident_pairs > overlap_pairs {
        certificate.push(format!(
            "COINCIDENT: {} face pairs are proven to coincide (identical, or all control points in one plane, exact): their intersection is a region, not curves; listed per pair, not certified as curves",
            coincident_pairs - overlap_pairs
        ));
    }
    if overlap_pairs > 0 {
        certificate.push(format!(
            "OVERLAP: {overlap_pairs} face pairs were measured to overlap (a 2x2 block of a 17x17 grid of points of one surface within tol of the other with parallel normals; local search: evidence, not proven): their intersection is a region; the branches and touch points inside it are removed and counted per pair (coincident.overlap); their coverage stays refused"
        ));
    }
    let contact_pairs = pairs.iter().filter(|p| p.tangent_contact.is_some()).count();
    if contact_pairs > 0 {
        certificate.push(format!(
            "TANGENT CONTACT: {contact_pairs} face pairs were measured to touch along a curve (at least {} uncertified points within tol of both surfaces with normals parallel to sin <= {}, spread over more than 100 tol; evidence, not proven): the tangential points and uncertified branches along it are listed per pair as one contact polyline (tangent_contact), not as curves; their coverage stays refused",
            super::tangent_contact::MIN_POINTS,
            super::tangent_contact::MAX_SIN
        ));
    }
    let borders: Vec<_> = pairs.iter().flat_map(|p| &p.common_borders).collect();
    let borders_not_proven = borders.iter().filter(|c| !c.certified()).count();
    if !borders.is_empty() {
        certificate.push(format!(
            "COMMON BORDERS: {} pieces of borders two faces have in common, piece by piece the same rational Bezier curves up to a proven gap (proportional weights, control points within the gap, exact rational arithmetic), listed per pair as common_borders, not as branches; the branch points and touch points traced within the match distance of them are moved into them (counted there, not in the branch and touch point figures); they are part of the output the coverage refers to. {} exact (gap 0): one curve on both faces, every point proven within curve_radius_max of the intersection (its border point lies on both faces); {borders_not_proven} NOT proven: within their gap of each other, whether the faces meet there is not decided",
            borders.len(),
            borders.len() - borders_not_proven,
        ));
    }
    if partial {
        certificate.push(format!(
            "PARTIAL: stopped by {}; {not_run} pairs not run, {} pairs stopped before their end",
            if prm.control.cancelled() {
                "cancellation"
            } else {
                "the time limit"
            },
            pairs.iter().filter(|p| !p.complete).count()
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
        tangent_contact_pairs: contact_pairs,
        common_borders: borders.len(),
        common_borders_not_proven: borders_not_proven,
        singular_points_proven,
        singular_points_uncertified,
        partial,
        certified: all_points_within_tol
            && !partial
            && (meshes || no_missed_branches)
            && singular_points_uncertified == 0
            && borders_not_proven == 0
            && faces_not_outlined.is_empty()
            && (!prm.respect_trims || faces_ambiguous.is_empty()),
        seconds: t0.elapsed().as_secs_f64(),
        certificate,
    };
    Ok(SsiResult { pairs, summary })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 20,000 disjoint planes: 2·10⁸ pairs considered, none intersected, without listing them.
    #[test]
    fn many_disjoint_faces_are_culled_without_a_pair_list() {
        use crate::model::Surface;
        use crate::spline::construct::bilinear;
        let n = 20_000;
        let surfaces = (0..n)
            .map(|k| {
                let z = k as f64;
                let s =
                    bilinear([0.0, 0.0, z], [1.0, 0.0, z], [0.0, 1.0, z], [1.0, 1.0, z]).unwrap();
                Surface::new("plane", s)
            })
            .collect();
        let m = Model {
            surfaces,
            ..Default::default()
        };
        let r = intersect_models(&m, None, &SsiParams::default(), &|_, _| {}).unwrap();
        assert_eq!(r.summary.pairs_considered, n * (n - 1) / 2);
        assert_eq!(r.summary.pairs_intersected, 0);
    }
}
