//! The `approximate` job: read a model and a layout file, build every approximant, join
//! them along shared curves ([`super::join`]), write all surfaces in one file (format by
//! extension), a JSON report and a VTK view. Output paths are checked writable first.

use super::join::{SharedCurve, join};
use super::layout::{Layout, LayoutError, Topology, build_all, topology};
use super::{Approximant, Params, Report};
use crate::brep::Brep;
use crate::brep::sew::{BoundaryLoop, FaceBoundary, sew};
use crate::io::vtk::{Array, PolyData};
use crate::model::{Model, Surface};
use serde::Serialize;
use std::path::Path;

/// Errors of the job.
#[derive(Debug, thiserror::Error)]
pub enum ApproximateError {
    #[error(transparent)]
    Read(#[from] crate::io::ReadError),
    #[error("{0}: {1}")]
    Layout(String, LayoutError),
    #[error("{0}")]
    Params(super::CoonsError),
    #[error("cannot read {0}: {1}")]
    ReadLayout(String, String),
    #[error("{0}: {1}")]
    Output(String, String),
    #[error("cannot write {0}: {1}")]
    Write(String, String),
    #[error("join: {0}")]
    Join(super::CoonsError),
}

impl ApproximateError {
    /// Whether the user's input is at fault (exit code 2).
    pub fn is_bad_input(&self) -> bool {
        match self {
            ApproximateError::Write(..) | ApproximateError::Join(_) => false,
            ApproximateError::Layout(_, e) => e.is_bad_input(),
            _ => true,
        }
    }
}

pub use super::job::Outputs;

impl From<super::job::OutputFault> for ApproximateError {
    fn from(f: super::job::OutputFault) -> Self {
        if f.unknown_type {
            ApproximateError::Output(f.path, f.why)
        } else {
            ApproximateError::Write(f.path, f.why)
        }
    }
}

/// One approximant in the report.
#[derive(Clone, Debug, Serialize)]
pub struct Entry {
    pub name: String,
    pub m: usize,
    pub n: usize,
    /// Measured error at the samples (17) after the join: evidence.
    pub max_error: f64,
    pub within_tol: bool,
    pub reason: String,
    pub report: Report,
}

/// The job's report.
#[derive(Clone, Debug, Serialize)]
pub struct LayoutReport {
    pub file: String,
    pub layout: String,
    pub unit: Option<String>,
    pub approximants: Vec<Entry>,
    /// Shared curves: gap before the join, the move, identical bit for bit (checked).
    pub shared: Vec<SharedCurve>,
    /// Curves used by one approximant (the open boundary of the replacement).
    pub open_curves: Vec<String>,
    pub unused_curves: Vec<String>,
    /// Approximants rebuilt to make counts along shared curves equal.
    pub rebuilds: usize,
    /// The approximants as one open shell (written with the surfaces to STEP and IGES).
    pub shell: Option<ShellReport>,
    /// Every approximant within tol (evidence) and every shared row identical (checked).
    pub within_tol: bool,
    pub warnings: Vec<String>,
    pub seconds: f64,
}

/// The shell the approximants form: one face per approximant, bounded by its four border
/// curves; edges used by two faces (the shared curves) and by one (the open boundary).
#[derive(Clone, Debug, Serialize)]
pub struct ShellReport {
    pub faces: usize,
    pub shared_edges: usize,
    pub free_edges: usize,
    /// Edges used by more than two faces (none for a valid layout).
    pub other_edges: usize,
    /// The distance within which border curves were matched (1e-9 of the approximants'
    /// size: shared rows are identical, so they match exactly).
    pub tolerance: f64,
}

/// The approximants as one open shell: each a face bounded by its borders
/// ([`crate::spline::sides::sides`], counterclockwise in its parameter plane, so the face
/// normal is the surface's), sewn where two borders coincide ([`crate::brep::sew`]). The
/// join makes the shared rows identical bit for bit and settles shared corners on one
/// point, so every shared curve becomes one edge of two faces. `None` when a surface is not
/// clamped (never for an approximant: triple interior, quadruple end knots).
pub fn shell(aps: &[Approximant], name: impl Fn(usize) -> String) -> Option<(Brep, ShellReport)> {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for ap in aps {
        for h in &ap.surface.hom.net {
            for k in 0..3 {
                let x = h.wp[k] / h.w;
                lo[k] = lo[k].min(x);
                hi[k] = hi[k].max(x);
            }
        }
    }
    let size = crate::geom::dist(&lo, &hi);
    let tol = 1e-9
        * if size.is_finite() && size > 0.0 {
            size
        } else {
            1.0
        };
    let mut faces = Vec::with_capacity(aps.len());
    for (a, ap) in aps.iter().enumerate() {
        let sides = crate::spline::sides::sides(&ap.surface)?;
        let n = name(a);
        faces.push(FaceBoundary {
            source: format!("approximant {n}"),
            surface: a,
            surface_source: format!("approximant {n}"),
            loops: vec![BoundaryLoop {
                outer: true,
                source: format!("approximant {n} boundary"),
                curves: sides
                    .into_iter()
                    .enumerate()
                    .map(|(k, c)| (format!("approximant {n} side {k}"), c))
                    .collect(),
            }],
        });
    }
    let (mut brep, stats) = sew(&faces, tol);
    brep.tolerance = tol;
    let report = ShellReport {
        faces: brep.faces.len(),
        shared_edges: stats.shared,
        free_edges: stats.free,
        other_edges: stats.more,
        tolerance: tol,
    };
    Some((brep, report))
}

/// The approximants and the report, as [`run`] returns them.
pub struct Joined {
    pub approximants: Vec<Approximant>,
    pub report: LayoutReport,
}

/// The joined approximants, what the join did, the topology.
pub struct Replacement {
    /// In layout order.
    pub approximants: Vec<Approximant>,
    pub shared: Vec<SharedCurve>,
    pub topology: Topology,
    /// Approximants rebuilt to make counts along shared curves equal.
    pub rebuilds: usize,
}

/// Build and join the approximants of `layout` over `model` (the library entry point;
/// §3.7).
pub fn approximate_layout(
    model: &Model,
    layout: &Layout,
    params: &Params,
    progress: &mut dyn FnMut(&str, usize),
) -> Result<Replacement, LayoutError> {
    params.validate().map_err(|source| LayoutError::Coons {
        approximant: "(all)".into(),
        source,
    })?;
    let topo = topology(layout)?;
    let (mut aps, rebuilds) = build_all(model, layout, &topo, params, progress)?;
    let shared = join(model, &mut aps, &topo, params).map_err(|source| LayoutError::Coons {
        approximant: "(join)".into(),
        source,
    })?;
    Ok(Replacement {
        approximants: aps,
        shared,
        topology: topo,
        rebuilds,
    })
}

/// Run the job.
pub fn run(
    model_path: &Path,
    layout_path: &Path,
    params: &Params,
    out: Outputs,
) -> Result<Joined, ApproximateError> {
    params.validate().map_err(ApproximateError::Params)?;
    out.check()?;
    let lfile = layout_path.display().to_string();
    let text = std::fs::read_to_string(layout_path)
        .map_err(|e| ApproximateError::ReadLayout(lfile.clone(), e.to_string()))?;
    let layout = Layout::parse(&text).map_err(|e| ApproximateError::Layout(lfile.clone(), e))?;
    let model = crate::io::read_model(model_path)?;
    let t0 = std::time::Instant::now();
    let mut progress = |stage: &str, k: usize| {
        if t0.elapsed().as_secs_f64() > 1.0 {
            out.progress
                .say(|| format!("[{:>7.1} s] {stage} {k}", t0.elapsed().as_secs_f64()));
        }
    };
    let Replacement {
        approximants: aps,
        shared,
        topology: topo,
        rebuilds,
    } = approximate_layout(&model, &layout, params, &mut progress).map_err(|e| match e {
        LayoutError::Coons { source, .. } if !e.is_bad_input() => ApproximateError::Join(source),
        e => ApproximateError::Layout(lfile.clone(), e),
    })?;
    let mut warnings = model.warnings.clone();
    for ap in &aps {
        warnings.extend(ap.report.warnings.iter().cloned());
    }
    let (brep, shell_report) = match shell(&aps, |a| layout.name(a)) {
        Some((b, r)) => (Some(b), Some(r)),
        None => {
            warnings.push(
                "the approximants are written without a shell (a surface is not clamped)".into(),
            );
            (None, None)
        }
    };
    if let Some(r) = &shell_report
        && (r.shared_edges != shared.len() || r.free_edges != topo.open.len() || r.other_edges > 0)
    {
        warnings.push(format!(
            "the shell's edges do not match the layout: {} shared and {} free edges for {} shared and {} open curves ({} used by more than two faces)",
            r.shared_edges,
            r.free_edges,
            shared.len(),
            topo.open.len(),
            r.other_edges
        ));
    }
    warnings.extend(
        out.write_surfaces(
            model.unit.clone(),
            aps.iter()
                .enumerate()
                .map(|(a, ap)| Surface::new(layout.name(a), ap.surface.clone()))
                .collect(),
            brep,
        )?,
    );
    out.write_vtk(|| view(&aps))?;
    let entries: Vec<Entry> = aps
        .iter()
        .enumerate()
        .map(|(a, ap)| Entry {
            name: layout.name(a),
            m: ap.report.m,
            n: ap.report.n,
            max_error: ap.report.evidence.max_error,
            within_tol: ap.report.within_tol,
            reason: ap.report.reason.clone(),
            report: ap.report.clone(),
        })
        .collect();
    let report = LayoutReport {
        file: model_path.display().to_string(),
        layout: lfile,
        unit: model.unit.clone(),
        within_tol: entries.iter().all(|e| e.within_tol) && shared.iter().all(|s| s.identical),
        approximants: entries,
        shared,
        open_curves: topo.open,
        unused_curves: topo.unused,
        rebuilds,
        shell: shell_report,
        warnings,
        seconds: t0.elapsed().as_secs_f64(),
    };
    out.write_report(&report)?;
    Ok(Joined {
        approximants: aps,
        report,
    })
}

/// The VTK view: every approximant as quads, cell data `approximant` (its index) and
/// `error` (0 on the surfaces).
pub fn view(aps: &[Approximant]) -> String {
    let mut p = PolyData::default();
    let mut which = Vec::new();
    for (a, ap) in aps.iter().enumerate() {
        let k = (4 * ap.report.m.max(ap.report.n)).clamp(16, 256);
        let cells = p.add_surface(&ap.surface, k);
        which.extend(std::iter::repeat_n(a as f64, cells));
    }
    p.cell_data.push(Array {
        name: "approximant".into(),
        values: which,
    });
    crate::io::vtk::render(&p)
}

impl std::fmt::Display for LayoutReport {
    fn fmt(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        writeln!(f, "approximate {} with layout {}", self.file, self.layout)?;
        writeln!(
            f,
            "{:>16} {:>5} {:>5} {:>10} {:>6}",
            "approximant", "M", "N", "max error", "ok"
        )?;
        for e in &self.approximants {
            writeln!(
                f,
                "{:>16} {:>5} {:>5} {:>10.3e} {:>6}",
                e.name, e.m, e.n, e.max_error, e.within_tol
            )?;
        }
        for s in &self.shared {
            writeln!(
                f,
                "shared curve {}: {} (gap before {:.3e}, moved {:.3e}, {} intervals; identical bit for bit: {})",
                s.curve, s.status, s.gap, s.moved, s.count, s.identical
            )?;
        }
        if !self.open_curves.is_empty() {
            writeln!(f, "open boundary curves: {}", self.open_curves.join(", "))?;
        }
        for w in &self.warnings {
            writeln!(f, "warning: {w}")?;
        }
        writeln!(
            f,
            "{} ({} rebuilds, {:.2} s)",
            if self.within_tol {
                "all approximants within tol (measured), shared rows identical (checked)"
            } else {
                "not all approximants within tol"
            },
            self.rebuilds,
            self.seconds
        )
    }
}
