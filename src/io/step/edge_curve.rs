//! The 3D curve of an `edge_curve` as an exact NURBS form over the edge's range, from its
//! start vertex to its end vertex: `line` (a segment), `circle` and `ellipse` (rational
//! quadratic arcs), `b_spline_curve_with_knots` and its rational complex form (the
//! sub-curve between the vertices' parameters); `trimmed_curve`, `surface_curve` and
//! `seam_curve` resolve to their basis curve / `curve_3d`, the vertices bounding the edge.
//! Pcurves (`pcurve` with a `definitional_representation` of a 2D `line` or B-spline) are
//! read from the `associated_geometry` of surface curves.

use super::entities::Reader;
use super::part21::Args;
use crate::brep::{CurveKind, EdgeCurve, IssueKind, PCurve, PCurveGeometry};
use crate::geom::{Point, dist, dot};
use crate::spline::NurbsCurve;
use crate::spline::construct;
use std::f64::consts::TAU;

/// Reference chains longer than this (trimmed curve of a surface curve of …) are refused.
pub(super) const MAX_DEPTH: usize = 8;

/// Why an edge has no curve: the entity at fault, its type and the fault.
pub(super) struct CurveFault {
    pub id: u64,
    pub ty: String,
    pub kind: IssueKind,
    /// Unsupported (recognised, not converted) rather than invalid.
    pub unsupported: bool,
}

type R<T> = Result<T, CurveFault>;

fn invalid(id: u64, ty: &str, reason: impl Into<String>) -> CurveFault {
    CurveFault {
        id,
        ty: ty.to_string(),
        kind: IssueKind::Malformed(reason.into()),
        unsupported: false,
    }
}

fn step(e: super::StepError, id: u64, ty: &str) -> CurveFault {
    invalid(id, ty, format!("{}: {}", e.location, e.reason))
}

/// What the walk from an edge to its curve found besides the curve.
#[derive(Default)]
pub(super) struct Found {
    /// `(id, type)` of every geometry entity converted.
    pub types: Vec<(u64, String)>,
    pub pcurves: Vec<PCurve>,
    /// Pcurves that could not be read (the 3D curve is still read).
    pub faults: Vec<CurveFault>,
}

/// The edge's curve and the pcurves found on the way: `geometry` is the `edge_geometry`,
/// `p0`, `p1` the start and end vertex points, `same_sense` whether the edge runs along the
/// curve's direction.
pub(super) fn edge_curve(
    r: &Reader,
    geometry: u64,
    p0: &[f64; 3],
    p1: &[f64; 3],
    same_sense: bool,
    found: &mut Found,
) -> R<EdgeCurve> {
    let mut id = geometry;
    let mut sense = same_sense;
    for _ in 0..MAX_DEPTH {
        let e = r.get(id).map_err(|e| CurveFault {
            id,
            ty: "(missing)".into(),
            kind: IssueKind::DanglingReference {
                to: e.location.clone(),
            },
            unsupported: false,
        })?;
        let ty = e.name().to_string();
        if let Some(a) = e.part("SURFACE_CURVE").or_else(|| e.part("SEAM_CURVE")) {
            let ty = if e.is("SEAM_CURVE") {
                "SEAM_CURVE"
            } else {
                "SURFACE_CURVE"
            };
            found.types.push((id, ty.to_string()));
            if let Some(list) = a.get(2).and_then(|v| v.list_refs()) {
                for g in list.flatten() {
                    match pcurve(r, g) {
                        Ok(Some(pc)) => {
                            found.types.push((g, "PCURVE".into()));
                            found.pcurves.push(pc);
                        }
                        Ok(None) => {}
                        Err(f) => found.faults.push(f),
                    }
                }
            }
            id = r.reference(id, a, 1).map_err(|e| step(e, id, ty))?;
            continue;
        }
        if let Some(a) = e.part("TRIMMED_CURVE") {
            found.types.push((id, "TRIMMED_CURVE".into()));
            if a.get(4).and_then(|v| v.enumeration()) == Some("F") {
                sense = !sense;
            }
            id = r
                .reference(id, a, 1)
                .map_err(|e| step(e, id, "TRIMMED_CURVE"))?;
            continue;
        }
        let c = basis_curve(r, id, &ty, p0, p1, sense)?;
        found.types.push((id, ty));
        return Ok(c);
    }
    Err(CurveFault {
        id: geometry,
        ty: r
            .get(geometry)
            .map_or("(missing)", |e| e.name())
            .to_string(),
        kind: IssueKind::TooDeep(MAX_DEPTH),
        unsupported: false,
    })
}

/// The part of a basis curve (line, conic, B-spline) between the vertex points.
fn basis_curve(
    r: &Reader,
    id: u64,
    ty: &str,
    p0: &[f64; 3],
    p1: &[f64; 3],
    sense: bool,
) -> R<EdgeCurve> {
    let e = r.get(id).map_err(|x| step(x, id, ty))?;
    let s = |x| step(x, id, ty);
    let spline = |x: crate::spline::SplineError| invalid(id, ty, x.to_string());
    // Along the curve's own direction the edge runs from `a` to `b`.
    let (a, b) = if sense { (p0, p1) } else { (p1, p0) };
    let (kind, along) = if let Some(args) = e.part("LINE") {
        let o = r.point(r.reference(id, args, 1).map_err(s)?).map_err(s)?;
        let v = r.reference(id, args, 2).map_err(s)?;
        let va = r
            .get(v)
            .map_err(s)?
            .part("VECTOR")
            .ok_or_else(|| invalid(v, "VECTOR", "the line's direction is not a VECTOR"))?;
        let d = r.direction(r.reference(v, va, 1).map_err(s)?).map_err(s)?;
        let at = |p: &[f64; 3]| o.add(&d.scale(&dot(&p.sub(&o), &d)));
        let c = NurbsCurve::new(
            vec![0.0, 0.0, 1.0, 1.0],
            1,
            vec![at(a), at(b)],
            vec![1.0; 2],
        )
        .map_err(spline)?;
        (CurveKind::Line, c)
    } else if let Some(args) = e.part("CIRCLE").or_else(|| e.part("ELLIPSE")) {
        let f = r
            .placement(r.reference(id, args, 1).map_err(s)?)
            .map_err(s)?;
        let ra = r.num(id, args, 2).map_err(s)?;
        let rb = if e.is("ELLIPSE") {
            r.num(id, args, 3).map_err(s)?
        } else {
            ra
        };
        let angle = |p: &[f64; 3]| {
            let d = p.sub(&f.o);
            (dot(&d, &f.y) / rb).atan2(dot(&d, &f.x) / ra)
        };
        let a0 = angle(a);
        let mut sweep = (angle(b) - a0).rem_euclid(TAU);
        if a == b || sweep == 0.0 {
            sweep = TAU;
        }
        let c = construct::conic_arc(a0, a0 + sweep, |x, y| f.at(ra * x, rb * y, 0.0))
            .map_err(spline)?;
        let k = if e.is("ELLIPSE") {
            CurveKind::Ellipse
        } else {
            CurveKind::Circle
        };
        (k, c)
    } else if e.is("B_SPLINE_CURVE_WITH_KNOTS") {
        let c = r.bspline_curve(id, e).map_err(s)?;
        let (_, w) = c.points_weights();
        let k = if w.iter().all(|x| *x == w[0]) {
            CurveKind::BSpline
        } else {
            CurveKind::RationalBSpline
        };
        (k, bspline_range(&c, a, b).map_err(|m| invalid(id, ty, m))?)
    } else {
        return Err(CurveFault {
            id,
            ty: ty.to_string(),
            kind: IssueKind::UnsupportedCurve(ty.to_string()),
            unsupported: true,
        });
    };
    let nurbs = if sense { along } else { along.reversed() };
    let (d0, d1) = nurbs.hom.domain();
    let vertex_gap = dist(&nurbs.eval(&d0), p0).max(dist(&nurbs.eval(&d1), p1));
    Ok(EdgeCurve {
        source: format!("#{id}"),
        kind,
        nurbs,
        vertex_gap,
    })
}

/// The parameter of the point of `c` closest to `p`: the best of a dense sampling, refined
/// by Newton steps on `(C(t) − p)·C'(t)`, kept inside the domain.
fn closest_parameter(c: &NurbsCurve<f64, 3>, p: &[f64; 3]) -> f64 {
    let (t0, t1) = c.hom.domain();
    let n = 16 * c.hom.control.len().max(4);
    let mut best = (f64::INFINITY, t0);
    for i in 0..=n {
        let t = t0 + (t1 - t0) * i as f64 / n as f64;
        let d = dist(&c.eval(&t), p);
        if d < best.0 {
            best = (d, t);
        }
    }
    let mut t = best.1;
    for _ in 0..20 {
        let (x, d1, d2) = c.derivatives2_at(&t);
        let e = x.sub(p);
        let g = dot(&e, &d1);
        let h = dot(&d1, &d1) + dot(&e, &d2);
        if h <= 0.0 || !h.is_finite() {
            break;
        }
        let nt = (t - g / h).clamp(t0, t1);
        if (nt - t).abs() <= 1e-15 * (t1 - t0) {
            t = nt;
            break;
        }
        t = nt;
    }
    if dist(&c.eval(&t), p) <= best.0 {
        t
    } else {
        best.1
    }
}

/// The sub-curve of `c` from the point nearest `a` to the point nearest `b` (the whole curve
/// when they are its ends; when `a` and `b` coincide on a closed curve, the whole curve
/// started at their point).
fn bspline_range(
    c: &NurbsCurve<f64, 3>,
    a: &[f64; 3],
    b: &[f64; 3],
) -> Result<NurbsCurve<f64, 3>, String> {
    let (d0, d1) = c.hom.domain();
    let span = d1 - d0;
    let snap = |t: f64| {
        if (t - d0).abs() <= 1e-9 * span {
            d0
        } else if (d1 - t).abs() <= 1e-9 * span {
            d1
        } else {
            t
        }
    };
    let closed = dist(&c.eval(&d0), &c.eval(&d1))
        <= 1e-9 * (1.0 + a.iter().map(|x| x.abs()).fold(0.0, f64::max));
    let (mut ta, mut tb) = (snap(closest_parameter(c, a)), snap(closest_parameter(c, b)));
    if closed && a == b {
        if ta == d0 || ta == d1 {
            return Ok(c.clone());
        }
        // A closed edge whose vertex lies inside the curve's range (periodic curves written
        // from another start point): the curve from the vertex round to the vertex.
        let head = c.hom.sub_curve(&ta, &d1).map_err(|e| e.to_string())?;
        let tail = c.hom.sub_curve(&d0, &ta).map_err(|e| e.to_string())?;
        return NurbsCurve { hom: head }
            .joined(&NurbsCurve { hom: tail })
            .map_err(|e| e.to_string());
    }
    if closed && ta == d1 {
        ta = d0;
    }
    if closed && tb == d0 {
        tb = d1;
    }
    if ta >= tb {
        return Err(format!(
            "the edge's vertices lie at parameters {ta} and {tb}: not an increasing range of the curve (a range across the closing point of a closed curve is not supported)"
        ));
    }
    if ta == d0 && tb == d1 {
        return Ok(c.clone());
    }
    Ok(NurbsCurve {
        hom: c.hom.sub_curve(&ta, &tb).map_err(|e| e.to_string())?,
    })
}

/// A 2D point or direction: the first two coordinates of `CARTESIAN_POINT` / `DIRECTION`.
fn coords2(r: &Reader, id: u64, ty: &str) -> R<[f64; 2]> {
    let e = r.get(id).map_err(|x| step(x, id, ty))?;
    let c: Option<Vec<f64>> = e.part(ty).and_then(|a| a.get(1)).and_then(|v| v.numbers());
    match c {
        Some(c) if c.len() == 2 && c.iter().all(|x| x.is_finite()) => Ok([c[0], c[1]]),
        _ => Err(invalid(id, ty, "not a 2D entity with two finite numbers")),
    }
}

/// A `pcurve` (`None` for another kind of associated geometry, e.g. a bare surface).
fn pcurve(r: &Reader, id: u64) -> R<Option<PCurve>> {
    let e = r.get(id).map_err(|x| step(x, id, "PCURVE"))?;
    let Some(a) = e.part("PCURVE") else {
        return Ok(None);
    };
    let s = |x| step(x, id, "PCURVE");
    let surface = r.reference(id, a, 1).map_err(s)?;
    let rep = r.reference(id, a, 2).map_err(s)?;
    let items = r
        .get(rep)
        .map_err(s)?
        .part("DEFINITIONAL_REPRESENTATION")
        .and_then(|d| d.get(1))
        .and_then(|v| v.list_refs())
        .ok_or_else(|| {
            invalid(
                rep,
                "DEFINITIONAL_REPRESENTATION",
                "expected a DEFINITIONAL_REPRESENTATION with a list of items",
            )
        })?;
    let Some(cid) = items.flatten().next() else {
        return Err(invalid(rep, "DEFINITIONAL_REPRESENTATION", "no curve item"));
    };
    let ce = r.get(cid).map_err(s)?;
    let geometry = if let Some(la) = ce.part("LINE") {
        let o = coords2(r, r.reference(cid, la, 1).map_err(s)?, "CARTESIAN_POINT")?;
        let v = r.reference(cid, la, 2).map_err(s)?;
        let va = r
            .get(v)
            .map_err(s)?
            .part("VECTOR")
            .ok_or_else(|| invalid(v, "VECTOR", "expected a VECTOR"))?;
        let d = coords2(r, r.reference(v, va, 1).map_err(s)?, "DIRECTION")?;
        let m = r.num(v, va, 2).map_err(s)?;
        let l = (d[0] * d[0] + d[1] * d[1]).sqrt();
        if l == 0.0 {
            return Err(invalid(v, "VECTOR", "zero direction"));
        }
        PCurveGeometry::Line {
            origin: o,
            direction: [d[0] / l * m, d[1] / l * m],
        }
    } else if let Some(args) = ce.part("CIRCLE").or_else(|| ce.part("ELLIPSE")) {
        PCurveGeometry::Nurbs(conic2(r, cid, args, ce.is("ELLIPSE"))?)
    } else if ce.is("B_SPLINE_CURVE_WITH_KNOTS") {
        let c = r.bspline_curve(cid, ce).map_err(s)?;
        let (pts, w) = c.points_weights();
        let c2 = NurbsCurve::new(
            c.hom.knots.knots().to_vec(),
            c.hom.degree(),
            pts.iter().map(|p| [p[0], p[1]]).collect(),
            w,
        )
        .map_err(|x| invalid(cid, "B_SPLINE_CURVE_WITH_KNOTS", x.to_string()))?;
        PCurveGeometry::Nurbs(c2)
    } else {
        let ty = ce.name().to_string();
        return Err(CurveFault {
            id: cid,
            kind: IssueKind::UnsupportedPCurve(format!("{ty} (as a pcurve of #{id})")),
            ty,
            unsupported: true,
        });
    };
    Ok(Some(PCurve {
        source: format!("#{id}"),
        surface_source: format!("#{surface}"),
        geometry,
    }))
}

/// A 2D circle or ellipse (`args` of instance `id`: name, `axis2_placement_2d`, radius or
/// semi-axes) as its exact rational quadratic NURBS form, the whole curve counter-clockwise
/// from the placement's `ref_direction` ([`construct::conic_arc`]). The edge's part
/// of it is found where it is used, from the vertices (`brep::pcurve::source`).
fn conic2(r: &Reader, id: u64, args: Args, ellipse: bool) -> R<NurbsCurve<f64, 2>> {
    let ty = if ellipse { "ELLIPSE" } else { "CIRCLE" };
    let s = |x| step(x, id, ty);
    let pl = r.reference(id, args, 1).map_err(s)?;
    let pa = r
        .get(pl)
        .map_err(|x| step(x, pl, "AXIS2_PLACEMENT_2D"))?
        .part("AXIS2_PLACEMENT_2D")
        .ok_or_else(|| invalid(pl, "AXIS2_PLACEMENT_2D", "expected an AXIS2_PLACEMENT_2D"))?;
    let o = coords2(r, r.reference(pl, pa, 1).map_err(s)?, "CARTESIAN_POINT")?;
    let x = match pa.get(2).and_then(|v| v.reference()) {
        Some(d) => coords2(r, d, "DIRECTION")?,
        None => [1.0, 0.0],
    };
    let l = (x[0] * x[0] + x[1] * x[1]).sqrt();
    if !(l > 0.0 && l.is_finite()) {
        return Err(invalid(pl, "AXIS2_PLACEMENT_2D", "zero ref_direction"));
    }
    let (x, y) = ([x[0] / l, x[1] / l], [-x[1] / l, x[0] / l]);
    let ra = r.num(id, args, 2).map_err(s)?;
    let rb = if ellipse {
        r.num(id, args, 3).map_err(s)?
    } else {
        ra
    };
    if !(ra > 0.0 && rb > 0.0 && ra.is_finite() && rb.is_finite()) {
        return Err(invalid(id, ty, "radius not positive and finite"));
    }
    construct::conic_arc(0.0, TAU, |a, b| {
        let (a, b) = (ra * a, rb * b);
        [o[0] + a * x[0] + b * y[0], o[1] + a * x[1] + b * y[1]]
    })
    .map_err(|e| invalid(id, ty, e.to_string()))
}
