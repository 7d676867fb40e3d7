//! 4 × 4 real matrices in `f64` for the Newton steps and preconditioners of the curve and
//! singular-point certificates (approximations only: any preconditioner keeps Krawczyk's
//! test sound, a good one lets it succeed).

pub(crate) type M4 = [[f64; 4]; 4];

/// Inverse of a 4 × 4 matrix (Gauss–Jordan, partial pivoting); `None` if singular.
pub(crate) fn inverse4(mut a: M4) -> Option<M4> {
    let mut inv: M4 = std::array::from_fn(|i| std::array::from_fn(|j| (i == j) as u8 as f64));
    for c in 0..4 {
        let p = (c..4).max_by(|&i, &k| a[i][c].abs().total_cmp(&a[k][c].abs()))?;
        if a[p][c] == 0.0 || a[p][c].is_nan() {
            return None;
        }
        a.swap(c, p);
        inv.swap(c, p);
        let d = a[c][c];
        for k in 0..4 {
            a[c][k] /= d;
            inv[c][k] /= d;
        }
        for r in 0..4 {
            if r != c {
                let f = a[r][c];
                for k in 0..4 {
                    a[r][k] -= f * a[c][k];
                    inv[r][k] -= f * inv[c][k];
                }
            }
        }
    }
    inv.iter().flatten().all(|x| x.is_finite()).then_some(inv)
}

pub(crate) fn mul4(m: &M4, v: &[f64; 4]) -> [f64; 4] {
    std::array::from_fn(|i| (0..4).map(|k| m[i][k] * v[k]).sum())
}
