//! Harnesses of the curve-on-surface certificate's exact kernels: the point-to-segment
//! distance of the Hausdorff bound, the single-sided classification of cubic pieces and
//! Yang et al.'s Theorem 1 on which the polyline bound rests, and knot-span location.

use vericad::predicates::single_sided::{Sidedness, single_sided};
use vericad::spline::KnotVector;

// ---------------------------------------------------------------- single-sided cubic

/// Yang et al. §3 closed form for cubics: with `b_i = (P_i - P_0) × (P_3 - P_0)`,
/// `f(t) = 3 t (1-t) [b_1 (1-t) + b_2 t]`, so the curve is single-sided iff `b_1 b_2 >= 0`
/// (computed here in exact integer arithmetic, independently of the library).
pub fn prop_single_sided_cubic_closed_form(p: [[i8; 2]; 4]) {
    let ctrl: Vec<[f64; 2]> = p.iter().map(|q| [q[0] as f64, q[1] as f64]).collect();
    let c = |i: usize| {
        let (dx, dy) = ((p[i][0] - p[0][0]) as i64, (p[i][1] - p[0][1]) as i64);
        let (cx, cy) = ((p[3][0] - p[0][0]) as i64, (p[3][1] - p[0][1]) as i64);
        dx * cy - dy * cx
    };
    let got = single_sided(&ctrl);
    if p[0] == p[3] {
        assert_eq!(got, Sidedness::DegenerateChord);
    } else if c(1) * c(2) >= 0 {
        assert!(
            matches!(got, Sidedness::SingleSided { .. }),
            "{p:?}: {got:?}"
        );
    } else {
        assert_eq!(got, Sidedness::DoubleSided { crossings: 1 }, "{p:?}");
    }
}

// ---------------------------------------------------------------- knot spans

/// For every valid knot vector (degree 2, 6 control points, small integer knots) and every
/// parameter in its domain, `find_span` returns `k` with `knots[k] <= t < knots[k+1]`, or
/// the last non-empty span at the domain's end.
pub fn prop_find_span_brackets(inner: [i8; 3], t2: i8) {
    let mut k = vec![0.0, 0.0, 0.0];
    k.extend(inner.iter().map(|x| *x as f64));
    k.extend([8.0, 8.0, 8.0]);
    let Ok(kv) = KnotVector::new(k.clone(), 2, 6) else {
        return;
    };
    let t = t2 as f64 / 2.0;
    if !(0.0..=8.0).contains(&t) {
        return;
    }
    let s = kv.find_span(&t);
    assert!((2..6).contains(&s));
    assert!(k[s] < k[s + 1], "span {s} is empty");
    if t < 8.0 {
        assert!(k[s] <= t && t < k[s + 1], "t = {t}, span {s}, knots {k:?}");
    } else {
        assert_eq!(k[s + 1], 8.0);
    }
}

// ---------------------------------------------------------------- point-to-segment distance

/// The exact squared distance from `p` to segment `[a, b]` used by the curve-on-surface
/// Hausdorff bound is the minimum of `f(t) = |p - a - t (b - a)|²` on `[0, 1]`, certified by
/// optimality (KKT) conditions of this convex quadratic, checked in exact integer arithmetic:
/// the value is attained at some `t* ∈ [0, 1]`, and `f'(t*) = 0` (interior), `f'(0) >= 0`
/// (at `a`) or `f'(1) <= 0` (at `b`).
pub fn prop_segment_distance_is_the_minimum(p: [i8; 2], a: [i8; 2], b: [i8; 2]) {
    use vericad::curve_on_surface::hausdorff::dist2_point_segment;
    use vericad::scalar::{Rational as Q, ratio};
    let q = |x: [i8; 2]| [Q::from(x[0] as i64), Q::from(x[1] as i64)];
    let d2 = dist2_point_segment(&q(p), &q(a), &q(b));
    let (px, py, ax, ay, bx, by) = (
        p[0] as i64,
        p[1] as i64,
        a[0] as i64,
        a[1] as i64,
        b[0] as i64,
        b[1] as i64,
    );
    let (ex, ey) = (bx - ax, by - ay);
    let len2 = ex * ex + ey * ey;
    // f(t) = |p-a|² - 2 t (p-a)·e + t² |e|²; f'(t) = 2 (t |e|² - (p-a)·e).
    let pa2 = (px - ax).pow(2) + (py - ay).pow(2);
    let dot = (px - ax) * ex + (py - ay) * ey;
    let f =
        |t: Q| -> Q { Q::from(pa2) - Q::from(2 * dot) * t.clone() + Q::from(len2) * t.clone() * t };
    if len2 == 0 {
        assert_eq!(d2, Q::from(pa2));
        return;
    }
    let t_star = if dot <= 0 {
        Q::ZERO
    } else if dot >= len2 {
        Q::ONE
    } else {
        ratio(dot, len2)
    };
    // Attained at t*, with the optimality conditions.
    assert_eq!(d2, f(t_star.clone()), "{p:?} {a:?} {b:?}");
    let fp = |t: &Q| Q::from(len2) * t.clone() - Q::from(dot);
    let zero = Q::ZERO;
    let one = Q::ONE;
    if t_star == zero {
        assert!(fp(&zero) >= zero);
    } else if t_star == one {
        assert!(fp(&one) <= zero);
    } else {
        assert_eq!(fp(&t_star), zero);
    }
}

// ---------------------------------------------------------------- Theorem 1 (Yang et al.)

/// Exact squared distance from `x` to the segment `[a, b]`, as a fraction `(num, den)`.
fn dist2_seg_i128(x: [i128; 2], a: [i128; 2], b: [i128; 2]) -> (i128, i128) {
    let (ab, ax) = ([b[0] - a[0], b[1] - a[1]], [x[0] - a[0], x[1] - a[1]]);
    let l2 = ab[0] * ab[0] + ab[1] * ab[1];
    let n2 = |v: [i128; 2]| v[0] * v[0] + v[1] * v[1];
    let dot = ax[0] * ab[0] + ax[1] * ab[1];
    if l2 == 0 || dot <= 0 {
        return (n2(ax), 1);
    }
    if dot >= l2 {
        return (n2([x[0] - b[0], x[1] - b[1]]), 1);
    }
    let c = ax[0] * ab[1] - ax[1] * ab[0];
    (c * c, l2)
}

fn frac_max(x: (i128, i128), y: (i128, i128)) -> (i128, i128) {
    if x.0 * y.1 >= y.0 * x.1 { x } else { y }
}

/// De Casteljau halves of an integer cubic, scaled by 8 (stays integer).
fn halves_i128(c: &[[i128; 2]; 4]) -> ([[i128; 2]; 4], [[i128; 2]; 4]) {
    let l = |i: usize| c[i];
    let m = |x: [i128; 2], y: [i128; 2]| [x[0] + y[0], x[1] + y[1]];
    let k = |x: [i128; 2], f: i128| [x[0] * f, x[1] * f];
    // Levels at t = 1/2, scaled by 2 per level, all brought to scale 8.
    let (p01, p12, p23) = (m(l(0), l(1)), m(l(1), l(2)), m(l(2), l(3)));
    let (p012, p123) = (m(p01, p12), m(p12, p23));
    let mid = m(p012, p123);
    (
        [k(l(0), 8), k(p01, 4), k(p012, 2), mid],
        [mid, k(p123, 2), k(p23, 4), k(l(3), 8)],
    )
}

/// Certified upper bound (squared, as a fraction over the curve's own scale squared) of the
/// distance of an integer cubic from its chord: convex hull of `2^levels` sub-pieces.
fn hull_bound2(c: [[i128; 2]; 4], levels: u32) -> (i128, i128) {
    let mut parts = vec![c];
    let mut scale = 1i128;
    for _ in 0..levels {
        parts = parts
            .iter()
            .flat_map(|p| {
                let (a, b) = halves_i128(p);
                [a, b]
            })
            .collect();
        scale *= 8;
    }
    let (a, b) = (
        [c[0][0] * scale, c[0][1] * scale],
        [c[3][0] * scale, c[3][1] * scale],
    );
    let mut best = (0, 1);
    for p in &parts {
        for q in p {
            best = frac_max(best, dist2_seg_i128(*q, a, b));
        }
    }
    (best.0, best.1 * scale * scale)
}

/// Outcome of one Theorem 1 case.
#[derive(Debug, PartialEq, Eq)]
pub enum Theorem1 {
    /// Proven: an upper bound of the polyline's Hausdorff distance is at most a lower bound
    /// of the piece's distance `H` to its chord.
    Proven,
    /// The bounds overlap (typically a tie: the farthest point is the same chord end before
    /// and after the split); no counterexample either.
    Undecided,
    /// Proven violation: a lower bound of the polyline's distance exceeds an upper bound of `H`.
    Counterexample,
}

/// Theorem 1 of Yang et al.: splitting a single-sided Bézier piece into a finer polyline
/// (vertices on the curve) keeps the Hausdorff distance within the piece's distance `H` to its
/// chord. Each case is decided with exact integer bounds:
/// * the polyline–curve Hausdorff distance is at most the largest distance of a sub-arc from
///   its own sub-chord (curve → polyline: a sub-arc point is that close to its sub-chord;
///   polyline → curve: the sub-arc's clamped projection covers the sub-chord), bounded
///   **from above** by the convex hull of 8 sub-pieces of each sub-arc; `H` is bounded **from
///   below** by the distance of 65 curve points from the chord: upper ≤ lower proves the case;
/// * a counterexample would be proven by 65 curve points farther from the polyline than an
///   upper bound of `H` (hull of 32 sub-pieces).
///
/// `None` for double-sided pieces (outside the theorem).
pub fn prop_theorem1(p: [[i8; 2]; 4], k: u8) -> Option<Theorem1> {
    let c: [[i128; 2]; 4] = p.map(|q| [q[0] as i128, q[1] as i128]);
    let ctrl: Vec<[f64; 2]> = p.iter().map(|q| [q[0] as f64, q[1] as f64]).collect();
    if !matches!(single_sided(&ctrl), Sidedness::SingleSided { .. }) {
        return None;
    }
    // Sub-arcs at s = k/4, by de Casteljau, scaled by 64 (integers).
    let (s, r) = (k as i128, 4 - k as i128);
    let lerp = |x: [i128; 2], y: [i128; 2]| [r * x[0] + s * y[0], r * x[1] + s * y[1]];
    let k4 = |x: [i128; 2], f: i128| [x[0] * f, x[1] * f];
    let (a1, a2, a3) = (lerp(c[0], c[1]), lerp(c[1], c[2]), lerp(c[2], c[3]));
    let (b1, b2) = (lerp(a1, a2), lerp(a2, a3));
    let m = lerp(b1, b2);
    let left = [k4(c[0], 64), k4(a1, 16), k4(b1, 4), m];
    let right = [m, k4(b2, 4), k4(a3, 16), k4(c[3], 64)];
    let big = |x: i128| vericad::scalar::BigInt::from(x);
    let le = |x: (i128, i128), y: (i128, i128)| big(x.0) * big(y.1) <= big(y.0) * big(x.1);
    // Curve points at t = j/64, scaled by 64³.
    const S3: i128 = 262_144;
    let samples: Vec<[i128; 2]> = (0..=64i128)
        .map(|j| {
            let (t, u) = (j, 64 - j);
            let w = [u * u * u, 3 * t * u * u, 3 * t * t * u, t * t * t];
            [
                (0..4).map(|i| w[i] * c[i][0]).sum::<i128>(),
                (0..4).map(|i| w[i] * c[i][1]).sum::<i128>(),
            ]
        })
        .collect();
    // Upper bound for the polyline (scale 64 → squared fraction over 64²).
    let up_p = frac_max(hull_bound2(left, 3), hull_bound2(right, 3));
    let up_p = (up_p.0, up_p.1 * 64 * 64);
    // Lower bound of H.
    let (a, b) = (k4(c[0], S3), k4(c[3], S3));
    let low_h = samples
        .iter()
        .fold((0, 1), |acc, x| frac_max(acc, dist2_seg_i128(*x, a, b)));
    let low_h = (low_h.0, low_h.1 * S3 * S3);
    if le(up_p, low_h) {
        return Some(Theorem1::Proven);
    }
    // Counterexample search: lower bound of the polyline's distance vs upper bound of H.
    let mm = k4(m, 4096);
    let low_p = samples.iter().fold((0, 1), |acc, x| {
        let d1 = dist2_seg_i128(*x, a, mm);
        let d2 = dist2_seg_i128(*x, mm, b);
        frac_max(acc, if le(d1, d2) { d1 } else { d2 })
    });
    let low_p = (low_p.0, low_p.1 * S3 * S3);
    let up_h = hull_bound2(c, 5);
    if le(low_p, up_h) {
        Some(Theorem1::Undecided)
    } else {
        Some(Theorem1::Counterexample)
    }
}

#[cfg(kani)]
mod kani_drivers {
    use super::*;
    #[kani::proof]
    #[kani::unwind(12)]
    fn find_span_brackets() {
        let inner: [i8; 3] = kani::any();
        let t2: i8 = kani::any();
        kani::assume(inner.iter().all(|x| (0..=8).contains(x)));
        prop_find_span_brackets(inner, t2);
    }
    #[kani::proof]
    #[kani::unwind(8)]
    fn segment_distance_is_the_minimum() {
        let (p, a, b): ([i8; 2], [i8; 2], [i8; 2]) = (kani::any(), kani::any(), kani::any());
        kani::assume(p.iter().chain(&a).chain(&b).all(|x| (-4..=4).contains(x)));
        prop_segment_distance_is_the_minimum(p, a, b);
    }
    #[kani::proof]
    #[kani::unwind(70)]
    fn theorem1_no_counterexample() {
        let p: [[i8; 2]; 4] = kani::any();
        let k: u8 = kani::any();
        kani::assume(p.iter().flatten().all(|x| (-2..=2).contains(x)) && (1..=3).contains(&k));
        assert_ne!(
            super::prop_theorem1(p, k),
            Some(super::Theorem1::Counterexample)
        );
    }

    #[kani::proof]
    #[kani::unwind(8)]
    fn single_sided_cubic_closed_form() {
        let p: [[i8; 2]; 4] = kani::any();
        kani::assume(p.iter().flatten().all(|x| (-2..=2).contains(x)));
        prop_single_sided_cubic_closed_form(p);
    }
}

#[test]
fn find_span_brackets_exhaustive() {
    for a in 0..=8 {
        for b in 0..=8 {
            for c in 0..=8 {
                for t2 in -1..=17 {
                    prop_find_span_brackets([a, b, c], t2);
                }
            }
        }
    }
}

/// Exhaustive over the sub-domain `P_0 = (0,0)`, `P_1, P_2, P_3 ∈ [-2,2]²`
/// (5^6 = 15,625 curves; translation invariance makes `P_0` free of loss), plus a
/// deterministic sweep with `P_0` moving over `[-2,2]²`.
#[test]
fn single_sided_cubic_closed_form_exhaustive() {
    let r = -2i8..=2;
    for x1 in r.clone() {
        for y1 in r.clone() {
            for x2 in r.clone() {
                for y2 in r.clone() {
                    for x3 in r.clone() {
                        for y3 in r.clone() {
                            prop_single_sided_cubic_closed_form([
                                [0, 0],
                                [x1, y1],
                                [x2, y2],
                                [x3, y3],
                            ]);
                        }
                    }
                }
            }
        }
    }
    for x0 in r.clone() {
        for y0 in r.clone() {
            for k in 0..625i32 {
                let d = |j: i32| ((k / 5i32.pow(j as u32)) % 5 - 2) as i8;
                prop_single_sided_cubic_closed_form([
                    [x0, y0],
                    [d(0), d(1)],
                    [d(2), d(3)],
                    [d(1), d(0)],
                ]);
            }
        }
    }
}

/// Exhaustive over `p, a, b ∈ [-2, 2]²` (5^6 = 15,625 triples).
#[test]
fn segment_distance_is_the_minimum_exhaustive() {
    let r = -2i8..=2;
    for px in r.clone() {
        for py in r.clone() {
            for ax in r.clone() {
                for ay in r.clone() {
                    for bx in r.clone() {
                        for by in r.clone() {
                            prop_segment_distance_is_the_minimum([px, py], [ax, ay], [bx, by]);
                        }
                    }
                }
            }
        }
    }
}

/// Theorem 1, exhaustively over single-sided cubics with `P_0 = (0,0)`,
/// `P_1, P_2, P_3 ∈ [-2,2]²` and splits at `s = 1/4, 1/2, 3/4`: no case is a proven
/// counterexample; the cases the bounds prove are counted, the undecided ones (ties) listed.
#[test]
fn theorem1_exhaustive() {
    let r = -2i8..=2;
    let (mut proven, mut undecided, mut counter) = (0usize, Vec::new(), Vec::new());
    for x1 in r.clone() {
        for y1 in r.clone() {
            for x2 in r.clone() {
                for y2 in r.clone() {
                    for x3 in r.clone() {
                        for y3 in r.clone() {
                            for k in 1..=3u8 {
                                let p = [[0, 0], [x1, y1], [x2, y2], [x3, y3]];
                                match prop_theorem1(p, k) {
                                    Some(Theorem1::Proven) => proven += 1,
                                    Some(Theorem1::Undecided) => undecided.push((p, k)),
                                    Some(Theorem1::Counterexample) => counter.push((p, k)),
                                    None => {}
                                }
                            }
                        }
                    }
                }
            }
        }
    }
    println!(
        "Theorem 1: {proven} cases proven, {} undecided by the bounds, {} counterexamples",
        undecided.len(),
        counter.len()
    );
    for u in undecided.iter().take(5) {
        println!("  undecided: {u:?}");
    }
    assert!(
        counter.is_empty(),
        "counterexamples: {:?}",
        &counter[..counter.len().min(5)]
    );
    assert!(proven > 20_000);
}
