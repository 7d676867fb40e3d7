//! The multiquadric fill (paper A §3.4) on its own: a plane through a hole, Franke's (1982)
//! test functions on a grid with a hole (the table in docs/coons.md), interpolation at the
//! centres, collinear centres.

use vericad::approx::coons::discrete::Grid;
use vericad::approx::coons::multiquadric::{fill, interpolate};

/// The multiquadric fill reproduces a plane through a hole to 1e-9.
#[test]
fn multiquadric_reproduces_a_plane() {
    let (m, n) = (20, 16);
    let plane = |u: f64, v: f64| 0.3 + 0.2 * u - 0.7 * v;
    let mut known = Grid::filled(m, n, None);
    let mut hole = 0;
    for i in 0..=m {
        for j in 0..=n {
            let (u, v) = (i as f64 / m as f64, j as f64 / n as f64);
            if (u - 0.45).powi(2) + (v - 0.55).powi(2) < 0.05 {
                hole += 1;
            } else {
                known.set(i, j, Some(plane(u, v)));
            }
        }
    }
    let (t, stats) = fill(&known, 8, 1.0, -0.5, true).unwrap();
    assert_eq!(stats.filled, hole);
    let mut worst: f64 = 0.0;
    for i in 0..=m {
        for j in 0..=n {
            worst = worst.max((t.at(i, j) - plane(i as f64 / m as f64, j as f64 / n as f64)).abs());
        }
    }
    eprintln!(
        "plane: {hole} filled, max error {worst:.3e}, max condition {:.3e}",
        stats.max_condition
    );
    assert!(worst < 1e-9, "{worst}");
}

/// Franke's (1982) test functions F1–F6.
fn franke(k: usize, x: f64, y: f64) -> f64 {
    let r2 = (x - 0.5).powi(2) + (y - 0.5).powi(2);
    match k {
        1 => {
            0.75 * (-((9.0 * x - 2.0).powi(2) + (9.0 * y - 2.0).powi(2)) / 4.0).exp()
                + 0.75 * (-(9.0 * x + 1.0).powi(2) / 49.0 - (9.0 * y + 1.0) / 10.0).exp()
                + 0.5 * (-((9.0 * x - 7.0).powi(2) + (9.0 * y - 3.0).powi(2)) / 4.0).exp()
                - 0.2 * (-(9.0 * x - 4.0).powi(2) - (9.0 * y - 7.0).powi(2)).exp()
        }
        2 => ((9.0 * y - 9.0 * x).tanh() + 1.0) / 9.0,
        3 => (1.25 + (5.4 * y).cos()) / (6.0 * (1.0 + (3.0 * x - 1.0).powi(2))),
        4 => (-81.0 / 16.0 * r2).exp() / 3.0,
        5 => (-81.0 / 4.0 * r2).exp() / 3.0,
        _ => (64.0 - 81.0 * r2).sqrt() / 9.0 - 0.5,
    }
}

/// Franke's functions on a 33 × 33 grid with a round hole (radius 0.12 about (0.4, 0.6)):
/// max and RMS error of the fill at the hole's points (the table in docs/coons.md).
#[test]
fn multiquadric_on_franke_functions() {
    let m = 32;
    for linear in [true, false] {
        for k in 1..=6 {
            let mut known = Grid::filled(m, m, None);
            for i in 0..=m {
                for j in 0..=m {
                    let (u, v) = (i as f64 / m as f64, j as f64 / m as f64);
                    if (u - 0.4).powi(2) + (v - 0.6).powi(2) >= 0.0144 {
                        known.set(i, j, Some(franke(k, u, v)));
                    }
                }
            }
            let (t, stats) = fill(&known, 8, 1.0, -0.5, linear).unwrap();
            let (mut worst, mut sum2, mut count) = (0.0f64, 0.0, 0);
            for i in 0..=m {
                for j in 0..=m {
                    if known.at(i, j).is_none() {
                        let e = (t.at(i, j) - franke(k, i as f64 / m as f64, j as f64 / m as f64))
                            .abs();
                        worst = worst.max(e);
                        sum2 += e * e;
                        count += 1;
                    }
                }
            }
            let rms = (sum2 / count as f64).sqrt();
            eprintln!(
                "Franke F{k} (linear part {linear}): {count} hole points, max {worst:.3e}, rms {rms:.3e}, condition ≤ {:.2e}",
                stats.max_condition
            );
            assert!(worst < 0.05, "F{k}: {worst}");
        }
    }
}

/// The plain interpolant is exact at its centres.
#[test]
fn multiquadric_interpolates_its_centres() {
    let c = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [0.7, 0.6], [0.2, 0.9]];
    let v = [1.0, -2.0, 0.5, 3.0, 0.0];
    for linear in [false, true] {
        let ip = interpolate(&c, &v, 0.1, -0.5, linear).unwrap();
        for (p, val) in c.iter().zip(&v) {
            assert!((ip.eval(p) - val).abs() < 1e-12);
        }
    }
}

/// Collinear centres (decided exactly) leave the linear part undetermined: it is dropped,
/// and the interpolant is still exact at the centres.
#[test]
fn multiquadric_on_collinear_centres() {
    let c = [
        [0.0, 0.25],
        [0.125, 0.25],
        [0.25, 0.25],
        [0.375, 0.25],
        [0.5, 0.25],
    ];
    let v = [0.1, 0.2, 0.4, 0.3, 0.0];
    let ip = interpolate(&c, &v, 0.0625, -0.5, true).unwrap();
    assert!(!ip.has_linear_part());
    for (p, val) in c.iter().zip(&v) {
        assert!((ip.eval(p) - val).abs() < 1e-12);
    }
}
