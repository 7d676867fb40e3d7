//! Step 8 — refinement of the sample points onto the true surfaces (paper §4, "Refinement",
//! Figs. 18–19): barycentric parameters from the triangle that holds the point, then the
//! Auxiliary Plane Method (Hosaka '92), eqs. (18)–(26) in the consistent form of
//! docs/papers.md §A (each tangent plane through its own surface's point).

use super::triangulate::SurfaceMesh;
use crate::geom::{Point, cross, dot, norm};
use crate::spline::NurbsSurface;

/// How a refinement ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum RefineStatus {
    /// `||s(u,v) - r(w,t)|| <= tol`.
    Converged,
    /// The normals became (nearly) parallel: `||n_p × n_q|| < sin(angle)`; the method breaks
    /// down there (docs/papers.md §A). The best iterate is kept.
    Tangential,
    /// The iteration left the parameter domain of one surface and stayed on its border.
    AtBoundary,
    /// No convergence within the iteration limit.
    NotConverged,
}

/// A point refined onto both surfaces.
#[derive(Clone, Copy, Debug)]
pub struct Refined {
    /// Midpoint of `s(uv_a)` and `r(uv_b)`.
    pub xyz: [f64; 3],
    pub uv_a: [f64; 2],
    pub uv_b: [f64; 2],
    /// `||s(uv_a) - r(uv_b)||` in floating point (the certificate recomputes it exactly).
    pub gap: f64,
    pub status: RefineStatus,
    pub iterations: u32,
    /// `sin` of the angle between the surface normals at the parameters, where the
    /// refinement computed it on the way (NaN where it did not).
    pub sin_angle: f64,
}

#[derive(Clone, Copy, Debug)]
pub struct RefineParams {
    pub tol: f64,
    pub max_iter: u32,
    /// `sin` of the angle between the normals below which the contact counts as tangential.
    pub tangent_sin: f64,
    /// Certify every output point against the curve ([`super::krawczyk`]); off: each is
    /// reported `not_requested` ([`super::SsiParams::certify`]).
    pub curve_certificates: bool,
    /// Fit each branch's cubic ([`super::SsiParams::fits`]).
    pub fits: bool,
    /// Cubic Hermite pieces between the points instead of chords ([`super::hermite`]).
    pub cubic: bool,
}

type V3 = [f64; 3];
// Short forms of the `Point` operations for the dense formulas below.
fn sub(a: &V3, b: &V3) -> V3 {
    a.sub(b)
}
fn add(a: &V3, b: &V3) -> V3 {
    a.add(b)
}
fn scale(a: &V3, s: f64) -> V3 {
    a.scale(&s)
}

pub use crate::spline::project::point_d1;

/// Parameter domain `[u0, u1] × [v0, v1]`.
pub fn domain(s: &NurbsSurface<f64, 3>) -> [f64; 4] {
    let (u0, u1, v0, v1) = s.hom.domain();
    [u0, u1, v0, v1]
}

/// Barycentric parameters of `x` in triangle `t` of `m` (Fig. 18): the normalized
/// sub-triangle areas, in the projection where the triangle is largest, clamped to the
/// triangle.
pub fn barycentric_uv(m: &SurfaceMesh, t: u32, x: &V3) -> [f64; 2] {
    let tri = m.triangles[t as usize];
    let p: [V3; 3] = std::array::from_fn(|k| m.vertices[tri[k] as usize]);
    let n = cross(&sub(&p[1], &p[0]), &sub(&p[2], &p[0]));
    let k = (0..3)
        .max_by(|&a, &b| n[a].abs().total_cmp(&n[b].abs()))
        .unwrap_or(2);
    let (i, j) = ((k + 1) % 3, (k + 2) % 3);
    let area =
        |a: &V3, b: &V3, c: &V3| (b[i] - a[i]) * (c[j] - a[j]) - (b[j] - a[j]) * (c[i] - a[i]);
    let total = area(&p[0], &p[1], &p[2]);
    let mut w = [
        area(x, &p[1], &p[2]) / total,
        area(&p[0], x, &p[2]) / total,
        area(&p[0], &p[1], x) / total,
    ];
    if !w.iter().all(|x| x.is_finite()) {
        w = [1.0 / 3.0; 3];
    }
    for wk in &mut w {
        *wk = wk.clamp(0.0, 1.0);
    }
    let s: f64 = w.iter().sum();
    let uv: [[f64; 2]; 3] = std::array::from_fn(|k| m.uv[tri[k] as usize]);
    std::array::from_fn(|c| (w[0] * uv[0][c] + w[1] * uv[1][c] + w[2] * uv[2][c]) / s)
}

fn clamp_uv(uv: [f64; 2], d: &[f64; 4]) -> ([f64; 2], bool) {
    let c = [uv[0].clamp(d[0], d[1]), uv[1].clamp(d[2], d[3])];
    (c, c != uv)
}

/// Parameter step moving `s(u, v)` by `delta` within its tangent plane (eqs. (23)–(24)):
/// `s_u* = s_u × n`, `s_v* = s_v × n`, `δu = (s_v*·δ)/(s_v*·s_u)`, `δv = (s_u*·δ)/(s_u*·s_v)`.
fn tangent_step(su: &V3, sv: &V3, n: &V3, delta: &V3) -> [f64; 2] {
    let sus = cross(su, n);
    let svs = cross(sv, n);
    [
        dot(&svs, delta) / dot(&svs, su),
        dot(&sus, delta) / dot(&sus, sv),
    ]
}

/// Steps taken past `gap <= tol` ([`auxiliary_plane`]).
const POLISH: u32 = 2;

/// The Auxiliary Plane Method from `(uv_a, uv_b)`.
pub fn auxiliary_plane(
    sa: &NurbsSurface<f64, 3>,
    sb: &NurbsSurface<f64, 3>,
    mut uv_a: [f64; 2],
    mut uv_b: [f64; 2],
    prm: &RefineParams,
) -> Refined {
    let (da, db) = (domain(sa), domain(sb));
    uv_a = clamp_uv(uv_a, &da).0;
    uv_b = clamp_uv(uv_b, &db).0;
    let mut best: Option<Refined> = None;
    let mut status = RefineStatus::NotConverged;
    let mut boundary_hits = 0;
    let mut converged: Option<Refined> = None;
    let mut polished = 0;
    for it in 0..=prm.max_iter {
        let (p0, su, sv) = point_d1(sa, uv_a[0], uv_a[1]);
        let (q0, rw, rt) = point_d1(sb, uv_b[0], uv_b[1]);
        let gap = norm(&sub(&p0, &q0));
        let cand = Refined {
            xyz: scale(&add(&p0, &q0), 0.5),
            uv_a,
            uv_b,
            gap,
            status,
            iterations: it,
            sin_angle: f64::NAN,
        };
        if best.is_none_or(|b| gap < b.gap || !b.gap.is_finite()) {
            best = Some(cand);
        }
        // Within tol of each other the points can still lie about `tol / sin θ` from the
        // curve (surfaces at an angle θ): up to [`POLISH`] more steps while the gap keeps
        // falling (quadratically: one step usually takes it to rounding level), so that
        // measurements against the curve (the insertion's) see the curve, not the tolerance.
        if let Some(c) = converged
            && gap.partial_cmp(&(0.5 * c.gap)) != Some(std::cmp::Ordering::Less)
        {
            return c;
        }
        if gap <= prm.tol {
            let c = Refined {
                status: RefineStatus::Converged,
                sin_angle: sin_between(&su, &sv, &rw, &rt),
                ..cand
            };
            polished += 1;
            if polished > POLISH || gap <= 1e-4 * prm.tol {
                return c;
            }
            converged = Some(c);
        }
        if it == prm.max_iter || !gap.is_finite() {
            break;
        }
        let (na, nb) = (cross(&su, &sv), cross(&rw, &rt));
        let (la, lb) = (norm(&na), norm(&nb));
        if !(la > 0.0 && lb > 0.0) {
            status = RefineStatus::NotConverged;
            break;
        }
        let (np, nq) = (scale(&na, 1.0 / la), scale(&nb, 1.0 / lb));
        let c = cross(&np, &nq);
        let lc = norm(&c);
        let x = if lc < prm.tangent_sin {
            // Eq. (22) breaks down: move both points towards their midpoint instead.
            status = RefineStatus::Tangential;
            scale(&add(&p0, &q0), 0.5)
        } else {
            // Eqs. (18)–(22): intersection of the two tangent planes and the auxiliary
            // plane through the midpoint, orthogonal to both.
            let nn = scale(&c, 1.0 / lc);
            let (dp, dq) = (dot(&np, &p0), dot(&nq, &q0));
            let dn = dot(&nn, &scale(&add(&p0, &q0), 0.5));
            let det = dot(&np, &cross(&nq, &nn));
            let num = add(
                &add(&scale(&cross(&nq, &nn), dp), &scale(&cross(&nn, &np), dq)),
                &scale(&cross(&np, &nq), dn),
            );
            scale(&num, 1.0 / det)
        };
        let step_a = tangent_step(&su, &sv, &np, &sub(&x, &p0));
        let step_b = tangent_step(&rw, &rt, &nq, &sub(&x, &q0));
        let (na_uv, ca) = clamp_uv([uv_a[0] + step_a[0], uv_a[1] + step_a[1]], &da);
        let (nb_uv, cb) = clamp_uv([uv_b[0] + step_b[0], uv_b[1] + step_b[1]], &db);
        if !(na_uv.iter().chain(&nb_uv).all(|x| x.is_finite())) {
            break;
        }
        if ca || cb {
            boundary_hits += 1;
            if boundary_hits >= 3 {
                status = RefineStatus::AtBoundary;
            }
        }
        uv_a = na_uv;
        uv_b = nb_uv;
    }
    if let Some(c) = converged {
        return c;
    }
    let b = best.unwrap_or(Refined {
        xyz: [f64::NAN; 3],
        uv_a,
        uv_b,
        gap: f64::INFINITY,
        status,
        iterations: prm.max_iter,
        sin_angle: f64::NAN,
    });
    Refined { status, ..b }
}

/// Iterations over which the tangential-point search must make progress.
const STALL_SPAN: usize = 4;
/// The least reduction of the squared residual over [`STALL_SPAN`] iterations.
const STALL_RATIO: f64 = 0.9;

/// Solve for a tangential point of the two surfaces near `(uv_a, uv_b)`: `s(u,v) = r(w,t)` with
/// `n_p · r_w = n_p · r_t = 0` (the normals parallel). Five equations in four unknowns, solved
/// in the least-squares sense by damped Gauss–Newton (Levenberg–Marquardt) with a
/// central-difference Jacobian. Such points are the touching points and the singular (branch)
/// points of the intersection, where the Auxiliary Plane Method breaks down. Returns the point
/// with status `Tangential` when both residuals vanish within `tol` and `tangent_sin`. A run
/// whose squared residual falls by less than `STALL_RATIO` over `STALL_SPAN` iterations
/// stops (a local minimum that is not a root: 80 % of the runs on crossing free-form sheets,
/// which went on to the iteration limit before). The search only proposes points: what it
/// misses the coverage certificate reports as uncertified.
pub fn tangential_point(
    sa: &NurbsSurface<f64, 3>,
    sb: &NurbsSurface<f64, 3>,
    uv_a: [f64; 2],
    uv_b: [f64; 2],
    prm: &RefineParams,
) -> Refined {
    tangential_point_until(sa, sb, (uv_a, uv_b), prm, |_| false).0
}

/// [`tangential_point`], stopped (status `NotConverged`) as soon as the midpoint of an
/// iterate satisfies `known` — the neighbourhood of a point already found, where the run
/// would end as a duplicate of it. A scheduling choice only: the search proposes points and
/// decides nothing. The flag says whether the run stalled short of a root (a local minimum
/// of the residual that is not a root).
pub fn tangential_point_until(
    sa: &NurbsSurface<f64, 3>,
    sb: &NurbsSurface<f64, 3>,
    (uv_a, uv_b): ([f64; 2], [f64; 2]),
    prm: &RefineParams,
    known: impl Fn(&[f64; 3]) -> bool,
) -> (Refined, bool) {
    let (da, db) = (domain(sa), domain(sb));
    let residual = |x: &[f64; 4]| -> ([f64; 5], f64, f64, [f64; 3]) {
        let (p, su, sv) = point_d1(sa, x[0], x[1]);
        let (q, rw, rt) = point_d1(sb, x[2], x[3]);
        let n = cross(&su, &sv);
        let ln = norm(&n);
        let n = if ln > 0.0 { scale(&n, 1.0 / ln) } else { n };
        let (lw, lt) = (norm(&rw), norm(&rt));
        let (cw, ct) = (dot(&n, &rw), dot(&n, &rt));
        let d = sub(&p, &q);
        let sin = (cw / lw.max(f64::MIN_POSITIVE))
            .abs()
            .max((ct / lt.max(f64::MIN_POSITIVE)).abs());
        (
            [d[0], d[1], d[2], cw, ct],
            norm(&d),
            sin,
            scale(&add(&p, &q), 0.5),
        )
    };
    let clamp = |x: [f64; 4]| -> [f64; 4] {
        [
            x[0].clamp(da[0], da[1]),
            x[1].clamp(da[2], da[3]),
            x[2].clamp(db[0], db[1]),
            x[3].clamp(db[2], db[3]),
        ]
    };
    let mut x = clamp([uv_a[0], uv_a[1], uv_b[0], uv_b[1]]);
    let h = [
        1e-7 * (da[1] - da[0]),
        1e-7 * (da[3] - da[2]),
        1e-7 * (db[1] - db[0]),
        1e-7 * (db[3] - db[2]),
    ];
    let mut lambda = 1e-3;
    let (mut r, mut gap, mut sin, mut mid) = residual(&x);
    let sq = |r: &[f64; 5]| r.iter().map(|c| c * c).sum::<f64>();
    let mut it = 0;
    // Squared residuals of the last `STALL_SPAN` accepted iterates: a run that has not
    // reduced them by `STALL_RATIO` over that span is stalled at a local minimum that is
    // not a root (towards a root Gauss–Newton's reduction is at least geometric).
    let mut recent = [f64::INFINITY; STALL_SPAN];
    let (mut duplicate, mut stalled) = (false, false);
    while it < prm.max_iter && !(gap <= prm.tol * 1e-2 && sin <= prm.tangent_sin * 1e-2) {
        if known(&mid) {
            duplicate = true;
            break;
        }
        let now = sq(&r);
        if now > STALL_RATIO * recent[it as usize % STALL_SPAN] {
            stalled = true;
            break;
        }
        recent[it as usize % STALL_SPAN] = now;
        it += 1;
        // Central-difference Jacobian J (5 × 4).
        let mut j = [[0.0; 4]; 5];
        for c in 0..4 {
            let (mut xp, mut xm) = (x, x);
            xp[c] += h[c];
            xm[c] -= h[c];
            let (rp, rm) = (residual(&clamp(xp)).0, residual(&clamp(xm)).0);
            let w = clamp(xp)[c] - clamp(xm)[c];
            if w == 0.0 {
                continue;
            }
            for row in 0..5 {
                j[row][c] = (rp[row] - rm[row]) / w;
            }
        }
        // (JᵀJ + λ diag) δ = -Jᵀ r
        let mut a = [[0.0; 4]; 4];
        let mut g = [0.0; 4];
        for p in 0..4 {
            for q in 0..4 {
                a[p][q] = (0..5).map(|k| j[k][p] * j[k][q]).sum();
            }
            g[p] = -(0..5).map(|k| j[k][p] * r[k]).sum::<f64>();
        }
        let mut improved = false;
        for _ in 0..8 {
            let mut m = a;
            for p in 0..4 {
                m[p][p] += lambda * a[p][p].max(1e-300);
            }
            let Some(d) = solve4(m, g) else {
                lambda *= 10.0;
                continue;
            };
            let xn = clamp([x[0] + d[0], x[1] + d[1], x[2] + d[2], x[3] + d[3]]);
            let (rn, gn, sn, mn) = residual(&xn);
            if sq(&rn) < sq(&r) {
                (x, r, gap, sin, mid) = (xn, rn, gn, sn, mn);
                lambda = (lambda * 0.3).max(1e-12);
                improved = true;
                break;
            }
            lambda *= 10.0;
        }
        if !improved {
            stalled = true;
            break;
        }
    }
    let root = !duplicate && gap <= prm.tol && sin <= prm.tangent_sin;
    let status = if root {
        RefineStatus::Tangential
    } else {
        RefineStatus::NotConverged
    };
    let r = Refined {
        xyz: mid,
        uv_a: [x[0], x[1]],
        uv_b: [x[2], x[3]],
        gap,
        status,
        iterations: it,
        sin_angle: f64::NAN,
    };
    (r, stalled && !root)
}

/// Gaussian elimination with partial pivoting for a 4 × 4 system.
fn solve4(mut a: [[f64; 4]; 4], mut b: [f64; 4]) -> Option<[f64; 4]> {
    for c in 0..4 {
        let p = (c..4).max_by(|&i, &k| a[i][c].abs().total_cmp(&a[k][c].abs()))?;
        if a[p][c].is_nan() || a[p][c] == 0.0 {
            return None;
        }
        a.swap(c, p);
        b.swap(c, p);
        for r in c + 1..4 {
            let f = a[r][c] / a[c][c];
            for k in c..4 {
                a[r][k] -= f * a[c][k];
            }
            b[r] -= f * b[c];
        }
    }
    let mut x = [0.0; 4];
    for c in (0..4).rev() {
        let s: f64 = (c + 1..4).map(|k| a[c][k] * x[k]).sum();
        x[c] = (b[c] - s) / a[c][c];
    }
    x.iter().all(|v| v.is_finite()).then_some(x)
}

/// Refine a point of the intersection curve onto a border line of one surface's domain:
/// parameter `coord` (0 = u, 1 = v) of surface `which` (0 = A, 1 = B) held at `value`, and
/// `s(u,v) = r(w,t)` solved for the other three parameters by Newton's method (3 × 3). Where
/// a curve leaves a face, its end then lies on the face's boundary, not near it.
pub fn refine_on_border(
    sa: &NurbsSurface<f64, 3>,
    sb: &NurbsSurface<f64, 3>,
    start: &Refined,
    which: usize,
    coord: usize,
    value: f64,
    prm: &RefineParams,
) -> Option<Refined> {
    let (da, db) = (domain(sa), domain(sb));
    let mut x = [start.uv_a[0], start.uv_a[1], start.uv_b[0], start.uv_b[1]];
    let fixed = 2 * which + coord;
    x[fixed] = value;
    let free: Vec<usize> = (0..4).filter(|&k| k != fixed).collect();
    let lim = [da[0], da[1], da[2], da[3], db[0], db[1], db[2], db[3]];
    for it in 0..prm.max_iter {
        let (p, su, sv) = point_d1(sa, x[0], x[1]);
        let (q, rw, rt) = point_d1(sb, x[2], x[3]);
        let r = sub(&p, &q);
        let gap = norm(&r);
        if gap <= prm.tol {
            return Some(Refined {
                xyz: scale(&add(&p, &q), 0.5),
                uv_a: [x[0], x[1]],
                uv_b: [x[2], x[3]],
                gap,
                status: RefineStatus::Converged,
                iterations: it,
                sin_angle: sin_between(&su, &sv, &rw, &rt),
            });
        }
        let cols = [su, sv, scale(&rw, -1.0), scale(&rt, -1.0)];
        let (c0, c1, c2) = (cols[free[0]], cols[free[1]], cols[free[2]]);
        let det = dot(&c0, &cross(&c1, &c2));
        if det.is_nan() || det == 0.0 {
            return None;
        }
        // Cramer's rule for J δ = -r.
        let nr = scale(&r, -1.0);
        let d = [
            dot(&nr, &cross(&c1, &c2)) / det,
            dot(&c0, &cross(&nr, &c2)) / det,
            dot(&c0, &cross(&c1, &nr)) / det,
        ];
        for (k, &f) in free.iter().enumerate() {
            x[f] = (x[f] + d[k]).clamp(lim[2 * f], lim[2 * f + 1]);
        }
        if !x.iter().all(|v| v.is_finite()) {
            return None;
        }
    }
    None
}

/// `sin` of the angle between the normals `S_u × S_v` and `R_w × R_t` (NaN or ∞ where a
/// normal vanishes or is not finite).
pub fn sin_between(su: &[f64; 3], sv: &[f64; 3], rw: &[f64; 3], rt: &[f64; 3]) -> f64 {
    let (na, nb) = (cross(su, sv), cross(rw, rt));
    let (la, lb) = (norm(&na), norm(&nb));
    if !(la > 0.0 && lb > 0.0 && la.is_finite() && lb.is_finite()) {
        return f64::NAN;
    }
    norm(&cross(&na, &nb)) / (la * lb)
}
