//! Parameter-space curves (pcurves) the writers give an edge on a face: the source's own,
//! restricted to the edge, where the face's surface is the source's B-spline surface
//! ([`source_pcurve`]); otherwise exact ones on planar patches ([`AffinePatch`]); otherwise
//! none, and readers project the edge's 3D curve themselves.

mod affine;
mod source;
pub use affine::AffinePatch;
pub use source::source_pcurve;

use crate::brep::{Brep, Face};
use crate::model::{Surface, SurfaceKind};
use crate::spline::NurbsCurve;

/// The pcurve a writer gives edge `e` on `face` of `b` (its model surface `surface`),
/// running from the edge's start vertex to its end vertex (see the module comment).
pub fn for_face(b: &Brep, e: usize, face: &Face, surface: &Surface) -> Option<NurbsCurve<f64, 2>> {
    let c = &b.edges.get(e)?.curve.as_ref()?.nurbs;
    if surface.kind == SurfaceKind::BSpline {
        let off = (100.0 * b.tolerance).max(1e-6 * b.extent());
        if let Some(pc) = source_pcurve(b, e, face, &surface.nurbs, off) {
            return Some(pc);
        }
    }
    AffinePatch::new(&surface.nurbs)?.pcurve(c)
}
