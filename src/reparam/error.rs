//! `E_max` of §2 (docs/papers.md §A: "the largest distance between the given surface and its
//! chord-length-parametrized replacement, checked at dense samples and refined by inserting
//! a knot in r at the parameter of the largest deviation, until E_max ≤ ε").
//!
//! What is measured. The new surface `R(ξ, η)` and the given `S(u, v)` are two maps of
//! (nearly) the same set, related by an unknown reparametrization φ, so the distance of
//! *corresponding* points is not defined; the distance between the two *sets* is. At every
//! sample `(ξ, η)` (a `k × k` lattice in each grid cell) this module computes
//!
//! * `d(R(ξ,η), S)`: closest-point projection of `R(ξ,η)` onto S (damped Gauss–Newton in the
//!   kernel, [`crate::spline::project::descend`]) started at `φ̃(ξ,η)`, the bilinear map of
//!   the grid cell, which is where the foot lies up to the interpolation error;
//! * `d(S(φ̃(ξ,η)), R)`: projection of the point of S onto R, started at `(ξ, η)`. The grid
//!   cells tile the domain of S, so these samples cover S as densely as the first cover R;
//! * `g = |R(ξ,η) − S(φ̃(ξ,η))|`, the distance of the points φ̃ makes correspond.
//!
//! The projections start where `g` is measured and only accept decreasing distances, so
//! both one-sided values are ≤ `g` at every sample. Everything here is *evidence*: the
//! maxima over samples are not bounds of the suprema. The proven bound is
//! [`super::bound`]: the same argument with φ a spline interpolating the grid's domain points
//! and `sup |R − S∘φ|` bounded by interval forms over parameter boxes.
//!
//! Refinement ("knot insertion at the worst point"): every grid span in ξ (η) holding a
//! sample above ε gets a new parameter line through its worst such sample (kept in the
//! span's middle half, so lines never crowd), in the direction(s) in which the sample's
//! cell is long: ξ when its physical extent along ξ is at least half that along η, and
//! vice versa.

use super::interior::{Grid, Line};
use super::{Deviation, Params};
use crate::spline::NurbsSurface;
use crate::spline::project::descend;
use rayon::prelude::*;

struct Sample {
    xi: f64,
    eta: f64,
    cell: (usize, usize),
    r_to_s: f64,
    s_to_r: f64,
    g: f64,
}

/// Sample the deviation of `r` (on `[0,1]²`) from `s` over the grid's cells; the lines to
/// insert where it exceeds ε, worst first.
pub fn measure(
    s: &NurbsSurface<f64, 3>,
    r: &NurbsSurface<f64, 3>,
    grid: &Grid,
    p: &Params,
) -> (Deviation, Vec<Line>) {
    let (n, m) = (grid.xi.len(), grid.eta.len());
    let k = p.samples_per_cell;
    let (u0, u1, v0, v1) = s.hom.domain();
    let ds = [u0, u1, v0, v1];
    let dr = [0.0, 1.0, 0.0, 1.0];
    let cells: Vec<(usize, usize)> = (0..n - 1)
        .flat_map(|i| (0..m - 1).map(move |j| (i, j)))
        .collect();
    let samples: Vec<Sample> = cells
        .par_iter()
        .flat_map_iter(|&(i, j)| {
            let qi = if i + 2 == n { k + 1 } else { k };
            let qj = if j + 2 == m { k + 1 } else { k };
            let mut out = Vec::with_capacity(qi * qj);
            for a in 0..qi {
                for b in 0..qj {
                    let xi = grid.xi[i] + (grid.xi[i + 1] - grid.xi[i]) * a as f64 / k as f64;
                    let eta = grid.eta[j] + (grid.eta[j + 1] - grid.eta[j]) * b as f64 / k as f64;
                    let (uv, _) = grid.map(xi, eta);
                    let rp = r.eval(&xi, &eta);
                    let sp = s.eval(&uv[0], &uv[1]);
                    let g = crate::geom::dist(&rp, &sp);
                    let (_, e_rs) = descend(s, &rp, uv, &ds);
                    let (_, e_sr) = descend(r, &sp, [xi, eta], &dr);
                    out.push(Sample {
                        xi,
                        eta,
                        cell: (i, j),
                        r_to_s: e_rs.sqrt(),
                        s_to_r: e_sr.sqrt(),
                        g,
                    });
                }
            }
            out
        })
        .collect();
    let mut dev = Deviation {
        samples: samples.len(),
        ..Default::default()
    };
    let err = |s: &Sample| s.r_to_s.max(s.s_to_r);
    // A NaN distance (a non-finite evaluation) counts as infinitely far.
    let err_or_inf = |s: &Sample| {
        let e = err(s);
        if e.is_nan() { f64::INFINITY } else { e }
    };
    let mut worst_e = -1.0;
    for smp in &samples {
        dev.r_to_s = dev.r_to_s.max(smp.r_to_s);
        dev.s_to_r = dev.s_to_r.max(smp.s_to_r);
        dev.correspondence = dev.correspondence.max(smp.g);
        let e = err_or_inf(smp);
        if e > worst_e {
            worst_e = e;
            dev.worst = [smp.xi, smp.eta];
        }
    }
    dev.e_max = worst_e.max(0.0);
    // Worst violating sample per span, per direction.
    let mut span_xi: Vec<Option<(f64, f64)>> = vec![None; n - 1];
    let mut span_eta: Vec<Option<(f64, f64)>> = vec![None; m - 1];
    for smp in samples.iter().filter(|s| err_or_inf(s) > p.tol) {
        let (i, j) = smp.cell;
        let x = &grid.x;
        let lu = (crate::geom::dist(&x[i + 1][j], &x[i][j])
            + crate::geom::dist(&x[i + 1][j + 1], &x[i][j + 1]))
            / 2.0;
        let lv = (crate::geom::dist(&x[i][j + 1], &x[i][j])
            + crate::geom::dist(&x[i + 1][j + 1], &x[i + 1][j]))
            / 2.0;
        let e = err_or_inf(smp);
        if lu >= 0.5 * lv && span_xi[i].is_none_or(|(w, _)| e > w) {
            span_xi[i] = Some((e, smp.xi));
        }
        if lv >= 0.5 * lu && span_eta[j].is_none_or(|(w, _)| e > w) {
            span_eta[j] = Some((e, smp.eta));
        }
    }
    let middle = |t: &[f64], k: usize, x: f64| {
        let q = (t[k + 1] - t[k]) / 4.0;
        x.clamp(t[k] + q, t[k + 1] - q)
    };
    let mut lines: Vec<(f64, Line)> = vec![];
    for (i, w) in span_xi.iter().enumerate() {
        if let Some((e, x)) = w {
            lines.push((*e, Line::Xi(middle(&grid.xi, i, *x))));
        }
    }
    for (j, w) in span_eta.iter().enumerate() {
        if let Some((e, x)) = w {
            lines.push((*e, Line::Eta(middle(&grid.eta, j, *x))));
        }
    }
    lines.sort_by(|a, b| b.0.total_cmp(&a.0));
    (dev, lines.into_iter().map(|(_, l)| l).collect())
}

/// The first `room` lines (the worst).
pub fn limit(mut lines: Vec<Line>, room: usize) -> Vec<Line> {
    lines.truncate(room);
    lines
}
