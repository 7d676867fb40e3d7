//! The NURBS form of a STEP surface entity other than a bare B-spline surface: `plane`,
//! `cylindrical_surface`, `conical_surface`, `spherical_surface` and `toroidal_surface`
//! (spanning the points of the face they bound), `surface_of_revolution`,
//! `surface_of_linear_extrusion` and `rectangular_trimmed_surface`.

use super::{R, Reader};
use crate::geom::Point;
use crate::io::step::StepError;
use crate::io::step::part21::Args;
use crate::model::SurfaceKind;
use crate::spline::construct::{self, Frame};
use crate::spline::{NurbsCurve, NurbsSurface};
use std::collections::BTreeSet;

impl Reader<'_> {
    /// Cartesian points bounding a face: vertices and curve control points reachable from
    /// its bounds, plus the bounding squares of circles.
    fn face_points(&self, face: u64) -> Vec<[f64; 3]> {
        let mut out = Vec::new();
        let mut seen = BTreeSet::new();
        let mut stack: Vec<u64> = self
            .p
            .entities
            .inst(face)
            .and_then(|e| e.part(e.name()))
            .and_then(|a| a.get(1))
            .map(|v| {
                let mut r = vec![];
                v.refs(&mut r);
                r
            })
            .unwrap_or_default();
        while let Some(id) = stack.pop() {
            if !seen.insert(id) || seen.len() > 100_000 {
                continue;
            }
            let Some(e) = self.p.entities.inst(id) else {
                continue;
            };
            if e.is("CARTESIAN_POINT") {
                if let Ok(p) = self.point(id) {
                    out.push(p);
                }
                continue;
            }
            if let Some(a) = e.part("CIRCLE") {
                if let (Some(pl), Some(r)) = (
                    a.get(1).and_then(|v| v.reference()),
                    a.get(2).and_then(|v| v.num()),
                ) && let Ok(f) = self.placement(pl)
                {
                    for (s, t) in [(1.0, 1.0), (1.0, -1.0), (-1.0, 1.0), (-1.0, -1.0)] {
                        out.push(f.at(s * r, t * r, 0.0));
                    }
                }
                continue;
            }
            let walk = [
                "FACE_BOUND",
                "FACE_OUTER_BOUND",
                "EDGE_LOOP",
                "ORIENTED_EDGE",
                "EDGE_CURVE",
                "VERTEX_POINT",
                "VERTEX_LOOP",
                "POLY_LOOP",
                "B_SPLINE_CURVE",
                "B_SPLINE_CURVE_WITH_KNOTS",
                "TRIMMED_CURVE",
                "SURFACE_CURVE",
                "SEAM_CURVE",
            ];
            if walk.iter().any(|w| e.is(w)) {
                stack.extend(e.refs());
            }
        }
        out
    }
    /// Axial range of points in a frame (`None` without points).
    fn axial_range(f: &Frame, pts: &[[f64; 3]]) -> Option<(f64, f64)> {
        Self::heights(f, pts).filter(|(lo, hi)| lo < hi)
    }
    /// The lowest and highest of `pts` along `f`'s z axis (`None` without points).
    fn heights(f: &Frame, pts: &[[f64; 3]]) -> Option<(f64, f64)> {
        pts.iter()
            .map(|p| crate::geom::dot(&p.sub(&f.o), &f.z))
            .fold(None, |m, h| {
                Some(m.map_or((h, h), |(lo, hi): (f64, f64)| (lo.min(h), hi.max(h))))
            })
    }
    /// The NURBS form of surface `id` (bounded by face `face` when given).
    pub(in crate::io::step) fn surface(
        &self,
        id: u64,
        face: Option<u64>,
    ) -> R<Option<(NurbsSurface<f64, 3>, SurfaceKind)>> {
        let e = self.get(id)?;
        let pts = face.map(|f| self.face_points(f)).unwrap_or_default();
        let conv = |r: Result<NurbsSurface<f64, 3>, crate::spline::SplineError>| {
            r.or_else(|x| self.err(id, x.to_string()))
        };
        if e.is("B_SPLINE_SURFACE_WITH_KNOTS") {
            return Ok(Some((self.bspline_surface(id, e)?, SurfaceKind::BSpline)));
        }
        if let Some(a) = e.part("RECTANGULAR_TRIMMED_SURFACE") {
            return self.rectangular_trimmed(id, a);
        }
        if let Some(a) = e.part("PLANE") {
            let f = self.placement(self.reference(id, a, 1)?)?;
            let s = conv(construct::plane_spanning(&f, &pts))?;
            return Ok(Some((s, SurfaceKind::Plane)));
        }
        if let Some(a) = e.part("CYLINDRICAL_SURFACE") {
            let f = self.placement(self.reference(id, a, 1)?)?;
            let r = self.num(id, a, 2)?;
            let (h0, h1) = Self::axial_range(&f, &pts).unwrap_or((0.0, r.max(1.0)));
            return Ok(Some((
                conv(construct::cylinder(&f, r, h0, h1))?,
                SurfaceKind::Cylinder,
            )));
        }
        if let Some(a) = e.part("CONICAL_SURFACE") {
            let f = self.placement(self.reference(id, a, 1)?)?;
            let (r, al) = (self.num(id, a, 2)?, self.num(id, a, 3)? * self.angle_scale);
            // A face bounded by one circle alone runs from it to the apex (radius
            // `r + h tan α` vanishes at `h = −r / tan α`): the only finite face it bounds.
            let apex = -r / al.tan();
            let flat = |lo: f64, hi: f64| hi - lo <= 1e-9 * (r.abs() + lo.abs() + hi.abs());
            let (h0, h1) = match Self::heights(&f, &pts) {
                Some((lo, hi)) if !flat(lo, hi) => (lo, hi),
                Some((h, _)) if apex.is_finite() => (h.min(apex), h.max(apex)),
                _ => (0.0, 1.0),
            };
            return Ok(Some((
                conv(construct::cone(&f, r, al, h0, h1))?,
                SurfaceKind::Cone,
            )));
        }
        if let Some(a) = e.part("SPHERICAL_SURFACE") {
            let f = self.placement(self.reference(id, a, 1)?)?;
            return Ok(Some((
                conv(construct::sphere(&f, self.num(id, a, 2)?))?,
                SurfaceKind::Sphere,
            )));
        }
        if let Some(a) = e.part("TOROIDAL_SURFACE") {
            let f = self.placement(self.reference(id, a, 1)?)?;
            return Ok(Some((
                conv(construct::torus(
                    &f,
                    self.num(id, a, 2)?,
                    self.num(id, a, 3)?,
                ))?,
                SurfaceKind::Torus,
            )));
        }
        if let Some(a) = e.part("SURFACE_OF_REVOLUTION") {
            let c = self.reference(id, a, 1)?;
            let ce = self.get(c)?;
            if !ce.is("B_SPLINE_CURVE_WITH_KNOTS") {
                return Ok(None);
            }
            let curve = self.bspline_curve(c, ce)?;
            let ax = self.reference(id, a, 2)?;
            let aa = self
                .get(ax)?
                .part("AXIS1_PLACEMENT")
                .ok_or_else(|| StepError {
                    file: self.file.into(),
                    location: format!("#{ax}"),
                    reason: "expected AXIS1_PLACEMENT".into(),
                })?;
            let o = self.point(self.reference(ax, aa, 1)?)?;
            let z = match aa.get(2).and_then(|v| v.reference()) {
                Some(r) => self.direction(r)?,
                None => [0.0, 0.0, 1.0],
            };
            return Ok(Some((
                conv(construct::revolve_curve(&o, &z, &curve))?,
                SurfaceKind::Revolution,
            )));
        }
        if let Some(a) = e.part("SURFACE_OF_LINEAR_EXTRUSION") {
            let c = self.reference(id, a, 1)?;
            let ce = self.get(c)?;
            if !ce.is("B_SPLINE_CURVE_WITH_KNOTS") {
                return Ok(None);
            }
            let curve = self.bspline_curve(c, ce)?;
            let v = self.reference(id, a, 2)?;
            let va = self.get(v)?.part("VECTOR").ok_or_else(|| StepError {
                file: self.file.into(),
                location: format!("#{v}"),
                reason: "expected VECTOR".into(),
            })?;
            let d = self
                .direction(self.reference(v, va, 1)?)?
                .scale(&self.num(v, va, 2)?);
            return Ok(Some((
                conv(construct::extrude(&curve, &d))?,
                SurfaceKind::Extrusion,
            )));
        }
        Ok(None)
    }

    /// `rectangular_trimmed_surface`: the basis surface over `[u1, u2] × [v1, v2]` of its own
    /// parametrization (ISO 10303-42), exactly: a B-spline basis by knot insertion
    /// (sub-patch), a plane as the bilinear patch of the rectangle, cylinders, cones, spheres
    /// and tori as the revolution of their profile segment or arc over the angle range.
    /// Angles in the file's plane-angle unit; a decreasing periodic range wraps once. Other
    /// bases: `None` (reported unsupported).
    fn rectangular_trimmed(
        &self,
        id: u64,
        a: Args,
    ) -> R<Option<(NurbsSurface<f64, 3>, SurfaceKind)>> {
        let basis = self.reference(id, a, 1)?;
        let [u1, u2, v1, v2] = [2, 3, 4, 5].map(|i| self.num(id, a, i));
        let (u1, u2, v1, v2) = (u1?, u2?, v1?, v2?);
        let be = self.get(basis)?;
        let conv = |r: Result<NurbsSurface<f64, 3>, crate::spline::SplineError>| {
            r.or_else(|x| self.err(id, x.to_string()))
        };
        let sorted = |a: f64, b: f64| if a <= b { (a, b) } else { (b, a) };
        // Angle ranges in radians, increasing (a decreasing range wraps once around).
        let angles = |a: f64, b: f64| {
            let (a, b) = (a * self.angle_scale, b * self.angle_scale);
            if b > a {
                (a, b)
            } else {
                (a, b + std::f64::consts::TAU)
            }
        };
        if be.is("B_SPLINE_SURFACE_WITH_KNOTS") {
            let s = self.bspline_surface(basis, be)?;
            let ((ua, ub), (va, vb)) = (sorted(u1, u2), sorted(v1, v2));
            let hom = s
                .hom
                .sub_patch(&ua, &ub, &va, &vb)
                .or_else(|x| self.err(id, x.to_string()))?;
            return Ok(Some((NurbsSurface { hom }, SurfaceKind::BSpline)));
        }
        let line = |p: [f64; 3], q: [f64; 3]| {
            NurbsCurve::new(vec![0.0, 0.0, 1.0, 1.0], 1, vec![p, q], vec![1.0; 2])
                .or_else(|x| self.err(id, x.to_string()))
        };
        if let Some(b) = be.part("PLANE") {
            let f = self.placement(self.reference(basis, b, 1)?)?;
            let ((ua, ub), (va, vb)) = (sorted(u1, u2), sorted(v1, v2));
            let s = conv(construct::bilinear(
                f.at(ua, va, 0.0),
                f.at(ub, va, 0.0),
                f.at(ua, vb, 0.0),
                f.at(ub, vb, 0.0),
            ))?;
            return Ok(Some((s, SurfaceKind::Plane)));
        }
        let (kind, f, profile, (ua, ub)) = if let Some(b) = be.part("CYLINDRICAL_SURFACE") {
            let f = self.placement(self.reference(basis, b, 1)?)?;
            let r = self.num(basis, b, 2)?;
            let (va, vb) = sorted(v1, v2);
            let p = line(f.at(r, 0.0, va), f.at(r, 0.0, vb))?;
            (SurfaceKind::Cylinder, f, p, angles(u1, u2))
        } else if let Some(b) = be.part("CONICAL_SURFACE") {
            let f = self.placement(self.reference(basis, b, 1)?)?;
            let (r, t) = (
                self.num(basis, b, 2)?,
                (self.num(basis, b, 3)? * self.angle_scale).tan(),
            );
            let (va, vb) = sorted(v1, v2);
            let p = line(f.at(r + va * t, 0.0, va), f.at(r + vb * t, 0.0, vb))?;
            (SurfaceKind::Cone, f, p, angles(u1, u2))
        } else if let Some(b) = be.part("SPHERICAL_SURFACE") {
            let f = self.placement(self.reference(basis, b, 1)?)?;
            let r = self.num(basis, b, 2)?;
            let (va, vb) = sorted(v1 * self.angle_scale, v2 * self.angle_scale);
            let meridian = Frame {
                o: f.o,
                x: f.x,
                y: f.z,
                z: f.y.scale(&-1.0),
            };
            let p = conv_curve(self, id, construct::arc(&meridian, r, va, vb))?;
            (SurfaceKind::Sphere, f, p, angles(u1, u2))
        } else if let Some(b) = be.part("TOROIDAL_SURFACE") {
            let f = self.placement(self.reference(basis, b, 1)?)?;
            let (major, minor) = (self.num(basis, b, 2)?, self.num(basis, b, 3)?);
            let (va, vb) = angles(v1, v2);
            let tube = Frame {
                o: f.at(major, 0.0, 0.0),
                x: f.x,
                y: f.z,
                z: f.y.scale(&-1.0),
            };
            let p = conv_curve(self, id, construct::arc(&tube, minor, va, vb))?;
            (SurfaceKind::Torus, f, p, angles(u1, u2))
        } else {
            return Ok(None);
        };
        // The profile lies at angle 0 (the placement's x direction); revolve_curve_range
        // measures its angles from there.
        let s = conv(construct::revolve_curve_range(&f.o, &f.z, &profile, ua, ub))?;
        Ok(Some((s, kind)))
    }
}

fn conv_curve(
    r: &Reader,
    id: u64,
    c: Result<NurbsCurve<f64, 3>, crate::spline::SplineError>,
) -> R<NurbsCurve<f64, 3>> {
    c.or_else(|x| r.err(id, x.to_string()))
}
