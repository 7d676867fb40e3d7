//! Curves measured independently of the library: (rational) Bézier segments by de Casteljau
//! on homogeneous points, and distances by projection (nearest sample, then golden-section
//! search), for the curve-on-surface tests.

/// Euclidean distance.
pub fn dist(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// A Bézier segment with optional weights at `t`, by de Casteljau on homogeneous points.
pub fn segment_point(cps: &[[f64; 3]], w: Option<&[f64]>, t: f64) -> [f64; 3] {
    let mut h: Vec<[f64; 4]> = cps
        .iter()
        .enumerate()
        .map(|(k, p)| {
            let w = w.map_or(1.0, |w| w[k]);
            [w * p[0], w * p[1], w * p[2], w]
        })
        .collect();
    let n = h.len();
    for r in 1..n {
        for i in 0..n - r {
            let next = h[i + 1];
            for (x, y) in h[i].iter_mut().zip(next) {
                *x = (1.0 - t) * *x + t * y;
            }
        }
    }
    [h[0][0] / h[0][3], h[0][1] / h[0][3], h[0][2] / h[0][3]]
}

/// Distance from `x` to the curve `f` on `[lo, hi]`: nearest of `k + 1` samples, then a
/// golden-section search on the bracket around it.
pub fn project(f: &dyn Fn(f64) -> [f64; 3], x: &[f64; 3], lo: f64, hi: f64, k: usize) -> f64 {
    let at = |i: usize| lo + (hi - lo) * i as f64 / k as f64;
    let best = (0..=k)
        .min_by(|&i, &j| dist(&f(at(i)), x).total_cmp(&dist(&f(at(j)), x)))
        .unwrap_or(0);
    let (mut a, mut b) = (at(best.saturating_sub(1)), at((best + 1).min(k)));
    let g = (5f64.sqrt() - 1.0) / 2.0;
    for _ in 0..80 {
        let (m1, m2) = (b - g * (b - a), a + g * (b - a));
        if dist(&f(m1), x) < dist(&f(m2), x) {
            b = m2;
        } else {
            a = m1;
        }
    }
    dist(&f(at(best)), x).min(dist(&f(0.5 * (a + b)), x))
}
