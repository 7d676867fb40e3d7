//! Where a segment meets the plane of a triangle, decided exactly.

use super::orient::orient3d;
use crate::scalar::{Scalar, Sign};

/// Exact relation of segment `ab` to the plane of triangle `pqr`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SegmentPlane {
    /// Both end points strictly on one side.
    Disjoint,
    /// The end points lie strictly on opposite sides: the segment crosses the plane at one
    /// interior point.
    Crosses,
    /// Exactly one end point lies in the plane (`0` for `a`, `1` for `b`).
    TouchesAt(u8),
    /// Both end points lie in the plane.
    InPlane,
}

/// Classify `ab` against the plane of `pqr` (signs by the exact `orient3d`).
pub fn segment_plane<S: Scalar>(
    a: &[S; 3],
    b: &[S; 3],
    p: &[S; 3],
    q: &[S; 3],
    r: &[S; 3],
) -> SegmentPlane {
    let sa = orient3d(p, q, r, a);
    let sb = orient3d(p, q, r, b);
    classify(sa, sb)
}

/// Classification from the two exact signs.
pub fn classify(sa: Sign, sb: Sign) -> SegmentPlane {
    match (sa, sb) {
        (Sign::Zero, Sign::Zero) => SegmentPlane::InPlane,
        (Sign::Zero, _) => SegmentPlane::TouchesAt(0),
        (_, Sign::Zero) => SegmentPlane::TouchesAt(1),
        (x, y) if x == y => SegmentPlane::Disjoint,
        _ => SegmentPlane::Crosses,
    }
}
