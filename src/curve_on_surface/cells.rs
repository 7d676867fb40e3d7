//! Step 1a — split S into Bézier patches by exact knot insertion ("cells": a patch with the
//! parameter rectangle it covers, its Lipschitz bound and 2D tolerance `d`, eq. 12).

use super::tolerance::{lipschitz_bound, tolerance_2d};
use crate::geom::lift_point;
use crate::scalar::lift;
use crate::spline::{BSplineSurface, BezierSurface};
use num_rational::BigRational;

type Q = BigRational;

/// One Bézier patch of S.
#[derive(Clone, Debug)]
pub struct Cell {
    pub u0: f64,
    pub u1: f64,
    pub v0: f64,
    pub v1: f64,
    /// Exact control points (from exact knot insertion).
    pub patch: BezierSurface<[Q; 3]>,
    /// The same, rounded to f64 (for tangents and evidence).
    pub patch_f64: BezierSurface<[f64; 3]>,
    /// Upper bound `K` on the Lipschitz constant in global parameters (eq. 12, scaled).
    pub lipschitz: f64,
    /// 2D tolerance `d = ε_D / K` (rounded down).
    pub d: f64,
    /// Exact hodographs `∂S/∂s`, `∂S/∂r` of the patch in its local coordinates.
    pub hodo_u: Option<BezierSurface<[Q; 3]>>,
    pub hodo_v: Option<BezierSurface<[Q; 3]>>,
}

/// The patch grid of S.
#[derive(Clone, Debug)]
pub struct Cells {
    pub u_breaks: Vec<f64>,
    pub v_breaks: Vec<f64>,
    /// The same breaks, lifted exactly once (for exact point location).
    u_breaks_q: Vec<Q>,
    v_breaks_q: Vec<Q>,
    /// Row-major: `cells[i * (v_breaks.len() - 1) + j]` covers `[u_i, u_{i+1}] × [v_j, v_{j+1}]`.
    pub cells: Vec<Cell>,
}

impl Cells {
    /// Split a polynomial B-spline surface into its Bézier patches, exactly.
    pub fn new(s: &BSplineSurface<[f64; 3]>, eps_d: f64) -> Cells {
        let sq: BSplineSurface<[Q; 3]> = s.map(|k| lift(*k), lift_point);
        let u_breaks = s.ku.breakpoints();
        let v_breaks = s.kv.breakpoints();
        let cells = sq
            .bezier_patches()
            .into_iter()
            .map(|bp| {
                let (u0, u1, v0, v1) = (
                    crate::Scalar::to_f64(&bp.u0),
                    crate::Scalar::to_f64(&bp.u1),
                    crate::Scalar::to_f64(&bp.v0),
                    crate::Scalar::to_f64(&bp.v1),
                );
                let lipschitz = lipschitz_bound(&bp.patch, u1 - u0, v1 - v0);
                Cell {
                    u0,
                    u1,
                    v0,
                    v1,
                    hodo_u: bp.patch.hodograph_u(),
                    hodo_v: bp.patch.hodograph_v(),
                    patch_f64: bp.patch.map(crate::geom::to_f64_point),
                    patch: bp.patch,
                    lipschitz,
                    d: tolerance_2d(eps_d, lipschitz),
                }
            })
            .collect();
        let lifted = |b: &[f64]| b.iter().map(|x| lift::<Q>(*x)).collect();
        Cells {
            u_breaks_q: lifted(&u_breaks),
            v_breaks_q: lifted(&v_breaks),
            u_breaks,
            v_breaks,
            cells,
        }
    }

    /// The cell whose closed rectangle contains `p` (exact comparisons); `None` outside the
    /// surface's domain.
    pub fn locate(&self, p: &[Q; 2]) -> Option<usize> {
        let find = |br: &[Q], x: &Q| -> Option<usize> {
            (0..br.len() - 1).find(|&i| br[i] <= *x && *x <= br[i + 1])
        };
        let i = find(&self.u_breaks_q, &p[0])?;
        let j = find(&self.v_breaks_q, &p[1])?;
        Some(i * (self.v_breaks.len() - 1) + j)
    }

    /// Whether the f64 point lies in cell `c`'s closed rectangle.
    pub fn contains(&self, c: usize, p: &[f64; 2]) -> bool {
        let k = &self.cells[c];
        k.u0 <= p[0] && p[0] <= k.u1 && k.v0 <= p[1] && p[1] <= k.v1
    }

    /// Clamp an f64 point into cell `c`'s rectangle.
    pub fn clamp(&self, c: usize, p: &[f64; 2]) -> [f64; 2] {
        let k = &self.cells[c];
        [p[0].clamp(k.u0, k.u1), p[1].clamp(k.v0, k.v1)]
    }

    /// Local patch coordinates of a global parameter point, exact.
    pub fn local(&self, c: usize, p: &[f64; 2]) -> [Q; 2] {
        let k = &self.cells[c];
        let f =
            |x: f64, a: f64, b: f64| (lift::<Q>(x) - lift::<Q>(a)) / (lift::<Q>(b) - lift::<Q>(a));
        [f(p[0], k.u0, k.u1), f(p[1], k.v0, k.v1)]
    }
}
