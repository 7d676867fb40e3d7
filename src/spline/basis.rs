//! B-spline basis functions and their derivatives (The NURBS Book, algorithms A2.2, A2.3),
//! allocation-free for degrees up to [`MAX_DEGREE`](super::MAX_DEGREE).

use super::knots::KnotVector;
use crate::scalar::Scalar;

/// Fixed-capacity buffer used on the evaluation hot path.
pub type Buf<S> = arrayvec::ArrayVec<S, 32>;

/// The `p + 1` non-zero basis functions `N_{span-p..=span, p}(t)` (A2.2).
pub fn basis_funs<S: Scalar>(kv: &KnotVector<S>, span: usize, t: &S) -> Buf<S> {
    let mut n = Buf::new();
    basis_funs_into(kv, span, t, &mut n);
    n
}

/// [`basis_funs`] into the caller's buffer (cleared first), with no copy of the buffer on
/// return.
#[inline]
pub fn basis_funs_into<S: Scalar>(kv: &KnotVector<S>, span: usize, t: &S, n: &mut Buf<S>) {
    let p = kv.degree();
    let u = kv.knots();
    n.clear();
    let mut left: Buf<S> = Buf::new();
    let mut right: Buf<S> = Buf::new();
    n.push(S::one());
    left.push(S::zero());
    right.push(S::zero());
    for j in 1..=p {
        left.push(t.clone() - u[span + 1 - j].clone());
        right.push(u[span + j].clone() - t.clone());
        let mut saved = S::zero();
        for r in 0..j {
            let den = right[r + 1].clone() + left[j - r].clone();
            // den = u[span+r+1] - u[span+1-j+r] > 0 inside a valid span.
            let temp = n[r].clone() / den;
            n[r] = saved + right[r + 1].clone() * temp.clone();
            saved = left[j - r].clone() * temp;
        }
        n.push(saved);
    }
}

/// The `p + 1` non-zero basis functions and their first derivatives at `t`, allocation-free:
/// `N'_{i,p} = p N_{i,p-1} / (u_{i+p} - u_i) - p N_{i+1,p-1} / (u_{i+p+1} - u_{i+1})`
/// (The NURBS Book eq. 2.7), with the degree-`p-1` row kept from the A2.2 triangle.
pub fn basis_funs_d1<S: Scalar>(kv: &KnotVector<S>, span: usize, t: &S) -> (Buf<S>, Buf<S>) {
    let (mut n, mut d) = (Buf::new(), Buf::new());
    basis_funs_d1_into(kv, span, t, &mut n, &mut d);
    (n, d)
}

/// [`basis_funs_d1`] into the caller's buffers (cleared first): returning two buffers by value
/// copied 528 bytes per call, about a tenth of a curve-certificate run.
#[inline]
pub fn basis_funs_d1_into<S: Scalar>(
    kv: &KnotVector<S>,
    span: usize,
    t: &S,
    n: &mut Buf<S>,
    d: &mut Buf<S>,
) {
    let p = kv.degree();
    let u = kv.knots();
    n.clear();
    d.clear();
    let mut left: Buf<S> = Buf::new();
    let mut right: Buf<S> = Buf::new();
    n.push(S::one());
    left.push(S::zero());
    right.push(S::zero());
    for j in 1..=p {
        if j == p {
            // The degree-(p-1) row is in `n` now: the derivatives (eq. 2.7) from it.
            let pp = S::from_i64(p as i64);
            for r in 0..=p {
                let i = span - p + r;
                let mut v = S::zero();
                if r >= 1 {
                    let den = u[i + p].clone() - u[i].clone();
                    if !den.is_zero() {
                        v = v + n[r - 1].clone() / den;
                    }
                }
                if r < p {
                    let den = u[i + p + 1].clone() - u[i + 1].clone();
                    if !den.is_zero() {
                        v = v - n[r].clone() / den;
                    }
                }
                d.push(v * pp.clone());
            }
        }
        left.push(t.clone() - u[span + 1 - j].clone());
        right.push(u[span + j].clone() - t.clone());
        let mut saved = S::zero();
        for r in 0..j {
            let den = right[r + 1].clone() + left[j - r].clone();
            let temp = n[r].clone() / den;
            n[r] = saved + right[r + 1].clone() * temp.clone();
            saved = left[j - r].clone() * temp;
        }
        n.push(saved);
    }
    if p == 0 {
        d.push(S::zero());
    }
}

/// Basis functions and their derivatives up to order `nd` (A2.3):
/// `ders[k][j]` is the k-th derivative of `N_{span-p+j, p}` at `t`; orders above `p` are 0.
pub fn ders_basis_funs<S: Scalar>(
    kv: &KnotVector<S>,
    span: usize,
    t: &S,
    nd: usize,
) -> Vec<Vec<S>> {
    let p = kv.degree();
    let u = kv.knots();
    let mut ndu = vec![vec![S::zero(); p + 1]; p + 1];
    let mut left = vec![S::zero(); p + 1];
    let mut right = vec![S::zero(); p + 1];
    ndu[0][0] = S::one();
    for j in 1..=p {
        left[j] = t.clone() - u[span + 1 - j].clone();
        right[j] = u[span + j].clone() - t.clone();
        let mut saved = S::zero();
        for r in 0..j {
            ndu[j][r] = right[r + 1].clone() + left[j - r].clone();
            let temp = ndu[r][j - 1].clone() / ndu[j][r].clone();
            ndu[r][j] = saved + right[r + 1].clone() * temp.clone();
            saved = left[j - r].clone() * temp;
        }
        ndu[j][j] = saved;
    }
    let mut ders = vec![vec![S::zero(); p + 1]; nd + 1];
    for j in 0..=p {
        ders[0][j] = ndu[j][p].clone();
    }
    let mut a = vec![vec![S::zero(); p + 1]; 2];
    for r in 0..=p {
        let (mut s1, mut s2) = (0usize, 1usize);
        a[0][0] = S::one();
        for k in 1..=nd.min(p) {
            let mut d = S::zero();
            let rk = r as isize - k as isize;
            let pk = p - k;
            if r >= k {
                a[s2][0] = a[s1][0].clone() / ndu[pk + 1][rk as usize].clone();
                d = a[s2][0].clone() * ndu[rk as usize][pk].clone();
            }
            let j1 = if rk >= -1 { 1 } else { (-rk) as usize };
            let j2 = if (r as isize - 1) <= pk as isize {
                k - 1
            } else {
                p - r
            };
            for j in j1..=j2 {
                let idx = (rk + j as isize) as usize;
                a[s2][j] = (a[s1][j].clone() - a[s1][j - 1].clone()) / ndu[pk + 1][idx].clone();
                d = d + a[s2][j].clone() * ndu[idx][pk].clone();
            }
            if r <= pk {
                a[s2][k] = -a[s1][k - 1].clone() / ndu[pk + 1][r].clone();
                d = d + a[s2][k].clone() * ndu[r][pk].clone();
            }
            ders[k][r] = d;
            std::mem::swap(&mut s1, &mut s2);
        }
    }
    let mut fac = S::from_i64(p as i64);
    for k in 1..=nd.min(p) {
        for j in 0..=p {
            ders[k][j] = ders[k][j].clone() * fac.clone();
        }
        fac = fac * S::from_i64((p - k) as i64);
    }
    ders
}

/// Largest order (degree + 1) of [`ders2_f64`].
pub const DERS2_MAX_ORDER: usize = 16;

/// [`ders_basis_funs`] up to the second derivative in `f64` without allocating (degree below
/// [`DERS2_MAX_ORDER`], else `None`): the same operations in the same order, so the same
/// numbers. `out[k][j]` is the k-th derivative of `N_{span-p+j,p}` at `t`.
pub fn ders2_f64(kv: &KnotVector<f64>, span: usize, t: f64) -> Option<[[f64; DERS2_MAX_ORDER]; 3]> {
    const M: usize = DERS2_MAX_ORDER;
    let p = kv.degree();
    if p >= M {
        return None;
    }
    let u = kv.knots();
    let mut ndu = [[0.0f64; M]; M];
    let (mut left, mut right) = ([0.0f64; M], [0.0f64; M]);
    ndu[0][0] = 1.0;
    for j in 1..=p {
        left[j] = t - u[span + 1 - j];
        right[j] = u[span + j] - t;
        let mut saved = 0.0;
        for r in 0..j {
            ndu[j][r] = right[r + 1] + left[j - r];
            let temp = ndu[r][j - 1] / ndu[j][r];
            ndu[r][j] = saved + right[r + 1] * temp;
            saved = left[j - r] * temp;
        }
        ndu[j][j] = saved;
    }
    let nd = 2;
    let mut ders = [[0.0f64; M]; 3];
    for j in 0..=p {
        ders[0][j] = ndu[j][p];
    }
    let mut a = [[0.0f64; M]; 2];
    for r in 0..=p {
        let (mut s1, mut s2) = (0usize, 1usize);
        a[0][0] = 1.0;
        for k in 1..=nd.min(p) {
            let mut d = 0.0;
            let rk = r as isize - k as isize;
            let pk = p - k;
            if r >= k {
                a[s2][0] = a[s1][0] / ndu[pk + 1][rk as usize];
                d = a[s2][0] * ndu[rk as usize][pk];
            }
            let j1 = if rk >= -1 { 1 } else { (-rk) as usize };
            let j2 = if (r as isize - 1) <= pk as isize {
                k - 1
            } else {
                p - r
            };
            for j in j1..=j2 {
                let idx = (rk + j as isize) as usize;
                a[s2][j] = (a[s1][j] - a[s1][j - 1]) / ndu[pk + 1][idx];
                d += a[s2][j] * ndu[idx][pk];
            }
            if r <= pk {
                a[s2][k] = -a[s1][k - 1] / ndu[pk + 1][r];
                d += a[s2][k] * ndu[r][pk];
            }
            ders[k][r] = d;
            std::mem::swap(&mut s1, &mut s2);
        }
    }
    let mut fac = p as f64;
    for (k, row) in ders.iter_mut().enumerate().take(nd.min(p) + 1).skip(1) {
        for x in row.iter_mut().take(p + 1) {
            *x *= fac;
        }
        fac *= (p - k) as f64;
    }
    Some(ders)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::Rational;

    #[test]
    fn ders2_f64_is_ders_basis_funs_bit_for_bit() {
        let knots = [0.0, 0.0, 0.0, 0.0, 0.13, 0.5, 0.5, 0.71, 1.0, 1.0, 1.0, 1.0];
        let kv = KnotVector::new(knots.to_vec(), 3, 8).unwrap();
        let kv1 = KnotVector::new(vec![0.0, 0.0, 0.3, 1.0, 1.0], 1, 3).unwrap();
        let kv5 = KnotVector::new(
            vec![
                -1.0, -1.0, -1.0, -1.0, -1.0, -1.0, 0.2, 2.0, 2.0, 2.0, 2.0, 2.0, 2.0,
            ],
            5,
            7,
        )
        .unwrap();
        for kv in [&kv, &kv1, &kv5] {
            let (a, b) = kv.domain();
            for i in 0..=97 {
                let t = a + (b - a) * i as f64 / 97.0;
                let span = kv.find_span(&t);
                let g = ders_basis_funs(kv, span, &t, 2);
                let f = ders2_f64(kv, span, t).unwrap();
                for (k, row) in g.iter().enumerate() {
                    for (j, x) in row.iter().enumerate() {
                        assert_eq!(x.to_bits(), f[k][j].to_bits(), "t {t} k {k} j {j}");
                    }
                }
            }
        }
    }

    #[test]
    fn partition_of_unity_exact() {
        let kv = KnotVector::<Rational>::new(
            [0., 0., 0., 0., 0.25, 0.5, 0.5, 1., 1., 1., 1.]
                .iter()
                .map(|&x| crate::scalar::lift(x))
                .collect(),
            3,
            7,
        )
        .unwrap();
        for i in 0..=20 {
            let t: Rational = crate::scalar::lift(i as f64 / 20.0);
            let span = kv.find_span(&t);
            let n = basis_funs(&kv, span, &t);
            let s = n.iter().fold(Rational::ZERO, |a, b| a + b.clone());
            assert_eq!(s, Rational::ONE);
            let d = ders_basis_funs(&kv, span, &t, 2);
            assert_eq!(d[0].as_slice(), n.as_slice());
            let (n1, d1) = basis_funs_d1(&kv, span, &t);
            assert_eq!(n1.as_slice(), n.as_slice());
            assert_eq!(d1.as_slice(), d[1].as_slice());
            let s1 = d[1].iter().fold(Rational::ZERO, |a, b| a + b.clone());
            assert_eq!(s1, Rational::ZERO);
        }
    }
}
