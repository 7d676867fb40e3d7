//! Step 9b — the curve certificate: for an output point `p` with parameters `(u, v)` on
//! `S_A` and `(s, t)` on `S_B`, a proven radius `r` such that a true intersection point
//! `q = S_A(u*, v*) = S_B(s*, t*)`, with `(u*, v*)` and `(s*, t*)` in the closed (untrimmed)
//! parameter domains of the two faces, lies within `r` of `p`. So `r` bounds the distance from
//! `p` to the intersection *curve* — unlike [`super::certify`], which bounds the distance to
//! each surface at `p`'s own parameters (near tangency a point within `d` of both surfaces can
//! be `d / θ` from the curve, `θ` the angle between the surfaces).
//!
//! **The system.** `F(u, v, s, t) = (S_A(u, v) − S_B(s, t), g)` with the fourth equation `g`
//! either `n · (S_A(u, v) − p)` (the plane through `p` across the curve; `n` a unit `f64`
//! approximation of the curve tangent `N_A × N_B` at `p`'s parameters) or, when the zero may
//! lie beyond a border of a domain, `z_k − c` (that parameter held on the border line). Any
//! fixed `n` keeps the argument sound; a good one keeps the Jacobian well conditioned.
//!
//! **Krawczyk's theorem** (Krawczyk 1969; in this form Rump, *Verification methods*, Acta
//! Numerica 2010, the Krawczyk operator). Let `X` be a box, `y ∈ X`, `Y` any real 4 × 4 matrix,
//! `F` continuous on `X`, and `J` an interval matrix such that for all `x, x' ∈ X` the
//! difference `F(x) − F(x')` equals `M (x − x')` for some real `M ∈ J` (each row an average
//! of gradients: the mean-value form). If
//!
//! `K(X) = y − Y F(y) + (I − Y J)(X − y) ⊂ interior(X)`
//!
//! then `Y` and every `M ∈ J` are non-singular, and `F` has exactly one zero in `X`, and it lies
//! in `K(X)`. (Existence: `x ↦ x − Y F(x)` maps `X` into `K(X) ⊂ X`, Brouwer; uniqueness: two
//! zeros give `M (x − x') = 0`.) Here `y` is the `f64` Newton solution of `F = 0` started at
//! `p`'s parameters, `Y ≈ J(y)⁻¹` in `f64`, `F(y)` is enclosed by interval evaluation, and `J`
//! encloses the Jacobian over the whole box ([`super::enclose`], one-sided across knot lines,
//! which is what the mean-value form needs) — or over a larger box shared with nearby points
//! ([`super::jet_cache`]: an enclosure over a superset is one over `X`). The box is chosen by ε-inflation: radius from
//! the Newton correction `|Y F(y)|`, doubled (or grown to hold `K`) for a few tries.
//!
//! **Runs.** Consecutive output points share one plane direction, one preconditioner and one
//! matrix `I − Y J` over their common box ([`RunCertifier`]); a point that shared test does
//! not settle within tol/8 is certified on its own as above.
//!
//! **The radius.** The zero `z*` lies in `K(X) ∩ X`; the point `q = S_A(z*_uv) = S_B(z*_st)` in
//! the intersection of the enclosures of `S_A` and `S_B` over that box (mean-value forms about
//! `y`, with the derivative enclosures over `X`), and `r` bounds
//! `sup ||p − q||` over it with upward rounding. The zero is a point of the *faces* only if its
//! parameters lie in the domains: that is checked (`K(X) ∩ X` inside the closed domains, the
//! held parameter equal to the border value); a box reaching past a border is retried with the
//! parameter held on that border. Where the curve leaves both domains at one point (a corner
//! of both), the plane is moved along the curve by `±δ` (`δ` from `1e-12` to `1e-6` of the
//! point's scale): any plane isolates *some* zero, and the radius is still measured from `p`,
//! so it comes out about `δ` when that zero lies inside both domains. Where `p` lies on a
//! proven seam (a closed surface's two borders one curve), the search on the moved planes
//! also starts from the seam's other border, where the zero across it lies.
//!
//! **Hypotheses.** The surfaces are continuous (interior knot multiplicity at most the
//! degree, enforced when a surface is built) and their weights do not vanish on the boxes
//! (proven by the interval quotient, refused otherwise). Nothing else: knots, control points
//! and `p` are taken as the exact `f64` values they are.
//!
//! **Uncertified** (never guessed): where the surfaces are tangent or nearly so (the normals
//! parallel, the Jacobian singular or the box not contracted after the tries), at singular
//! points of the intersection, where the zero leaves both a domain and the border retry, and
//! where an enclosure fails. The reason is reported per point ([`Uncertified`]).

mod moved;
mod run;
mod system;

pub use run::RunCertifier;

use super::certify::distance_upper;
use super::enclose::Jet;
use super::jet_cache::JetCache;
use super::refine::{domain, point_d1};
use crate::geom::{cross, norm};
use crate::scalar::Interval;
use crate::spline::NurbsSurface;
use moved::inside_near;
use serde::Serialize;
use system::{Eval, Fourth, System, pt};

/// Why a point is not certified against the curve.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Uncertified {
    /// A coordinate or parameter is not finite.
    NotFinite,
    /// The surface normals at the point are parallel to working precision (tangency or a
    /// singular point): there is no curve tangent and the system is singular.
    Tangency,
    /// The `f64` Jacobian at the Newton solution could not be inverted.
    Singular,
    /// No box passed the Krawczyk test (ill-conditioned: near tangency).
    NoContraction,
    /// The zero may lie beyond a border of a face's domain, and holding that parameter on
    /// the border does not isolate it either (a curve running along the border, as where
    /// adjacent faces meet at their common edge; a corner of both domains).
    OutsideDomain,
    /// An interval enclosure failed (a weight enclosure holds 0, or overflow).
    Enclosure,
    /// Not attempted: the certificates were switched off ([`super::SsiParams::certify`]).
    NotRequested,
    /// Near a proven branch point, where this test fails: a true intersection point was
    /// proven by a sign change ([`super::sign_change`]), but farther from the point than tol
    /// (the radius is not reported as a certificate).
    SignChangeAboveTol,
}

/// A proven curve point near `p`.
#[derive(Clone, Copy, Debug)]
pub struct CurveCertificate {
    /// Upper bound on `||p − q||`, `q` a true intersection point of the two faces.
    pub radius: f64,
    /// Box of parameters `(u, v, s, t)` holding the unique zero of the system.
    pub params: [Interval; 4],
    /// The parameter held on a border line instead of the plane across the curve.
    pub held: Option<usize>,
    /// Some try of the test took `J` from a shared enclosure ([`JetCache`]): the box and the
    /// radius can be wider than with `J` over `X` alone.
    pub shared_jacobian: bool,
    /// The box's centre `y` (the `f64` Newton solution), and enclosures of `S_A(y_0, y_1)` and
    /// `S_B(y_2, y_3)` (outward-rounded interval evaluation at the point): they bound the
    /// distance of a point to each surface at these parameters without evaluating again.
    pub centre: [f64; 4],
    pub at_centre: [[Interval; 3]; 2],
    /// Enclosure of the true common point `q` the radius is measured to.
    pub point: [Interval; 3],
}

pub(crate) use super::linalg4::{M4, inverse4, mul4};

/// Result of one attempt; `Outside(k, c)`: the zero may leave the domain across the border
/// `z_k = c`.
// Returned once per attempt and consumed at once: the size difference costs nothing.
#[allow(clippy::large_enum_variant)]
enum Attempt {
    Done(CurveCertificate),
    Outside(usize, f64),
    Fail(Uncertified),
}

/// Sines of the angle between the normals below which the point counts as tangential.
const TANGENT_SIN: f64 = 1e-12;
/// Newton steps in `f64`, and ε-inflation tries.
const NEWTON_STEPS: usize = 12;
const TRIES: usize = 8;

/// Newton in `f64` towards the zero of `sys` from `z0`: the last iterate, the Jacobian there
/// (`Some` when `want_j`), and whether the last step was at the level of the domain's
/// rounding; `None` where the Jacobian became singular. Without `want_j` a converged step
/// is not followed by an evaluation at the new iterate (the iterates are the same either way).
fn newton(
    sys: &System,
    z0: [f64; 4],
    at_z0: Option<(Eval, Eval)>,
    want_j: bool,
) -> Option<([f64; 4], Option<M4>, bool)> {
    let mut y = z0;
    let (mut f, mut j) = match at_z0 {
        Some((ea, eb)) => sys.assemble(&y, ea, eb),
        None => sys.eval_f64(&y),
    };
    let mut converged = false;
    for _ in 0..NEWTON_STEPS {
        let ji = inverse4(j)?;
        let d = mul4(&ji, &f);
        let next: [f64; 4] = std::array::from_fn(|i| y[i] - d[i]);
        if !next.iter().all(|x| x.is_finite()) {
            break;
        }
        y = next;
        if let Fourth::Hold { k, c } = sys.e {
            y[k] = c;
        }
        // Converged when the step was at the level of the domain's rounding (1e-12 of its
        // size): the next one would be below the box radius anyway.
        let done = (0..4).all(|i| d[i].abs() <= 1e-12 * (sys.hi[i] - sys.lo[i] + y[i].abs()));
        if done && !want_j {
            return Some((y, None, true));
        }
        (f, j) = sys.eval_f64(&y);
        if done {
            converged = true;
            break;
        }
    }
    Some((y, Some(j), converged))
}

/// Enclosure of the common point `q = S_A(z*_uv) = S_B(z*_st)` for a zero `z*` in the box `z`:
/// the intersection of the mean-value forms of both surfaces about `y` (`at_y` their
/// enclosures at `y`, `jets` derivative enclosures over a box holding `y` and `z`); `None` when
/// the two do not meet (impossible for a true zero: a claim is refused rather than made).
fn common_point(
    z: &[Interval; 4],
    y: &[f64; 4],
    at_y: &[[Interval; 3]; 2],
    jets: &[Jet; 2],
) -> Option<[Interval; 3]> {
    let mv = |s0: &[Interval; 3], j: &Jet, a: usize| -> [Interval; 3] {
        let (du, dv) = (z[a] - pt(y[a]), z[a + 1] - pt(y[a + 1]));
        std::array::from_fn(|c| s0[c] + j.su[c] * du + j.sv[c] * dv)
    };
    let (ea, eb) = (mv(&at_y[0], &jets[0], 0), mv(&at_y[1], &jets[1], 2));
    let mut q = [pt(0.0); 3];
    for c in 0..3 {
        let (lo, hi) = (ea[c].lo.max(eb[c].lo), ea[c].hi.min(eb[c].hi));
        if lo > hi {
            return None;
        }
        q[c] = Interval::new(lo, hi);
    }
    Some(q)
}

fn attempt(sys: &System, z0: [f64; 4], at_z0: Option<(Eval, Eval)>) -> Attempt {
    // Newton in f64 towards the zero (any centre is sound; a good one keeps the box small).
    let Some((y, Some(j), _)) = newton(sys, z0, at_z0, true) else {
        return Attempt::Fail(Uncertified::Singular);
    };
    // Newton ran far off the faces: no isolated zero near p (tangency, or no curve there).
    if !(0..4).all(|i| {
        let w = sys.hi[i] - sys.lo[i];
        y[i] >= sys.lo[i] - 0.25 * w && y[i] <= sys.hi[i] + 0.25 * w
    }) {
        return Attempt::Fail(Uncertified::NoContraction);
    }
    // The preconditioner: the inverse of the f64 Jacobian at y (any matrix is sound).
    let Some(yinv) = inverse4(j) else {
        return Attempt::Fail(Uncertified::Singular);
    };
    let Some((fy, at_y)) = sys.f_at(&y) else {
        return Attempt::Fail(Uncertified::Enclosure);
    };
    // Starting radius: twice the (enclosed) Newton correction plus a few ulps of the scale.
    let mut rad = [0.0f64; 4];
    for i in 0..4 {
        let mut corr = pt(0.0);
        for l in 0..4 {
            corr = corr + pt(yinv[i][l]) * fy[l];
        }
        let scale = y[i].abs() + (sys.hi[i] - sys.lo[i]);
        rad[i] = 2.0 * corr.mag() + 64.0 * f64::EPSILON * scale;
    }
    let mut found = None;
    let mut shared_jacobian = false;
    for try_no in 0..TRIES {
        let x: [Interval; 4] = std::array::from_fn(|i| {
            Interval::new((pt(y[i]) - pt(rad[i])).lo, (pt(y[i]) + pt(rad[i])).hi)
        });
        shared_jacobian |= sys.cache.is_some_and(|c| c.covers(&x));
        let Some((k, jets)) = sys.krawczyk(&y, &x, &yinv, &fy) else {
            // A grown box may reach where a weight enclosure holds 0.
            return Attempt::Fail(if try_no == 0 {
                Uncertified::Enclosure
            } else {
                Uncertified::NoContraction
            });
        };
        if !k.iter().all(|v| v.is_finite()) {
            return Attempt::Fail(Uncertified::NoContraction);
        }
        if (0..4).all(|i| k[i].lo > x[i].lo && k[i].hi < x[i].hi) {
            found = Some((x, k, jets));
            break;
        }
        for i in 0..4 {
            let reach = (k[i].lo - y[i]).abs().max((k[i].hi - y[i]).abs());
            rad[i] = (2.0 * rad[i]).max(1.25 * reach);
        }
        if !(0..4)
            .all(|i| rad[i].is_finite() && rad[i] <= 0.25 * (sys.hi[i] - sys.lo[i]).max(1e-300))
        {
            break;
        }
    }
    let Some((x, k, jets)) = found else {
        return Attempt::Fail(Uncertified::NoContraction);
    };
    // The zero lies in K(X) ∩ X; a held parameter equals its border value exactly.
    let mut z: [Interval; 4] =
        std::array::from_fn(|i| Interval::new(k[i].lo.max(x[i].lo), k[i].hi.min(x[i].hi)));
    let held = match sys.e {
        Fourth::Hold { k, c } => {
            z[k] = pt(c);
            Some(k)
        }
        Fourth::Plane { .. } => None,
    };
    for i in 0..4 {
        if z[i].lo < sys.lo[i] {
            return Attempt::Outside(i, sys.lo[i]);
        }
        if z[i].hi > sys.hi[i] {
            return Attempt::Outside(i, sys.hi[i]);
        }
    }
    // q = S_A(z*_uv) = S_B(z*_st), enclosed by the mean-value form about y over z ⊂ X.
    let Some(q) = common_point(&z, &y, &at_y, &jets) else {
        // Both enclose q: cannot happen; refuse rather than claim.
        return Attempt::Fail(Uncertified::Enclosure);
    };
    match distance_upper(&sys.p, &q) {
        Some(radius) => Attempt::Done(CurveCertificate {
            radius,
            shared_jacobian,
            params: z,
            held,
            centre: y,
            at_centre: at_y,
            point: q,
        }),
        None => Attempt::Fail(Uncertified::Enclosure),
    }
}

/// The curve certificate of the point `p` with parameters `uv_a` on `sa` and `uv_b` on `sb`
/// (see the module comment).
pub fn certify_on_curve(
    sa: &NurbsSurface<f64, 3>,
    sb: &NurbsSurface<f64, 3>,
    p: &[f64; 3],
    uv_a: &[f64; 2],
    uv_b: &[f64; 2],
) -> Result<CurveCertificate, Uncertified> {
    certify_with(sa, sb, p, uv_a, uv_b, None)
}

/// [`certify_on_curve`] taking the Jacobian enclosure from `cache` for every box it holds
/// ([`JetCache`]). Where that fails, or gives a radius above `goal` after a try with the
/// shared enclosure (the wider enclosure widens `K(X)`, most near tangency, where `Y` is
/// large, and a failed try grows the box), the point is certified again without it and the
/// smaller radius kept.
pub fn certify_on_curve_cached(
    sa: &NurbsSurface<f64, 3>,
    sb: &NurbsSurface<f64, 3>,
    p: &[f64; 3],
    uv_a: &[f64; 2],
    uv_b: &[f64; 2],
    cache: Option<&JetCache>,
    goal: f64,
) -> Result<CurveCertificate, Uncertified> {
    if cache.is_none() {
        return certify_with(sa, sb, p, uv_a, uv_b, None);
    }
    match certify_with(sa, sb, p, uv_a, uv_b, cache) {
        Ok(c) if c.radius <= goal || !c.shared_jacobian => Ok(c),
        Ok(c) => match certify_with(sa, sb, p, uv_a, uv_b, None) {
            Ok(d) if d.radius < c.radius => Ok(d),
            _ => Ok(c),
        },
        Err(_) => certify_with(sa, sb, p, uv_a, uv_b, None),
    }
}

/// The `f64` Newton solution `y` of the certificate's system (the plane across the curve
/// through `p`, started at `p`'s parameters), when the steps converged and `y` lies in both
/// closed domains: the centre the certificate starts from, found without enclosures. It only
/// moves points onto the curve (near tangency a point within tol of both surfaces can lie far
/// from it); nothing is claimed from it.
pub fn newton_on_curve(
    sa: &NurbsSurface<f64, 3>,
    sb: &NurbsSurface<f64, 3>,
    p: &[f64; 3],
    uv_a: &[f64; 2],
    uv_b: &[f64; 2],
) -> Option<[f64; 4]> {
    let (sys, z0, at_z0, _) = plane_system(sa, sb, p, uv_a, uv_b, None).ok()?;
    let (y, _, converged) = newton(&sys, z0, Some(at_z0), false)?;
    (converged && (0..4).all(|i| y[i] >= sys.lo[i] && y[i] <= sys.hi[i])).then_some(y)
}

/// The system with the plane across the curve through `p`, the start `z0`, the surfaces'
/// `f64` jets there, and the plane's normal.
type PlaneSystem<'a> = (System<'a>, [f64; 4], (Eval, Eval), [f64; 3]);

/// The system with the plane across the curve through `p` (its normal `N_A × N_B` at `p`'s
/// parameters), the start `z0`, the surfaces' `f64` jets there, and the plane's normal.
fn plane_system<'a>(
    sa: &'a NurbsSurface<f64, 3>,
    sb: &'a NurbsSurface<f64, 3>,
    p: &[f64; 3],
    uv_a: &[f64; 2],
    uv_b: &[f64; 2],
    cache: Option<&'a JetCache>,
) -> Result<PlaneSystem<'a>, Uncertified> {
    if !p.iter().chain(uv_a).chain(uv_b).all(|x| x.is_finite()) {
        return Err(Uncertified::NotFinite);
    }
    let (da, db) = (domain(sa), domain(sb));
    let lo = [da[0], da[2], db[0], db[2]];
    let hi = [da[1], da[3], db[1], db[3]];
    let z0 = [uv_a[0], uv_a[1], uv_b[0], uv_b[1]];
    let ea = point_d1(sa, z0[0], z0[1]);
    let eb = point_d1(sb, z0[2], z0[3]);
    let ((_, au, av), (_, bs, bt)) = (ea, eb);
    let (na, nb) = (cross(&au, &av), cross(&bs, &bt));
    let t = cross(&na, &nb);
    let (la, lb, lt) = (norm(&na), norm(&nb), norm(&t));
    if !(la > 0.0 && lb > 0.0 && lt > TANGENT_SIN * la * lb && lt.is_finite()) {
        return Err(Uncertified::Tangency);
    }
    let n = t.map(|c| c / lt);
    let sys = System {
        sa,
        sb,
        cache,
        e: Fourth::Plane { n, p: *p },
        p: *p,
        lo,
        hi,
    };
    Ok((sys, z0, (ea, eb), n))
}

fn certify_with(
    sa: &NurbsSurface<f64, 3>,
    sb: &NurbsSurface<f64, 3>,
    p: &[f64; 3],
    uv_a: &[f64; 2],
    uv_b: &[f64; 2],
    cache: Option<&JetCache>,
) -> Result<CurveCertificate, Uncertified> {
    // The plane across the curve through p; if the zero may lie beyond a border, that
    // parameter held on the border instead.
    let (mut sys, z0, at_z0, n) = plane_system(sa, sb, p, uv_a, uv_b, cache)?;
    match attempt(&sys, z0, Some(at_z0)) {
        Attempt::Done(c) => Ok(c),
        Attempt::Fail(u) => Err(u),
        Attempt::Outside(k, c) => {
            sys.e = Fourth::Hold { k, c };
            let mut z = z0;
            z[k] = c;
            match attempt(&sys, z, None) {
                Attempt::Done(c) => Ok(c),
                // The zero lies on or near a border where holding the parameter does not
                // isolate it (a curve along the border, a corner of both domains): look for
                // a zero a little inside, on planes moved along the curve.
                Attempt::Fail(_) | Attempt::Outside(..) => inside_near(&mut sys, z0, n, p),
            }
        }
    }
}

#[cfg(test)]
mod tests;
