//! Clipping intersection curves to the faces' trimming loops (on by default; `--untrimmed` turns it off).
//!
//! Each trim loop is polygonized in the parameter plane (every curve sampled at
//! [`SAMPLES_PER_CURVE`] + 1 parameters, the curves' end points exactly) and outlined as the
//! mesher outlines it ([`crate::tessellate::trimmed`]); a parameter point is
//! inside the face when the even-odd rule over all loops says so, decided with exact
//! orientation signs against the polygon edges. The polygon is an approximation of the trim
//! curves (evidence-level near the trim boundary, said in the report); the decision for the
//! polygon is exact. A branch is cut where it leaves either face; the cut ends are marked
//! [`EndKind::TrimBoundary`].

use super::fit::fit_branch;
use super::krawczyk::Uncertified;
use super::report::{BranchOut, EndKind};
use crate::model::{Model, Surface};
use crate::spline::closure::Closure;
use crate::tessellate::region::FaceRegion;
use crate::tessellate::{MeshParams, face_regions, trimmed};

pub use crate::tessellate::trimmed::SAMPLES_PER_CURVE;

/// Every face's or surface's region (`None`: not clipped), the faces that could not be
/// outlined (with why), and the faces outlined against their declared outer loop
/// ([`FaceRegion::ambiguous`]).
pub type Outlined = (Vec<Option<TrimRegion>>, Vec<String>, Vec<String>);

/// A face's trimmed region as polygons in its parameter plane: one or more
/// [`FaceRegion`]s (a B-rep face each, or the face's own trim loops); inside any of them is
/// inside the face.
pub struct TrimRegion {
    regions: Vec<FaceRegion>,
}

impl TrimRegion {
    /// `None` when the face has no trim loops (the whole domain is the face). The loops are
    /// outlined as the mesher outlines them ([`trimmed::trim_polygons`]): with only inner
    /// loops (holes; IGES 144 with no outer boundary, N1 = 0: "the outer boundary is the
    /// boundary of D") the face is the domain minus the holes (a frame around them), loops
    /// winding around a seam are closed into bands. On a surface closed in a direction (a seam, [`Closure`]) the face is
    /// periodic in it, as a B-rep face's region is: a point is in the face when some shift
    /// by whole periods puts it in the polygons. `Err` when the loops' polygons cross (exact,
    /// [`crate::tessellate::simple::first_crossing`]): the even-odd rule would take a pocket
    /// of the face for its complement, or the reverse.
    pub fn of(s: &Surface) -> Result<Option<TrimRegion>, String> {
        if s.trim_loops.is_empty() {
            return Ok(None);
        }
        let size = trimmed::surface_size(s);
        let p = MeshParams::for_area();
        let mut none = |_: [f64; 3]| 0;
        let polys = trimmed::trim_polygons(
            s,
            size,
            SAMPLES_PER_CURVE,
            (p.relative_edge * size, p.max_turn),
            &mut none,
        )
        .map_err(|e| format!("surface {}: its trim loops are not outlined: {e}", s.name))?;
        let closure = Closure::of(&s.nurbs);
        let (u0, u1, v0, v1) = s.nurbs.hom.domain();
        let period = [
            closure.seam_u.then_some(u1 - u0),
            closure.seam_v.then_some(v1 - v0),
        ];
        Ok(Some(TrimRegion {
            regions: vec![FaceRegion::new(0, &polys, period, [u0, u1, v0, v1])],
        }))
    }

    /// The regions of the B-rep faces on each surface of `m` (`None`: no face of the B-rep
    /// uses the surface, or none could be outlined — then the surface is not clipped; the
    /// faces that could not be outlined are returned with the reason).
    pub fn of_brep(m: &Model) -> Outlined {
        let mut out: Vec<Option<TrimRegion>> = (0..m.surfaces.len()).map(|_| None).collect();
        let mut failed = Vec::new();
        let mut ambiguous = Vec::new();
        let mut unclipped = vec![false; m.surfaces.len()];
        let Some(brep) = &m.brep else {
            return (out, failed, ambiguous);
        };
        for (f, r) in brep
            .faces
            .iter()
            .zip(face_regions(m, brep, &MeshParams::for_area()))
        {
            match r {
                Ok(r) => {
                    if r.ambiguous {
                        ambiguous.push(format!(
                            "face {}: a loop declared outer runs clockwise about the face's normal on a closed surface (taken as the rest of the surface, as the orientation says; the declaration says its inside)",
                            f.source
                        ));
                    }
                    let s = r.surface;
                    out[s]
                        .get_or_insert_with(|| TrimRegion { regions: vec![] })
                        .regions
                        .push(r)
                }
                Err(e) => {
                    failed.push(format!("face {}: {e}", f.source));
                    if let Some(s) = f.surface.filter(|s| *s < out.len()) {
                        unclipped[s] = true;
                    }
                }
            }
        }
        // A surface with a face that could not be outlined is not clipped at all (its other
        // faces' regions would leave that face's part out).
        for (s, u) in unclipped.iter().enumerate() {
            if *u {
                out[s] = None;
            }
        }
        (out, failed, ambiguous)
    }

    /// The regions of every surface of `m`: its B-rep faces' when it has a B-rep
    /// ([`TrimRegion::of_brep`]), else each surface's own trim loops ([`TrimRegion::of`]);
    /// with the faces or surfaces that could not be outlined (not clipped), and why, and the
    /// ambiguous faces.
    pub fn of_model(m: &Model) -> Outlined {
        if m.brep.is_some() {
            TrimRegion::of_brep(m)
        } else {
            let mut failed = Vec::new();
            let regions = m
                .surfaces
                .iter()
                .map(|s| {
                    TrimRegion::of(s).unwrap_or_else(|e| {
                        failed.push(e);
                        None
                    })
                })
                .collect();
            (regions, failed, vec![])
        }
    }

    /// The parameter box lies wholly inside one of the regions.
    pub fn box_inside(&self, b: &[f64; 4]) -> bool {
        self.regions.iter().any(|r| r.box_inside(b))
    }

    /// The parameter box, widened by `margin` of the domain, lies wholly inside one of the
    /// regions.
    pub fn box_inside_widened(&self, b: &[f64; 4], margin: f64) -> bool {
        self.regions.iter().any(|r| {
            let mu = margin * (r.domain[1] - r.domain[0]).abs();
            let mv = margin * (r.domain[3] - r.domain[2]).abs();
            r.box_inside(&[b[0] - mu, b[1] + mu, b[2] - mv, b[3] + mv])
        })
    }

    /// Inside any of the regions.
    pub fn inside(&self, p: &[f64; 2]) -> bool {
        self.regions.iter().any(|r| r.inside(p))
    }

    /// The loop polygons' edges meeting the parameter box widened by `margin` of the domain
    /// ([`crate::tessellate::region::FaceRegion::edges_meeting`], over every region).
    pub fn edges_meeting(
        &self,
        b: &[f64; 4],
        margin: f64,
    ) -> Vec<crate::tessellate::region::LoopEdge> {
        self.regions
            .iter()
            .flat_map(|r| r.edges_meeting(b, margin))
            .collect()
    }

    /// The parameter box (widened by `margin` of the domain) lies outside every region.
    pub fn box_outside(&self, b: &[f64; 4], margin: f64) -> bool {
        self.regions.iter().all(|r| r.box_outside(b, margin))
    }
}

fn refit(b: &mut BranchOut) {
    b.fit = if b.tangents.is_empty() {
        fit_branch(&b.points, &b.uv_a, &b.uv_b, b.closed)
    } else {
        super::fit::fit_pieces(&b.pieces())
    };
}

/// The parts of `b` inside both trimmed faces (`None`: untrimmed face).
pub fn clip(b: &BranchOut, ra: Option<&TrimRegion>, rb: Option<&TrimRegion>) -> Vec<BranchOut> {
    let keep: Vec<bool> = (0..b.points.len())
        .map(|i| ra.is_none_or(|r| r.inside(&b.uv_a[i])) && rb.is_none_or(|r| r.inside(&b.uv_b[i])))
        .collect();
    clip_mask(b, &keep)
}

/// The runs of points of `b` with `keep` set, as branches of their own (cut ends
/// [`EndKind::TrimBoundary`]); runs of one point are dropped.
pub fn clip_mask(b: &BranchOut, keep: &[bool]) -> Vec<BranchOut> {
    clip_mask_as(b, keep, EndKind::TrimBoundary)
}

/// [`clip_mask`] with cut ends of kind `cut`.
pub fn clip_mask_as(b: &BranchOut, keep: &[bool], cut: EndKind) -> Vec<BranchOut> {
    let n = b.points.len();
    if keep.iter().all(|k| *k) {
        return vec![b.clone()];
    }
    // Runs of kept points; for a closed branch, start after a dropped point so a run may wrap.
    let start = if b.closed {
        keep.iter().position(|k| !k).unwrap_or(0)
    } else {
        0
    };
    let mut runs: Vec<Vec<usize>> = Vec::new();
    let mut cur: Vec<usize> = Vec::new();
    for s in 0..n {
        let i = (start + s) % n;
        if keep[i] {
            cur.push(i);
        } else if !cur.is_empty() {
            runs.push(std::mem::take(&mut cur));
        }
    }
    if !cur.is_empty() {
        runs.push(cur);
    }
    runs.into_iter()
        .filter(|r| r.len() >= 2)
        .map(|r| {
            let end_kind = |i: usize, first: bool| -> EndKind {
                let orig_end = !b.closed && ((first && i == 0) || (!first && i == n - 1));
                if orig_end {
                    b.ends[if first { 0 } else { 1 }]
                } else {
                    cut
                }
            };
            let curve = b.curve_results();
            let mut out = BranchOut {
                closed: false,
                points: r.iter().map(|&i| b.points[i]).collect(),
                uv_a: r.iter().map(|&i| b.uv_a[i]).collect(),
                uv_b: r.iter().map(|&i| b.uv_b[i]).collect(),
                tangents: if b.tangents.is_empty() {
                    Vec::new()
                } else {
                    r.iter()
                        .map(|&i| b.tangents.get(i).copied().flatten())
                        .collect()
                },
                ends: vec![end_kind(r[0], true), end_kind(r[r.len() - 1], false)],
                fit: None,
                ..b.clone()
            };
            out.set_curve_results(
                r.iter()
                    .map(|&i| curve.get(i).copied().unwrap_or(Err(Uncertified::NotFinite)))
                    .collect(),
            );
            // The part gets its own fit when the branch had one.
            if b.fit.is_some() {
                refit(&mut out);
            }
            out
        })
        .collect()
}
