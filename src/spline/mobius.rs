//! Reparametrization of a NURBS surface by a linear rational (Möbius) function in one
//! direction: the same surface, other weights and knots. Used to bring a rational patch's
//! corner weights to 1 where that is possible, so that patches meeting at a corner can share
//! one homogeneous point there without changing shape (repair, `crate::repair`).
//!
//! **The map.** On the direction's domain `[a, b]`, with `t = (u − a)/(b − a)` and likewise `s`,
//! `t = φ(s) = ρ s / ((ρ − 1) s + 1)`, `ρ > 0`: an increasing bijection of `[0, 1]` onto
//! itself, `φ(0) = 0`, `φ(1) = 1`, inverse `s = t / (ρ − (ρ − 1) t)`.
//!
//! **New representation.** The homogeneous surface is piecewise polynomial of degree `p` in
//! `t`; `D(s) = ((ρ − 1) s + 1)^p C^h(φ(s))` is piecewise polynomial of degree `p` in `s`, with
//! breakpoints `s_i = φ⁻¹(t_i)`, and projects to the same points (a common factor of the
//! homogeneous coordinates). Its blossom is `d[s₁, …, s_p] = Π_k ((ρ − 1) s_k + 1) ·
//! c[φ(s₁), …, φ(s_p)]` (each factor `((ρ − 1) s + 1) φ(s) = ρ s` is affine in `s`), and the
//! control points of a B-spline are its blossom at the knots `(t_{i+1}, …, t_{i+p})`. Hence, on
//! the knots `s_i`, the homogeneous control points are `Π_{k=1}^{p} ((ρ − 1) s_{i+k} + 1) ·
//! P_i^h`: the Cartesian control points stay, the weights are multiplied by that product (the
//! NURBS Book's reparametrization with a linear rational function, §6.4; for a Bézier piece the
//! factor is `ρ^i`, the conic's `c^i`). The end weights are multiplied by `1` and `ρ^p`.
//!
//! Computed in `f64`: knots and weights carry rounding (relative `O(p ε)`), so the surface is
//! the same up to rounding, not exactly.

use super::nurbs::NurbsSurface;
use crate::geom::Hom;

/// `φ⁻¹` on the knot `u` of the domain `[a, b]`.
fn inverse(u: f64, a: f64, b: f64, rho: f64) -> f64 {
    if u <= a {
        return a;
    }
    if u >= b {
        return b;
    }
    let t = (u - a) / (b - a);
    let s = t / (rho - (rho - 1.0) * t);
    (a + (b - a) * s).clamp(a, b)
}

/// The new knots and the weight factor of every control point along one direction.
fn direction(knots: &[f64], p: usize, n: usize, rho: f64) -> (Vec<f64>, Vec<f64>) {
    let (a, b) = (knots[p], knots[knots.len() - 1 - p]);
    let s: Vec<f64> = knots.iter().map(|&u| inverse(u, a, b, rho)).collect();
    let factor = (0..n)
        .map(|i| {
            (1..=p)
                .map(|k| (rho - 1.0) * (s[i + k] - a) / (b - a) + 1.0)
                .product()
        })
        .collect();
    (s, factor)
}

/// `s` reparametrized by `φ` with `ρ_u` in `u` and `ρ_v` in `v` (`1`: that direction
/// unchanged), and every weight then multiplied by `scale`. `None` for a non-positive or
/// non-finite `ρ` or `scale`, or when a knot vector comes out invalid.
pub fn reparametrized(
    s: &NurbsSurface<f64, 3>,
    rho_u: f64,
    rho_v: f64,
    scale: f64,
) -> Option<NurbsSurface<f64, 3>> {
    let ok = |x: f64| x.is_finite() && x > 0.0;
    if !(ok(rho_u) && ok(rho_v) && ok(scale)) {
        return None;
    }
    let (p, q) = s.hom.degrees();
    let (nu, nv) = (s.hom.nu(), s.hom.nv());
    let (ku, fu) = direction(s.hom.ku.knots(), p, nu, rho_u);
    let (kv, fv) = direction(s.hom.kv.knots(), q, nv, rho_v);
    let (pts, w) = s.points_weights();
    let w: Vec<f64> = (0..nu)
        .flat_map(|i| (0..nv).map(move |j| (i, j)))
        .map(|(i, j)| w[i * nv + j] * fu[i] * fv[j] * scale)
        .collect();
    if !w.iter().all(|&x| ok(x)) {
        return None;
    }
    NurbsSurface::new(ku, p, kv, q, nu, nv, pts, w).ok()
}

/// Corner weights `[w(0,0), w(1,0), w(0,1), w(1,1)]` (first/last in u, then in v).
pub fn corner_weights(s: &NurbsSurface<f64, 3>) -> [f64; 4] {
    let (nu, nv) = (s.hom.nu(), s.hom.nv());
    let w = |i: usize, j: usize| -> f64 {
        let h: &Hom<f64, 3> = &s.hom.net[i * nv + j];
        h.w
    };
    [w(0, 0), w(nu - 1, 0), w(0, nv - 1), w(nu - 1, nv - 1)]
}

/// The same surface with its four corner weights 1, when its corner weights are not all 1
/// already and `w(0,0) w(1,1) = w(1,0) w(0,1)` within a relative `1e-12` (the cross ratio the
/// reparametrizations and a common factor cannot change); `None` otherwise.
pub fn unit_corner_weights(s: &NurbsSurface<f64, 3>) -> Option<NurbsSurface<f64, 3>> {
    let [w00, w10, w01, w11] = corner_weights(s);
    if [w00, w10, w01, w11].iter().all(|&w| w == 1.0) {
        return None;
    }
    let cross = w00 * w11 / (w10 * w01);
    if (cross - 1.0).abs() > 1e-12 || cross.is_nan() {
        return None;
    }
    let (p, q) = s.hom.degrees();
    // Degree 0: no reparametrization moves the ends' weights apart.
    if (p == 0 && w00 != w10) || (q == 0 && w00 != w01) {
        return None;
    }
    // Ends multiplied by 1 and ρ^p: ρ_u^p = w00 / w10, ρ_v^q = w00 / w01, all by 1 / w00.
    let root = |x: f64, k: usize| if k == 0 { 1.0 } else { x.powf(1.0 / k as f64) };
    let (rho_u, rho_v) = (root(w00 / w10, p), root(w00 / w01, q));
    reparametrized(s, rho_u, rho_v, 1.0 / w00)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A bi-quadratic rational patch with two spans in u, generic weights.
    fn patch() -> NurbsSurface<f64, 3> {
        let ku = vec![0.0, 0.0, 0.0, 0.4, 1.0, 1.0, 1.0];
        let kv = vec![0.0, 0.0, 0.0, 2.0, 2.0, 2.0];
        let (nu, nv) = (4, 3);
        let pts: Vec<[f64; 3]> = (0..nu * nv)
            .map(|k| {
                let (i, j) = ((k / nv) as f64, (k % nv) as f64);
                [i, j, (0.7 * i).sin() + 0.3 * j * j]
            })
            .collect();
        let w: Vec<f64> = (0..nu * nv)
            .map(|k| 0.6 + 0.1 * ((k * 7) % 5) as f64)
            .collect();
        NurbsSurface::new(ku, 2, kv, 2, nu, nv, pts, w).unwrap()
    }

    /// `φ` on the domain `[a, b]`.
    fn forward(s: f64, a: f64, b: f64, rho: f64) -> f64 {
        let x = (s - a) / (b - a);
        a + (b - a) * rho * x / ((rho - 1.0) * x + 1.0)
    }

    #[test]
    fn reparametrized_surface_is_the_same_surface() {
        let s = patch();
        for (ru, rv) in [(0.5, 1.0), (1.0, 3.0), (2.7, 0.31)] {
            let r = reparametrized(&s, ru, rv, 1.7).unwrap();
            for i in 0..=10 {
                for j in 0..=10 {
                    let (su, sv) = (i as f64 / 10.0, 2.0 * j as f64 / 10.0);
                    let a = r.eval(&su, &sv);
                    let b = s.eval(&forward(su, 0.0, 1.0, ru), &forward(sv, 0.0, 2.0, rv));
                    let d = crate::geom::dist(&a, &b);
                    assert!(d < 1e-13, "{ru} {rv} at ({su}, {sv}): {d:e}");
                }
            }
        }
    }

    #[test]
    fn corner_weights_brought_to_one() {
        // Product-form corner weights: a patch of weights a_i b_j.
        let s = patch();
        let (nu, nv) = (s.hom.nu(), s.hom.nv());
        let (pts, _) = s.points_weights();
        let a = [0.8, 1.1, 0.9, 1.3];
        let b = [1.2, 0.7, 0.5];
        let w: Vec<f64> = (0..nu * nv).map(|k| a[k / nv] * b[k % nv]).collect();
        let s = NurbsSurface::new(
            s.hom.ku.knots().to_vec(),
            2,
            s.hom.kv.knots().to_vec(),
            2,
            nu,
            nv,
            pts,
            w,
        )
        .unwrap();
        let r = unit_corner_weights(&s).unwrap();
        for w in corner_weights(&r) {
            assert!((w - 1.0).abs() < 1e-14, "{w}");
        }
        // Same surface: every point of r is a point of s (at φ of its parameters).
        let [w00, w10, w01, _] = corner_weights(&s);
        let (ru, rv) = ((w00 / w10).sqrt(), (w00 / w01).sqrt());
        for i in 0..=8 {
            let (su, sv) = (i as f64 / 8.0, 2.0 * ((i * 3) % 8) as f64 / 8.0);
            let d = crate::geom::dist(
                &r.eval(&su, &sv),
                &s.eval(&forward(su, 0.0, 1.0, ru), &forward(sv, 0.0, 2.0, rv)),
            );
            assert!(d < 1e-13, "{d:e}");
        }
        // A generic patch (cross ratio not 1) and a polynomial one are left alone.
        assert!(unit_corner_weights(&patch()).is_none());
        let poly = reparametrized(&patch(), 1.0, 1.0, 1.0).unwrap();
        let ones = NurbsSurface::new(
            poly.hom.ku.knots().to_vec(),
            2,
            poly.hom.kv.knots().to_vec(),
            2,
            4,
            3,
            poly.points_weights().0,
            vec![1.0; 12],
        )
        .unwrap();
        assert!(unit_corner_weights(&ones).is_none());
    }
}
