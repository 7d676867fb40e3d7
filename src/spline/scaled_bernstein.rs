//! Polynomials in *scaled* Bernstein form with interval coefficients: the coefficient `k` of
//! a polynomial of degree `n` on `[0, 1]` kept as `C(n, k) f_k`. Products are then plain
//! convolutions (`C(m,i) C(n,j) B_i^m B_j^n = C(m+n,k) B_k^{m+n}`, `k = i + j`), and the
//! binomials are divided out once, where a convex hull of Bernstein coefficients is read
//! (DeRose et al.'s composition by Bernstein products, as [`super::compose`] does exactly).
//! Every operation is outward rounded ([`Interval`]), so each result encloses the exact one.

use crate::scalar::Interval;

type I = Interval;

/// `C(n, k)`, exact for `n ≤ 56` (`C(56, 28) < 2⁵³`).
pub fn binom(n: usize, k: usize) -> f64 {
    let k = k.min(n - k);
    let mut r: u64 = 1;
    for i in 0..k {
        r = r * (n - i) as u64 / (i + 1) as u64;
    }
    r as f64
}

/// Product of two polynomials in *scaled* Bernstein form on `[0, 1]` — the coefficient `k`
/// of a polynomial of degree `n` kept as `C(n, k) f_k` — enclosed: in that form the product's
/// coefficients are the plain convolution `c̃_k = Σ_{i+j=k} f̃_i g̃_j`, since
/// `C(m,i) C(n,j) B_i^m B_j^n = C(m+n,k) B_k^{m+n}` with `k = i + j` (the usual product
/// formula `c_k = Σ C(m,i) C(n,j) / C(m+n,k) f_i g_j`, multiplied through by `C(m+n,k)`).
pub fn mul(f: &[I], g: &[I]) -> Vec<I> {
    if f.is_empty() || g.is_empty() {
        return Vec::new();
    }
    let mut c = vec![I::point(0.0); f.len() + g.len() - 1];
    for (i, fi) in f.iter().enumerate() {
        for (ck, gj) in c[i..].iter_mut().zip(g) {
            *ck = *ck + *fi * *gj;
        }
    }
    c
}

/// Bernstein coefficients into the scaled form of [`mul`] (`f_k C(n, k)`, enclosed).
pub fn scaled(f: impl ExactSizeIterator<Item = I>) -> Vec<I> {
    let n = f.len().saturating_sub(1);
    f.enumerate()
        .map(|(k, x)| x * I::point(binom(n, k)))
        .collect()
}

/// The scaled form of [`mul`] back to Bernstein coefficients (`f̃_k / C(n, k)`, enclosed; a
/// binomial is a positive point, so the quotient always exists).
pub fn unscaled(f: &[I]) -> Vec<I> {
    let n = f.len().saturating_sub(1);
    f.iter()
        .enumerate()
        .map(|(k, x)| x.checked_div(I::point(binom(n, k))).unwrap_or(*x))
        .collect()
}

/// `x^0, …, x^k`, all in the scaled form of [`mul`] (`x` given in it).
pub fn powers(x: &[I], k: usize) -> Vec<Vec<I>> {
    let mut out = vec![vec![I::point(1.0)]];
    for i in 1..=k {
        let next = mul(&out[i - 1], x);
        out.push(next);
    }
    out
}
