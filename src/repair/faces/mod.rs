//! Repair of a B-rep whose faces are trimmed: the paper's steps that apply to faces bounded
//! by curves inside their surfaces, with edges in place of patch borders.
//!
//! Uva, Monno & Hamann repair patch sets whose patches meet along their parameter
//! rectangles' borders: averaging (§4) rewrites a patch's boundary row and merging (§5–6)
//! joins rectangles of patches. A trimmed face's boundary is a curve inside its surface, so
//! neither applies to it. What does:
//! 1. **Connectivity (Algorithm 1)** — [`sew`]: free edges whose end vertices lie within
//!    `u1` of each other and whose curves agree within `u1` become one shared edge; the end
//!    vertices move to their cluster's mean (§4 iv).
//! 2. **Verification (§3.1)** — per shared edge, the gap between the two faces' boundaries:
//!    each face's pcurve of the edge has a proven Hausdorff bound to the edge's curve where
//!    [`crate::brep::edge_check::edge_faces`] proves one, and the two faces' boundary
//!    images are then within the sum of the two bounds of each other (triangle inequality):
//!    a **proven** gap. Where a side has no bound within `u2`, the edge's measured distance
//!    from that face's surface stands in (evidence). Edges at or above `u2` are listed.
//! 3. **Feature edges (§5.1)** — [`angles`]: the largest angle between the faces' normals
//!    along each shared edge; above the feature angle a feature edge (sampled: evidence).
//!
//! The surfaces, trims and edge curves are not changed; gaps are reported, not closed.

pub mod angles;
mod check;
pub mod job;
pub mod picture;
mod report;
pub mod sew;
mod t_split;

use super::{RepairError, RepairParams};
use crate::brep::Brep;
use crate::model::Model;
use serde::Serialize;
use std::collections::BTreeMap;

/// One shared edge after repair: the gap between its faces' boundaries and their angle.
#[derive(Clone, Debug, Serialize)]
pub struct EdgeGap {
    /// Index into the repaired B-rep's edges.
    #[serde(skip)]
    pub index: usize,
    /// Source ids of the edge and of its two faces.
    pub edge: String,
    pub faces: [String; 2],
    /// Proven bound on the distance between the two faces' boundaries along the edge (the
    /// sum of both faces' proven pcurve bounds; `None` where a side has none).
    pub gap_bound_proven: Option<f64>,
    /// The same sum with the measured distance of the edge from a face's surface where that
    /// side has no bound within `u2` (evidence).
    pub gap_evidence: f64,
    /// Largest angle between the faces' normals along the edge (degrees; sampled).
    pub normal_angle_deg: Option<f64>,
    pub feature: bool,
}

/// A shell after repair: closed when every edge of its faces is used exactly twice.
#[derive(Clone, Debug, Serialize)]
pub struct ShellClosure {
    pub source: String,
    pub faces: usize,
    pub closed: bool,
}

/// What the repair of a B-rep's faces did and found.
#[derive(Clone, Debug, Default, Serialize)]
pub struct FacesReport {
    /// Always `"faces"` (a patch-set repair's report has no such field).
    pub mode: &'static str,
    pub faces: usize,
    /// Faces not bounded by their surface's parameter rectangle ([`crate::brep::natural`]).
    pub trimmed_faces: Vec<String>,
    pub edges_before: usize,
    pub edges_after: usize,
    /// Edges used by one face, before and after.
    pub free_edges_before: usize,
    pub free_edges_after: usize,
    /// Edges used by more than two faces, after.
    pub non_manifold_edges: Vec<String>,
    /// Shells, and how many were closed, before the repair.
    pub shells_before: usize,
    pub closed_shells_before: usize,
    /// The shells after (shells that sewn edges connect are one).
    pub shells: Vec<ShellClosure>,
    pub sewing: sew::Sewing,
    /// Every edge used by two faces (a seam: the same face twice, left out), after.
    pub edges: Vec<EdgeGap>,
    /// The repaired B-rep's tolerance: the largest gap below `u2` along a shared edge
    /// (proven where proven), at least the source's.
    pub tolerance: f64,
    /// Shared edges whose gap is proven below `u2`.
    pub gaps_proven_below_u2: usize,
    /// Largest proven gap, where every shared edge has one.
    pub gap_max_proven: Option<f64>,
    pub gap_max_evidence: f64,
    /// Shared edges whose gap (proven, else evidence) is at or above `u2`.
    pub gaps_left: Vec<String>,
    pub feature_edges: usize,
    /// Edges still used by one face, with that face.
    pub free_edges: Vec<[String; 2]>,
    /// Their indices into the repaired B-rep's edges.
    #[serde(skip)]
    pub free_edge_index: Vec<usize>,
    pub not_done: Vec<String>,
    pub seconds: f64,
}

/// The report and the repaired B-rep (the model's surfaces are unchanged).
#[derive(Clone, Debug)]
pub struct FacesResult {
    pub report: FacesReport,
    pub brep: Brep,
}

/// The figure an edge's gap is judged by: the smaller of the proven bound (when there is
/// one) and the evidence. An edge is left open when it is at or above `u2`, and the repaired
/// B-rep's tolerance is the largest below `u2`.
pub fn gap_figure(proven: Option<f64>, evidence: f64) -> f64 {
    proven.map_or(evidence, |p| p.min(evidence))
}

fn free_count(b: &Brep) -> usize {
    angles::edge_uses(b)
        .values()
        .filter(|u| u.len() == 1)
        .count()
}

fn closed(b: &Brep, faces: &[(usize, bool)]) -> bool {
    let uses = b.edge_uses(faces);
    !uses.is_empty() && uses.values().all(|n| *n == 2)
}

/// Repair the faces of `m`'s B-rep (see the module comment).
pub fn repair_faces(
    m: &Model,
    prm: &RepairParams,
    progress: &dyn Fn(&str),
) -> Result<FacesResult, RepairError> {
    let t0 = std::time::Instant::now();
    super::check_params(prm)?;
    let mut b = m.brep.clone().ok_or(RepairError::NoFaces)?;
    if b.faces.is_empty() {
        return Err(RepairError::NoFaces);
    }
    if let Some(why) = check::dangling(&b, m.surfaces.len()) {
        return Err(RepairError::Brep(why));
    }
    let natural = crate::brep::natural::natural_faces(&b, m);
    let mut r = FacesReport {
        mode: "faces",
        faces: b.faces.len(),
        trimmed_faces: b
            .faces
            .iter()
            .zip(&natural)
            .filter(|x| !x.1)
            .map(|x| x.0.source.clone())
            .collect(),
        edges_before: b.edges.len(),
        free_edges_before: free_count(&b),
        ..Default::default()
    };
    r.shells_before = b.shells.len();
    r.closed_shells_before = b.shells.iter().filter(|s| closed(&b, &s.faces)).count();
    progress("connectivity: free edges");
    r.sewing = sew::sew_free_edges(&mut b, prm.u1);
    r.edges_after = b.edges.len();
    let after: Vec<bool> = b.shells.iter().map(|s| closed(&b, &s.faces)).collect();
    for (s, c) in b.shells.iter_mut().zip(after) {
        r.shells.push(ShellClosure {
            source: s.source.clone(),
            faces: s.faces.len(),
            closed: c,
        });
        s.closed = c;
    }
    progress("verification: edges on faces");
    // Pcurves are made for edges within the B-rep's tolerance of their faces: u2 during
    // the verification; afterwards the largest gap found below u2 (at least the source's).
    let source_tolerance = b.tolerance;
    b.tolerance = b.tolerance.max(prm.u2);
    let on_faces = crate::brep::edge_check::edge_faces(&b, m, prm.u2 / 2.0);
    let mut side: BTreeMap<(usize, usize), (Option<f64>, f64)> = BTreeMap::new();
    for p in on_faces {
        let evidence = match (p.bound, p.measured) {
            (Some(d), _) if d <= prm.u2 / 2.0 => d,
            (_, Some(x)) => x,
            (Some(d), None) => d,
            (None, None) => f64::INFINITY,
        };
        side.insert((p.edge, p.face), (p.bound, evidence));
    }
    progress("feature angles");
    let uses = angles::edge_uses(&b);
    let mut feet = BTreeMap::new();
    for (&e, us) in &uses {
        let source = b.edges[e].source.clone();
        match us[..] {
            [a] => {
                r.free_edges.push([source, b.faces[a.face].source.clone()]);
                r.free_edge_index.push(e);
            }
            [a, c] if a.face != c.face => {
                let (sa, sc) = (side.get(&(e, a.face)), side.get(&(e, c.face)));
                let proven = match (sa.and_then(|x| x.0), sc.and_then(|x| x.0)) {
                    // Rounded up: the sum of two bounds is a bound.
                    (Some(x), Some(y)) => Some((x + y).next_up()),
                    _ => None,
                };
                let evidence =
                    sa.map_or(f64::INFINITY, |x| x.1) + sc.map_or(f64::INFINITY, |x| x.1);
                let angle = angles::normal_angle(&b, m, &mut feet, e, [a, c]);
                let feature = angle.is_some_and(|x| x > prm.feature_angle_deg);
                if gap_figure(proven, evidence) >= prm.u2 {
                    r.gaps_left.push(source.clone());
                }
                r.edges.push(EdgeGap {
                    index: e,
                    edge: source,
                    faces: [
                        b.faces[a.face].source.clone(),
                        b.faces[c.face].source.clone(),
                    ],
                    gap_bound_proven: proven,
                    gap_evidence: evidence,
                    normal_angle_deg: angle,
                    feature,
                });
            }
            [_, _] => {}
            _ => r.non_manifold_edges.push(source),
        }
    }
    r.free_edges_after = r.free_edges.len();
    r.feature_edges = r.edges.iter().filter(|e| e.feature).count();
    r.gaps_proven_below_u2 = r
        .edges
        .iter()
        .filter(|e| e.gap_bound_proven.is_some_and(|g| g < prm.u2))
        .count();
    r.gap_max_proven = r
        .edges
        .iter()
        .map(|e| e.gap_bound_proven)
        .try_fold(0.0f64, |m, g| g.map(|g| m.max(g)));
    r.gap_max_evidence = r.edges.iter().map(|e| e.gap_evidence).fold(0.0, f64::max);
    b.tolerance = r
        .edges
        .iter()
        .map(|e| gap_figure(e.gap_bound_proven, e.gap_evidence))
        .filter(|g| *g < prm.u2)
        .fold(source_tolerance, f64::max);
    r.tolerance = b.tolerance;
    if !r.trimmed_faces.is_empty() {
        r.not_done.push(format!(
            "boundary averaging and merging (§4–6) need faces bounded by their surfaces' parameter rectangles; {} of {} faces are trimmed: surfaces, trims and edge curves are unchanged, gaps are reported, not closed",
            r.trimmed_faces.len(),
            r.faces
        ));
    }
    if !r.gaps_left.is_empty() {
        r.not_done.push(format!(
            "{} shared edge(s) with a gap at or above u2 (not closed)",
            r.gaps_left.len()
        ));
    }
    r.seconds = t0.elapsed().as_secs_f64();
    let out = FacesResult { report: r, brep: b };
    debug_assert!(out.check().is_empty(), "{:?}", out.check());
    Ok(out)
}
