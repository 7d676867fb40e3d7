//! Step 1a, f64 path — the Bézier extraction of S (de Boor on one span) in f64, with its
//! error bound.

/// `bspline_span_bezier` on exact f64 control points (or midpoints with radius `r`), in
/// f64: the Bézier control points of span `s` and a bound on every coordinate's distance to
/// the exact ones. Each de Boor level computes `fl((1 - α̂) d + α̂ d')` with
/// `α̂ = fl(fl(x - u_j) / fl(u_e - u_j)) ∈ [0, 1]` (rounding is monotone), `|α̂ - α| ≤
/// 3.0000001 u α`; so a level adds at most `3.0000001 u M` (the lerp lemma of [`super::ibez`])
/// plus `|α̂ - α| |d' - d| ≤ 6.7e-16 M`, i.e. below `1.1e-15 M`, `M` bounding the values
/// (`≤ mx (1 + 1e-12)`). `None` when a knot difference is not positive, or so small that
/// underflow could spoil the relative bounds.
pub fn bspline_span_bezier_f64(
    knots: &[f64],
    p: usize,
    ctrl: &[[f64; 3]],
    r: f64,
    s: usize,
) -> Option<(Vec<[f64; 3]>, f64)> {
    let mut out = Vec::with_capacity(p + 1);
    let err = bspline_span_bezier_f64_into(knots, p, ctrl, r, s, &mut out)?;
    Some((out, err))
}

/// [`bspline_span_bezier_f64`] appending the `p + 1` points to `out`. Point `k` is the de
/// Boor recurrence with `p - k` levels at `a = u_s` then `k` at `b = u_{s+1}`; the levels at
/// `a` are shared by all `k` (each point takes exactly the operations of its own recurrence).
pub fn bspline_span_bezier_f64_into(
    knots: &[f64],
    p: usize,
    ctrl: &[[f64; 3]],
    r: f64,
    s: usize,
    out: &mut Vec<[f64; 3]>,
) -> Option<f64> {
    let base = &ctrl[s - p..=s];
    let mx = base.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()));
    for lvl in 1..=p {
        for j in s - p + lvl..=s {
            let den = knots[j + p + 1 - lvl] - knots[j];
            if den.is_nan() || den < 1e-290 {
                return None;
            }
        }
    }
    if span_fixed(&knots[s - p..=s + p], p, base, &mut *out).is_none() {
        span_general(&knots[s - p..=s + p], p, base, out);
    }
    Some(err_of(r, p, mx))
}

/// The general loop of [`span_fixed`] (any degree up to 31).
fn span_general(kk: &[f64], p: usize, base: &[[f64; 3]], out: &mut Vec<[f64; 3]>) {
    let (a, b) = (kk[p], kk[p + 1]);
    // One de Boor level at `x` on `d` (local indices `lvl..=p` of the span's points).
    let level = |d: &mut [[f64; 3]], lvl: usize, x: f64| {
        for i in (lvl..=p).rev() {
            let (uj, ue) = (kk[i], kk[i + p + 1 - lvl]);
            let alpha = (x - uj) / (ue - uj);
            for c in 0..3 {
                d[i][c] = (1.0 - alpha) * d[i - 1][c] + alpha * d[i][c];
            }
        }
    };
    let start = out.len();
    out.resize(start + p + 1, [0.0; 3]);
    let (mut da, mut e) = ([[0.0; 3]; 32], [[0.0; 3]; 32]);
    let (da, e) = (&mut da[..=p], &mut e[..=p]);
    da.copy_from_slice(base);
    for na in 0..=p {
        if na > 0 {
            level(da, na, a);
        }
        e.copy_from_slice(da);
        for lvl in na + 1..=p {
            level(e, lvl, b);
        }
        out[start + p - na] = e[p];
    }
}

/// The bound of [`bspline_span_bezier_f64`].
fn err_of(r: f64, p: usize, mx: f64) -> f64 {
    (r + p as f64 * (1.1e-15 * mx * (1.0 + 1e-12) + 1e-300)) * (1.0 + 1e-14)
}

/// [`bspline_span_bezier_f64_into`] for `L = p + 1 ≤ 5` points with the sizes known at
/// compile time: the same operations (`α = (x - u_j) / (u_e - u_j)` computed once per level
/// and index for each of `a`, `b`; the same lerps in the same order). `kk` = the knots
/// `u_{s-p} ..= u_{s+p}`; `None` when no fixed kernel exists.
fn span_fixed(kk: &[f64], p: usize, base: &[[f64; 3]], out: &mut Vec<[f64; 3]>) -> Option<()> {
    fn run<const L: usize>(kk: &[f64], base: &[[f64; 3]], out: &mut Vec<[f64; 3]>) {
        let p = L - 1;
        let (a, b) = (kk[p], kk[p + 1]);
        // alpha[lvl][i] for the point `i` (local index) at level `lvl`.
        let mut al_a = [[0.0; L]; L];
        let mut al_b = [[0.0; L]; L];
        for lvl in 1..L {
            for i in lvl..L {
                let (uj, ue) = (kk[i], kk[i + p + 1 - lvl]);
                al_a[lvl][i] = (a - uj) / (ue - uj);
                al_b[lvl][i] = (b - uj) / (ue - uj);
            }
        }
        let level = |d: &mut [[f64; 3]; L], lvl: usize, al: &[f64; L]| {
            for i in (lvl..L).rev() {
                let alpha = al[i];
                for c in 0..3 {
                    d[i][c] = (1.0 - alpha) * d[i - 1][c] + alpha * d[i][c];
                }
            }
        };
        let mut da: [[f64; 3]; L] = std::array::from_fn(|i| base[i]);
        let start = out.len();
        out.resize(start + L, [0.0; 3]);
        for na in 0..L {
            if na > 0 {
                level(&mut da, na, &al_a[na]);
            }
            let mut e = da;
            for lvl in na + 1..L {
                level(&mut e, lvl, &al_b[lvl]);
            }
            out[start + p - na] = e[p];
        }
    }
    match p + 1 {
        1 => run::<1>(kk, base, out),
        2 => run::<2>(kk, base, out),
        3 => run::<3>(kk, base, out),
        4 => run::<4>(kk, base, out),
        5 => run::<5>(kk, base, out),
        _ => return None,
    }
    Some(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::curve_on_surface::float::ibez::tests::{q_, rng};
    use crate::scalar::{Rational, Scalar};

    /// The fixed-size span extraction computes bit for bit what the general loop does.
    #[test]
    fn fixed_span_extraction_equals_the_general_loop() {
        let mut r = rng(11);
        let mut compared = 0;
        for p in 1..=4usize {
            for _ in 0..20 {
                let mut kk: Vec<f64> = (0..2 * p + 1).map(|_| r().abs()).collect();
                kk.sort_by(f64::total_cmp);
                if kk[p + 1] <= kk[p] || kk.windows(2).any(|w| w[1] <= w[0]) {
                    continue;
                }
                let base: Vec<[f64; 3]> = (0..=p).map(|_| [r(), r(), r()]).collect();
                let (mut f, mut g) = (Vec::new(), Vec::new());
                span_fixed(&kk, p, &base, &mut f).unwrap();
                span_general(&kk, p, &base, &mut g);
                assert_eq!(f, g, "degree {p}");
                compared += 1;
            }
        }
        assert!(compared >= 60, "{compared}");
        assert!(span_fixed(&[0.0; 11], 5, &[[0.0; 3]; 6], &mut Vec::new()).is_none());
    }

    #[test]
    fn f64_span_extraction_is_within_its_bound() {
        use crate::spline::BSplineSurface;
        let mut r = rng(7);
        for trial in 0..40 {
            let (p, q) = (1 + trial % 3, 1 + (trial / 3) % 3);
            let mut ku = vec![0.0; p + 1];
            let mut kv = vec![0.0; q + 1];
            for k in [0.1 + r().abs().min(0.2), 0.5, 0.7 + r().abs().min(0.2)] {
                ku.push(k);
                kv.push(k);
            }
            ku.extend(std::iter::repeat_n(1.0, p + 1));
            kv.extend(std::iter::repeat_n(1.0, q + 1));
            let (nu, nv) = (ku.len() - p - 1, kv.len() - q - 1);
            let net: Vec<[f64; 3]> = (0..nu * nv).map(|_| [r(), r(), r()]).collect();
            let s = BSplineSurface::new(ku.clone(), p, kv.clone(), q, nu, nv, net.clone()).unwrap();
            let exact = s
                .map(|k| q_(*k), crate::geom::lift_point::<Rational, 3>)
                .bezier_patches();
            for bp in &exact {
                let (u0, v0) = (Scalar::to_f64(&bp.u0), Scalar::to_f64(&bp.v0));
                let su = s.ku.find_span(&u0);
                let sv = s.kv.find_span(&v0);
                let mut rows = Vec::new();
                let mut e_rows = 0.0f64;
                for i in su - p..=su {
                    let (pts, e) =
                        bspline_span_bezier_f64(&kv, q, &net[i * nv..(i + 1) * nv], 0.0, sv)
                            .unwrap();
                    e_rows = e_rows.max(e);
                    rows.push(pts);
                }
                for l in 0..=q {
                    let mut col = vec![[0.0; 3]; su + 1];
                    for (k, i) in (su - p..=su).enumerate() {
                        col[i] = rows[k][l];
                    }
                    let (pts, e) = bspline_span_bezier_f64(&ku, p, &col, e_rows, su).unwrap();
                    for (k, x) in pts.iter().enumerate() {
                        let ex = bp.patch.at(k, l);
                        for c in 0..3 {
                            let d = (q_(x[c]) - ex[c].clone()).abs();
                            assert!(
                                d <= q_(e),
                                "trial {trial}: off by {} > {e}",
                                Scalar::to_f64(&d)
                            );
                        }
                    }
                }
            }
        }
    }
}
