//! Step 6 — map each final chord to a Bézier curve of degree `p + q` lying exactly on S, by
//! blossoming (`spline::compose::compose_line`, DeRose): computed in exact arithmetic from
//! the exact patch, then rounded to f64 for output with the rounding error measured exactly.

use super::CosError;
use super::cells::Cells;
use super::segments::Seg;
use crate::curve_on_surface::CosInternal;
use crate::geom::to_f64_point;
use crate::scalar::Scalar;
use crate::spline::BezierCurve;
use crate::spline::compose::compose_line;
use num_rational::BigRational;

type Q = BigRational;

/// A mapped segment.
#[derive(Clone, Debug)]
pub struct MappedSegment {
    /// Exact control points (BigRational): the image of the chord, exactly.
    pub exact: BezierCurve<[Q; 3]>,
    /// The same, rounded to f64.
    pub control_points: Vec<[f64; 3]>,
    /// Chord end points in the domain.
    pub domain: [[f64; 2]; 2],
    pub cell: usize,
}

/// Map every segment; also returns the largest coordinate rounding error of the f64 output.
pub fn map_segments(segs: &[Seg], cells: &Cells) -> Result<(Vec<MappedSegment>, f64), CosError> {
    let zero = Q::from_integer(0.into());
    let one = Q::from_integer(1.into());
    let mut out = Vec::with_capacity(segs.len());
    let mut rounding = 0.0f64;
    for s in segs {
        let (a, b) = (cells.local(s.cell, &s.a), cells.local(s.cell, &s.b));
        // The chord must lie in its patch: then its image is on S exactly.
        for x in a.iter().chain(b.iter()) {
            if *x < zero || *x > one {
                return Err(CosInternal::ChordLeavesPatch { a: s.a, b: s.b }.into());
            }
        }
        let exact = compose_line(&cells.cells[s.cell].patch, &a, &b);
        let cps: Vec<[f64; 3]> = exact.control.iter().map(to_f64_point).collect();
        for (r, e) in cps.iter().zip(&exact.control) {
            for i in 0..3 {
                let d = (crate::scalar::lift::<Q>(r[i]) - e[i].clone())
                    .abs()
                    .to_f64()
                    .next_up();
                rounding = rounding.max(d);
            }
        }
        out.push(MappedSegment {
            exact,
            control_points: cps,
            domain: [s.a, s.b],
            cell: s.cell,
        });
    }
    Ok((out, rounding))
}
