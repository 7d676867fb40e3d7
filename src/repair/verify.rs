//! Step 2 — verification of patch connectivity (paper §3.1): each candidate edge pair is
//! discretized uniformly by arc length; the largest closest-point distance (both ways) is the
//! pair's gap; below `u2` the edges are neighbours, otherwise they are marked disconnected with
//! their measured gap (Fig. 6). The gap is measured at samples: evidence, named so.

use super::connectivity::Connection;
use super::edges::{CurveFoot, arc_length_samples, edge_curve};
use crate::spline::NurbsSurface;
use serde::Serialize;

/// A candidate connection with its measured gap.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct VerifiedEdge {
    pub connection: Connection,
    /// Largest closest-point distance between the two edges at the samples.
    pub gap: f64,
    pub connected: bool,
}

/// Gap between edge `ep` of `p` and edge `eq` of `q` with `n` samples per edge.
pub fn edge_gap(
    p: &NurbsSurface<f64, 3>,
    ep: usize,
    q: &NurbsSurface<f64, 3>,
    eq: usize,
    n: usize,
) -> f64 {
    let (a, b) = (edge_curve(p, ep), edge_curve(q, eq));
    let one_way = |x: &crate::spline::NurbsCurve<f64, 3>, y: &crate::spline::NurbsCurve<f64, 3>| {
        let foot = CurveFoot::new(y);
        arc_length_samples(x, n)
            .iter()
            .map(|(_, pt)| foot.closest(pt).2)
            .fold(0.0, f64::max)
    };
    one_way(&a, &b).max(one_way(&b, &a))
}

pub fn verify(
    patches: &[NurbsSurface<f64, 3>],
    candidates: &[Connection],
    u2: f64,
    n: usize,
) -> Vec<VerifiedEdge> {
    use rayon::prelude::*;
    candidates
        .par_iter()
        .map(|c| {
            // Edges with the same control points, weights and knots are the same curve: gap 0
            // exactly, at any coordinate scale (sampling carries rounding errors relative to
            // the coordinates, which exceed any absolute u2 far from the origin).
            let (p, q) = (&patches[c.p], &patches[c.q]);
            let gap = if super::average::identical(p, c.ep, q, c.eq, c.same_direction) {
                0.0
            } else {
                edge_gap(p, c.ep, q, c.eq, n)
            };
            VerifiedEdge {
                connection: *c,
                gap,
                connected: gap < u2,
            }
        })
        .collect()
}
