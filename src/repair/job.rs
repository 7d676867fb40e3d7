//! The `repair` job: read a patch set, repair, write the patches, the report and a VTK view.

use super::features::FeatureOverrides;
use super::{RepairError, RepairParams, RepairReport, RepairResult, repair};
use crate::io::vtk::{Array, PolyData, render};
use crate::model::{Model, Surface};
use std::path::Path;

#[derive(Debug, thiserror::Error)]
pub enum JobError {
    #[error(transparent)]
    Read(#[from] crate::io::ReadError),
    #[error("{0}: {1}")]
    Overrides(String, String),
    #[error(transparent)]
    Repair(#[from] RepairError),
    #[error("cannot write {0}: {1}")]
    Write(String, String),
}

impl JobError {
    pub fn is_bad_input(&self) -> bool {
        !matches!(self, JobError::Write(..))
    }
}

#[derive(Clone, Copy, Debug, Default)]
pub struct Outputs<'a> {
    pub model: Option<&'a Path>,
    pub report: Option<&'a Path>,
    /// Patches (cell array `patch`), feature edges and gaps left as lines (`feature`, `gap`).
    pub vtk: Option<&'a Path>,
    /// A picture: the output patches shaded, feature edges and gaps left drawn over them
    /// ([`super::picture`]), seen along `view`.
    pub svg: Option<&'a Path>,
    pub view: crate::io::picture::View,
    /// Where progress lines go on runs over a second (default: nowhere).
    pub progress: crate::progress::Progress,
}

fn write(path: &Path, text: &str) -> Result<(), JobError> {
    crate::io::write_atomic(path, text)
        .map_err(|e| JobError::Write(path.display().to_string(), e.to_string()))
}

/// Run the job; returns the report (the patches are in [`run_result`]).
pub fn run(
    input: &Path,
    prm: &RepairParams,
    features: Option<&Path>,
    out: Outputs,
) -> Result<RepairReport, JobError> {
    run_result(input, prm, features, out).map(|r| r.report)
}

/// Run the job and return the whole result: the report and the repaired patches.
pub fn run_result(
    input: &Path,
    prm: &RepairParams,
    features: Option<&Path>,
    out: Outputs,
) -> Result<RepairResult, JobError> {
    let m = read(input, &out)?;
    run_on(&m, prm, features, out)
}

/// Read the model and check every output path writable (before the work: an unwritable
/// path fails at once).
pub(super) fn read(input: &Path, out: &Outputs) -> Result<Model, JobError> {
    let m = crate::io::read_model(input)?;
    crate::io::check_all_writable([out.model, out.report, out.vtk, out.svg])
        .map_err(|(p, e)| JobError::Write(p.display().to_string(), e.to_string()))?;
    Ok(m)
}

/// The faces of `m` whose trims a patch-set repair ignores: B-rep faces not bounded by their
/// surface's rectangle, else surfaces carrying parameter-space trims (source ids).
pub fn trims_ignored(m: &Model) -> Vec<String> {
    match &m.brep {
        Some(b) => b
            .faces
            .iter()
            .zip(crate::brep::natural::natural_faces(b, m))
            .filter(|x| !x.1)
            .map(|x| x.0.source.clone())
            .collect(),
        None => m
            .surfaces
            .iter()
            .filter(|s| !s.trim_loops.is_empty())
            .map(|s| s.name.clone())
            .collect(),
    }
}

/// The patch-set repair of `m`'s surfaces (their trims ignored, which the report says).
pub(super) fn run_on(
    m: &Model,
    prm: &RepairParams,
    features: Option<&Path>,
    out: Outputs,
) -> Result<RepairResult, JobError> {
    let overrides: FeatureOverrides = match features {
        Some(p) => {
            let t = std::fs::read_to_string(p)
                .map_err(|e| JobError::Overrides(p.display().to_string(), e.to_string()))?;
            serde_json::from_str(&t)
                .map_err(|e| JobError::Overrides(p.display().to_string(), e.to_string()))?
        }
        None => FeatureOverrides::default(),
    };
    let patches: Vec<_> = m.surfaces.iter().map(|s| s.nurbs.clone()).collect();
    let t0 = std::time::Instant::now();
    let progress = |step: &str| {
        if t0.elapsed().as_secs_f64() > 1.0 {
            out.progress
                .say(|| format!("repair: {step} ({:.1} s)", t0.elapsed().as_secs_f64()));
        }
    };
    let mut r = repair(patches, prm, &overrides, &progress)?;
    let ignored = trims_ignored(m);
    if !ignored.is_empty() {
        r.report.not_done.push(format!(
            "trims ignored: {} of {} faces are trimmed ({}); this repair works on their untrimmed surfaces (without --patches, repair keeps the trims and sews the faces instead)",
            ignored.len(),
            m.brep.as_ref().map_or(m.surfaces.len(), |b| b.faces.len()),
            ignored.iter().take(5).cloned().collect::<Vec<_>>().join(", ")
                + if ignored.len() > 5 { ", ..." } else { "" }
        ));
    }
    if let Some(p) = out.model {
        let mut om = Model {
            unit: m.unit.clone(),
            ..Default::default()
        };
        for (k, s) in r.patches.iter().enumerate() {
            let from = &r.report.patch_origin[k];
            let src = &m.surfaces[from[0]];
            let name = if from.len() > 1 {
                format!("merged from {} patches ({}, ...)", from.len(), src.name)
            } else {
                format!("{} (repaired)", src.name)
            };
            let mut ns = Surface::new(name, s.clone());
            ns.source = src.source.clone();
            om.surfaces.push(ns);
        }
        crate::io::write_model(p, &om)
            .map_err(|e| JobError::Write(p.display().to_string(), e.to_string()))?;
    }
    if let Some(p) = out.report {
        crate::io::json_text::write_file(p, &r.report)
            .map_err(|e| JobError::Write(p.display().to_string(), e.to_string()))?;
    }
    if let Some(p) = out.svg {
        write(
            p,
            &super::picture::picture(&r, m.unit.as_deref(), &out.view),
        )?;
    }
    if let Some(p) = out.vtk {
        let mut pd = PolyData::default();
        let mut patch = Vec::new();
        for (k, s) in r.patches.iter().enumerate() {
            let n = pd.add_surface(s, 8);
            patch.extend(std::iter::repeat_n(k as f64, n));
        }
        let polys = pd.polys.len();
        let (mut feature, mut gap) = (Vec::new(), Vec::new());
        for e in &r.report.edges {
            if e.feature {
                let c = super::edges::edge_curve(&r.connected_patches[e.p], e.ep);
                let pts: Vec<[f64; 3]> = super::edges::arc_length_samples(&c, 16)
                    .into_iter()
                    .map(|x| x.1)
                    .collect();
                pd.add_polyline(&pts);
                feature.push(1.0);
                gap.push(0.0);
            }
        }
        for g in &r.report.gaps_left {
            let c = super::edges::edge_curve(&r.connected_patches[g.connection.p], g.connection.ep);
            let pts: Vec<[f64; 3]> = super::edges::arc_length_samples(&c, 16)
                .into_iter()
                .map(|x| x.1)
                .collect();
            pd.add_polyline(&pts);
            feature.push(0.0);
            gap.push(g.gap);
        }
        let lines = feature.len();
        patch.extend(std::iter::repeat_n(-1.0, lines));
        let pad = |v: Vec<f64>| {
            let mut w = vec![-1.0; polys];
            w.extend(v);
            w
        };
        pd.cell_data = vec![
            Array {
                name: "patch".into(),
                values: patch,
            },
            Array {
                name: "feature".into(),
                values: pad(feature),
            },
            Array {
                name: "gap".into(),
                values: pad(gap),
            },
        ];
        write(p, &render(&pd))?;
    }
    Ok(r)
}

impl std::fmt::Display for RepairReport {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        writeln!(f, "repair of a patch set")?;
        writeln!(
            f,
            "  patches: {} in, {} out ({} T-junction splits)",
            self.patches_in, self.patches_out, self.t_junctions
        )?;
        writeln!(
            f,
            "  edges: {} candidates, {} connected ({} flipped pairs), {} non-manifold, {} collapsed, {} free, {} gaps left above u2",
            self.candidate_edges,
            self.edges_connected,
            self.flipped_pairs,
            self.non_manifold.len(),
            self.collapsed_edges,
            self.free_edges,
            self.gaps_left.len()
        )?;
        writeln!(
            f,
            "  gaps (measured at samples): max {:.3e}, mean {:.3e} before; max {:.3e} after averaging; {} shared edges identical",
            self.gap_max_before,
            self.gap_mean_before,
            self.gap_max_after,
            self.shared_edges_identical
        )?;
        writeln!(
            f,
            "  averaging: {} corner clusters (largest move {:.3e}; {} rational patches reparametrized to corner weights 1 first), {} edges by control points, {} by fitted curves (largest fit residual {:.3e}, evidence), {} left",
            self.averaging.corner_clusters,
            self.averaging.max_corner_move,
            self.averaging.corner_weights_unified,
            self.averaging.edges_averaged,
            self.averaging.edges_fitted,
            self.averaging.max_fit_error_evidence,
            self.averaging.edges_incompatible.len()
        )?;
        writeln!(
            f,
            "  patch deviation: {:.3e} measured (evidence, closest points){}",
            self.averaging.max_deviation_measured_evidence,
            match self.averaging.max_deviation_bound_proven {
                Some(b) => format!(
                    "; proven bound at equal parameters {b:.3e} (patches whose weights were kept)"
                ),
                None => String::new(),
            }
        )?;
        writeln!(
            f,
            "  groups: {} ({} patches turned to fit their group), {} not merged",
            self.groups.unwrap_or(0),
            self.reoriented,
            self.groups_not_merged
        )?;
        writeln!(
            f,
            "  feature edges: {} ({} overridden)",
            self.feature_edges, self.features_overridden
        )?;
        for n in &self.not_done {
            writeln!(f, "  NOT DONE: {n}")?;
        }
        writeln!(f, "  time {:.3} s", self.seconds)
    }
}
