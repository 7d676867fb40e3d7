//! Tests of Krawczyk's crossing enclosure (`super`).
use super::*;

fn iv(x: f64) -> Interval {
    Interval::point(x)
}

/// The plane z = 0 over [-1, 1]² as a bilinear patch, and a straight segment from `a` to
/// `b` as a degree-2 Bézier curve (middle point at the midpoint).
fn plane() -> IPatch {
    let pts = [
        [-1.0, -1.0, 0.0],
        [-1.0, 1.0, 0.0],
        [1.0, -1.0, 0.0],
        [1.0, 1.0, 0.0],
    ];
    IPatch {
        p: 1,
        q: 1,
        x: pts.iter().map(|p| p.map(iv)).collect(),
        w: vec![iv(1.0); 4],
    }
}
fn segment(a: [f64; 3], b: [f64; 3]) -> ICurve {
    let m: [f64; 3] = std::array::from_fn(|k| 0.5 * (a[k] + b[k]));
    ICurve {
        x: [a, m, b].iter().map(|p| p.map(iv)).collect(),
        w: vec![iv(1.0); 3],
    }
}

/// A segment crossing the plane at a known point: the box holds it and is small; a
/// segment above the plane: no crossing.
#[test]
fn a_crossing_is_enclosed_and_a_miss_is_excluded() {
    let c = segment([0.2, 0.1, -0.3], [0.3, -0.1, 0.1]);
    // z = 0 at t = 0.75: (0.275, -0.05, 0).
    match crossings(&c, &plane(), &patch_jet(&plane()).unwrap(), 1e-15) {
        Crossings::Within(b) => {
            let x = [0.275, -0.05, 0.0];
            for k in 0..3 {
                assert!(b.0[k] <= x[k] && x[k] <= b.1[k], "{b:?}");
                assert!(b.1[k] - b.0[k] < 1e-12, "{b:?}");
            }
        }
        other => panic!("{other:?}"),
    }
    let above = segment([0.2, 0.1, 0.3], [0.3, -0.1, 0.1]);
    assert_eq!(
        crossings(&above, &plane(), &patch_jet(&plane()).unwrap(), 1e-15),
        Crossings::None
    );
}

/// de Casteljau in `f64` (a few ulps off the exact value).
fn casteljau(mut c: Vec<f64>, t: f64) -> f64 {
    for l in 1..c.len() {
        for k in 0..c.len() - l {
            c[k] = c[k] * (1.0 - t) + c[k + 1] * t;
        }
    }
    c[0]
}

/// A bicubic graph `z = f(x, y)` (control points on the grid `x = i/3`, `y = j/3`, so
/// `x = u`, `y = v` exactly) crossed by vertical lines at known `(x*, y*)`: the crossing
/// is `t* = (f(x*, y*) + 1) / 3` on `C(t) = (x*, y*, 3t − 1)`. Curve and patch are split
/// together with their parameter ranges tracked; wherever the ranges hold the crossing,
/// "no crossing" would be false and a box must hold the point — and the test must find
/// the crossing in a small box at some depth.
#[test]
fn crossings_of_lines_with_a_bicubic_graph() {
    let mut rng = crate::spline::test_params::rng(7);
    for _ in 0..40 {
        let z: Vec<f64> = (0..16).map(|_| rng() - 0.5).collect();
        let patch = IPatch {
            p: 3,
            q: 3,
            x: (0..16)
                .map(|k| [iv((k / 4) as f64 / 3.0), iv((k % 4) as f64 / 3.0), iv(z[k])])
                .collect(),
            w: vec![iv(1.0); 16],
        };
        let (xs, ys) = (0.05 + 0.9 * rng(), 0.05 + 0.9 * rng());
        let rows: Vec<f64> = (0..4)
            .map(|i| casteljau(z[4 * i..4 * i + 4].to_vec(), ys))
            .collect();
        let f = casteljau(rows, xs);
        let root = [(f + 1.0) / 3.0, xs, ys];
        let line = ICurve {
            x: [-1.0, 0.5, 2.0]
                .iter()
                .map(|&z| [iv(xs), iv(ys), iv(z)])
                .collect(),
            w: vec![iv(1.0); 3],
        };
        let mut found = false;
        let mut stack = vec![(line, patch, [0.0, 1.0, 0.0, 1.0, 0.0, 1.0], 0)];
        while let Some((c, s, r, depth)) = stack.pop() {
            let holds = (0..3).all(|k| r[2 * k] <= root[k] && root[k] <= r[2 * k + 1]);
            let split = match crossings(&c, &s, &patch_jet(&s).unwrap(), 1e-9) {
                Crossings::None => {
                    assert!(!holds, "no crossing claimed at {r:?}");
                    false
                }
                Crossings::Within(b) => {
                    let small = (0..3).all(|k| b.1[k] - b.0[k] < 1e-6);
                    if holds {
                        let p = [xs, ys, f];
                        for k in 0..3 {
                            assert!(b.0[k] - 1e-13 <= p[k] && p[k] <= b.1[k] + 1e-13);
                        }
                        found |= small;
                    }
                    !small
                }
                Crossings::Undecided => true,
            };
            match split {
                true if depth < 8 => {
                    let (tm, um, vm) = (
                        0.5 * (r[0] + r[1]),
                        0.5 * (r[2] + r[3]),
                        0.5 * (r[4] + r[5]),
                    );
                    let (c0, c1) = c.halve();
                    let q = s.quarters();
                    let uvs = [
                        [r[2], um, r[4], vm],
                        [r[2], um, vm, r[5]],
                        [um, r[3], r[4], vm],
                        [um, r[3], vm, r[5]],
                    ];
                    for (ci, tr) in [(c0, [r[0], tm]), (c1, [tm, r[1]])] {
                        for (qi, uv) in q.iter().zip(uvs) {
                            let rr = [tr[0], tr[1], uv[0], uv[1], uv[2], uv[3]];
                            stack.push((ci.clone(), qi.clone(), rr, depth + 1));
                        }
                    }
                }
                _ => {}
            }
        }
        assert!(
            found,
            "the crossing at {root:?} was never enclosed in a small box"
        );
    }
}

/// The cut rows enclose the exact control points of the curve on `[fl↓(a/b)·b, b]`
/// (exact rational de Casteljau at the same `f64` parameters), for random rational rows.
#[test]
fn cut_rows_enclose_the_exact_sub_curve() {
    use crate::scalar::Rational as Q;
    use crate::scalar::lift;
    let split_q = |xs: &[Q], t: &Q, left: bool| -> Vec<Q> {
        let mut x = xs.to_vec();
        let n = x.len() - 1;
        let mut out = vec![if left { x[0].clone() } else { x[n].clone() }; n + 1];
        for level in 1..=n {
            for k in 0..=n - level {
                x[k] = x[k].clone() * (Q::ONE - t) + x[k + 1].clone() * t;
            }
            if left {
                out[level] = x[0].clone();
            } else {
                out[n - level] = x[n - level].clone();
            }
        }
        out
    };
    let mut rng = crate::spline::test_params::rng(11);
    for _ in 0..300 {
        let n = 1 + (rng() * 4.0) as usize;
        let xs: Vec<[f64; 3]> = (0..=n)
            .map(|_| [rng() * 8.0 - 4.0, rng(), -rng()])
            .collect();
        let ws: Vec<f64> = (0..=n).map(|_| 0.2 + rng()).collect();
        let (a, b) = {
            let (p, q) = (rng(), rng());
            (p.min(q), p.max(q))
        };
        let (cx, cw) = sub_row(
            &xs.iter().map(|x| x.map(iv)).collect::<Vec<_>>(),
            &ws.iter().map(|&w| iv(w)).collect::<Vec<_>>(),
            (a, b),
        )
        .unwrap();
        let s = if a == 0.0 {
            0.0
        } else {
            (a / b).next_down().max(0.0)
        };
        assert!(lift::<Q>(s) * lift::<Q>(b) <= lift::<Q>(a));
        // Homogeneous coordinates, one component at a time.
        for k in 0..4 {
            let row: Vec<Q> = (0..=n)
                .map(|i| {
                    let w = lift::<Q>(ws[i]);
                    if k == 3 { w } else { lift::<Q>(xs[i][k]) }
                })
                .collect();
            let left = if b < 1.0 {
                split_q(&row, &lift(b), true)
            } else {
                row
            };
            let part = if a == 0.0 {
                left
            } else {
                split_q(&left, &lift(s), false)
            };
            for (i, e) in part.iter().enumerate() {
                let got = if k == 3 { cw[i] } else { cx[i][k] };
                assert!(
                    lift::<Q>(got.lo) <= *e && *e <= lift::<Q>(got.hi),
                    "{k} {i}"
                );
            }
        }
    }
}

/// A curve lying in the surface (every point a crossing) is never enclosed in a small box.
#[test]
fn a_curve_in_the_surface_is_not_claimed_small() {
    let c = segment([-0.5, 0.0, 0.0], [0.5, 0.0, 0.0]);
    match crossings(&c, &plane(), &patch_jet(&plane()).unwrap(), 1e-15) {
        Crossings::Within(b) => assert!(b.0[0] <= -0.5 && b.1[0] >= 0.5, "{b:?}"),
        Crossings::Undecided => {}
        Crossings::None => panic!("the curve lies in the plane"),
    }
}
