//! Checks on whole models: the finiteness every reader guarantees (re-checked for models
//! built in code), the coordinate range the intersection code supports, and degenerate
//! geometry worth a warning.
//!
//! Readers reject non-finite data where it is built: the spline constructors refuse
//! non-finite knots, knot spans, control points, weights, homogeneous coordinates `w·p` and
//! control points whose differences overflow ([`crate::spline::SplineError::NotFinite`]),
//! and every reader names the entity. Finite but huge coordinates are accepted on reading;
//! computations that square distances call [`Model::check_coordinate_range`] first.

use super::{Model, Surface};
use crate::spline::nurbs::{check_control, check_weights};
use crate::spline::{KnotVector, NurbsCurve, NurbsSurface};

/// Largest coordinate magnitude vericad computes with: `2^500` (about 3.27e150). Below it,
/// a difference of two coordinates is below `2^501` and a sum of three squared differences
/// below `2^1004`, so squared distances never overflow `f64` (whose range ends at `2^1024`).
pub const MAX_COORDINATE: f64 = 3.273390607896142e150;

/// A coordinate outside the supported range ([`MAX_COORDINATE`]).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error(
    "{what}: coordinate {value:e} is outside the supported range |x| <= 2^500 (about 3.3e150): squared distances would overflow f64"
)]
pub struct RangeError {
    /// The surface, curve or triangulation, with its source id when known.
    pub what: String,
    pub value: f64,
}

fn surface_label(i: usize, s: &Surface) -> String {
    match &s.source {
        Some(src) if *src != s.name => format!("surface {i} ({}, {src})", s.name),
        _ => format!("surface {i} ({})", s.name),
    }
}

fn largest<const D: usize>(pts: impl Iterator<Item = [f64; D]>) -> f64 {
    pts.flatten().fold(0.0f64, |a, x| {
        if x.is_nan() {
            f64::INFINITY
        } else {
            a.max(x.abs())
        }
    })
}

fn surface_points(s: &NurbsSurface<f64, 3>) -> impl Iterator<Item = [f64; 3]> + '_ {
    s.hom
        .net
        .iter()
        .map(|h| std::array::from_fn(|d| h.wp[d] / h.w))
}

fn curve_points<const D: usize>(c: &NurbsCurve<f64, D>) -> impl Iterator<Item = [f64; D]> + '_ {
    c.hom
        .control
        .iter()
        .map(|h| std::array::from_fn(|d| h.wp[d] / h.w))
}

/// `ids` as a short list: the first ten, then how many more.
pub fn list_ids(ids: impl IntoIterator<Item = String>) -> String {
    let v: Vec<String> = ids.into_iter().collect();
    let mut s = v.iter().take(10).cloned().collect::<Vec<_>>().join(", ");
    if v.len() > 10 {
        s += &format!(" and {} more", v.len() - 10);
    }
    s
}

impl Model {
    /// Every control point of every surface, space curve and triangulation vertex lies within
    /// `|x| <= MAX_COORDINATE`; otherwise the first one outside, named. Domain curves live
    /// in parameter space and are not checked. Intersection (`ssi`, `certify-ssi`) calls
    /// this before computing: its squared distances overflow beyond the range.
    pub fn check_coordinate_range(&self) -> Result<(), RangeError> {
        for (i, s) in self.surfaces.iter().enumerate() {
            let m = largest(surface_points(&s.nurbs));
            if m > MAX_COORDINATE {
                return Err(RangeError {
                    what: surface_label(i, s),
                    value: m,
                });
            }
        }
        for (i, c) in self.curves.iter().enumerate() {
            if let super::CurveGeometry::Space(c3) = &c.geometry {
                let m = largest(curve_points(c3));
                if m > MAX_COORDINATE {
                    return Err(RangeError {
                        what: format!("curve {i} ({})", c.name),
                        value: m,
                    });
                }
            }
        }
        for (i, t) in self.triangulations.iter().enumerate() {
            let m = largest(t.vertices.iter().copied());
            if m > MAX_COORDINATE {
                return Err(RangeError {
                    what: format!("triangulation {i} ({})", t.name),
                    value: m,
                });
            }
        }
        Ok(())
    }

    /// Re-check what the readers guarantee, for models built or changed in code: every
    /// surface, curve and trim curve satisfies the spline constructors' finiteness rules.
    /// The error names the item (and its source id) and the reason.
    pub fn validate(&self) -> Result<(), String> {
        for (i, s) in self.surfaces.iter().enumerate() {
            check_surface(&s.nurbs).map_err(|e| format!("{}: {e}", surface_label(i, s)))?;
            for (l, tl) in s.trim_loops.iter().enumerate() {
                for (k, c) in tl.curves.iter().enumerate() {
                    check_curve(c).map_err(|e| {
                        format!("{}: trim loop {l}, curve {k}: {e}", surface_label(i, s))
                    })?;
                }
            }
        }
        for (i, c) in self.curves.iter().enumerate() {
            let r = match &c.geometry {
                super::CurveGeometry::Domain(d) => check_curve(d),
                super::CurveGeometry::Space(s) => check_curve(s),
            };
            r.map_err(|e| format!("curve {i} ({}): {e}", c.name))?;
        }
        for (i, t) in self.triangulations.iter().enumerate() {
            if let Some(k) = t
                .vertices
                .iter()
                .position(|v| !v.iter().all(|x| x.is_finite()))
            {
                return Err(format!(
                    "triangulation {i} ({}): vertex {k} is not finite",
                    t.name
                ));
            }
            let n = t.vertices.len();
            if let Some(k) = t
                .triangles
                .iter()
                .position(|tr| tr.iter().any(|&v| v as usize >= n))
            {
                return Err(format!(
                    "triangulation {i} ({}): triangle {k} refers to a missing vertex",
                    t.name
                ));
            }
        }
        Ok(())
    }

    /// Warnings for degenerate surfaces: every control point the same (the surface is a
    /// point). Readers append these to [`Model::warnings`].
    pub fn degeneracy_warnings(&self) -> Vec<String> {
        let mut out = Vec::new();
        for (i, s) in self.surfaces.iter().enumerate() {
            let mut pts = surface_points(&s.nurbs);
            if let Some(p0) = pts.next()
                && pts.all(|p| p == p0)
            {
                out.push(format!(
                    "{}: degenerate, every control point is ({}, {}, {}): the surface is a single point",
                    surface_label(i, s),
                    p0[0],
                    p0[1],
                    p0[2]
                ));
            }
        }
        out
    }
}

/// A model curve against the constructor rules of [`NurbsCurve::new`] (knots, knot span,
/// weights, control points, `w·p`), on the stored homogeneous points.
pub fn check_curve<const D: usize>(c: &NurbsCurve<f64, D>) -> Result<(), String> {
    let k = &c.hom.knots;
    KnotVector::new(k.knots().to_vec(), k.degree(), k.n_ctrl()).map_err(|e| e.to_string())?;
    let (pts, w) = c.points_weights();
    check_weights(&w).map_err(|e| e.to_string())?;
    check_control(&pts, &c.hom.control, |k| k.to_string()).map_err(|e| e.to_string())
}

/// A model surface against the constructor rules of [`NurbsSurface::new`], on the stored
/// homogeneous net.
pub fn check_surface(s: &NurbsSurface<f64, 3>) -> Result<(), String> {
    for k in [&s.hom.ku, &s.hom.kv] {
        KnotVector::new(k.knots().to_vec(), k.degree(), k.n_ctrl()).map_err(|e| e.to_string())?;
    }
    let nv = s.hom.kv.n_ctrl().max(1);
    let (pts, w) = s.points_weights();
    check_weights(&w).map_err(|e| e.to_string())?;
    check_control(&pts, &s.hom.net, |k| format!("[{}][{}]", k / nv, k % nv))
        .map_err(|e| e.to_string())
}
