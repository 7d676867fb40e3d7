//! Evaluate a model's surface or curve at a parameter, in f64 and exactly.

use super::{CurveGeometry, Model};
use crate::geom::{Hom, Point, lift_point, to_f64_point};
use crate::scalar::{Scalar, lift};
use crate::spline::{BSplineCurve, BSplineSurface};
use num_rational::BigRational;
use serde::Serialize;

/// What `vericad eval` reports.
#[derive(Clone, Debug, Serialize)]
pub struct EvalReport {
    pub target: String,
    pub parameter: Vec<f64>,
    /// f64 evaluation.
    pub point: Vec<f64>,
    /// Exact (BigRational) evaluation at the same f64 parameter, rounded to nearest.
    pub exact_point: Vec<f64>,
    /// Largest coordinate difference |f64 − exact| (exact arithmetic, rounded up).
    pub f64_error: f64,
    /// First partial derivatives (surfaces: S_u, S_v; curves: C'), f64.
    pub derivatives: Vec<Vec<f64>>,
    /// Unit normal (surfaces), f64.
    pub normal: Option<Vec<f64>>,
}

/// Why evaluation was refused.
#[derive(Debug, thiserror::Error)]
pub enum EvalError {
    #[error("no {0} with index {1} (the model has {2})")]
    NoSuch(&'static str, usize, usize),
    #[error("parameter {0:?} lies outside the domain {1:?}")]
    OutOfDomain(Vec<f64>, Vec<f64>),
    #[error("need {0} parameter value(s), got {1}")]
    Arity(usize, usize),
    #[error("parameter is not a finite number")]
    NotFinite,
}

fn lift_surface(s: &BSplineSurface<Hom<f64, 3>>) -> BSplineSurface<Hom<BigRational, 3>> {
    s.map(
        |k| lift(*k),
        |h| Hom {
            wp: lift_point(&h.wp),
            w: lift(h.w),
        },
    )
}

fn lift_curve<const D: usize>(c: &BSplineCurve<Hom<f64, D>>) -> BSplineCurve<Hom<BigRational, D>> {
    c.map(
        |k| lift(*k),
        |h| Hom {
            wp: lift_point(&h.wp),
            w: lift(h.w),
        },
    )
}

fn err_of<const D: usize>(a: &[f64; D], e: &[BigRational; D]) -> f64 {
    (0..D)
        .map(|i| {
            (lift::<BigRational>(a[i]) - e[i].clone())
                .abs()
                .to_f64()
                .next_up()
        })
        .fold(0.0, f64::max)
}

/// Evaluate surface `index` at `(u, v)`.
pub fn eval_surface(m: &Model, index: usize, uv: &[f64]) -> Result<EvalReport, EvalError> {
    let s = m
        .surfaces
        .get(index)
        .ok_or(EvalError::NoSuch("surface", index, m.surfaces.len()))?;
    if uv.len() != 2 {
        return Err(EvalError::Arity(2, uv.len()));
    }
    if uv.iter().any(|x| !x.is_finite()) {
        return Err(EvalError::NotFinite);
    }
    let (u0, u1, v0, v1) = s.nurbs.hom.domain();
    if uv[0] < u0 || uv[0] > u1 || uv[1] < v0 || uv[1] > v1 {
        return Err(EvalError::OutOfDomain(uv.to_vec(), vec![u0, u1, v0, v1]));
    }
    let d = s.nurbs.derivatives2(&uv[0], &uv[1]);
    let exact_h = lift_surface(&s.nurbs.hom).eval(&lift(uv[0]), &lift(uv[1]));
    let exact = exact_h.project().unwrap_or_else(|| exact_h.wp.clone());
    Ok(EvalReport {
        target: format!("surface {index} ({})", s.name),
        parameter: uv.to_vec(),
        point: d[0].to_vec(),
        exact_point: to_f64_point(&exact).to_vec(),
        f64_error: err_of(&d[0], &exact),
        derivatives: vec![d[1].to_vec(), d[2].to_vec()],
        normal: s.nurbs.unit_normal(&uv[0], &uv[1]).map(|n| n.to_vec()),
    })
}

fn eval_curve_d<const D: usize>(
    c: &crate::spline::NurbsCurve<f64, D>,
    t: f64,
    target: String,
) -> Result<EvalReport, EvalError> {
    let (a, b) = c.hom.domain();
    if t < a || t > b {
        return Err(EvalError::OutOfDomain(vec![t], vec![a, b]));
    }
    let p = c.eval(&t);
    let e = lift_curve(&c.hom).eval(&lift(t));
    let exact = e.project().unwrap_or_else(|| e.wp.clone());
    Ok(EvalReport {
        target,
        parameter: vec![t],
        point: p.to_vec(),
        exact_point: to_f64_point(&exact).to_vec(),
        f64_error: err_of(&p, &exact),
        derivatives: vec![c.derivative_at(&t).coords()],
        normal: None,
    })
}

/// Evaluate curve `index` at `t`.
pub fn eval_curve(m: &Model, index: usize, t: &[f64]) -> Result<EvalReport, EvalError> {
    let c = m
        .curves
        .get(index)
        .ok_or(EvalError::NoSuch("curve", index, m.curves.len()))?;
    if t.len() != 1 {
        return Err(EvalError::Arity(1, t.len()));
    }
    if !t[0].is_finite() {
        return Err(EvalError::NotFinite);
    }
    let target = format!("curve {index} ({})", c.name);
    match &c.geometry {
        CurveGeometry::Domain(g) => eval_curve_d(g, t[0], target),
        CurveGeometry::Space(g) => eval_curve_d(g, t[0], target),
    }
}

impl std::fmt::Display for EvalReport {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        writeln!(f, "{} at {:?}", self.target, self.parameter)?;
        writeln!(f, "  point        {:?}", self.point)?;
        writeln!(
            f,
            "  exact point  {:?} (BigRational, rounded)",
            self.exact_point
        )?;
        writeln!(
            f,
            "  f64 error    {:.3e} (proven: exact difference, rounded up)",
            self.f64_error
        )?;
        for (i, d) in self.derivatives.iter().enumerate() {
            writeln!(f, "  derivative {i} {d:?}")?;
        }
        if let Some(n) = &self.normal {
            writeln!(f, "  unit normal  {n:?}")?;
        }
        Ok(())
    }
}
