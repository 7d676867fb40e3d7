//! Points and vectors over a [`Scalar`]: `[S; D]` for Cartesian points and [`Hom`] for
//! homogeneous (weighted) points of rational curves and surfaces. Both implement [`Point`],
//! the affine-combination interface the spline kernel is written against, so one
//! de Casteljau / de Boor routine serves polynomial and rational geometry on every backend.

mod aabb;
pub mod bvh;
pub mod tri_tree;
pub mod triangle;
pub use aabb::Aabb;

use crate::scalar::{RealScalar, Scalar};

/// What the spline kernel needs of a control point: a vector space over `S`.
pub trait Point: Clone + std::fmt::Debug + PartialEq + Send + Sync + 'static {
    type S: Scalar;
    fn origin() -> Self;
    fn add(&self, o: &Self) -> Self;
    fn sub(&self, o: &Self) -> Self;
    fn scale(&self, s: &Self::S) -> Self;
    /// `(1-t) a + t b`, written as `a + t (b - a)`.
    fn lerp(&self, o: &Self, t: &Self::S) -> Self {
        self.add(&o.sub(self).scale(t))
    }
    /// Affine combination `(b - t) / (b - a) * self + (t - a) / (b - a) * o`
    /// where the caller guarantees `a != b`.
    fn lerp_on(&self, o: &Self, a: &Self::S, b: &Self::S, t: &Self::S) -> Self {
        let w = (t.clone() - a.clone()) / (b.clone() - a.clone());
        self.lerp(o, &w)
    }
    /// Coordinates, for conversion and finiteness checks.
    fn coords(&self) -> Vec<Self::S>;
}

impl<S: Scalar, const D: usize> Point for [S; D] {
    type S = S;
    #[inline(always)]
    fn origin() -> Self {
        std::array::from_fn(|_| S::zero())
    }
    #[inline(always)]
    fn add(&self, o: &Self) -> Self {
        std::array::from_fn(|i| self[i].clone() + o[i].clone())
    }
    #[inline(always)]
    fn sub(&self, o: &Self) -> Self {
        std::array::from_fn(|i| self[i].clone() - o[i].clone())
    }
    #[inline(always)]
    fn scale(&self, s: &S) -> Self {
        std::array::from_fn(|i| self[i].clone() * s.clone())
    }
    fn coords(&self) -> Vec<S> {
        self.to_vec()
    }
}

/// A homogeneous point `(w·x, w)`: the weighted control point of a rational curve or
/// surface. Affine combinations of `Hom` points followed by [`Hom::project`] give NURBS
/// evaluation (The NURBS Book, §4.2).
#[derive(Clone, Debug, PartialEq)]
pub struct Hom<S: Scalar, const D: usize> {
    /// `w · x`.
    pub wp: [S; D],
    /// `w`.
    pub w: S,
}

impl<S: Scalar, const D: usize> Hom<S, D> {
    /// Weighted point from a Cartesian point and its weight.
    pub fn from_point(p: &[S; D], w: &S) -> Self {
        Hom {
            wp: p.scale(w),
            w: w.clone(),
        }
    }
    /// Cartesian point `wp / w`; `None` when `w == 0`.
    pub fn project(&self) -> Option<[S; D]> {
        if self.w.is_zero() {
            return None;
        }
        Some(std::array::from_fn(|i| self.wp[i].clone() / self.w.clone()))
    }
}

impl<S: Scalar, const D: usize> Point for Hom<S, D> {
    type S = S;
    fn origin() -> Self {
        Hom {
            wp: <[S; D]>::origin(),
            w: S::zero(),
        }
    }
    fn add(&self, o: &Self) -> Self {
        Hom {
            wp: self.wp.add(&o.wp),
            w: self.w.clone() + o.w.clone(),
        }
    }
    fn sub(&self, o: &Self) -> Self {
        Hom {
            wp: self.wp.sub(&o.wp),
            w: self.w.clone() - o.w.clone(),
        }
    }
    fn scale(&self, s: &S) -> Self {
        Hom {
            wp: self.wp.scale(s),
            w: self.w.clone() * s.clone(),
        }
    }
    fn coords(&self) -> Vec<S> {
        let mut v = self.wp.to_vec();
        v.push(self.w.clone());
        v
    }
}

/// Dot product.
pub fn dot<S: Scalar, const D: usize>(a: &[S; D], b: &[S; D]) -> S {
    let mut s = S::zero();
    for i in 0..D {
        s = s + a[i].clone() * b[i].clone();
    }
    s
}

/// Cross product in 3D.
pub fn cross<S: Scalar>(a: &[S; 3], b: &[S; 3]) -> [S; 3] {
    [
        a[1].clone() * b[2].clone() - a[2].clone() * b[1].clone(),
        a[2].clone() * b[0].clone() - a[0].clone() * b[2].clone(),
        a[0].clone() * b[1].clone() - a[1].clone() * b[0].clone(),
    ]
}

/// 2D cross product (z component): `a.x b.y - a.y b.x`.
pub fn cross2<S: Scalar>(a: &[S; 2], b: &[S; 2]) -> S {
    a[0].clone() * b[1].clone() - a[1].clone() * b[0].clone()
}

/// Squared Euclidean norm.
pub fn norm2<S: Scalar, const D: usize>(a: &[S; D]) -> S {
    dot(a, a)
}

/// Euclidean norm (rounded for the real backends).
pub fn norm<S: RealScalar, const D: usize>(a: &[S; D]) -> S {
    norm2(a).sqrt()
}

/// Euclidean distance.
pub fn dist<S: RealScalar, const D: usize>(a: &[S; D], b: &[S; D]) -> S {
    norm(&a.sub(b))
}

/// A well-spread triple of `pts`: the first point, the point farthest from it, and the point
/// farthest from the line through those two (of equally far ones, the last); `None` when
/// `pts` is empty. Collinear points give a degenerate triple.
pub fn spread_triple(pts: &[[f64; 3]]) -> Option<[[f64; 3]; 3]> {
    let &p0 = pts.first()?;
    let far = |key: &dyn Fn(&[f64; 3]) -> f64| {
        pts.iter()
            .copied()
            .max_by(|a, b| key(a).total_cmp(&key(b)))
            .unwrap_or(p0)
    };
    let p1 = far(&|p| norm2(&p.sub(&p0)));
    let e = p1.sub(&p0);
    let p2 = far(&|p| norm2(&cross(&e, &p.sub(&p0))));
    Some([p0, p1, p2])
}

/// Distance from `x` to the segment `pq` (to `p` when the segment is a point).
pub fn dist_to_segment<S: RealScalar, const D: usize>(x: &[S; D], p: &[S; D], q: &[S; D]) -> S {
    let d = q.sub(p);
    let l2 = norm2(&d);
    let t = if l2.sign() == crate::scalar::Sign::Positive {
        let t = dot(&x.sub(p), &d) / l2;
        if t < S::zero() {
            S::zero()
        } else if t > S::one() {
            S::one()
        } else {
            t
        }
    } else {
        S::zero()
    };
    dist(x, &p.add(&d.scale(&t)))
}

/// Lift an `f64` point exactly into another backend.
pub fn lift_point<S: Scalar, const D: usize>(p: &[f64; D]) -> [S; D] {
    std::array::from_fn(|i| crate::scalar::lift(p[i]))
}

/// Nearest `f64` point.
pub fn to_f64_point<S: Scalar, const D: usize>(p: &[S; D]) -> [f64; D] {
    std::array::from_fn(|i| p[i].to_f64())
}
