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

/// One edge on one face: the proven bound on the Hausdorff distance between the image of the
/// face's pcurve of the edge and the edge, where one was proven, else the measured distance
/// of the edge from the face's surface (when the bound is missing or above the tolerance it
/// was checked against).
#[derive(Clone, Debug)]
pub struct EdgeFace {
    /// Indices into the B-rep's faces and edges.
    pub face: usize,
    pub edge: usize,
    /// The pcurve tried, when one could be had.
    pub pcurve: Option<PcurveOrigin>,
    /// The proven bound, when one was proven.
    pub bound: Option<f64>,
    /// Why none was proven, when none was.
    pub unproven: Option<String>,
    /// Largest distance from 33 points of the edge (`SAMPLES` + 1) to the nearest surface points
    /// found (evidence); measured only where no bound within the tolerance was proven and
    /// the edge has a 3D curve.
    pub measured: Option<f64>,
}

/// Every edge of every face of `b` (surfaces in `m`) once per face (a seam edge counts once),
/// with its proven bound, and its measurement where the bound is not within `tolerance`.
pub fn edge_faces(b: &Brep, m: &Model, tolerance: f64) -> Vec<EdgeFace> {
    let mut pcs = Pcurves::new(b, m);
    let mut out = Vec::new();
    for (fi, face) in b.faces.iter().enumerate() {
        let Some(surface) = face.surface.and_then(|s| m.surfaces.get(s)) else {
            continue;
        };
        let mut seen = std::collections::BTreeSet::new();
        let mut foot: Option<crate::spline::project::SurfaceFoot> = None;
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
                let mut pair = EdgeFace {
                    face: fi,
                    edge: oe.edge,
                    pcurve: None,
                    bound: None,
                    unproven: Some("the edge has no 3D curve".into()),
                    measured: None,
                };
                let Some(arc) = edge.curve.as_ref().map(|c| &c.nurbs) else {
                    out.push(pair);
                    continue;
                };
                // The face's own pcurve (source or plane, rational ones too) first: proven
                // within the tolerance, it decides without a projection.
                if let Some((origin, Ok(d))) = pcs.own_bound(oe.edge, fi, tolerance)
                    && d <= tolerance
                {
                    (pair.bound, pair.unproven, pair.pcurve) = (Some(d), None, Some(origin));
                    out.push(pair);
                    continue;
                }
                let pc = pcs.polynomial(oe.edge, fi, 0);
                (pair.bound, pair.unproven) = match pc.as_ref().map(|p| &p.bound) {
                    Some(Ok(d)) => (Some(*d), None),
                    Some(Err(why)) => (None, Some(why.clone())),
                    None => (None, Some("no pcurve could be made".to_string())),
                };
                pair.pcurve = pc.map(|p| p.origin);
                if pair.bound.is_some_and(|d| d <= tolerance) {
                    out.push(pair);
                    continue;
                }
                let (t0, t1) = arc.hom.domain();
                let foot = foot.get_or_insert_with(|| {
                    crate::spline::project::SurfaceFoot::new(&surface.nurbs)
                });
                pair.measured = Some(
                    (0..=SAMPLES)
                        .map(|i| {
                            let x = arc.eval(&(t0 + (t1 - t0) * i as f64 / SAMPLES as f64));
                            let uv = foot.closest(&x);
                            crate::geom::dist(&surface.nurbs.eval(&uv[0], &uv[1]), &x)
                        })
                        .fold(0.0, f64::max),
                );
                out.push(pair);
            }
        }
    }
    out
}

/// Check every edge of every face of `b` (surfaces in `m`).
pub fn check_edges(b: &Brep, m: &Model) -> EdgeChecks {
    let tolerance = b.tolerance.max(1e-8 * b.extent());
    let mut out = EdgeChecks {
        tolerance,
        ..Default::default()
    };
    for pair in edge_faces(b, m, tolerance) {
        out.pairs += 1;
        if let Some(d) = pair.bound.filter(|d| *d <= tolerance) {
            out.proven += 1;
            out.largest_bound = out.largest_bound.max(d);
            continue;
        }
        out.not_proven.push(EdgeOffFace {
            face: b.faces[pair.face].source.clone(),
            edge: b.edges[pair.edge].source.clone(),
            pcurve: pair.pcurve,
            bound: pair.bound,
            unproven: pair.unproven,
            measured: pair.measured,
            above_tolerance: pair.measured.is_some_and(|d| d > tolerance),
        });
    }
    out
}
