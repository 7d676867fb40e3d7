//! The `ssi` job: read one or two model files, intersect, write the JSON result and optional
//! VTK / IGES outputs, report progress on long runs.

use super::report::{SingularKind, SsiResult};
use super::{SsiError, SsiParams, intersect_models};
use crate::io::vtk::{Array, PolyData, render};
use crate::model::{Curve, CurveGeometry, Model};
use crate::spline::NurbsCurve;
use std::path::Path;
use std::time::Instant;

#[derive(Debug, thiserror::Error)]
pub enum JobError {
    #[error(transparent)]
    Read(#[from] crate::io::ReadError),
    #[error(transparent)]
    Compute(#[from] SsiError),
    #[error("cannot write {0}: {1}")]
    Write(String, String),
    #[error("thread pool: {0}")]
    Threads(String),
    #[error("foreign curves: {0}")]
    Foreign(String),
    #[error("{0}: {1}")]
    Range(String, crate::model::check::RangeError),
}

/// Read a model and refuse coordinates outside the supported range (squared distances in the
/// certificates must not overflow).
fn read_in_range(f: &Path) -> Result<Model, JobError> {
    let m = crate::io::read_model(f)?;
    m.check_coordinate_range()
        .map_err(|e| JobError::Range(f.display().to_string(), e))?;
    Ok(m)
}

impl JobError {
    pub fn is_bad_input(&self) -> bool {
        matches!(
            self,
            JobError::Read(_)
                | JobError::Foreign(_)
                | JobError::Range(..)
                | JobError::Compute(
                    SsiError::Tolerance(_)
                        | SsiError::Parameter(..)
                        | SsiError::Empty
                        | SsiError::FaceIndex { .. }
                        | SsiError::Input(_)
                )
        )
    }
}

/// Output files of the job.
#[derive(Clone, Copy, Debug, Default)]
pub struct Outputs<'a> {
    pub json: Option<&'a Path>,
    /// Branches as polylines (cell arrays `pair`, `branch`, `closed`, `dist_max`), the
    /// tangential points, and the intersected faces sampled on a grid.
    pub vtk: Option<&'a Path>,
    /// The fitted cubic of every branch as IGES 126 curves.
    pub iges: Option<&'a Path>,
    /// Keep every branch's fitted cubic (`fit`: knots and control points in 3D and in both
    /// domains, about three control points per branch point) in the returned result and the
    /// JSON. Off by default: the fits repeat the points' information at four times its size
    /// (they are always in the IGES output).
    pub fits: bool,
    /// A picture of the result: faces shaded, branches coloured by certificate
    /// ([`super::picture`]), seen along `view`.
    pub svg: Option<&'a Path>,
    pub view: crate::io::picture::View,
}

/// Fail before the work when an output cannot be written.
fn check_writable<'a>(paths: impl IntoIterator<Item = Option<&'a Path>>) -> Result<(), JobError> {
    crate::io::check_all_writable(paths)
        .map_err(|(p, e)| JobError::Write(p.display().to_string(), e.to_string()))
}

/// Write through a temporary file and a rename: a failed write keeps the previous file.
/// A result as readable JSON ([`crate::io::json_text`]), streamed to the file.
fn write_json<T: serde::Serialize>(path: &Path, v: &T) -> Result<(), JobError> {
    crate::io::json_text::write_file(path, v)
        .map_err(|e| JobError::Write(path.display().to_string(), e.to_string()))
}

fn write(path: &Path, text: &str) -> Result<(), JobError> {
    crate::io::write_atomic(path, text)
        .map_err(|e| JobError::Write(path.display().to_string(), e.to_string()))
}

/// The result as VTK PolyData.
pub fn to_vtp(r: &SsiResult, a: &Model, b: Option<&Model>) -> String {
    let mut p = PolyData::default();
    let mut face = Vec::new();
    let mut faces_done = std::collections::BTreeSet::new();
    for pair in &r.pairs {
        for (m, i, tag) in [(a, pair.a, 0usize), (b.unwrap_or(a), pair.b, 1usize)] {
            let key = (if b.is_some() { tag } else { 0 }, i);
            if faces_done.insert(key)
                && let Some(s) = m.surfaces.get(i)
            {
                let n = p.add_surface(&s.nurbs, 24);
                face.extend(std::iter::repeat_n(i as f64, n));
            }
        }
    }
    let polys = p.polys.len();
    let (mut pair_id, mut branch_id, mut closed, mut dist) =
        (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for (k, pair) in r.pairs.iter().enumerate() {
        for (j, br) in pair.branches.iter().enumerate() {
            let mut pts = br.points.clone();
            if br.closed && !pts.is_empty() {
                pts.push(pts[0]);
            }
            p.add_polyline(&pts);
            pair_id.push(k as f64);
            branch_id.push(j as f64);
            closed.push(br.closed as u8 as f64);
            dist.push(br.dist_a_max.max(br.dist_b_max));
        }
    }
    let pad = |v: Vec<f64>, fill: f64| {
        let mut w = vec![fill; polys];
        w.extend(v);
        w
    };
    let lines = pair_id.len();
    face.extend(std::iter::repeat_n(-1.0, lines));
    p.cell_data = vec![
        Array {
            name: "face".into(),
            values: face,
        },
        Array {
            name: "pair".into(),
            values: pad(pair_id, -1.0),
        },
        Array {
            name: "branch".into(),
            values: pad(branch_id, -1.0),
        },
        Array {
            name: "closed".into(),
            values: pad(closed, -1.0),
        },
        Array {
            name: "dist_max".into(),
            values: pad(dist, -1.0),
        },
    ];
    render(&p)
}

/// The fitted branches as a model of space curves.
pub fn curves_model(r: &SsiResult) -> Model {
    let mut m = Model::default();
    for (k, pair) in r.pairs.iter().enumerate() {
        for (j, br) in pair.branches.iter().enumerate() {
            if let Some(f) = &br.fit
                && let Ok(c) = NurbsCurve::new(
                    f.knots.clone(),
                    f.degree,
                    f.control_points.clone(),
                    vec![1.0; f.control_points.len()],
                )
            {
                m.curves.push(Curve {
                    name: format!("ssi pair {k} ({}, {}) branch {j}", pair.a, pair.b),
                    geometry: CurveGeometry::Space(c),
                });
            }
        }
    }
    m
}

/// Run the job.
pub fn run(
    file_a: &Path,
    file_b: Option<&Path>,
    prm: &SsiParams,
    threads: Option<usize>,
    outputs: Outputs,
) -> Result<SsiResult, JobError> {
    let a = read_in_range(file_a)?;
    let b = match file_b {
        Some(f) => Some(read_in_range(f)?),
        None => None,
    };
    check_writable([outputs.json, outputs.vtk, outputs.iges, outputs.svg])?;
    let t0 = Instant::now();
    let last = std::sync::Mutex::new(0.0f64);
    let progress = |done: usize, total: usize| {
        let el = t0.elapsed().as_secs_f64();
        if let Ok(mut l) = last.lock()
            && el > 1.0
            && (el - *l >= 1.0 || done == total)
        {
            *l = el;
            eprintln!("ssi: {done}/{total} face pairs ({el:.1} s)");
        }
    };
    // Inside a long face pair too, at most once a second.
    let mut prm = prm.clone();
    if prm.control.progress.is_none() {
        let last = std::sync::Mutex::new(0.0f64);
        prm.control.progress = Some(std::sync::Arc::new(move |s: &super::control::Stage| {
            let el = t0.elapsed().as_secs_f64();
            if let Ok(mut l) = last.lock()
                && el > 1.0
                && el - *l >= 1.0
            {
                *l = el;
                eprintln!(
                    "ssi: faces ({}, {}): {} {}/{} ({el:.1} s)",
                    s.pair.0, s.pair.1, s.step, s.done, s.total
                );
            }
        }));
    }
    let prm = &prm;
    let mut builder = rayon::ThreadPoolBuilder::new();
    if let Some(n) = threads {
        builder = builder.num_threads(n);
    }
    let pool = builder
        .build()
        .map_err(|e| JobError::Threads(e.to_string()))?;
    let mut r = pool.install(|| intersect_models(&a, b.as_ref(), prm, &progress))?;
    if let Some(p) = outputs.vtk {
        write(p, &to_vtp(&r, &a, b.as_ref()))?;
    }
    if let Some(p) = outputs.svg {
        write(
            p,
            &super::picture::picture(&r, &a, b.as_ref(), &outputs.view),
        )?;
    }
    if let Some(p) = outputs.iges {
        write(
            p,
            &crate::io::iges::write::to_string(&curves_model(&r), "vericad ssi"),
        )?;
    }
    if !outputs.fits {
        for br in r.pairs.iter_mut().flat_map(|p| p.branches.iter_mut()) {
            br.fit = None;
        }
    }
    if let Some(p) = outputs.json {
        write_json(p, &r)?;
    }
    Ok(r)
}

impl std::fmt::Display for SsiResult {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let s = &self.summary;
        writeln!(f, "surface-surface intersection, tol {:e}", s.tol)?;
        writeln!(
            f,
            "  faces: {} x {}; pairs considered {}, culled by bounds {}, intersected {}, with curves {}",
            s.faces_a,
            s.faces_b,
            s.pairs_considered,
            s.pairs_culled_by_bounds,
            s.pairs_intersected,
            s.pairs_with_branches
        )?;
        writeln!(
            f,
            "  branches: {} ({} closed), {} points; largest proven distance to a surface {:.3e}, to the curve {} ({})",
            s.branches,
            s.closed_branches,
            s.points,
            s.dist_max,
            match s.dist_curve_max {
                Some(d) => format!("{d:.3e}"),
                None => format!("unproven at {} points", s.points_curve_uncertified),
            },
            if s.all_points_within_tol {
                "all within tol of the curve"
            } else {
                "NOT all proven within tol of the curve"
            }
        )?;
        if s.singular_points_proven + s.singular_points_uncertified > 0 {
            writeln!(
                f,
                "  singular points: {} proven (touching or branch point), {} uncertified",
                s.singular_points_proven, s.singular_points_uncertified
            )?;
        }
        for p in self
            .pairs
            .iter()
            .filter(|p| !p.branches.is_empty() || !p.touch_points.is_empty())
        {
            writeln!(
                f,
                "  faces ({}, {}): {} branches, {} tangential points, {} + {} triangles, {:.3} s",
                p.a,
                p.b,
                p.branches.len(),
                p.touch_points.len(),
                p.stats.triangles_a,
                p.stats.triangles_b,
                p.stats.seconds
            )?;
            for (j, b) in p.branches.iter().enumerate() {
                writeln!(
                    f,
                    "    branch {j}: {}, {} points, proven dist {:.2e} / {:.2e}, to the curve {}, ends: {}",
                    if b.closed { "closed" } else { "open" },
                    b.points.len(),
                    b.dist_a_max,
                    b.dist_b_max,
                    match (b.dist_curve_max, b.curve_cert.len()) {
                        (Some(d), 0) => format!("{d:.2e}"),
                        (Some(d), n) => format!("{d:.2e} ({n} by sign change at a branch point)"),
                        (None, _) => format!("unproven at {} points", b.curve_uncertified_points),
                    },
                    if b.ends.is_empty() {
                        "none".to_string()
                    } else {
                        b.ends
                            .iter()
                            .map(|e| e.as_str())
                            .collect::<Vec<_>>()
                            .join(", ")
                    }
                )?;
            }
            for (j, t) in p.touch_points.iter().enumerate() {
                let Some(s) = &t.singular else { continue };
                let at = format!("({:.6}, {:.6}, {:.6})", t.point[0], t.point[1], t.point[2]);
                let what = match (s.kind, s.reason) {
                    (SingularKind::TouchingPoint, _) => "touching point, proven".to_string(),
                    (SingularKind::BranchPoint, _) => "branch point, proven".to_string(),
                    (SingularKind::Uncertified, Some(r)) => format!("uncertified ({})", r.as_str()),
                    (SingularKind::Uncertified, None) => "uncertified".to_string(),
                };
                let dist = s
                    .distance
                    .map(|d| format!(", distance at the root ≤ {:.1e}", d[1]))
                    .unwrap_or_default();
                writeln!(
                    f,
                    "    singular point {j} at {at}: {what}{dist}, {} branch ends",
                    t.branch_ends
                )?;
            }
        }
        for p in &self.pairs {
            let Some(c) = &p.tangent_contact else {
                continue;
            };
            let n = c.points.len();
            let at = |k: usize| match c.points.get(k) {
                Some(q) => format!("({:.6}, {:.6}, {:.6})", q[0], q[1], q[2]),
                None => "(not listed)".to_string(),
            };
            writeln!(
                f,
                "  faces ({}, {}): TANGENT CONTACT along a curve (measured): {} points from {} to {}, normals' sine <= {:.1e}, gap <= {:.1e}; {} tangential points and {} uncertified branches moved into it",
                p.a,
                p.b,
                n + c.points_not_listed(),
                at(0),
                at(n.saturating_sub(1)),
                c.max_sin_angle,
                c.max_gap,
                c.touch_points_moved,
                c.branches_moved
            )?;
        }
        let cov: Vec<_> = self
            .pairs
            .iter()
            .filter_map(|p| p.coverage.as_ref())
            .collect();
        if !cov.is_empty() {
            let (pairs, free, near, tube, tr, unc) = cov.iter().fold((0, 0, 0, 0, 0, 0), |a, c| {
                (
                    a.0 + c.pairs,
                    a.1 + c.free,
                    a.2 + c.near_output,
                    a.3 + c.near_shared_edges,
                    a.4 + c.transversal,
                    a.5 + c.uncertified,
                )
            });
            let tube = if tube > 0 {
                format!(", {tube} in the tube around a shared edge")
            } else {
                String::new()
            };
            writeln!(
                f,
                "  coverage: {pairs} parameter-box pairs: {free} proven free, {near} within the match distance of the output{tube}, {tr} transversal with every border crossing near the output, {unc} uncertified"
            )?;
        }
        if s.partial {
            writeln!(
                f,
                "  PARTIAL RESULT: time limit reached, {} pairs not run",
                s.pairs_not_run
            )?;
        }
        for c in &s.certificate {
            writeln!(f, "  - {c}")?;
        }
        writeln!(f, "  time {:.3} s", s.seconds)
    }
}

/// Progress on stderr for runs over a second (at most once a second, and at the end).
fn progress_printer(what: &'static str, t0: Instant) -> impl Fn(usize, usize) + Sync {
    let last = std::sync::Mutex::new(0.0f64);
    move |done: usize, total: usize| {
        let el = t0.elapsed().as_secs_f64();
        if el > 1.0
            && let Ok(mut l) = last.lock()
            && (el - *l >= 1.0 || done == total)
            && *l < el
        {
            *l = el;
            eprintln!("certify-ssi: {done}/{total} {what} ({el:.1} s)");
        }
    }
}

/// The `certify-ssi` job: a foreign result checked against faces of `file_a` and `file_b`
/// (`None`: every pair of distinct faces of `file_a`), and vericad's own branches of the
/// same faces checked for presence in it. `--out` is checked writable before the work.
pub fn run_certify(
    file_a: &Path,
    file_b: Option<&Path>,
    curves: &Path,
    prm: &SsiParams,
    match_distance: Option<f64>,
    json_out: Option<&Path>,
) -> Result<super::foreign::CertifyReport, JobError> {
    prm.validate()?;
    let m = match_distance.unwrap_or(100.0 * prm.tol);
    if !(m > 0.0 && m.is_finite()) {
        return Err(JobError::Compute(SsiError::Parameter("match distance", m)));
    }
    let a = read_in_range(file_a)?;
    let b = match file_b {
        Some(f) => Some(read_in_range(f)?),
        None => None,
    };
    let foreign = super::foreign::read_foreign(curves).map_err(JobError::Foreign)?;
    check_writable([json_out])?;
    let t0 = Instant::now();
    let r = intersect_models(
        &a,
        b.as_ref(),
        prm,
        &progress_printer("face pairs (vericad ssi)", t0),
    )?;
    let rep = super::foreign::certify(
        &a,
        b.as_ref(),
        &foreign,
        &r,
        prm.tol,
        m,
        &progress_printer("foreign points", t0),
    );
    if let Some(p) = json_out {
        write_json(p, &rep)?;
    }
    Ok(rep)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Surface;
    use crate::spline::construct::bilinear;

    /// A face restriction can leave a tangent contact whose listed points all went to a
    /// shared edge while unlisted ones remain (occt-hammer.iges did: the report then
    /// indexed an empty polyline). The report names the count and says none is listed.
    #[test]
    fn a_contact_without_listed_points_is_reported() {
        let plane = |z0: f64, z1: f64| {
            let s = bilinear(
                [0.0, 0.0, z0],
                [1.0, 0.0, z0],
                [0.0, 1.0, z1],
                [1.0, 1.0, z1],
            );
            Surface::new("plane", s.expect("a finite bilinear patch"))
        };
        let m = Model {
            surfaces: vec![plane(0.0, 0.0), plane(-0.5, 0.5)],
            ..Default::default()
        };
        let mut r = intersect_models(&m, None, &SsiParams::default(), &|_, _| {})
            .expect("two crossing planes intersect");
        assert_eq!(r.pairs.len(), 1);
        r.pairs[0].tangent_contact = Some(super::super::tangent_contact::TangentContactOut {
            unlisted: vec![([0.0; 3], [0.0; 2], [0.0; 2]); 7],
            ..Default::default()
        });
        let text = r.to_string();
        assert!(
            text.contains("TANGENT CONTACT along a curve (measured): 7 points from (not listed)"),
            "{text}"
        );
    }
}
