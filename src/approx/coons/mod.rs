//! One local approximant (paper A §3.1–3.6): a bicubic C1 B-spline surface over four
//! boundary curves, projected onto the original surfaces, with gaps bridged by Hardy's
//! reciprocal multiquadric (see `docs/coons.md`).
//!
//! One file per step of the paper:
//! * [`boundary`] — step 1: the four boundary curves (model curves or polylines), checked
//!   (closed, no zero-length side, no self-crossing) and sampled uniformly in arc length;
//! * [`discrete`] — step 2: the discrete bilinear Coons patch, §3.2 (3)/(4);
//! * [`normals`] — §3.3: normals by central differences (5), offsets `a`, `b` (6) at the
//!   distance `d` of (7);
//! * [`project`] — step 3: culling against the offset hull, triangulation with `uv`,
//!   segments `a–b` against triangles by exact predicates, (8)/(9) and Newton onto the
//!   exact surface;
//! * [`trim`] — step 3: the faces' trimmed regions in their parameter planes;
//! * [`multiquadric`] — step 4, §3.4: artificial projections (10)–(13);
//! * [`bicubic`] — step 5, §3.5: the C1 bicubic interpolant (14)–(16);
//! * [`error`] — §3.6: the discrete error at `e`, `f`, `g` (17) and the proven claims;
//! * [`approximant`] — the loop raising `M` and `N` until the error is within tolerance;
//! * [`job`] — the `coons` command: files in, surface, report and view out;
//! * [`layout`] — many approximants: the layout file, its topology, equal counts along
//!   shared curves;
//! * [`join`] — shared boundary rows made identical bit for bit (checked);
//! * [`layout_job`] — the `approximate` command.

pub mod approximant;
pub mod bicubic;
pub mod boundary;
pub mod discrete;
pub mod error;
pub mod job;
pub mod join;
pub mod layout;
pub mod layout_job;
pub mod multiquadric;
pub mod normals;
pub mod project;
pub mod trim;

pub use approximant::{Approximant, Report, approximate, approximate_with_progress};

use serde::Serialize;

/// Bad input or a geometry the method cannot treat: each names the curve (or parameter)
/// at fault and why.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum CoonsError {
    /// The tolerance is not a positive finite number.
    #[error("tolerance {0:e} is not a positive finite number")]
    Tolerance(f64),
    /// A resolution `M` or `N` (or its maximum) that is zero or out of range.
    #[error("resolution {name} = {value}: {why}")]
    Resolution {
        name: &'static str,
        value: usize,
        why: &'static str,
    },
    /// Another parameter out of its range.
    #[error("parameter {name} = {value:e}: {why}")]
    Parameter {
        name: &'static str,
        value: f64,
        why: &'static str,
    },
    /// The boundary description itself (count of curves, JSON).
    #[error("boundary: {0}")]
    Boundary(String),
    /// A boundary curve that cannot be used: unknown index or name, a domain curve, too
    /// few points, a non-finite point.
    #[error("boundary curve {curve}: {why}")]
    Curve { curve: String, why: String },
    /// Consecutive boundary curves do not meet: the loop does not close.
    #[error(
        "boundary curves {from} and {to} do not meet: their nearest end points are {gap:e} apart (closure tolerance {closure:e})"
    )]
    NotClosed {
        from: String,
        to: String,
        gap: f64,
        closure: f64,
    },
    /// A side of zero length.
    #[error("boundary curve {curve} is degenerate: its length is {length:e}")]
    Degenerate { curve: String, length: f64 },
    /// The loop crosses itself (seen along its mean normal).
    #[error("the boundary loop crosses itself: curve {a} crosses curve {b}")]
    SelfCrossing { a: String, b: String },
    /// The loop encloses no area seen along any direction (its Newell normal is zero).
    #[error("the boundary loop encloses no area (curves {0})")]
    Flat(String),
    /// No original surface meets the offset hull, or no segment hits one.
    #[error(
        "no original surface within the offset distance {d:e} of the Coons patch bounded by curves {curves}: {why}"
    )]
    FarFromSurfaces { curves: String, d: f64, why: String },
    /// A computed point is not finite.
    #[error("non-finite value in {0}")]
    NotFinite(String),
    /// The interpolant could not be built.
    #[error("interpolant: {0}")]
    Spline(String),
}

/// Parameters of one approximant.
#[derive(Clone, Debug, Serialize)]
pub struct Params {
    /// Largest deviation (model units) accepted at the error samples (17).
    pub tol: f64,
    /// Initial resolution `M` (intervals between boundary curves 3 and 1) and `N`.
    pub m: usize,
    pub n: usize,
    /// Largest `M` and `N` the refinement may reach.
    pub max_resolution: usize,
    /// End points of consecutive boundary curves may be this far apart (model units);
    /// `None`: the tolerance.
    pub closure: Option<f64>,
    /// K: known projections used per artificial projection (paper: 5–10).
    pub k_nearest: usize,
    /// μ: exponent of the reciprocal multiquadric `(R + r²)^μ` (negative).
    pub mu: f64,
    /// R as a multiple of the paper's `0.5 (δ_u + δ_v)`.
    pub r_scale: f64,
    /// Add a linear polynomial to the multiquadric (exact on planes); the paper has none.
    pub linear_precision: bool,
    /// Triangles per knot span and direction for the original surfaces (at least).
    pub triangles_per_span: usize,
    /// Offset distance `d` as a multiple of eq. (7).
    pub d_scale: f64,
}

impl Default for Params {
    fn default() -> Self {
        Params {
            tol: 1e-3,
            m: 8,
            n: 8,
            max_resolution: 128,
            closure: None,
            k_nearest: 8,
            mu: -0.5,
            r_scale: 1.0,
            linear_precision: true,
            triangles_per_span: 8,
            d_scale: 1.0,
        }
    }
}

impl Params {
    /// Check every parameter.
    pub fn validate(&self) -> Result<(), CoonsError> {
        if !(self.tol > 0.0 && self.tol.is_finite()) {
            return Err(CoonsError::Tolerance(self.tol));
        }
        let res = |name, value: usize| {
            if value == 0 {
                Err(CoonsError::Resolution {
                    name,
                    value,
                    why: "must be at least 1",
                })
            } else if value > 1024 {
                Err(CoonsError::Resolution {
                    name,
                    value,
                    why: "must be at most 1024",
                })
            } else {
                Ok(())
            }
        };
        res("M", self.m)?;
        res("N", self.n)?;
        res("max_resolution", self.max_resolution)?;
        let bad = |name, value: f64, why| Err(CoonsError::Parameter { name, value, why });
        if let Some(c) = self.closure
            && !(c >= 0.0 && c.is_finite())
        {
            return bad("closure", c, "must be a finite number ≥ 0");
        }
        if !(1..=64).contains(&self.k_nearest) {
            return bad("k_nearest", self.k_nearest as f64, "must lie in 1..=64");
        }
        if !(self.mu < 0.0 && self.mu >= -8.0) {
            return bad(
                "mu",
                self.mu,
                "must lie in [-8, 0) (a reciprocal multiquadric)",
            );
        }
        if !(self.r_scale > 0.0 && self.r_scale.is_finite()) {
            return bad("r_scale", self.r_scale, "must be positive and finite");
        }
        if !(self.d_scale > 0.0 && self.d_scale.is_finite()) {
            return bad("d_scale", self.d_scale, "must be positive and finite");
        }
        if !(1..=256).contains(&self.triangles_per_span) {
            return bad(
                "triangles_per_span",
                self.triangles_per_span as f64,
                "must lie in 1..=256",
            );
        }
        Ok(())
    }
}
