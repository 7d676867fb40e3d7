//! Do the edges lie on their faces? For every edge a face's loops use, the pcurve the
//! writers and `curve-on-surface --face` would take ([`Pcurves::polynomial`]: the file's own,
//! a plane's, or one projected from the edge) and a proven bound on the Hausdorff distance
//! between its image and the edge (`spline::pcurve_bound`). Where no bound within the model
//! tolerance is proven, the edge is measured against the surface — the distance from samples
//! of the edge to the nearest surface points found (`spline::project`, in f64: about an upper
//! bound of each sample's distance to the surface; evidence for the edge) — and reported with
//! the face's and edge's ids. An edge without a 3D curve is listed as not proven. A measurement above the tolerance says the edge was not found on its
//! face; it does not prove the edge off it (the search may miss the nearest point).

use super::pcurve::{PcurveOrigin, Pcurves};
use super::{Brep, LoopKind};
use crate::model::Model;
use serde::Serialize;

/// Samples of an edge measured against its face's surface when no bound is proven.
const SAMPLES: usize = 32;

/// One edge on one face whose agreement was not proven.
#[derive(Clone, Debug, Serialize)]
pub struct EdgeOffFace {
    pub face: String,
    pub edge: String,
    /// The pcurve tried, when one could be had.
    pub pcurve: Option<PcurveOrigin>,
    /// The proven bound, when one was proven (above the tolerance).
    pub bound: Option<f64>,
    /// Why none was proven, when none was.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub unproven: Option<String>,
    /// Largest distance from the edge's samples to the nearest surface points found
    /// (measured, evidence); `None` for an edge without a 3D curve.
    pub measured: Option<f64>,
    /// Whether the measured distance is above the tolerance.
    pub above_tolerance: bool,
}

/// What the check found.
#[derive(Clone, Debug, Default, Serialize)]
pub struct EdgeChecks {
    /// The tolerance checked against: the model's, at least `1e-8` of its size.
    pub tolerance: f64,
    /// Edge–face pairs checked (a seam edge counts once per face).
    pub pairs: usize,
    /// Pairs whose distance is proven within the tolerance, and the largest such bound.
    pub proven: usize,
    pub largest_bound: f64,
    /// Pairs not proven, with their measurement.
    pub not_proven: Vec<EdgeOffFace>,
}

impl EdgeChecks {
    /// Pairs measured above the tolerance.
    pub fn above_tolerance(&self) -> usize {
        self.not_proven.iter().filter(|x| x.above_tolerance).count()
    }
}

/// Check every edge of every face of `b` (surfaces in `m`).
pub fn check_edges(b: &Brep, m: &Model) -> EdgeChecks {
    let mut pcs = Pcurves::new(b, m);
    let tolerance = b.tolerance.max(1e-8 * b.extent());
    let mut out = EdgeChecks {
        tolerance,
        ..Default::default()
    };
    for (fi, face) in b.faces.iter().enumerate() {
        let Some(surface) = face.surface.and_then(|s| m.surfaces.get(s)) else {
            continue;
        };
        let mut seen = std::collections::BTreeSet::new();
        for l in &face.loops {
            let LoopKind::Edges(oes) = &l.kind else {
                continue;
            };
            for oe in oes {
                if !seen.insert(oe.edge) {
                    continue;
                }
                let Some(edge) = b.edges.get(oe.edge) else {
                    continue;
                };
                out.pairs += 1;
                let Some(arc) = edge.curve.as_ref().map(|c| &c.nurbs) else {
                    out.not_proven.push(EdgeOffFace {
                        face: face.source.clone(),
                        edge: edge.source.clone(),
                        pcurve: None,
                        bound: None,
                        unproven: Some("the edge has no 3D curve".into()),
                        measured: None,
                        above_tolerance: false,
                    });
                    continue;
                };
                let pc = pcs.polynomial(oe.edge, fi, 0);
                let (bound, unproven) = match pc.as_ref().map(|p| &p.bound) {
                    Some(Ok(d)) => (Some(*d), None),
                    Some(Err(why)) => (None, Some(why.clone())),
                    None => (None, Some("no pcurve could be made".to_string())),
                };
                if let Some(d) = bound.filter(|d| *d <= tolerance) {
                    out.proven += 1;
                    out.largest_bound = out.largest_bound.max(d);
                    continue;
                }
                let (t0, t1) = arc.hom.domain();
                let mut foot = crate::spline::project::SurfaceFoot::new(&surface.nurbs);
                let measured = (0..=SAMPLES)
                    .map(|i| {
                        let x = arc.eval(&(t0 + (t1 - t0) * i as f64 / SAMPLES as f64));
                        let uv = foot.closest(&x);
                        crate::geom::dist(&surface.nurbs.eval(&uv[0], &uv[1]), &x)
                    })
                    .fold(0.0, f64::max);
                out.not_proven.push(EdgeOffFace {
                    face: face.source.clone(),
                    edge: edge.source.clone(),
                    pcurve: pc.map(|p| p.origin),
                    bound,
                    unproven,
                    measured: Some(measured),
                    above_tolerance: measured > tolerance,
                });
            }
        }
    }
    out
}
