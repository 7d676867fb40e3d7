//! Orientation predicates: each backend's own exact implementation (adaptive on f64).

use crate::scalar::{Scalar, Sign};

/// Sign of `det[b-a, c-a]`: positive when `a, b, c` turn counter-clockwise.
#[inline]
pub fn orient2d<S: Scalar>(a: &[S; 2], b: &[S; 2], c: &[S; 2]) -> Sign {
    S::orient2d(a, b, c)
}

/// Sign of `det[b-a, c-a, d-a]`: positive when `d` lies on the side of plane `abc` into which
/// `(b-a)×(c-a)` points.
#[inline]
pub fn orient3d<S: Scalar>(a: &[S; 3], b: &[S; 3], c: &[S; 3], d: &[S; 3]) -> Sign {
    S::orient3d(a, b, c, d)
}

/// Drop coordinate `k` (project onto the other two axes, in cyclic order so that the
/// projected orientation is the `k`-th component of the 3D cross product).
#[inline]
pub fn project<S: Scalar>(p: &[S; 3], k: usize) -> [S; 2] {
    [p[(k + 1) % 3].clone(), p[(k + 2) % 3].clone()]
}

/// An axis `k` along which the triangle's normal has a non-zero component, with the sign of
/// that component; `None` when the triangle is degenerate (collinear vertices). Exact: the
/// `k`-th normal component is the orientation of the projection dropping axis `k`.
pub fn dominant_axis<S: Scalar>(t: &[[S; 3]; 3]) -> Option<(usize, Sign)> {
    (0..3).find_map(|k| {
        let s = orient2d(&project(&t[0], k), &project(&t[1], k), &project(&t[2], k));
        (s != Sign::Zero).then_some((k, s))
    })
}
