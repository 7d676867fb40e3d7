//! Certifying one foreign point (steps 1 and 2 of the parent's list): proven bounds on its
//! distance to each face set ([`crate::ssi::closest`]), then the curve certificate
//! ([`crate::ssi::krawczyk`]) on the nearest faces, and the point's verdict with the reason.

use super::PointStatus;
use crate::ssi::closest::{ClosestParams, IvSurface, closest};
use crate::ssi::krawczyk::{Uncertified, certify_on_curve};
use crate::ssi::trims::TrimRegion;

/// The trimmed regions of each face set's surfaces (`None` for a surface: the whole domain is
/// the face; the second set `None`: one-file mode, the first set's).
pub(crate) type Trims<'a> = (&'a [Option<TrimRegion>], Option<&'a [Option<TrimRegion>]>);

/// Where a certified true intersection point lies with respect to the two faces' trims.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum InFaces {
    /// Its parameter box lies inside both faces' trim polygons.
    Inside,
    /// Its parameter box lies outside one face's trim polygon.
    Outside,
    /// Neither: the box meets a trim polygon's edge.
    Boundary,
}

/// Where the parameter box `params` (`u, v` on face `i` of the first set, `s, t` on face `j`
/// of the second) lies with respect to the faces' trims.
pub(super) fn in_faces(trims: Trims, i: usize, j: usize, params: &[[f64; 2]; 4]) -> InFaces {
    let second = trims.1.unwrap_or(trims.0);
    let ba = [params[0][0], params[0][1], params[1][0], params[1][1]];
    let bb = [params[2][0], params[2][1], params[3][0], params[3][1]];
    let mut out = InFaces::Inside;
    for (r, b) in [(trims.0.get(i), ba), (second.get(j), bb)] {
        let Some(Some(r)) = r else { continue };
        if r.box_outside(&b, 0.0) {
            return InFaces::Outside;
        }
        if !r.box_inside(&b) {
            out = InFaces::Boundary;
        }
    }
    out
}

/// Whether `uv` lies on a trim polygon's edge or outside it (a box of a relative 1e-7 of the
/// domain around it is not wholly inside; `false` for an untrimmed face).
fn on_trim(r: Option<&Option<TrimRegion>>, f: &IvSurface, uv: &[f64; 2]) -> bool {
    let Some(Some(r)) = r else { return false };
    let d = f.dom;
    let (wu, wv) = (1e-7 * (d[1] - d[0]), 1e-7 * (d[3] - d[2]));
    !r.box_inside(&[uv[0] - wu, uv[0] + wu, uv[1] - wv, uv[1] + wv])
}

/// Whether `uv` lies on (within a relative 1e-7 of) a border of the face's domain.
fn on_border(f: &IvSurface, uv: &[f64; 2]) -> bool {
    let d = f.dom;
    let (wu, wv) = (1e-7 * (d[1] - d[0]), 1e-7 * (d[3] - d[2]));
    uv[0] <= d[0] + wu || uv[0] >= d[1] - wu || uv[1] <= d[2] + wv || uv[1] >= d[3] - wv
}

pub(super) struct Check {
    pub(super) status: PointStatus,
    pub(super) reason: &'static str,
    pub(super) upper_a: f64,
    pub(super) upper_b: f64,
    pub(super) lower: f64,
    pub(super) radius: Option<f64>,
}

fn fail_name(e: Uncertified) -> &'static str {
    match e {
        Uncertified::NotFinite => "not_finite",
        Uncertified::Tangency => "tangency",
        Uncertified::Singular => "singular",
        Uncertified::NoContraction => "no_contraction",
        Uncertified::OutsideDomain => "face_border",
        Uncertified::Enclosure => "no_enclosure",
        Uncertified::SignChangeAboveTol => "sign_change_above_tol",
        Uncertified::NotRequested => "not_requested",
    }
}

/// A proven radius within which a true intersection point of the two surfaces lies
/// ([`super::super::krawczyk`]), and the parameter box `(u, v, s, t)` holding it.
pub(super) fn curve_point_radius(
    a: &IvSurface,
    b: &IvSurface,
    x: &[f64; 3],
    uv_a: [f64; 2],
    uv_b: [f64; 2],
) -> Result<(f64, [[f64; 2]; 4]), Uncertified> {
    certify_on_curve(&a.s, &b.s, x, &uv_a, &uv_b)
        .map(|c| (c.radius, c.params.map(|p| [p.lo, p.hi])))
}

/// Check one foreign point against face sets `fa` and `fb` (`None`: one-file mode, the
/// distinct faces of `fa`), trimmed by `trims`.
pub(super) fn check_point(
    fa: &[IvSurface],
    fb: Option<&[IvSurface]>,
    trims: Trims,
    x: &[f64; 3],
    tol: f64,
) -> Check {
    let prm = ClosestParams {
        eps: 0.01 * tol,
        max_pieces: 4000,
    };
    let mut out = Check {
        status: PointStatus::Uncertified,
        reason: "no_face",
        upper_a: f64::INFINITY,
        upper_b: f64::INFINITY,
        lower: 0.0,
        radius: None,
    };
    let Some(ca) = closest(fa, x, &prm, &|_| true) else {
        return out;
    };
    let other = fb.unwrap_or(fa);
    let same = fb.is_none();
    let not_a = |i: usize| !same || i != ca.face;
    let Some(cb) = closest(other, x, &prm, &not_a) else {
        return out;
    };
    out.upper_a = ca.upper;
    out.upper_b = cb.upper;
    out.lower = ca.lower.max(cb.lower);
    if out.lower > tol {
        out.status = PointStatus::Off;
        out.reason = "off_surface";
        return out;
    }
    // Candidate faces: the nearest, then the next nearest within tol (a point near a face
    // border may have its true curve point on the neighbouring face).
    let second = |set: &[IvSurface],
                  first: &super::super::closest::Closest,
                  excl: Option<usize>| {
        closest(set, x, &prm, &|i| i != first.face && Some(i) != excl).filter(|c| c.upper <= tol)
    };
    let mut cands_a = vec![ca];
    let mut cands_b = vec![cb];
    let mut err = Uncertified::NoContraction;
    // A true point within tol whose parameters lie outside a face, or on a trim's edge.
    let (mut outside, mut boundary) = (false, false);
    for round in 0..2 {
        if round == 1 {
            if let Some(c) = second(fa, &ca, same.then_some(cb.face)) {
                cands_a.push(c);
            }
            if let Some(c) = second(other, &cb, same.then_some(ca.face)) {
                cands_b.push(c);
            }
        }
        for (i, a) in cands_a.iter().enumerate() {
            for (j, b) in cands_b.iter().enumerate() {
                if (round == 1 && i == 0 && j == 0) || (same && a.face == b.face) {
                    continue;
                }
                match curve_point_radius(&fa[a.face], &other[b.face], x, a.uv, b.uv) {
                    Ok((r, params)) => {
                        if r <= tol {
                            match in_faces(trims, a.face, b.face, &params) {
                                InFaces::Inside => {
                                    out.radius = Some(r);
                                    out.status = PointStatus::OnCurve;
                                    out.reason = "";
                                    return out;
                                }
                                InFaces::Outside => outside = true,
                                InFaces::Boundary => boundary = true,
                            }
                            continue;
                        }
                        out.radius = Some(out.radius.map_or(r, |q: f64| q.min(r)));
                    }
                    Err(e) => err = e,
                }
            }
        }
    }
    out.reason = if boundary {
        "trim_boundary"
    } else if outside {
        "outside_faces"
    } else if out.radius.is_some() {
        "radius_above_tol"
    } else {
        fail_name(err)
    };
    let border = |c: &super::super::closest::Closest| {
        on_border(&fa[c.face], &c.uv) || on_trim(trims.0.get(c.face), &fa[c.face], &c.uv)
    };
    if same && ca.upper <= tol && cb.upper <= tol && (border(&ca) || border(&cb)) {
        out.status = PointStatus::SharedEdge;
    } else if outside && !boundary {
        out.status = PointStatus::OutsideFaces;
    }
    out
}
