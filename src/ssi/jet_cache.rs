//! Jacobian enclosures shared by nearby points of a branch, for the curve certificate
//! ([`super::krawczyk`]). Krawczyk's test needs an interval matrix `J` holding the Jacobian
//! over the point's box `X` (the mean-value form). An enclosure over a larger box `B ⊇ X` is
//! one too (interval evaluation is inclusion monotone): consecutive output points lie close
//! together, so one enclosure of both surfaces' first derivatives over the parameter hull of
//! a few consecutive points, grown by a margin, serves every one of their boxes that it holds.
//! The wider `J` only widens `K(X)` by `|Y| · width(J) · rad(X)`; where the test fails with it,
//! the point is tried again with `J` over its own box, so no certificate is lost.

use super::enclose::{Jet, enclose_jet};
use crate::scalar::Interval;
use crate::spline::NurbsSurface;

/// Enclosures of `S_A`, `S_B` and their first derivatives over a parameter box `(u, v, s, t)`.
pub struct JetCache {
    pub boxes: [Interval; 4],
    pub jets: [Jet; 2],
}

/// The margin the hull is grown by, relative to each domain's width.
const MARGIN: f64 = 1e-6;
/// Hulls wider than this part of a domain get no cache (the enclosure would be wide).
const MAX_WIDTH: f64 = 1e-2;

impl JetCache {
    /// The enclosures over the hull of the parameter points `uvs` (`(uv_a, uv_b)` each),
    /// grown by `MARGIN` of the domains; `None` for no points, non-finite parameters, a hull
    /// wider than `MAX_WIDTH` of a domain, or a failed enclosure.
    pub fn over(
        sa: &NurbsSurface<f64, 3>,
        sb: &NurbsSurface<f64, 3>,
        uvs: impl Iterator<Item = ([f64; 2], [f64; 2])>,
    ) -> Option<JetCache> {
        let (a0, a1, a2, a3) = sa.hom.domain();
        let (b0, b1, b2, b3) = sb.hom.domain();
        let width = [a1 - a0, a3 - a2, b1 - b0, b3 - b2];
        let mut lo = [f64::INFINITY; 4];
        let mut hi = [f64::NEG_INFINITY; 4];
        for (ua, ub) in uvs {
            let z = [ua[0], ua[1], ub[0], ub[1]];
            for k in 0..4 {
                lo[k] = lo[k].min(z[k]);
                hi[k] = hi[k].max(z[k]);
            }
        }
        let mut boxes = [Interval::point(0.0); 4];
        for k in 0..4 {
            let m = MARGIN * width[k];
            if !(lo[k].is_finite() && hi[k].is_finite() && m.is_finite())
                || hi[k] - lo[k] > MAX_WIDTH * width[k]
            {
                return None;
            }
            boxes[k] = Interval::new(lo[k] - m, hi[k] + m);
        }
        let ja = enclose_jet(sa, boxes[0], boxes[1])?;
        let jb = enclose_jet(sb, boxes[2], boxes[3])?;
        Some(JetCache {
            boxes,
            jets: [ja, jb],
        })
    }

    /// Whether the box `x` lies inside the cached box.
    pub fn covers(&self, x: &[Interval; 4]) -> bool {
        (0..4).all(|k| self.boxes[k].lo <= x[k].lo && x[k].hi <= self.boxes[k].hi)
    }
}
