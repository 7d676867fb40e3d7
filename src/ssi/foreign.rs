//! Certifying a foreign intersection result (`vericad certify-ssi A B --curves FILE`): for
//! every point of another system's intersection curves, a proven upper bound on its distance
//! to each of the two face sets; and the branches vericad finds that the foreign result lacks.
//!
//! A point `x` is projected onto each face (grid start, then Newton on
//! `(S - x)·S_u = (S - x)·S_v = 0`, clamped to the domain); the bound at the projected
//! parameters (interval / exact evaluation, [`super::certify`]) is an upper bound on the
//! distance from `x` to that face, since `S(u, v)` lies on it; the smallest over the faces is
//! the reported bound. Foreign B-spline curves are checked at sample points: the bound holds
//! at those points (between them it is evidence only — said in the report).

use super::certify::ExactSurface;
use super::refine::{domain, point_d1};
use super::report::SsiResult;
use crate::geom::{Point, dist_to_segment, dot};
use crate::model::Model;
use crate::spline::NurbsSurface;
use serde::Serialize;

/// Samples per foreign spline curve.
pub const CURVE_SAMPLES: usize = 200;

/// One foreign curve, checked.
#[derive(Clone, Debug, Serialize)]
pub struct ForeignCurve {
    pub index: usize,
    pub name: String,
    /// `polyline` (every vertex checked) or `spline` (checked at samples).
    pub kind: &'static str,
    pub points_checked: usize,
    /// Largest proven distance bound of a checked point to faces A / to faces B.
    pub dist_a_max: f64,
    pub dist_b_max: f64,
    pub within_tol: bool,
}

/// A vericad branch and how much of it the foreign curves cover.
#[derive(Clone, Debug, Serialize)]
pub struct BranchCoverage {
    pub face_a: usize,
    pub face_b: usize,
    pub branch: usize,
    pub closed: bool,
    pub points: usize,
    /// Fraction of the branch's points within `match_distance` of a foreign curve.
    pub covered_fraction: f64,
    /// `missing` (< 50% covered), `partial`, or `found`.
    pub status: &'static str,
}

#[derive(Clone, Debug, Serialize)]
pub struct CertifyReport {
    pub tol: f64,
    pub match_distance: f64,
    pub curves: Vec<ForeignCurve>,
    pub curves_within_tol: usize,
    pub branches: Vec<BranchCoverage>,
    pub missing_branches: usize,
    pub partial_branches: usize,
    pub notes: Vec<String>,
}

struct Face {
    s: NurbsSurface<f64, 3>,
    exact: ExactSurface,
    lo: [f64; 3],
    hi: [f64; 3],
}

fn faces(m: &Model) -> Vec<Face> {
    m.surfaces
        .iter()
        .map(|f| {
            let pts = f.nurbs.points_weights().0;
            let lo =
                std::array::from_fn(|k| pts.iter().map(|p| p[k]).fold(f64::INFINITY, f64::min));
            let hi =
                std::array::from_fn(|k| pts.iter().map(|p| p[k]).fold(f64::NEG_INFINITY, f64::max));
            Face {
                s: f.nurbs.clone(),
                exact: ExactSurface::new(&f.nurbs),
                lo,
                hi,
            }
        })
        .collect()
}

fn sub(a: &[f64; 3], b: &[f64; 3]) -> [f64; 3] {
    a.sub(b)
}

/// Damped Gauss–Newton from `uv` towards the closest point of `s` to `x`.
fn descend(
    s: &NurbsSurface<f64, 3>,
    x: &[f64; 3],
    mut uv: [f64; 2],
    d: &[f64; 4],
) -> ([f64; 2], f64) {
    let err = |uv: &[f64; 2]| {
        let p = s.eval(&uv[0], &uv[1]);
        dot(&sub(&p, x), &sub(&p, x))
    };
    let mut e = err(&uv);
    for _ in 0..40 {
        let (p, su, sv) = point_d1(s, uv[0], uv[1]);
        let r = sub(&p, x);
        let (a, b, c) = (dot(&su, &su), dot(&su, &sv), dot(&sv, &sv));
        let (g0, g1) = (dot(&r, &su), dot(&r, &sv));
        let det = a * c - b * b;
        if det.is_nan() || det == 0.0 {
            break;
        }
        let step = [-(c * g0 - b * g1) / det, -(a * g1 - b * g0) / det];
        let mut t = 1.0;
        let mut moved = false;
        for _ in 0..12 {
            let next = [
                (uv[0] + t * step[0]).clamp(d[0], d[1]),
                (uv[1] + t * step[1]).clamp(d[2], d[3]),
            ];
            let en = err(&next);
            if en < e {
                (uv, e, moved) = (next, en, true);
                break;
            }
            t *= 0.5;
        }
        if !moved {
            break;
        }
    }
    (uv, e)
}

/// Parameters of (a local) closest point of `s` to `x`: the best of several grid starts,
/// each refined by damped Gauss–Newton.
pub fn project(s: &NurbsSurface<f64, 3>, x: &[f64; 3]) -> [f64; 2] {
    let d = domain(s);
    let n = 16;
    let mut starts: Vec<(f64, [f64; 2])> = Vec::with_capacity((n + 1) * (n + 1));
    for i in 0..=n {
        for j in 0..=n {
            let uv = [
                d[0] + (d[1] - d[0]) * i as f64 / n as f64,
                d[2] + (d[3] - d[2]) * j as f64 / n as f64,
            ];
            let p = s.eval(&uv[0], &uv[1]);
            starts.push((dot(&sub(&p, x), &sub(&p, x)), uv));
        }
    }
    starts.sort_by(|a, b| a.0.total_cmp(&b.0));
    starts
        .iter()
        .take(4)
        .map(|(_, uv)| descend(s, x, *uv, &d))
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .map_or([d[0], d[2]], |r| r.0)
}

/// Proven upper bound on the distance from `x` to the union of `fs` (infinite if none).
fn distance_to(fs: &[Face], x: &[f64; 3]) -> f64 {
    let mut best = f64::INFINITY;
    for f in fs {
        // Lower bound by the control-net box (convex hull): skip faces that cannot be closer.
        let gap2: f64 = (0..3)
            .map(|k| (f.lo[k] - x[k]).max(x[k] - f.hi[k]).max(0.0).powi(2))
            .sum();
        if gap2.sqrt() >= best {
            continue;
        }
        let uv = project(&f.s, x);
        if let Some(d) = f.exact.distance_bound(x, &uv) {
            best = best.min(d);
        }
    }
    best
}

/// A foreign curve as points: `(name, kind, points)`.
pub type ForeignInput = (String, &'static str, Vec<[f64; 3]>);

/// The curves of a foreign result file: a model's space curves (sampled), or JSON
/// polylines (`[[[x,y,z],...],...]`, `{"curves": [...]}`, or a vericad `ssi` result).
pub fn read_foreign(path: &std::path::Path) -> Result<Vec<ForeignInput>, String> {
    let text = std::fs::read(path).map_err(|e| format!("{}: {e}", path.display()))?;
    if let Ok(v) = serde_json::from_slice::<serde_json::Value>(&text) {
        let polys = if let Some(pairs) = v.get("pairs").and_then(|p| p.as_array()) {
            pairs
                .iter()
                .flat_map(|p| p["branches"].as_array().cloned().unwrap_or_default())
                .map(|b| b["points"].clone())
                .collect()
        } else if let Some(c) = v.get("curves").and_then(|c| c.as_array()) {
            c.clone()
        } else if let Some(c) = v.as_array() {
            c.clone()
        } else {
            Vec::new()
        };
        if !polys.is_empty() || v.get("pairs").is_some() {
            return polys
                .iter()
                .enumerate()
                .map(|(i, p)| {
                    let pts: Vec<[f64; 3]> = serde_json::from_value(p.clone()).map_err(|e| {
                        format!("{}: curve {i}: expected [[x,y,z],...]: {e}", path.display())
                    })?;
                    if pts.iter().flatten().any(|c| !c.is_finite()) {
                        return Err(format!(
                            "{}: curve {i}: non-finite coordinate",
                            path.display()
                        ));
                    }
                    Ok((format!("polyline {i}"), "polyline", pts))
                })
                .collect();
        }
    }
    let m = crate::io::read_model(path).map_err(|e| e.to_string())?;
    if m.curves.is_empty() {
        return Err(format!("{}: no curves found", path.display()));
    }
    Ok(m.curves
        .iter()
        .map(|c| {
            let s = c.geometry.to_space();
            let (t0, t1) = s.hom.domain();
            let pts = (0..CURVE_SAMPLES)
                .map(|k| s.eval(&(t0 + (t1 - t0) * k as f64 / (CURVE_SAMPLES - 1) as f64)))
                .collect();
            (c.name.clone(), "spline", pts)
        })
        .collect())
}

/// Check foreign curves against faces `a` and `b`, and vericad's own `result` against them.
pub fn certify(
    a: &Model,
    b: &Model,
    foreign: &[ForeignInput],
    result: &SsiResult,
    tol: f64,
    match_distance: f64,
) -> CertifyReport {
    let (fa, fb) = (faces(a), faces(b));
    let curves: Vec<ForeignCurve> = foreign
        .iter()
        .enumerate()
        .map(|(i, (name, kind, pts))| {
            let da = pts.iter().map(|x| distance_to(&fa, x)).fold(0.0, f64::max);
            let db = pts.iter().map(|x| distance_to(&fb, x)).fold(0.0, f64::max);
            ForeignCurve {
                index: i,
                name: name.clone(),
                kind,
                points_checked: pts.len(),
                dist_a_max: da,
                dist_b_max: db,
                within_tol: da <= tol && db <= tol,
            }
        })
        .collect();
    let mut branches = Vec::new();
    for p in &result.pairs {
        for (k, br) in p.branches.iter().enumerate() {
            let covered = br
                .points
                .iter()
                .filter(|x| {
                    foreign.iter().any(|(_, _, f)| {
                        if f.len() == 1 {
                            dist_to_segment(x, &f[0], &f[0]) <= match_distance
                        } else {
                            f.windows(2)
                                .any(|w| dist_to_segment(x, &w[0], &w[1]) <= match_distance)
                        }
                    })
                })
                .count();
            let frac = covered as f64 / br.points.len().max(1) as f64;
            branches.push(BranchCoverage {
                face_a: p.a,
                face_b: p.b,
                branch: k,
                closed: br.closed,
                points: br.points.len(),
                covered_fraction: frac,
                status: if frac < 0.5 {
                    "missing"
                } else if frac < 1.0 {
                    "partial"
                } else {
                    "found"
                },
            });
        }
    }
    CertifyReport {
        tol,
        match_distance,
        curves_within_tol: curves.iter().filter(|c| c.within_tol).count(),
        missing_branches: branches.iter().filter(|b| b.status == "missing").count(),
        partial_branches: branches.iter().filter(|b| b.status == "partial").count(),
        curves,
        branches,
        notes: vec![
            "dist_*_max are proven upper bounds at the checked points (projection, then interval/exact evaluation); for spline curves the points are samples, so between samples it is evidence".into(),
            "a branch is missing when fewer than half of vericad's refined points lie within match_distance of a foreign curve".into(),
        ],
    }
}

impl std::fmt::Display for CertifyReport {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        writeln!(
            f,
            "certify foreign SSI result, tol {:e}, match distance {:e}",
            self.tol, self.match_distance
        )?;
        for c in &self.curves {
            writeln!(
                f,
                "  curve {} ({}, {} points): proven distance <= {:.3e} to A, <= {:.3e} to B {}",
                c.index,
                c.kind,
                c.points_checked,
                c.dist_a_max,
                c.dist_b_max,
                if c.within_tol {
                    "(within tol)"
                } else {
                    "(NOT within tol)"
                }
            )?;
        }
        writeln!(
            f,
            "  vericad branches: {} ({} missing from the foreign result, {} partly covered)",
            self.branches.len(),
            self.missing_branches,
            self.partial_branches
        )?;
        for b in self.branches.iter().filter(|b| b.status != "found") {
            writeln!(
                f,
                "    faces ({}, {}) branch {} ({}, {} points): {} ({:.0}% covered)",
                b.face_a,
                b.face_b,
                b.branch,
                if b.closed { "closed" } else { "open" },
                b.points,
                b.status,
                100.0 * b.covered_fraction
            )?;
        }
        for n in &self.notes {
            writeln!(f, "  - {n}")?;
        }
        Ok(())
    }
}
