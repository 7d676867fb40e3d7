//! Step 1a — split S into Bézier patches by exact knot insertion ("cells": a patch with the
//! parameter rectangle it covers, its Lipschitz bound and 2D tolerance `d`, eq. 12).

use super::g1::F64Patch;
use super::tolerance::{lipschitz_bound, sqrt_up, tolerance_2d};
use crate::geom::{Point, lift_point};
use crate::scalar::{Rational, Scalar, lift};
use crate::spline::{BSplineSurface, BezierSurface};

type Q = Rational;

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
    /// For a rational surface: `patch` and its hodographs are those of the centred
    /// numerator `Q = X − c W` (see `float::rational` for the argument), and this holds
    /// the rest.
    pub rational: Option<ExactRational>,
}

/// The rational part of an exact cell: `S − c = Q / W` (module `float::rational`).
#[derive(Clone, Debug)]
pub struct ExactRational {
    /// The homogeneous patch `(X, W)` (for the mapping).
    pub hom: BezierSurface<[Q; 4]>,
    /// The weight patch in coordinate 0, and its hodographs.
    pub w: BezierSurface<[Q; 3]>,
    pub w_hodo_u: Option<BezierSurface<[Q; 3]>>,
    pub w_hodo_v: Option<BezierSurface<[Q; 3]>>,
    /// `Q` and the weights rounded to f64, with their hodographs (for tangents).
    pub q_f64: F64Patch,
    pub w_f64: F64Patch,
    /// Upper bound of `max |P_ij − c|`, lower bound (positive) of `min W_ij`.
    pub rho: f64,
    pub w_lo: f64,
}

impl ExactRational {
    /// `(K_Q + ρ K_W) / w_lo`, rounded up (`float::rational`).
    pub fn lipschitz(&self, k_q: f64, k_w: f64) -> f64 {
        super::tolerance::rational_lipschitz(k_q, k_w, self.rho, self.w_lo)
    }
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
    /// Split a B-spline surface into its Bézier patches, exactly; for a rational surface
    /// `s` holds the homogeneous points `w·P` and `weights` the weights. `None` when a
    /// rational patch has a weight that is not positive: the patch's rectangle.
    pub fn new(
        s: &BSplineSurface<[f64; 3]>,
        weights: Option<&[f64]>,
        eps_d: f64,
    ) -> Result<Cells, [f64; 4]> {
        let u_breaks = s.ku.breakpoints();
        let v_breaks = s.kv.breakpoints();
        let cells = match weights {
            None => Self::polynomial(s, eps_d),
            Some(w) => Self::rational(s, w, eps_d)?,
        };
        let lifted = |b: &[f64]| b.iter().map(|x| lift::<Q>(*x)).collect();
        Ok(Cells {
            u_breaks_q: lifted(&u_breaks),
            v_breaks_q: lifted(&v_breaks),
            u_breaks,
            v_breaks,
            cells,
        })
    }

    /// The cells of a rational surface (`Cells::new`).
    fn rational(
        s: &BSplineSurface<[f64; 3]>,
        weights: &[f64],
        eps_d: f64,
    ) -> Result<Vec<Cell>, [f64; 4]> {
        let sq: BSplineSurface<[Q; 3]> = s.map(|k| lift(*k), lift_point);
        let hom: BSplineSurface<[Q; 4]> = BSplineSurface {
            ku: sq.ku,
            kv: sq.kv,
            net: s
                .net
                .iter()
                .zip(weights)
                .map(|(p, w)| [lift(p[0]), lift(p[1]), lift(p[2]), lift(*w)])
                .collect(),
        };
        let zero = Q::ZERO;
        hom.bezier_patches()
            .into_iter()
            .map(|bp| {
                let h = &bp.patch;
                let rect = [
                    Scalar::to_f64(&bp.u0),
                    Scalar::to_f64(&bp.u1),
                    Scalar::to_f64(&bp.v0),
                    Scalar::to_f64(&bp.v1),
                ];
                let w_lo_q = h.net.iter().map(|x| x[3].clone()).min().ok_or(rect)?;
                if w_lo_q <= zero {
                    return Err(rect);
                }
                let pts: Vec<[Q; 3]> = h
                    .net
                    .iter()
                    .map(|x| std::array::from_fn(|c| x[c].clone() / x[3].clone()))
                    .collect();
                let center: [Q; 3] = std::array::from_fn(|c| {
                    let lo = pts
                        .iter()
                        .map(|p| Scalar::to_f64(&p[c]))
                        .fold(f64::INFINITY, f64::min);
                    let hi = pts
                        .iter()
                        .map(|p| Scalar::to_f64(&p[c]))
                        .fold(f64::NEG_INFINITY, f64::max);
                    lift(0.5 * lo + 0.5 * hi)
                });
                let rho = pts
                    .iter()
                    .map(|p| sqrt_up(&crate::geom::norm2(&p.sub(&center))))
                    .fold(0.0, f64::max);
                let w_lo = {
                    let f = Scalar::to_f64(&w_lo_q);
                    if lift::<Q>(f) > w_lo_q {
                        f.next_down()
                    } else {
                        f
                    }
                };
                if w_lo.is_nan() || w_lo <= 0.0 {
                    return Err(rect);
                }
                let q = h.map(|x| {
                    std::array::from_fn(|c| x[c].clone() - center[c].clone() * x[3].clone())
                });
                let w = h.map(|x| [x[3].clone(), zero.clone(), zero.clone()]);
                let r = ExactRational {
                    w_hodo_u: w.hodograph_u(),
                    w_hodo_v: w.hodograph_v(),
                    q_f64: F64Patch::new(q.map(crate::geom::to_f64_point)),
                    w_f64: F64Patch::new(w.map(crate::geom::to_f64_point)),
                    hom: h.clone(),
                    w,
                    rho,
                    w_lo,
                };
                let (du, dv) = (
                    Scalar::to_f64(&bp.u1) - Scalar::to_f64(&bp.u0),
                    Scalar::to_f64(&bp.v1) - Scalar::to_f64(&bp.v0),
                );
                let lipschitz =
                    r.lipschitz(lipschitz_bound(&q, du, dv), lipschitz_bound(&r.w, du, dv));
                Ok(Cell {
                    u0: Scalar::to_f64(&bp.u0),
                    u1: Scalar::to_f64(&bp.u1),
                    v0: Scalar::to_f64(&bp.v0),
                    v1: Scalar::to_f64(&bp.v1),
                    hodo_u: q.hodograph_u(),
                    hodo_v: q.hodograph_v(),
                    patch_f64: q.map(crate::geom::to_f64_point),
                    patch: q,
                    lipschitz,
                    d: tolerance_2d(eps_d, lipschitz),
                    rational: Some(r),
                })
            })
            .collect()
    }

    /// The cells of a polynomial surface (`Cells::new`).
    fn polynomial(s: &BSplineSurface<[f64; 3]>, eps_d: f64) -> Vec<Cell> {
        let sq: BSplineSurface<[Q; 3]> = s.map(|k| lift(*k), lift_point);
        sq.bezier_patches()
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
                    rational: None,
                }
            })
            .collect()
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
