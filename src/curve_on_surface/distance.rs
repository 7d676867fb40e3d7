//! Step 4 loop — subdivide at the farthest point until every piece is within its cell's `d`
//! (the certified Hausdorff bound of [`super::hausdorff`]).

use super::cells::Cells;
use super::hausdorff::{farthest_parameter, hausdorff_bound};
use super::segments::Seg;
use super::tolerance::local_lipschitz;
use super::{Bound, CosError};
use crate::scalar::Rational;
use crate::spline::BezierCurve;

type Q = Rational;

/// The Lipschitz constant used for a segment: eq. (12) per patch, or the local refinement
/// on the segment's bounding rectangle (local patch coordinates, clamped to the patch).
fn lipschitz(s: &Seg, c: &BezierCurve<[Q; 2]>, cells: &Cells, bound: Bound) -> f64 {
    let cell = &cells.cells[s.cell];
    match bound {
        Bound::PaperEq12 => cell.lipschitz,
        Bound::Local => {
            // Bounding rectangle of the piece's control points and the chord, in local patch
            // coordinates, rounded outward to f64 and clamped to the patch.
            let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
            let spans = [(cell.u0, cell.u1), (cell.v0, cell.v1)];
            for p in &c.control {
                for i in 0..2 {
                    let x = crate::Scalar::to_f64(&p[i]);
                    lo[i] = lo[i].min(x.next_down());
                    hi[i] = hi[i].max(x.next_up());
                }
            }
            for p in [&s.a, &s.b] {
                for i in 0..2 {
                    lo[i] = lo[i].min(p[i]);
                    hi[i] = hi[i].max(p[i]);
                }
            }
            // Rounded outward to the 2^-16 grid: the rectangle only grows (still a valid
            // region for the bound) and its short dyadic corners keep the exact blossoms cheap.
            let local = |x: f64, (a, b): (f64, f64), up: bool| {
                let y = (x - a) / (b - a);
                let g = 65536.0;
                let y = if up {
                    (y.next_up().next_up() * g).ceil() / g
                } else {
                    (y.next_down().next_down() * g).floor() / g
                };
                crate::scalar::lift::<Q>(y.clamp(0.0, 1.0))
            };
            let r = [
                local(lo[0], spans[0], false),
                local(hi[0], spans[0], true),
                local(lo[1], spans[1], false),
                local(hi[1], spans[1], true),
            ];
            let (du, dv) = (cell.u1 - cell.u0, cell.v1 - cell.v0);
            let k = local_lipschitz(
                cell.hodo_u.as_ref(),
                cell.hodo_v.as_ref(),
                r.clone(),
                du,
                dv,
            );
            let k = match &cell.rational {
                None => k,
                Some(w) => w.lipschitz(
                    k,
                    local_lipschitz(w.w_hodo_u.as_ref(), w.w_hodo_v.as_ref(), r, du, dv),
                ),
            };
            k.min(cell.lipschitz)
        }
    }
}

/// Compute `h` (and `K`) for every segment whose bound is unknown; split those with
/// `K · h > ε_D` at their farthest point.
pub fn enforce_distance(
    mut segs: Vec<Seg>,
    pieces: &[BezierCurve<[Q; 2]>],
    cells: &Cells,
    eps_d: f64,
    bound: Bound,
    max_segments: usize,
) -> Result<Vec<Seg>, CosError> {
    loop {
        let mut out = Vec::with_capacity(segs.len());
        let mut changed = false;
        for mut s in segs {
            // The exact sub-curve is built at most once per segment and pass.
            let mut curve = None;
            if s.h.is_infinite() {
                let c = curve.insert(s.curve(pieces));
                s.k = lipschitz(&s, c, cells, bound);
                let d = super::tolerance::tolerance_2d(eps_d, s.k);
                s.h = hausdorff_bound(c, &s.a, &s.b, s.ea.max(s.eb), d);
            }
            if (s.k * s.h).next_up() <= eps_d {
                out.push(s);
            } else {
                changed = true;
                let c = curve.unwrap_or_else(|| s.curve(pieces));
                let (l, r) = s.split(&farthest_parameter(&c), pieces, cells);
                out.push(l);
                out.push(r);
            }
        }
        if out.len() > max_segments {
            return Err(CosError::TooManySegments(max_segments));
        }
        segs = out;
        if !changed {
            return Ok(segs);
        }
    }
}
