//! Degree elevation and knot refinement of B-spline curves and surfaces, both exact in exact
//! arithmetic (on `f64` the new control points carry the rounding of a few affine
//! combinations).
//!
//! * Degree elevation by one (The NURBS Book §5.5, by blossoming): the elevated curve has
//!   every distinct knot's multiplicity raised by one, and its control point `Q_i` is the
//!   blossom of the elevated polynomial piece at `t'_{i+1}, …, t'_{i+p+1}`, which is the
//!   average of the original piece's blossom over the `p + 1` ways of leaving one argument
//!   out (Ramshaw's symmetrization). Any polynomial piece whose span lies in the support of
//!   `N'_i` gives the same value; the span nearest the middle of the support is used.
//! * Refinement to a knot vector: Boehm insertion of every knot of the target that the curve
//!   lacks (the target must contain the curve's knots with at least their multiplicities).
//!
//! Surfaces are elevated or refined in one direction by doing so on every row or column.

use super::bspline_curve::BSplineCurve;
use super::bspline_surface::BSplineSurface;
use super::knots::KnotVector;
use crate::geom::Point;
use crate::scalar::Scalar;

/// Blossom of the polynomial piece of `c` on the non-empty span `k`
/// (`knots[k] <= t < knots[k+1]`) at the `p` arguments `xs` (de Boor's algorithm with one
/// argument per level).
fn piece_blossom<P: Point>(c: &BSplineCurve<P>, k: usize, xs: &[P::S]) -> P {
    let p = c.degree();
    let u = c.knots.knots();
    let mut d: Vec<P> = c.control[k - p..=k].to_vec();
    for r in 1..=p {
        for j in (r..=p).rev() {
            let i = k - p + j;
            let a = (xs[r - 1].clone() - u[i].clone()) / (u[i + p + 1 - r].clone() - u[i].clone());
            d[j] = d[j - 1].lerp(&d[j], &a);
        }
    }
    d.swap_remove(p)
}

/// Distinct values of a sorted knot sequence with their multiplicities.
pub fn runs<S: Scalar>(k: &[S]) -> Vec<(S, usize)> {
    let mut out: Vec<(S, usize)> = Vec::new();
    for x in k {
        match out.last_mut() {
            Some((v, m)) if v == x => *m += 1,
            _ => out.push((x.clone(), 1)),
        }
    }
    out
}

/// The curve raised by one degree, the same curve (exactly so in exact arithmetic).
pub fn elevate_curve<P: Point>(c: &BSplineCurve<P>) -> BSplineCurve<P> {
    let p = c.degree();
    let mut nk: Vec<P::S> = Vec::with_capacity(c.knots.len() * 2);
    for (v, m) in runs(c.knots.knots()) {
        nk.extend(std::iter::repeat_n(v, m + 1));
    }
    let q = p + 1;
    let n_new = nk.len() - q - 1;
    let (lo, hi) = c.knots.domain();
    let two = P::S::from_i64(2);
    let control: Vec<P> = (0..n_new)
        .map(|i| {
            // Non-empty spans of the new knots inside the support [t'_i, t'_{i+q+1}) and
            // inside the domain; the one nearest the middle of the support.
            let cands: Vec<usize> = (i..=i + q)
                .filter(|&j| nk[j] < nk[j + 1] && nk[j] >= lo && nk[j + 1] <= hi)
                .collect();
            let j = match cands.get(cands.len() / 2) {
                Some(&j) => j,
                // Unclamped ends: any non-empty span of the support (there is one, since no
                // new multiplicity exceeds the new degree plus one).
                None => (i..=i + q).find(|&j| nk[j] < nk[j + 1]).unwrap_or(i),
            };
            let mid = (nk[j].clone() + nk[j + 1].clone()) / two.clone();
            let k = c.knots.find_span(&mid);
            let args = &nk[i + 1..=i + q];
            let mut acc = P::origin();
            for leave in 0..q {
                let xs: Vec<P::S> = args
                    .iter()
                    .enumerate()
                    .filter(|(m, _)| *m != leave)
                    .map(|(_, x)| x.clone())
                    .collect();
                acc = acc.add(&piece_blossom(c, k, &xs));
            }
            acc.scale(&(P::S::one() / P::S::from_i64(q as i64)))
        })
        .collect();
    let mut control: Vec<P> = control;
    // Clamped ends: the end control points are the curve's ends, kept as they are (the
    // symmetrization would give them back only up to rounding).
    let k = c.knots.knots();
    if k[..=p].iter().all(|x| *x == k[0]) {
        control[0] = c.control[0].clone();
    }
    if k[k.len() - p - 1..].iter().all(|x| *x == k[k.len() - 1]) {
        let last = control.len() - 1;
        control[last] = c.control[c.control.len() - 1].clone();
    }
    BSplineCurve {
        knots: KnotVector::new_unchecked(nk, q),
        control,
    }
}

/// The curve raised to degree `d` (unchanged when its degree is already at least `d`).
pub fn elevate_curve_to<P: Point>(c: &BSplineCurve<P>, d: usize) -> BSplineCurve<P> {
    let mut c = c.clone();
    while c.degree() < d {
        c = elevate_curve(&c);
    }
    c
}

/// The curve with knot vector `target` (Boehm insertion of the missing knots); `None` when
/// `target` lacks one of the curve's knots (value and multiplicity) or has another degree's
/// end multiplicities.
pub fn refine_to<P: Point>(c: &BSplineCurve<P>, target: &[P::S]) -> Option<BSplineCurve<P>> {
    let have = runs(c.knots.knots());
    let want = runs(target);
    let mut out = c.clone();
    let mut h = have.iter().peekable();
    for (v, m) in &want {
        let cur = match h.peek() {
            Some((x, n)) if x == v => {
                h.next();
                *n
            }
            _ => 0,
        };
        if cur > *m {
            return None;
        }
        if cur < *m {
            out = out.insert_knot(v, m - cur);
        }
    }
    if h.next().is_some() || out.knots.knots() != target {
        return None;
    }
    Some(out)
}

fn columns<P: Point>(s: &BSplineSurface<P>) -> Vec<BSplineCurve<P>> {
    (0..s.nv()).map(|j| s.column(j)).collect()
}

fn rows<P: Point>(s: &BSplineSurface<P>) -> Vec<BSplineCurve<P>> {
    (0..s.nu()).map(|i| s.row(i)).collect()
}

fn from_columns<P: Point>(kv: KnotVector<P::S>, cols: Vec<BSplineCurve<P>>) -> BSplineSurface<P> {
    let ku = cols[0].knots.clone();
    let nu = cols[0].control.len();
    let mut net = Vec::with_capacity(nu * cols.len());
    for i in 0..nu {
        for c in &cols {
            net.push(c.control[i].clone());
        }
    }
    BSplineSurface { ku, kv, net }
}

fn from_rows<P: Point>(ku: KnotVector<P::S>, rs: Vec<BSplineCurve<P>>) -> BSplineSurface<P> {
    let kv = rs[0].knots.clone();
    BSplineSurface {
        ku,
        kv,
        net: rs.into_iter().flat_map(|r| r.control).collect(),
    }
}

/// The surface raised to degree `d` in u (`dir == 0`) or v (`dir == 1`).
pub fn elevate_surface_to<P: Point>(
    s: &BSplineSurface<P>,
    dir: usize,
    d: usize,
) -> BSplineSurface<P> {
    if dir == 0 {
        let cols = columns(s).iter().map(|c| elevate_curve_to(c, d)).collect();
        from_columns(s.kv.clone(), cols)
    } else {
        let rs = rows(s).iter().map(|c| elevate_curve_to(c, d)).collect();
        from_rows(s.ku.clone(), rs)
    }
}

/// The surface with knot vector `target` in u (`dir == 0`) or v (`dir == 1`), see
/// [`refine_to`].
pub fn refine_surface_to<P: Point>(
    s: &BSplineSurface<P>,
    dir: usize,
    target: &[P::S],
) -> Option<BSplineSurface<P>> {
    if dir == 0 {
        let cols: Option<Vec<_>> = columns(s).iter().map(|c| refine_to(c, target)).collect();
        Some(from_columns(s.kv.clone(), cols?))
    } else {
        let rs: Option<Vec<_>> = rows(s).iter().map(|c| refine_to(c, target)).collect();
        Some(from_rows(s.ku.clone(), rs?))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::Rational;
    type Q = Rational;
    fn q(x: f64) -> Q {
        crate::scalar::lift(x)
    }

    fn curve() -> BSplineCurve<[Q; 2]> {
        let k = [0., 0., 0., 0.25, 0.6, 0.6, 1., 1., 1.];
        let pts = [[0., 0.], [1., 2.], [2., -1.], [3., 3.], [4., 0.5], [5., 1.]];
        BSplineCurve::new(
            k.iter().map(|&x| q(x)).collect(),
            2,
            pts.iter().map(|p| [q(p[0]), q(p[1])]).collect(),
        )
        .unwrap()
    }

    #[test]
    fn elevation_and_refinement_are_exact() {
        let c = curve();
        let e = elevate_curve_to(&c, 4);
        assert_eq!(e.degree(), 4);
        // Every distinct knot two more times (ends included).
        assert_eq!(e.knots.len(), c.knots.len() + 2 * 4);
        let mut target: Vec<Q> = e.knots.knots().to_vec();
        for x in [0.1, 0.25, 0.8, 0.8] {
            target.push(q(x));
        }
        target.sort();
        let r = refine_to(&e, &target).unwrap();
        for i in 0..=40 {
            let t = q(i as f64 / 40.0);
            assert_eq!(e.eval(&t), c.eval(&t));
            assert_eq!(r.eval(&t), c.eval(&t));
        }
        // A target lacking one of the curve's knots is refused.
        assert!(refine_to(&c, &[q(0.), q(0.), q(0.), q(1.), q(1.), q(1.)]).is_none());
    }
}
