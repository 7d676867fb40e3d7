//! Exact NURBS forms of analytic surfaces (The NURBS Book §7.5, A8.1): full circles as nine
//! weighted points, surfaces of revolution and linear extrusions of NURBS profiles. Weights
//! `√2/2` are rounded to f64 (the only inexact quantity).

use super::{NurbsCurve, NurbsSurface, SplineError};
use crate::geom::Point;

const H: f64 = std::f64::consts::FRAC_1_SQRT_2;

/// Unit circle in the plane, as a rational quadratic with 9 control points `(x, y, w)`.
pub const UNIT_CIRCLE: [([f64; 2], f64); 9] = [
    ([1.0, 0.0], 1.0),
    ([1.0, 1.0], H),
    ([0.0, 1.0], 1.0),
    ([-1.0, 1.0], H),
    ([-1.0, 0.0], 1.0),
    ([-1.0, -1.0], H),
    ([0.0, -1.0], 1.0),
    ([1.0, -1.0], H),
    ([1.0, 0.0], 1.0),
];
/// Its knots on `[0, 1]`.
pub const CIRCLE_KNOTS: [f64; 12] = [
    0.0, 0.0, 0.0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1.0, 1.0, 1.0,
];

/// A placement: origin and orthonormal axes `x`, `y`, `z`.
#[derive(Clone, Copy, Debug)]
pub struct Frame {
    pub o: [f64; 3],
    pub x: [f64; 3],
    pub y: [f64; 3],
    pub z: [f64; 3],
}

impl Frame {
    /// The world frame: origin and the coordinate axes.
    pub const WORLD: Frame = Frame {
        o: [0.0; 3],
        x: [1.0, 0.0, 0.0],
        y: [0.0, 1.0, 0.0],
        z: [0.0, 0.0, 1.0],
    };

    /// The point `o + a x + b y + c z`.
    pub fn at(&self, a: f64, b: f64, c: f64) -> [f64; 3] {
        self.o
            .add(&self.x.scale(&a))
            .add(&self.y.scale(&b))
            .add(&self.z.scale(&c))
    }
}

/// Revolve a profile given in the frame's `(x, z)` half-plane (points `(ρ, h)` with weights)
/// a full turn about the frame's z axis: `S(u, v)`, u around the axis, v along the profile.
pub fn revolve(
    f: &Frame,
    profile: &[([f64; 2], f64)],
    profile_knots: Vec<f64>,
    degree: usize,
) -> Result<NurbsSurface<f64, 3>, SplineError> {
    let mut pts = Vec::with_capacity(9 * profile.len());
    let mut ws = Vec::with_capacity(9 * profile.len());
    for (c, wc) in UNIT_CIRCLE {
        for (p, wp) in profile {
            pts.push(f.at(p[0] * c[0], p[0] * c[1], p[1]));
            ws.push(wc * wp);
        }
    }
    NurbsSurface::new(
        CIRCLE_KNOTS.to_vec(),
        2,
        profile_knots,
        degree,
        9,
        profile.len(),
        pts,
        ws,
    )
}

/// Revolve a 3D NURBS profile a full turn about the axis through `o` with unit direction
/// `z` (The NURBS Book A8.1, full circle): each control point sweeps the circle about the
/// axis through it, in its own radial frame.
pub fn revolve_curve(
    o: &[f64; 3],
    z: &[f64; 3],
    c: &NurbsCurve<f64, 3>,
) -> Result<NurbsSurface<f64, 3>, SplineError> {
    revolve_curve_range(o, z, c, 0.0, std::f64::consts::TAU)
}

/// Revolve a 3D NURBS profile about the axis through `o` with unit direction `z` from angle
/// `a0` to `a1` (radians; the profile's position is angle 0): the u direction is the arc of
/// [`arc`] (pieces of at most 90°, weights `cos(Δ/2)`), v the profile.
pub fn revolve_curve_range(
    o: &[f64; 3],
    z: &[f64; 3],
    c: &NurbsCurve<f64, 3>,
    a0: f64,
    a1: f64,
) -> Result<NurbsSurface<f64, 3>, SplineError> {
    let unit = Frame::WORLD;
    let circle = arc(&unit, 1.0, a0, a1)?;
    let (cpts, cws) = circle.points_weights();
    let (pp, pw) = c.points_weights();
    let n = pp.len();
    let mut pts = Vec::with_capacity(cpts.len() * n);
    let mut ws = Vec::with_capacity(cpts.len() * n);
    for (cp, wc) in cpts.iter().zip(&cws) {
        for (p, wp) in pp.iter().zip(&pw) {
            let rel = p.sub(o);
            let h = crate::geom::dot(&rel, z);
            let radial = rel.sub(&z.scale(&h));
            let y = crate::geom::cross(z, &radial);
            pts.push(
                o.add(&z.scale(&h))
                    .add(&radial.scale(&cp[0]))
                    .add(&y.scale(&cp[1])),
            );
            ws.push(wc * wp);
        }
    }
    NurbsSurface::new(
        circle.hom.knots.knots().to_vec(),
        2,
        c.hom.knots.knots().to_vec(),
        c.hom.degree(),
        cpts.len(),
        n,
        pts,
        ws,
    )
}

/// Circular arc of radius `r` in the frame's `(x, y)` plane, counter-clockwise from angle
/// `a0` to `a1` (radians, `a1 > a0`, at most a full turn): rational quadratic pieces of at
/// most 90°, middle weights `cos(Δ/2)` (The NURBS Book A7.1).
pub fn arc(f: &Frame, r: f64, a0: f64, a1: f64) -> Result<NurbsCurve<f64, 3>, SplineError> {
    positive("arc radius", r)?;
    // Angles beyond ±2^52 have no fractional part left: the arc would not be where it says.
    let sweep = a1 - a0;
    let usable = a0.abs() <= 4.5e15
        && a1.abs() <= 4.5e15
        && sweep > 0.0
        && sweep <= std::f64::consts::TAU * (1.0 + 1e-9);
    if !usable {
        return Err(SplineError::Invalid(format!(
            "arc angles {a0:e} .. {a1:e} (radians) are not an increasing range of at most a full turn"
        )));
    }
    let sweep = sweep.clamp(1e-300, std::f64::consts::TAU);
    let n = (sweep / std::f64::consts::FRAC_PI_2 - 1e-12)
        .ceil()
        .max(1.0) as usize;
    let d = sweep / n as f64;
    let w1 = (d / 2.0).cos();
    let at = |a: f64| f.at(r * a.cos(), r * a.sin(), 0.0);
    let mut pts = vec![at(a0)];
    let mut ws = vec![1.0];
    let mut knots = vec![0.0; 3];
    for k in 0..n {
        let (s, e) = (a0 + k as f64 * d, a0 + (k + 1) as f64 * d);
        let m = (s + e) / 2.0;
        pts.push(f.at(r / w1 * m.cos(), r / w1 * m.sin(), 0.0));
        ws.push(w1);
        pts.push(at(e));
        ws.push(1.0);
        if k + 1 < n {
            knots.extend([(k + 1) as f64 / n as f64; 2]);
        }
    }
    knots.extend([1.0; 3]);
    NurbsCurve::new(knots, 2, pts, ws)
}

/// The affine image `place(x, y)` of the unit circle's arc from `a0` to `a1` ([`arc`]): a
/// circular or elliptic arc in any frame, 2D or 3D. Exact: an affine image of a NURBS curve is
/// the curve of its control points' images with the same knots and weights.
pub fn conic_arc<const D: usize>(
    a0: f64,
    a1: f64,
    place: impl Fn(f64, f64) -> [f64; D],
) -> Result<NurbsCurve<f64, D>, SplineError> {
    let unit = arc(&Frame::WORLD, 1.0, a0, a1)?;
    let (pts, ws) = unit.points_weights();
    let pts = pts.iter().map(|p| place(p[0], p[1])).collect();
    NurbsCurve::new(unit.hom.knots.knots().to_vec(), 2, pts, ws)
}

/// Extrude a NURBS curve along `d`: `S(u, v) = C(u) + v d`, `v ∈ [0, 1]`.
pub fn extrude(c: &NurbsCurve<f64, 3>, d: &[f64; 3]) -> Result<NurbsSurface<f64, 3>, SplineError> {
    let (cp, cw) = c.points_weights();
    let n = cp.len();
    let mut pts = Vec::with_capacity(2 * n);
    let mut ws = Vec::with_capacity(2 * n);
    for (p, w) in cp.iter().zip(&cw) {
        pts.push(*p);
        pts.push(p.add(d));
        ws.push(*w);
        ws.push(*w);
    }
    NurbsSurface::new(
        c.hom.knots.knots().to_vec(),
        c.hom.degree(),
        vec![0.0, 0.0, 1.0, 1.0],
        1,
        n,
        2,
        pts,
        ws,
    )
}

/// Bilinear patch with corners `p00, p10, p01, p11` (u along the first index).
pub fn bilinear(
    p00: [f64; 3],
    p10: [f64; 3],
    p01: [f64; 3],
    p11: [f64; 3],
) -> Result<NurbsSurface<f64, 3>, SplineError> {
    let k = vec![0.0, 0.0, 1.0, 1.0];
    NurbsSurface::new(
        k.clone(),
        1,
        k,
        1,
        2,
        2,
        vec![p00, p01, p10, p11],
        vec![1.0; 4],
    )
}

/// The rectangle of the frame's xy plane spanning the projections of `pts` (a plane face's
/// points), as a bilinear patch; the square `[-1, 1]²` when they span no area.
pub fn plane_spanning(f: &Frame, pts: &[[f64; 3]]) -> Result<NurbsSurface<f64, 3>, SplineError> {
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for p in pts {
        let d = p.sub(&f.o);
        let c = [crate::geom::dot(&d, &f.x), crate::geom::dot(&d, &f.y)];
        for i in 0..2 {
            lo[i] = lo[i].min(c[i]);
            hi[i] = hi[i].max(c[i]);
        }
    }
    if !(lo[0] < hi[0] && lo[1] < hi[1]) {
        (lo, hi) = ([-1.0, -1.0], [1.0, 1.0]);
    }
    bilinear(
        f.at(lo[0], lo[1], 0.0),
        f.at(hi[0], lo[1], 0.0),
        f.at(lo[0], hi[1], 0.0),
        f.at(hi[0], hi[1], 0.0),
    )
}

/// Cylinder of radius `r` about the frame's z axis for `h ∈ [h0, h1]`.
pub fn cylinder(f: &Frame, r: f64, h0: f64, h1: f64) -> Result<NurbsSurface<f64, 3>, SplineError> {
    positive("cylinder radius", r)?;
    revolve(
        f,
        &[([r, h0], 1.0), ([r, h1], 1.0)],
        vec![0.0, 0.0, 1.0, 1.0],
        1,
    )
}

/// Cone with radius `r` at `h = 0` and semi-angle `alpha`, for `h ∈ [h0, h1]`.
pub fn cone(
    f: &Frame,
    r: f64,
    alpha: f64,
    h0: f64,
    h1: f64,
) -> Result<NurbsSurface<f64, 3>, SplineError> {
    let t = alpha.tan();
    revolve(
        f,
        &[([r + h0 * t, h0], 1.0), ([r + h1 * t, h1], 1.0)],
        vec![0.0, 0.0, 1.0, 1.0],
        1,
    )
}

/// `x` is a positive finite number, or an error naming `what`.
fn positive(what: &str, x: f64) -> Result<(), SplineError> {
    if x > 0.0 && x.is_finite() {
        Ok(())
    } else {
        Err(SplineError::Invalid(format!(
            "{what} {x:e} is not a positive finite number"
        )))
    }
}

/// Full sphere of radius `r` centred at the frame's origin.
pub fn sphere(f: &Frame, r: f64) -> Result<NurbsSurface<f64, 3>, SplineError> {
    positive("sphere radius", r)?;
    let prof = [
        ([0.0, -r], 1.0),
        ([r, -r], H),
        ([r, 0.0], 1.0),
        ([r, r], H),
        ([0.0, r], 1.0),
    ];
    revolve(f, &prof, vec![0.0, 0.0, 0.0, 0.5, 0.5, 1.0, 1.0, 1.0], 2)
}

/// Full torus: tube of radius `minor` around the circle of radius `major`.
pub fn torus(f: &Frame, major: f64, minor: f64) -> Result<NurbsSurface<f64, 3>, SplineError> {
    positive("torus minor radius", minor)?;
    positive("torus major radius", major)?;
    let prof: Vec<([f64; 2], f64)> = UNIT_CIRCLE
        .iter()
        .map(|(c, w)| ([major + minor * c[0], minor * c[1]], *w))
        .collect();
    revolve(f, &prof, CIRCLE_KNOTS.to_vec(), 2)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::{dist, norm};
    fn frame() -> Frame {
        let z = [0.0, 0.6, 0.8];
        let x = [1.0, 0.0, 0.0];
        Frame {
            o: [1.0, -2.0, 3.0],
            x,
            y: crate::geom::cross(&z, &x),
            z,
        }
    }
    #[test]
    fn partial_revolution_is_exact() {
        // A line parallel to the axis at distance 2, revolved over 30°..200°: a cylinder piece.
        let prof = NurbsCurve::new(
            vec![0.0, 0.0, 1.0, 1.0],
            1,
            vec![[2.0, 0.0, -1.0], [2.0, 0.0, 3.0]],
            vec![1.0, 1.0],
        )
        .unwrap();
        let (a0, a1) = (30f64.to_radians(), 200f64.to_radians());
        let s = revolve_curve_range(&[0.0; 3], &[0.0, 0.0, 1.0], &prof, a0, a1).unwrap();
        for i in 0..=30 {
            for j in 0..=4 {
                let p = s.eval(&(i as f64 / 30.0), &(j as f64 / 4.0));
                assert!(((p[0] * p[0] + p[1] * p[1]).sqrt() - 2.0).abs() < 1e-14);
                let ang = p[1].atan2(p[0]).rem_euclid(std::f64::consts::TAU);
                assert!(ang >= a0 - 1e-12 && ang <= a1 + 1e-12, "{ang}");
            }
        }
        let start = s.eval(&0.0, &0.0);
        assert!(
            (start[0] - 2.0 * a0.cos()).abs() < 1e-14 && (start[1] - 2.0 * a0.sin()).abs() < 1e-14
        );
    }

    #[test]
    fn closed_forms_hold_at_many_parameters() {
        let f = frame();
        let s = sphere(&f, 2.5).unwrap();
        let c = cylinder(&f, 1.5, -1.0, 2.0).unwrap();
        let k = cone(&f, 1.0, 0.3, -0.5, 1.5).unwrap();
        let t = torus(&f, 3.0, 0.75).unwrap();
        for i in 0..=40 {
            for j in 0..=40 {
                let (u, v) = (i as f64 / 40.0, j as f64 / 40.0);
                assert!((dist(&s.eval(&u, &v), &f.o) - 2.5).abs() < 1e-14 * 8.0);
                let p = c.eval(&u, &v).sub(&f.o);
                let h = crate::geom::dot(&p, &f.z);
                assert!((norm(&p.sub(&f.z.scale(&h))) - 1.5).abs() < 1e-14 * 8.0);
                let p = k.eval(&u, &v).sub(&f.o);
                let h = crate::geom::dot(&p, &f.z);
                assert!((norm(&p.sub(&f.z.scale(&h))) - (1.0 + h * 0.3f64.tan())).abs() < 1e-13);
                let p = t.eval(&u, &v).sub(&f.o);
                let h = crate::geom::dot(&p, &f.z);
                let rho = norm(&p.sub(&f.z.scale(&h)));
                assert!((((rho - 3.0).powi(2) + h * h).sqrt() - 0.75).abs() < 1e-13);
            }
        }
    }
}
