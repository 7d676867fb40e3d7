//! The quality measure of a parametrization: how far it is from chord length.
//!
//! On a uniform `N × N` parameter grid, along every iso-line (`N + 1` lines of constant u,
//! `N + 1` of constant v), the *spacing ratio* of the `k`-th step is
//! `ρ_k = (|x_{k+1} − x_k| / Σ_l |x_{l+1} − x_l|) / (1 / N)`: the physical spacing over the
//! parametric spacing, each normalised by the line's total. `ρ ≡ 1` on a line exactly when
//! its uniform parameter steps have equal chords (docs/papers.md §A, property (1)). Lines of
//! zero length (a pole: shorter than 1e-9 of the longest line, the rest being rounding noise)
//! are skipped and counted.

use crate::spline::NurbsSurface;
use serde::Serialize;

/// Histogram bin edges of the spacing ratio.
pub const BINS: [f64; 13] = [
    0.0,
    0.5,
    0.8,
    0.9,
    0.95,
    0.98,
    1.02,
    1.05,
    1.1,
    1.25,
    2.0,
    5.0,
    f64::INFINITY,
];

/// One histogram bin `[lo, hi)`.
#[derive(Clone, Debug, Serialize)]
pub struct Bin {
    pub lo: f64,
    /// `null` in JSON for the open last bin.
    pub hi: Option<f64>,
    pub count: usize,
}

/// Spacing ratio statistics.
#[derive(Clone, Debug, Default, Serialize)]
pub struct Spacing {
    pub min: f64,
    pub max: f64,
    /// `max |ρ − 1|`.
    pub max_deviation: f64,
    /// Grid intervals per direction.
    pub grid: usize,
    pub steps: usize,
    pub skipped_lines: usize,
    pub histogram: Vec<Bin>,
}

/// Spacing ratios along the iso-lines of an `n × n` uniform parameter grid of `s`: each
/// line's ratios, in order (`u = const` lines first, then `v = const`; empty for a line of
/// zero length).
pub fn ratios(s: &NurbsSurface<f64, 3>, n: usize) -> Vec<Vec<f64>> {
    let (u0, u1, v0, v1) = s.hom.domain();
    let pts: Vec<Vec<[f64; 3]>> = (0..=n)
        .map(|i| {
            let u = u0 + (u1 - u0) * i as f64 / n as f64;
            (0..=n)
                .map(|j| s.eval(&u, &(v0 + (v1 - v0) * j as f64 / n as f64)))
                .collect()
        })
        .collect();
    let mut lines: Vec<Vec<[f64; 3]>> = pts.clone();
    for j in 0..=n {
        lines.push((0..=n).map(|i| pts[i][j]).collect());
    }
    let steps: Vec<Vec<f64>> = lines
        .iter()
        .map(|p| {
            p.windows(2)
                .map(|w| crate::geom::dist(&w[0], &w[1]))
                .collect()
        })
        .collect();
    let totals: Vec<f64> = steps.iter().map(|d| d.iter().sum()).collect();
    // A line shorter than 1e-9 of the longest is a pole (its length is rounding noise).
    let longest = totals
        .iter()
        .copied()
        .filter(|t| t.is_finite())
        .fold(0.0, f64::max);
    steps
        .iter()
        .zip(&totals)
        .map(|(d, &total)| {
            if total > 1e-9 * longest && total.is_finite() {
                d.iter().map(|x| x * n as f64 / total).collect()
            } else {
                vec![]
            }
        })
        .collect()
}

/// The statistics of [`ratios`].
pub fn spacing(s: &NurbsSurface<f64, 3>, n: usize) -> Spacing {
    let lines = ratios(s, n);
    let mut sp = Spacing {
        min: f64::INFINITY,
        max: 0.0,
        grid: n,
        histogram: BINS
            .windows(2)
            .map(|w| Bin {
                lo: w[0],
                hi: w[1].is_finite().then_some(w[1]),
                count: 0,
            })
            .collect(),
        ..Default::default()
    };
    for l in &lines {
        if l.is_empty() {
            sp.skipped_lines += 1;
        }
        for &r in l {
            sp.steps += 1;
            sp.min = sp.min.min(r);
            sp.max = sp.max.max(r);
            sp.max_deviation = sp.max_deviation.max((r - 1.0).abs());
            let b = BINS.partition_point(|&e| e <= r).clamp(1, BINS.len() - 1) - 1;
            sp.histogram[b].count += 1;
        }
    }
    if sp.steps == 0 {
        sp.min = 0.0;
    }
    sp
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bilinear_square_is_chord_length_and_skewed_knots_are_not() {
        let s = crate::spline::construct::bilinear(
            [0.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [2.0, 1.0, 0.0],
        )
        .unwrap();
        let q = spacing(&s, 10);
        assert!((q.min - 1.0).abs() < 1e-12 && (q.max - 1.0).abs() < 1e-12);
        assert_eq!(q.steps, 22 * 10);
        // x = u² along u: ratios (2k+1)/N, from 0.1 to 1.9.
        let t = NurbsSurface::new(
            vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
            2,
            vec![0.0, 0.0, 1.0, 1.0],
            1,
            3,
            2,
            vec![
                [0.0, 0.0, 0.0],
                [0.0, 1.0, 0.0],
                [0.0, 0.0, 0.0],
                [0.0, 1.0, 0.0],
                [1.0, 0.0, 0.0],
                [1.0, 1.0, 0.0],
            ],
            vec![1.0; 6],
        )
        .unwrap();
        let q = spacing(&t, 10);
        assert!((q.min - 0.1).abs() < 1e-12 && (q.max - 1.9).abs() < 1e-12);
    }
}
