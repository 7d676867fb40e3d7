//! The region of a proven branch point: a parameter box `W = W_x × W_y` around the root `z*`
//! (on the surface the normal distance `h` is a function of, `x`, and on the other, `y`) in
//! which no closed loop of the intersection can hide except one through `z*`. The coverage
//! certificate decides pairs of pieces inside `W` with it, where normal cones cannot be
//! separated (they cannot near a branch point: the normals are parallel there).
//!
//! **Proven over `W`** (outward-rounded enclosures of the surfaces and their first and
//! second derivatives over `W`, [`crate::spline::enclose2`]; one smooth piece per direction,
//! so both surfaces are C² on `W`):
//! 1. *One critical point.* Every real matrix in the enclosure `J_G(W)` of the Jacobian of
//!    the tangency system `G` (the parent module) is non-singular: `‖I − C J_G(W)‖_∞ < 1`
//!    for `C` the inverse of its midpoint. By the mean-value theorem row by row,
//!    `G(z) − G(z') = M (z − z')` with `M` in `J_G(W)`, so `G` has at most one zero in `W`;
//!    the singular-point proof's root box lies in `W`, so that zero is `z*`.
//! 2. *One foot.* The parametric Krawczyk test on `(G1, G2)` in `y`, with `x` ranging over
//!    `W_x`: `K = y_m − C₂ G₁₂(W_x, y_m) + (I − C₂ J₁₂(W)) (W_y − y_m) ⊂ int W_y`. For each
//!    `x ∈ W_x` the operator of `y ↦ G₁₂(x, y)` lies in `K` (inclusion monotonicity), so it
//!    has exactly one zero `y(x)` in `W_y`, inside `int W_y`, and `J₁₂` is non-singular
//!    there: `y(x)` is C¹ (implicit function theorem).
//! 3. *A normal.* `n = S_y,s × S_y,t` has a component of one strict sign over `W_y`.
//!
//! **Lemma.** Let `α ⊆ W_x`, `β ⊆ W_y` be closed boxes, `I` the intersection. Every connected
//! component `K` of `I ∩ (α × β)` meets the border of `α × β` or contains `z*`.
//!
//! *Proof.* An intersection point `(x, y) ∈ α × β` has `S(x) = S'(y)`, so `G₁ = G₂ = 0`
//! and, by 2, `y = y(x)`; hence `I ∩ (α × W_y)` is the graph of `y` over the zero set of
//! `h(x) = (S(x) − S'(y(x)))·n̂(y(x))`, a continuous function on `α` with
//! `∇h = (S_u·n̂, S_v·n̂)` (the parent module; `S − S' = h n̂` at a foot), zero exactly
//! where `G₃ = G₄ = 0`, i.e. by 1 only at `x*` (when `z* = (x*, y(x*))`). Suppose `K` lies in
//! the interior of `α × β`. A compact component lying in the interior of a box is also a
//! component of the intersection with any larger box (it has a neighbourhood that is
//! open and closed in both), so `K` is a component of `I ∩ (α × W_y)`, and its projection
//! `K_x` a component of `{h = 0} ∩ α` in `int α`. If `x* ∉ K_x`, `∇h ≠ 0` on `K_x`, which is
//! then a compact connected 1-manifold without boundary — a Jordan curve in the box `α` — bounding
//! a disc `Ω ⊂ int α` with `h = 0` on its border. `h` is not zero on all of `Ω` (its gradient
//! would vanish on an open set), so `h` takes a non-zero extremum on `Ω̄` at an interior point:
//! a local extremum, a critical point, so `x*`. But `x*` is a non-degenerate saddle (the
//! singular-point proof: `det Hess h < 0`), not a local extremum. So `x* ∈ K_x`, `z* ∈ K`. ∎
//!
//! Hypotheses: positive weights (the enclosures are refused otherwise), the proof of the
//! branch point itself (one smooth piece, root box in both domains).

use super::{I, Roles, pt, system};
use crate::spline::NurbsSurface;
use crate::spline::enclose2::bezier_jet;
use crate::spline::enclosed_bezier::{EnclosedPatch, enclosed_bezier_patches};
use crate::ssi::krawczyk::inverse4;
use crate::ssi::report::{SingularKind, SingularOut};

/// A proven region (see the module comment), in the coordinates of A and B.
#[derive(Clone, Debug)]
pub struct BranchRegion {
    /// `W` on A (`[u0, u1, v0, v1]`) and on B.
    pub w_a: [f64; 4],
    pub w_b: [f64; 4],
    /// A model-space box holding the branch point `S_A(x*)` (the enclosure of the surface
    /// over the root box).
    pub point: ([f64; 3], [f64; 3]),
}

impl BranchRegion {
    /// Whether the pair of parameter boxes lies in `W` (each label widened by a margin for
    /// the rounding of subdivision labels: exact halves carry rounded midpoints).
    pub fn holds(&self, uv_a: &[f64; 4], uv_b: &[f64; 4]) -> bool {
        inside(uv_a, &self.w_a) && inside(uv_b, &self.w_b)
    }
}

/// The regions that meet no other one (4-D boxes `W_A × W_B`): the coverage argument
/// follows a component out of a region to a pair of pieces outside every region, which needs
/// the regions disjoint.
pub fn disjoint_regions(r: Vec<BranchRegion>) -> Vec<BranchRegion> {
    let apart =
        |p: &[f64; 4], q: &[f64; 4]| p[1] < q[0] || q[1] < p[0] || p[3] < q[2] || q[3] < p[2];
    (0..r.len())
        .filter(|&i| {
            (0..r.len())
                .all(|k| k == i || apart(&r[i].w_a, &r[k].w_a) || apart(&r[i].w_b, &r[k].w_b))
        })
        .map(|i| r[i].clone())
        .collect()
}

fn inside(c: &[f64; 4], w: &[f64; 4]) -> bool {
    let m = |a: f64, b: f64| 1e-12 * (1.0 + a.abs().max(b.abs()));
    let (mu, mv) = (m(w[0], w[1]), m(w[2], w[3]));
    w[0] + mu <= c[0] && c[1] <= w[1] - mu && w[2] + mv <= c[2] && c[3] <= w[3] - mv
}

/// Halvings of the region's size tried, from half the root's Bézier piece down.
const TRIES: usize = 24;

/// The largest region found (halving from half the root's Bézier piece) around a proven branch
/// point, or `None` (not a proven branch point, or no size passed the tests).
pub fn branch_region(
    sa: &NurbsSurface<f64, 3>,
    sb: &NurbsSurface<f64, 3>,
    s: &SingularOut,
) -> Option<BranchRegion> {
    if s.kind != SingularKind::BranchPoint || s.pieces != 1 {
        return None;
    }
    let (ra, rb) = (s.root_a?, s.root_b?);
    let swapped = match s.critical_on? {
        'a' => false,
        'b' => true,
        _ => return None,
    };
    let (x, y, rx, ry) = if swapped {
        (sb, sa, rb, ra)
    } else {
        (sa, sb, ra, rb)
    };
    let (dx, dy) = (super::domain(x), super::domain(y));
    let r = Roles {
        a: x,
        b: y,
        lo: [dx[0], dx[2], dy[0], dy[2]],
        hi: [dx[1], dx[3], dy[1], dy[3]],
        per: [false; 4],
    };
    let root: [I; 4] = [
        I::new(rx[0], rx[1]),
        I::new(rx[2], rx[3]),
        I::new(ry[0], ry[1]),
        I::new(ry[2], ry[3]),
    ];
    // The root inside the domains (a root past a seam is left alone).
    if (0..4).any(|i| root[i].lo < r.lo[i] || root[i].hi > r.hi[i]) {
        return None;
    }
    let c: [f64; 4] = root.map(|i| i.mid());
    // The foot's derivative at the root steers W_y's size: dy/dx = −J12⁻¹ J11.
    let (_, j) = r.eval_f64(&c)?;
    let inv = inverse2([[j[0][2], j[0][3]], [j[1][2], j[1][3]]])?;
    let dydx: [[f64; 2]; 2] = std::array::from_fn(|i| {
        std::array::from_fn(|k| -(inv[i][0] * j[0][k] + inv[i][1] * j[1][k]))
    });
    // W lies in one Bézier piece of each surface (the ones holding the root's centre), where
    // the surfaces are polynomial or rational functions and the Bernstein jets apply.
    let piece = |s: &NurbsSurface<f64, 3>, uv: [f64; 2]| {
        enclosed_bezier_patches(s)?
            .into_iter()
            .find(|e| e.uv[0] <= uv[0] && uv[0] <= e.uv[1] && e.uv[2] <= uv[1] && uv[1] <= e.uv[3])
    };
    let (px, py) = (piece(x, [c[0], c[1]])?, piece(y, [c[2], c[3]])?);
    let span = [
        px.uv[0], px.uv[1], px.uv[2], px.uv[3], py.uv[0], py.uv[1], py.uv[2], py.uv[3],
    ];
    let mut rho = [0.5 * (span[1] - span[0]), 0.5 * (span[3] - span[2])];
    for _ in 0..TRIES {
        let ry: [f64; 2] = std::array::from_fn(|i| {
            2.0 * (dydx[i][0].abs() * rho[0] + dydx[i][1].abs() * rho[1])
                + 0.05 * (r.hi[2 + i] - r.lo[2 + i]) * rho[0].max(rho[1])
                    / (r.hi[0] - r.lo[0]).max(r.hi[1] - r.lo[1])
        });
        let rad = [rho[0], rho[1], ry[0], ry[1]];
        let w: [I; 4] = std::array::from_fn(|i| {
            I::new(
                (c[i] - rad[i]).max(span[2 * i]),
                (c[i] + rad[i]).min(span[2 * i + 1]),
            )
        });
        if proven(&r, (&px, &py), &w, &root) {
            let (xs, ys) = ([w[0], w[1]], [w[2], w[3]]);
            let b4 = |p: [I; 2]| [p[0].lo, p[0].hi, p[1].lo, p[1].hi];
            let g = r.box_groups(&root)?;
            let (jx, _) = r.jets(&g, &[0; 4], &root)?;
            let point = (jx.s.map(|i| i.lo), jx.s.map(|i| i.hi));
            let (w_a, w_b) = if swapped {
                (b4(ys), b4(xs))
            } else {
                (b4(xs), b4(ys))
            };
            return Some(BranchRegion { w_a, w_b, point });
        }
        rho = [0.5 * rho[0], 0.5 * rho[1]];
    }
    None
}

/// Tests 1–3 of the module comment over `w`, and the root box inside `w`.
fn proven(
    r: &Roles,
    (px, py): (&EnclosedPatch, &EnclosedPatch),
    w: &[I; 4],
    root: &[I; 4],
) -> bool {
    if !(0..4).all(|i| w[i].lo <= root[i].lo && root[i].hi <= w[i].hi && w[i].lo < w[i].hi) {
        return false;
    }
    let (Some(ja), Some(jb)) = (bezier_jet(px, w[0], w[1]), bezier_jet(py, w[2], w[3])) else {
        return false;
    };
    let (_, jw) = system(&ja, &jb);
    // 3. A normal component of one sign.
    let n = [
        jb.su[1] * jb.sv[2] - jb.su[2] * jb.sv[1],
        jb.su[2] * jb.sv[0] - jb.su[0] * jb.sv[2],
        jb.su[0] * jb.sv[1] - jb.su[1] * jb.sv[0],
    ];
    if n.iter().all(|c| c.contains_zero()) {
        return false;
    }
    // 1. J_G(W) regular.
    let Some(cinv) = inverse4(jw.map(|row| row.map(|e| e.mid()))) else {
        return false;
    };
    for i in 0..4 {
        let mut norm = 0.0f64;
        for k in 0..4 {
            let mut e = pt(if i == k { 1.0 } else { 0.0 });
            for l in 0..4 {
                e = e - pt(cinv[i][l]) * jw[l][k];
            }
            norm = (norm + e.mag()).next_up();
        }
        if norm.partial_cmp(&1.0) != Some(std::cmp::Ordering::Less) {
            return false;
        }
    }
    // 2. The parametric Krawczyk test for the foot.
    let ym = [w[2].mid(), w[3].mid()];
    let z = [w[0], w[1], pt(ym[0]), pt(ym[1])];
    let Some(gz) = r.box_groups(&z) else {
        return false;
    };
    // The x-surface's jet over W_x is `ja` (above); the foot surface's at the point y_m.
    let Some((_, zb)) = r.jets(&gz, &[0; 4], &z) else {
        return false;
    };
    let (gz_direct, jz) = system(&ja, &zb);
    // G₁₂(W_x, y_m): the direct enclosure met with the mean-value form about `x_m`
    // (`G₁₂(x_m, y_m) + J₁₁(W_x, y_m) (W_x − x_m)`); both hold every value.
    let xm = [w[0].mid(), w[1].mid()];
    let zm = [pt(xm[0]), pt(xm[1]), pt(ym[0]), pt(ym[1])];
    let Some(gzm) = r.box_groups(&zm) else {
        return false;
    };
    let Some((ma, mb)) = r.jets(&gzm, &[0; 4], &zm) else {
        return false;
    };
    let (g0, _) = system(&ma, &mb);
    let gm: [I; 2] = std::array::from_fn(|l| {
        let mv = g0[l] + jz[l][0] * (w[0] - pt(xm[0])) + jz[l][1] * (w[1] - pt(xm[1]));
        let (lo, hi) = (mv.lo.max(gz_direct[l].lo), mv.hi.min(gz_direct[l].hi));
        if lo <= hi {
            I::new(lo, hi)
        } else {
            gz_direct[l]
        }
    });
    let Some(c2) = inverse2([
        [jw[0][2].mid(), jw[0][3].mid()],
        [jw[1][2].mid(), jw[1][3].mid()],
    ]) else {
        return false;
    };
    for i in 0..2 {
        let mut k = pt(ym[i]);
        for l in 0..2 {
            k = k - pt(c2[i][l]) * gm[l];
        }
        for col in 0..2 {
            let mut e = pt(if i == col { 1.0 } else { 0.0 });
            for l in 0..2 {
                e = e - pt(c2[i][l]) * jw[l][2 + col];
            }
            k = k + e * (w[2 + col] - pt(ym[col]));
        }
        if !(k.is_finite() && k.lo > w[2 + i].lo && k.hi < w[2 + i].hi) {
            return false;
        }
    }
    true
}

/// Inverse of a real 2 × 2 matrix (an `f64` approximation: it steers, or preconditions a
/// test that holds for any matrix); `None` when singular or not finite.
fn inverse2(m: [[f64; 2]; 2]) -> Option<[[f64; 2]; 2]> {
    let det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
    (det != 0.0 && det.is_finite()).then_some([
        [m[1][1] / det, -m[0][1] / det],
        [-m[1][0] / det, m[0][0] / det],
    ])
}
