//! The `curve-on-surface` job: pick the surface and domain curve from model files, run the
//! algorithm, write the JSON result and an optional SVG plot of the domain.

use super::{CosError, CurveOnSurface, Params, approximate_with_progress};
use crate::curve_on_surface::CosInternal;
use crate::model::{CurveGeometry, ModelError};
use crate::spline::NurbsCurve;

/// Errors of the job: bad input (files, indices) or a refused computation.
#[derive(Debug, thiserror::Error)]
pub enum JobError {
    #[error(transparent)]
    Model(#[from] ModelError),
    #[error(transparent)]
    Read(#[from] crate::io::ReadError),
    #[error("{0}: {1}")]
    Select(String, String),
    #[error(transparent)]
    Compute(#[from] CosError),
    #[error("cannot write {0}: {1}")]
    Write(String, std::io::Error),
}

impl JobError {
    /// Whether the user's input is at fault (exit code 2) rather than the computation.
    pub fn is_bad_input(&self) -> bool {
        match self {
            JobError::Model(_) | JobError::Read(_) | JobError::Select(..) => true,
            JobError::Compute(e) => {
                !matches!(e, CosError::Internal(_) | CosError::TooManySegments(_))
            }
            JobError::Write(..) => false,
        }
    }
}

/// `FILE[:INDEX]` split into path and index (default 0).
pub fn file_and_index(spec: &str) -> (String, usize) {
    if let Some((f, i)) = spec.rsplit_once(':')
        && let Ok(i) = i.parse::<usize>()
    {
        return (f.to_string(), i);
    }
    (spec.to_string(), 0)
}

/// Optional output files of the job.
#[derive(Clone, Copy, Debug, Default)]
pub struct Outputs<'a> {
    pub json: Option<&'a std::path::Path>,
    pub svg: Option<&'a std::path::Path>,
    /// The B-spline form as an IGES 126 curve (with the surface as 128).
    pub iges: Option<&'a std::path::Path>,
    /// The segments as polylines with per-cell `segment`, `bound` and `certified` arrays,
    /// and the surface, in a `.vtp`.
    pub vtk: Option<&'a std::path::Path>,
    /// A 3D picture: the surface shaded, the segments over it coloured by their bound
    /// ([`super::picture`]), seen along `view`.
    pub svg_3d: Option<&'a std::path::Path>,
    pub view: crate::io::picture::View,
    /// Where progress lines go on runs over a second (default: nowhere).
    pub progress: crate::progress::Progress,
}

/// Run the job.
pub fn run(
    surface_spec: &str,
    curve_spec: &str,
    params: &Params,
    outputs: Outputs,
) -> Result<CurveOnSurface, JobError> {
    let (out, svg) = (outputs.json, outputs.svg);
    // Outputs are checked before the work: an unwritable path fails at once.
    crate::io::check_all_writable([out, svg, outputs.iges, outputs.vtk, outputs.svg_3d])
        .map_err(|(p, e)| JobError::Write(p.display().to_string(), e))?;
    let (sf, si) = file_and_index(surface_spec);
    let sm = crate::io::read_model(std::path::Path::new(&sf))?;
    let surf = sm.surfaces.get(si).ok_or_else(|| {
        JobError::Select(
            sf.clone(),
            format!("no surface {si} (the file has {})", sm.surfaces.len()),
        )
    })?;
    let (cf, ci) = file_and_index(curve_spec);
    let cm = crate::io::read_model(std::path::Path::new(&cf))?;
    // Domain curves; as in IGES curves on surfaces, a 3D curve whose control points all
    // have z = 0 is read as a (u, v) curve.
    let domain_curves: Vec<NurbsCurve<f64, 2>> = cm
        .curves
        .iter()
        .filter_map(|c| c.geometry.to_domain())
        .collect();
    let curve = domain_curves.get(ci).ok_or_else(|| {
        JobError::Select(
            cf.clone(),
            format!(
                "no domain curve {ci} (the file has {} domain curves)",
                domain_curves.len()
            ),
        )
    })?;
    let r = {
        // Progress once a run takes longer than a second.
        let start = std::time::Instant::now();
        let mut report = |stage: &str, n: usize| {
            if start.elapsed().as_secs_f64() > 1.0 {
                outputs.progress.say(|| {
                    format!(
                        "[{:>7.1} s] {stage}: {n} segments",
                        start.elapsed().as_secs_f64()
                    )
                });
            }
        };
        approximate_with_progress(&surf.nurbs, curve, params, &mut report)?
    };
    if let Some(o) = out {
        crate::io::json_text::write_file(o, &r)
            .map_err(|e| JobError::Write(o.display().to_string(), e))?;
    }
    if let Some(p) = svg {
        let (a, b) = curve.hom.domain();
        let samples: Vec<[f64; 2]> = (0..=400)
            .map(|i| curve.eval(&(a + (b - a) * i as f64 / 400.0)))
            .collect();
        let h = &surf.nurbs.hom;
        let (u0, u1, v0, v1) = h.domain();
        let doc = crate::io::svg::render(&crate::io::svg::DomainPlot {
            domain: [u0, u1, v0, v1],
            u_knots: &h.ku.breakpoints(),
            v_knots: &h.kv.breakpoints(),
            curve: &samples,
            polyline: &r.domain_polyline,
            title: &format!(
                "{} segments, proven Hausdorff bound {:.3e}",
                r.num_segments, r.certificate.hausdorff_bound
            ),
        });
        crate::io::write_atomic(p, doc).map_err(|e| JobError::Write(p.display().to_string(), e))?;
    }
    if let Some(p) = outputs.iges {
        let b = &r.bspline;
        let curve = crate::spline::NurbsCurve::new(
            b.knots.clone(),
            b.degree,
            b.control_points.clone(),
            b.weights
                .clone()
                .unwrap_or_else(|| vec![1.0; b.control_points.len()]),
        )
        .map_err(|e| JobError::Compute(CosInternal::Curve(e).into()))?;
        let m = crate::model::Model {
            surfaces: vec![surf.clone()],
            curves: vec![crate::model::Curve {
                name: "curve-on-surface".into(),
                geometry: CurveGeometry::Space(curve),
            }],
            unit: sm.unit.clone(),
            ..Default::default()
        };
        crate::io::write_atomic(p, crate::io::iges::write::to_string(&m, "curve-on-surface"))
            .map_err(|e| JobError::Write(p.display().to_string(), e))?;
    }
    if let Some(p) = outputs.svg_3d {
        let doc = super::picture::picture(&r, &surf.nurbs, sm.unit.as_deref(), &outputs.view);
        crate::io::write_atomic(p, doc).map_err(|e| JobError::Write(p.display().to_string(), e))?;
    }
    if let Some(p) = outputs.vtk {
        let mut pd = crate::io::vtk::PolyData::default();
        let quads = pd.add_surface(&surf.nurbs, 32);
        let (mut seg, mut bound, mut cert) =
            (vec![-1.0; quads], vec![0.0; quads], vec![0.0; quads]);
        for (k, sg) in r.segments.iter().enumerate() {
            let pts: Vec<[f64; 3]> = (0..=16).map(|i| sg.eval(i as f64 / 16.0)).collect();
            pd.add_polyline(&pts);
            seg.push(k as f64);
            bound.push(sg.bound);
            cert.push(if sg.bound <= r.certificate.eps_d {
                1.0
            } else {
                0.0
            });
        }
        pd.cell_data.push(crate::io::vtk::Array {
            name: "segment".into(),
            values: seg,
        });
        pd.cell_data.push(crate::io::vtk::Array {
            name: "bound".into(),
            values: bound,
        });
        pd.cell_data.push(crate::io::vtk::Array {
            name: "certified".into(),
            values: cert,
        });
        crate::io::write_atomic(p, crate::io::vtk::render(&pd))
            .map_err(|e| JobError::Write(p.display().to_string(), e))?;
    }
    Ok(r)
}
