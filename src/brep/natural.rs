//! Which faces are bounded by their surface's own parameter rectangle (*natural* faces, as a
//! patch of a patch set is) and which are trimmed inside it.
//!
//! A face is natural when it has one loop, every edge of the loop lies along the border of
//! its surface's parameter rectangle, and the edges together run along each of the four
//! sides — except sides that collapse to a point (poles) and, on a closed surface, the pair
//! of sides that meet at the seam (one of them suffices). "Lies along the border" is decided
//! at [`SAMPLES`] points of each edge's 3D curve, each taken to the surface's parameters by a
//! closest-point search ([`crate::spline::project::SurfaceFoot`]) and compared with the
//! border within [`RELATIVE`] of the rectangle's extent. This is a classification (which
//! repair applies to a face), made at samples: evidence, not a proof; every face it calls
//! trimmed is named in the reports that use it.

use super::{Brep, LoopKind};
use crate::model::Model;
use crate::spline::closure::Closure;
use crate::spline::project::SurfaceFoot;

/// Points of each edge taken to the surface's parameters.
pub const SAMPLES: usize = 5;
/// Distance from a side, relative to the rectangle's extent in that direction, within which
/// a parameter point counts as on it.
pub const RELATIVE: f64 = 1e-6;

/// Per face of `b`: whether it is bounded by its surface's parameter rectangle (see the
/// module comment). A face without a surface, a 3D curve on some edge or any loop is not.
pub fn natural_faces(b: &Brep, m: &Model) -> Vec<bool> {
    b.faces
        .iter()
        .map(|f| {
            let Some(s) = f.surface.and_then(|s| m.surfaces.get(s)) else {
                return false;
            };
            let [l] = &f.loops[..] else {
                return false;
            };
            let LoopKind::Edges(oes) = &l.kind else {
                return false;
            };
            let curves: Option<Vec<_>> = oes
                .iter()
                .map(|oe| {
                    b.edges
                        .get(oe.edge)
                        .and_then(|e| e.curve.as_ref())
                        .map(|c| &c.nurbs)
                })
                .collect();
            let Some(curves) = curves else {
                return false;
            };
            let nurbs = &s.nurbs;
            let (u0, u1, v0, v1) = nurbs.hom.domain();
            let d = [u0, u1, v0, v1];
            let eps = [RELATIVE * (u1 - u0), RELATIVE * (v1 - v0)];
            let mut foot = SurfaceFoot::new(nurbs);
            // Per side (u = u0, u = u1, v = v0, v = v1): the spans of the other parameter
            // that edges lying on it cover.
            let mut spans: [Vec<(f64, f64)>; 4] = Default::default();
            for c in curves {
                let (t0, t1) = c.hom.domain();
                let uv: Vec<[f64; 2]> = (0..SAMPLES)
                    .map(|i| {
                        let t = t0 + (t1 - t0) * i as f64 / (SAMPLES - 1) as f64;
                        foot.closest(&c.eval(&t))
                    })
                    .collect();
                let mut on_some = false;
                for (side, span) in spans.iter_mut().enumerate() {
                    let (k, other) = (side / 2, 1 - side / 2);
                    if uv.iter().all(|p| (p[k] - d[side]).abs() <= eps[k]) {
                        on_some = true;
                        let lo = uv.iter().map(|p| p[other]).fold(f64::INFINITY, f64::min);
                        let hi = uv
                            .iter()
                            .map(|p| p[other])
                            .fold(f64::NEG_INFINITY, f64::max);
                        span.push((lo, hi));
                    }
                }
                if !on_some {
                    return false;
                }
            }
            let closure = Closure::of(nurbs);
            let covered = |side: usize| {
                let other = 1 - side / 2;
                covers(
                    &mut spans[side].clone(),
                    (d[2 * other], d[2 * other + 1]),
                    eps[other],
                )
            };
            let side_ok = |side: usize| closure.degenerate[side] || covered(side);
            let pair_ok = |a: usize, seam: bool| {
                if seam {
                    side_ok(a) || side_ok(a + 1)
                } else {
                    side_ok(a) && side_ok(a + 1)
                }
            };
            pair_ok(0, closure.seam_u) && pair_ok(2, closure.seam_v)
        })
        .collect()
}

/// Whether the union of `spans` covers `[lo, hi]` with gaps of at most `eps`.
fn covers(spans: &mut [(f64, f64)], (lo, hi): (f64, f64), eps: f64) -> bool {
    spans.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut reach = lo;
    for &(a, b) in spans.iter() {
        if a > reach + eps {
            return false;
        }
        reach = reach.max(b);
    }
    reach >= hi - eps
}

#[cfg(test)]
mod tests {
    use super::covers;

    #[test]
    fn spans_cover_only_without_gaps() {
        assert!(covers(&mut [(0.5, 1.0), (0.0, 0.5)], (0.0, 1.0), 1e-9));
        assert!(!covers(&mut [(0.0, 0.4), (0.6, 1.0)], (0.0, 1.0), 1e-9));
        assert!(!covers(&mut [(0.0, 0.9)], (0.0, 1.0), 1e-9));
        assert!(!covers(&mut [], (0.0, 1.0), 1e-9));
    }
}
