//! Step 9b for a run of consecutive output points: one plane direction, one preconditioner
//! and one Krawczyk matrix for the whole run, so that each point costs two interval point
//! evaluations and a 4 × 4 interval product.
//!
//! The theorem is the parent module's (Krawczyk's test on `F = (S_A − S_B, n · (S_A − p))`),
//! with its free choices made once per run instead of once per point:
//!
//! * `n`: the unit `f64` curve tangent `N_A × N_B` at the run's middle point. Any fixed `n`
//!   is sound; the plane through each point `p` is still its own (`n · (S_A − p) = 0`).
//! * `J`: the interval Jacobian over the run's shared box `B` ([`JetCache`]): every point's
//!   box `X ⊂ B` is checked, and an enclosure over `B` is one over `X`.
//! * `Y`: the inverse of the `f64` Jacobian at the middle point (any real matrix is sound);
//!   so `C = I − Y J` is computed once.
//! * `y = z0`: the `f64` Newton solution of the point's own system (any point of `X` is
//!   sound; a good one keeps the box small), as in the parent module.
//!
//! Then `K(X) = z0 − Y F(z0) + C (X − z0)`, `F(z0)` enclosed by interval evaluation at the
//! point; `K(X) ⊂ int X` proves exactly one zero in `X`, lying in `K(X) ∩ X`, and the radius
//! is bounded as in the parent module. Where the test fails, the box leaves `B` or a domain,
//! or the radius is larger than wanted, the caller certifies the point on its own
//! ([`super::certify_on_curve_cached`]): this path only saves work, it never decides a point
//! uncertified.

use super::system::{Fourth, System, pt};
use super::{CurveCertificate, M4, inverse4};
use super::{common_point, newton};
use crate::geom::{cross, dot, norm};
use crate::scalar::Interval;
use crate::spline::NurbsSurface;
use crate::spline::enclose::enclose_point;
use crate::spline::project::point_d1;
use crate::ssi::certify::distance_upper;
use crate::ssi::jet_cache::JetCache;
use crate::ssi::refine::domain;

/// The shared parts of the test for one run.
pub struct RunCertifier<'a> {
    sa: &'a NurbsSurface<f64, 3>,
    sb: &'a NurbsSurface<f64, 3>,
    cache: &'a JetCache,
    n: [f64; 3],
    y: M4,
    /// `I − Y J` over the cache's box.
    c: [[Interval; 4]; 4],
    lo: [f64; 4],
    hi: [f64; 4],
}

/// Sine of the angle between the normals below which no run certifier is made (the shared
/// enclosure would not contract there; the points are certified one by one).
const MIN_SIN: f64 = 1e-3;
/// ε-inflation tries per point.
const TRIES: usize = 3;

impl<'a> RunCertifier<'a> {
    /// The certifier for the points whose parameters the cache's box holds, its choices made
    /// at the parameters `mid` (`uv_a`, `uv_b`) of the run's middle point; `None` near
    /// tangency or where the Jacobian there is singular.
    pub fn new(
        sa: &'a NurbsSurface<f64, 3>,
        sb: &'a NurbsSurface<f64, 3>,
        cache: &'a JetCache,
        mid: (&[f64; 2], &[f64; 2]),
    ) -> Option<RunCertifier<'a>> {
        let (_, au, av) = point_d1(sa, mid.0[0], mid.0[1]);
        let (_, bs, bt) = point_d1(sb, mid.1[0], mid.1[1]);
        let (na, nb) = (cross(&au, &av), cross(&bs, &bt));
        let t = cross(&na, &nb);
        let (la, lb, lt) = (norm(&na), norm(&nb), norm(&t));
        if !(la > 0.0 && lb > 0.0 && lt > MIN_SIN * la * lb && lt.is_finite()) {
            return None;
        }
        let n = t.map(|c| c / lt);
        let mut j = [[0.0; 4]; 4];
        for k in 0..3 {
            j[k] = [au[k], av[k], -bs[k], -bt[k]];
        }
        j[3] = [dot(&n, &au), dot(&n, &av), 0.0, 0.0];
        let y = inverse4(j)?;
        let [ja, jb] = &cache.jets;
        let mut ji = [[pt(0.0); 4]; 4];
        for k in 0..3 {
            ji[k] = [ja.su[k], ja.sv[k], pt(0.0) - jb.su[k], pt(0.0) - jb.sv[k]];
        }
        let d = |v: &[Interval; 3]| (0..3).fold(pt(0.0), |acc, k| acc + pt(n[k]) * v[k]);
        ji[3] = [d(&ja.su), d(&ja.sv), pt(0.0), pt(0.0)];
        let mut c = [[pt(0.0); 4]; 4];
        for i in 0..4 {
            for col in 0..4 {
                let mut cij = pt(if i == col { 1.0 } else { 0.0 });
                for l in 0..4 {
                    cij = cij - pt(y[i][l]) * ji[l][col];
                }
                c[i][col] = cij;
            }
        }
        if !c.iter().flatten().all(|x| x.is_finite()) {
            return None;
        }
        let (da, db) = (domain(sa), domain(sb));
        Some(RunCertifier {
            sa,
            sb,
            cache,
            n,
            y,
            c,
            lo: [da[0], da[2], db[0], db[2]],
            hi: [da[1], da[3], db[1], db[3]],
        })
    }

    /// The curve certificate of the point `p` with parameters `uv_a`, `uv_b`, or `None` where
    /// this shared test does not settle it (see the module comment).
    pub fn certify(
        &self,
        p: &[f64; 3],
        uv_a: &[f64; 2],
        uv_b: &[f64; 2],
    ) -> Option<CurveCertificate> {
        let start = [uv_a[0], uv_a[1], uv_b[0], uv_b[1]];
        if !p.iter().chain(&start).all(|x| x.is_finite()) {
            return None;
        }
        // The centre: Newton in f64 on this point's system from its parameters (the
        // refinement leaves points about tol/8 off the curve; the centre lands on it to f64
        // accuracy, and the caller moves the point there).
        let sys = System {
            sa: self.sa,
            sb: self.sb,
            cache: None,
            e: Fourth::Plane { n: self.n, p: *p },
            p: *p,
            lo: self.lo,
            hi: self.hi,
        };
        let (z0, _, converged) = newton(&sys, start, None, false)?;
        if !converged || !(0..4).all(|i| z0[i] >= self.lo[i] && z0[i] <= self.hi[i]) {
            return None;
        }
        let fa = enclose_point(self.sa, pt(z0[0]), pt(z0[1]))?;
        let fb = enclose_point(self.sb, pt(z0[2]), pt(z0[3]))?;
        let g = (0..3).fold(pt(0.0), |acc, k| acc + pt(self.n[k]) * (fa[k] - pt(p[k])));
        let f = [fa[0] - fb[0], fa[1] - fb[1], fa[2] - fb[2], g];
        let yf: [Interval; 4] =
            std::array::from_fn(|i| (0..4).fold(pt(0.0), |acc, l| acc + pt(self.y[i][l]) * f[l]));
        // Starting radii shaped to the operator: `C` is not small here (its `J` spans the
        // run), so `K` reaches about `|Y F| + |C| rad`; a few fixed-point steps of
        // `r ← |Y F| + |C| r` give radii in proportion (a guess: the test below decides).
        let slack: [f64; 4] = std::array::from_fn(|i| {
            64.0 * f64::EPSILON * (z0[i].abs() + (self.hi[i] - self.lo[i]))
        });
        let mut r: [f64; 4] = std::array::from_fn(|i| yf[i].mag() + slack[i]);
        for _ in 0..4 {
            r = std::array::from_fn(|i| {
                yf[i].mag() + slack[i] + (0..4).map(|c| self.c[i][c].mag() * r[c]).sum::<f64>()
            });
        }
        let mut rad: [f64; 4] = r.map(|x| 1.5 * x);
        let mut found = None;
        for _ in 0..TRIES {
            let x: [Interval; 4] = std::array::from_fn(|i| {
                Interval::new((pt(z0[i]) - pt(rad[i])).lo, (pt(z0[i]) + pt(rad[i])).hi)
            });
            if !self.cache.covers(&x) {
                return None;
            }
            let k: [Interval; 4] = std::array::from_fn(|i| {
                (0..4).fold(pt(z0[i]) - yf[i], |acc, col| {
                    acc + self.c[i][col] * (x[col] - pt(z0[col]))
                })
            });
            if !k.iter().all(|v| v.is_finite()) {
                return None;
            }
            if (0..4).all(|i| k[i].lo > x[i].lo && k[i].hi < x[i].hi) {
                found = Some((x, k));
                break;
            }
            for i in 0..4 {
                let reach = (k[i].lo - z0[i]).abs().max((k[i].hi - z0[i]).abs());
                rad[i] = (1.5 * rad[i]).max(1.25 * reach);
            }
        }
        let (x, k) = found?;
        // The zero lies in K(X) ∩ X, which must lie in both closed domains.
        let z: [Interval; 4] =
            std::array::from_fn(|i| Interval::new(k[i].lo.max(x[i].lo), k[i].hi.min(x[i].hi)));
        if !(0..4).all(|i| z[i].lo >= self.lo[i] && z[i].hi <= self.hi[i]) {
            return None;
        }
        // q = S_A(z*_uv) = S_B(z*_st), enclosed by the mean-value forms about z0 with the
        // derivative enclosures over the cache's box (which holds z0 and z).
        let q = common_point(&z, &z0, &[fa, fb], &self.cache.jets)?;
        Some(CurveCertificate {
            radius: distance_upper(p, &q)?,
            params: z,
            held: None,
            shared_jacobian: true,
            centre: z0,
            at_centre: [fa, fb],
            point: q,
        })
    }
}
