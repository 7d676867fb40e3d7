//! The `ssi` job: read one or two model files, intersect, write the JSON result and optional
//! VTK / IGES outputs, report progress on long runs.

mod text_report;

use super::report::SsiResult;
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
    Threads(#[from] rayon::ThreadPoolBuildError),
    #[error("foreign curves: {0}")]
    Foreign(#[from] super::foreign_read::ForeignError),
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
    /// Where progress lines go on runs over a second (default: nowhere).
    pub progress: crate::progress::Progress,
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
    let (mut pair_id, mut branch_id, mut closed, mut dist, mut border) =
        (Vec::new(), Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for (k, pair) in r.pairs.iter().enumerate() {
        for (j, br) in pair.branches.iter().enumerate() {
            // Cubic pieces drawn at 16 samples each (the points alone would be a coarse
            // polygon).
            p.add_polyline(&br.drawn(16));
            pair_id.push(k as f64);
            branch_id.push(j as f64);
            closed.push(br.closed as u8 as f64);
            dist.push(br.dist_a_max.max(br.dist_b_max));
            border.push(0.0);
        }
        // Common borders: `common_border` 1 exact, 2 within a gap; their index as `branch`.
        for (j, c) in pair.common_borders.iter().enumerate() {
            p.add_polyline(&c.points);
            pair_id.push(k as f64);
            branch_id.push(j as f64);
            closed.push(0.0);
            dist.push(c.dist_a_max.max(c.dist_b_max));
            border.push(if c.exact { 1.0 } else { 2.0 });
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
        Array {
            name: "common_border".into(),
            values: pad(border, -1.0),
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
            outputs
                .progress
                .say(|| format!("ssi: {done}/{total} face pairs ({el:.1} s)"));
        }
    };
    // Inside a long face pair too, at most once a second.
    let mut prm = prm.clone();
    // The cubic fits only where an output holds them.
    prm.fits = outputs.fits || outputs.iges.is_some();
    if prm.control.progress.is_none()
        && let Some(say) = outputs.progress.0
    {
        let last = std::sync::Mutex::new(0.0f64);
        prm.control.progress = Some(std::sync::Arc::new(move |s: &super::control::Stage| {
            let el = t0.elapsed().as_secs_f64();
            if let Ok(mut l) = last.lock()
                && el > 1.0
                && el - *l >= 1.0
            {
                *l = el;
                say(&format!(
                    "ssi: faces ({}, {}): {} {}/{} ({el:.1} s)",
                    s.pair.0, s.pair.1, s.step, s.done, s.total
                ));
            }
        }));
    }
    let prm = &prm;
    let mut builder = rayon::ThreadPoolBuilder::new();
    if let Some(n) = threads {
        builder = builder.num_threads(n);
    }
    let pool = builder.build()?;
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

/// Progress lines to `say` for runs over a second (at most once a second, and at the end).
fn progress_printer(
    what: &'static str,
    t0: Instant,
    say: crate::progress::Progress,
) -> impl Fn(usize, usize) + Sync {
    let last = std::sync::Mutex::new(0.0f64);
    move |done: usize, total: usize| {
        let el = t0.elapsed().as_secs_f64();
        if el > 1.0
            && let Ok(mut l) = last.lock()
            && (el - *l >= 1.0 || done == total)
            && *l < el
        {
            *l = el;
            say.say(|| format!("certify-ssi: {done}/{total} {what} ({el:.1} s)"));
        }
    }
}

/// The `certify-ssi` job: a foreign result checked against faces of `file_a` and `file_b`
/// (`None`: every pair of distinct faces of `file_a`), and vericad's own branches of the
/// same faces checked for presence in it. `--out` is checked writable before the work;
/// progress lines go to `progress` on runs over a second.
pub fn run_certify(
    file_a: &Path,
    file_b: Option<&Path>,
    curves: &Path,
    prm: &SsiParams,
    match_distance: Option<f64>,
    (json_out, progress): (Option<&Path>, crate::progress::Progress),
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
    let foreign = super::foreign::read_foreign(curves, prm.tol)?;
    check_writable([json_out])?;
    let t0 = Instant::now();
    // The check compares points; no fit is output.
    let prm = &SsiParams {
        fits: false,
        ..prm.clone()
    };
    let r = intersect_models(
        &a,
        b.as_ref(),
        prm,
        &progress_printer("face pairs (vericad ssi)", t0, progress),
    )?;
    let rep = super::foreign::certify(
        &a,
        b.as_ref(),
        &foreign,
        &r,
        prm.tol,
        m,
        &progress_printer("foreign points", t0, progress),
    );
    if let Some(p) = json_out {
        write_json(p, &rep)?;
    }
    Ok(rep)
}
