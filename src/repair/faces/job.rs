//! The `repair` job with its choice of repair: a model whose B-rep has trimmed faces gets
//! the faces repair ([`super::repair_faces`]: trims kept, free edges sewn, gaps and feature
//! edges reported), any other model the patch-set repair of the paper
//! ([`crate::repair::job`]); either can be asked for.

use super::{FacesReport, FacesResult, repair_faces};
use crate::io::vtk::{Array, PolyData, render};
use crate::repair::job::{JobError, Outputs};
use crate::repair::{RepairParams, RepairReport, RepairResult};
use crate::tessellate::{BrepMesh, MeshParams, mesh_brep};
use serde::Serialize;
use std::path::Path;

/// Which repair a model gets.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Mode {
    /// Faces when the model has a B-rep with a trimmed face, else patches.
    #[default]
    Auto,
    /// The paper's repair on the untrimmed surfaces (trims ignored, which the report says).
    Patches,
    /// The faces repair (the model must have a B-rep).
    Faces,
}

/// What either repair gave.
pub enum Repaired {
    Patches(RepairResult),
    Faces(FacesResult),
}

/// Either repair's report (JSON: the report itself; a faces report has `"mode": "faces"`).
#[derive(Clone, Debug, Serialize)]
#[serde(untagged)]
pub enum Report {
    Patches(Box<RepairReport>),
    Faces(Box<FacesReport>),
}

impl std::fmt::Display for Report {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Report::Patches(r) => r.fmt(f),
            Report::Faces(r) => r.fmt(f),
        }
    }
}

impl Repaired {
    pub fn report(self) -> Report {
        match self {
            Repaired::Patches(r) => Report::Patches(Box::new(r.report)),
            Repaired::Faces(r) => Report::Faces(Box::new(r.report)),
        }
    }
}

/// Whether `mode` gives the model `m` the faces repair: asked for, or (`Auto`) the model has
/// a B-rep with a trimmed face ([`crate::brep::natural`]).
pub fn faces_chosen(m: &crate::model::Model, mode: Mode) -> bool {
    match mode {
        Mode::Patches => false,
        Mode::Faces => true,
        Mode::Auto => m
            .brep
            .as_ref()
            .is_some_and(|b| crate::brep::natural::natural_faces(b, m).contains(&false)),
    }
}

impl std::str::FromStr for Mode {
    type Err = String;
    fn from_str(s: &str) -> Result<Mode, String> {
        match s {
            "auto" => Ok(Mode::Auto),
            "patches" => Ok(Mode::Patches),
            "faces" => Ok(Mode::Faces),
            other => Err(format!(
                "the repair mode must be `auto`, `patches` or `faces`, not `{other}`"
            )),
        }
    }
}

fn write_err(p: &Path, e: impl std::fmt::Display) -> JobError {
    JobError::Write(p.display().to_string(), e.to_string())
}

/// Run the repair `mode` chooses on the model in `input`, writing `out`.
pub fn run(
    input: &Path,
    prm: &RepairParams,
    features: Option<&Path>,
    out: Outputs,
    mode: Mode,
) -> Result<Repaired, JobError> {
    let m = crate::repair::job::read(input, &out)?;
    if !faces_chosen(&m, mode) {
        return crate::repair::job::run_on(&m, prm, features, out).map(Repaired::Patches);
    }
    if features.is_some() {
        return Err(JobError::Overrides(
            "--features".into(),
            "overrides name patch edges; the faces repair takes none".into(),
        ));
    }
    let t0 = std::time::Instant::now();
    let progress = |step: &str| {
        if t0.elapsed().as_secs_f64() > 1.0 {
            out.progress
                .say(|| format!("repair: {step} ({:.1} s)", t0.elapsed().as_secs_f64()));
        }
    };
    let r = repair_faces(&m, prm, &progress)?;
    let mut om = m;
    om.brep = Some(r.brep.clone());
    if let Some(p) = out.model {
        crate::io::write_model(p, &om).map_err(|e| write_err(p, e))?;
    }
    if let Some(p) = out.report {
        crate::io::json_text::write_file(p, &r.report).map_err(|e| write_err(p, e))?;
    }
    if out.vtk.is_some() || out.svg.is_some() {
        let mesh = mesh_brep(&om, &r.brep, &MeshParams::default());
        if let Some(p) = out.svg {
            let text = super::picture::picture(&r, &mesh, om.unit.as_deref(), &out.view);
            crate::io::write_atomic(p, &text).map_err(|e| write_err(p, e))?;
        }
        if let Some(p) = out.vtk {
            crate::io::write_atomic(p, render(&vtk(&r, &mesh))).map_err(|e| write_err(p, e))?;
        }
    }
    Ok(Repaired::Faces(r))
}

/// The VTK view: the faces' triangles (cell array `face`), then the feature edges
/// (`feature = 1`), the free edges (`free = 1`) and the shared edges with their gap
/// (`gap`, proven where proven, else evidence) as lines.
fn vtk(r: &FacesResult, mesh: &BrepMesh) -> PolyData {
    let mut pd = PolyData {
        points: mesh.triangulation.vertices.clone(),
        ..Default::default()
    };
    let mut face = Vec::new();
    for (k, f) in mesh.faces.iter().enumerate() {
        if let Ok((range, _)) = f {
            for t in &mesh.triangulation.triangles[range.clone()] {
                pd.polys.push(t.to_vec());
                face.push(k as f64);
            }
        }
    }
    let polys = pd.polys.len();
    let (mut feature, mut free, mut gap) = (Vec::new(), Vec::new(), Vec::new());
    for e in &r.report.edges {
        let pts = super::picture::edge_points(&r.brep, e.index);
        if pts.len() > 1 {
            pd.add_polyline(&pts);
            feature.push(if e.feature { 1.0 } else { 0.0 });
            free.push(0.0);
            gap.push(e.gap_bound_proven.unwrap_or(e.gap_evidence));
        }
    }
    for &e in &r.report.free_edge_index {
        let pts = super::picture::edge_points(&r.brep, e);
        if pts.len() > 1 {
            pd.add_polyline(&pts);
            feature.push(0.0);
            free.push(1.0);
            gap.push(-1.0);
        }
    }
    face.extend(std::iter::repeat_n(-1.0, feature.len()));
    let pad = |v: Vec<f64>| {
        let mut w = vec![-1.0; polys];
        w.extend(v);
        w
    };
    pd.cell_data = vec![
        Array {
            name: "face".into(),
            values: face,
        },
        Array {
            name: "feature".into(),
            values: pad(feature),
        },
        Array {
            name: "free".into(),
            values: pad(free),
        },
        Array {
            name: "gap".into(),
            values: pad(gap),
        },
    ];
    pd
}
