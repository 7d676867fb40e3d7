//! Polynomial pcurves with a proven distance to their edges: the domain curves a face's
//! boundary gives the certified curves on a surface (`crate::curve_on_surface::face`),
//! which take polynomial domain curves (Yang et al. treat B-spline `D`).

use super::Pcurves;
use crate::spline::NurbsCurve;

/// Where a face's pcurve of an edge came from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum PcurveOrigin {
    /// The source's own pcurve (on its B-spline surface), restricted to the edge.
    Source,
    /// The edge mapped into a planar patch's parameters (exact, affine).
    Plane,
    /// Projected onto the surface ([`super::project`]), where the source gave none, gave a
    /// rational one, or the edge is a seam (one pcurve per side).
    Projected,
}

/// A polynomial pcurve of an edge on a face, from the edge's start vertex to its end vertex,
/// in one piece or — where the edge's projection crosses the surface's seam — in pieces cut
/// there, in order; and the proven bound on the Hausdorff distance between each piece's
/// image and its part of the edge's 3D curve (the largest; `Err`: why none was proven).
#[derive(Clone, Debug)]
pub struct PolynomialPcurve {
    pub pieces: Vec<NurbsCurve<f64, 2>>,
    pub origin: PcurveOrigin,
    pub bound: Result<f64, String>,
}

impl Pcurves<'_> {
    /// The polynomial pcurve of edge `e` on face `fi` for its `use_index`-th use in the
    /// face's loops (a seam edge, used twice, takes a different side of the seam on each
    /// use): the source's or a plane's when polynomial, else a projected one. `None` where
    /// the edge has no 3D curve, the face no surface, or no pcurve could be made.
    pub fn polynomial(
        &mut self,
        e: usize,
        fi: usize,
        use_index: usize,
    ) -> Option<PolynomialPcurve> {
        let (b, m) = (self.b, self.m);
        let face = b.faces.get(fi)?;
        let surface = m.surfaces.get(face.surface?)?;
        let arc = &b.edges.get(e)?.curve.as_ref()?.nurbs;
        let target = self.fit.aim;
        let uses = super::uses(face, e);
        if uses > 1
            && let Some(sides) = self.seam_sides(e, fi)
        {
            let si = face.surface?;
            let bound = self.seams.get(&(e, si))?.as_ref()?.1;
            return Some(PolynomialPcurve {
                pieces: vec![sides[use_index.min(1)].clone()],
                origin: PcurveOrigin::Projected,
                bound: Ok(bound),
            });
        }
        // Polynomial with control points in the domain (then the curve is in it: convex
        // hull); a plane's or the source's pcurve reaching past the surface's domain (an
        // edge within the file's tolerance of the face but off its patch) is projected.
        let (u0, u1, v0, v1) = surface.nurbs.hom.domain();
        let polynomial = |c: &NurbsCurve<f64, 2>| {
            c.hom
                .control
                .iter()
                .all(|h| h.w == 1.0 && (u0..=u1).contains(&h.wp[0]) && (v0..=v1).contains(&h.wp[1]))
        };
        let own = super::own_pcurve(b, e, face, surface);
        let fit = self.fit;
        let projector = self.face_projector(fi)?.1;
        match own {
            Some((c, origin)) if polynomial(&c) => Some(PolynomialPcurve {
                bound: projector.check(&c, arc, target),
                pieces: vec![c],
                origin,
            }),
            _ => {
                let parts = projector.project_cut(arc, fit)?;
                let bound = parts
                    .iter()
                    .map(|(_, p)| p.bound)
                    .try_fold(0.0f64, |m, b| b.map(|b| m.max(b)))
                    .ok_or_else(|| {
                        "the projection's bound is above the model tolerance or unproven".into()
                    });
                Some(PolynomialPcurve {
                    pieces: parts.into_iter().map(|(_, p)| p.curve).collect(),
                    origin: PcurveOrigin::Projected,
                    bound,
                })
            }
        }
    }

    /// The source's or a plane's pcurve of edge `e` on face `fi`, polynomial or rational, with
    /// the proven bound on the distance between its image and the edge (the same composition
    /// as for the polynomial ones, [`crate::spline::pcurve_bound`], which takes rational
    /// pcurves with positive weights); `None` where the face has no such pcurve or uses the
    /// edge more than once (a seam: one pcurve per side, [`Pcurves::polynomial`]). A bound
    /// needs no polynomial pcurve, so no projection is made for it.
    pub fn own_bound(
        &mut self,
        e: usize,
        fi: usize,
        target: f64,
    ) -> Option<(PcurveOrigin, Result<f64, String>)> {
        let (b, m) = (self.b, self.m);
        let face = b.faces.get(fi)?;
        let surface = m.surfaces.get(face.surface?)?;
        let arc = &b.edges.get(e)?.curve.as_ref()?.nurbs;
        let uses = super::uses(face, e);
        if uses != 1 {
            return None;
        }
        let (c, origin) = super::own_pcurve(b, e, face, surface)?;
        let projector = self.face_projector(fi)?.1;
        Some((origin, projector.check(&c, arc, target)))
    }
}
