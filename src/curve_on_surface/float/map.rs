//! Step 6, f64 path — map each chord to the Bézier curve of degree `p + q` on S by
//! blossoming, enclosed in interval arithmetic: the printed control points are the
//! enclosures' midpoints, within the proven `control_point_rounding` of the exact blossom
//! of the exact patch on the f64 chord (which lies on S exactly).

use super::cells::FCells;
use super::{FSeg, FloatError, Undecided};
use crate::curve_on_surface::CosInternal;

/// The printed control points (and weights, for a rational surface) of every segment, and
/// the largest rounding.
pub type Mapped = (Vec<(Vec<[f64; 3]>, Option<Vec<f64>>)>, f64);

/// Map every segment; also returns the largest coordinate distance between a printed control
/// point and the exact one (proven upper bound) — for a rational surface, the bound of
/// [`super::rational::RationalCell::compose_line`] on the distance between the printed
/// rational curve and the exact one.
pub fn map_segments(segs: &[FSeg], cells: &FCells) -> Result<Mapped, FloatError> {
    let mut out = Vec::with_capacity(segs.len());
    let mut rounding = 0.0f64;
    for s in segs {
        let c = cells.get(s.cell).map_err(FloatError::from)?;
        let inside = |p: &[f64; 2]| c.u0 <= p[0] && p[0] <= c.u1 && c.v0 <= p[1] && p[1] <= c.v1;
        if !inside(&s.a) || !inside(&s.b) {
            return Err(FloatError::Cos(
                CosInternal::ChordLeavesPatch { a: s.a, b: s.b }.into(),
            ));
        }
        // Local coordinates `(x - u0) / (u1 - u0)` in f64: two roundings in the operands and
        // one in the quotient give `|x̂ - x*| ≤ ((1 + u)² / (1 - u) - 1) x* ≤ 3.4e-16` for the
        // exact `x* ∈ [0, 1]` (the chord is in the cell); clamping to [0, 1] keeps that.
        let local = |x: f64, lo: f64, hi: f64| -> Option<f64> {
            let d = hi - lo;
            (d >= 1e-290).then(|| ((x - lo) / d).clamp(0.0, 1.0))
        };
        let (Some(a0), Some(a1), Some(b0), Some(b1)) = (
            local(s.a[0], c.u0, c.u1),
            local(s.a[1], c.v0, c.v1),
            local(s.b[0], c.u0, c.u1),
            local(s.b[1], c.v0, c.v1),
        ) else {
            return Err(FloatError::Undecided(Undecided::ZeroWidthPatch));
        };
        let dt = 3.4e-16 + 1e-30;
        let (cps, weights, err) = match &c.rational {
            None => {
                let (cps, err) = c.mpatch.compose_line([a0, a1], [b0, b1], dt);
                (cps, None, err)
            }
            Some(r) => match r.compose_line(&c.mpatch, [a0, a1], [b0, b1], dt) {
                Some((cps, w, err)) => (cps, Some(w), err),
                None => return Err(FloatError::Undecided(Undecided::MappingOverflow)),
            },
        };
        let finite = |x: &f64| x.is_finite();
        if !err.is_finite()
            || !cps.iter().flatten().all(finite)
            || !weights.iter().flatten().all(finite)
        {
            return Err(FloatError::Undecided(Undecided::MappingOverflow));
        }
        rounding = rounding.max(err);
        out.push((cps, weights));
    }
    Ok((out, rounding))
}
