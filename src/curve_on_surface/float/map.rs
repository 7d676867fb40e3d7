//! Step 6, f64 path — map each chord to the Bézier curve of degree `p + q` on S by
//! blossoming, enclosed in interval arithmetic: the printed control points are the
//! enclosures' midpoints, within the proven `control_point_rounding` of the exact blossom
//! of the exact patch on the f64 chord (which lies on S exactly).

use super::cells::FCells;
use super::ibez::{I, IP};
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
        // Local coordinates, enclosed; the exact ones lie in [0, 1] (the chord is in the
        // cell), so the clamped midpoint is within the radius of them.
        let local = |p: &[f64; 2]| -> Option<(IP<2>, [f64; 2], f64)> {
            let x: IP<2> = [
                (I::point(p[0]) - I::point(c.u0)).checked_div(I::point(c.u1) - I::point(c.u0))?,
                (I::point(p[1]) - I::point(c.v0)).checked_div(I::point(c.v1) - I::point(c.v0))?,
            ];
            let m = [x[0].mid().clamp(0.0, 1.0), x[1].mid().clamp(0.0, 1.0)];
            let dt = x[0].radius_about_mid().max(x[1].radius_about_mid());
            Some((x, m, dt))
        };
        let (Some((_, a, da)), Some((_, b, db))) = (local(&s.a), local(&s.b)) else {
            return Err(FloatError::Undecided("a patch of zero width".into()));
        };
        let (cps, err) = c.mpatch.compose_line(a, b, da.max(db));
        if !err.is_finite() || cps.iter().flatten().any(|x| !x.is_finite()) {
            return Err(FloatError::Undecided("overflow in the mapping".into()));
        }
        rounding = rounding.max(err);
        out.push(cps);
    }
    Ok((out, rounding))
}
