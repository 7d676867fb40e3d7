//! The side of its loops a face lies on. A face's loops run counter-clockwise around it about
//! its normal (holes clockwise), so in the parameter plane oriented by the normal the face is
//! on the left of every loop. Two places need that rule, where the loops alone do not say
//! which region they bound:
//!
//! * a band between two loops winding around a periodic direction, on a surface periodic in
//!   the other direction too (a torus): the loops bound two strips, the face and the rest;
//! * a face whose loops are all holes (a sphere minus a cap, an IGES 144 face with no outer
//!   boundary): the face is the domain minus the holes, outlined here by a *frame* — the
//!   domain, one period wide in each periodic direction, placed where no hole crosses it.
//!
//! The frame's sides are seams (the two copies share their vertices), pole lines (every point
//! is the pole's vertex) or the surface's open borders, so the face's triangulation closes
//! across them as [`super::domain::join_band`] closes a band.

use super::domain::{self, BoundaryPoint, FaceSurface};
use super::face::FaceError;
use std::collections::HashMap;

/// How a face's loops are to be read: its normal's sense and whether a loop is declared the
/// outer one.
#[derive(Clone, Copy, Debug)]
pub struct Sense {
    /// The face's normal is `S_u × S_v`.
    pub same_sense: bool,
    /// One of its edge loops is declared outer (a STEP `FACE_OUTER_BOUND`, an IGES 144 outer
    /// boundary).
    pub declared_outer: bool,
}

impl Sense {
    /// The signed area of `p` in the parameter plane oriented by the face's normal.
    pub fn area(&self, p: &[BoundaryPoint]) -> f64 {
        let a = domain::signed_area(p);
        if self.same_sense { a } else { -a }
    }
}

/// Whether the face is the domain minus its polygons: their total area, oriented by the
/// normal, is negative (every loop is a hole), and the surface is closed (a seam or a pole:
/// there "outer" has no meaning) or no loop is declared outer. On an open surface a loop
/// declared outer bounds the face whatever its orientation (files with a clockwise outer loop
/// exist).
pub fn holes_only<P: AsRef<[BoundaryPoint]>>(fs: &FaceSurface, polys: &[P], sense: Sense) -> bool {
    let total: f64 = polys.iter().map(|p| sense.area(p.as_ref())).sum();
    let closed = fs.period.iter().any(Option::is_some) || fs.closure.degenerate.iter().any(|d| *d);
    total < 0.0 && (closed || !sense.declared_outer)
}

/// The lowest value `g` such that no polygon's range in periodic direction `d` (period
/// `per`) contains `g` modulo the period: the middle of the widest gap between the ranges.
fn gap(polys: &[Vec<BoundaryPoint>], d: usize, per: f64) -> Option<f64> {
    let mut spans: Vec<(f64, f64)> = Vec::new();
    for p in polys {
        let lo = p.iter().map(|b| b.uv[d]).fold(f64::INFINITY, f64::min);
        let hi = p.iter().map(|b| b.uv[d]).fold(f64::NEG_INFINITY, f64::max);
        // Not less than a period (or not a number): no gap.
        if (hi - lo).partial_cmp(&per) != Some(std::cmp::Ordering::Less) {
            return None;
        }
        let s = lo.rem_euclid(per);
        spans.push((s, s + (hi - lo)));
    }
    spans.sort_by(|a, b| a.0.total_cmp(&b.0));
    let first = spans.first().copied()?;
    // Sweep the covered arcs from the first start, covered up to where the first span or one
    // running past the period's end reaches; the widest uncovered arc (the last wraps around
    // to the first start).
    let past_end = spans
        .iter()
        .map(|x| x.1 - per)
        .fold(f64::NEG_INFINITY, f64::max);
    let (mut reach, mut best) = (first.1.max(past_end), (0.0f64, 0.0f64));
    for &(s, e) in &spans[1..] {
        if s > reach && s - reach > best.0 {
            best = (s - reach, (s + reach) / 2.0);
        }
        reach = reach.max(e);
    }
    let wrap = first.0 + per - reach;
    if wrap > best.0 {
        best = (wrap, reach + wrap / 2.0);
    }
    (best.0 > 0.0).then_some(best.1)
}

/// The frame of a face whose polygons are all holes ([`holes_only`]): the polygons are
/// shifted by whole periods into it, and the frame returned, running counter-clockwise about
/// the face's normal. `n[d]`: interior points on the sides along direction `d`. `None` when
/// the holes cover a whole period between them (no place for the frame's seam).
pub fn frame(
    fs: &FaceSurface,
    polys: &mut [Vec<BoundaryPoint>],
    sense: Sense,
    n: [usize; 2],
    add: &mut dyn FnMut([f64; 3]) -> usize,
) -> Result<Vec<BoundaryPoint>, FaceError> {
    let mut lo = [fs.domain[0], fs.domain[2]];
    let mut hi = [fs.domain[1], fs.domain[3]];
    for d in 0..2 {
        if let Some(per) = fs.period[d] {
            let g = gap(polys, d, per).ok_or(FaceError::Covered)?;
            lo[d] = g;
            hi[d] = g + per;
            for p in polys.iter_mut() {
                let min = p.iter().map(|b| b.uv[d]).fold(f64::INFINITY, f64::min);
                let s = ((g - min) / per).ceil() * per;
                for b in p.iter_mut() {
                    *b = b.shifted(d, s);
                }
            }
        }
    }
    // One mesh vertex per surface point of the frame: a periodic coordinate is taken at the
    // frame's low side, a pole side's free coordinate at its low end.
    let mut vertices: HashMap<[u64; 2], usize> = HashMap::new();
    let mut vertex = |uv: [f64; 2]| -> usize {
        let mut key = uv;
        for d in 0..2 {
            if fs.period[d].is_some() && uv[d] == hi[d] {
                key[d] = lo[d];
            }
        }
        for (side, d) in [(0, 0), (1, 0), (2, 1), (3, 1)] {
            let at = if side % 2 == 0 { lo[d] } else { hi[d] };
            if fs.period[d].is_none() && fs.closure.degenerate[side] && uv[d] == at {
                key[1 - d] = lo[1 - d];
            }
        }
        *vertices
            .entry([key[0].to_bits(), key[1].to_bits()])
            .or_insert_with(|| add(fs.eval(&key)))
    };
    // Counter-clockwise in (u, v): along v = lo, up u = hi, back along v = hi, down u = lo.
    // The opposite sides take the same values backwards, so that a seam's two copies meet the
    // same vertices.
    let steps = |d: usize| -> Vec<f64> {
        (0..=n[d])
            .map(|i| lo[d] + (hi[d] - lo[d]) * (i as f64 / (n[d] + 1) as f64))
            .collect()
    };
    let (us, vs) = (steps(0), steps(1));
    // Bottom from (lo, lo), right from (hi, lo), top from (hi, hi), left from (lo, hi); each
    // side's points exclude its end (the next side's start).
    let back = |xs: &[f64], end: f64| -> Vec<f64> {
        std::iter::once(end)
            .chain(xs[1..].iter().rev().copied())
            .collect()
    };
    let sides = us
        .iter()
        .map(|&u| [u, lo[1]])
        .chain(vs.iter().map(|&v| [hi[0], v]))
        .chain(back(&us, hi[0]).into_iter().map(|u| [u, hi[1]]))
        .chain(back(&vs, hi[1]).into_iter().map(|v| [lo[0], v]));
    let mut out: Vec<BoundaryPoint> = Vec::new();
    for uv in sides {
        out.push(BoundaryPoint::straight(uv, vertex(uv)));
    }
    if !sense.same_sense {
        out.reverse();
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn poly(lo: f64, hi: f64) -> Vec<BoundaryPoint> {
        [[lo, 0.0], [hi, 0.0], [hi, 1.0], [lo, 1.0]]
            .iter()
            .map(|uv| BoundaryPoint::straight(*uv, 0))
            .collect()
    }

    #[test]
    fn the_widest_gap_between_ranges_modulo_the_period() {
        // Ranges [1, 2] and [5, 9] modulo 10: gaps (2, 5) of 3 and (9, 11) of 2.
        let g = gap(&[poly(1.0, 2.0), poly(15.0, 19.0)], 0, 10.0).unwrap();
        assert!((g - 3.5).abs() < 1e-12, "{g}");
        // The gap across the period's end: [2, 8] leaves (8, 12), middle 10.
        let g = gap(&[poly(2.0, 8.0)], 0, 10.0).unwrap();
        assert!((g - 10.0).abs() < 1e-12, "{g}");
        // A range running past the period's end covers the start: [1, 2], [3, 4] and
        // [8, 13.5] (covering [0, 3.5]) leave (4, 8) only.
        let g = gap(&[poly(1.0, 2.0), poly(3.0, 4.0), poly(8.0, 13.5)], 0, 10.0).unwrap();
        assert!((g - 6.0).abs() < 1e-12, "{g}");
        // Ranges covering the whole period between them: no place for a seam.
        assert!(gap(&[poly(0.0, 6.0), poly(5.0, 11.0)], 0, 10.0).is_none());
        assert!(gap(&[poly(0.0, 10.0)], 0, 10.0).is_none());
    }
}
