//! A proven bound on the chordal deviation of a triangle: how far the flat triangle with
//! corners `V_0, V_1, V_2` (mesh points) lies from the surface over its parameter triangle
//! `T = (q_0, q_1, q_2)`.
//!
//! **Theorem.** Let `S` be C² on the convex parameter triangle `T`, and
//! `M ≥ sup_{x ∈ T} (max(‖S_uu(x)‖, ‖S_vv(x)‖) + ‖S_uv(x)‖)`. For `x = Σ λ_i q_i ∈ T`
//! (barycentric), the mesh point `P(x) = Σ λ_i V_i` satisfies
//!
//! `‖P(x) − S(x)‖ ≤ max_i ‖V_i − S(q_i)‖ + ½ M r²`,
//!
//! with `r` the radius of the smallest disc holding `T` (in the parameter plane). So every
//! point of the flat triangle lies within that bound of the surface, and every point of the
//! surface over `T` within it of the triangle: a two-sided (Hausdorff) bound between the mesh
//! and the surface over the union of the parameter triangles.
//!
//! *Proof.* `‖P(x) − L(x)‖ ≤ max_i ‖V_i − S(q_i)‖` for the linear interpolant
//! `L(x) = Σ λ_i S(q_i)` (a convex combination). Since `Σ λ_i (q_i − x) = 0`,
//! `L(x) − S(x) = Σ λ_i (S(q_i) − S(x) − DS(x)(q_i − x)) = Σ λ_i ∫₀¹ (1 − s) D²S(x + s(q_i − x))(q_i − x, q_i − x) ds`
//! (Taylor with integral remainder along segments inside the convex `T`). For a unit vector
//! `w`, `‖D²S(w, w)‖ = ‖S_uu w_u² + 2 S_uv w_u w_v + S_vv w_v²‖ ≤ max(‖S_uu‖, ‖S_vv‖) + ‖S_uv‖`
//! (`2|w_u w_v| ≤ 1`), so `‖L(x) − S(x)‖ ≤ ½ M Σ λ_i |q_i − x|²`, and for any centre `c`,
//! `Σ λ_i |q_i − x|² = Σ λ_i |q_i − c|² − |x − c|² ≤ max_i |q_i − c|²`; with `c` the centre of
//! the smallest disc holding the corners this is `r²` (Waldron 1998 gives the same constant).
//!
//! **Splitting.** `P` is affine in the parameters, so over each of the four midpoint
//! triangles of `T` it is the affine map with the midpoints of the `V_i` at the midpoints of
//! the `q_i`: the theorem applies to each part with those corners (their gaps to the surface
//! enclosed again, `M` and `r` of the part), and the triangle's bound is the largest of its
//! parts' (or its own, if smaller). Parts are split while their bound is above a goal (twice
//! the measured deviation), at most [`MAX_SPLITS`] levels: the curvature term falls by four
//! per level, toward the largest gap at the corners.
//!
//! **Computed rigorously**: `M` from outward-rounded enclosures of the second derivatives over
//! the parameter box of `T` ([`crate::spline::enclose2`]: interval Cox–de Boor and the
//! rational quotient rule); `S(q_i)` enclosed at the corner and `‖V_i − S(q_i)‖` bounded
//! above from the enclosure; `r²` and the final sum rounded up; the parts' corners (midpoints)
//! carried as interval boxes holding the exact midpoints.
//!
//! **Knot lines.** Where a knot line of multiplicity at least the degree − 1 (the surface not
//! C² across it; in a closed direction also one period away) crosses a part's box, the part is
//! cut along it into two convex polygons, fanned into triangles: the crossing points of its
//! edges are enclosed in intervals (on the line exactly in its direction), `P` at them by the
//! same interpolation, and each piece is bounded with the surface's function on its side (at
//! most [`MAX_CUTS`] cuts a triangle). A triangle gets no bound (counted) where a corner's box
//! straddles such a line, past the cuts, where a box leaves the domain in a direction that is
//! not closed, where an enclosure fails (a weight not proven positive), and every triangle of
//! a face (or surface) meshed into more than [`MAX_TRIANGLES`].

use crate::scalar::Interval;
use crate::spline::NurbsSurface;
use crate::spline::enclose2::{Piece, group_jet, groups, restrict};

type I = Interval;

fn pt(x: f64) -> I {
    Interval::point(x)
}

/// The surface with what the bound needs: its domain and which directions are closed (a
/// parameter there runs on across the seam into the next period).
pub struct BoundSurface<'a> {
    pub s: &'a NurbsSurface<f64, 3>,
    /// `[u0, u1, v0, v1]`.
    pub domain: [f64; 4],
    pub periodic: [bool; 2],
}

/// The one C² group of each direction over the box `[u] × [v]`, if the surface is C² there
/// and the box stays in the domain where the direction is not closed.
fn group(bs: &BoundSurface, u: I, v: I) -> Grouped {
    let h = &bs.s.hom;
    for (d, x) in [u, v].into_iter().enumerate() {
        let (lo, hi) = (bs.domain[2 * d], bs.domain[2 * d + 1]);
        if !bs.periodic[d] && (x.lo < lo || x.hi > hi) {
            return Grouped::Refused;
        }
    }
    let (Some(mut gu), Some(mut gv)) = (
        groups(&h.ku, u, bs.periodic[0]),
        groups(&h.kv, v, bs.periodic[1]),
    ) else {
        return Grouped::Refused;
    };
    // A knot line where the surface is not C² crosses the box: the knot (first span of the
    // second group).
    for (d, g, k) in [(0, &gu, &h.ku), (1, &gv, &h.kv)] {
        if g.len() > 1 {
            return match g[1].first() {
                // One period away in a closed direction: the knot plus the offset, when that
                // sum is exact (Knuth's TwoSum error zero).
                Some(&(span, _, o)) => {
                    let t = k.knots()[span];
                    let s = t + o;
                    let bb = s - t;
                    if (t - (s - bb)) + (o - bb) == 0.0 && s.is_finite() {
                        Grouped::Cut(d, s)
                    } else {
                        Grouped::Refused
                    }
                }
                None => Grouped::Refused,
            };
        }
    }
    match (gu.pop(), gv.pop()) {
        (Some(a), Some(b)) => Grouped::One(a, b),
        _ => Grouped::Refused,
    }
}

/// The C² groups over a box: one in each direction, or a knot line to cut at, or none.
enum Grouped {
    One(Vec<Piece>, Vec<Piece>),
    /// Direction and knot value of a line where the surface is not C².
    Cut(usize, f64),
    Refused,
}

/// The corners of `q` (values `v`) on each side of the line `x_d = k`, with the points where
/// the triangle's edges cross it, as convex polygons (left, right); `None` where a corner's
/// box straddles the line without lying on it.
type Poly = Vec<([I; 3], [I; 2])>;
fn cut(v: &[[I; 3]; 3], q: &[[I; 2]; 3], d: usize, k: f64) -> Option<(Poly, Poly)> {
    let side = |x: I| {
        if x.hi < k {
            Some(-1)
        } else if x.lo > k {
            Some(1)
        } else if x.lo == k && x.hi == k {
            Some(0)
        } else {
            None
        }
    };
    let s: Vec<i8> = q.iter().map(|p| side(p[d])).collect::<Option<_>>()?;
    let (mut left, mut right) = (Vec::new(), Vec::new());
    for i in 0..3 {
        let j = (i + 1) % 3;
        let here = (v[i], q[i]);
        if s[i] <= 0 {
            left.push(here);
        }
        if s[i] >= 0 {
            right.push(here);
        }
        if s[i] * s[j] < 0 {
            // The crossing point of edge i → j: t = (k − q_i) / (q_j − q_i), enclosed; on the
            // line exactly in direction d.
            let t = (pt(k) - q[i][d]).checked_div(q[j][d] - q[i][d])?;
            let t = I::new(t.lo.max(0.0), t.hi.min(1.0));
            let x: [I; 2] = std::array::from_fn(|c| {
                if c == d {
                    pt(k)
                } else {
                    q[i][c] + t * (q[j][c] - q[i][c])
                }
            });
            let p: [I; 3] = std::array::from_fn(|c| v[i][c] + t * (v[j][c] - v[i][c]));
            left.push((p, x));
            right.push((p, x));
        }
    }
    Some((left, right))
}

/// Cuts at knot lines allowed per triangle (each adds at most three parts).
pub const MAX_CUTS: u32 = 4;

/// Squared distance between two parameter points (intervals), enclosed.
fn d2(a: &[I; 2], b: &[I; 2]) -> I {
    let (x, y) = (a[0] - b[0], a[1] - b[1]);
    x * x + y * y
}

/// An upper bound of `r²`, `r` the radius of a disc holding the three parameter points
/// (each known to lie in its interval box): half the longest side where the angle opposite it
/// is proven right or obtuse, else the smaller of the circumradius and the largest distance
/// from the centroid (any disc holding the corners serves the theorem).
fn enclosing_radius_sq(q: &[[I; 2]; 3]) -> Option<f64> {
    // Sides squared, opposite each corner.
    let s = [d2(&q[1], &q[2]), d2(&q[0], &q[2]), d2(&q[0], &q[1])];
    let (k, longest) = (0..3)
        .map(|k| (k, s[k]))
        .fold((0, s[0]), |b, x| if x.1.hi > b.1.hi { x } else { b });
    let (a, b) = (s[(k + 1) % 3], s[(k + 2) % 3]);
    if (a + b - longest).hi <= 0.0 {
        return Some((longest * pt(0.25)).hi);
    }
    let third = pt(1.0 / 3.0);
    let c = [
        (q[0][0] + q[1][0] + q[2][0]) * third,
        (q[0][1] + q[1][1] + q[2][1]) * third,
    ];
    // The centroid's box: the distance to it is bounded over the whole box (the theorem's
    // centre may be any point, so the exact centroid, inside the box, serves).
    let centroid = q.iter().map(|p| d2(p, &c).hi).fold(0.0, f64::max);
    // Circumradius² = x y z / (16 area²) in squared sides, 16 area² by Heron's formula.
    let (x, y, z) = (s[0], s[1], s[2]);
    let area16 = pt(2.0) * (x * y + y * z + z * x) - (x * x + y * y + z * z);
    let circum = (x * y * z)
        .checked_div(area16)
        .map_or(f64::INFINITY, |r| r.hi);
    let r2 = if area16.lo > 0.0 {
        circum.min(centroid)
    } else {
        centroid
    };
    r2.is_finite().then_some(r2)
}

/// Levels of splitting a triangle into its four midpoint triangles where its bound is above
/// the goal.
pub const MAX_SPLITS: u32 = 3;

/// The bound of the piece of the flat triangle over the parameter triangle `q` (corners in
/// interval boxes) whose flat corners are `v` (enclosed), split into four where it is above
/// `goal` (see the module comment: the flat triangle is affine in the parameters, so its
/// points over the midpoint triangles have the midpoints of `v` as corners).
fn piece_bound(
    bs: &BoundSurface,
    v: &[[I; 3]; 3],
    q: &[[I; 2]; 3],
    goal: f64,
    depth: u32,
    cuts: u32,
    gaps: &mut Gaps,
) -> Option<f64> {
    let lo = |d: usize| q.iter().map(|p| p[d].lo).fold(f64::INFINITY, f64::min);
    let hi = |d: usize| q.iter().map(|p| p[d].hi).fold(f64::NEG_INFINITY, f64::max);
    let (gu, gv) = match group(bs, I::new(lo(0), hi(0)), I::new(lo(1), hi(1))) {
        Grouped::One(a, b) => (a, b),
        Grouped::Refused => return None,
        Grouped::Cut(d, k) => {
            // The surface is C² on each side: the triangle cut there into convex polygons,
            // each fanned into triangles (P stays affine on them).
            if cuts == 0 {
                return None;
            }
            let (l, r) = cut(v, q, d, k)?;
            let mut worst = 0.0f64;
            for poly in [l, r] {
                for i in 1..poly.len().saturating_sub(1) {
                    let pv = [poly[0].0, poly[i].0, poly[i + 1].0];
                    let pq = [poly[0].1, poly[i].1, poly[i + 1].1];
                    let b = piece_bound(bs, &pv, &pq, goal, depth, cuts - 1, gaps)?;
                    worst = worst.max(b);
                }
            }
            return Some(worst);
        }
    };
    let j = group_jet(bs.s, &gu, &gv)?;
    let m = pt(I::norm_hi(&j.suu).max(I::norm_hi(&j.svv))) + pt(I::norm_hi(&j.suv));
    let r2 = enclosing_radius_sq(q)?;
    let mut corner = 0.0f64;
    for (vi, qi) in v.iter().zip(q) {
        // A mesh vertex at a parameter point: its gap is the same in every triangle using it.
        let key = (vi.iter().chain(qi).all(|x| x.lo == x.hi))
            .then(|| [vi[0].lo, vi[1].lo, vi[2].lo, qi[0].lo, qi[1].lo].map(f64::to_bits));
        if let Some(g) = key.and_then(|k| gaps.get(&k)) {
            corner = corner.max(*g);
            continue;
        }
        // The group's function at the corner is the surface's there (continuous), also on a
        // knot line at the box's border.
        let s = group_jet(bs.s, &restrict(&gu, qi[0]), &restrict(&gv, qi[1]))?.s;
        let gap: [I; 3] = std::array::from_fn(|k| vi[k] - s[k]);
        let g = I::norm_hi(&gap);
        if let Some(k) = key {
            gaps.insert(k, g);
        }
        corner = corner.max(g);
    }
    let b = (pt(corner) + pt(0.5) * m * pt(r2)).hi;
    if !b.is_finite() {
        return None;
    }
    if b <= goal || depth == 0 {
        return Some(b);
    }
    let half = pt(0.5);
    let mv = |i: usize, k: usize| -> [I; 3] { std::array::from_fn(|c| (v[i][c] + v[k][c]) * half) };
    let mq = |i: usize, k: usize| -> [I; 2] { std::array::from_fn(|c| (q[i][c] + q[k][c]) * half) };
    let (v01, v12, v02) = (mv(0, 1), mv(1, 2), mv(0, 2));
    let (q01, q12, q02) = (mq(0, 1), mq(1, 2), mq(0, 2));
    let parts = [
        ([v[0], v01, v02], [q[0], q01, q02]),
        ([v01, v[1], v12], [q01, q[1], q12]),
        ([v02, v12, v[2]], [q02, q12, q[2]]),
        ([v01, v12, v02], [q01, q12, q02]),
    ];
    let mut worst = 0.0f64;
    for (pv, pq) in &parts {
        worst = worst.max(piece_bound(bs, pv, pq, goal, depth - 1, cuts, gaps)?);
    }
    Some(worst.min(b))
}

/// The proven bound of one triangle with mesh corners `v` over the parameter triangle `q`
/// (see the module comment), its parameter triangle split into midpoint triangles (at most
/// [`MAX_SPLITS`] levels) while the bound of a part is above `goal`; `None` where no bound is
/// given.
pub fn triangle_bound(
    bs: &BoundSurface,
    v: &[[f64; 3]; 3],
    q: &[[f64; 2]; 3],
    goal: f64,
    gaps: &mut Gaps,
) -> Option<f64> {
    let (v, q) = (v.map(|p| p.map(pt)), q.map(|p| p.map(pt)));
    piece_bound(bs, &v, &q, goal, MAX_SPLITS, MAX_CUTS, gaps)
}

/// Proven gaps between mesh vertices and the surface at their parameters, by the bits of the
/// vertex and the parameters.
pub type Gaps = std::collections::HashMap<[u64; 5], f64>;

/// A face (or surface) meshed into more triangles than this gets no proven bound (its cost, several interval
/// evaluations per triangle, would pass the meshing's own many times).
pub const MAX_TRIANGLES: usize = 200_000;

/// The largest proven bound over triangles with corners `v` and parameter corners `q` (each
/// split while above `goal`, see [`triangle_bound`]), and how many triangles got none.
pub fn mesh_bound(
    bs: &BoundSurface,
    corners: impl Iterator<Item = [[f64; 3]; 3]>,
    q: &[[[f64; 2]; 3]],
    goal: f64,
) -> (f64, usize) {
    if q.len() > MAX_TRIANGLES {
        return (0.0, q.len());
    }
    let mut gaps = Gaps::new();
    corners.zip(q).fold((0.0, 0), |(b, n), (v, q)| {
        match triangle_bound(bs, &v, q, goal, &mut gaps) {
            Some(x) => (b.max(x), n),
            None => (b, n + 1),
        }
    })
}
