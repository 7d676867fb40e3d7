//! A proven intersection point near a given point: the Krawczyk test on the intersection
//! system restricted to a plane.
//!
//! For surfaces `S_A`, `S_B`, a point `c` and a unit-ish vector `n` (the rough curve tangent
//! `N_A × N_B` at the start), the unknowns `z = (u, v, s, t)` solve
//!
//! ```text
//! F(z) = [ S_A(u, v) − S_B(s, t) ;  n·(S_A(u, v) − c) ] = 0      (4 equations)
//! ```
//!
//! A root is a true intersection point `p = S_A(u, v) = S_B(s, t)` in the plane through `c`
//! normal to `n`. Krawczyk's theorem (Krawczyk 1969; Moore 1977; Neumaier, *Interval methods
//! for systems of equations*, 1990, Thm. 5.1.8): for a box `X`, a point `z̃ ∈ X` and any real
//! matrix `Y`, let `K(X) = z̃ − Y F(z̃) + (I − Y J(X)) (X − z̃)` with `J(X)` an interval
//! enclosure of the Jacobians `F'` over `X`. If `K(X) ⊂ int X`, then `F` has exactly one
//! zero in `X`, and it lies in `K(X)`. `F` need only be continuous and piecewise `C¹` on `X`
//! (the mean-value inclusion holds for Lipschitz maps with `J(X)` the hull of the one-sided
//! Jacobians), so boxes that straddle a knot line are allowed where the surface is continuous
//! ([`super::closest::IvSurface::enclose`]).
//!
//! All of `F(z̃)`, `J(X)` and `K(X)` are computed in outward-rounded interval arithmetic
//! from the enclosed Bézier pieces; `z̃`, `Y` and `n` are ordinary floating-point numbers
//! (their errors cannot spoil the test). The root must also lie in both parameter domains
//! (`K(X)` inside them; beyond the domain the end spans' polynomials are not the face). Then
//! `p` lies in `S_A(K_uv) ∩ S_B(K_st)` (enclosed), and the distance from the query point to
//! that box, rounded up, is the proven radius.
//!
//! Where the Jacobian is singular — surfaces tangent at the root, a pole of the
//! parametrization — `K(X) ⊂ int X` cannot hold for any box: such points are never
//! certified. When the root sits on a domain border (an open branch ending on a face border,
//! a loop through the seam of a closed face), the plane is shifted along `n` by a small
//! distance, both ways, so that the root moves into the domain; the shift is part of the
//! reported radius (it is measured from the query point).
//!
//! This is the foreign-point form (`certify-ssi`); the same test certifies vericad's own
//! points when given their parameters.

use super::closest::{IvSurface, far_upper};
use super::refine::point_d1;
use crate::scalar::Interval;

/// Why a point could not be certified.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum KrawczykFail {
    /// The normals are (nearly) parallel at the start, or the Jacobian is not invertible:
    /// a tangent contact, a pole, or a degenerate piece.
    Singular,
    /// `K(X) ⊂ int X` did not hold for any of the boxes tried.
    NoContraction,
    /// The root's enclosure leaves a parameter domain (a face border), also after shifting
    /// the plane.
    FaceBorder,
    /// No enclosure of a surface over the box.
    NoEnclosure,
}

fn iv(x: f64) -> Interval {
    Interval::point(x)
}

fn cross(a: &[f64; 3], b: &[f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn norm(a: &[f64; 3]) -> f64 {
    (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt()
}

/// Inverse of a 4×4 matrix by Gauss–Jordan with partial pivoting (floating point; only an
/// approximate inverse is needed).
fn inverse(m: &[[f64; 4]; 4]) -> Option<[[f64; 4]; 4]> {
    let mut a = *m;
    let mut b = [[0.0; 4]; 4];
    for (i, r) in b.iter_mut().enumerate() {
        r[i] = 1.0;
    }
    let scale = m.iter().flatten().fold(0.0f64, |s, x| s.max(x.abs()));
    for c in 0..4 {
        let p = (c..4).max_by(|&i, &j| a[i][c].abs().total_cmp(&a[j][c].abs()))?;
        if a[p][c].abs().partial_cmp(&(1e-14 * scale)) != Some(std::cmp::Ordering::Greater) {
            return None;
        }
        a.swap(c, p);
        b.swap(c, p);
        let d = a[c][c];
        for k in 0..4 {
            a[c][k] /= d;
            b[c][k] /= d;
        }
        for r in 0..4 {
            if r != c {
                let f = a[r][c];
                for k in 0..4 {
                    a[r][k] -= f * a[c][k];
                    b[r][k] -= f * b[c][k];
                }
            }
        }
    }
    b.iter().flatten().all(|x| x.is_finite()).then_some(b)
}

/// Floating-point `F` and `J` at `z`.
fn f_and_j(
    a: &IvSurface,
    b: &IvSurface,
    z: &[f64; 4],
    n: &[f64; 3],
    c: &[f64; 3],
) -> ([f64; 4], [[f64; 4]; 4]) {
    let (pa, au, av) = point_d1(&a.s, z[0], z[1]);
    let (pb, bs, bt) = point_d1(&b.s, z[2], z[3]);
    let mut f = [0.0; 4];
    let mut j = [[0.0; 4]; 4];
    for k in 0..3 {
        f[k] = pa[k] - pb[k];
        j[k] = [au[k], av[k], -bs[k], -bt[k]];
    }
    f[3] = (0..3).map(|k| n[k] * (pa[k] - c[k])).sum();
    j[3] = [
        (0..3).map(|k| n[k] * au[k]).sum(),
        (0..3).map(|k| n[k] * av[k]).sum(),
        0.0,
        0.0,
    ];
    (f, j)
}

/// Krawczyk with the plane through `c` normal to `n`, from `z0`. On success, the enclosure
/// of the root's parameters.
fn krawczyk(
    a: &IvSurface,
    b: &IvSurface,
    c: &[f64; 3],
    n: &[f64; 3],
    z0: [f64; 4],
) -> Result<[Interval; 4], KrawczykFail> {
    // Newton in floating point.
    let mut z = z0;
    for _ in 0..30 {
        let (f, j) = f_and_j(a, b, &z, n, c);
        let y = inverse(&j).ok_or(KrawczykFail::Singular)?;
        let dz: [f64; 4] = std::array::from_fn(|i| (0..4).map(|k| y[i][k] * f[k]).sum());
        for i in 0..4 {
            z[i] -= dz[i];
        }
        if !z.iter().all(|x| x.is_finite()) {
            return Err(KrawczykFail::NoContraction);
        }
        let small = (0..4).all(|i| dz[i].abs() <= 1e-15 * (1.0 + z[i].abs()));
        if small {
            break;
        }
    }
    let (_, j) = f_and_j(a, b, &z, n, c);
    let y = inverse(&j).ok_or(KrawczykFail::Singular)?;
    // F(z̃) enclosed.
    let ea = a.point(&[z[0], z[1]]).ok_or(KrawczykFail::NoEnclosure)?;
    let eb = b.point(&[z[2], z[3]]).ok_or(KrawczykFail::NoEnclosure)?;
    let mut fz = [iv(0.0); 4];
    for k in 0..3 {
        fz[k] = ea[k] - eb[k];
    }
    fz[3] = (0..3).fold(iv(0.0), |s, k| s + iv(n[k]) * (ea[k] - iv(c[k])));
    let yf: [Interval; 4] =
        std::array::from_fn(|i| (0..4).fold(iv(0.0), |s, k| s + iv(y[i][k]) * fz[k]));
    let width = [
        a.dom[1] - a.dom[0],
        a.dom[3] - a.dom[2],
        b.dom[1] - b.dom[0],
        b.dom[3] - b.dom[2],
    ];
    let mut r: [f64; 4] =
        std::array::from_fn(|i| 4.0 * yf[i].mag() + 1e-14 * (width[i].abs() + z[i].abs()));
    for _ in 0..10 {
        let x: [Interval; 4] = std::array::from_fn(|i| {
            Interval::new((z[i] - r[i]).next_down(), (z[i] + r[i]).next_up())
        });
        let ja = a.enclose(x[0], x[1]).ok_or(KrawczykFail::NoEnclosure)?;
        let jb = b.enclose(x[2], x[3]).ok_or(KrawczykFail::NoEnclosure)?;
        let mut m = [[iv(0.0); 4]; 4];
        for k in 0..3 {
            m[k] = [ja.su[k], ja.sv[k], -jb.su[k], -jb.sv[k]];
        }
        let nn = n.map(iv);
        m[3] = [
            (0..3).fold(iv(0.0), |s, k| s + nn[k] * ja.su[k]),
            (0..3).fold(iv(0.0), |s, k| s + nn[k] * ja.sv[k]),
            iv(0.0),
            iv(0.0),
        ];
        let mut k_ok = true;
        let mut kx = [iv(0.0); 4];
        for i in 0..4 {
            let mut acc = iv(z[i]) - yf[i];
            for jj in 0..4 {
                let mut cij = if i == jj { iv(1.0) } else { iv(0.0) };
                for l in 0..4 {
                    cij = cij - iv(y[i][l]) * m[l][jj];
                }
                acc = acc + cij * (x[jj] - iv(z[jj]));
            }
            kx[i] = acc;
            if !(acc.is_finite() && acc.lo > x[i].lo && acc.hi < x[i].hi) {
                k_ok = false;
            }
        }
        if k_ok {
            return Ok(kx);
        }
        for i in 0..4 {
            let reach = (kx[i].lo - z[i]).abs().max((kx[i].hi - z[i]).abs());
            r[i] = (4.0 * r[i]).max(2.0 * reach);
            if !r[i].is_finite() {
                return Err(KrawczykFail::NoContraction);
            }
        }
    }
    Err(KrawczykFail::NoContraction)
}

fn in_domain(k: &[Interval; 4], a: &IvSurface, b: &IvSurface) -> bool {
    k[0].lo >= a.dom[0]
        && k[0].hi <= a.dom[1]
        && k[1].lo >= a.dom[2]
        && k[1].hi <= a.dom[3]
        && k[2].lo >= b.dom[0]
        && k[2].hi <= b.dom[1]
        && k[3].lo >= b.dom[2]
        && k[3].hi <= b.dom[3]
}

/// Proven radius `r` such that a true intersection point `S_A(u, v) = S_B(s, t)`, with
/// `(u, v)` in A's domain and `(s, t)` in B's, lies within `r` of `x` (module comment);
/// `uv_a`, `uv_b` are starting parameters near `x`. The point is also the only root of the
/// plane-restricted system in the Krawczyk box (no branch jumping).
pub fn curve_point_radius(
    a: &IvSurface,
    b: &IvSurface,
    x: &[f64; 3],
    uv_a: [f64; 2],
    uv_b: [f64; 2],
) -> Result<f64, KrawczykFail> {
    if !x.iter().chain(&uv_a).chain(&uv_b).all(|c| c.is_finite()) {
        return Err(KrawczykFail::NoEnclosure);
    }
    let (_, au, av) = point_d1(&a.s, uv_a[0], uv_a[1]);
    let (_, bs, bt) = point_d1(&b.s, uv_b[0], uv_b[1]);
    let (na, nb) = (cross(&au, &av), cross(&bs, &bt));
    let t = cross(&na, &nb);
    let lt = norm(&t);
    if lt.partial_cmp(&(1e-10 * norm(&na) * norm(&nb))) != Some(std::cmp::Ordering::Greater)
        || !lt.is_finite()
    {
        return Err(KrawczykFail::Singular);
    }
    let n = t.map(|c| c / lt);
    let z0 = [uv_a[0], uv_a[1], uv_b[0], uv_b[1]];
    let scale = 1.0 + x.iter().fold(0.0f64, |m, c| m.max(c.abs()));
    let mut last = KrawczykFail::NoContraction;
    for shift in [0.0, 1e-10, -1e-10, 1e-9, -1e-9, 1e-8, -1e-8] {
        let c: [f64; 3] = std::array::from_fn(|k| x[k] + shift * scale * n[k]);
        match krawczyk(a, b, &c, &n, z0) {
            Ok(k) if in_domain(&k, a, b) => {
                let sa = a.enclose(k[0], k[1]).ok_or(KrawczykFail::NoEnclosure)?.s;
                let sb = b.enclose(k[2], k[3]).ok_or(KrawczykFail::NoEnclosure)?.s;
                // The root's point lies in both enclosures.
                let mut p = sa;
                for i in 0..3 {
                    p[i] = Interval::new(sa[i].lo.max(sb[i].lo), sa[i].hi.min(sb[i].hi));
                    if p[i].lo > p[i].hi {
                        // Impossible for true enclosures; refuse rather than guess.
                        return Err(KrawczykFail::NoEnclosure);
                    }
                }
                return Ok(far_upper(x, &p));
            }
            Ok(_) => last = KrawczykFail::FaceBorder,
            Err(e) => {
                last = e;
                if shift == 0.0 && e == KrawczykFail::Singular {
                    return Err(e);
                }
            }
        }
    }
    Err(last)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spline::construct::{Frame, bilinear, sphere};

    /// Sphere of radius 1 at the origin cut by the plane z = h: the circle of radius
    /// sqrt(1 − h²). Points on it are certified with tiny radii; points 1e-3 off in the
    /// plane get radius ~1e-3; a tangent plane gives no certificate.
    #[test]
    fn sphere_plane_points() {
        let f = Frame {
            o: [0.0; 3],
            x: [1.0, 0.0, 0.0],
            y: [0.0, 1.0, 0.0],
            z: [0.0, 0.0, 1.0],
        };
        let s = IvSurface::new(&sphere(&f, 1.0).unwrap());
        let h = 0.3;
        let p = IvSurface::new(
            &bilinear(
                [-2.0, -2.0, h],
                [2.0, -2.0, h],
                [-2.0, 2.0, h],
                [2.0, 2.0, h],
            )
            .unwrap(),
        );
        let rho = (1.0f64 - h * h).sqrt();
        let prm = super::super::closest::ClosestParams {
            eps: 1e-10,
            max_pieces: 10_000,
        };
        for k in 0..16 {
            let phi = 0.1 + k as f64 * 0.39;
            let x = [rho * phi.cos(), rho * phi.sin(), h];
            let ca = super::super::closest::closest(std::slice::from_ref(&s), &x, &prm, &|_| true)
                .unwrap();
            let cb = super::super::closest::closest(std::slice::from_ref(&p), &x, &prm, &|_| true)
                .unwrap();
            let r = curve_point_radius(&s, &p, &x, ca.uv, cb.uv).unwrap();
            assert!(r < 1e-12, "{k}: {r}");
            let y = [x[0] * 1.001, x[1] * 1.001, h];
            let r = curve_point_radius(&s, &p, &y, ca.uv, cb.uv).unwrap();
            assert!(r >= 0.99e-3 * rho && r < 1.01e-3 * rho, "{k}: {r}");
        }
        // Tangent plane z = 1 at the pole, and a tangent plane x = 1 at the equator.
        let tz = IvSurface::new(
            &bilinear(
                [-2.0, -2.0, 1.0],
                [2.0, -2.0, 1.0],
                [-2.0, 2.0, 1.0],
                [2.0, 2.0, 1.0],
            )
            .unwrap(),
        );
        let x = [1e-3, 0.0, 1.0];
        let ca =
            super::super::closest::closest(std::slice::from_ref(&s), &x, &prm, &|_| true).unwrap();
        let cb =
            super::super::closest::closest(std::slice::from_ref(&tz), &x, &prm, &|_| true).unwrap();
        assert!(curve_point_radius(&s, &tz, &x, ca.uv, cb.uv).is_err());
    }
}
