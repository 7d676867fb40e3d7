//! The `curve-on-surface --face` job: certified curves along the loops of B-rep faces read
//! from a STEP or IGES file ([`super::face`]), a report per face, the curves as JSON and IGES.

use super::Params;
use super::face::{FaceCurves, face_curves};
use super::job::JobError;
use crate::brep::pcurve::{PcurveOrigin, Pcurves};
use crate::model::{Curve, CurveGeometry, Model};
use serde::Serialize;

/// The report of the job.
#[derive(Clone, Debug, Serialize)]
pub struct FacesReport {
    pub file: String,
    pub eps_d: f64,
    pub faces: Vec<FaceCurves>,
    /// Edges (loop uses) with a certified curve, and all of them.
    pub certified: usize,
    pub edges: usize,
    /// Edge uses whose pcurve came from the source, a plane, a projection.
    pub pcurves: [usize; 3],
}

impl FacesReport {
    /// Whether every edge of every selected face carries a certified curve.
    pub fn all_certified(&self) -> bool {
        self.certified == self.edges
    }
}

/// Face indices from `spec`: `all`, or a comma-separated list of indices (0-based, in file
/// order) and source ids (`#12` in STEP, `DE 12` in IGES, as the reports print them).
pub fn select(m: &Model, spec: &str) -> Result<Vec<usize>, String> {
    let b = m.brep.as_ref().ok_or("the file has no B-rep faces")?;
    if spec.trim() == "all" {
        return Ok((0..b.faces.len()).collect());
    }
    spec.split(',')
        .map(|s| {
            let s = s.trim();
            if let Ok(i) = s.parse::<usize>() {
                return (i < b.faces.len()).then_some(i).ok_or(format!(
                    "no face {i} (the file has {} faces)",
                    b.faces.len()
                ));
            }
            b.faces
                .iter()
                .position(|f| f.source == s)
                .ok_or(format!("no face with source id `{s}`"))
        })
        .collect()
}

/// Run the job on `file`'s faces `spec` ([`select`]); writes the JSON result and the curves
/// as IGES (rational B-splines, 126) when asked; progress lines go to `progress` on runs over
/// a second.
pub fn run(
    file: &str,
    spec: &str,
    params: &Params,
    (json, iges): (Option<&std::path::Path>, Option<&std::path::Path>),
    progress: crate::progress::Progress,
) -> Result<FacesReport, JobError> {
    crate::io::check_all_writable([json, iges])
        .map_err(|(p, e)| JobError::Write(p.display().to_string(), e))?;
    let m = crate::io::read_model(std::path::Path::new(file))?;
    let picked = select(&m, spec).map_err(|e| JobError::Select(file.to_string(), e))?;
    let Some(b) = m.brep.as_ref() else {
        return Err(JobError::Select(
            file.into(),
            "the file has no B-rep faces".into(),
        ));
    };
    let mut pcs = Pcurves::new(b, &m);
    let start = std::time::Instant::now();
    let mut faces = Vec::new();
    for (k, &fi) in picked.iter().enumerate() {
        if start.elapsed().as_secs_f64() > 1.0 {
            progress.say(|| {
                format!(
                    "[{:>7.1} s] face {} of {}",
                    start.elapsed().as_secs_f64(),
                    k + 1,
                    picked.len()
                )
            });
        }
        match face_curves(b, &m, fi, params, &mut pcs) {
            Some(f) => faces.push(f),
            None => {
                return Err(JobError::Select(
                    file.into(),
                    format!("face {} has no surface", b.faces[fi].source),
                ));
            }
        }
    }
    let edges = faces.iter().map(|f| f.edges().count()).sum();
    let certified = faces
        .iter()
        .map(|f| f.edges().filter(|e| e.certified()).count())
        .sum();
    let report = FacesReport {
        file: file.to_string(),
        eps_d: params.eps_d,
        certified,
        edges,
        pcurves: [
            PcurveOrigin::Source,
            PcurveOrigin::Plane,
            PcurveOrigin::Projected,
        ]
        .map(|o| {
            faces
                .iter()
                .flat_map(|f| f.edges())
                .filter(|e| e.pcurve == Some(o))
                .count()
        }),
        faces,
    };
    if let Some(o) = json {
        crate::io::json_text::write_file(o, &report)
            .map_err(|e| JobError::Write(o.display().to_string(), e))?;
    }
    if let Some(p) = iges {
        let out = Model {
            curves: curves(&report)?,
            unit: m.unit.clone(),
            ..Default::default()
        };
        crate::io::write_atomic(
            p,
            crate::io::iges::write::to_string(&out, "curve-on-surface"),
        )
        .map_err(|e| JobError::Write(p.display().to_string(), e))?;
    }
    Ok(report)
}

/// The certified curves as model curves named `face #F loop #L edge #E` (`part K` where an
/// edge was cut at a seam): the B-spline forms, their weights kept. Held as homogeneous points
/// `w·P` and written back as `P`, a rational curve's points may differ from the printed ones
/// by an ulp or two of their coordinates (not in the bound).
fn curves(r: &FacesReport) -> Result<Vec<Curve>, JobError> {
    let mut out = Vec::new();
    for f in &r.faces {
        for l in &f.loops {
            for (e, (k, c)) in l
                .edges
                .iter()
                .flat_map(|e| e.curves.iter().enumerate().map(move |x| (e, x)))
            {
                let b = &c.bspline;
                let w = b
                    .weights
                    .clone()
                    .unwrap_or_else(|| vec![1.0; b.control_points.len()]);
                let n = crate::spline::NurbsCurve::new(
                    b.knots.clone(),
                    b.degree,
                    b.control_points.clone(),
                    w,
                )
                .map_err(|e| JobError::Compute(super::CosInternal::Curve(e).into()))?;
                let part = if e.curves.len() > 1 {
                    format!(" part {}", k + 1)
                } else {
                    String::new()
                };
                out.push(Curve {
                    name: format!("face {} loop {} edge {}{part}", f.face, l.bound, e.edge),
                    geometry: CurveGeometry::Space(n),
                });
            }
        }
    }
    Ok(out)
}

impl std::fmt::Display for FacesReport {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        writeln!(
            f,
            "Curves on surfaces along face loops of {}: {} face(s), {} of {} edge uses certified (eps_D = {:.1e})",
            self.file,
            self.faces.len(),
            self.certified,
            self.edges,
            self.eps_d
        )?;
        writeln!(
            f,
            "  each curve: Bézier segments exactly on the face's surface, within eps of the image of the edge's pcurve; bound to edge = eps + the pcurve's proven distance to the edge"
        )?;
        for fc in &self.faces {
            for l in &fc.loops {
                let n = l.edges.len();
                let ok = l.edges.iter().filter(|e| e.certified()).count();
                let worst = l
                    .edges
                    .iter()
                    .filter_map(|e| e.bound_to_edge)
                    .fold(0.0, f64::max);
                let segs: usize = l
                    .edges
                    .iter()
                    .flat_map(|e| e.curves.iter().map(|r| r.num_segments))
                    .sum();
                writeln!(
                    f,
                    "  face {} ({}) loop {}{}: {ok} of {n} edges certified, {segs} segments, largest bound to edge {worst:.2e}",
                    fc.face,
                    if fc.rational {
                        "rational"
                    } else {
                        "polynomial"
                    },
                    l.bound,
                    if l.outer { " (outer)" } else { "" },
                )?;
                for e in l.edges.iter().filter(|e| !e.certified()) {
                    let why = e
                        .error
                        .as_deref()
                        .or(e.pcurve_unproven.as_deref())
                        .unwrap_or("unproven");
                    writeln!(f, "    not certified: edge {}: {why}", e.edge)?;
                }
            }
        }
        let [source, plane, projected] = self.pcurves;
        writeln!(
            f,
            "  pcurves: {source} the source's, {plane} exact on planes, {projected} projected from the edges (certified projection)"
        )
    }
}
