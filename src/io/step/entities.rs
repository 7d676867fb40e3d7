//! Conversion of STEP geometry entities (B-spline and analytic surfaces and curves, with
//! their placements) into NURBS, each fault located at its entity.

mod surfaces;

use super::StepError;
use super::part21::{Args, Inst, Part21, Val};
use crate::geom::Point;
use crate::spline::construct::Frame;
use crate::spline::{NurbsCurve, NurbsSurface};

pub(super) struct Reader<'a> {
    pub p: &'a Part21,
    pub file: &'a str,
    pub angle_scale: f64,
}

type R<T> = Result<T, StepError>;

impl<'a> Reader<'a> {
    pub(super) fn err<T>(&self, id: u64, reason: impl Into<String>) -> R<T> {
        Err(StepError {
            file: self.file.into(),
            location: format!("#{id}"),
            reason: reason.into(),
        })
    }
    pub(super) fn get(&self, id: u64) -> R<Inst<'a>> {
        match self.p.entities.inst(id) {
            Some(e) => Ok(e),
            None => self.err(id, "reference to a missing instance"),
        }
    }
    pub(super) fn arg<'b>(&self, id: u64, args: Args<'b>, i: usize) -> R<Val<'b>> {
        match args.get(i) {
            Some(v) => Ok(v),
            None => self.err(id, format!("missing attribute {i}")),
        }
    }
    pub(super) fn num(&self, id: u64, args: Args, i: usize) -> R<f64> {
        match self.arg(id, args, i)?.num() {
            Some(x) if x.is_finite() => Ok(x),
            _ => self.err(id, format!("attribute {i} is not a number")),
        }
    }
    /// A degree (or other count): an integer, not a real that would be truncated.
    fn degree(&self, id: u64, args: Args, i: usize) -> R<usize> {
        let x = self.num(id, args, i)?;
        if x.fract() != 0.0 || !(1.0..=crate::spline::MAX_DEGREE as f64).contains(&x) {
            return self.err(
                id,
                format!(
                    "attribute {i} (degree) is {x}, not an integer in 1..={}",
                    crate::spline::MAX_DEGREE
                ),
            );
        }
        Ok(x as usize)
    }
    pub(super) fn reference(&self, id: u64, args: Args, i: usize) -> R<u64> {
        match self.arg(id, args, i)?.reference() {
            Some(r) => Ok(r),
            None => self.err(id, format!("attribute {i} is not a reference")),
        }
    }
    pub(super) fn point(&self, id: u64) -> R<[f64; 3]> {
        let a = self
            .get(id)?
            .part("CARTESIAN_POINT")
            .ok_or_else(|| StepError {
                file: self.file.into(),
                location: format!("#{id}"),
                reason: "expected a CARTESIAN_POINT".into(),
            })?;
        match self.arg(id, a, 1).map(|v| v.numbers())? {
            Some(c) if c.len() == 3 && c.iter().all(|x| x.is_finite()) => Ok([c[0], c[1], c[2]]),
            Some(c) if c.len() == 2 => Ok([c[0], c[1], 0.0]),
            _ => self.err(id, "point coordinates are not 2 or 3 finite numbers"),
        }
    }
    pub(super) fn direction(&self, id: u64) -> R<[f64; 3]> {
        let a = self.get(id)?.part("DIRECTION").ok_or_else(|| StepError {
            file: self.file.into(),
            location: format!("#{id}"),
            reason: "expected a DIRECTION".into(),
        })?;
        match self.arg(id, a, 1).map(|v| v.numbers())? {
            Some(c) if c.len() == 3 => {
                let l = crate::geom::norm(&[c[0], c[1], c[2]]);
                if l > 0.0 && l.is_finite() {
                    Ok([c[0] / l, c[1] / l, c[2] / l])
                } else {
                    self.err(id, "zero or non-finite direction")
                }
            }
            _ => self.err(id, "direction is not 3 numbers"),
        }
    }
    pub(super) fn placement(&self, id: u64) -> R<Frame> {
        let a = self
            .get(id)?
            .part("AXIS2_PLACEMENT_3D")
            .or_else(|| self.p.entities.inst(id)?.part("AXIS1_PLACEMENT"));
        let Some(a) = a else {
            return self.err(id, "expected an AXIS2_PLACEMENT_3D");
        };
        let o = self.point(self.reference(id, a, 1)?)?;
        let z = match a.get(2).and_then(|v| v.reference()) {
            Some(r) => self.direction(r)?,
            None => [0.0, 0.0, 1.0],
        };
        let xr = match a.get(3).and_then(|v| v.reference()) {
            Some(r) => self.direction(r)?,
            None => {
                if z[0].abs() < 0.9 {
                    [1.0, 0.0, 0.0]
                } else {
                    [0.0, 1.0, 0.0]
                }
            }
        };
        let x = xr.sub(&z.scale(&crate::geom::dot(&xr, &z)));
        let l = crate::geom::norm(&x);
        if l == 0.0 {
            return self.err(id, "ref_direction parallel to axis");
        }
        let x = x.scale(&(1.0 / l));
        Ok(Frame {
            o,
            x,
            y: crate::geom::cross(&z, &x),
            z,
        })
    }
    fn knots(&self, id: u64, mults: Val, knots: Val) -> R<Vec<f64>> {
        let (Some(m), Some(k)) = (mults.list(), knots.numbers()) else {
            return self.err(id, "knot multiplicities or knots malformed");
        };
        if m.len() != k.len() {
            return self.err(
                id,
                format!("{} multiplicities for {} knots", m.len(), k.len()),
            );
        }
        let mut out = Vec::new();
        for (mi, ki) in m.into_iter().zip(&k) {
            match mi.int() {
                Some(c) if (1..=64).contains(&c) => {
                    out.extend(std::iter::repeat_n(*ki, c as usize))
                }
                _ => return self.err(id, "knot multiplicity is not a small positive integer"),
            }
        }
        Ok(out)
    }
    fn bspline_surface(&self, id: u64, e: Inst) -> R<NurbsSurface<f64, 3>> {
        // Simple instances carry the name first; complex ones split the attributes.
        let (base, k) =
            match e.simple_args() {
                Some(a) => (a.from(1), a.from(8)),
                None => match (
                    e.part("B_SPLINE_SURFACE"),
                    e.part("B_SPLINE_SURFACE_WITH_KNOTS"),
                ) {
                    (Some(b), Some(k)) => (b, k),
                    _ => return self.err(
                        id,
                        "complex B-spline surface without B_SPLINE_SURFACE and _WITH_KNOTS parts",
                    ),
                },
            };
        let p = self.degree(id, base, 0)?;
        let q = self.degree(id, base, 1)?;
        let rows = self.arg(id, base, 2)?.list().ok_or_else(|| StepError {
            file: self.file.into(),
            location: format!("#{id}"),
            reason: "control points are not a list".into(),
        })?;
        let nu = rows.len();
        let nv = rows
            .first()
            .and_then(|v| v.list_refs())
            .map_or(0, |r| r.len());
        let mut pts = Vec::with_capacity(nu * nv);
        for r in rows {
            let Some(r) = r.list_refs() else {
                return self.err(id, "control point row is not a list");
            };
            if r.len() != nv {
                return self.err(id, "control net is not rectangular");
            }
            for c in r {
                match c {
                    Some(pid) => pts.push(self.point(pid)?),
                    None => return self.err(id, "control point is not a reference"),
                }
            }
        }
        let ku = self.knots(id, self.arg(id, k, 0)?, self.arg(id, k, 2)?)?;
        let kv = self.knots(id, self.arg(id, k, 1)?, self.arg(id, k, 3)?)?;
        let w = match e.part("RATIONAL_B_SPLINE_SURFACE") {
            Some(rw) => {
                let Some(wr) = rw.first().and_then(|v| v.list()) else {
                    return self.err(id, "weights are not a list");
                };
                let mut w = Vec::with_capacity(nu * nv);
                for r in wr {
                    match r.numbers() {
                        Some(x) if x.len() == nv => w.extend(x),
                        _ => return self.err(id, "weight row malformed"),
                    }
                }
                w
            }
            None => vec![1.0; nu * nv],
        };
        NurbsSurface::new(ku, p, kv, q, nu, nv, pts, w).or_else(|e| self.err(id, e.to_string()))
    }
    pub(super) fn bspline_curve(&self, id: u64, e: Inst) -> R<NurbsCurve<f64, 3>> {
        let (base, k) = match e.simple_args() {
            Some(a) => (a.from(1), a.from(6)),
            None => match (
                e.part("B_SPLINE_CURVE"),
                e.part("B_SPLINE_CURVE_WITH_KNOTS"),
            ) {
                (Some(b), Some(k)) => (b, k),
                _ => {
                    return self.err(
                        id,
                        "complex B-spline curve without B_SPLINE_CURVE and _WITH_KNOTS parts",
                    );
                }
            },
        };
        let p = self.degree(id, base, 0)?;
        let Some(cl) = self.arg(id, base, 1)?.list_refs() else {
            return self.err(id, "control points are not a list");
        };
        let pts = cl
            .map(|c| {
                c.map_or_else(
                    || self.err(id, "control point is not a reference"),
                    |r| self.point(r),
                )
            })
            .collect::<R<Vec<_>>>()?;
        let knots = self.knots(id, self.arg(id, k, 0)?, self.arg(id, k, 1)?)?;
        let w = match e.part("RATIONAL_B_SPLINE_CURVE") {
            Some(rw) => match rw.first().and_then(|v| v.numbers()) {
                Some(w) => w,
                None => return self.err(id, "weights malformed"),
            },
            None => vec![1.0; pts.len()],
        };
        NurbsCurve::new(knots, p, pts, w).or_else(|e| self.err(id, e.to_string()))
    }
}
