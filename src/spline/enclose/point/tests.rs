use super::*;
use crate::scalar::{Rational, Scalar, ratio};
use crate::spline::construct::{Frame, sphere, torus};
use crate::spline::exact_point::ExactEvaluator;
use crate::spline::test_params::rng;

/// A random rational surface: degrees 1–5, clamped knots with random interior knots
/// (repeated ones included), control points of magnitude `scale` around an offset, weights
/// from 0.05 to 20.
fn random_surface(r: &mut impl FnMut() -> f64, scale: f64) -> NurbsSurface<f64, 3> {
    let knots = |deg: usize, n: usize, r: &mut dyn FnMut() -> f64| {
        let mut inner: Vec<f64> = (0..n - deg - 1).map(|_| r()).collect();
        if inner.len() >= 2 && deg >= 2 && r() < 0.3 {
            inner[1] = inner[0];
        }
        inner.sort_by(f64::total_cmp);
        let (a, b) = (-1.0 + r(), 2.0 + r());
        let mut k = vec![a; deg + 1];
        k.extend(inner.iter().map(|x| a + x * (b - a)));
        k.extend(vec![b; deg + 1]);
        k
    };
    let (p, q) = (1 + (r() * 5.0) as usize, 1 + (r() * 5.0) as usize);
    let (nu, nv) = (p + 1 + (r() * 4.0) as usize, q + 1 + (r() * 4.0) as usize);
    let ku = knots(p, nu, r);
    let kv = knots(q, nv, r);
    let off = [3.0 * scale, -7.0 * scale, 0.5 * scale];
    let pts: Vec<[f64; 3]> = (0..nu * nv)
        .map(|_| std::array::from_fn(|k| off[k] + scale * (r() - 0.5)))
        .collect();
    let w: Vec<f64> = (0..nu * nv).map(|_| 0.05 + 20.0 * r() * r()).collect();
    NurbsSurface::new(ku, p, kv, q, nu, nv, pts, w).unwrap()
}

fn contains(i: &Interval, x: &Rational) -> bool {
    (i.lo == f64::NEG_INFINITY || Rational::try_from(i.lo).unwrap() <= *x)
        && (i.hi == f64::INFINITY || *x <= Rational::try_from(i.hi).unwrap())
}

/// The enclosure holds the exact value (fraction-free rational evaluation, an independent
/// computation) on random rational surfaces of degrees 1–5 at magnitudes 1e-310 … 1e200, at
/// random parameters, knots and domain ends, and on a sphere and a torus in a rotated frame;
/// and it is narrow: within 1e-12 of the net's largest coordinate.
#[test]
fn point_enclosures_hold_the_exact_point() {
    let mut r = rng(0x5851_f42d_4c95_7f2d);
    let mut surfaces: Vec<NurbsSurface<f64, 3>> = Vec::new();
    for k in 0..72 {
        // 1e-310: subnormal control points, so products fall below the normal range.
        let scale = [1.0, 1e-200, 1e200, 1e-5, 1e8, 1e-310][k % 6];
        surfaces.push(random_surface(&mut r, scale));
    }
    let frame = Frame {
        o: [10.0, -3.0, 0.25],
        x: [0.6, 0.0, 0.8],
        y: [0.0, 1.0, 0.0],
        z: [-0.8, 0.0, 0.6],
    };
    surfaces.push(sphere(&frame, 2.0).unwrap());
    surfaces.push(torus(&frame, 3.0, 0.5).unwrap());
    let mut fast = 0;
    for s in &surfaces {
        let ev = ExactEvaluator::new(s).unwrap();
        for k in 0..40 {
            let (u, v) = crate::spline::test_params::params(s, k, &mut r);
            let Some(e) = enclose_point_f64(s, u, v) else {
                continue;
            };
            fast += 1;
            let x = ev.point(u, v).unwrap();
            let q = x.rational();
            for c in 0..3 {
                let exact = &q[c];
                assert!(contains(&e[c], exact), "({u}, {v}) {c}: {:?}", e[c]);
                // Narrow: relative to the point's scale (the control points' magnitude).
                let m = s
                    .hom
                    .net
                    .iter()
                    .map(|h| h.wp[c].abs() / h.w)
                    .fold(0.0, f64::max);
                assert!(e[c].hi - e[c].lo <= 1e-12 * m + 1e-300, "{:?} vs {m}", e[c]);
            }
        }
    }
    // The fast path applies almost everywhere.
    assert!(fast >= 60 * 40 * 9 / 10, "{fast}");
    // Outside the domain: no claim.
    let s = &surfaces[0];
    let (_, u1, v0, _) = s.hom.domain();
    assert!(enclose_point_f64(s, u1 + 1e-9, v0).is_none());
    assert!(enclose_point_f64(s, f64::NAN, v0).is_none());
}

/// The interval path and the fast path agree: both hold the f64 evaluation's neighbourhood
/// and they overlap (two enclosures of one number).
#[test]
fn fast_and_interval_paths_overlap() {
    let mut r = rng(0x1234_5678_9abc_def1);
    for _ in 0..200 {
        let s = random_surface(&mut r, 1.0);
        let (u0, u1, v0, v1) = s.hom.domain();
        let (u, v) = (u0 + r() * (u1 - u0), v0 + r() * (v1 - v0));
        let (Some(a), Some(b)) = (
            enclose_point_f64(&s, u, v),
            super::super::enclose(&s, Interval::point(u), Interval::point(v), false),
        ) else {
            continue;
        };
        for c in 0..3 {
            assert!(a[c].lo <= b.s[c].hi && b.s[c].lo <= a[c].hi);
        }
    }
}

/// Where the basis functions are exact (parameters 1/2 on a bilinear patch: every weight is
/// 1/4) and the coordinates cancel (0.1 + 0.2 − 0.3 + 0 in binary is 2.8e-17, the f64 sum
/// 5.6e-17), only the rounding term of the bound holds the exact value: one ulp outward of
/// the computed sum would not.
#[test]
fn cancellation_at_exact_basis_values() {
    let s = NurbsSurface::new(
        vec![0.0, 0.0, 1.0, 1.0],
        1,
        vec![0.0, 0.0, 1.0, 1.0],
        1,
        2,
        2,
        vec![
            [0.1, 1.0, -1e-310],
            [0.2, -2.0, 1e-310],
            [-0.3, 1.0 / 3.0, 3e-310],
            [0.0, 2.0 / 3.0, -3e-310],
        ],
        vec![1.0; 4],
    )
    .unwrap();
    let e = enclose_point_f64(&s, 0.5, 0.5).unwrap();
    let x = ExactEvaluator::new(&s).unwrap().point(0.5, 0.5).unwrap();
    let q = x.rational();
    for c in 0..3 {
        let exact = &q[c];
        assert!(contains(&e[c], exact), "{c}: {:?}", e[c]);
    }
    // The x coordinate's computed sum is off by more than an ulp of itself.
    let naive: f64 = 0.5 * (0.5 * 0.1 + 0.5 * 0.2) + 0.5 * (0.5 * -0.3 + 0.5 * 0.0);
    let exact_x = q[0].clone();
    let one_ulp = Interval::new(naive.next_down(), naive.next_up());
    assert!(!contains(&one_ulp, &exact_x));
}

/// Products below the normal range: a biquintic patch at (1/2, 1/2) (basis (1, 5, 10, 10, 5,
/// 1)/32, exact) whose z coordinates are multiples of 2⁻¹⁰⁷⁴ up to 3,838. The f64 sum is
/// 2,013 units of 2⁻¹⁰⁷⁴ where the exact value is 2,009.77 units, off by more than the
/// sum's own one-unit outward rounding; the enclosure holds it (the bound's underflow term,
/// with the quotient's outward rounding, which here alone would also do).
#[test]
fn products_below_the_normal_range() {
    let z: [[i32; 6]; 6] = [
        [2411, 2420, 3799, 2105, 3185, 2209],
        [3786, 683, 2390, 509, 3838, 433],
        [633, 1800, 1432, 2873, 565, 447],
        [1780, 3652, 3484, 1336, 1732, 2978],
        [1734, 1501, 1649, 789, 3564, 2950],
        [3620, 2827, 2490, 148, 2457, 554],
    ];
    let tiny = f64::from_bits(1);
    let pts: Vec<[f64; 3]> = (0..36)
        .map(|k| {
            [
                k as f64,
                (k * k) as f64 / 7.0,
                z[k / 6][k % 6] as f64 * tiny,
            ]
        })
        .collect();
    let knots = vec![0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0];
    let s = NurbsSurface::new(knots.clone(), 5, knots, 5, 6, 6, pts, vec![1.0; 36]).unwrap();
    let e = enclose_point_f64(&s, 0.5, 0.5).unwrap();
    let b = [1, 5, 10, 10, 5, 1];
    let units: i64 = (0..36)
        .map(|k| (b[k / 6] * b[k % 6] * z[k / 6][k % 6]) as i64)
        .sum();
    let exact = ratio(units, 1024) * Rational::try_from(tiny).unwrap();
    assert!(contains(&e[2], &exact), "{:?}", e[2]);
    assert!(e[2].hi - e[2].lo <= 1e-300);
}

/// `N_{i,p}(x)` exactly, from the definition (the triangular recurrence
/// `N_{i,k} = (x − t_i)/(t_{i+k} − t_i) N_{i,k−1} + (t_{i+k+1} − x)/(t_{i+k+1} − t_{i+1}) N_{i+1,k−1}`,
/// terms with a zero knot difference dropped), in rationals.
fn basis_exact(t: &[Rational], span: usize, p: usize, x: &Rational) -> Vec<Rational> {
    let m = t.len() - 1;
    let mut n: Vec<Rational> = (0..m)
        .map(|i| {
            if i == span {
                Rational::ONE
            } else {
                Rational::ZERO
            }
        })
        .collect();
    for k in 1..=p {
        n = (0..m - k)
            .map(|i| {
                let mut v = Rational::ZERO;
                let d1 = &t[i + k] - &t[i];
                if !d1.is_zero() {
                    v += (x - &t[i]) / d1 * &n[i];
                }
                let d2 = &t[i + k + 1] - &t[i + 1];
                if !d2.is_zero() {
                    v += (&t[i + k + 1] - x) / d2 * &n[i + 1];
                }
                v
            })
            .collect();
    }
    n[span - p..=span].to_vec()
}

/// The `f64` basis enclosures hold the exact basis values: random clamped knot vectors of
/// degrees 1–15 (repeated knots, spacings down to 1e-12 of the span) at magnitudes
/// 1e-300 … 1e300, parameters inside spans, at knots and next to them. Where the `f64` run is
/// refused (`None`), the interval recurrence must still enclose. The radius is also tight
/// (within 1e-13 relative).
#[test]
fn basis_f64_encloses_exact_basis() {
    let mut r = rng(0x5eed_ba5e);
    let (mut fast, mut refused) = (0, 0);
    for case in 0..400 {
        let p = 1 + case % 15;
        let scale = 10f64.powi((case as i32 % 61) * 10 - 300);
        let inner = (r() * 5.0) as usize;
        let knots = crate::spline::test_params::clamped_knots(&mut r, p, inner, scale);
        // (At the smallest scales close knots may round together into a multiplicity the
        // degree refuses: such vectors are skipped.)
        let Ok(kv) = KnotVector::new(knots.clone(), p, knots.len() - p - 1) else {
            continue;
        };
        let exact: Vec<Rational> = knots
            .iter()
            .map(|x| Rational::try_from(*x).unwrap())
            .collect();
        for trial in 0..4 {
            let (a, b) = (knots[p], knots[knots.len() - 1 - p]);
            let x = match trial {
                0 => a + r() * (b - a),
                1 => knots[p + (r() * (inner + 1) as f64) as usize],
                2 => knots[p + (r() * (inner + 1) as f64) as usize]
                    .next_up()
                    .min(b),
                _ => b,
            };
            let span = kv.find_span(&x);
            let f64_run = basis_f64(&kv, span, x);
            if f64_run.is_some() {
                fast += 1;
            } else {
                refused += 1;
            }
            let (c, w) = basis(&kv, span, x).unwrap();
            let want = basis_exact(&exact, span, p, &Rational::try_from(x).unwrap());
            for (i, n) in want.iter().enumerate() {
                // The claim, checked exactly: |Ñ − N| ≤ w and 0 ≤ N ≤ Ñ + w.
                let (cr, wr) = (
                    Rational::try_from(c[i]).unwrap(),
                    Rational::try_from(w[i]).unwrap(),
                );
                let off = &cr - n;
                assert!(
                    off <= wr && -off <= wr && *n >= Rational::try_from(0.0).unwrap(),
                    "case {case} trial {trial}: N_{i} = {} not within {} of {}",
                    Scalar::to_f64(n),
                    w[i],
                    c[i]
                );
                let v = Scalar::to_f64(n);
                assert!(
                    f64_run.is_none() || w[i] <= 1e-13 * v.abs(),
                    "case {case}: N_{i} radius {} at {v}",
                    w[i]
                );
            }
        }
    }
    assert!(
        fast > 1300 && refused < fast / 10,
        "{fast} fast, {refused} refused"
    );
}
