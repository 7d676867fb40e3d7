//! Certified curves along a B-rep face's boundary: every edge of every loop of a face, as a
//! chain of Bézier segments of degree `p + q` lying exactly on the face's surface.
//!
//! The domain curve `D` of an edge is its pcurve on the face, polynomial
//! ([`crate::brep::pcurve::PolynomialPcurve`]: the source's, a plane's, or one projected from
//! the edge's 3D curve), with a proven bound `δ` on the Hausdorff distance between `S(D)` and
//! the edge. The algorithm ([`super::approximate`]) proves `ε` between its printed output
//! and `S(D)` (its certified bound plus the output's rounding); by the triangle inequality
//! for the Hausdorff distance the output is within `ε + δ` of the edge, and that sum is
//! reported as `bound_to_edge` — only when both are proven. An edge cut at a seam into parts
//! has `δ` proven for each part's pcurve against the edge over that part's range; the union
//! of the parts' outputs is then within the largest `ε + δ` of the union of the parts.

use super::{CurveOnSurface, Params, approximate};
use crate::brep::pcurve::{PcurveOrigin, Pcurves};
use crate::brep::{Brep, LoopKind};
use crate::model::Model;
use serde::Serialize;

/// One edge of a loop.
#[derive(Clone, Debug, Serialize)]
pub struct EdgeOnFace {
    /// The edge's source id.
    pub edge: String,
    /// Where its pcurve came from; `None` when the face has none for it.
    pub pcurve: Option<PcurveOrigin>,
    /// Proven bound `δ` on the Hausdorff distance between the pcurve's image and the edge.
    pub pcurve_bound: Option<f64>,
    /// Why `δ` (or the pcurve) is missing.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pcurve_unproven: Option<String>,
    /// `ε + δ`: proven bound on the Hausdorff distance between the output (the printed
    /// segments: `ε` includes their rounding, [`CurveOnSurface::printed_bound`]) and the
    /// edge's 3D curve.
    pub bound_to_edge: Option<f64>,
    /// The certified curves on the surface, one per pcurve piece (two or more where the
    /// edge's projection crosses the surface's seam and was cut there), in the edge's order;
    /// empty when any piece failed.
    pub curves: Vec<CurveOnSurface>,
    /// Why there are none.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub error: Option<String>,
}

/// One loop of a face.
#[derive(Clone, Debug, Serialize)]
pub struct LoopOnFace {
    /// Source id of the bound.
    pub bound: String,
    pub outer: bool,
    pub edges: Vec<EdgeOnFace>,
}

/// The curves along one face's loops.
#[derive(Clone, Debug, Serialize)]
pub struct FaceCurves {
    /// The face's source id.
    pub face: String,
    /// Source id of its surface.
    pub surface: String,
    /// Whether the surface is rational.
    pub rational: bool,
    pub loops: Vec<LoopOnFace>,
}

impl EdgeOnFace {
    /// Certified: a curve within `ε` of `S(D)`, and `δ` proven.
    pub fn certified(&self) -> bool {
        self.bound_to_edge.is_some()
    }
}

impl FaceCurves {
    pub fn edges(&self) -> impl Iterator<Item = &EdgeOnFace> {
        self.loops.iter().flat_map(|l| &l.edges)
    }
}

/// The certified curves along every loop of face `fi` of `b` (its surfaces in `m`); `pcs`
/// holds the pcurves (shared by the faces of one model). `None` when the face does not exist
/// or has no surface.
pub fn face_curves(
    b: &Brep,
    m: &Model,
    fi: usize,
    params: &Params,
    pcs: &mut Pcurves,
) -> Option<FaceCurves> {
    let face = b.faces.get(fi)?;
    let surface = m.surfaces.get(face.surface?)?;
    let mut loops = Vec::new();
    let mut uses = std::collections::BTreeMap::<usize, usize>::new();
    for l in &face.loops {
        let LoopKind::Edges(oes) = &l.kind else {
            continue;
        };
        let mut edges = Vec::new();
        for oe in oes {
            let k = uses.entry(oe.edge).or_insert(0);
            let use_index = *k;
            *k += 1;
            let source = b
                .edges
                .get(oe.edge)
                .map(|x| x.source.clone())
                .unwrap_or_default();
            edges.push(edge_on_face(
                pcs, oe.edge, fi, use_index, surface, params, source,
            ));
        }
        loops.push(LoopOnFace {
            bound: l.source.clone(),
            outer: l.outer,
            edges,
        });
    }
    Some(FaceCurves {
        face: face.source.clone(),
        surface: face.surface_source.clone(),
        rational: !surface.nurbs.is_polynomial(),
        loops,
    })
}

fn edge_on_face(
    pcs: &mut Pcurves,
    e: usize,
    fi: usize,
    use_index: usize,
    surface: &crate::model::Surface,
    params: &Params,
    edge: String,
) -> EdgeOnFace {
    let Some(pc) = pcs.polynomial(e, fi, use_index) else {
        return EdgeOnFace {
            edge,
            pcurve: None,
            pcurve_bound: None,
            pcurve_unproven: Some(
                "no pcurve: the edge has no 3D curve, or its projection strays beyond the model tolerance".into(),
            ),
            bound_to_edge: None,
            curves: Vec::new(),
            error: Some("no domain curve".into()),
        };
    };
    let (pcurve_bound, pcurve_unproven) = match pc.bound {
        Ok(d) => (Some(d), None),
        Err(why) => (None, Some(why)),
    };
    let (curves, error) = match pc
        .pieces
        .iter()
        .map(|d| approximate(&surface.nurbs, d, params))
        .collect::<Result<Vec<_>, _>>()
    {
        Ok(r) => (r, None),
        Err(e) => (Vec::new(), Some(e.to_string())),
    };
    // The printed curves' bound (the certified one plus their rounding).
    let eps = curves
        .iter()
        .map(CurveOnSurface::printed_bound)
        .fold(0.0, f64::max);
    let bound_to_edge = match (curves.is_empty(), pcurve_bound) {
        (false, Some(d)) => Some((eps + d).next_up()),
        _ => None,
    };
    EdgeOnFace {
        edge,
        pcurve: Some(pc.origin),
        pcurve_bound,
        pcurve_unproven,
        bound_to_edge,
        curves,
        error,
    }
}
