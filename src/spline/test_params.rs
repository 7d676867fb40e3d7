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
