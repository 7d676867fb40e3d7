//! The intersection of two parametric surfaces (paper §4, steps 1–9 for one pair).

use super::branch::{BranchNear, BranchResult, PairGeometry, refine_branch};
use super::certify::ExactSurface;
use super::coincide::coincidence;
use super::common_borders;
use super::control::CHECK_EVERY;
use super::coverage::Suspects;
use super::coverage::{CoverageParams, Reason, coverage_in};
use super::pair_meshes::meshes;
use super::refine::RefineParams;
use super::refine::Refined;
use super::report::{ContactOut, PairOut, PairStats, SingularKind};
use super::topology::Topology;
use super::touch::{region, tangential_points_in, touch_out};
use super::trace::{check_invariants, trace};
use super::tri_tri::intersect_pair;
use super::tri_tri::{Feature, PointId};
use super::triangulate::SurfaceMesh;
use super::{SsiError, SsiParams};
use crate::geom::tri_tree::{TriTree, triangle_box};
use crate::predicates::tri_tri::ConstructedPoint;
use crate::spline::NurbsSurface;
use rustc_hash::FxHashMap as HashMap;
use std::time::Instant;

/// Triangle `t` of `m` as three points.
pub(crate) fn tri(m: &SurfaceMesh, t: u32) -> [[f64; 3]; 3] {
    let v = m.triangles[t as usize];
    std::array::from_fn(|k| m.vertices[v[k] as usize])
}

/// Triangle-box tree of a mesh.
pub fn tree(m: &SurfaceMesh) -> TriTree {
    let boxes: Vec<_> = (0..m.triangles.len() as u32)
        .map(|t| triangle_box(&tri(m, t)))
        .collect();
    TriTree::build(&boxes)
}

/// Unit normal of a triangle (`None` when degenerate).
pub(crate) fn unit_normal(t: &[[f64; 3]; 3]) -> Option<[f64; 3]> {
    let a: [f64; 3] = std::array::from_fn(|k| t[1][k] - t[0][k]);
    let b: [f64; 3] = std::array::from_fn(|k| t[2][k] - t[0][k]);
    let n = [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ];
    let l = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    (l > 0.0).then(|| n.map(|c| c / l))
}

/// Size of a model-space box around both surfaces' control nets.
pub fn net_diagonal(ss: &[&NurbsSurface<f64, 3>]) -> f64 {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for s in ss {
        for p in s.points_weights().0 {
            for k in 0..3 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
    }
    (0..3).map(|k| (hi[k] - lo[k]).powi(2)).sum::<f64>().sqrt()
}

/// Intersect surfaces `sa` (face `a`) and `sb` (face `b`).
pub fn intersect_surfaces(
    sa: &NurbsSurface<f64, 3>,
    sb: &NurbsSurface<f64, 3>,
    ids: (usize, usize),
    prm: &SsiParams,
    deadline: Option<Instant>,
) -> Result<PairOut, SsiError> {
    let t0 = Instant::now();
    let ctl = &prm.control;
    let stop = || ctl.stop(deadline);
    let mut stats = PairStats::default();
    // A pair that ends before anything is traced: nothing listed.
    let early = |mut stats: PairStats, complete, coverage, coincident| {
        stats.seconds = t0.elapsed().as_secs_f64();
        Ok(PairOut {
            a: ids.0,
            b: ids.1,
            branches: Vec::new(),
            touch_points: Vec::new(),
            contacts: Vec::new(),
            stats,
            coverage,
            complete,
            coincident,
            faces: None,
            tangent_contact: None,
            common_borders: Vec::new(),
        })
    };
    // What a pair stopped (time limit, cancel) before its branches are traced returns.
    let stopped = |stats: PairStats| early(stats, false, None, None);
    let coverage_on = prm.coverage && prm.certify;
    let mut cp = coverage_params(prm, deadline);
    // Faces proven to have no common point (pieces subdivided until all pairs are free):
    // nothing to trace, and the coverage certificate holds as it stands (reported when
    // asked for).
    // The Bézier pieces of both faces, extracted once for the disjointness test, the cone
    // test and the coverage certificate.
    let pieces = super::coverage::PairPieces::new(sa, sb);
    if let Some(c) = super::coverage::disjoint::proven_disjoint_in(&pieces, &cp) {
        stats.proven_disjoint = true;
        return early(stats, true, coverage_on.then_some(c), None);
    }
    if let Some(c) = coincidence(sa, sb) {
        return early(stats, true, None, Some(c));
    }
    // Where no normal of A is ever parallel to one of B (proven), there is no tangential
    // point to look for, and no near-tangency to mesh finely.
    let transversal = super::coverage::normals_never_parallel_in(&pieces);
    // Where tangential points may lie (pairs of parameter boxes); none: proven absent.
    let suspects = if transversal {
        Some(Suspects::new(Vec::new()))
    } else {
        super::coverage::tangency_suspects(&pieces, prm.tol).map(Suspects::new)
    };
    let no_tangency = suspects.as_ref().is_some_and(Suspects::is_empty);
    ctl.report(ids, "triangulate", 0, 2);
    let (ma, mb) = meshes(sa, sb, prm, no_tangency, suspects.as_ref(), &mut stats);
    stats.triangles_a = ma.triangles.len();
    stats.triangles_b = mb.triangles.len();
    stats.unresolved_cells_a = ma.unresolved_cells;
    stats.unresolved_cells_b = mb.unresolved_cells;
    if stop() {
        return stopped(stats);
    }
    let ea = ExactSurface::new(sa);
    let eb = ExactSurface::new(sb);
    let g = PairGeometry {
        sa,
        sb,
        ma: &ma,
        mb: &mb,
        ea: &ea,
        eb: &eb,
        shared: prm.shared_tubes.as_deref(),
    };
    let rp = RefineParams {
        tol: prm.tol,
        max_iter: 60,
        tangent_sin: prm.refine_tangent_sin,
        curve_certificates: prm.certify,
        fits: prm.fits,
        cubic: prm.pieces == crate::ssi::Pieces::Cubic,
    };
    let flat = prm.flatness.unwrap_or(net_diagonal(&[sa, sb]) * 2e-3);
    ctl.report(ids, "tangential points", 0, 0);
    // Nor where every pair of pieces within `tol` of each other is proven to have normals
    // never parallel (`coverage::apart`): there is no tangential point to look for either.
    let singular = if no_tangency {
        Vec::new()
    } else {
        tangential_points_in(&g, flat, prm.tangent_angle_deg, &rp, suspects.as_ref())
    };
    if stop() {
        return stopped(stats);
    }
    let regions = SingularRegions::new(&ma, &mb, &singular, flat);
    ctl.report(ids, "candidate triangle pairs", 0, 0);
    let pairs = tree(&ma).overlapping_pairs(&tree(&mb));
    stats.candidate_pairs = pairs.len();
    let Some((mut topo, contacts)) = build_topology(
        &pairs,
        &|t| (tri(&ma, t), ma.topo_triangle(t)),
        &|t| (tri(&mb, t), mb.topo_triangle(t)),
        &mut stats,
        &|e| regions.merge(e, &singular),
        &|done, total| {
            ctl.report(ids, "triangle intersections", done, total);
            stop()
        },
    ) else {
        return stopped(stats);
    };
    let branches = trace(&mut topo);
    check_invariants(&topo, &branches)?;
    let mut out = PairOut {
        a: ids.0,
        b: ids.1,
        branches: Vec::new(),
        touch_points: Vec::new(),
        contacts,
        stats,
        coverage: None,
        complete: true,
        coincident: None,
        faces: None,
        tangent_contact: None,
        common_borders: Vec::new(),
    };
    for (k, r) in singular.iter().enumerate() {
        out.touch_points.push(touch_out(
            &g,
            r,
            topo.uses_of(&SingularRegions::id(k as u32)),
            prm.tol,
        ));
    }
    // Proven branch points: the points next to them get the sign-change certificate where
    // Krawczyk's test fails.
    let near = BranchNear::new(
        out.touch_points
            .iter()
            .filter_map(|t| t.singular.as_ref())
            .filter(|s| s.kind == SingularKind::BranchPoint)
            .filter_map(|s| s.root_point)
            .collect(),
        prm.tol,
    );
    for (k, b) in branches.iter().enumerate() {
        ctl.report(ids, "refine branches", k, branches.len());
        if stop() {
            out.complete = false;
            break;
        }
        let step = |done: usize, total: usize| {
            ctl.report(ids, "certify branch points", done, total);
            stop()
        };
        match refine_branch(
            &topo,
            b,
            &g,
            &rp,
            prm.max_insert_depth,
            &singular,
            &near,
            &step,
        ) {
            Some(BranchResult::Curve(c)) => out.branches.push(c),
            Some(BranchResult::Touch(t)) => out.touch_points.push(t),
            Some(BranchResult::OnSharedEdges(pts)) => count_on_shared(&mut out, g.shared, &pts),
            None => {
                out.complete = false;
                break;
            }
        }
    }
    // Borders the faces have in common: listed as such, with what the meshes traced along
    // them, and part of the output the coverage refers to.
    let borders = crate::spline::border_match::common_borders(sa, sb, prm.tol);
    if !borders.is_empty() {
        out.common_borders = borders
            .iter()
            .map(|m| common_borders::sample(m, (sa, sb), (&ea, &eb), cp.match_distance))
            .collect();
        common_borders::absorb(&mut out, cp.match_distance);
        let d = cp.match_distance;
        if common_borders::out_of_reach(&out.common_borders, (sa, sb), cp.outside.as_ref(), d) {
            cp.max_boxes = cp.max_boxes.min(common_borders::OUT_OF_REACH_BOXES);
        }
        // The coverage refers to the borders as the faces mode keeps them.
        cp.borders = std::sync::Arc::new(match &cp.restrict {
            Some(r) => out
                .common_borders
                .iter()
                .flat_map(|c| common_borders::clip_to_faces(c, (sa, sb), &*r.meets, &*r.shared).0)
                .map(|c| c.points)
                .collect(),
            None => out
                .common_borders
                .iter()
                .map(|c| c.points.clone())
                .collect(),
        });
    }
    if out.complete && coverage_on && stop() {
        out.complete = false;
    }
    if out.complete && coverage_on {
        ctl.report(ids, "coverage", 0, 0);
        out.coverage = Some(coverage_in(&pieces, &out.branches, &out.touch_points, &cp));
        super::regions::refine_undecided_in(&mut out, &pieces, prm, &cp, deadline);
        let parallel = out.coverage.as_ref().is_some_and(|c| {
            c.uncertified_regions.iter().any(|r| {
                matches!(
                    r.reason,
                    Reason::NormalsNotSeparated | Reason::Budget | Reason::TrimInPair
                )
            })
        });
        if parallel {
            ctl.report(ids, "overlap", 0, 0);
            super::overlap::diagnose(&mut out, sa, sb, prm.tol);
            super::tangent_contact::diagnose(&mut out, sa, sb, prm.tol);
        }
    }
    out.stats.seconds = t0.elapsed().as_secs_f64();
    Ok(out)
}

/// The coverage certificate's parameters for a pair run with `prm`.
fn coverage_params(prm: &SsiParams, deadline: Option<Instant>) -> CoverageParams {
    CoverageParams {
        match_distance: prm.coverage_match.unwrap_or(10.0 * prm.tol),
        max_pair_depth: prm.coverage_max_depth,
        max_crossing_depth: 96,
        max_boxes: prm.coverage_max_boxes,
        deadline,
        cancel: prm.control.cancel.clone(),
        outside: prm.coverage_outside.clone(),
        restrict: prm.coverage_restrict.clone(),
        tubes: std::sync::Arc::new(
            prm.shared_tubes
                .as_ref()
                .map(|t| t.polylines())
                .unwrap_or_default(),
        ),
        borders: Default::default(),
    }
}

/// Count the points of a traced curve lying wholly along shared edges to those edges (the
/// tally is completed by [`super::brep_faces::Faces::apply`]).
pub(crate) fn count_on_shared(
    out: &mut PairOut,
    tubes: Option<&super::shared_tubes::SharedTubes>,
    pts: &[[f64; 3]],
) {
    let Some(t) = tubes else {
        return;
    };
    let faces = out.faces.get_or_insert_with(Default::default);
    if faces.shared_edges.is_empty() {
        faces.shared_edges = t.tally();
    }
    for x in pts {
        t.attribute(x, &mut faces.shared_edges);
    }
}

/// Triangles of each mesh in the singular region of a tangential point, and the merge of
/// crossing points named by their features (see [`super::touch`]).
struct SingularRegions {
    tri_a: HashMap<u32, u32>,
    tri_b: HashMap<u32, u32>,
    edges_a: HashMap<(u32, u32), Vec<u32>>,
    edges_b: HashMap<(u32, u32), Vec<u32>>,
}

fn edge_map(m: &SurfaceMesh) -> HashMap<(u32, u32), Vec<u32>> {
    let mut e: HashMap<(u32, u32), Vec<u32>> = HashMap::default();
    for t in 0..m.triangles.len() as u32 {
        let v = m.topo_triangle(t);
        for k in 0..3 {
            let (a, b) = (v[k], v[(k + 1) % 3]);
            e.entry((a.min(b), a.max(b))).or_default().push(t);
        }
    }
    e
}

impl SingularRegions {
    fn new(ma: &SurfaceMesh, mb: &SurfaceMesh, singular: &[Refined], r: f64) -> Self {
        let mut s = SingularRegions {
            tri_a: HashMap::default(),
            tri_b: HashMap::default(),
            edges_a: HashMap::default(),
            edges_b: HashMap::default(),
        };
        if singular.is_empty() {
            return s;
        }
        for (k, p) in singular.iter().enumerate() {
            for t in region(ma, &p.xyz, r) {
                s.tri_a.entry(t).or_insert(k as u32);
            }
            for t in region(mb, &p.xyz, r) {
                s.tri_b.entry(t).or_insert(k as u32);
            }
        }
        s.edges_a = edge_map(ma);
        s.edges_b = edge_map(mb);
        s
    }
    fn id(k: u32) -> PointId {
        PointId {
            a: Feature::Singular(k),
            b: Feature::Singular(k),
        }
    }
    fn of(
        f: Feature,
        tris: &HashMap<u32, u32>,
        edges: &HashMap<(u32, u32), Vec<u32>>,
    ) -> Option<u32> {
        match f {
            Feature::Triangle(t) => tris.get(&t).copied(),
            Feature::Edge(a, b) => edges
                .get(&(a, b))
                .and_then(|ts| ts.iter().filter_map(|t| tris.get(t).copied()).min()),
            Feature::Singular(k) => Some(k),
        }
    }
    /// The point itself, or the singular point whose region its features touch.
    fn merge(
        &self,
        e: (PointId, ConstructedPoint),
        singular: &[Refined],
    ) -> (PointId, ConstructedPoint) {
        if self.tri_a.is_empty() && self.tri_b.is_empty() {
            return e;
        }
        let k = match (
            Self::of(e.0.a, &self.tri_a, &self.edges_a),
            Self::of(e.0.b, &self.tri_b, &self.edges_b),
        ) {
            (Some(x), Some(y)) => Some(x.min(y)),
            (x, y) => x.or(y),
        };
        match k {
            Some(k) => (
                Self::id(k),
                ConstructedPoint {
                    p: singular[k as usize].xyz,
                    err: 0.0,
                    exact_fallback: false,
                },
            ),
            None => e,
        }
    }
}

/// A triangle as points and (topological) vertex numbers.
pub(crate) type TriangleOf<'a> = &'a dyn Fn(u32) -> ([[f64; 3]; 3], [u32; 3]);

/// Steps 4–5 over the candidate pairs: exact triangle intersections into the Point / PointUse /
/// Segment structure (each end passed through `merge`), counting into `stats`; the first 100
/// non-transversal contacts are listed. `stop(done, total)` is asked every
/// [`CHECK_EVERY`] pairs; `None` when it said stop (the topology is incomplete then).
pub(crate) fn build_topology(
    pairs: &[(u32, u32)],
    a: TriangleOf,
    b: TriangleOf,
    stats: &mut PairStats,
    merge: &dyn Fn((PointId, ConstructedPoint)) -> (PointId, ConstructedPoint),
    stop: &dyn Fn(usize, usize) -> bool,
) -> Option<(Topology, Vec<ContactOut>)> {
    let mut topo = Topology::new();
    let mut contacts = Vec::new();
    for (k, &(ta, tb)) in pairs.iter().enumerate() {
        if k.is_multiple_of(CHECK_EVERY) && stop(k, pairs.len()) {
            return None;
        }
        let ((pa, va), (pb, vb)) = (a(ta), b(tb));
        let o = intersect_pair(&pa, &va, ta, &pb, &vb, tb);
        stats.degenerate_triangle_pairs += o.degenerate as usize;
        stats.inconsistent_triangle_pairs += o.inconsistent as usize;
        if let Some(kind) = o.contact {
            stats.contacts += 1;
            if contacts.len() < 100 {
                contacts.push(ContactOut {
                    kind,
                    triangle_a: ta,
                    triangle_b: tb,
                });
            }
        }
        if let Some(s) = o.segment {
            let [p, q] = s.ends.map(merge);
            topo.add_segment(p, q, s.ta, s.tb);
        }
    }
    stats.segments = topo.segments.len();
    stats.points = topo.points.len();
    stats.duplicate_segments = topo.duplicate_segments;
    Some((topo, contacts))
}
