//! Fixed-size f64 de Casteljau kernels for the small degrees CAD data uses (up to 5 control
//! points per direction): the same arithmetic as the general loops — every step is
//! `(1 - t) a + t b` in the same order, so the error lemmas that bound the general loops
//! (see `float::ibez::mr_error`) bound these too — with the array sizes known at compile
//! time, so nothing is allocated, zeroed or copied beyond the points used.

/// Largest number of control points per direction with a fixed-size kernel.
pub const FIXED_MAX: usize = 5;

/// Polar values `b(x^{n-j} y^j)`, `j = 0..=n`, of the `L = n + 1` points `m` into `out`:
/// the de Casteljau levels at `y` are kept and `x` is applied to each level.
#[inline]
fn polar_values_fixed<const L: usize, const D: usize>(
    m: &[[f64; D]],
    x: f64,
    y: f64,
    out: &mut [[f64; D]],
) {
    let (sx, sy) = (1.0 - x, 1.0 - y);
    let mut ylev: [[f64; D]; L] = std::array::from_fn(|i| m[i]);
    for j in 0..L {
        let len = L - j;
        let mut w = ylev;
        for r in 1..len {
            for i in 0..len - r {
                for c in 0..D {
                    w[i][c] = sx * w[i][c] + x * w[i + 1][c];
                }
            }
        }
        out[j] = w[0];
        for i in 0..len - 1 {
            for c in 0..D {
                ylev[i][c] = sy * ylev[i][c] + y * ylev[i + 1][c];
            }
        }
    }
}

/// The general loop of [`polar_values_fixed`] for up to 16 points.
fn polar_values_general<const D: usize>(m: &[[f64; D]], x: f64, y: f64, out: &mut [[f64; D]]) {
    let n = m.len() - 1;
    let (sx, sy) = (1.0 - x, 1.0 - y);
    let mut ylev = [[0.0; D]; 16];
    ylev[..=n].copy_from_slice(m);
    let mut w = [[0.0; D]; 16];
    for (j, o) in out.iter_mut().enumerate().take(n + 1) {
        let len = n + 1 - j;
        w[..len].copy_from_slice(&ylev[..len]);
        for r in 1..len {
            for i in 0..len - r {
                for c in 0..D {
                    w[i][c] = sx * w[i][c] + x * w[i + 1][c];
                }
            }
        }
        *o = w[0];
        for i in 0..len - 1 {
            for c in 0..D {
                ylev[i][c] = sy * ylev[i][c] + y * ylev[i + 1][c];
            }
        }
    }
}

/// Polar values `b(x^{n-j} y^j)`, `j = 0..=n`, of the Bézier points `m` (at most 16) into
/// `out[..=n]`.
pub fn polar_values<const D: usize>(m: &[[f64; D]], x: f64, y: f64, out: &mut [[f64; D]]) {
    match m.len() {
        1 => polar_values_fixed::<1, D>(m, x, y, out),
        2 => polar_values_fixed::<2, D>(m, x, y, out),
        3 => polar_values_fixed::<3, D>(m, x, y, out),
        4 => polar_values_fixed::<4, D>(m, x, y, out),
        5 => polar_values_fixed::<5, D>(m, x, y, out),
        _ => polar_values_general(m, x, y, out),
    }
}

/// The tensor polar net of a `P1 × Q1` net (`net[i * Q1 + j]`, `i` along u): rows take the
/// polar values in v (`x_v`, `y_v`), then columns in u (`x_u`, `y_u`).
#[inline]
fn polar_net_fixed<const P1: usize, const Q1: usize>(
    m: &[[f64; 3]],
    [xu, yu, xv, yv]: [f64; 4],
    out: &mut [[f64; 3]],
) {
    let mut rows = [[[0.0; 3]; Q1]; P1];
    for (i, row) in rows.iter_mut().enumerate() {
        polar_values_fixed::<Q1, 3>(&m[i * Q1..(i + 1) * Q1], xv, yv, row);
    }
    for j in 0..Q1 {
        let col: [[f64; 3]; P1] = std::array::from_fn(|i| rows[i][j]);
        let mut vals = [[0.0; 3]; P1];
        polar_values_fixed::<P1, 3>(&col, xu, yu, &mut vals);
        for (i, v) in vals.iter().enumerate() {
            out[i * Q1 + j] = *v;
        }
    }
}

/// `polar_net_fixed` for runtime sizes: `Some(())` when a fixed kernel exists (both
/// directions with at most [`FIXED_MAX`] points), `None` otherwise (nothing written).
pub fn polar_net(
    m: &[[f64; 3]],
    p1: usize,
    q1: usize,
    args: [f64; 4],
    out: &mut [[f64; 3]],
) -> Option<()> {
    macro_rules! dispatch {
        ($($p:literal),*) => {
            match p1 {
                $( $p => dispatch!(@q $p; 1, 2, 3, 4, 5), )*
                _ => return None,
            }
        };
        (@q $p:literal; $($q:literal),*) => {
            match q1 {
                $( $q => polar_net_fixed::<$p, $q>(m, args, out), )*
                _ => return None,
            }
        };
    }
    dispatch!(1, 2, 3, 4, 5);
    Some(())
}

/// de Casteljau evaluation at `t` of the scalar Bézier coefficients `m` (any number): the
/// lerps `(1 - t) a + t b` of the general loops.
pub fn eval_1d(m: &[f64], t: f64) -> f64 {
    fn fixed<const L: usize>(m: &[f64], t: f64) -> f64 {
        let mut w: [f64; L] = std::array::from_fn(|i| m[i]);
        let s = 1.0 - t;
        for r in 1..L {
            for i in 0..L - r {
                w[i] = s * w[i] + t * w[i + 1];
            }
        }
        w[0]
    }
    match m.len() {
        2 => return fixed::<2>(m, t),
        3 => return fixed::<3>(m, t),
        4 => return fixed::<4>(m, t),
        5 => return fixed::<5>(m, t),
        6 => return fixed::<6>(m, t),
        _ => {}
    }
    let mut buf = [0.0; 32];
    let mut heap = Vec::new();
    let w: &mut [f64] = if m.len() <= buf.len() {
        &mut buf[..m.len()]
    } else {
        heap.resize(m.len(), 0.0);
        &mut heap
    };
    w.copy_from_slice(m);
    let s = 1.0 - t;
    for r in 1..w.len() {
        for i in 0..w.len() - r {
            w[i] = s * w[i] + t * w[i + 1];
        }
    }
    w[0]
}

/// de Casteljau evaluation of the `L` points `w` at `t`.
#[inline]
fn casteljau_fixed<const L: usize>(mut w: [[f64; 3]; L], t: f64) -> [f64; 3] {
    for r in 1..L {
        for i in 0..L - r {
            for c in 0..3 {
                w[i][c] = (1.0 - t) * w[i][c] + t * w[i + 1][c];
            }
        }
    }
    w[0]
}

#[inline]
fn eval_tensor_fixed<const P1: usize, const Q1: usize>(
    net: &[[f64; 3]],
    u: f64,
    v: f64,
) -> [f64; 3] {
    let col: [[f64; 3]; P1] =
        std::array::from_fn(|i| casteljau_fixed::<Q1>(std::array::from_fn(|j| net[i * Q1 + j]), v));
    casteljau_fixed::<P1>(col, u)
}

/// Tensor-product de Casteljau at `(u, v)` of a `p1 × q1` net (`net[i * q1 + j]`): `None`
/// when no fixed kernel exists for the sizes.
pub fn eval_tensor(net: &[[f64; 3]], p1: usize, q1: usize, u: f64, v: f64) -> Option<[f64; 3]> {
    macro_rules! dispatch {
        ($($p:literal),*) => {
            match p1 {
                $( $p => dispatch!(@q $p; 1, 2, 3, 4, 5), )*
                _ => None,
            }
        };
        (@q $p:literal; $($q:literal),*) => {
            match q1 {
                $( $q => Some(eval_tensor_fixed::<$p, $q>(net, u, v)), )*
                _ => None,
            }
        };
    }
    dispatch!(1, 2, 3, 4, 5)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lcg(seed: u64) -> impl FnMut() -> f64 {
        let mut s = seed;
        move || {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((s >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
        }
    }

    /// The fixed kernels compute exactly (bit for bit) what the general loops compute.
    #[test]
    fn fixed_kernels_equal_the_general_loops() {
        let mut r = lcg(3);
        for p1 in 1..=FIXED_MAX {
            for q1 in 1..=FIXED_MAX {
                let net: Vec<[f64; 3]> = (0..p1 * q1).map(|_| [r(), r(), r()]).collect();
                let (x, y, u, v) = (r().abs(), r().abs(), r().abs(), r().abs());
                let mut fixed = vec![[0.0; 3]; p1 * q1];
                polar_net(&net, p1, q1, [x, y, u, v], &mut fixed).unwrap();
                let mut rows = vec![[0.0; 3]; p1 * q1];
                for i in 0..p1 {
                    polar_values_general(
                        &net[i * q1..(i + 1) * q1],
                        u,
                        v,
                        &mut rows[i * q1..(i + 1) * q1],
                    );
                }
                for j in 0..q1 {
                    let col: Vec<[f64; 3]> = (0..p1).map(|i| rows[i * q1 + j]).collect();
                    let mut vals = vec![[0.0; 3]; p1];
                    polar_values_general(&col, x, y, &mut vals);
                    for i in 0..p1 {
                        assert_eq!(fixed[i * q1 + j], vals[i], "{p1}x{q1}");
                    }
                }
                // Evaluation is the polar value with both arguments equal.
                let e = eval_tensor(&net, p1, q1, u, v).unwrap();
                let mut pv = vec![[0.0; 3]; p1 * q1];
                polar_net(&net, p1, q1, [u, u, v, v], &mut pv).unwrap();
                assert_eq!(e, pv[0], "{p1}x{q1}");
            }
        }
        assert!(eval_tensor(&[[0.0; 3]; 6], 6, 1, 0.5, 0.5).is_none());
        // Scalar evaluation: the fixed sizes and the general loop (40 coefficients) against
        // the plain recurrence.
        for len in (1..=8).chain([40]) {
            let m: Vec<f64> = (0..len).map(|_| r()).collect();
            let t = r().abs();
            let mut w = m.clone();
            for k in 1..len {
                for i in 0..len - k {
                    w[i] = (1.0 - t) * w[i] + t * w[i + 1];
                }
            }
            assert_eq!(eval_1d(&m, t), w[0], "{len}");
        }
        assert!(polar_net(&[[0.0; 3]; 6], 1, 6, [0.0; 4], &mut [[0.0; 3]; 6]).is_none());
    }
}
