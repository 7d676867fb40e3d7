//! Step 6, f64 path — map each chord to the Bézier curve of degree `p + q` on S by
//! blossoming, enclosed in interval arithmetic: the printed control points are the
//! enclosures' midpoints, within the proven `control_point_rounding` of the exact blossom
//! of the exact patch on the f64 chord (which lies on S exactly).

use super::cells::FCells;
use super::ibez::{I, IP, mid};
use super::{FSeg, FloatError};
use crate::curve_on_surface::CosError;

/// The printed control points of every segment, and the largest rounding.
pub type Mapped = (Vec<Vec<[f64; 3]>>, f64);

/// Map every segment; also returns the largest coordinate distance between a printed control
/// point and the exact one (proven upper bound).
pub fn map_segments(segs: &[FSeg], cells: &FCells) -> Result<Mapped, FloatError> {
    let mut out = Vec::with_capacity(segs.len());
    let mut rounding = 0.0f64;
    for s in segs {
        let c = cells
            .get(s.cell)
            .map_err(|e| FloatError::Cos(CosError::Internal(e.0)))?;
        let inside = |p: &[f64; 2]| c.u0 <= p[0] && p[0] <= c.u1 && c.v0 <= p[1] && p[1] <= c.v1;
        if !inside(&s.a) || !inside(&s.b) {
            return Err(FloatError::Cos(CosError::Internal(format!(
                "chord {:?} -> {:?} leaves its patch",
                s.a, s.b
            ))));
        }
        let local = |p: &[f64; 2]| -> Option<IP<2>> {
            Some([
                (I::point(p[0]) - I::point(c.u0)).checked_div(I::point(c.u1) - I::point(c.u0))?,
                (I::point(p[1]) - I::point(c.v0)).checked_div(I::point(c.v1) - I::point(c.v0))?,
            ])
        };
        let (Some(a), Some(b)) = (local(&s.a), local(&s.b)) else {
            return Err(FloatError::Undecided("a patch of zero width".into()));
        };
        let enc = c.patch.compose_line(&a, &b);
        for q in &enc {
            for x in q {
                if !x.is_finite() {
                    return Err(FloatError::Undecided("overflow in the mapping".into()));
                }
                rounding = rounding.max(x.radius_about_mid());
            }
        }
        out.push(enc.iter().map(mid).collect());
    }
    Ok((out, rounding))
}
