//! Adaptive refinement where the coverage certificate is undecided: the listed regions are
//! triangulated again, finer, and the pair is run again there, a few rounds within a budget.
//!
//! A small loop (a dome barely crossing a plane: loop radius 1e-4, the dome 1e-8 above the
//! plane at its top) is invisible to a mesh whose flatness exceeds the dome's height over the
//! plane: the meshes cross in no loop or in a wrong one, and the coverage certificate
//! ([`super::coverage`]) rightly lists undecided box pairs there. This step takes those
//! regions, clusters them (parameter boxes that touch on both surfaces), widens each
//! cluster's boxes `R_A × R_B` by their own size on every side, and runs steps 1–8 again with
//! both meshes made on `R_A`, `R_B` only: each surface's part over its box (knot insertion in
//! `f64`; the mesh only steers), cells at most `1/(16 · 2^k)` of the region's net diagonal and
//! flatness `0.002 / 4^k` of it in round `k`. Everything that is claimed is computed on the
//! *original* surfaces: the branches' points are refined and certified on them (distance to
//! each surface, curve radius) exactly as in the first run, and the coverage certificate is
//! computed again, from scratch, on the original surfaces and the new output — a theorem about
//! whatever output it is given, so nothing here needs to be trusted.
//!
//! What is replaced: a cluster is run only when every reported branch lies either wholly in
//! `R_A × R_B` (every point's `uv_a` in `R_A` and `uv_b` in `R_B`) or wholly outside it (no
//! point in it, and no chord between consecutive points whose parameter boxes meet it);
//! the branches wholly inside are replaced by the region run's branches (so no curve is
//! reported twice), the others kept. A round is kept only when the new coverage has fewer
//! undecided box pairs than before; otherwise the output stays as it was and the refinement
//! stops. At most [`MAX_ROUNDS`] rounds of at most [`MAX_RUNS`] clusters each; clusters whose
//! box covers more than a quarter of either domain are not run (a region that large is not a
//! small feature; the pair's own run already saw it at that scale); the pair's deadline and
//! cancel flag stop it like every other step. Region runs do not search tangential points
//! (a branch point inside a region leaves its points uncertified, which the run reports).

use super::SsiParams;
use super::branch::{BranchNear, BranchResult, PairGeometry, refine_branch};
use super::certify::ExactSurface;
use super::coverage::{CoverageParams, PairPieces, Reason, RegionOut, coverage_in};
use super::pair::{build_topology, net_diagonal, tree, tri};
use super::refine::{RefineParams, domain};
use super::report::{BranchOut, PairOut, PairStats, TouchOut};
use super::trace::{check_invariants, trace};
use super::triangulate::{TriangulateParams, triangulate};
use crate::spline::NurbsSurface;
use rustc_hash::FxHashSet as HashSet;
use serde::Serialize;
use std::time::Instant;

/// Rounds of region runs per pair.
pub const MAX_ROUNDS: u32 = 3;
/// Clusters run per round.
pub const MAX_RUNS: usize = 4;

/// What the refinement did (`coverage.refinement` in the JSON).
#[derive(Clone, Debug, Default, Serialize)]
pub struct RegionRefinement {
    /// Rounds kept (each lowered the number of undecided box pairs).
    pub rounds: u32,
    /// Region runs in the kept rounds.
    pub runs: usize,
    /// Region runs in all, kept or not.
    pub runs_tried: usize,
    /// Clusters not run: a branch crossing the cluster's border, a box too large, or a
    /// failed sub-surface.
    pub skipped: usize,
    /// Branches replaced (wholly inside a region) and branches found by region runs.
    pub branches_removed: usize,
    pub branches_added: usize,
    /// Undecided box pairs before the first round.
    pub uncertified_before: usize,
    pub seconds: f64,
}

fn touches(a: &[f64; 4], b: &[f64; 4]) -> bool {
    a[0] <= b[1] && b[0] <= a[1] && a[2] <= b[3] && b[2] <= a[3]
}

fn hull(a: &[f64; 4], b: &[f64; 4]) -> [f64; 4] {
    [
        a[0].min(b[0]),
        a[1].max(b[1]),
        a[2].min(b[2]),
        a[3].max(b[3]),
    ]
}

/// Clusters of regions whose boxes touch on both surfaces (transitively): hulls `(R_A, R_B)`.
pub fn clusters(regions: &[RegionOut]) -> Vec<([f64; 4], [f64; 4])> {
    let mut out: Vec<([f64; 4], [f64; 4])> = Vec::new();
    for r in regions {
        let mut c = (r.uv_a, r.uv_b);
        // Merge every cluster this one touches, until none does.
        while let Some(k) = out
            .iter()
            .position(|(a, b)| touches(a, &c.0) && touches(b, &c.1))
        {
            let (a, b) = out.swap_remove(k);
            c = (hull(&a, &c.0), hull(&b, &c.1));
        }
        out.push(c);
    }
    out
}

/// `b` widened by its own size on every side, clamped to the domain `d`.
pub fn widen(b: &[f64; 4], d: &[f64; 4]) -> [f64; 4] {
    let (w, h) = (b[1] - b[0], b[3] - b[2]);
    [
        (b[0] - w).max(d[0]),
        (b[1] + w).min(d[1]),
        (b[2] - h).max(d[2]),
        (b[3] + h).min(d[3]),
    ]
}

fn inside(uv: &[f64; 2], b: &[f64; 4]) -> bool {
    b[0] <= uv[0] && uv[0] <= b[1] && b[2] <= uv[1] && uv[1] <= b[3]
}

/// The parameter box of the chord `p`–`q`, or `None` when it spans half the domain `d` or more
/// in a direction (a chord across a seam: its box says nothing).
fn chord_box(p: &[f64; 2], q: &[f64; 2], d: &[f64; 4]) -> Option<[f64; 4]> {
    let b = [
        p[0].min(q[0]),
        p[0].max(q[0]),
        p[1].min(q[1]),
        p[1].max(q[1]),
    ];
    (b[1] - b[0] < 0.5 * (d[1] - d[0]) && b[3] - b[2] < 0.5 * (d[3] - d[2])).then_some(b)
}

/// Whether every point of `br` lies in `ra × rb` (`Some(true)`), none does and no chord
/// between consecutive points passes through it (`Some(false)`), or neither (`None`). A
/// branch whose chord spans the region without a point in it would otherwise count as
/// outside, and the region run would report that part of its curve a second time.
fn placement(
    br: &BranchOut,
    ra: &[f64; 4],
    rb: &[f64; 4],
    d: (&[f64; 4], &[f64; 4]),
) -> Option<bool> {
    let n = br.uv_a.len();
    let k = br
        .uv_a
        .iter()
        .zip(&br.uv_b)
        .filter(|(x, y)| inside(x, ra) && inside(y, rb))
        .count();
    let spans = if br.closed { n } else { n.saturating_sub(1) };
    let crosses = (0..spans).any(|i| {
        let j = (i + 1) % n;
        match (
            chord_box(&br.uv_a[i], &br.uv_a[j], d.0),
            chord_box(&br.uv_b[i], &br.uv_b[j], d.1),
        ) {
            (Some(a), Some(b)) => touches(&a, ra) && touches(&b, rb),
            _ => false,
        }
    });
    if k == n {
        Some(true)
    } else if k == 0 && !crosses {
        Some(false)
    } else {
        None
    }
}

fn small(b: &[f64; 4], d: &[f64; 4]) -> bool {
    (b[1] - b[0]) * (b[3] - b[2]) <= 0.25 * (d[1] - d[0]) * (d[3] - d[2])
        && b[0] < b[1]
        && b[2] < b[3]
}

fn part(s: &NurbsSurface<f64, 3>, b: &[f64; 4]) -> Option<NurbsSurface<f64, 3>> {
    let hom = s.hom.sub_patch(&b[0], &b[1], &b[2], &b[3]).ok()?;
    Some(NurbsSurface { hom })
}

/// Steps 1–8 on the region `ra × rb` at round `k` (see the module comment): the branches and
/// zero-length branches (touch points) found there, refined and certified on `sa`, `sb`.
#[allow(clippy::too_many_arguments)]
fn region_run(
    sa: &NurbsSurface<f64, 3>,
    sb: &NurbsSurface<f64, 3>,
    ea: &ExactSurface,
    eb: &ExactSurface,
    ra: &[f64; 4],
    rb: &[f64; 4],
    k: u32,
    prm: &SsiParams,
    stop: &dyn Fn() -> bool,
) -> Option<(Vec<BranchOut>, Vec<TouchOut>)> {
    let (pa, pb) = (part(sa, ra)?, part(sb, rb)?);
    let diag = net_diagonal(&[&pa, &pb]);
    if !(diag > 0.0 && diag.is_finite()) {
        return None;
    }
    let scale = f64::from(1u32 << k);
    let tp = TriangulateParams {
        flatness: diag * 2e-3 / (scale * scale),
        max_edge: diag / (f64::from(prm.min_cells_per_diagonal.max(1)) * scale),
        max_depth: prm.max_depth,
    };
    let none = HashSet::default();
    let (ma, mb) = (triangulate(&pa, &tp, &none), triangulate(&pb, &tp, &none));
    let g = PairGeometry {
        sa,
        sb,
        ma: &ma,
        mb: &mb,
        ea,
        eb,
        shared: prm.shared_tubes.as_deref(),
    };
    let pairs = tree(&ma).overlapping_pairs(&tree(&mb));
    let mut stats = PairStats::default();
    let (mut topo, _) = build_topology(
        &pairs,
        &|t| (tri(&ma, t), ma.topo_triangle(t)),
        &|t| (tri(&mb, t), mb.topo_triangle(t)),
        &mut stats,
        &|e| e,
        &|_, _| stop(),
    )?;
    let traced = trace(&mut topo);
    check_invariants(&topo, &traced).ok()?;
    let rp = RefineParams {
        tol: prm.tol,
        max_iter: 60,
        tangent_sin: prm.refine_tangent_sin,
        curve_certificates: prm.certify,
        fits: prm.fits,
        cubic: prm.pieces == crate::ssi::Pieces::Cubic,
    };
    let near = BranchNear::new(Vec::new(), prm.tol);
    let (mut branches, mut points) = (Vec::new(), Vec::new());
    for b in &traced {
        match refine_branch(
            &topo,
            b,
            &g,
            &rp,
            prm.max_insert_depth,
            &[],
            &near,
            &|_, _| stop(),
        )? {
            BranchResult::Curve(c) => branches.push(c),
            BranchResult::Touch(t) => points.push(t),
            // Along a shared edge: the coverage accounts for it through the edge's tube (the
            // points are counted to the edge in the pair's own run only).
            BranchResult::OnSharedEdges(_) => {}
        }
    }
    Some((branches, points))
}

/// Refine where `out.coverage` is undecided (see the module comment); `cp` are the coverage
/// parameters of the pair's own run.
pub fn refine_undecided(
    out: &mut PairOut,
    sa: &NurbsSurface<f64, 3>,
    sb: &NurbsSurface<f64, 3>,
    prm: &SsiParams,
    cp: &CoverageParams,
    deadline: Option<Instant>,
) {
    refine_undecided_in(out, &PairPieces::new(sa, sb), prm, cp, deadline);
}

/// [`refine_undecided`] on the pair's shared pieces (each round's coverage reuses their
/// quarters and cones).
pub(crate) fn refine_undecided_in(
    out: &mut PairOut,
    pp: &PairPieces,
    prm: &SsiParams,
    cp: &CoverageParams,
    deadline: Option<Instant>,
) {
    let (sa, sb) = pp.surfaces();
    let t0 = Instant::now();
    let stop = || prm.control.stop(deadline);
    let Some(first) = out.coverage.as_ref() else {
        return;
    };
    if first.no_missed_branches || first.uncertified_regions.is_empty() {
        return;
    }
    let mut rec = RegionRefinement {
        uncertified_before: first.uncertified,
        ..Default::default()
    };
    let (ea, eb) = (ExactSurface::new(sa), ExactSurface::new(sb));
    let (da, db) = (domain(sa), domain(sb));
    for k in 0..MAX_ROUNDS {
        let Some(cov) = out.coverage.as_ref() else {
            break;
        };
        let undecided = |r: &RegionOut| {
            matches!(
                r.reason,
                Reason::CrossingAwayFromOutput | Reason::NormalsNotSeparated
            )
        };
        if cov.no_missed_branches || stop() || cov.uncertified_regions.iter().any(|r| !undecided(r))
        {
            break;
        }
        let before = cov.uncertified;
        let mut branches = out.branches.clone();
        let mut touch_points = out.touch_points.clone();
        let (mut runs, mut skipped, mut removed, mut added) = (0, 0, 0, 0);
        for (ca, cb) in clusters(&cov.uncertified_regions)
            .into_iter()
            .take(MAX_RUNS)
        {
            let (ra, rb) = (widen(&ca, &da), widen(&cb, &db));
            let placed: Option<Vec<bool>> = branches
                .iter()
                .map(|b| placement(b, &ra, &rb, (&da, &db)))
                .collect();
            let ok = small(&ra, &da) && small(&rb, &db);
            let (Some(placed), true) = (placed, ok) else {
                skipped += 1;
                continue;
            };
            let Some((found, points)) = region_run(sa, sb, &ea, &eb, &ra, &rb, k, prm, &stop)
            else {
                skipped += 1;
                continue;
            };
            let mut keep = placed.iter().map(|p| !p);
            branches.retain(|_| keep.next().unwrap_or(true));
            removed += placed.iter().filter(|p| **p).count();
            added += found.len();
            branches.extend(found);
            touch_points.extend(points);
            runs += 1;
        }
        rec.skipped += skipped;
        rec.runs_tried += runs;
        if runs == 0 || stop() {
            break;
        }
        let cov2 = coverage_in(pp, &branches, &touch_points, cp);
        if cov2.uncertified >= before {
            break;
        }
        out.branches = branches;
        out.touch_points = touch_points;
        out.coverage = Some(cov2);
        rec.rounds += 1;
        rec.runs += runs;
        rec.branches_removed += removed;
        rec.branches_added += added;
    }
    rec.seconds = t0.elapsed().as_secs_f64();
    if let Some(c) = out.coverage.as_mut() {
        c.refinement = Some(rec);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn region(a: [f64; 4], b: [f64; 4]) -> RegionOut {
        RegionOut {
            uv_a: a,
            uv_b: b,
            reason: Reason::CrossingAwayFromOutput,
            point: None,
        }
    }

    /// Regions touching on both surfaces form one cluster, transitively; regions apart on
    /// either surface do not.
    #[test]
    fn clusters_join_touching_regions() {
        let r = [
            region([0.0, 0.1, 0.0, 0.1], [0.5, 0.6, 0.5, 0.6]),
            region([0.2, 0.3, 0.0, 0.1], [0.5, 0.6, 0.5, 0.6]),
            region([0.1, 0.2, 0.0, 0.1], [0.6, 0.7, 0.5, 0.6]),
            region([0.1, 0.2, 0.0, 0.1], [0.9, 1.0, 0.9, 1.0]),
        ];
        let mut c = clusters(&r);
        c.sort_by(|x, y| x.1[0].total_cmp(&y.1[0]));
        assert_eq!(c.len(), 2);
        assert_eq!(c[0], ([0.0, 0.3, 0.0, 0.1], [0.5, 0.7, 0.5, 0.6]));
        assert_eq!(c[1], ([0.1, 0.2, 0.0, 0.1], [0.9, 1.0, 0.9, 1.0]));
        assert_eq!(
            widen(&[0.25, 0.5, 0.0, 0.5], &[0.0, 1.0, 0.0, 1.0]),
            [0.0, 0.75, 0.0, 1.0]
        );
    }

    /// A branch with no point in the region but a chord through it is not "outside": the
    /// region run would report that part of its curve again. A chord across a seam (half the
    /// domain or more) says nothing and is not counted.
    #[test]
    fn a_chord_through_the_region_is_not_outside() {
        let d = [0.0, 1.0, 0.0, 1.0];
        let br = |a: Vec<[f64; 2]>, closed| BranchOut {
            closed,
            uv_b: a.clone(),
            uv_a: a,
            ..Default::default()
        };
        let (ra, rb) = ([0.4, 0.6, 0.4, 0.6], [0.4, 0.6, 0.4, 0.6]);
        let through = br(vec![[0.3, 0.5], [0.7, 0.5], [0.8, 0.5]], false);
        assert_eq!(placement(&through, &ra, &rb, (&d, &d)), None);
        let beside = br(vec![[0.3, 0.7], [0.7, 0.7], [0.8, 0.7]], false);
        assert_eq!(placement(&beside, &ra, &rb, (&d, &d)), Some(false));
        let inside_all = br(vec![[0.45, 0.5], [0.55, 0.5]], false);
        assert_eq!(placement(&inside_all, &ra, &rb, (&d, &d)), Some(true));
        // Closed: the closing chord counts too.
        let closing = br(vec![[0.5, 0.3], [0.8, 0.3], [0.8, 0.7], [0.5, 0.7]], true);
        assert_eq!(placement(&closing, &ra, &rb, (&d, &d)), None);
        let open = br(vec![[0.5, 0.3], [0.8, 0.3], [0.8, 0.7], [0.5, 0.7]], false);
        assert_eq!(placement(&open, &ra, &rb, (&d, &d)), Some(false));
        // Across the seam: the chord from u = 0.95 to u = 0.05 is not a chord through 0.5.
        let seam = br(vec![[0.95, 0.5], [0.05, 0.5]], false);
        assert_eq!(placement(&seam, &ra, &rb, (&d, &d)), Some(false));
    }
}
