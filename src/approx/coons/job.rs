//! The `coons` job: read a model and a boundary file, build one approximant, write the
//! surface (format by extension), a JSON report and a VTK view. Output paths are checked
//! writable before the work.

use super::boundary::BoundarySpec;
use super::{Approximant, CoonsError, Params, Report, approximate_with_progress};
use crate::io::vtk::{Array, PolyData};
use crate::model::{Model, Surface};
use crate::spline::NurbsSurface;
use serde::Serialize;
use std::path::Path;

/// Errors of the job.
#[derive(Debug, thiserror::Error)]
pub enum JobError {
    #[error(transparent)]
    Read(#[from] crate::io::ReadError),
    #[error("{0}: {1}")]
    Boundary(String, CoonsError),
    #[error("{0}")]
    Coons(CoonsError),
    #[error("cannot read {0}: {1}")]
    ReadBoundary(String, String),
    #[error("{0}: {1}")]
    Output(String, String),
    #[error("cannot write {0}: {1}")]
    Write(String, String),
}

impl JobError {
    /// Whether the user's input is at fault (exit code 2).
    pub fn is_bad_input(&self) -> bool {
        match self {
            JobError::Write(..) => false,
            JobError::Coons(e) => !matches!(e, CoonsError::NotFinite(_) | CoonsError::Spline(_)),
            _ => true,
        }
    }
}

/// Optional outputs (of `coons` and of `approximate`).
#[derive(Clone, Copy, Debug, Default)]
pub struct Outputs<'a> {
    /// The approximant(s) (`.igs`, `.step`, `.json`).
    pub model: Option<&'a Path>,
    pub report: Option<&'a Path>,
    pub vtk: Option<&'a Path>,
    /// Where progress lines go on runs over a second (default: nowhere).
    pub progress: crate::progress::Progress,
}

/// An output that cannot be written: its path, why, and whether its type is the fault.
pub(super) struct OutputFault {
    pub path: String,
    pub why: String,
    pub unknown_type: bool,
}

impl OutputFault {
    fn write(path: &Path, why: impl std::fmt::Display) -> Self {
        OutputFault {
            path: path.display().to_string(),
            why: why.to_string(),
            unknown_type: false,
        }
    }
}

impl From<OutputFault> for JobError {
    fn from(f: OutputFault) -> Self {
        if f.unknown_type {
            JobError::Output(f.path, f.why)
        } else {
            JobError::Write(f.path, f.why)
        }
    }
}

impl Outputs<'_> {
    /// Before the work: every output writable, the surfaces' file of a type that holds them.
    pub(super) fn check(&self) -> Result<(), OutputFault> {
        crate::io::check_all_writable([self.model, self.report, self.vtk])
            .map_err(|(p, e)| OutputFault::write(p, e))?;
        use crate::io::Format;
        if let Some(p) = self.model
            && !matches!(
                crate::io::format_of(p),
                Some(Format::Iges | Format::Step | Format::Json)
            )
        {
            return Err(OutputFault {
                path: p.display().to_string(),
                why: "unknown output type (expected .igs/.iges, .step/.stp, .json)".into(),
                unknown_type: true,
            });
        }
        Ok(())
    }

    /// Write `surfaces` (in `unit`) to the model output, if any; the writer's notes. The
    /// shell `brep` goes to the formats that hold topology (STEP, IGES); the native JSON holds
    /// the surfaces only (docs/coons.md).
    pub(super) fn write_surfaces(
        &self,
        unit: Option<String>,
        surfaces: Vec<Surface>,
        brep: Option<crate::brep::Brep>,
    ) -> Result<Vec<String>, OutputFault> {
        let Some(p) = self.model else {
            return Ok(vec![]);
        };
        let brep = brep.filter(|_| {
            matches!(
                crate::io::format_of(p),
                Some(crate::io::Format::Step | crate::io::Format::Iges)
            )
        });
        let m = Model {
            unit,
            surfaces,
            brep,
            ..Default::default()
        };
        crate::io::write_model(p, &m).map_err(|e| match e {
            crate::io::WriteError::Io(f, e) => OutputFault {
                path: f,
                why: e.to_string(),
                unknown_type: false,
            },
            e => OutputFault::write(p, e),
        })
    }

    /// Write the VTK view, if asked for (`view` makes it).
    pub(super) fn write_vtk(&self, view: impl FnOnce() -> String) -> Result<(), OutputFault> {
        match self.vtk {
            Some(p) => crate::io::write_atomic(p, view()).map_err(|e| OutputFault::write(p, e)),
            None => Ok(()),
        }
    }

    /// Write the JSON report, if asked for.
    pub(super) fn write_report<T: serde::Serialize>(&self, r: &T) -> Result<(), OutputFault> {
        let Some(p) = self.report else {
            return Ok(());
        };
        crate::io::json_text::write_file(p, r).map_err(|e| OutputFault::write(p, e))
    }
}

/// The job's report.
#[derive(Clone, Debug, Serialize)]
pub struct JobReport {
    pub file: String,
    pub boundary: String,
    /// The model's length unit, if the file names one.
    pub unit: Option<String>,
    pub approximant: Report,
    /// The error samples (17): `[ξ, η, distance]`, distance `null` over a gap.
    pub samples: Vec<(f64, f64, Option<f64>)>,
    pub warnings: Vec<String>,
}

/// Run the job.
pub fn run(
    model_path: &Path,
    boundary_path: &Path,
    params: &Params,
    out: Outputs,
) -> Result<JobReport, JobError> {
    run_surface(model_path, boundary_path, params, out).map(|(r, _)| r)
}

/// Run the job; returns the report and the approximant.
pub fn run_surface(
    model_path: &Path,
    boundary_path: &Path,
    params: &Params,
    out: Outputs,
) -> Result<(JobReport, NurbsSurface<f64, 3>), JobError> {
    params.validate().map_err(JobError::Coons)?;
    out.check()?;
    let bfile = boundary_path.display().to_string();
    let text = std::fs::read_to_string(boundary_path)
        .map_err(|e| JobError::ReadBoundary(bfile.clone(), e.to_string()))?;
    let spec = BoundarySpec::parse(&text).map_err(|e| JobError::Boundary(bfile.clone(), e))?;
    let model = crate::io::read_model(model_path)?;
    let t0 = std::time::Instant::now();
    let mut progress = |stage: &str, k: usize| {
        if t0.elapsed().as_secs_f64() > 1.0 {
            out.progress
                .say(|| format!("[{:>7.1} s] {stage} {k}", t0.elapsed().as_secs_f64()));
        }
    };
    let ap =
        approximate_with_progress(&model, &spec, params, &mut progress).map_err(|e| match e {
            e @ (CoonsError::Boundary(_) | CoonsError::Curve { .. }) => {
                JobError::Boundary(bfile.clone(), e)
            }
            e => JobError::Coons(e),
        })?;
    let mut warnings = model.warnings.clone();
    warnings.extend(ap.report.warnings.iter().cloned());
    warnings.extend(out.write_surfaces(
        model.unit.clone(),
        vec![Surface::new("coons approximant", ap.surface.clone())],
        None,
    )?);
    out.write_vtk(|| view(&ap))?;
    let report = JobReport {
        file: model_path.display().to_string(),
        boundary: bfile,
        unit: model.unit.clone(),
        samples: ap
            .samples
            .iter()
            .map(|s| (s.param[0], s.param[1], s.distance))
            .collect(),
        approximant: ap.report,
        warnings,
    };
    out.write_report(&report)?;
    Ok((report, ap.surface))
}

/// The VTK view: the approximant (quads, `part` 0), the projected points as small
/// crosses (`part` 1 found, 2 artificial), the error samples (`part` 3 measured with
/// `error` = distance, 4 skipped over a gap).
pub fn view(ap: &Approximant) -> String {
    let mut p = PolyData::default();
    let k = (4 * ap.report.m.max(ap.report.n)).clamp(16, 256);
    let cells = p.add_surface(&ap.surface, k);
    let mut part = vec![0.0; cells];
    let mut err = vec![0.0; cells];
    let size = {
        let d = &ap.coons;
        crate::geom::dist(d.at(0, 0), d.at(d.m, d.n)) / (4.0 * (d.m + d.n) as f64)
    };
    let mut cross = |p: &mut PolyData, c: [f64; 3], tag: f64, e: f64| {
        for ax in 0..3 {
            let mut lo = c;
            let mut hi = c;
            lo[ax] -= size;
            hi[ax] += size;
            p.add_polyline(&[lo, hi]);
            part.push(tag);
            err.push(e);
        }
    };
    for (q, art) in ap.points.data.iter().zip(&ap.artificial.data) {
        cross(&mut p, *q, if *art { 2.0 } else { 1.0 }, 0.0);
    }
    for s in &ap.samples {
        match s.distance {
            Some(d) => cross(&mut p, s.point, 3.0, d),
            None => cross(&mut p, s.point, 4.0, 0.0),
        }
    }
    p.cell_data.push(Array {
        name: "part".into(),
        values: part,
    });
    p.cell_data.push(Array {
        name: "error".into(),
        values: err,
    });
    crate::io::vtk::render(&p)
}

impl std::fmt::Display for JobReport {
    fn fmt(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        let r = &self.approximant;
        writeln!(
            f,
            "coons {} with boundary {} (tol {:e})",
            self.file, self.boundary, r.params.tol
        )?;
        writeln!(
            f,
            "{:>5} {:>5} {:>7} {:>8} {:>10} {:>9} {:>5}",
            "M", "N", "hits", "artif.", "max error", "measured", "gap"
        )?;
        for x in &r.rounds {
            writeln!(
                f,
                "{:>5} {:>5} {:>7} {:>8} {:>10.3e} {:>9} {:>5}",
                x.m, x.n, x.hits, x.artificial, x.max_error, x.measured, x.skipped_gap
            )?;
        }
        writeln!(
            f,
            "proven: interpolates the grid points: {}; boundary within {:.3e} of the boundary grid polylines",
            r.proven.interpolates_grid_points, r.proven.boundary_hull_bound
        )?;
        writeln!(
            f,
            "evidence: max error {:.3e} at {} samples ({} over gaps skipped, {} beyond a surface's border); multiquadric condition ≤ {:.2e}",
            r.evidence.max_error,
            r.evidence.measured,
            r.evidence.skipped_gap,
            r.evidence.at_edge,
            r.fill.max_condition
        )?;
        for w in &self.warnings {
            writeln!(f, "warning: {w}")?;
        }
        writeln!(f, "{} ({:.2} s)", r.reason, r.seconds)
    }
}
