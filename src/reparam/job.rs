//! The `reparam` job: read a model, reparametrize one face (`FILE:INDEX`) or every face,
//! write the new surfaces (format by extension), a JSON report, an SVG and a VTK view.
//! Output paths are checked writable before the work.

use super::{FaceReport, Params, ReparamError, plot, reparametrize_with_progress};
use crate::model::{Model, Surface, SurfaceKind};
use serde::Serialize;
use std::path::Path;

/// Errors of the job.
#[derive(Debug, thiserror::Error)]
pub enum JobError {
    #[error(transparent)]
    Read(#[from] crate::io::ReadError),
    #[error("{0}: {1}")]
    Select(String, String),
    /// The parameters (ε ≤ 0 or NaN, ...) or the one selected face cannot be treated.
    #[error("face {face}: {source}")]
    Reparam { face: usize, source: ReparamError },
    #[error("parameters: {0}")]
    Params(ReparamError),
    #[error("cannot write {0}: {1}")]
    Write(String, String),
}

impl JobError {
    /// Whether the user's input is at fault (exit code 2) rather than writing an output.
    pub fn is_bad_input(&self) -> bool {
        !matches!(self, JobError::Write(..))
    }
}

/// Optional outputs.
#[derive(Clone, Copy, Debug, Default)]
pub struct Outputs<'a> {
    /// The new surfaces (`.igs`, `.step`, `.json`).
    pub model: Option<&'a Path>,
    pub report: Option<&'a Path>,
    pub svg: Option<&'a Path>,
    pub vtk: Option<&'a Path>,
    /// Where progress lines go on runs over a second (default: nowhere).
    pub progress: crate::progress::Progress,
}

/// One face's entry in the report: its report, or why it was not reparametrized.
#[derive(Clone, Debug, Serialize)]
pub struct FaceEntry {
    pub index: usize,
    pub name: String,
    pub source: Option<String>,
    pub kind: SurfaceKind,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub result: Option<FaceReport>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub error: Option<String>,
}

/// The job's report.
#[derive(Clone, Debug, Serialize)]
pub struct JobReport {
    pub file: String,
    pub params: Params,
    pub faces: Vec<FaceEntry>,
    /// Every face reparametrized with `E_max ≤ ε` (measured, evidence) and a converged
    /// relaxation.
    pub within_tol: bool,
    pub warnings: Vec<String>,
    pub seconds: f64,
}

/// `FILE[:INDEX]`: the path and the face index, if any.
pub fn file_and_face(spec: &str) -> (String, Option<usize>) {
    if let Some((f, i)) = spec.rsplit_once(':')
        && let Ok(i) = i.parse::<usize>()
    {
        return (f.to_string(), Some(i));
    }
    (spec.to_string(), None)
}

fn write(path: &Path, text: impl AsRef<[u8]>) -> Result<(), JobError> {
    crate::io::write_atomic(path, text)
        .map_err(|e| JobError::Write(path.display().to_string(), e.to_string()))
}

/// Run the job on `spec` (`FILE` or `FILE:FACE`).
pub fn run(spec: &str, params: &Params, out: Outputs) -> Result<JobReport, JobError> {
    params.validate().map_err(JobError::Params)?;
    crate::io::check_all_writable([out.model, out.report, out.svg, out.vtk])
        .map_err(|(p, e)| JobError::Write(p.display().to_string(), e.to_string()))?;
    use crate::io::Format;
    if let Some(p) = out.model
        && !matches!(
            crate::io::format_of(p),
            Some(Format::Iges | Format::Step | Format::Json)
        )
    {
        return Err(JobError::Select(
            p.display().to_string(),
            "unknown output type (expected .igs/.iges, .step/.stp, .json)".into(),
        ));
    }
    let (file, face) = file_and_face(spec);
    let model = crate::io::read_model(Path::new(&file))?;
    let indices: Vec<usize> = match face {
        Some(i) if i < model.surfaces.len() => vec![i],
        Some(i) => {
            return Err(JobError::Select(
                file,
                format!("no face {i} (the file has {})", model.surfaces.len()),
            ));
        }
        None if model.surfaces.is_empty() => {
            return Err(JobError::Select(file, "the file has no faces".into()));
        }
        None => (0..model.surfaces.len()).collect(),
    };
    let t0 = std::time::Instant::now();
    let mut warnings = vec![];
    let mut faces = vec![];
    let mut done: Vec<(usize, super::Reparametrized)> = vec![];
    for (count, &k) in indices.iter().enumerate() {
        let f = &model.surfaces[k];
        let mut progress = |stage: &str, n: usize| {
            if t0.elapsed().as_secs_f64() > 1.0 {
                out.progress.say(|| {
                    format!(
                        "[{:>7.1} s] face {k} ({}/{}): {stage} {n}",
                        t0.elapsed().as_secs_f64(),
                        count + 1,
                        indices.len()
                    )
                });
            }
        };
        let mut entry = FaceEntry {
            index: k,
            name: f.name.clone(),
            source: f.source.clone(),
            kind: f.kind,
            result: None,
            error: None,
        };
        match reparametrize_with_progress(&f.nurbs, params, &mut progress) {
            Ok(r) => {
                if !f.trim_loops.is_empty() {
                    warnings.push(format!(
                        "face {k}: its {} trimming loop(s) are not carried over: the new surface covers the whole domain of the face's surface",
                        f.trim_loops.len()
                    ));
                }
                entry.result = Some(r.report.clone());
                done.push((k, r));
            }
            Err(e) if face.is_some() => return Err(JobError::Reparam { face: k, source: e }),
            Err(e) => entry.error = Some(e.to_string()),
        }
        faces.push(entry);
    }
    let within_tol = faces
        .iter()
        .all(|f| f.result.as_ref().is_some_and(|r| r.within_tol));
    if let Some(p) = out.model {
        let m = Model {
            unit: model.unit.clone(),
            surfaces: done
                .iter()
                .map(|(k, r)| Surface {
                    name: model.surfaces[*k].name.clone(),
                    nurbs: r.surface.clone(),
                    source: model.surfaces[*k].source.clone(),
                    kind: SurfaceKind::BSpline,
                    trim_loops: vec![],
                    reversed: model.surfaces[*k].reversed,
                })
                .collect(),
            ..Default::default()
        };
        let w = crate::io::write_model(p, &m).map_err(|e| match e {
            crate::io::WriteError::Io(f, e) => JobError::Write(f, e.to_string()),
            e => JobError::Write(p.display().to_string(), e.to_string()),
        })?;
        warnings.extend(w);
    }
    let n = params.quality_grid;
    if let Some(p) = out.svg {
        let panels: Vec<plot::Panel> = done
            .iter()
            .map(|(k, r)| plot::Panel {
                given: &model.surfaces[*k].nurbs,
                new: &r.surface,
                titles: [
                    format!(
                        "face {k} given: spacing ratio {:.3}..{:.3}",
                        r.report.spacing_before.min, r.report.spacing_before.max
                    ),
                    format!(
                        "reparametrized: {:.3}..{:.3}, E_max {:.2e}",
                        r.report.spacing_after.min,
                        r.report.spacing_after.max,
                        r.report.deviation.e_max
                    ),
                ],
            })
            .collect();
        write(p, plot::svg(&panels, n))?;
    }
    if let Some(p) = out.vtk {
        let faces: Vec<_> = done
            .iter()
            .map(|(k, r)| (*k, &model.surfaces[*k].nurbs, &r.surface))
            .collect();
        write(p, plot::vtk(&faces, n))?;
    }
    let report = JobReport {
        file,
        params: params.clone(),
        faces,
        within_tol,
        warnings,
        seconds: t0.elapsed().as_secs_f64(),
    };
    if let Some(p) = out.report {
        crate::io::json_text::write_file(p, &report)
            .map_err(|e| JobError::Write(p.display().to_string(), e.to_string()))?;
    }
    Ok(report)
}

impl std::fmt::Display for JobReport {
    fn fmt(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        writeln!(f, "reparam {} (ε = {:e})", self.file, self.params.tol)?;
        writeln!(
            f,
            "{:>5}  {:<10} {:>17} {:>17} {:>10} {:>10} {:>9} {:>7}  status",
            "face", "kind", "spacing before", "spacing after", "E_max", "proven", "ctrl", "s"
        )?;
        for e in &self.faces {
            match (&e.result, &e.error) {
                (Some(r), _) => writeln!(
                    f,
                    "{:>5}  {:<10} {:>8.3}..{:<7.3} {:>8.4}..{:<7.4} {:>10.3e} {:>10} {:>4}x{:<4} {:>7.2}  {}",
                    e.index,
                    format!("{:?}", e.kind),
                    r.spacing_before.min,
                    r.spacing_before.max,
                    r.spacing_after.min,
                    r.spacing_after.max,
                    r.deviation.e_max,
                    r.deviation
                        .e_max_proven
                        .map_or("—".to_string(), |b| format!("{b:.3e}")),
                    r.control_points_after[0],
                    r.control_points_after[1],
                    r.seconds,
                    if r.within_tol_proven {
                        "E_max ≤ ε (proven)"
                    } else if r.within_tol {
                        "E_max ≤ ε (measured only; not proven)"
                    } else if !r.relaxation.converged {
                        "relaxation not converged"
                    } else {
                        "ε not reached"
                    }
                )?,
                (None, err) => writeln!(
                    f,
                    "{:>5}  {:<10} not reparametrized: {}",
                    e.index,
                    format!("{:?}", e.kind),
                    err.as_deref().unwrap_or("")
                )?,
            }
        }
        for w in &self.warnings {
            writeln!(f, "warning: {w}")?;
        }
        writeln!(
            f,
            "{} ({:.2} s)",
            if self.within_tol {
                "every face within ε (proven or at the samples: see status)"
            } else {
                "not every face within ε"
            },
            self.seconds
        )
    }
}
