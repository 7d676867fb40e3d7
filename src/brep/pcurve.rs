//! Parameter-space curves (pcurves) the writers give an edge on a face: the source's own,
//! restricted to the edge, where the face's surface is the source's B-spline surface
//! ([`source_pcurve`]); otherwise exact ones on planar patches ([`AffinePatch`]); otherwise
//! one made by projecting the edge's 3D curve onto the surface ([`project`]), with a proven
//! bound on its image's distance from the edge where one can be had; otherwise none, and
//! readers project the edge themselves (an edge a face uses twice — a seam — or whose
//! projection would cross the surface's seam).

mod affine;
mod chart;
mod check;
mod cut;
mod polynomial;
pub mod project;
mod seam_sides;
mod source;
pub use affine::AffinePatch;
pub use polynomial::{PcurveOrigin, PolynomialPcurve};
pub use source::source_pcurve;

use crate::brep::{Brep, Face, LoopKind};
use crate::model::{Model, Surface, SurfaceKind};
use crate::spline::NurbsCurve;
use project::{Fit, Projector};
use std::collections::BTreeMap;

/// The pcurve a writer gives edge `e` on `face` of `b` (its model surface `surface`) from the
/// source or a plane, running from the edge's start vertex to its end vertex (see the module
/// comment); [`Pcurves`] adds projected ones.
pub fn for_face(b: &Brep, e: usize, face: &Face, surface: &Surface) -> Option<NurbsCurve<f64, 2>> {
    own_pcurve(b, e, face, surface).map(|x| x.0)
}

/// [`for_face`] with where the pcurve came from.
fn own_pcurve(
    b: &Brep,
    e: usize,
    face: &Face,
    surface: &Surface,
) -> Option<(NurbsCurve<f64, 2>, PcurveOrigin)> {
    let c = &b.edges.get(e)?.curve.as_ref()?.nurbs;
    if surface.kind == SurfaceKind::BSpline {
        let off = (100.0 * b.tolerance).max(1e-6 * b.extent());
        if let Some(pc) = source_pcurve(b, e, face, &surface.nurbs, off) {
            return Some((pc, PcurveOrigin::Source));
        }
    }
    AffinePatch::new(&surface.nurbs)?
        .pcurve(c)
        .map(|pc| (pc, PcurveOrigin::Plane))
}

/// How many times the loops of `face` use edge `e` (twice: a seam).
fn uses(face: &Face, e: usize) -> usize {
    face.loops
        .iter()
        .map(|l| match &l.kind {
            LoopKind::Edges(oes) => oes.iter().filter(|o| o.edge == e).count(),
            LoopKind::Vertex(_) => 0,
        })
        .sum()
}

/// The pcurves one writer gives a B-rep's edges, projected ones included, with what the
/// projections gave for its notes.
pub struct Pcurves<'a> {
    b: &'a Brep,
    m: &'a Model,
    /// How near a projected pcurve's image is to lie to its edge: aiming at 1e-8 of the
    /// model's size, accepting the model tolerance.
    fit: Fit,
    projectors: BTreeMap<usize, Projector<'a>>,
    /// `(edge, model surface)` → the projected pcurve and its proven bound.
    made: BTreeMap<(usize, usize), Option<Made>>,
    /// `(seam edge, model surface)` → its pcurves on both sides and their proven bound.
    seams: BTreeMap<(usize, usize), Option<SeamSides>>,
}

/// A projected pcurve and its proven bound, when it has one.
type Made = (NurbsCurve<f64, 2>, Option<f64>);

/// A seam edge's pcurves on the two sides of its surface's seam, and their proven bound.
type SeamSides = ([NurbsCurve<f64, 2>; 2], f64);

impl<'a> Pcurves<'a> {
    pub fn new(b: &'a Brep, m: &'a Model) -> Pcurves<'a> {
        Pcurves {
            b,
            m,
            fit: Fit {
                aim: 1e-8 * b.extent(),
                off: b.tolerance.max(1e-8 * b.extent()),
            },
            projectors: BTreeMap::new(),
            made: BTreeMap::new(),
            seams: BTreeMap::new(),
        }
    }

    /// The pcurve of edge `e` on face `fi`, from its start vertex to its end vertex.
    pub fn get(&mut self, e: usize, fi: usize) -> Option<NurbsCurve<f64, 2>> {
        let (b, m) = (self.b, self.m);
        let face = b.faces.get(fi)?;
        let si = face.surface?;
        let surface = m.surfaces.get(si)?;
        if let Some(pc) = for_face(b, e, face, surface) {
            return Some(pc);
        }
        if let Some(made) = self.made.get(&(e, si)) {
            return made.as_ref().map(|x| x.0.clone());
        }
        if uses(face, e) > 1 {
            // A seam edge: one pcurve per side ([`Pcurves::seam_sides`]).
            return None;
        }
        let c = &b.edges.get(e)?.curve.as_ref()?.nurbs;
        let fit = self.fit;
        let made = self
            .face_projector(fi)?
            .1
            .project(c, None, None, fit)
            .map(|p| (p.curve, p.bound));
        let out = made.as_ref().map(|x| x.0.clone());
        self.made.insert((e, si), made);
        out
    }

    /// Face `fi`'s model surface and the projector on it (made once per surface).
    fn face_projector(&mut self, fi: usize) -> Option<(usize, &Projector<'a>)> {
        let (b, m) = (self.b, self.m);
        let si = b.faces.get(fi)?.surface?;
        let surface = m.surfaces.get(si)?;
        let p = self
            .projectors
            .entry(si)
            .or_insert_with(|| Projector::new(&surface.nurbs));
        Some((si, p))
    }

    /// The pcurves of edge `e` on both sides of the seam of face `fi`'s closed surface, each
    /// from the edge's start vertex to its end vertex, where the face's loops use `e` twice
    /// (a seam edge) and it lies along the seam; a loop takes the side its neighbours' pcurves
    /// meet ([`crate::io`]'s writers decide).
    pub fn seam_sides(&mut self, e: usize, fi: usize) -> Option<[NurbsCurve<f64, 2>; 2]> {
        let b = self.b;
        let si = b.faces.get(fi)?.surface?;
        if !self.seams.contains_key(&(e, si)) {
            let c = &b.edges.get(e)?.curve.as_ref()?.nurbs;
            let fit = self.fit;
            let sides = self.face_projector(fi)?.1.seam_sides(c, fit);
            self.seams.insert((e, si), sides);
        }
        self.seams.get(&(e, si))?.as_ref().map(|s| s.0.clone())
    }

    /// Whether `a` and `b`, parameters on face `fi`'s surface, lie on one of its poles (one
    /// point of space, where a loop may jump in the parameter plane).
    pub fn on_one_pole(&mut self, fi: usize, a: [f64; 2], b: [f64; 2]) -> bool {
        self.face_projector(fi)
            .is_some_and(|(_, p)| p.chart.on_one_pole(a, b))
    }

    /// The loop of pcurves `pcs` of face `fi` with segments along its surface's poles where
    /// the loop crosses one (`project::pole_joins`).
    pub fn pole_joins(
        &mut self,
        fi: usize,
        pcs: Vec<NurbsCurve<f64, 2>>,
    ) -> Vec<NurbsCurve<f64, 2>> {
        match self.face_projector(fi) {
            Some((_, p)) => project::pole_joins(p, pcs),
            None => pcs,
        }
    }

    /// The proven bound on the distance between the image of the projected pcurve of edge
    /// `e` on face `fi` and the edge (`None` where [`Pcurves::get`] gave none, gave the
    /// source's or a plane's, or gave one on evidence only).
    pub fn bound(&self, e: usize, fi: usize) -> Option<f64> {
        let si = self.b.faces.get(fi)?.surface?;
        self.made.get(&(e, si))?.as_ref()?.1
    }

    /// What the projections gave, for a writer's notes (`None` when none was tried).
    pub fn note(&self) -> Option<String> {
        if self.made.is_empty() && self.seams.is_empty() {
            return None;
        }
        let made: Vec<Option<f64>> = self.made.values().flatten().map(|x| x.1).collect();
        let proven: Vec<f64> = made.iter().flatten().copied().collect();
        let worst = proven.iter().copied().fold(0.0, f64::max);
        let mut s = format!(
            "pcurves made by projecting edges onto faces the source gave none on: {} of {} edge-surface pairs; {} proven within {:.1e} of their edges (largest bound {:.1e}; interval Bézier composition, crate::spline::pcurve_bound)",
            made.len(),
            self.made.len(),
            proven.len(),
            self.fit.off,
            worst
        );
        if proven.len() < made.len() {
            s += &format!(", {} checked at samples only", made.len() - proven.len());
        }
        if made.len() < self.made.len() {
            s += &format!(
                "; {} left to the reader (a projection that would cross the surface's seam, or none within the tolerance)",
                self.made.len() - made.len()
            );
        }
        let seams: Vec<f64> = self.seams.values().flatten().map(|x| x.1).collect();
        if !seams.is_empty() {
            s += &format!(
                "; {} seam edge(s) given pcurves on both sides of their surface's seam, proven (largest bound {:.1e})",
                seams.len(),
                seams.iter().copied().fold(0.0, f64::max)
            );
        }
        Some(s)
    }
}
