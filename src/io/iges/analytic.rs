//! IGES 5.3 analytic surfaces (§4.23–4.27 of the 5.3 specification): plane (190), right
//! circular cylinder (192), right circular cone (194), sphere (196) and torus (198), each
//! placed by a point (116) and unit directions (123), converted exactly to NURBS.
//!
//! Parameters (form 1 adds the reference direction that fixes the angular origin; form 0 has
//! none and a perpendicular is chosen):
//!
//! | type | parameters |
//! |---|---|
//! | 108 | A, B, C, D (the plane `Ax + By + Cz = D`), PTR, X, Y, Z, SIZE |
//! | 190 | LOCATION, NORMAL[, REFDIR] |
//! | 192 | LOCATION, AXIS, RADIUS[, REFDIR] |
//! | 194 | LOCATION, AXIS, RADIUS (at LOCATION), SANGLE (semi-angle, degrees)[, REFDIR] |
//! | 196 | LOCATION (centre), RADIUS[, AXIS, REFDIR] |
//! | 198 | LOCATION (centre), AXIS, MAJRAD, MINRAD[, REFDIR] |
//!
//! The plane entity 108 has no parametrization (its face's boundary curves bound it). The
//! planes, the cylinder and the cone are unbounded: their NURBS forms span the points of
//! the face that uses them (the vertices and the control points of its edge curves, whose
//! convex hull holds the edges), as for STEP's planes and cylinders. Spheres and tori are
//! whole. A transformation (124) of the surface entity moves the frame; one that is not a
//! rotation (it would turn a circle into an ellipse) is refused with the entity's DE number.
//! The parametrization differs from IGES's (rational quadratic circles instead of angles),
//! so a face's parameter-space curves on these surfaces are not used as trims (the face's
//! B-rep loops are).

use super::{R, Reader};
use crate::geom::Point;
use crate::model::SurfaceKind;
use crate::spline::NurbsSurface;
use crate::spline::construct::{self, Frame};

/// Analytic surface entity types.
pub(super) const ANALYTIC: [i64; 6] = [108, 190, 192, 194, 196, 198];

impl Reader<'_> {
    /// The coordinates of a point entity (116) in model space (its own transformation
    /// applied), or of a direction (123) with only the linear part applied.
    fn vector(&self, owner: usize, i: usize, expect: i64) -> R<[f64; 3]> {
        let de = self.ptr(owner, i)?;
        let ty = self.e[&de].etype;
        if ty != expect {
            return self.err(
                owner,
                format!("parameter {i} points to DE {de} of type {ty}, expected {expect}"),
            );
        }
        let v = self.nums(de, 1, 3)?;
        let mut p = [[v[0], v[1], v[2]]];
        if expect == 116 {
            self.apply(de, &mut p)?;
        } else if let Some((r, _)) = self.transform(de)? {
            p[0] = std::array::from_fn(|k| (0..3).map(|j| r[k][j] * v[j]).sum());
        }
        if !p[0].iter().all(|x| x.is_finite()) {
            return self.err(de, "coordinates are not finite");
        }
        Ok(p[0])
    }

    /// A unit direction (123) parameter.
    fn unit(&self, owner: usize, i: usize) -> R<[f64; 3]> {
        let d = self.vector(owner, i, 123)?;
        let l = crate::geom::norm(&d);
        if !(l > 0.0 && l.is_finite()) {
            return self.err(owner, format!("direction (parameter {i}) has length {l:e}"));
        }
        Ok(d.scale(&(1.0 / l)))
    }

    /// A positive finite number parameter.
    fn positive(&self, de: usize, i: usize, what: &str) -> R<f64> {
        let x = self.nums(de, i, 1)?[0];
        if !(x > 0.0 && x.is_finite()) {
            return self.err(de, format!("{what} {x:e} is not a positive finite number"));
        }
        Ok(x)
    }

    /// The right-handed frame of an analytic surface: origin, axis `z`, angular origin `x`
    /// (the reference direction projected off the axis, or any perpendicular), with the
    /// surface entity's transformation applied (refused unless it is a rotation).
    fn frame(&self, de: usize, o: [f64; 3], z: [f64; 3], refdir: Option<[f64; 3]>) -> R<Frame> {
        let perpendicular = |z: &[f64; 3]| {
            let a = if z[0].abs() < 0.9 {
                [1.0, 0.0, 0.0]
            } else {
                [0.0, 1.0, 0.0]
            };
            a.sub(&z.scale(&crate::geom::dot(&a, z)))
        };
        let mut x = match refdir {
            Some(r) => r.sub(&z.scale(&crate::geom::dot(&r, &z))),
            None => perpendicular(&z),
        };
        let mut l = crate::geom::norm(&x);
        if l <= 1e-9 {
            // The reference direction is along the axis: any perpendicular will do.
            x = perpendicular(&z);
            l = crate::geom::norm(&x);
        }
        let x = x.scale(&(1.0 / l));
        let mut f = Frame {
            o,
            x,
            y: crate::geom::cross(&z, &x),
            z,
        };
        if let Some((r, t)) = self.transform(de)? {
            let lin = |v: &[f64; 3]| -> [f64; 3] {
                std::array::from_fn(|k| (0..3).map(|j| r[k][j] * v[j]).sum())
            };
            let o = lin(&f.o).add(&t);
            let (x, y, z) = (lin(&f.x), lin(&f.y), lin(&f.z));
            let d = crate::geom::dot;
            let off = [d(&x, &x) - 1.0, d(&y, &y) - 1.0, d(&z, &z) - 1.0]
                .iter()
                .chain([d(&x, &y), d(&y, &z), d(&x, &z)].iter())
                .fold(0.0f64, |a, e| a.max(e.abs()));
            if off.is_nan() || off > 1e-9 || !o.iter().all(|c| c.is_finite()) {
                return self.err(
                    de,
                    format!(
                        "transformation DE {} is not a rotation (axes off orthonormal by {off:e}): it would distort the surface",
                        self.e[&de].transform
                    ),
                );
            }
            f = Frame { o, x, y, z };
        }
        Ok(f)
    }

    /// The NURBS form of analytic surface `de`, spanning `pts` (points of the face using
    /// it) where the surface is unbounded.
    pub(super) fn analytic(
        &self,
        de: usize,
        pts: &[[f64; 3]],
    ) -> R<Option<(NurbsSurface<f64, 3>, SurfaceKind)>> {
        let x = &self.e[&de];
        let form1 = x.form == 1;
        let conv = |r: Result<NurbsSurface<f64, 3>, crate::spline::SplineError>| {
            r.or_else(|e| self.err(de, e.to_string()))
        };
        let refdir = |i: usize| -> R<Option<[f64; 3]>> {
            if form1 {
                Ok(Some(self.unit(de, i)?))
            } else {
                Ok(None)
            }
        };
        // Axial range of the face's points in a frame (a unit span without points).
        let axial = |f: &Frame| -> (f64, f64) {
            let hs = pts.iter().map(|p| crate::geom::dot(&p.sub(&f.o), &f.z));
            let lo = hs.clone().fold(f64::INFINITY, f64::min);
            let hi = hs.fold(f64::NEG_INFINITY, f64::max);
            if lo < hi { (lo, hi) } else { (0.0, 1.0) }
        };
        let out = match x.etype {
            108 | 190 => {
                let f = if x.etype == 108 {
                    let c = self.nums(de, 1, 4)?;
                    let n = [c[0], c[1], c[2]];
                    let l2 = crate::geom::dot(&n, &n);
                    if !(l2 > 0.0 && l2.is_finite() && c[3].is_finite()) {
                        return self.err(de, format!("plane coefficients {c:?} define no plane"));
                    }
                    // The point of the plane nearest the origin, the normal, any x.
                    let o = n.scale(&(c[3] / l2));
                    self.frame(de, o, n.scale(&(1.0 / l2.sqrt())), None)?
                } else {
                    let o = self.vector(de, 1, 116)?;
                    self.frame(de, o, self.unit(de, 2)?, refdir(3)?)?
                };
                let s = conv(construct::plane_spanning(&f, pts))?;
                (s, SurfaceKind::Plane)
            }
            192 => {
                let o = self.vector(de, 1, 116)?;
                let r = self.positive(de, 3, "cylinder radius")?;
                let f = self.frame(de, o, self.unit(de, 2)?, refdir(4)?)?;
                let (h0, h1) = axial(&f);
                (
                    conv(construct::cylinder(&f, r, h0, h1))?,
                    SurfaceKind::Cylinder,
                )
            }
            194 => {
                let o = self.vector(de, 1, 116)?;
                let r = self.nums(de, 3, 1)?[0];
                let angle = self.nums(de, 4, 1)?[0];
                if !(r >= 0.0 && r.is_finite() && angle > 0.0 && angle < 90.0) {
                    return self.err(
                        de,
                        format!("cone radius {r:e} or semi-angle {angle:e}° out of range (r ≥ 0, 0° < angle < 90°)"),
                    );
                }
                let f = self.frame(de, o, self.unit(de, 2)?, refdir(5)?)?;
                let (h0, h1) = axial(&f);
                let s = construct::cone(&f, r, angle.to_radians(), h0, h1);
                (conv(s)?, SurfaceKind::Cone)
            }
            196 => {
                let o = self.vector(de, 1, 116)?;
                let r = self.positive(de, 2, "sphere radius")?;
                let (z, rd) = if form1 {
                    (self.unit(de, 3)?, Some(self.unit(de, 4)?))
                } else {
                    ([0.0, 0.0, 1.0], None)
                };
                let f = self.frame(de, o, z, rd)?;
                (conv(construct::sphere(&f, r))?, SurfaceKind::Sphere)
            }
            198 => {
                let o = self.vector(de, 1, 116)?;
                let major = self.positive(de, 3, "torus major radius")?;
                let minor = self.positive(de, 4, "torus minor radius")?;
                let f = self.frame(de, o, self.unit(de, 2)?, refdir(5)?)?;
                (
                    conv(construct::torus(&f, major, minor))?,
                    SurfaceKind::Torus,
                )
            }
            _ => return Ok(None),
        };
        Ok(Some(out))
    }
}
