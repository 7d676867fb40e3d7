//! Singular points of the intersection — touching points and branch points — classified with
//! a proof, or reported uncertified with the reason (never guessed).
//!
//! **The system.** With `A = S_A(u, v)`, `B = S_B(s, t)`, `D = A − B` and the unnormalised
//! normal `n = B_s × B_t`, the square system in `z = (u, v, s, t)`
//!
//! `G1 = D·B_s,  G2 = D·B_t,  G3 = n·A_u,  G4 = n·A_v`.
//!
//! `G1 = G2 = 0` makes `B(s, t)` a normal foot of `A(u, v)` on `S_B`: `D = h n̂` with the
//! signed normal distance `h = D·n̂`, `n̂ = n / |n|`. Near a root `z*` at which
//! `J_12 = ∂(G1, G2)/∂(s, t)` is non-singular, the foot is a C¹ function `y(x)` of
//! `x = (u, v)` (implicit function theorem), and `∇h(x) = (A_u·n̂, A_v·n̂)` (the terms of
//! `∂D` along `B`'s tangent plane and `h n̂·∂n̂ = 0` drop out). So `G = 0` ⟺ `x` is a critical
//! point of the normal distance `h`, and the surfaces' normals are parallel there.
//!
//! **Type.** Write `J = J_G(z*) = [[J11, J12], [J21, J22]]` in the blocks `x`, `y`. The map
//! `g(x) = (G3, G4)(x, y(x)) = |n(y(x))| ∇h(x)` has `Dg = J21 − J22 J12⁻¹ J11` (the Schur
//! complement), and at a critical point `Dg = |n| Hess h`. Hence
//! `det J = det J12 · |n|² · det Hess h`: with `det J12` of proven sign (it is
//! `det(−metric of S_B + D·second derivatives)`, positive near a contact), the sign of
//! `det J` is the sign of `det Hess h`: **positive → extremum** of `h` (a touching point when
//! `h(z*) = 0`), **negative → saddle** (two intersection branches crossing — a branch point —
//! when `h(z*) = 0`).
//!
//! **Proof.** Krawczyk's test ([`super::krawczyk`], same operator) on `G` over a box `X`
//! around the `f64` Newton solution `y` of `G = 0`: `G(y)` enclosed at the point, the
//! Jacobian `J_G(X)` over the box from outward-rounded enclosures of `S`, its first and second
//! partial derivatives ([`super::enclose2`], the NURBS Book A2.3 with interval parameters; quotient
//! rule, eq. 4.20, for the rational surface). `K(X) ⊂ int X` proves a unique zero `z*` of `G`
//! in `X`, inside `K(X)`, and that every real matrix of `J_G(X)` is non-singular; `J_G(X)` is
//! connected, so `det` has one sign on it, which is the sign of `det` of its midpoint matrix
//! (enclosed). `det J12` is enclosed over `X` directly. The distance at the root,
//! `|h(z*)| = |S_A − S_B|`, is enclosed over `K(X) ∩ X`.
//!
//! **Pieces.** The mean-value form needs `G` continuous and piecewise C¹ on `X`, and the
//! type argument (a Hessian at the root) needs the surfaces C² there: every knot inside the
//! box of multiplicity at most the degree − 2. A box that meets a knot line of multiplicity
//! ≥ the degree − 1 (where the parametrisation is not C² — every interior knot of a
//! quadratic, the C0 joints of the standard circle, sphere, torus forms) is cut there into
//! closed *pieces*; on each, the surface is one C² function, extended analytically over all
//! of `X`, and the test is run per piece with the same `X`. Each piece's system then has exactly
//! one zero in `X`; every critical point of the normal distance in the closed piece (with the
//! piece's one-sided derivatives) is that zero; all of them lie in the reported root box. The
//! claim is per piece (`pieces > 1`); existence of a critical point *on* the cut line is not
//! claimed beyond that. In a closed direction ([`closed`]: `S(d0, ·) = S(d1, ·)` exactly) the
//! parameter runs on across the seam into a copy of the domain one period away, and the seam
//! cuts the box like such a knot line.
//!
//! **The claim** (`kind` touching_point / branch_point): "in this box, the normal distance
//! from one surface to the other has a unique critical point (per piece), non-degenerate, of
//! type extremum / saddle, at which the distance between the surfaces lies in `distance`
//! (upper end ≤ tol)". `h(z*) = 0` is not claimed (not decidable in floating point), and
//! nothing is claimed about the intersection away from the root box.
//!
//! Hypotheses: weights positive on the box (proven by the interval quotients, refused
//! otherwise); the root inside both closed parameter domains (checked in the open
//! directions). The theorem, its proof and the claim in full: docs/ssi.md, "Singular points".

mod proof;
mod region;

pub use region::{BranchRegion, branch_region, disjoint_regions};

use super::refine::domain;
use super::report::{SingularKind, SingularOut, SingularReason};
use crate::scalar::Interval;
use crate::spline::NurbsSurface;

type I = Interval;
type V = [I; 3];
use super::enclose2::{Jet2, Piece, group_jet, groups, restrict};
use super::krawczyk::M4;
use crate::spline::closure::exact_seam as closed;
use proof::prove;

fn pt(x: f64) -> I {
    Interval::point(x)
}

/// Most pieces (products of smooth groups in the four directions).
const MAX_PIECES: usize = 16;
const NEWTON_STEPS: usize = 30;
const TRIES: usize = 10;

fn dot(a: &V, b: &V) -> I {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn cross(a: &V, b: &V) -> V {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn add(a: &V, b: &V) -> V {
    std::array::from_fn(|k| a[k] + b[k])
}
fn sub(a: &V, b: &V) -> V {
    std::array::from_fn(|k| a[k] - b[k])
}

/// `G` and its Jacobian from the jets of the distance surface `a` (parameters `u, v`) and the
/// foot surface `b` (`s, t`).
pub fn system(a: &Jet2, b: &Jet2) -> ([I; 4], [[I; 4]; 4]) {
    let d = sub(&a.s, &b.s);
    let n = cross(&b.su, &b.sv);
    let ns = add(&cross(&b.suu, &b.sv), &cross(&b.su, &b.suv));
    let nt = add(&cross(&b.suv, &b.sv), &cross(&b.su, &b.svv));
    let g = [
        dot(&d, &b.su),
        dot(&d, &b.sv),
        dot(&n, &a.su),
        dot(&n, &a.sv),
    ];
    let j = [
        [
            dot(&a.su, &b.su),
            dot(&a.sv, &b.su),
            dot(&d, &b.suu) - dot(&b.su, &b.su),
            dot(&d, &b.suv) - dot(&b.sv, &b.su),
        ],
        [
            dot(&a.su, &b.sv),
            dot(&a.sv, &b.sv),
            dot(&d, &b.suv) - dot(&b.su, &b.sv),
            dot(&d, &b.svv) - dot(&b.sv, &b.sv),
        ],
        [
            dot(&n, &a.suu),
            dot(&n, &a.suv),
            dot(&ns, &a.su),
            dot(&nt, &a.su),
        ],
        [
            dot(&n, &a.suv),
            dot(&n, &a.svv),
            dot(&ns, &a.sv),
            dot(&nt, &a.sv),
        ],
    ];
    (g, j)
}

/// Enclosure of the determinant of a real 4 × 4 matrix (Laplace expansion in intervals).
fn det4(m: &M4) -> I {
    let e = |i: usize, j: usize| pt(m[i][j]);
    let det3 = |r: [usize; 3], c: [usize; 3]| {
        e(r[0], c[0]) * (e(r[1], c[1]) * e(r[2], c[2]) - e(r[1], c[2]) * e(r[2], c[1]))
            - e(r[0], c[1]) * (e(r[1], c[0]) * e(r[2], c[2]) - e(r[1], c[2]) * e(r[2], c[0]))
            + e(r[0], c[2]) * (e(r[1], c[0]) * e(r[2], c[1]) - e(r[1], c[1]) * e(r[2], c[0]))
    };
    let mut acc = pt(0.0);
    for j in 0..4 {
        let cols: Vec<usize> = (0..4).filter(|&c| c != j).collect();
        let minor = det3([1, 2, 3], [cols[0], cols[1], cols[2]]);
        let term = e(0, j) * minor;
        acc = if j % 2 == 0 { acc + term } else { acc - term };
    }
    acc
}

fn sign(x: I) -> Option<i8> {
    if x.is_pos() {
        Some(1)
    } else if x.is_neg() {
        Some(-1)
    } else {
        None
    }
}

/// One piece of the box: a smooth group in each of the four directions.
type PieceIdx = [usize; 4];

/// The two surfaces in their roles: `h` is a function on `a`'s parameters, its foot on `b`.
struct Roles<'a> {
    a: &'a NurbsSurface<f64, 3>,
    b: &'a NurbsSurface<f64, 3>,
    lo: [f64; 4],
    hi: [f64; 4],
    /// Closed directions (the parameter may run on across the seam).
    per: [bool; 4],
}

/// Groups of every direction over the box `x`.
type BoxGroups = [Vec<Vec<Piece>>; 4];

impl Roles<'_> {
    fn box_groups(&self, x: &[I; 4]) -> Option<BoxGroups> {
        let (ha, hb) = (&self.a.hom, &self.b.hom);
        Some([
            groups(&ha.ku, x[0], self.per[0])?,
            groups(&ha.kv, x[1], self.per[1])?,
            groups(&hb.ku, x[2], self.per[2])?,
            groups(&hb.kv, x[3], self.per[3])?,
        ])
    }
    fn pieces(g: &BoxGroups) -> Vec<PieceIdx> {
        let mut out = Vec::new();
        for i in 0..g[0].len() {
            for j in 0..g[1].len() {
                for k in 0..g[2].len() {
                    for l in 0..g[3].len() {
                        out.push([i, j, k, l]);
                    }
                }
            }
        }
        out
    }
    /// Jets of piece `c` over the sub-box `z ⊂ X`.
    fn jets(&self, g: &BoxGroups, c: &PieceIdx, z: &[I; 4]) -> Option<(Jet2, Jet2)> {
        let r = |d: usize| restrict(&g[d][c[d]], z[d]);
        Some((
            group_jet(self.a, &r(0), &r(1))?,
            group_jet(self.b, &r(2), &r(3))?,
        ))
    }
    /// `G` and `J_G` in `f64` at `y` (the first piece there; only steers).
    fn eval_f64(&self, y: &[f64; 4]) -> Option<([f64; 4], M4)> {
        let z: [I; 4] = y.map(pt);
        let g = self.box_groups(&z)?;
        let (ja, jb) = self.jets(&g, &[0; 4], &z)?;
        let (gv, jm) = system(&ja, &jb);
        let f = gv.map(|x| x.mid());
        let j = jm.map(|r| r.map(|x| x.mid()));
        (f.iter().chain(j.iter().flatten()).all(|x| x.is_finite())).then_some((f, j))
    }
}

struct Proven {
    x: [I; 4],
    root: [I; 4],
    pieces: usize,
    saddle: bool,
    distance: [f64; 2],
}

fn box4(a: I, b: I) -> [f64; 4] {
    [a.lo, a.hi, b.lo, b.hi]
}

/// Classify the singular point near the parameters `uv_a` on `sa`, `uv_b` on `sb` (a
/// tangential point found by [`super::refine::tangential_point`]): proven touching point or
/// branch point, or uncertified with the reason (see the module comment). `tol`: largest
/// distance between the surfaces at the root for which a contact is claimed.
pub fn classify(
    sa: &NurbsSurface<f64, 3>,
    sb: &NurbsSurface<f64, 3>,
    uv_a: &[f64; 2],
    uv_b: &[f64; 2],
    tol: f64,
) -> SingularOut {
    let (da, db) = (domain(sa), domain(sb));
    // h on A with its foot on B, then the other way round (a parametric degeneracy of one
    // surface — a pole — may spoil one of them).
    let (pa, pb) = (
        [closed(sa, 0), closed(sa, 1)],
        [closed(sb, 0), closed(sb, 1)],
    );
    let ab = Roles {
        a: sa,
        b: sb,
        lo: [da[0], da[2], db[0], db[2]],
        hi: [da[1], da[3], db[1], db[3]],
        per: [pa[0], pa[1], pb[0], pb[1]],
    };
    let ba = Roles {
        a: sb,
        b: sa,
        lo: [db[0], db[2], da[0], da[2]],
        hi: [db[1], db[3], da[1], da[3]],
        per: [pb[0], pb[1], pa[0], pa[1]],
    };
    // A parameter of a closed direction beyond the domain names the point one period away.
    let wrap = |x: f64, lo: f64, hi: f64| {
        if x < lo {
            x + (hi - lo)
        } else if x > hi {
            x - (hi - lo)
        } else {
            x
        }
    };
    let first = prove(&ab, [uv_a[0], uv_a[1], uv_b[0], uv_b[1]]);
    let (res, swapped) = match first {
        Ok(p) => (Ok(p), false),
        Err(e) => match prove(&ba, [uv_b[0], uv_b[1], uv_a[0], uv_a[1]]) {
            Ok(p) => (Ok(p), true),
            Err(_) => (Err(e), false),
        },
    };
    match res {
        Err(reason) => SingularOut {
            kind: SingularKind::Uncertified,
            box_a: None,
            box_b: None,
            root_a: None,
            root_b: None,
            root_point: None,
            distance: None,
            pieces: 0,
            critical_on: None,
            reason: Some(reason),
        },
        Ok(p) => {
            let (xa, xb) = if swapped {
                ((p.x[2], p.x[3]), (p.x[0], p.x[1]))
            } else {
                ((p.x[0], p.x[1]), (p.x[2], p.x[3]))
            };
            let (ra, rb) = if swapped {
                ((p.root[2], p.root[3]), (p.root[0], p.root[1]))
            } else {
                ((p.root[0], p.root[1]), (p.root[2], p.root[3]))
            };
            let within = p.distance[1] <= tol;
            SingularOut {
                kind: match (within, p.saddle) {
                    (false, _) => SingularKind::Uncertified,
                    (true, false) => SingularKind::TouchingPoint,
                    (true, true) => SingularKind::BranchPoint,
                },
                box_a: Some(box4(xa.0, xa.1)),
                box_b: Some(box4(xb.0, xb.1)),
                root_a: Some(box4(ra.0, ra.1)),
                root_b: Some(box4(rb.0, rb.1)),
                root_point: Some(sa.eval(
                    &wrap(ra.0.mid(), da[0], da[1]),
                    &wrap(ra.1.mid(), da[2], da[3]),
                )),
                distance: Some(p.distance),
                pieces: p.pieces,
                critical_on: Some(if swapped { 'b' } else { 'a' }),
                reason: (!within).then_some(SingularReason::DistanceAboveTol),
            }
        }
    }
}
