//! Certifying a foreign intersection result (`vericad certify-ssi A [B] --curves FILE`): an
//! oracle. For every point `x` of another system's intersection curves:
//!
//! 1. proven bounds `[lower, upper]` on the distance from `x` to face set A and to face set
//!    B, global over all faces ([`super::closest`]: branch and bound on enclosed Bézier
//!    pieces; no local search decides anything);
//! 2. a proven radius `r`: a true intersection point `S_A(u, v) = S_B(s, t)` (parameters in
//!    the faces' domains) lies within `r` of `x` ([`super::krawczyk`], the same certificate as vericad's own points: Krawczyk on
//!    the intersection system restricted to the plane through `x` normal to the curve).
//!
//! A point is `on_curve` when `r <= tol`; `off` when `max(lower_A, lower_B) > tol` (proven:
//! no intersection point lies within tol of it — every such point lies on both face sets);
//! otherwise `uncertified` (e.g. at a tangent contact, where the Jacobian is singular: a
//! curve that merely runs close to both surfaces there is never accepted), or, in one-file
//! mode, `shared_edge` when it lies within tol of the two faces it is nearest to and on the
//! border of one of them (faces of a B-rep meet along edges: not a wrong curve, not
//! certified either).
//!
//! vericad intersects the faces itself; a vericad branch is `missing` (or `partial`) only
//! when one of its points is certified by the same Krawczyk test and the true point within
//! `r` of it is proven farther than `match_distance` from every foreign polyline; when some
//! of its points are not covered but none can be certified so, it is `unverified`.
//! Foreign spline curves are checked at sample points: the bounds hold at those points
//! (between them it is evidence only — said in the report).

mod point;
mod text_report;

use super::closest::IvSurface;
use super::coverage::near::Near;
use super::report::SsiResult;
use super::trims::TrimRegion;
use crate::model::Model;
use crate::scalar::Interval;
use point::{Check, InFaces, check_point, curve_point_radius, in_faces};
use rayon::prelude::*;
use serde::Serialize;

pub use super::foreign_read::{CURVE_SAMPLES, ForeignInput, read_foreign};

/// The verdict on one foreign point.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum PointStatus {
    /// A true intersection point is proven within tol.
    OnCurve,
    /// Proven farther than tol from face set A or from face set B.
    Off,
    /// One-file mode: within tol of the two nearest faces and on the border of one of them
    /// (faces of a B-rep meeting along an edge).
    SharedEdge,
    /// A true intersection point of the surfaces is proven within tol, but its parameters lie
    /// outside a face's trim loops (decided against the trim polygon): the curve follows the
    /// untrimmed surfaces there, not the faces.
    OutsideFaces,
    /// Neither could be proven.
    Uncertified,
}

/// A point that is not `on_curve`, with the reason.
#[derive(Clone, Debug, Serialize)]
pub struct PointIssue {
    pub index: usize,
    pub point: [f64; 3],
    pub status: PointStatus,
    /// `singular`, `no_contraction`, `face_border`, `no_enclosure` (Krawczyk),
    /// `radius_above_tol`, `off_surface`, `no_face`, `outside_faces` (the true point lies
    /// outside a face's trim), `trim_boundary` (its parameter box meets a trim's edge).
    pub reason: String,
    /// Proven lower bound on the distance to the intersection (max over the two face sets).
    pub dist_lower: f64,
    /// Proven radius to a true intersection point, when one was certified.
    pub curve_radius: Option<f64>,
}

/// One foreign curve, checked.
#[derive(Clone, Debug, Serialize)]
pub struct ForeignCurve {
    pub index: usize,
    pub name: String,
    /// `polyline` (every vertex checked) or `spline` (checked at samples).
    pub kind: &'static str,
    pub points_checked: usize,
    /// Largest proven upper bound on a checked point's distance to face set A / to face set
    /// B (global: the closest point over all faces).
    pub dist_a_max: f64,
    pub dist_b_max: f64,
    /// Largest proven lower bound on a checked point's distance to the intersection
    /// (`max(dist to A, dist to B)` from below); above tol means proven off.
    pub dist_lower_max: f64,
    /// Largest proven radius to a true intersection point over the checked points; `None`
    /// when some point has none.
    pub curve_dist_max: Option<f64>,
    pub points_on_curve: usize,
    pub points_off: usize,
    pub points_shared_edge: usize,
    pub points_outside_faces: usize,
    pub points_uncertified: usize,
    /// `within_tol` (every point on_curve), `off` (some point proven off), `outside_faces`
    /// (some point's true curve point outside a face's trim, none off), `shared_edge`
    /// (one-file mode: on_curve or on a shared edge), `uncertified`.
    pub status: &'static str,
    /// `status == within_tol`.
    pub within_tol: bool,
    /// The first points that are not on_curve (up to 5).
    pub issues: Vec<PointIssue>,
}

/// A vericad branch and how much of it the foreign curves cover.
#[derive(Clone, Debug, Serialize)]
pub struct BranchCoverage {
    pub face_a: usize,
    pub face_b: usize,
    pub branch: usize,
    pub closed: bool,
    pub points: usize,
    /// Fraction of the branch's points proven within `match_distance` of a foreign curve.
    pub covered_fraction: f64,
    /// `found` (every point covered); `missing` (< 50% covered) or `partial` — only with a
    /// witness: a point certified within `witness_radius` of a true intersection point that
    /// is proven farther than `match_distance` from every foreign curve; `unverified`
    /// (points not covered, none certified as such a witness).
    pub status: &'static str,
    pub witness: Option<[f64; 3]>,
    pub witness_radius: Option<f64>,
}

#[derive(Clone, Debug, Serialize)]
pub struct CertifyReport {
    /// `two_files` (faces of A against faces of B) or `one_file` (all distinct face pairs
    /// of one model).
    pub mode: &'static str,
    pub tol: f64,
    pub match_distance: f64,
    pub points_checked: usize,
    pub curves: Vec<ForeignCurve>,
    pub curves_within_tol: usize,
    pub curves_off: usize,
    pub branches: Vec<BranchCoverage>,
    pub missing_branches: usize,
    pub partial_branches: usize,
    pub unverified_branches: usize,
    /// vericad's touching points and common-border points not within `match_distance` of a
    /// foreign curve (each leaves `foreign_complete` false).
    pub touch_and_border_points_not_covered: usize,
    /// vericad's own coverage certificate: every true branch comes within its match
    /// distance of vericad's output (and the run is complete).
    pub vericad_no_missed_branches: bool,
    /// vericad's coverage holds and every vericad branch is found: every branch of the true
    /// intersection comes within `vericad_match + match_distance` of a foreign curve.
    pub foreign_complete: bool,
    /// Every foreign curve within tol of the intersection and `foreign_complete`: the
    /// command exits with 0 only then.
    pub certified: bool,
    pub seconds: f64,
    pub notes: Vec<String>,
}

/// Proven lower bound on the distance from `c` to the segment `[p, q]`.
fn seg_lower(c: &[f64; 3], p: &[f64; 3], q: &[f64; 3]) -> f64 {
    let iv = Interval::point;
    let d: [Interval; 3] = std::array::from_fn(|k| iv(q[k]) - iv(p[k]));
    let e: [Interval; 3] = std::array::from_fn(|k| iv(c[k]) - iv(p[k]));
    let f: [Interval; 3] = std::array::from_fn(|k| iv(c[k]) - iv(q[k]));
    let dotp = |a: &[Interval; 3], b: &[Interval; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let norm_lo = |s: Interval| {
        if s.lo > 0.0 {
            s.lo.sqrt().next_down().max(0.0)
        } else {
            0.0
        }
    };
    let len2 = |a: &[Interval; 3]| a[0].sqr() + a[1].sqr() + a[2].sqr();
    let dd = len2(&d);
    let ed = dotp(&e, &d);
    if dd.hi == 0.0 || ed.hi < 0.0 {
        return norm_lo(len2(&e));
    }
    if (ed - dd).lo > 0.0 {
        return norm_lo(len2(&f));
    }
    // Distance to the line (a lower bound on the distance to the segment): |e × d| / |d|.
    let cr = [
        e[1] * d[2] - e[2] * d[1],
        e[2] * d[0] - e[0] * d[2],
        e[0] * d[1] - e[1] * d[0],
    ];
    let num = len2(&cr);
    if num.lo.partial_cmp(&(0.0)) != Some(std::cmp::Ordering::Greater) || !dd.hi.is_finite() {
        return 0.0;
    }
    (num.lo / dd.hi)
        .next_down()
        .max(0.0)
        .sqrt()
        .next_down()
        .max(0.0)
}

/// Check foreign curves against faces `a` and `b` (`None`: one-file mode, every pair of
/// distinct faces of `a`), and vericad's own `result` against them. `progress(done, total)`
/// is called as points are checked.
pub fn certify(
    a: &Model,
    b: Option<&Model>,
    foreign: &[ForeignInput],
    result: &SsiResult,
    tol: f64,
    match_distance: f64,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> CertifyReport {
    let t0 = std::time::Instant::now();
    let prep = |m: &Model| -> Vec<IvSurface> {
        m.surfaces
            .par_iter()
            .map(|f| IvSurface::new(&f.nurbs))
            .collect()
    };
    let fa = prep(a);
    let fb = b.map(prep);
    let fbs = fb.as_deref();
    let (ta, mut failed, mut ambiguous) = TrimRegion::of_model(a);
    let tb = b.map(|m| {
        let (t, f, amb) = TrimRegion::of_model(m);
        failed.extend(f);
        ambiguous.extend(amb);
        t
    });
    let trims = (&ta[..], tb.as_deref());
    let trimmed = ta
        .iter()
        .chain(tb.iter().flatten())
        .filter(|r| r.is_some())
        .count();
    let total: usize = foreign.iter().map(|f| f.2.len()).sum();
    let done = std::sync::atomic::AtomicUsize::new(0);
    let curves: Vec<ForeignCurve> = foreign
        .iter()
        .enumerate()
        .map(|(i, (name, kind, pts))| {
            let checks: Vec<Check> = pts
                .par_iter()
                .map(|x| {
                    let c = check_point(&fa, fbs, trims, x, tol);
                    let n = done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
                    progress(n, total);
                    c
                })
                .collect();
            let count = |s: PointStatus| checks.iter().filter(|c| c.status == s).count();
            let (on, off, shared, outside, unc) = (
                count(PointStatus::OnCurve),
                count(PointStatus::Off),
                count(PointStatus::SharedEdge),
                count(PointStatus::OutsideFaces),
                count(PointStatus::Uncertified),
            );
            let status = if on == checks.len() {
                "within_tol"
            } else if off > 0 {
                "off"
            } else if outside > 0 {
                "outside_faces"
            } else if unc == 0 {
                "shared_edge"
            } else {
                "uncertified"
            };
            let issues = checks
                .iter()
                .enumerate()
                .filter(|(_, c)| c.status != PointStatus::OnCurve)
                .take(5)
                .map(|(k, c)| PointIssue {
                    index: k,
                    point: pts[k],
                    status: c.status,
                    reason: c.reason.into(),
                    dist_lower: c.lower,
                    curve_radius: c.radius,
                })
                .collect();
            ForeignCurve {
                index: i,
                name: name.clone(),
                kind,
                points_checked: pts.len(),
                dist_a_max: checks.iter().map(|c| c.upper_a).fold(0.0, f64::max),
                dist_b_max: checks.iter().map(|c| c.upper_b).fold(0.0, f64::max),
                dist_lower_max: checks.iter().map(|c| c.lower).fold(0.0, f64::max),
                curve_dist_max: checks
                    .iter()
                    .try_fold(0.0f64, |m, c| c.radius.map(|r| m.max(r))),
                points_on_curve: on,
                points_off: off,
                points_shared_edge: shared,
                points_outside_faces: outside,
                points_uncertified: unc,
                status,
                within_tol: status == "within_tol",
                issues,
            }
        })
        .collect();
    // vericad's branches against the foreign polylines.
    let mut segs = Vec::new();
    for (_, _, f) in foreign {
        if f.len() == 1 {
            segs.push((f[0], f[0]));
        }
        for w in f.windows(2) {
            segs.push((w[0], w[1]));
        }
    }
    let near = Near::new(segs.clone());
    let far_from_foreign = |x: &[f64; 3], r: f64| -> bool {
        let l = segs
            .iter()
            .map(|(p, q)| seg_lower(x, p, q))
            .fold(f64::INFINITY, f64::min);
        (Interval::point(l) - Interval::point(r)).lo > match_distance
    };
    let jobs: Vec<(usize, usize)> = result
        .pairs
        .iter()
        .enumerate()
        .flat_map(|(i, p)| (0..p.branches.len()).map(move |k| (i, k)))
        .collect();
    let branches: Vec<BranchCoverage> = jobs
        .par_iter()
        .map(|&(i, k)| {
            let p = &result.pairs[i];
            let br = &p.branches[k];
            // Points of vericad's branch outside the faces (the outer ends of chords leaving
            // them) are not the faces' intersection: not asked of the foreign curves.
            let on_faces = |j: usize| match (br.uv_a.get(j), br.uv_b.get(j)) {
                (Some(a), Some(b)) => {
                    in_faces(
                        trims,
                        p.a,
                        p.b,
                        &[[a[0], a[0]], [a[1], a[1]], [b[0], b[0]], [b[1], b[1]]],
                    ) != InFaces::Outside
                }
                _ => true,
            };
            let uncovered: Vec<usize> = (0..br.points.len())
                .filter(|&j| {
                    let x = br.points[j];
                    !near.box_within(&(x, x), match_distance) && on_faces(j)
                })
                .collect();
            let frac = 1.0 - uncovered.len() as f64 / br.points.len().max(1) as f64;
            let mut witness = None;
            let sb = fbs.unwrap_or(&fa);
            if !uncovered.is_empty()
                && br.uv_a.len() == br.points.len()
                && br.uv_b.len() == br.points.len()
                && p.a < fa.len()
                && p.b < sb.len()
            {
                let step = (uncovered.len() / 16).max(1);
                for &j in uncovered.iter().step_by(step).take(16) {
                    let x = br.points[j];
                    if let Ok((r, params)) =
                        curve_point_radius(&fa[p.a], &sb[p.b], &x, br.uv_a[j], br.uv_b[j])
                        && in_faces(trims, p.a, p.b, &params) == InFaces::Inside
                        && far_from_foreign(&x, r)
                    {
                        witness = Some((x, r));
                        break;
                    }
                }
            }
            BranchCoverage {
                face_a: p.a,
                face_b: p.b,
                branch: k,
                closed: br.closed,
                points: br.points.len(),
                covered_fraction: frac,
                status: match (uncovered.is_empty(), witness.is_some()) {
                    (true, _) => "found",
                    (false, false) => "unverified",
                    (false, true) if frac < 0.5 => "missing",
                    (false, true) => "partial",
                },
                witness: witness.map(|w| w.0),
                witness_radius: witness.map(|w| w.1),
            }
        })
        .collect();
    let count = |s: &str| branches.iter().filter(|b| b.status == s).count();
    let vericad_ok = result.summary.no_missed_branches && !result.summary.partial;
    // vericad's touching points and common borders are components (or parts) of the
    // intersection too: each point of them not within the match distance of a foreign curve
    // leaves the foreign result's completeness not established.
    let points_not_covered: usize = result
        .pairs
        .iter()
        .flat_map(|p| {
            p.touch_points.iter().map(|t| t.point).chain(
                p.common_borders
                    .iter()
                    .flat_map(|c| c.points.iter().copied()),
            )
        })
        .filter(|x| !near.box_within(&(*x, *x), match_distance))
        .count();
    let foreign_complete =
        vericad_ok && points_not_covered == 0 && branches.iter().all(|b| b.status == "found");
    let curves_within_tol = curves.iter().filter(|c| c.within_tol).count();
    let mut notes = vec![
        "dist_a_max / dist_b_max: proven upper bounds on each checked point's distance to face set A / B, global over all faces (branch and bound on enclosed Bezier pieces); dist_lower_max: proven lower bound on the distance to the intersection".into(),
        "a point is on_curve when a true intersection point (S_A(u,v) = S_B(s,t) exactly, parameters in the faces' domains) is proven within tol of it by the Krawczyk test on the intersection system in the plane through the point normal to the curve; where the surfaces are tangent the Jacobian is singular and the point is uncertified, never accepted".into(),
        "for spline curves the points are samples: between samples the verdict is evidence".into(),
        format!("a vericad branch is missing (or partial) only with a witness: a point of it certified within witness_radius of a true intersection point that is proven farther than match_distance = {match_distance:e} from every foreign polyline; unverified when it is not covered but no such witness was found"),
    ];
    if b.is_none() {
        notes.push("one-file mode: foreign points are checked against every pair of distinct faces of the model (the nearest face and the nearest other face); points within tol of both and on the border of one of them (edges along which faces of a B-rep meet) that cannot be certified are reported shared_edge: not wrong, not certified".into());
    }
    if trimmed > 0 {
        notes.push(format!("trimmed faces ({trimmed}): a point is on_curve only when the parameter box of its true intersection point lies inside both faces' trim loops, and a witness of a missing branch likewise; outside_faces when it lies outside one face's loops, uncertified (trim_boundary) when it meets a loop; the loops are decided as parameter-plane polygons through points of the trim curves (exact for the polygons, evidence against the curves themselves)"));
    }
    for f in &failed {
        notes.push(format!(
            "{f}: its loops could not be outlined, so its whole surface is taken as the face"
        ));
    }
    for f in &ambiguous {
        notes.push(format!(
            "{f}: verdicts on points near it rest on that reading"
        ));
    }
    if points_not_covered > 0 {
        notes.push(format!("{points_not_covered} of vericad's touching points and common-border points are not within match_distance of a foreign curve: the completeness of the foreign result is not established"));
    }
    if !vericad_ok {
        notes.push("vericad's own coverage certificate does not hold on this input (uncertified regions or a partial run): the completeness of the foreign result is not established".into());
    }
    CertifyReport {
        mode: if b.is_none() { "one_file" } else { "two_files" },
        tol,
        match_distance,
        points_checked: total,
        curves_within_tol,
        curves_off: curves.iter().filter(|c| c.status == "off").count(),
        missing_branches: count("missing"),
        partial_branches: count("partial"),
        unverified_branches: count("unverified"),
        touch_and_border_points_not_covered: points_not_covered,
        vericad_no_missed_branches: vericad_ok,
        foreign_complete,
        certified: foreign_complete && curves_within_tol == curves.len(),
        curves,
        branches,
        seconds: t0.elapsed().as_secs_f64(),
        notes,
    }
}
