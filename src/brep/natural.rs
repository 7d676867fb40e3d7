//! Which faces are bounded by their surface's own parameter rectangle (*natural* faces, as a
//! patch of a patch set is) and which are trimmed inside it.
//!
//! A face is natural when every edge of its loops lies along the border of its surface's
//! parameter rectangle, every vertex loop at a pole, and the edges together run along each of
//! the four sides — except sides that collapse to a point (poles) and, on a closed surface,
//! the pair of sides that meet at the seam: they are one curve inside the face, which a seam
//! edge may follow or not (a closed surface's whole face often has one loop per end and no
//! seam edge: a cylinder between two circles). A loop inside the rectangle has edges off its
//! border, so a face with a hole is trimmed. "Lies along the border" is decided
//! at [`SAMPLES`] points of each edge's 3D curve and at its knot spans' ends and middles
//! (`sample_parameters`), each taken to the surface's parameters by a
//! closest-point search ([`crate::spline::project::SurfaceFoot`]) and compared with the
//! border within [`RELATIVE`] of the rectangle's extent. On a closed surface a point on the
//! seam may come out at either end of the closed direction: it counts on both seam sides (and
//! a point on a pole, whose other parameter is arbitrary, on every side),
//! and the values an edge meets along a closed direction are unwrapped round the period
//! before the part of the side it covers is taken (a whole circle at the end of a cylinder
//! covers its side wherever its samples fall). This is a classification (which
//! repair applies to a face), made at samples: evidence, not a proof; every face it calls
//! trimmed is named in the reports that use it.

use super::{Brep, LoopKind};
use crate::model::Model;
use crate::spline::closure::Closure;
use crate::spline::project::SurfaceFoot;

/// Points of each edge taken to the surface's parameters, evenly spread over its domain;
/// besides them, each knot span's ends and middle (`sample_parameters`).
pub const SAMPLES: usize = 9;
/// Knot spans of an edge sampled on their own at most (beyond, the even samples only).
pub const MAX_SPANS: usize = 256;
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
            if f.loops.is_empty() {
                return false;
            }
            // Every loop's edges (a closed surface's natural face has one loop per end,
            // joined by no seam edge in many files); vertex loops' points.
            let mut curves = Vec::new();
            let mut points = Vec::new();
            for l in &f.loops {
                match &l.kind {
                    LoopKind::Edges(oes) => {
                        for oe in oes {
                            let Some(c) = b.edges.get(oe.edge).and_then(|e| e.curve.as_ref())
                            else {
                                return false;
                            };
                            curves.push(&c.nurbs);
                        }
                    }
                    LoopKind::Vertex(v) => match b.vertices.get(*v) {
                        Some(v) => points.push(v.point),
                        None => return false,
                    },
                }
            }
            let nurbs = &s.nurbs;
            let (u0, u1, v0, v1) = nurbs.hom.domain();
            let d = [u0, u1, v0, v1];
            let eps = [RELATIVE * (u1 - u0), RELATIVE * (v1 - v0)];
            let mut foot = SurfaceFoot::new(nurbs);
            let closure = Closure::of(nurbs);
            let closed = [closure.seam_u, closure.seam_v];
            // Whether `p` lies on a pole (a side that is a single point) of direction `k`:
            // its other parameter is then arbitrary.
            let pole = |p: &[f64; 2], k: usize| {
                (2 * k..2 * k + 2)
                    .any(|side| closure.degenerate[side] && (p[k] - d[side]).abs() <= eps[k])
            };
            // A vertex loop is natural only at a pole.
            for p in &points {
                let uv = foot.closest(p);
                if !(pole(&uv, 0) || pole(&uv, 1)) {
                    return false;
                }
            }
            // Per side (u = u0, u = u1, v = v0, v = v1): the spans of the other parameter
            // that edges lying on it cover. A sample on a pole lies on every side, and only
            // its pole's own parameter says where along a side it is.
            let mut spans: [Vec<(f64, f64)>; 4] = Default::default();
            for c in curves {
                let uv: Vec<[f64; 2]> = sample_parameters(c)
                    .into_iter()
                    .map(|t| foot.closest(&c.eval(&t)))
                    .collect();
                let mut on_some = false;
                for (side, span) in spans.iter_mut().enumerate() {
                    let (k, other) = (side / 2, 1 - side / 2);
                    // In a closed direction the two sides are one curve (the seam): a point
                    // on either lies on both.
                    let on = |p: &[f64; 2]| {
                        (p[k] - d[side]).abs() <= eps[k]
                            || (closed[k] && (p[k] - d[side ^ 1]).abs() <= eps[k])
                            || pole(p, other)
                    };
                    if uv.iter().all(on) {
                        on_some = true;
                        let along: Vec<f64> = uv
                            .iter()
                            .filter(|p| !pole(p, k))
                            .map(|p| p[other])
                            .collect();
                        let range = (d[2 * other], d[2 * other + 1]);
                        span.extend(arc_spans(&along, range, closed[other], eps[other]));
                    }
                }
                if !on_some {
                    return false;
                }
            }
            let covered = |side: usize| {
                let other = 1 - side / 2;
                covers(
                    &mut spans[side].clone(),
                    (d[2 * other], d[2 * other + 1]),
                    eps[other],
                )
            };
            let side_ok = |side: usize| closure.degenerate[side] || covered(side);
            // The two sides that meet at a seam are one curve inside the face: a seam edge
            // may run along it or not (a cylinder between two circles), either way the face
            // is whole across it.
            let pair_ok = |a: usize, seam: bool| seam || (side_ok(a) && side_ok(a + 1));
            pair_ok(0, closure.seam_u) && pair_ok(2, closure.seam_v)
        })
        .collect()
}

/// The parameters at which an edge is sampled, in increasing order: [`SAMPLES`] evenly spread
/// over its domain and, for up to [`MAX_SPANS`] knot spans, each span's ends and middle (a
/// polyline edge whose vertices alone lie on the border, dipping inside between them, is
/// seen at its spans' middles).
fn sample_parameters(c: &crate::spline::NurbsCurve<f64, 3>) -> Vec<f64> {
    let (t0, t1) = c.hom.domain();
    let mut ts: Vec<f64> = (0..SAMPLES)
        .map(|i| t0 + (t1 - t0) * i as f64 / (SAMPLES - 1) as f64)
        .collect();
    let breaks = c.hom.knots.breakpoints();
    if breaks.len() <= MAX_SPANS + 1 {
        for w in breaks.windows(2) {
            ts.extend([w[0], 0.5 * (w[0] + w[1]), w[1]]);
        }
    }
    ts.retain(|t| (t0..=t1).contains(t));
    ts.sort_by(f64::total_cmp);
    ts.dedup();
    ts
}

/// The spans of `[lo, hi]` that the values `t` met one after another along an edge cover:
/// `[min, max]` in an open direction. In a closed one (period `hi − lo`) a value at the seam
/// may come out at either end, so the values are unwrapped first — each step taken as the
/// shortest way round, which holds while consecutive samples are less than half a period
/// apart — and the arc they sweep is cut at the seam into at most two spans (the whole range
/// when it sweeps a period, within `eps`).
fn arc_spans(t: &[f64], (lo, hi): (f64, f64), closed: bool, eps: f64) -> Vec<(f64, f64)> {
    let period = hi - lo;
    let Some(&first) = t.first() else {
        return Vec::new();
    };
    if !closed || period <= 0.0 {
        let min = t.iter().copied().fold(f64::INFINITY, f64::min);
        let max = t.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        return vec![(min, max)];
    }
    let (mut w, mut min, mut max) = (first, first, first);
    for pair in t.windows(2) {
        let step = pair[1] - pair[0];
        w += step - period * (step / period).round();
        min = min.min(w);
        max = max.max(w);
    }
    if max - min >= period - eps {
        return vec![(lo, hi)];
    }
    let a = lo + (min - lo).rem_euclid(period);
    let b = a + (max - min);
    if b <= hi {
        vec![(a, b)]
    } else {
        vec![(a, hi), (lo, b - period)]
    }
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
    use super::{arc_spans, covers};

    #[test]
    fn arcs_in_a_closed_direction_are_unwrapped_round_the_seam() {
        let r = (0.0, 1.0);
        // A whole circle whose ends came out at either end of the period.
        for ends in [(0.0, 1.0), (1.0, 0.0), (1.0, 1.0), (0.0, 0.0)] {
            let t = [ends.0, 0.25, 0.5, 0.75, ends.1];
            assert_eq!(arc_spans(&t, r, true, 1e-9), vec![(0.0, 1.0)], "{ends:?}");
        }
        // Backwards round the circle.
        assert_eq!(
            arc_spans(&[1.0, 0.7, 0.4, 0.1, 0.0], r, true, 1e-9),
            vec![(0.0, 1.0)]
        );
        // An arc from the seam: its start at the far end is its start at the near end.
        let s = arc_spans(&[1.0, 0.1, 0.2], r, true, 1e-9);
        assert!(
            s.len() == 1 && s[0].0 == 0.0 && (s[0].1 - 0.2).abs() < 1e-12,
            "{s:?}"
        );
        // An arc across the seam: two spans.
        let s = arc_spans(&[0.9, 0.95, 0.05, 0.1], r, true, 1e-9);
        assert_eq!(s.len(), 2);
        assert!((s[0].0 - 0.9).abs() < 1e-12 && s[0].1 == 1.0);
        assert!(s[1].0 == 0.0 && (s[1].1 - 0.1).abs() < 1e-12);
        assert!(!covers(&mut s.clone(), r, 1e-9));
        // Open direction: as the samples lie.
        assert_eq!(
            arc_spans(&[1.0, 0.25, 0.0], r, false, 1e-9),
            vec![(0.0, 1.0)]
        );
        assert_eq!(arc_spans(&[0.2, 0.6], r, false, 1e-9), vec![(0.2, 0.6)]);
        assert!(arc_spans(&[], r, true, 1e-9).is_empty());
    }

    #[test]
    fn spans_cover_only_without_gaps() {
        assert!(covers(&mut [(0.5, 1.0), (0.0, 0.5)], (0.0, 1.0), 1e-9));
        assert!(!covers(&mut [(0.0, 0.4), (0.6, 1.0)], (0.0, 1.0), 1e-9));
        assert!(!covers(&mut [(0.0, 0.9)], (0.0, 1.0), 1e-9));
        assert!(!covers(&mut [], (0.0, 1.0), 1e-9));
    }
}
