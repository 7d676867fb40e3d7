//! Evaluate a model's surface or curve at a parameter, in f64 and exactly.

use super::{CurveGeometry, Model};
use crate::geom::{Hom, Point, lift_point, to_f64_point};
use crate::scalar::{Rational, Scalar, lift};
use crate::spline::{BSplineCurve, BSplineSurface};
use serde::Serialize;

/// What `vericad eval` reports.
#[derive(Clone, Debug, Serialize)]
pub struct EvalReport {
    pub target: String,
    pub parameter: Vec<f64>,
    /// f64 evaluation.
    pub point: Vec<f64>,
    /// Exact (Rational) evaluation at the same f64 parameter, rounded to nearest.
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

fn lift_surface(s: &BSplineSurface<Hom<f64, 3>>) -> BSplineSurface<Hom<Rational, 3>> {
    s.map(
        |k| lift(*k),
        |h| Hom {
            wp: lift_point(&h.wp),
            w: lift(h.w),
        },
    )
}

fn lift_curve<const D: usize>(c: &BSplineCurve<Hom<f64, D>>) -> BSplineCurve<Hom<Rational, D>> {
    c.map(
        |k| lift(*k),
        |h| Hom {
            wp: lift_point(&h.wp),
            w: lift(h.w),
        },
    )
}

/// Largest `|a_i − e_i|`, rounded up; infinite where the f64 evaluation overflowed.
fn err_of<const D: usize>(a: &[f64; D], e: &[Rational; D]) -> f64 {
    (0..D)
        .map(|i| match Rational::from_f64(a[i]) {
            Ok(x) => Scalar::to_f64(&(x - e[i].clone()).abs()).next_up(),
            Err(_) => f64::INFINITY,
        })
        .fold(0.0, f64::max)
}

/// `S_u × S_v` normalized, with each derivative scaled to unit largest component first, so
/// that huge finite coordinates (up to the f64 limit) give a unit normal, not an overflow
/// to NaN; `None` where the normal vanishes.
fn unit_normal(su: &[f64; 3], sv: &[f64; 3]) -> Option<[f64; 3]> {
    let scaled = |x: &[f64; 3]| {
        let m = x.iter().fold(0.0f64, |a, c| a.max(c.abs()));
        (m > 0.0 && m.is_finite()).then(|| x.map(|c| c / m))
    };
    let (a, b) = (scaled(su)?, scaled(sv)?);
    let n = [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ];
    let l = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    (l > 0.0).then(|| n.map(|c| c / l))
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
        normal: unit_normal(&d[1], &d[2]).map(|n| n.to_vec()),
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
            "  exact point  {:?} (Rational, rounded)",
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
