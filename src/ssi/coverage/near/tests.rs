use super::*;
use crate::scalar::Interval;

#[test]
fn box_near_a_polyline() {
    let segs: Vec<_> = (0..100)
        .map(|i| ([i as f64, 0.0, 0.0], [i as f64 + 1.0, 0.0, 0.0]))
        .collect();
    let n = Near::new(segs);
    assert!(n.box_within(&([10.2, -0.1, -0.1], [10.4, 0.1, 0.1]), 0.15));
    // Corner distance is sqrt(0.02) = 0.1414..: refused just below it.
    assert!(!n.box_within(&([10.2, -0.1, -0.1], [10.4, 0.1, 0.1]), 0.141));
    // A box spanning a vertex of the polyline: within d of one segment only if it fits.
    assert!(!n.box_within(&([10.5, 2.0, 0.0], [10.6, 2.1, 0.0]), 1.0));
    assert!(!Near::new(Vec::new()).box_within(&([0.0; 3], [0.0; 3]), 1.0));
    assert!(n.box_within(&([0.0; 3], [0.0; 3]), 1e-300));
}

/// Every corner of a box lies within the ball's radius of its centre (exact rationals), for
/// boxes a few ulps wide and wide ones, at magnitudes 1e-300 … 1e300, subnormal widths
/// included; a point box is a ball of radius 0.
#[test]
fn ball_holds_its_box() {
    use crate::scalar::Rational;
    let q = |x: f64| Rational::try_from(x).unwrap();
    let mut r = crate::spline::test_params::rng(0xba11);
    for k in 0..3000 {
        let scale = 10f64.powi((k % 61) * 10 - 300);
        let p: V = std::array::from_fn(|_| {
            let lo = (r() - 0.5) * scale;
            let hi = match k % 3 {
                0 => lo.next_up().next_up(),
                1 => lo + r() * scale,
                _ => lo + f64::from_bits(1 + (r() * 8.0) as u64),
            };
            Interval::new(lo, hi.max(lo))
        });
        let (c, rad) = ball(&p);
        let r2 = q(rad) * q(rad);
        for m in 0..8 {
            let d2 = (0..3).fold(Rational::ZERO, |s, i| {
                let e = if m >> i & 1 == 0 { p[i].lo } else { p[i].hi };
                let v = q(e) - q(c[i]);
                s + &v * &v
            });
            assert!(d2 <= r2, "{p:?}: corner {m} outside radius {rad} of {c:?}");
        }
    }
    let x = [Interval::point(1.5); 3];
    assert_eq!(ball(&x), ([1.5; 3], 0.0));
}

/// Against the exact distance to the segment (rationals: the exact foot, clamped): the
/// bound is never below it, at magnitudes 1e-300 … 1e300, points on, near and far from the
/// segment, degenerate segments included; and it is tight (within 1e-12 relative plus
/// 1e-14 of the coordinates' magnitude).
#[test]
fn dist_upper_is_an_upper_bound() {
    use crate::scalar::Rational;
    let r = |x: f64| Rational::try_from(x).unwrap();
    let mut x = 0x2545_f491_4f6c_dd1du64;
    let mut next = || {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        (x >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    };
    for k in 0..3000 {
        let scale = 10f64.powi((k % 61) * 10 - 300);
        let p = [next() * scale, next() * scale, next() * scale];
        let q = if k % 17 == 0 {
            p
        } else {
            [next() * scale, next() * scale, next() * scale]
        };
        let t = next() + 0.5;
        let off = [0.0, 1e-12, 1e-6, 1.0][k as usize % 4] * scale;
        let c: [f64; 3] = std::array::from_fn(|i| p[i] + t * (q[i] - p[i]) + off * next());
        let u = dist_upper(&c, &p, &q);
        if u.is_infinite() {
            // Only where the squares overflow (no claim).
            assert!(scale > 1e150, "{c:?} {p:?} {q:?}");
            continue;
        }
        let (pr, qr, cr) = (p.map(r), q.map(r), c.map(r));
        let d: Vec<Rational> = (0..3).map(|i| &qr[i] - &pr[i]).collect();
        let e: Vec<Rational> = (0..3).map(|i| &cr[i] - &pr[i]).collect();
        let dd = d.iter().fold(Rational::ZERO, |s, v| s + v * v);
        let ed = (0..3).fold(Rational::ZERO, |s, i| s + &e[i] * &d[i]);
        let tt = if dd.is_zero() {
            Rational::ZERO
        } else {
            (ed / dd).max(Rational::ZERO).min(Rational::ONE)
        };
        let dist2 = (0..3).fold(Rational::ZERO, |s, i| {
            let v = &e[i] - &tt * &d[i];
            s + &v * &v
        });
        let ur = r(u);
        assert!(
            dist2 <= &ur * &ur,
            "{c:?} {p:?} {q:?}: bound {u} below the distance"
        );
        let exact = crate::scalar::Scalar::to_f64(&dist2).sqrt();
        let m = c
            .iter()
            .chain(&p)
            .chain(&q)
            .fold(0.0f64, |m, v| m.max(v.abs()));
        assert!(
            u <= exact * (1.0 + 1e-12) + 1e-14 * m + 1e-159,
            "{u} vs {exact}"
        );
    }
}

/// The tree finds what a scan of every entry finds: polylines on a helix and a circle (an
/// open arc, a closed loop) and a touching point, with chords, queried with small boxes at
/// random along them and with boxes around vertices; the answers agree, and some boxes are
/// decided only by a chord (they straddle a vertex), so chords are in the tree.
#[test]
fn tree_answers_as_a_scan_of_every_entry() {
    let mut r = crate::spline::test_params::rng(0x7ee5);
    let circle = |c: [f64; 3], rad: f64, n: usize, turn: f64| -> Vec<[f64; 3]> {
        (0..=n)
            .map(|i| {
                let t = turn * i as f64 / n as f64;
                [c[0] + rad * t.cos(), c[1] + rad * t.sin(), c[2] + 0.1 * t]
            })
            .collect()
    };
    let mut segs = Vec::new();
    for (pts, closed) in [
        (circle([0.0; 3], 1.0, 2500, 4.0), false),
        (
            circle([3.0, 0.5, -1.0], 0.5, 900, std::f64::consts::TAU),
            true,
        ),
    ] {
        let n = pts.len() - usize::from(closed);
        for k in 0..n {
            segs.push((pts[k], pts[(k + 1) % pts.len()]));
        }
    }
    segs.push(([5.0, 5.0, 5.0], [5.0, 5.0, 5.0]));
    let d = 1e-4;
    let near = Near::with_chords(segs.clone(), d);
    let plain = Near::new(segs.clone());
    assert!(near.segs.len() > segs.len(), "no chord kept");
    let scan =
        |n: &Near, balls: &[Ball]| (0..n.segs.len() as u32).any(|s| n.entry_holds(s, balls, d));
    let mut by_chord_only = 0;
    for k in 0..3000 {
        let s = &segs[(r() * segs.len() as f64) as usize];
        // Around a vertex (half-widths where a cube is within d of a chord but of no
        // segment), or anywhere along a segment.
        let (t, w, off) = if k % 2 == 0 {
            (0.0, d * (0.58 + 0.12 * r()), 0.0)
        } else {
            (
                r(),
                d * [0.01, 0.3, 1.5][k % 3] * r(),
                d * 2.0 * (r() - 0.5),
            )
        };
        let c: [f64; 3] = std::array::from_fn(|i| s.0[i] + t * (s.1[i] - s.0[i]) + off);
        let b: Box3 = (c.map(|x| x - w), c.map(|x| x + w));
        let corners: Vec<Ball> = (0..8)
            .map(|m| {
                (
                    std::array::from_fn(|i| if m >> i & 1 == 0 { b.0[i] } else { b.1[i] }),
                    0.0,
                )
            })
            .collect();
        let tree = near.box_within(&b, d);
        assert_eq!(tree, scan(&near, &corners), "box {b:?}");
        assert_eq!(plain.box_within(&b, d), scan(&plain, &corners), "box {b:?}");
        by_chord_only += usize::from(tree && !scan(&plain, &corners));
    }
    assert!(
        by_chord_only > 100,
        "{by_chord_only} boxes decided by a chord only"
    );
}
