//! Step 4 of the RCA parametrization (§2): "pass a C2-continuous interpolating" surface
//! through the grid — the bicubic B-spline interpolating `x_ij` at `(ξ_i, η_j)`, by curve
//! interpolation through the columns and then through the rows of the intermediate control
//! points (The NURBS Book §9.2.5, A9.4), knots by averaging (eq. 9.8). Interior knots are
//! simple, so the surface is C2.

use super::ReparamError;
use super::interior::Grid;
use crate::spline::NurbsSurface;
use crate::spline::interpolate::interpolate_with_parameters;

/// The bicubic (degree `min(3, lines − 1)` per direction) through the grid, on `[0, 1]²`.
pub fn interpolate(g: &Grid) -> Result<NurbsSurface<f64, 3>, ReparamError> {
    interpolate_values(&g.xi, &g.eta, &g.x)
}

/// The same interpolation (same knots, same degrees: the knots depend on `ξ`, `η` only)
/// of any values `x_ij` at `(ξ_i, η_j)`. It is linear in the values; [`super::bound`] uses it
/// for the domain points `(u_ij, v_ij, 0)`, which gives the map φ of the proven bound.
pub fn interpolate_values(
    xi: &[f64],
    eta: &[f64],
    x: &[Vec<[f64; 3]>],
) -> Result<NurbsSurface<f64, 3>, ReparamError> {
    let (n, m) = (xi.len(), eta.len());
    let fail = |e: crate::spline::SplineError| {
        ReparamError::Degenerate(format!("interpolating the grid failed: {e}"))
    };
    // Through x_{·,j} at ξ for every j: intermediate points R_{i,j}.
    let mut r = vec![vec![[0.0; 3]; m]; n];
    let mut ku = vec![];
    for j in 0..m {
        let col: Vec<[f64; 3]> = (0..n).map(|i| x[i][j]).collect();
        let c = interpolate_with_parameters(&col, xi, 3.min(n - 1)).map_err(fail)?;
        for i in 0..n {
            r[i][j] = c.control[i];
        }
        ku = c.knots.knots().to_vec();
    }
    // Through R_{i,·} at η for every i: the control points.
    let mut net = Vec::with_capacity(n * m);
    let mut kv = vec![];
    for row in &r {
        let c = interpolate_with_parameters(row, eta, 3.min(m - 1)).map_err(fail)?;
        net.extend_from_slice(&c.control);
        kv = c.knots.knots().to_vec();
    }
    NurbsSurface::new(
        ku,
        3.min(n - 1),
        kv,
        3.min(m - 1),
        n,
        m,
        net,
        vec![1.0; n * m],
    )
    .map_err(fail)
}
