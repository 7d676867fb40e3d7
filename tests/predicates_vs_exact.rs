//! Differential tests: every predicate on f64 (adaptive exact, Shewchuk filters) against the
//! same predicate on Rational (f64 inputs lifted exactly), on random, nearly-degenerate,
//! coplanar/collinear and integer-grid inputs. Zero disagreements are allowed.

mod common;
use common::*;
use vericad::geom::Point;
use vericad::predicates::point_in_triangle::{point_in_triangle, point_in_triangle_3d};
use vericad::predicates::segment_plane::segment_plane;
use vericad::predicates::single_sided::single_sided;
use vericad::predicates::tri_tri::{TriTriContact, construct, tri_tri};
use vericad::predicates::{orient2d, orient3d};
use vericad::scalar::{Rational, Scalar};

/// One of four input families, chosen per case.
fn pts2(r: &mut Rng, k: usize) -> [[f64; 2]; 3] {
    match k % 4 {
        0 => [r.p2(10.0), r.p2(10.0), r.p2(10.0)],
        1 => {
            // Nearly collinear: c on the line ab (rounded), then nudged by a few ulps.
            let (a, b) = (r.p2(10.0), r.p2(10.0));
            let t = r.range(-2.0, 3.0);
            let c = [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])];
            [a, b, [r.nudge(c[0], 2), r.nudge(c[1], 2)]]
        }
        2 => {
            // Exactly collinear (integer multiples along an integer direction).
            let a = [r.int(-50, 50) as f64, r.int(-50, 50) as f64];
            let d = [r.int(-5, 5) as f64, r.int(-5, 5) as f64];
            let (s, t) = (r.int(-9, 9) as f64, r.int(-9, 9) as f64);
            [
                a,
                [a[0] + s * d[0], a[1] + s * d[1]],
                [a[0] + t * d[0], a[1] + t * d[1]],
            ]
        }
        _ => [
            [r.int(-3, 3) as f64, r.int(-3, 3) as f64],
            [r.int(-3, 3) as f64, r.int(-3, 3) as f64],
            [r.int(-3, 3) as f64, r.int(-3, 3) as f64],
        ],
    }
}

fn pts3(r: &mut Rng, k: usize) -> [[f64; 3]; 4] {
    match k % 4 {
        0 => [r.p3(10.0), r.p3(10.0), r.p3(10.0), r.p3(10.0)],
        1 => {
            // Nearly coplanar: d = a + s(b-a) + t(c-a), rounded and nudged.
            let (a, b, c) = (r.p3(10.0), r.p3(10.0), r.p3(10.0));
            let (s, t) = (r.range(-1.0, 2.0), r.range(-1.0, 2.0));
            let d: [f64; 3] =
                std::array::from_fn(|i| r.nudge(a[i] + s * (b[i] - a[i]) + t * (c[i] - a[i]), 2));
            [a, b, c, d]
        }
        2 => {
            // Exactly coplanar: integer points in the plane z = 2x - 3y + 1.
            let mut g = || {
                let (x, y) = (r.int(-20, 20) as f64, r.int(-20, 20) as f64);
                [x, y, 2.0 * x - 3.0 * y + 1.0]
            };
            [g(), g(), g(), g()]
        }
        _ => [r.grid3(2), r.grid3(2), r.grid3(2), r.grid3(2)],
    }
}

#[test]
fn orient2d_agrees_with_exact() {
    let mut r = Rng(1);
    let n = cases();
    let mut zeros = 0;
    for k in 0..n {
        let [a, b, c] = pts2(&mut r, k);
        let f = orient2d(&a, &b, &c);
        let e = orient2d(&q2(&a), &q2(&b), &q2(&c));
        assert_eq!(f, e, "case {k}: {a:?} {b:?} {c:?}");
        zeros += (e == vericad::Sign::Zero) as usize;
    }
    // The degenerate families must actually produce degenerate cases.
    assert!(zeros > n / 10, "only {zeros} collinear cases");
}

#[test]
fn orient3d_agrees_with_exact() {
    let mut r = Rng(2);
    let n = cases();
    let mut zeros = 0;
    for k in 0..n {
        let [a, b, c, d] = pts3(&mut r, k);
        let f = orient3d(&a, &b, &c, &d);
        let e = orient3d(&q3(&a), &q3(&b), &q3(&c), &q3(&d));
        assert_eq!(f, e, "case {k}: {a:?} {b:?} {c:?} {d:?}");
        zeros += (e == vericad::Sign::Zero) as usize;
    }
    assert!(zeros > n / 10, "only {zeros} coplanar cases");
}

/// Magnitudes at the edges of the f64 range (huge, tiny, subnormal), where an unguarded
/// floating-point filter would overflow or underflow.
#[test]
fn orientation_at_extreme_magnitudes_agrees_with_exact() {
    let mut r = Rng(9);
    let scales = [1e-310, 1e-250, 1e-160, 1e150, 1e200, 1e300];
    for k in 0..cases() / 5 {
        let s = scales[k % scales.len()];
        let p = |r: &mut Rng| -> [f64; 3] {
            std::array::from_fn(|_| {
                r.int(-3, 3) as f64
                    * s
                    * if r.unit() < 0.5 {
                        1.0
                    } else {
                        1.0 + f64::EPSILON
                    }
            })
        };
        let (a, b, c, d) = (p(&mut r), p(&mut r), p(&mut r), p(&mut r));
        assert_eq!(
            orient3d(&a, &b, &c, &d),
            orient3d(&q3(&a), &q3(&b), &q3(&c), &q3(&d)),
            "case {k}"
        );
        let (a2, b2, c2) = ([a[0], a[1]], [b[0], b[1]], [c[0], c[1]]);
        assert_eq!(
            orient2d(&a2, &b2, &c2),
            orient2d(&q2(&a2), &q2(&b2), &q2(&c2)),
            "case {k}"
        );
    }
}

#[test]
fn segment_plane_and_point_in_triangle_agree_with_exact() {
    let mut r = Rng(3);
    for k in 0..cases() {
        let [a, b, c, d] = pts3(&mut r, k);
        let e = pts3(&mut r, k + 1)[0];
        assert_eq!(
            segment_plane(&d, &e, &a, &b, &c),
            segment_plane(&q3(&d), &q3(&e), &q3(&a), &q3(&b), &q3(&c)),
            "case {k}"
        );
        let [p, s, t] = pts2(&mut r, k);
        let x = if k % 3 == 0 {
            [(p[0] + s[0]) * 0.5, (p[1] + s[1]) * 0.5]
        } else {
            pts2(&mut r, k)[0]
        };
        assert_eq!(
            point_in_triangle(&[p, s, t], &x),
            point_in_triangle(&[q2(&p), q2(&s), q2(&t)], &q2(&x)),
            "case {k}"
        );
        assert_eq!(
            point_in_triangle_3d(&[a, b, c], &d),
            point_in_triangle_3d(&[q3(&a), q3(&b), q3(&c)], &q3(&d)),
            "case {k}"
        );
    }
}

/// Pairs of triangles from the four families, plus pairs sharing a vertex or an edge.
fn tri_pair(r: &mut Rng, k: usize) -> ([[f64; 3]; 3], [[f64; 3]; 3]) {
    let [a0, a1, a2, b0] = pts3(r, k);
    let [b1, b2, x, _] = pts3(r, k + (k / 4) % 4);
    let a = [a0, a1, a2];
    match (k / 16) % 3 {
        0 => (a, [b0, b1, b2]),
        1 => (a, [a0, b1, x]),
        _ => (a, [a1, a0, if k.is_multiple_of(2) { b2 } else { x }]),
    }
}

#[test]
fn tri_tri_agrees_with_exact_and_endpoints_are_certified() {
    let mut r = Rng(4);
    let n = cases();
    let mut crossings = 0;
    let mut kinds = std::collections::BTreeMap::new();
    for k in 0..n {
        let (a, b) = tri_pair(&mut r, k);
        let f = tri_tri(&a, &b);
        let qa = [q3(&a[0]), q3(&a[1]), q3(&a[2])];
        let qb = [q3(&b[0]), q3(&b[1]), q3(&b[2])];
        let e = tri_tri(&qa, &qb);
        assert_eq!(f, e, "case {k}: {a:?} {b:?}");
        *kinds
            .entry(format!("{:?}", std::mem::discriminant(&f)))
            .or_insert(0usize) += 1;
        if let TriTriContact::Crossing(p, q) = f {
            crossings += 1;
            // The exact end point lies in both planes; the f64 one within its bound of it.
            for cp in [p, q] {
                let c = construct(&a, &b, cp);
                let exact = exact_point(&qa, &qb, cp);
                let d: f64 = (0..3)
                    .map(|i| {
                        let x: Rational = vericad::scalar::lift(c.p[i]);
                        vericad::Scalar::to_f64(&vericad::Scalar::abs(&(x - exact[i].clone())))
                    })
                    .sum();
                assert!(
                    d <= c.err * 1.0000001 + f64::MIN_POSITIVE,
                    "case {k}: distance {d} > bound {}",
                    c.err
                );
            }
        }
    }
    assert!(crossings > n / 50, "only {crossings} crossings: {kinds:?}");
    assert!(kinds.len() >= 5, "families too narrow: {kinds:?}");
}

/// Exact end point of a contact, constructed independently in Rational.
fn exact_point(
    a: &[[Rational; 3]; 3],
    b: &[[Rational; 3]; 3],
    cp: vericad::predicates::tri_tri::ContactPoint,
) -> [Rational; 3] {
    use vericad::predicates::tri_tri::ContactPoint::*;
    let seg = |p: &[Rational; 3], q: &[Rational; 3], t: &[[Rational; 3]; 3]| {
        let n = vericad::geom::cross(&t[1].sub(&t[0]), &t[2].sub(&t[0]));
        let op = vericad::geom::dot(&n, &p.sub(&t[0]));
        let oq = vericad::geom::dot(&n, &q.sub(&t[0]));
        p.lerp(q, &(op.clone() / (op - oq)))
    };
    match cp {
        VertexA(i) => a[i as usize].clone(),
        VertexB(j) => b[j as usize].clone(),
        EdgeAPlaneB(i) => seg(&a[i as usize], &a[(i as usize + 1) % 3], b),
        EdgeBPlaneA(j) => seg(&b[j as usize], &b[(j as usize + 1) % 3], a),
    }
}

#[test]
fn tri_tri_is_symmetric() {
    let mut r = Rng(5);
    for k in 0..cases() / 4 {
        let (a, b) = tri_pair(&mut r, k);
        let ab = tri_tri(&a, &b);
        let ba = tri_tri(&b, &a);
        use TriTriContact::*;
        let same_kind = matches!(
            (ab, ba),
            (Disjoint, Disjoint)
                | (TouchPoint(_), TouchPoint(_))
                | (TouchEdge(..), TouchEdge(..))
                | (Crossing(..), Crossing(..))
                | (CoplanarTouch, CoplanarTouch)
                | (CoplanarOverlap, CoplanarOverlap)
                | (Degenerate(0), Degenerate(1))
                | (Degenerate(1), Degenerate(0))
                | (Degenerate(_), Degenerate(_))
        );
        assert!(same_kind, "case {k}: {ab:?} vs {ba:?}");
    }
}

#[test]
fn single_sided_agrees_with_exact() {
    let mut r = Rng(6);
    let n = cases();
    let mut by_roots = 0;
    for k in 0..n {
        let deg = 2 + k % 4;
        let ctrl: Vec<[f64; 2]> = match k % 3 {
            0 => (0..=deg).map(|_| r.p2(5.0)).collect(),
            1 => (0..=deg)
                .map(|_| [r.int(-3, 3) as f64, r.int(-3, 3) as f64])
                .collect(),
            _ => {
                // Control points nearly on the chord: mixed signs decided by root analysis.
                let (a, b) = (r.p2(5.0), r.p2(5.0));
                (0..=deg)
                    .map(|i| {
                        let t = i as f64 / deg as f64;
                        let p = [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])];
                        if i == 0 || i == deg {
                            if i == 0 { a } else { b }
                        } else {
                            [r.nudge(p[0], 3), r.nudge(p[1], 3)]
                        }
                    })
                    .collect()
            }
        };
        let f = single_sided(&ctrl);
        let qc: Vec<[Rational; 2]> = ctrl.iter().map(q2).collect();
        let e = single_sided(&qc);
        assert_eq!(f, e, "case {k}: {ctrl:?}");
        if matches!(
            f,
            vericad::predicates::Sidedness::SingleSided {
                decided_by_hull: false
            } | vericad::predicates::Sidedness::DoubleSided { .. }
        ) {
            by_roots += 1;
        }
    }
    assert!(
        by_roots > n / 20,
        "only {by_roots} cases reached the exact root analysis"
    );
}

/// The point where a segment crosses a triangle's plane, on segments lying in the plane up
/// to rounding (where the interval filter fails and the exact construction runs): the point
/// computed independently in Rational, `a + o_a / (o_a − o_b) · (b − a)`, lies within the
/// returned bound of the returned point, and the bound is a few ulps.
#[test]
fn segment_plane_points_near_the_plane_are_within_their_bound() {
    use vericad::predicates::tri_tri::segment_plane_point;
    let q = |x: f64| Rational::try_from(x).unwrap();
    let mut r = Rng(7);
    let mut exact_runs = 0;
    for k in 0..400 {
        let scale = [1.0, 1e-3, 1e4][k % 3];
        let t: [[f64; 3]; 3] =
            std::array::from_fn(|_| std::array::from_fn(|_| r.range(-1.0, 1.0) * scale));
        let in_plane = |r: &mut Rng| -> [f64; 3] {
            let (al, be) = (r.range(-0.5, 1.0), r.range(-0.5, 1.0));
            std::array::from_fn(|i| t[0][i] + al * (t[1][i] - t[0][i]) + be * (t[2][i] - t[0][i]))
        };
        let (a, b) = (in_plane(&mut r), in_plane(&mut r));
        let c = segment_plane_point(&a, &b, &t);
        let (qa, qb) = (a.map(q), b.map(q));
        let qt = t.map(|p| p.map(q));
        let d = |x: &[Rational; 3], y: &[Rational; 3]| -> [Rational; 3] {
            std::array::from_fn(|i| x[i].clone() - y[i].clone())
        };
        let (u, v) = (d(&qt[1], &qt[0]), d(&qt[2], &qt[0]));
        let n: [Rational; 3] = [
            u[1].clone() * v[2].clone() - u[2].clone() * v[1].clone(),
            u[2].clone() * v[0].clone() - u[0].clone() * v[2].clone(),
            u[0].clone() * v[1].clone() - u[1].clone() * v[0].clone(),
        ];
        let o = |x: &[Rational; 3]| -> Rational {
            let w = d(x, &qt[0]);
            n[0].clone() * w[0].clone() + n[1].clone() * w[1].clone() + n[2].clone() * w[2].clone()
        };
        let (oa, ob) = (o(&qa), o(&qb));
        let den = oa.clone() - ob;
        let exact: [Rational; 3] = if den.is_zero() {
            qa.clone()
        } else {
            std::array::from_fn(|i| {
                qa[i].clone() + oa.clone() / den.clone() * (qb[i].clone() - qa[i].clone())
            })
        };
        let dist2: f64 = (0..3)
            .map(|i| {
                let e = Scalar::to_f64(&(exact[i].clone() - q(c.p[i])));
                e * e
            })
            .sum();
        assert!(
            dist2.sqrt() <= c.err,
            "case {k}: {} > {}",
            dist2.sqrt(),
            c.err
        );
        let mag = c.p.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        assert!(
            c.err <= 8.0 * f64::EPSILON * mag.max(f64::MIN_POSITIVE),
            "case {k}: bound {} at {mag}",
            c.err
        );
        exact_runs += usize::from(c.exact_fallback);
    }
    assert!(exact_runs >= 100, "only {exact_runs} exact constructions");
}
