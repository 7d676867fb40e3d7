//! Steps 8–9 applied to one traced curve: refine its sample points onto the true surfaces,
//! insert points where the polyline strays from the true curve by more than `tol`, certify
//! every point (distance to each surface, [`super::certify`]; distance to the intersection
//! curve, [`super::krawczyk`]), classify the ends, fit splines.

use super::certify::ExactSurface;
use super::fit::{fit_branch, fit_pieces};
use super::hermite::{P7, branch_jets, branch_pieces};
use super::insert::{Inserter, newton_onto_curve, packed, seams, small_angle};
use super::krawczyk::Uncertified;
use super::point_certs::{JET_RUN, certify_run};
use super::refine::{
    RefineParams, RefineStatus, Refined, auxiliary_plane, barycentric_uv, domain, refine_on_border,
};
use super::report::{BranchOut, CurveCertKind, CurveResult, EndKind, TouchOut};
use super::shared_tubes::SharedTubes;
use super::sign_change::{SignChangeCert, SignChangeFail, certify_by_sign_change};
use super::thin::thin;
use super::topology::Topology;
use super::touch::touch_out;
use super::trace::Branch;
use super::tri_tri::Feature;
use super::triangulate::SurfaceMesh;
use crate::geom::dist;
use crate::spline::NurbsSurface;
use rayon::prelude::*;
use rustc_hash::FxHashMap as HashMap;
use std::sync::Mutex;

/// The two surfaces of a pair with their meshes and exact forms.
pub struct PairGeometry<'a> {
    pub sa: &'a NurbsSurface<f64, 3>,
    pub sb: &'a NurbsSurface<f64, 3>,
    pub ma: &'a SurfaceMesh,
    pub mb: &'a SurfaceMesh,
    pub ea: &'a ExactSurface,
    pub eb: &'a ExactSurface,
    /// One-file runs on a B-rep: the tubes around the edges and vertices the two faces share.
    pub shared: Option<&'a SharedTubes>,
}

/// The proven branch points of a pair: points where Krawczyk's test fails within
/// [`BranchNear::radius`] of one get the sign-change certificate ([`super::sign_change`])
/// instead, if its radius is within tol. A branch point's vertex ends several branches: the
/// result is computed once per point.
pub struct BranchNear {
    /// Root points of the proven branch points.
    pub points: Vec<[f64; 3]>,
    /// How far from a proven branch point the certificate is tried (100 tol).
    pub radius: f64,
    pub tol: f64,
    cache: Mutex<HashMap<[u64; 7], Result<SignChangeCert, SignChangeFail>>>,
}

impl BranchNear {
    pub fn new(points: Vec<[f64; 3]>, tol: f64) -> Self {
        BranchNear {
            points,
            radius: 100.0 * tol,
            tol,
            cache: Mutex::new(HashMap::default()),
        }
    }

    /// The curve result of `r`, whose Krawczyk test failed with `reason`.
    fn certify(&self, g: &PairGeometry, r: &Refined, reason: Uncertified) -> CurveResult {
        if !self.points.iter().any(|b| dist(b, &r.xyz) <= self.radius) {
            return Err(reason);
        }
        let key: [u64; 7] = [
            r.xyz[0], r.xyz[1], r.xyz[2], r.uv_a[0], r.uv_a[1], r.uv_b[0], r.uv_b[1],
        ]
        .map(f64::to_bits);
        let cached = self.cache.lock().ok().and_then(|c| c.get(&key).copied());
        let res = cached.unwrap_or_else(|| {
            let res =
                certify_by_sign_change(g.sa, g.sb, g.ea, g.eb, &r.xyz, &r.uv_a, &r.uv_b, self.tol);
            if let Ok(mut c) = self.cache.lock() {
                c.insert(key, res);
            }
            res
        });
        match res {
            Ok(c) => Ok((c.radius, CurveCertKind::SignChange)),
            Err(SignChangeFail::AboveTol(_)) => Err(Uncertified::SignChangeAboveTol),
            Err(SignChangeFail::NoSignChange) => Err(reason),
        }
    }
}

/// A refined branch, or a touching point when the branch has zero length.
// One per branch, moved once: the size difference costs nothing.
#[allow(clippy::large_enum_variant)]
pub enum BranchResult {
    Curve(BranchOut),
    Touch(TouchOut),
    /// Every traced point, refined onto both surfaces, lies in a tube around an edge or vertex
    /// the two faces share ([`PairGeometry::shared`]): the curve is where the faces meet by
    /// construction. Its points (not refined further, nor certified) are counted to the edges.
    OnSharedEdges(Vec<[f64; 3]>),
}

fn on_border(uv: &[f64; 2], d: &[f64; 4]) -> bool {
    let eu = 1e-9 * (d[1] - d[0]);
    let ev = 1e-9 * (d[3] - d[2]);
    (uv[0] - d[0]).abs() <= eu
        || (uv[0] - d[1]).abs() <= eu
        || (uv[1] - d[2]).abs() <= ev
        || (uv[1] - d[3]).abs() <= ev
}

/// The border line `(coordinate, value)` of the parameter domain that the mesh feature lies
/// on, when it is an edge with both end vertices on the same border line: the crossing point
/// is then on the surface's boundary.
fn border_line(f: Feature, m: &SurfaceMesh, d: &[f64; 4]) -> Option<(usize, f64)> {
    let Feature::Edge(a, b) = f else {
        return None;
    };
    let (p, q) = (m.uv[a as usize], m.uv[b as usize]);
    if p[0] == q[0] && (p[0] == d[0] || p[0] == d[1]) {
        Some((0, p[0]))
    } else if p[1] == q[1] && (p[1] == d[2] || p[1] == d[3]) {
        Some((1, p[1]))
    } else {
        None
    }
}

/// Indices of the refined points kept: a point that coincides with the one kept before it
/// (within `4 ε` of the larger coordinate: traced points on either side of a knot line or a
/// mesh vertex refine to one curve point) is dropped, so the output has no segment of zero
/// length; the ends of an open branch are kept (the last replaces a coincident one before
/// it), and a closed branch does not end on its first point.
fn distinct(pts: &[Refined], closed: bool) -> Vec<usize> {
    let same = |a: &Refined, b: &Refined| {
        let scale = a
            .xyz
            .iter()
            .chain(&b.xyz)
            .fold(0.0f64, |m, x| m.max(x.abs()));
        dist(&a.xyz, &b.xyz) <= 4.0 * f64::EPSILON * scale
    };
    let n = pts.len();
    let mut kept: Vec<usize> = Vec::with_capacity(n);
    for k in 0..n {
        match kept.last() {
            Some(&l) if same(&pts[l], &pts[k]) => {
                if !closed && k == n - 1 && kept.len() > 1 {
                    kept.pop();
                    kept.push(k);
                }
            }
            _ => kept.push(k),
        }
    }
    if !closed && kept.len() == 1 && n > 1 {
        kept.push(n - 1);
    }
    while closed && kept.len() > 1 && same(&pts[kept[kept.len() - 1]], &pts[kept[0]]) {
        kept.pop();
    }
    kept
}

fn border_edge(f: Feature, m: &SurfaceMesh, d: &[f64; 4]) -> bool {
    border_line(f, m, d).is_some()
}

/// Refine, certify and fit one traced branch. `stop(done, total)` is asked before every
/// point of each step (refinement, insertion, certification; a point costs far more than
/// the question); `None` when it said stop.
#[allow(clippy::too_many_arguments)]
pub fn refine_branch(
    t: &Topology,
    b: &Branch,
    g: &PairGeometry,
    prm: &RefineParams,
    max_insert_depth: u32,
    singular: &[Refined],
    near: &BranchNear,
    stop: &dyn Fn(usize, usize) -> bool,
) -> Option<BranchResult> {
    let check = |k: usize, n: usize| stop(k, n);
    let raw: Vec<[f64; 3]> = b.points.iter().map(|&p| t.points[p as usize].xyz).collect();
    let mut pts_in_order = b.points.clone();
    if b.closed {
        pts_in_order.pop();
    }
    // Triangles of the segment each point is refined from.
    let seg_of = |k: usize| -> (u32, u32) {
        let s = &t.segments[b.segments[k.min(b.segments.len() - 1)] as usize];
        (s.ta, s.tb)
    };
    let singular_of = |k: usize| match t.points[b.points[k] as usize].id.a {
        Feature::Singular(s) => singular.get(s as usize).copied(),
        _ => None,
    };
    let refine_at = |k: usize| -> Refined {
        if let Some(r) = singular_of(k) {
            return r;
        }
        let (ta, tb) = seg_of(k);
        let x = raw[k];
        auxiliary_plane(
            g.sa,
            g.sb,
            barycentric_uv(g.ma, ta, &x),
            barycentric_uv(g.mb, tb, &x),
            prm,
        )
    };
    if raw.iter().all(|x| *x == raw[0]) {
        return Some(BranchResult::Touch(touch_out(g, &refine_at(0), 0, prm.tol)));
    }
    let n = pts_in_order.len();
    let mut refined: Vec<Refined> = Vec::with_capacity(n);
    for k in 0..n {
        if check(k, n) {
            return None;
        }
        refined.push(refine_at(k));
    }
    if !b.closed {
        // Ends on a face boundary: put them on it.
        let last = refined.len() - 1;
        for (k, p) in [(0, b.points[0]), (last, b.points[b.points.len() - 1])] {
            let id = t.points[p as usize].id;
            let target = border_line(id.a, g.ma, &domain(g.sa))
                .map(|(c, v)| (0, c, v))
                .or_else(|| border_line(id.b, g.mb, &domain(g.sb)).map(|(c, v)| (1, c, v)));
            if let Some((which, coord, value)) = target
                && let Some(r) = refine_on_border(g.sa, g.sb, &refined[k], which, coord, value, prm)
            {
                refined[k] = r;
            }
        }
    }
    // Near tangency the refined points (within tol of both surfaces) can lie far from the
    // curve; they move onto it before the insertion measures chords against the curve, as the
    // inserted points do (otherwise a chord between two points off the curve on one side can
    // pass the test and stray from the curve once its ends have moved).
    refined.par_iter_mut().with_min_len(64).for_each(|r| {
        if r.status == RefineStatus::Converged && small_angle(g, r) {
            newton_onto_curve(g, r, prm.tol);
        }
    });
    if let Some(t) = g.shared
        && refined.iter().all(|r| t.nearest(&r.xyz).is_some())
    {
        return Some(BranchResult::OnSharedEdges(
            refined.iter().map(|r| r.xyz).collect(),
        ));
    }
    let mut ins = Inserter {
        g,
        prm,
        max_depth: max_insert_depth,
        inserted: 0,
        max_dev: 0.0,
        refused: 0,
        stop: &|| stop(0, 0),
        stopped: false,
        seam_a: seams(g.sa),
        seam_b: seams(g.sb),
    };
    let mut all: Vec<Refined> = Vec::with_capacity(refined.len() * 2);
    let mut kept = distinct(&refined, b.closed);
    if prm.cubic {
        kept = thin(g.sa, g.sb, &refined, &kept, b.closed, prm.tol);
    }
    let n = kept.len();
    let spans = if b.closed { n } else { n - 1 };
    for j in 0..n {
        if check(j, n) {
            return None;
        }
        let k = kept[j];
        all.push(refined[k]);
        if j < spans {
            let q = refined[kept[(j + 1) % n]];
            ins.between(&refined[k], &q, seg_of(k), 0, &mut all);
        }
    }
    if ins.stopped {
        return None;
    }
    let tangential = all
        .iter()
        .filter(|r| r.status == RefineStatus::Tangential)
        .count();
    let unconverged = all
        .iter()
        .filter(|r| {
            matches!(
                r.status,
                RefineStatus::NotConverged | RefineStatus::AtBoundary
            )
        })
        .count();
    // Points whose proven distance to the curve exceeds tol/8 move onto the curve (see
    // [`onto_curve`]).
    // Per point, independent of the others: on the worker threads, a chunk at a time between
    // cancellation checks (results in point order, so they do not depend on the thread count).
    let total = all.len();
    let mut per_point = Vec::with_capacity(total);
    for (c, chunk) in all.chunks_mut(1024).enumerate() {
        if check(c * 1024, total) {
            return None;
        }
        per_point.par_extend(
            chunk
                .par_chunks_mut(JET_RUN)
                .flat_map_iter(|run| certify_run(g, prm, run)),
        );
    }
    let da_max = per_point.iter().fold(0.0f64, |m, p| m.max(p.1));
    let db_max = per_point.iter().fold(0.0f64, |m, p| m.max(p.2));
    // Krawczyk's failures next to a proven branch point: the sign-change certificate.
    let radii: Vec<CurveResult> = per_point
        .into_iter()
        .zip(&all)
        .map(|(p, r)| match p.0 {
            Ok(x) => Ok((x, CurveCertKind::Krawczyk)),
            Err(Uncertified::NotRequested) => Err(Uncertified::NotRequested),
            Err(u) => near.certify(g, r, u),
        })
        .collect();
    let ends = if b.closed {
        Vec::new()
    } else {
        let (dom_a, dom_b) = (domain(g.sa), domain(g.sb));
        [
            (b.points[0], &all[0]),
            (b.points[b.points.len() - 1], &all[all.len() - 1]),
        ]
        .iter()
        .map(|(p, r)| {
            let pt = &t.points[*p as usize];
            if pt.uses.len() > 2 {
                EndKind::BranchPoint
            } else if matches!(pt.id.a, Feature::Singular(_)) {
                EndKind::Tangential
            } else if border_edge(pt.id.a, g.ma, &dom_a)
                || border_edge(pt.id.b, g.mb, &dom_b)
                || on_border(&r.uv_a, &dom_a)
                || on_border(&r.uv_b, &dom_b)
            {
                EndKind::Boundary
            } else if r.status == RefineStatus::Tangential {
                EndKind::Tangential
            } else {
                EndKind::Unexplained
            }
        })
        .collect()
    };
    let points: Vec<[f64; 3]> = all.iter().map(|r| r.xyz).collect();
    let uv_a: Vec<[f64; 2]> = all.iter().map(|r| r.uv_a).collect();
    let uv_b: Vec<[f64; 2]> = all.iter().map(|r| r.uv_b).collect();
    let pk: Vec<P7> = if prm.cubic {
        all.iter().map(packed).collect()
    } else {
        Vec::new()
    };
    let tangents = if prm.cubic {
        branch_jets(g.sa, g.sb, &pk, b.closed)
    } else {
        Vec::new()
    };
    let fit = if !prm.fits {
        None
    } else if prm.cubic {
        fit_pieces(&branch_pieces(&pk, &tangents, b.closed))
    } else {
        fit_branch(&points, &uv_a, &uv_b, b.closed)
    };
    let mut out = BranchOut {
        closed: b.closed,
        points,
        uv_a,
        uv_b,
        dist_a_max: da_max,
        dist_b_max: db_max,
        ends,
        tangential_points: tangential,
        unconverged_points: unconverged,
        refused_insertions: ins.refused,
        inserted_points: ins.inserted,
        max_chord_deviation: ins.max_dev,
        fit,
        tangents,
        dist_curve_max: None,
        curve_uncertified_points: 0,
        curve_radius: Vec::new(),
        curve_uncertified: Vec::new(),
        curve_cert: Vec::new(),
    };
    out.set_curve_results(radii);
    Some(BranchResult::Curve(out))
}
