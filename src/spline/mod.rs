//! The spline kernel, generic over [`Scalar`](crate::scalar::Scalar) and over the control
//! point type ([`Point`](crate::geom::Point)): polynomial and rational, 2D and 3D, on every
//! backend, from one source.
//!
//! * [`knots`] — validated knot vectors, spans, multiplicities;
//! * [`basis`] — B-spline basis functions and their derivatives (The NURBS Book A2.2/A2.3);
//! * [`bezier_curve`], [`bezier_surface`] — de Casteljau, blossoms, subdivision, degree
//!   elevation, hodographs;
//! * [`bspline_curve`], [`bspline_surface`] — de Boor evaluation, derivative splines, Boehm
//!   knot insertion, Bézier extraction, sub-patch extraction;
//! * [`nurbs`] — rational curves/surfaces via homogeneous points, rational derivatives, normals;
//! * [`compose`] — a planar Bézier curve composed with a Bézier surface, exactly;
//! * [`interpolate`], [`fit`] — cubic interpolation and least-squares fitting;
//! * [`elevate`] — degree elevation and refinement to a knot vector, exact;
//! * [`fit_knots`] — least-squares fitting on a given knot vector;
//! * [`linalg`] — the small dense solver both use;
//! * [`enclose`], [`enclose_net`] (centred, with derivative nets), [`enclosed_bezier`] — outward-rounded interval enclosures of a surface and
//!   its first derivatives over parameter boxes, and of its Bézier pieces.

pub mod basis;
pub mod bezier_curve;
pub mod bezier_surface;
pub mod border_match;
pub mod bspline_curve;
pub mod bspline_surface;
pub mod closure;
pub mod compose;
pub mod construct;
pub mod elevate;
pub mod enclose;
pub mod enclose2;
pub mod enclose_net;
pub mod enclosed_bezier;
pub mod exact_point;
pub mod fit;
pub mod fit_knots;
pub mod interpolate;
pub mod knots;
pub mod linalg;
pub mod mobius;
pub mod nurbs;
pub mod pcurve_bound;
pub mod project;
pub mod scaled_bernstein;
pub mod sides;
#[cfg(test)]
pub(crate) mod test_params;

pub use bezier_curve::BezierCurve;
pub use bezier_surface::BezierSurface;
pub use bspline_curve::BSplineCurve;
pub use bspline_surface::BSplineSurface;
pub use knots::{KnotError, KnotVector};
pub use nurbs::{NurbsCurve, NurbsSurface};

/// Largest degree the allocation-free evaluation paths support.
pub const MAX_DEGREE: usize = 31;

/// Errors of spline construction and operations.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SplineError {
    #[error("knot vector: {0}")]
    Knots(#[from] KnotError),
    #[error("control net has {got} points, expected {expected} ({what})")]
    NetSize {
        got: usize,
        expected: usize,
        what: &'static str,
    },
    #[error("degree {0} is not supported (1..={MAX_DEGREE})")]
    Degree(usize),
    #[error("weight {index} is not positive")]
    Weight { index: usize },
    /// A control point, weight or homogeneous coordinate `w·p` that is not a finite `f64`,
    /// or control points whose differences overflow: evaluation would give NaN or infinity.
    #[error("{0}")]
    NotFinite(String),
    /// Arguments of a constructor that describe no curve or surface (a radius that is not
    /// positive, an angle range that is not a turn or less, ...).
    #[error("{0}")]
    Invalid(String),
    #[error("parameter {0} lies outside the domain [{1}, {2}]")]
    OutOfDomain(f64, f64, f64),
    #[error("need at least {need} points, got {got}")]
    TooFewPoints { need: usize, got: usize },
    #[error("parameters are not strictly increasing at index {0}")]
    Parameters(usize),
    #[error("linear system is singular")]
    Singular,
}
