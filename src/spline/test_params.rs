//! Parameters for tests that evaluate a surface: the domain's two corners, a knot in `u`,
//! then random points of the domain; and the xorshift generator they are drawn from.

use super::NurbsSurface;

/// The `k`-th test parameter pair of `s` (random ones from `r`, uniform in `[0, 1)`).
pub fn params(s: &NurbsSurface<f64, 3>, k: usize, r: &mut impl FnMut() -> f64) -> (f64, f64) {
    let (u0, u1, v0, v1) = s.hom.domain();
    let ku = s.hom.ku.knots();
    match k {
        0 => (u0, v0),
        1 => (u1, v1),
        2 => (ku[ku.len() / 2], v0 + 0.5 * (v1 - v0)),
        _ => (u0 + r() * (u1 - u0), v0 + r() * (v1 - v0)),
    }
}

/// A deterministic generator of numbers uniform in `[0, 1)` (xorshift64, 53 bits).
pub fn rng(seed: u64) -> impl FnMut() -> f64 {
    let mut x = seed;
    move || {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        (x >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// A clamped knot vector of degree `p` for basis-function tests: `inner` interior knots drawn
/// from `r` (for `p ≥ 2`, with probability 0.4 the first two made equal or 1e-12 apart), ends
/// `0` and `1` repeated `p + 1` times, all shifted by `−0.3` and scaled by `scale`.
pub fn clamped_knots(r: &mut impl FnMut() -> f64, p: usize, inner: usize, scale: f64) -> Vec<f64> {
    let mut k: Vec<f64> = (0..inner).map(|_| r()).collect();
    if inner >= 2 && p >= 2 && r() < 0.4 {
        k[1] = k[0] + if r() < 0.5 { 0.0 } else { 1e-12 };
    }
    k.sort_by(f64::total_cmp);
    let mut knots = vec![0.0; p + 1];
    knots.extend(k);
    knots.extend(vec![1.0; p + 1]);
    knots.iter().map(|x| (x - 0.3) * scale).collect()
}
