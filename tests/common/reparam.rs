//! Badly parametrized surfaces whose shapes are known, shared by the reparametrization tests.

use std::f64::consts::FRAC_1_SQRT_2;
use vericad::spline::NurbsSurface;

/// Tensor-product net `P_ij = (x_i, y_j, 0)` with product weights `a_i b_j`: the map is
/// `(X(u), Y(v))`, so the chord-length parametrization is `(x_max ξ, y_max η)`; the set is the
/// rectangle `[0,4] × [0,2]`.
pub fn separable_plane() -> NurbsSurface<f64, 3> {
    let xs = [0.0, 0.2, 0.9, 2.5, 3.5, 4.0];
    let a = [1.0, 3.0, 0.5, 2.0, 1.0, 4.0];
    let ys = [0.0, 0.1, 1.5, 2.0];
    let b = [1.0, 0.3, 2.0, 1.0];
    let mut pts = vec![];
    let mut w = vec![];
    for i in 0..6 {
        for j in 0..4 {
            pts.push([xs[i], ys[j], 0.0]);
            w.push(a[i] * b[j]);
        }
    }
    NurbsSurface::new(
        vec![0.0, 0.0, 0.0, 0.0, 0.05, 0.1, 1.0, 1.0, 1.0, 1.0],
        3,
        vec![0.0, 0.0, 0.0, 0.8, 1.0, 1.0, 1.0],
        2,
        6,
        4,
        pts,
        w,
    )
    .unwrap()
}

/// The quarter cylinder of radius `rad`, `0 ≤ θ ≤ π/2`, `0 ≤ z ≤ h`: the arc as a rational
/// quadratic Möbius-reparametrized by `rho`, non-uniform axial weights.
pub fn quarter_cylinder(rad: f64, h: f64, rho: f64) -> NurbsSurface<f64, 3> {
    let arc = [
        ([rad, 0.0], 1.0),
        ([rad, rad], rho * FRAC_1_SQRT_2),
        ([0.0, rad], rho * rho),
    ];
    let zs = [0.0, 0.05, 0.3, h];
    let wz = [1.0, 4.0, 0.5, 1.0];
    let (mut pts, mut w) = (vec![], vec![]);
    for (q, wa) in arc {
        for (z, wb) in zs.iter().zip(wz) {
            pts.push([q[0], q[1], *z]);
            w.push(wa * wb);
        }
    }
    NurbsSurface::new(
        vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
        2,
        vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0],
        3,
        3,
        4,
        pts,
        w,
    )
    .unwrap()
}

/// A patch of the sphere of radius 1.5 about the origin reaching its pole (side v = 1).
pub fn pole_sphere_patch() -> NurbsSurface<f64, 3> {
    let sph =
        vericad::spline::construct::sphere(&vericad::spline::construct::Frame::WORLD, 1.5).unwrap();
    NurbsSurface {
        hom: sph.hom.sub_patch(&0.0, &0.25, &0.5, &1.0).unwrap(),
    }
}

/// Samples `(ξ, η)` of `[0,1]²`, `k + 1` per direction.
pub fn lattice(k: usize) -> impl Iterator<Item = (f64, f64)> {
    (0..=k).flat_map(move |i| (0..=k).map(move |j| (i as f64 / k as f64, j as f64 / k as f64)))
}
