//! Triangle–triangle intersection, classified exactly, with the crossing segment's end
//! points and a rigorous bound on their rounding error.
//!
//! Every decision is a sign of `orient3d` / `orient2d` (adaptive exact on f64), so the
//! classification is the one exact arithmetic would give. No intersection point is
//! constructed to make a decision: a candidate end point is identified *combinatorially*
//! (a vertex of one triangle in the other's plane, or an edge of one triangle crossing the
//! other's plane), which is also the identity the SSI topology deduplicates points by.
//!
//! Membership of a candidate in the other triangle, for an edge `ab` of A crossing plane B
//! at `X`, and an edge `cd` of B: `orient3d(c, d, a, b) = ((d-c)×(X-c))·(b-a)`, so the side
//! of `X` relative to `cd` within plane B is `orient3d(c,d,a,b) · sign(n_B·(b-a))`, and
//! `sign(n_B·(b-a))` is the sign of `b` against plane B. For a vertex lying in plane B the
//! side is a 2D orientation in the projection where B is non-degenerate.
//!
//! Coplanar pairs are classified by the separating-axis test on the projected triangles:
//! closed triangles are disjoint iff the other triangle lies strictly outside the line of
//! some edge; their interiors are disjoint iff it lies in a closed outer half-plane of one.

use super::orient::{dominant_axis, orient2d, orient3d, project};
use crate::scalar::{Interval, Scalar, Sign};

/// A point of the intersection, named by how it arises.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, serde::Serialize)]
pub enum ContactPoint {
    /// Vertex `i` of triangle A, lying in B's plane.
    VertexA(u8),
    /// Vertex `j` of triangle B, lying in A's plane.
    VertexB(u8),
    /// Edge `i` of A (vertex `i` to `i+1 mod 3`) crossing B's plane at an interior point.
    EdgeAPlaneB(u8),
    /// Edge `j` of B crossing A's plane at an interior point.
    EdgeBPlaneA(u8),
}

/// Exact classification of two closed triangles A and B.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
pub enum TriTriContact {
    Disjoint,
    /// Triangle A (`0`) or B (`1`) has collinear vertices.
    Degenerate(u8),
    /// The triangles share exactly one point and do not cross.
    TouchPoint(ContactPoint),
    /// They share a segment lying along an edge of one of them, which touches the other's
    /// plane from one side (or lies in it): a tangential contact.
    TouchEdge(ContactPoint, ContactPoint),
    /// Each triangle has vertices strictly on both sides of the other's plane: they cross
    /// along the segment between the two points.
    Crossing(ContactPoint, ContactPoint),
    /// Coplanar, sharing boundary points only.
    CoplanarTouch,
    /// Coplanar with overlapping interiors.
    CoplanarOverlap,
}

/// Side of each edge of `t` (interior positive) that a point lying in `t`'s plane is on,
/// for a point given as a vertex coplanar with `t`.
fn sides_of_coplanar_vertex<S: Scalar>(
    t: &[[S; 3]; 3],
    axis: (usize, Sign),
    x: &[S; 3],
) -> [Sign; 3] {
    let (k, s) = axis;
    let px = project(x, k);
    std::array::from_fn(|e| {
        orient2d(&project(&t[e], k), &project(&t[(e + 1) % 3], k), &px).times(s)
    })
}

/// Sides for the point where segment `ab` crosses `t`'s plane; `sb` is the sign of `b`
/// against that plane (non-zero).
pub(crate) fn sides_of_crossing<S: Scalar>(
    t: &[[S; 3]; 3],
    a: &[S; 3],
    b: &[S; 3],
    sb: Sign,
) -> [Sign; 3] {
    std::array::from_fn(|e| orient3d(&t[e], &t[(e + 1) % 3], a, b).times(sb))
}

struct Candidate {
    cp: ContactPoint,
    sides: [Sign; 3],
}

fn candidates<S: Scalar>(
    own: &[[S; 3]; 3],
    other: &[[S; 3]; 3],
    other_axis: (usize, Sign),
    s: &[Sign; 3],
    is_a: bool,
) -> Vec<Candidate> {
    let mut out = Vec::with_capacity(2);
    for i in 0..3 {
        if s[i] == Sign::Zero {
            out.push(Candidate {
                cp: if is_a {
                    ContactPoint::VertexA(i as u8)
                } else {
                    ContactPoint::VertexB(i as u8)
                },
                sides: sides_of_coplanar_vertex(other, other_axis, &own[i]),
            });
        }
        let j = (i + 1) % 3;
        if s[i].times(s[j]) == Sign::Negative {
            out.push(Candidate {
                cp: if is_a {
                    ContactPoint::EdgeAPlaneB(i as u8)
                } else {
                    ContactPoint::EdgeBPlaneA(i as u8)
                },
                sides: sides_of_crossing(other, &own[i], &own[j], s[j]),
            });
        }
    }
    out
}

fn inside(s: &[Sign; 3]) -> bool {
    !s.contains(&Sign::Negative)
}

/// Whether candidate `x` (of one triangle, with its sides against the other triangle T)
/// is the same point as `y` (a feature of T crossing or lying in the first's plane).
fn coincide(x_sides: &[Sign; 3], y: ContactPoint) -> bool {
    match y {
        ContactPoint::VertexA(k) | ContactPoint::VertexB(k) => {
            // At vertex k of T: on the lines of edges k-1 and k.
            let k = k as usize;
            x_sides[k] == Sign::Zero && x_sides[(k + 2) % 3] == Sign::Zero
        }
        ContactPoint::EdgeAPlaneB(k) | ContactPoint::EdgeBPlaneA(k) => {
            x_sides[k as usize] == Sign::Zero
        }
    }
}

/// Classify the intersection of triangles `a` and `b` exactly.
pub fn tri_tri<S: Scalar>(a: &[[S; 3]; 3], b: &[[S; 3]; 3]) -> TriTriContact {
    let Some(axis_a) = dominant_axis(a) else {
        return TriTriContact::Degenerate(0);
    };
    let Some(axis_b) = dominant_axis(b) else {
        return TriTriContact::Degenerate(1);
    };
    let sa: [Sign; 3] = std::array::from_fn(|i| orient3d(&b[0], &b[1], &b[2], &a[i]));
    if sa[0] != Sign::Zero && sa[0] == sa[1] && sa[1] == sa[2] {
        return TriTriContact::Disjoint;
    }
    if sa.iter().all(|s| *s == Sign::Zero) {
        return coplanar(a, b, axis_a.0);
    }
    let sb: [Sign; 3] = std::array::from_fn(|j| orient3d(&a[0], &a[1], &a[2], &b[j]));
    if sb[0] != Sign::Zero && sb[0] == sb[1] && sb[1] == sb[2] {
        return TriTriContact::Disjoint;
    }
    let ca = candidates(a, b, axis_b, &sa, true);
    let cb = candidates(b, a, axis_a, &sb, false);
    let mut pts: Vec<ContactPoint> = Vec::with_capacity(2);
    let a_in: Vec<&Candidate> = ca.iter().filter(|c| inside(&c.sides)).collect();
    for c in &a_in {
        pts.push(c.cp);
    }
    for y in cb.iter().filter(|c| inside(&c.sides)) {
        if !a_in.iter().any(|x| coincide(&x.sides, y.cp)) {
            pts.push(y.cp);
        }
    }
    let straddles = |s: &[Sign; 3]| s.contains(&Sign::Positive) && s.contains(&Sign::Negative);
    match pts.as_slice() {
        [] => TriTriContact::Disjoint,
        [p] => TriTriContact::TouchPoint(*p),
        [p, q] => {
            if straddles(&sa) && straddles(&sb) {
                TriTriContact::Crossing(*p, *q)
            } else {
                TriTriContact::TouchEdge(*p, *q)
            }
        }
        // Impossible for non-degenerate triangles (every candidate in the other triangle is
        // an end point of the common segment); kept total rather than panicking.
        [p, .., q] => TriTriContact::TouchEdge(*p, *q),
    }
}

fn coplanar<S: Scalar>(a: &[[S; 3]; 3], b: &[[S; 3]; 3], k: usize) -> TriTriContact {
    let mut pa: [[S; 2]; 3] = std::array::from_fn(|i| project(&a[i], k));
    let mut pb: [[S; 2]; 3] = std::array::from_fn(|i| project(&b[i], k));
    // Orient both counter-clockwise in the projection. B is non-degenerate in 3D and
    // coplanar with A, whose projection along k is non-degenerate, so B's is too.
    if orient2d(&pa[0], &pa[1], &pa[2]) == Sign::Negative {
        pa.swap(1, 2);
    }
    if orient2d(&pb[0], &pb[1], &pb[2]) == Sign::Negative {
        pb.swap(1, 2);
    }
    let mut weak = false;
    for (t, o) in [(&pa, &pb), (&pb, &pa)] {
        for e in 0..3 {
            let s: [Sign; 3] = std::array::from_fn(|v| orient2d(&t[e], &t[(e + 1) % 3], &o[v]));
            if s.iter().all(|x| *x == Sign::Negative) {
                return TriTriContact::Disjoint;
            }
            if s.iter().all(|x| *x != Sign::Positive) {
                weak = true;
            }
        }
    }
    if weak {
        TriTriContact::CoplanarTouch
    } else {
        TriTriContact::CoplanarOverlap
    }
}

/// A constructed point with a rigorous bound on its distance to the exact point.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct ConstructedPoint {
    pub p: [f64; 3],
    /// `|p - exact| <= err` (Euclidean), proven: by outward-rounded interval arithmetic, or by
    /// exact rational construction followed by rounding when the intervals were too wide.
    pub err: f64,
    /// Whether the exact rational fallback was needed.
    pub exact_fallback: bool,
}

fn iv(p: &[f64; 3]) -> [Interval; 3] {
    std::array::from_fn(|i| Interval::point(p[i]))
}

fn orient_iv(
    p: &[Interval; 3],
    q: &[Interval; 3],
    r: &[Interval; 3],
    x: &[Interval; 3],
) -> Interval {
    let u: [Interval; 3] = std::array::from_fn(|i| q[i] - p[i]);
    let v: [Interval; 3] = std::array::from_fn(|i| r[i] - p[i]);
    let w: [Interval; 3] = std::array::from_fn(|i| x[i] - p[i]);
    u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0])
        + u[2] * (v[0] * w[1] - v[1] * w[0])
}

/// Point where segment `ab` crosses the plane of `t`: `a + s (b - a)`,
/// `s = o_a / (o_a - o_b)` with `o_x = det[t1-t0, t2-t0, x-t0]`.
pub fn segment_plane_point(a: &[f64; 3], b: &[f64; 3], t: &[[f64; 3]; 3]) -> ConstructedPoint {
    let (ia, ib) = (iv(a), iv(b));
    let it = [iv(&t[0]), iv(&t[1]), iv(&t[2])];
    let oa = orient_iv(&it[0], &it[1], &it[2], &ia);
    let ob = orient_iv(&it[0], &it[1], &it[2], &ib);
    if let Some(s) = oa.checked_div(oa - ob) {
        let p: [Interval; 3] = std::array::from_fn(|i| ia[i] + s * (ib[i] - ia[i]));
        if p.iter().all(|x| x.is_finite()) {
            let err = p
                .iter()
                .map(|x| x.radius_about_mid())
                .fold(0.0, |acc: f64, r| (acc + r).next_up());
            // Keep the bound honest only when it is small relative to the segment.
            let len = (0..3).map(|i| (b[i] - a[i]).abs()).fold(0.0, f64::max);
            if err <= len * 1e-6 || err == 0.0 {
                return ConstructedPoint {
                    p: std::array::from_fn(|i| p[i].mid()),
                    err,
                    exact_fallback: false,
                };
            }
        }
    }
    exact_segment_plane_point(a, b, t)
}

/// [`segment_plane_point`] in exact arithmetic: every coordinate is an integer times
/// `2^e` for the smallest exponent `e` among them, so the orientations `o_a`, `o_b` and the
/// numerators `a_i (o_a − o_b) + (b_i − a_i) o_a` are exact big integers (no fraction is
/// reduced on the way); each coordinate is then the quotient by `o_a − o_b` rounded to f64,
/// with its rounding error bounded from the exact remainder (the remainder's quotient, rounded
/// to nearest by the exact rational's conversion, then one ulp up).
fn exact_segment_plane_point(a: &[f64; 3], b: &[f64; 3], t: &[[f64; 3]; 3]) -> ConstructedPoint {
    use crate::scalar::{BigInt, Rational};
    use dashu_int::ops::{Abs, UnsignedAbs};
    let all = [a, b, &t[0], &t[1], &t[2]];
    let e0 = all
        .iter()
        .flat_map(|p| p.iter())
        .filter(|x| **x != 0.0)
        .map(|x| integer_decode(*x).1)
        .min()
        .unwrap_or(0);
    let big = |x: f64| -> BigInt {
        let (m, e, sign) = integer_decode(x);
        if m == 0 {
            return BigInt::ZERO;
        }
        let v = BigInt::from(m) << ((e - e0) as usize);
        if sign < 0 { -v } else { v }
    };
    let q = |p: &[f64; 3]| -> [BigInt; 3] { [big(p[0]), big(p[1]), big(p[2])] };
    let (qa, qb) = (q(a), q(b));
    let qt = [q(&t[0]), q(&t[1]), q(&t[2])];
    let sub = |x: &[BigInt; 3], y: &[BigInt; 3]| -> [BigInt; 3] {
        [&x[0] - &y[0], &x[1] - &y[1], &x[2] - &y[2]]
    };
    let (u, v) = (sub(&qt[1], &qt[0]), sub(&qt[2], &qt[0]));
    let n = [
        &u[1] * &v[2] - &u[2] * &v[1],
        &u[2] * &v[0] - &u[0] * &v[2],
        &u[0] * &v[1] - &u[1] * &v[0],
    ];
    let dot = |x: &[BigInt; 3]| -> BigInt { &n[0] * &x[0] + &n[1] * &x[1] + &n[2] * &x[2] };
    let oa = dot(&sub(&qa, &qt[0]));
    let ob = dot(&sub(&qb, &qt[0]));
    let mut den = &oa - &ob;
    if den.is_zero() {
        return ConstructedPoint {
            p: *a,
            err: 0.0,
            exact_fallback: true,
        };
    }
    let flip = den < BigInt::ZERO;
    let oa = if flip { -oa } else { oa };
    if flip {
        den = -den;
    }
    let mut p = [0.0; 3];
    let mut err = 0.0f64;
    for i in 0..3 {
        // exact_i = num / den · 2^e0.
        let mut num: BigInt = &qa[i] * &den + (&qb[i] - &qa[i]) * &oa;
        let mut d = den.clone();
        if e0 >= 0 {
            num <<= e0 as usize;
        } else {
            d <<= (-e0) as usize;
        }
        // `d > 0`: the quotient rounded to nearest (±inf beyond the range).
        let x = Scalar::to_f64(&Rational::from_parts(num.clone(), (&d).unsigned_abs()));
        p[i] = x;
        if !x.is_finite() {
            err = f64::INFINITY;
            continue;
        }
        // |exact - x| = |num - X·2^k·d| / d with x = X·2^k; both sides to the power 2^s.
        let (m, k, sign) = integer_decode(x);
        let xm = if sign < 0 {
            -BigInt::from(m)
        } else {
            BigInt::from(m)
        };
        let s = k.min(0);
        let lhs = num << ((-s) as usize);
        let rhs = (xm * &d) << ((k - s) as usize);
        let rem = (lhs - rhs).abs();
        let d2 = d << ((-s) as usize);
        let r = Scalar::to_f64(&Rational::from_parts(rem, d2.unsigned_abs()));
        err = (err + r.next_up()).next_up();
    }
    ConstructedPoint {
        p,
        err,
        exact_fallback: true,
    }
}

/// `x = sign · m · 2^e` for a finite `x`, with the significand `m` as an integer (subnormals
/// as `m · 2^-1075` with `m` even; `m = 0` for zero).
fn integer_decode(x: f64) -> (u64, i16, i8) {
    let bits = x.to_bits();
    let sign: i8 = if bits >> 63 == 0 { 1 } else { -1 };
    let exp = ((bits >> 52) & 0x7ff) as i16;
    let frac = bits & ((1u64 << 52) - 1);
    let m = if exp == 0 {
        frac << 1
    } else {
        frac | (1u64 << 52)
    };
    (m, exp - 1075, sign)
}

/// Coordinates of a contact point of `tri_tri(a, b)` with a rigorous error bound.
pub fn construct(a: &[[f64; 3]; 3], b: &[[f64; 3]; 3], cp: ContactPoint) -> ConstructedPoint {
    let exact = |p: [f64; 3]| ConstructedPoint {
        p,
        err: 0.0,
        exact_fallback: false,
    };
    match cp {
        ContactPoint::VertexA(i) => exact(a[i as usize]),
        ContactPoint::VertexB(j) => exact(b[j as usize]),
        ContactPoint::EdgeAPlaneB(i) => {
            let i = i as usize;
            segment_plane_point(&a[i], &a[(i + 1) % 3], b)
        }
        ContactPoint::EdgeBPlaneA(j) => {
            let j = j as usize;
            segment_plane_point(&b[j], &b[(j + 1) % 3], a)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const A: [[f64; 3]; 3] = [[0., 0., 0.], [4., 0., 0.], [0., 4., 0.]];

    #[test]
    fn configurations() {
        // B pierces A's interior: crossing.
        let b = [[1., 1., -1.], [1., 1., 1.], [2., 1., 1.]];
        assert!(matches!(tri_tri(&A, &b), TriTriContact::Crossing(..)));
        // Far away.
        let far = [[10., 10., 1.], [11., 10., 1.], [10., 11., 2.]];
        assert_eq!(tri_tri(&A, &far), TriTriContact::Disjoint);
        // Vertex of B touching A's interior from above.
        let v = [[1., 1., 0.], [1., 2., 1.], [2., 1., 1.]];
        assert_eq!(
            tri_tri(&A, &v),
            TriTriContact::TouchPoint(ContactPoint::VertexB(0))
        );
        // Edge of B lying in A, B above: touching along an edge.
        let e = [[1., 1., 0.], [2., 1., 0.], [1., 1., 1.]];
        assert!(matches!(tri_tri(&A, &e), TriTriContact::TouchEdge(..)));
        // Coplanar overlap, touch, disjoint.
        assert_eq!(
            tri_tri(&A, &[[1., 1., 0.], [5., 1., 0.], [1., 5., 0.]]),
            TriTriContact::CoplanarOverlap
        );
        assert_eq!(tri_tri(&A, &A), TriTriContact::CoplanarOverlap);
        assert_eq!(
            tri_tri(&A, &[[4., 0., 0.], [8., 0., 0.], [4., 4., 0.]]),
            TriTriContact::CoplanarTouch
        );
        assert_eq!(
            tri_tri(&A, &[[5., 0., 0.], [8., 0., 0.], [5., 4., 0.]]),
            TriTriContact::Disjoint
        );
        // Shared edge, hinged (not coplanar): touch along the edge.
        let h = [[0., 0., 0.], [4., 0., 0.], [0., 0., 4.]];
        assert!(matches!(tri_tri(&A, &h), TriTriContact::TouchEdge(..)));
        // Degenerate.
        assert_eq!(
            tri_tri(&A, &[[0., 0., 0.], [1., 1., 1.], [2., 2., 2.]]),
            TriTriContact::Degenerate(1)
        );
        // B straddles A's plane and meets A along A's edge y = 0, which lies in B's plane:
        // A touches B there (A is on one side of B's plane).
        let c = [[2., 0., 0.], [2., -1., 1.], [3., 1., -1.]];
        assert_eq!(
            tri_tri(&A, &c),
            TriTriContact::TouchEdge(ContactPoint::VertexB(0), ContactPoint::EdgeBPlaneA(1))
        );
    }

    #[test]
    fn constructed_endpoints_are_within_their_bounds() {
        let b = [[1., 1., -1.], [1.1, 1.3, 1.], [2.7, 0.9, 0.7]];
        if let TriTriContact::Crossing(p, q) = tri_tri(&A, &b) {
            for cp in [p, q] {
                let c = construct(&A, &b, cp);
                assert!(c.err < 1e-14, "{c:?}");
                // The point lies (within err) in A's plane z = 0.
                assert!(c.p[2].abs() <= c.err);
            }
        } else {
            panic!("expected a crossing");
        }
    }
}
