//! Exact location of a point relative to a triangle in the plane (or in a triangle's own
//! plane in 3D, for coplanar points).

use super::orient::{dominant_axis, orient2d, project};
use crate::scalar::{Scalar, Sign};

/// Where a point lies relative to a closed triangle.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Location {
    Outside,
    Inside,
    /// On the relative interior of edge `i` (from vertex `i` to vertex `i+1 mod 3`).
    OnEdge(u8),
    /// At vertex `i`.
    OnVertex(u8),
    /// The triangle is degenerate (collinear vertices).
    Degenerate,
}

/// Locate `x` relative to triangle `t` in the plane. Exact.
pub fn point_in_triangle<S: Scalar>(t: &[[S; 2]; 3], x: &[S; 2]) -> Location {
    let o = orient2d(&t[0], &t[1], &t[2]);
    if o == Sign::Zero {
        return Location::Degenerate;
    }
    let s: [Sign; 3] = std::array::from_fn(|i| orient2d(&t[i], &t[(i + 1) % 3], x).times(o));
    from_edge_signs(s)
}

/// Location from the signs of `x` against each directed edge, with the interior positive.
pub fn from_edge_signs(s: [Sign; 3]) -> Location {
    if s.contains(&Sign::Negative) {
        return Location::Outside;
    }
    let zeros: Vec<usize> = (0..3).filter(|&i| s[i] == Sign::Zero).collect();
    match zeros.as_slice() {
        [] => Location::Inside,
        [i] => Location::OnEdge(*i as u8),
        // On edges i and j: at their common vertex.
        [0, 1] => Location::OnVertex(1),
        [1, 2] => Location::OnVertex(2),
        [0, 2] => Location::OnVertex(0),
        _ => Location::Degenerate,
    }
}

/// Locate `x`, assumed coplanar with the 3D triangle `t`, in the triangle. Exact: both are
/// projected onto the axis plane in which the triangle's projection is non-degenerate,
/// which preserves orientations up to one common sign.
pub fn point_in_triangle_3d<S: Scalar>(t: &[[S; 3]; 3], x: &[S; 3]) -> Location {
    match dominant_axis(t) {
        None => Location::Degenerate,
        Some((k, _)) => {
            let t2 = [project(&t[0], k), project(&t[1], k), project(&t[2], k)];
            point_in_triangle(&t2, &project(x, k))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    #[test]
    fn locations() {
        let t = [[0., 0.], [1., 0.], [0., 1.]];
        assert_eq!(point_in_triangle(&t, &[0.25, 0.25]), Location::Inside);
        assert_eq!(point_in_triangle(&t, &[0.5, 0.0]), Location::OnEdge(0));
        assert_eq!(point_in_triangle(&t, &[0.5, 0.5]), Location::OnEdge(1));
        assert_eq!(point_in_triangle(&t, &[1.0, 0.0]), Location::OnVertex(1));
        assert_eq!(point_in_triangle(&t, &[0.6, 0.5]), Location::Outside);
        let cw = [[0., 0.], [0., 1.], [1., 0.]];
        assert_eq!(point_in_triangle(&cw, &[0.25, 0.25]), Location::Inside);
        assert_eq!(
            point_in_triangle(&[[0., 0.], [1., 1.], [2., 2.]], &[0., 0.]),
            Location::Degenerate
        );
        let t3 = [[0., 0., 1.], [1., 0., 1.], [0., 1., 1.]];
        assert_eq!(
            point_in_triangle_3d(&t3, &[0.25, 0.25, 1.]),
            Location::Inside
        );
    }
}
