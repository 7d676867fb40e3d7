//! Step 7 baseline — degree reduction of the exact composition, in the manner of Renner &
//! Weiß (CAD 2004), the "Degree reduction" column of the paper's Tables 2–4.
//!
//! The exact image `S(D)` is a chain of Bézier curves of degree `(p + q) · d` (one per piece
//! of D between knot lines of S; composition by blossoming, `spline::compose::compose`,
//! here in f64). Each is replaced by a **cubic with the same end points and end derivatives**
//! (C1 Hermite data: for degree 3 with C1 end constraints the constrained degree reduction
//! has no free control point left, so this is the constrained reduction itself); where the
//! cubic deviates from the exact piece by more than the tolerance (measured at samples, as
//! parametric distance, an upper bound of the distance at those samples), the piece is
//! halved and each half reduced again. The result is G1 (C1 within each exact piece; where the
//! exact image is C1 the junction tangents are parallel, and the chain is counted as the C1
//! cubic B-spline with double interior knots, `2n + 2` control points, as the paper counts) and
//! lies *near* S, not on it: the distance to S is measured by projecting samples onto S.
//!
//! Everything here is measured, not proven: it is a baseline for comparison tables.

use super::CosError;
use super::float::{cells::FCells, ibez::mid, split::split};
use crate::curve_on_surface::CosInternal;
use crate::geom::dist;
use crate::spline::compose::compose;
use crate::spline::{
    BSplineCurve, BSplineSurface, BezierCurve, BezierSurface, NurbsCurve, NurbsSurface,
};
use serde::Serialize;

/// Result of the baseline.
#[derive(Clone, Debug, Serialize)]
pub struct DegreeReduction {
    pub degree: usize,
    pub segments: usize,
    /// Control points of the G1 chain (shared end points counted once).
    pub control_points: usize,
    /// Control points of the chain as a cubic B-spline: `2n + 2` with double interior knots
    /// when every junction's tangents are parallel and alike in direction (then interval
    /// lengths following the end-derivative ratios make it C1 — the paper's count, 16 for
    /// its 7 segments), else `3n + 1`.
    pub control_points_bspline: usize,
    /// Largest angle (degrees, f64) between the tangents meeting at a junction.
    pub max_junction_angle_deg: f64,
    /// Largest measured deviation from the exact image (parametric, at samples).
    pub max_deviation_sampled: f64,
    /// Largest measured distance of the cubic chain from S (samples projected onto S).
    pub max_distance_to_surface_sampled: f64,
    /// Degree and number of pieces of the exact composition it started from.
    pub exact_degree: usize,
    pub exact_pieces: usize,
    pub elapsed_ms: f64,
    /// The cubic segments' control points.
    #[serde(skip)]
    pub cubics: Vec<[[f64; 3]; 4]>,
}

/// Samples per piece for the deviation test.
const SAMPLES: usize = 32;
/// Halving depth limit per exact piece.
const MAX_DEPTH: u32 = 24;

fn hermite(c: &BezierCurve<[f64; 3]>) -> [[f64; 3]; 4] {
    let n = c.control.len() - 1;
    let (p0, p1, pn1, pn) = (c.control[0], c.control[1], c.control[n - 1], c.control[n]);
    // C'(0) = n (P1 - P0); cubic: 3 (Q1 - Q0).
    let k = n as f64 / 3.0;
    let q1 = std::array::from_fn(|i| p0[i] + k * (p1[i] - p0[i]));
    let q2 = std::array::from_fn(|i| pn[i] - k * (pn[i] - pn1[i]));
    [p0, q1, q2, pn]
}

fn deviation(c: &BezierCurve<[f64; 3]>, q: &[[f64; 3]; 4]) -> f64 {
    let cubic = BezierCurve {
        control: q.to_vec(),
    };
    (0..=SAMPLES)
        .map(|i| {
            let t = i as f64 / SAMPLES as f64;
            dist(&c.eval(&t), &cubic.eval(&t))
        })
        .fold(0.0, f64::max)
}

fn reduce(c: &BezierCurve<[f64; 3]>, tol: f64, depth: u32, out: &mut Vec<[[f64; 3]; 4]>) -> f64 {
    let q = hermite(c);
    let dev = deviation(c, &q);
    if dev <= tol || depth >= MAX_DEPTH {
        out.push(q);
        return dev;
    }
    let (l, r) = c.subdivide(&0.5);
    reduce(&l, tol, depth + 1, out).max(reduce(&r, tol, depth + 1, out))
}

/// Run the baseline: exact composition, then cubic reduction within `tol`.
pub fn degree_reduction(
    surface: &NurbsSurface<f64, 3>,
    curve: &NurbsCurve<f64, 2>,
    tol: f64,
) -> Result<DegreeReduction, CosError> {
    let start = std::time::Instant::now();
    if !(tol > 0.0 && tol.is_finite()) {
        return Err(CosError::ReductionTolerance(tol));
    }
    if !surface.is_polynomial() {
        return Err(CosError::RationalSurface);
    }
    let (spts, _) = surface.points_weights();
    let s = BSplineSurface {
        ku: surface.hom.ku.clone(),
        kv: surface.hom.kv.clone(),
        net: spts,
    };
    let (cpts, _) = curve.points_weights();
    let d = BSplineCurve {
        knots: curve.hom.knots.clone(),
        control: cpts,
    };
    let cells = FCells::new(&s);
    let (pieces, segs) = split(&d, &cells).map_err(|e| match e {
        super::float::FloatError::Cos(e) => e,
        super::float::FloatError::Undecided(w) => CosInternal::Undecided(w).into(),
    })?;
    let mut cubics = Vec::new();
    let mut worst = 0.0f64;
    let mut exact_degree = 0;
    for seg in &segs {
        let cell = cells.get(seg.cell).map_err(CosError::from)?;
        let patch = BezierSurface {
            p: cell.patch.p,
            q: cell.patch.q,
            net: cell.patch.net.iter().map(mid).collect(),
        };
        // The domain piece in the patch's local coordinates.
        let local: Vec<[f64; 2]> = super::float::distance::sub_curve(seg, &pieces)
            .m
            .iter()
            .map(|m| {
                [
                    ((m[0] - cell.u0) / (cell.u1 - cell.u0)).clamp(0.0, 1.0),
                    ((m[1] - cell.v0) / (cell.v1 - cell.v0)).clamp(0.0, 1.0),
                ]
            })
            .collect();
        let exact = compose(&patch, &BezierCurve { control: local });
        exact_degree = exact.control.len() - 1;
        worst = worst.max(reduce(&exact, tol, 0, &mut cubics));
    }
    let elapsed_ms = start.elapsed().as_secs_f64() * 1e3;
    // Distance of the cubic chain from S, measured by projection (not timed).
    let mut to_s = 0.0f64;
    for q in &cubics {
        let cubic = BezierCurve {
            control: q.to_vec(),
        };
        for i in 0..=8 {
            let x = cubic.eval(&(i as f64 / 8.0));
            let uv = crate::spline::project::project(surface, &x);
            to_s = to_s.max(dist(&surface.eval(&uv[0], &uv[1]), &x));
        }
    }
    let mut max_angle = 0.0f64;
    let mut parallel = true;
    for w in cubics.windows(2) {
        let t0: [f64; 3] = std::array::from_fn(|i| w[0][3][i] - w[0][2][i]);
        let t1: [f64; 3] = std::array::from_fn(|i| w[1][1][i] - w[1][0][i]);
        match super::g1::angle_deg(&t0, &t1) {
            Some(a) => max_angle = max_angle.max(a),
            None => parallel = false,
        }
    }
    // Parallel up to the f64 composition (local coordinates from rounded sub-curves; Table 2
    // measures 1.5e-6°).
    parallel &= max_angle < 1e-3;
    let n = cubics.len();
    Ok(DegreeReduction {
        degree: 3,
        segments: n,
        control_points: 3 * n + 1,
        control_points_bspline: if parallel { 2 * n + 2 } else { 3 * n + 1 },
        max_junction_angle_deg: max_angle,
        max_deviation_sampled: worst,
        max_distance_to_surface_sampled: to_s,
        exact_degree,
        exact_pieces: segs.len(),
        elapsed_ms,
        cubics,
    })
}
