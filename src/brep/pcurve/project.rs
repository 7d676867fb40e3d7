//! Pcurves made by projecting an edge's 3D curve onto a face's surface, each with a proven
//! bound on how far its image lies from the edge where one can be had
//! ([`crate::spline::pcurve_bound`]).
//!
//! The edge is sampled at evenly spread parameters and each sample projected onto the surface
//! (seeded from the previous one; closed parameters unwrapped along the edge). The pcurve is
//! cut where the samples cross a knot line of the surface and at the edge's own knots (inside
//! such a piece both the surface and the edge are smooth, so is the preimage), and each piece
//! is a cubic through projected samples at the same fractions of the piece's edge range as of
//! its own. A piece's samples are doubled until its image is near the edge (`Fit`) and
//! *proven* within the model tolerance of the edge
//! (the bound pairs the two ranges linearly, which this construction makes a good pairing);
//! where the bound cannot be had (the surface's cells cannot be enclosed, the pcurve would
//! leave the domain) the piece is accepted on evidence — its image halfway between samples
//! within the tolerance of the edge, by projection onto the edge — and the pcurve carries no
//! bound.
//! A straight segment is tried first where a parameter stays constant (an edge along a
//! parameter line).

pub(crate) use super::chart::{Chart, segment, unwrap};
use crate::spline::closure::{Closure, exact_seam};
use crate::spline::interpolate::interpolate_with_parameters;
use crate::spline::pcurve_bound::SurfaceCells;
use crate::spline::project::{CurveFoot, project};
use crate::spline::{NurbsCurve, NurbsSurface};

/// Samples scanned along an edge before it is cut into pieces.
const SCAN: usize = 132;

/// Bisection steps locating a knot crossing.
const BISECTIONS: usize = 64;

/// Samples a piece of a pcurve is first interpolated through.
const PIECE_SAMPLES: usize = 9;

/// Most samples a piece is interpolated through before it is given up.
const MAX_PIECE_SAMPLES: usize = 257;

/// A projected pcurve.
pub(crate) struct Projected {
    pub curve: NurbsCurve<f64, 2>,
    /// Its end's parameters.
    pub end: [f64; 2],
    /// A proven bound on the Hausdorff distance between its image and the edge, when every
    /// piece has one.
    pub bound: Option<f64>,
}

/// One surface, ready to take pcurves of many edges.
pub(crate) struct Projector<'a> {
    pub chart: Chart<'a>,
    pub(super) cells: Option<SurfaceCells>,
    /// Directions in which the surface is closed exactly (clamped knots and its two border
    /// rows of homogeneous control points identical, [`exact_seam`]; not [`Closure::of`],
    /// which allows rounding): `S(lo, ·) = S(hi, ·)` there, so a curve on one side of the
    /// seam and its copy on the other have the same image.
    pub(super) exact_seam: [bool; 2],
}

impl<'a> Projector<'a> {
    pub fn new(s: &'a NurbsSurface<f64, 3>) -> Projector<'a> {
        Projector {
            // A search aid only (the pcurves are checked): borders that meet within 1e-7
            // of the net's size count as a seam.
            chart: Chart::new(s, &Closure::within(s, 1e-7)),
            cells: SurfaceCells::new(s),
            exact_seam: [exact_seam(s, 0), exact_seam(s, 1)],
        }
    }

    /// The pcurve of `arc` (its whole domain, in its direction), starting at `from` when
    /// given (the closed parameters already unwrapped as the caller wants them) and pinned
    /// to `end` when given; without `from` the pcurve is placed inside the domain, and
    /// `None` is returned where it cannot be (it would cross a seam). `None` also where no
    /// piece meets `fit.off` even on evidence.
    pub fn project(
        &self,
        arc: &NurbsCurve<f64, 3>,
        from: Option<[f64; 2]>,
        end: Option<[f64; 2]>,
        fit: Fit,
    ) -> Option<Projected> {
        self.project_against(arc, arc, from, end, fit)
    }

    /// [`Projector::project`] of `arc`, with every bound proven against `against` over
    /// `arc`'s domain instead: `arc` is a part of `against` cut out in `f64` (rounded), and the
    /// bound wanted is to the edge itself.
    pub fn project_against(
        &self,
        arc: &NurbsCurve<f64, 3>,
        against: &NurbsCurve<f64, 3>,
        from: Option<[f64; 2]>,
        end: Option<[f64; 2]>,
        fit: Fit,
    ) -> Option<Projected> {
        let c = &self.chart;
        let (lo, hi) = (c.lo, c.hi);
        let (t0, t1) = arc.hom.domain();
        let ts: Vec<f64> = (0..SCAN)
            .map(|i| t0 + (t1 - t0) * i as f64 / (SCAN - 1) as f64)
            .collect();
        let first = from.unwrap_or_else(|| project(c.s, &arc.eval(&t0)));
        let mut scan = vec![first];
        for t in &ts[1..] {
            let last = scan[scan.len() - 1];
            scan.push(c.foot(arc, *t, last));
        }
        if from.is_none() {
            c.at_poles(&mut scan);
            self.place_in_domain(&mut scan)?;
        }
        let first = scan[0];
        let last = end.unwrap_or(scan[SCAN - 1]);
        let flat = (0..2).any(|d| {
            scan.iter()
                .all(|p| (p[d] - first[d]).abs() <= 1e-8 * (hi[d] - lo[d]))
        });
        // A segment along a parameter line, and its bound when proven within `off`.
        let mut straight = None;
        if flat {
            // On the edge's own range, as the cubic pieces are.
            let mut ends = [first, last];
            self.snap_to_lines(&mut ends);
            let l = NurbsCurve::new(vec![t0, t0, t1, t1], 1, ends.to_vec(), vec![1.0; 2]).ok()?;
            let cert = self
                .cells
                .as_ref()
                .map(|x| x.bound(&l, against, (t0, t1), fit.aim));
            match cert {
                Some(Ok(r)) if r <= fit.aim => {
                    return Some(Projected {
                        curve: l,
                        end: last,
                        bound: Some(r),
                    });
                }
                // Proven, but not within `aim`: the pairing may be what is off; cubic
                // pieces pair by the same fractions.
                Some(Ok(r)) => straight = Some((l, Some(r).filter(|r| *r <= fit.off))),
                _ => {
                    return Some(Projected {
                        curve: l,
                        end: last,
                        bound: None,
                    });
                }
            }
        }
        // Cuts at knot-line crossings (with the line: the piece ends are put exactly on it,
        // so that the curve-on-surface split sees an end on the line, not a near-tangency)
        // and at the edge's own knots.
        let mut cuts: Vec<(f64, Option<(usize, f64)>)> = self
            .knot_crossings(arc, &ts, &scan)
            .into_iter()
            .map(|(t, d, k)| (t, Some((d, k))))
            .collect();
        cuts.extend(
            arc.hom
                .knots
                .interior_breaks()
                .into_iter()
                .map(|t| (t, None)),
        );
        let tiny = 1e-9 * (t1 - t0);
        cuts.retain(|t| t.0 > t0 + tiny && t.0 < t1 - tiny);
        cuts.sort_by(|x, y| x.0.total_cmp(&y.0));
        cuts.dedup_by(|x, y| (x.0 - y.0).abs() <= tiny);
        let mut bounds = vec![(t0, None)];
        bounds.extend(cuts);
        bounds.push((t1, None));
        let seed = |t: f64| {
            let i = ts.partition_point(|x| *x < t).min(SCAN - 1);
            scan[i]
        };
        let mut x = first;
        let mut exact_join = true;
        let mut out: Option<NurbsCurve<f64, 2>> = None;
        let mut bound = Some(0.0f64);
        let pieces = bounds.len() - 1;
        let as_straight = |s: (NurbsCurve<f64, 2>, Option<f64>)| Projected {
            curve: s.0,
            end: last,
            bound: s.1,
        };
        for (i, w) in bounds.windows(2).enumerate() {
            let e = if i + 1 == pieces {
                end
            } else {
                w[1].1.map(|(d, k)| {
                    let mut y = c.foot(arc, w[1].0, seed(w[1].0));
                    y[d] = k;
                    y
                })
            };
            let Some((pc, y, r)) = self.piece((arc, against), w[0].0, w[1].0, x, e, fit) else {
                return straight.map(as_straight);
            };
            bound = bound.zip(r).map(|(a, b)| a.max(b));
            out = Some(match out {
                None => pc,
                Some(c) => {
                    // Joining keeps `c`'s end point for `pc`'s start: the pieces' bounds hold
                    // for the joined curve when the two are the same point (they are: both
                    // are the same sample, clamped and snapped alike) and the knots are not
                    // shifted (`pc` starts where `c` ends); otherwise the joined curve is
                    // proven again below.
                    exact_join &= c.hom.control.last() == pc.hom.control.first()
                        && c.hom.domain().1 == pc.hom.domain().0;
                    c.joined(&pc).ok()?
                }
            });
            x = y;
        }
        match straight {
            Some(s) if s.1.is_some_and(|r| bound.is_none_or(|b| r <= b)) => Some(as_straight(s)),
            _ => out.map(|curve| {
                let bound = if exact_join {
                    bound
                } else {
                    self.check_on(&curve, against, (t0, t1), fit.aim)
                        .ok()
                        .filter(|r| *r <= fit.off)
                };
                Projected {
                    curve,
                    end: x,
                    bound,
                }
            }),
        }
    }

    /// Moves unwrapped samples by whole periods into the domain; `None` where they span more
    /// than it (the edge crosses a seam). Samples outside by up to 1e-6 of the period (a
    /// vertex on the seam projected a little off it) are clamped; the pcurve is checked.
    fn place_in_domain(&self, scan: &mut [[f64; 2]]) -> Option<()> {
        let c = &self.chart;
        for d in 0..2 {
            let (lo, hi) = (c.lo[d], c.hi[d]);
            let slack = 1e-6 * (hi - lo);
            let (mn, mx) = scan
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
                    (a.min(p[d]), b.max(p[d]))
                });
            let shift = if c.closed[d] && mn < lo - slack {
                ((lo - slack - mn) / c.period(d)).ceil() * c.period(d)
            } else if c.closed[d] && mx > hi + slack {
                -((mx - hi - slack) / c.period(d)).ceil() * c.period(d)
            } else {
                0.0
            };
            if !(mn + shift >= lo - slack && mx + shift <= hi + slack) {
                return None;
            }
            for p in scan.iter_mut() {
                p[d] = (p[d] + shift).clamp(lo, hi);
            }
        }
        Some(())
    }

    /// The curve parameters where `arc` crosses a knot line of the surface (inside each knot
    /// span the surface is smooth, so is the pcurve; across one it need not be). `scan`
    /// holds the arc's parameters at `ts` (unwrapped).
    fn knot_crossings(
        &self,
        arc: &NurbsCurve<f64, 3>,
        ts: &[f64],
        scan: &[[f64; 2]],
    ) -> Vec<(f64, usize, f64)> {
        let c = &self.chart;
        let lines = [c.s.hom.ku.interior_breaks(), c.s.hom.kv.interior_breaks()];
        let mut out = Vec::new();
        for (i, w) in scan.windows(2).enumerate() {
            for d in 0..2 {
                let (x, y) = (w[0][d], w[1][d]);
                // A closed direction's knots, its ends included, repeat every period.
                let shifts: Vec<f64> = if c.closed[d] {
                    let p = c.period(d);
                    let lo_m = ((x.min(y) - c.lo[d]) / p).floor() as i64;
                    let hi_m = ((x.max(y) - c.lo[d]) / p).floor() as i64;
                    (lo_m..=hi_m).map(|m| m as f64 * p).collect()
                } else {
                    vec![0.0]
                };
                let mut lines_d = lines[d].clone();
                if c.closed[d] {
                    lines_d.push(c.lo[d]);
                }
                for kappa in lines_d
                    .iter()
                    .flat_map(|l| shifts.iter().map(move |m| l + m))
                {
                    if (x - kappa) * (y - kappa) >= 0.0 {
                        continue;
                    }
                    let (mut a, mut b) = (ts[i], ts[i + 1]);
                    for _ in 0..BISECTIONS {
                        let mid = 0.5 * (a + b);
                        if mid <= a || mid >= b {
                            break;
                        }
                        let q = c.foot(arc, mid, w[0])[d];
                        if (q - kappa) * (x - kappa) > 0.0 {
                            a = mid
                        } else {
                            b = mid
                        }
                    }
                    out.push((0.5 * (a + b), d, kappa));
                }
            }
        }
        out
    }

    /// The cubic pcurve of `arc` over `[a, b]` from `from`, pinned to `end` when given, with
    /// its end and its proven bound to `against` over `[a, b]` (module comment; `against` is
    /// `arc` or the edge `arc` was cut from). A doubling keeps the samples it has
    /// and adds the halfway ones. Doubling stops when the image, measured halfway between
    /// samples, is within `fit.aim` of the arc, or within `fit.off` and no longer halving
    /// (the arc lies off the surface by about that much, as edges of files with a coarse
    /// tolerance do), or at [`MAX_PIECE_SAMPLES`].
    fn piece(
        &self,
        (arc, against): (&NurbsCurve<f64, 3>, &NurbsCurve<f64, 3>),
        a: f64,
        b: f64,
        from: [f64; 2],
        end: Option<[f64; 2]>,
        fit: Fit,
    ) -> Option<(NurbsCurve<f64, 2>, [f64; 2], Option<f64>)> {
        let c = &self.chart;
        let (lo, hi) = (c.lo, c.hi);
        let near = CurveFoot::new(arc);
        let at_f = |f: f64| a + (b - a) * f;
        // Samples at the fractions `i / (n − 1)`, the first `from`.
        let mut n = PIECE_SAMPLES;
        let mut pts = vec![from];
        for i in 1..n {
            let last = pts[i - 1];
            pts.push(c.foot(arc, at_f(i as f64 / (n - 1) as f64), last));
        }
        // The last piece that met `off` on evidence only.
        let mut evidence = None;
        let mut before = f64::INFINITY;
        while n <= MAX_PIECE_SAMPLES {
            let f: Vec<f64> = (0..n).map(|i| i as f64 / (n - 1) as f64).collect();
            let mut fitted = pts.clone();
            if let Some(e) = end {
                fitted[n - 1] = e;
            } else {
                fitted[n - 1] = c.at_pole(fitted[n - 1], fitted[n - 2]);
            }
            let interp = interpolate_with_parameters(&fitted, &f, 3).ok()?;
            // Control points outside the domain by rounding (or an overshoot, which both
            // checks then see) are moved onto its border.
            let mut ctrl: Vec<[f64; 2]> = interp
                .control
                .iter()
                .map(|q| [q[0].clamp(lo[0], hi[0]), q[1].clamp(lo[1], hi[1])])
                .collect();
            self.snap_to_lines(&mut ctrl);
            let w = vec![1.0; ctrl.len()];
            // On the arc's own range `[a, b]`: joined, the pieces share the edge's parameter.
            let k = interp.knots.knots();
            let knots: Vec<f64> = k
                .iter()
                .map(|x| {
                    if *x <= 0.0 {
                        a
                    } else if *x >= 1.0 {
                        b
                    } else {
                        at_f(*x)
                    }
                })
                .collect();
            let pc = NurbsCurve::new(knots, interp.knots.degree(), ctrl, w).ok()?;
            let err = f
                .windows(2)
                .map(|w| {
                    let q = pc.eval(&at_f(0.5 * (w[0] + w[1])));
                    let q = [q[0].clamp(lo[0], hi[0]), q[1].clamp(lo[1], hi[1])];
                    near.closest(&c.s.eval(&q[0], &q[1])).2
                })
                .fold(0.0, f64::max);
            let last = 2 * n - 1 > MAX_PIECE_SAMPLES || err > 0.5 * before;
            if err <= fit.aim || (last && err <= fit.off) {
                let target = fit.aim.max(2.0 * err);
                match self
                    .cells
                    .as_ref()
                    .map(|x| x.bound(&pc, against, (a, b), target))
                {
                    Some(Ok(r)) if r <= fit.off => return Some((pc, fitted[n - 1], Some(r))),
                    Some(Ok(_)) => evidence = Some((pc, fitted[n - 1], None)),
                    _ => return Some((pc, fitted[n - 1], None)),
                }
            }
            if 2 * n - 1 > MAX_PIECE_SAMPLES {
                break;
            }
            before = err;
            let m = 2 * n - 1;
            let mut more = Vec::with_capacity(m);
            for (i, p) in pts.iter().enumerate() {
                if i > 0 {
                    let last = more[more.len() - 1];
                    more.push(c.foot(arc, at_f((2 * i - 1) as f64 / (m - 1) as f64), last));
                }
                more.push(*p);
            }
            (pts, n) = (more, m);
        }
        evidence
    }
}

/// How close a projected pcurve's image is to be to its edge: doubling its samples aims at
/// `aim`; `off` is the most that is accepted (the model's tolerance).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Fit {
    pub aim: f64,
    pub off: f64,
}

/// The parameter-space loop of `pcs` (a closed chain of pcurves on `s`) with a straight
/// segment along the pole inserted wherever one pcurve ends on a degenerate border of `s` (a
/// pole) and the next starts elsewhere on it: a loop that runs into a pole and out again
/// crosses it in the parameter plane, where a 2D curve (IGES 142) must be continuous.
pub(crate) fn pole_joins(p: &Projector, pcs: Vec<NurbsCurve<f64, 2>>) -> Vec<NurbsCurve<f64, 2>> {
    let n = pcs.len();
    let ends: Vec<([f64; 2], [f64; 2])> = pcs
        .iter()
        .map(|c| {
            let (a, z) = c.hom.domain();
            (c.eval(&a), c.eval(&z))
        })
        .collect();
    let mut out = Vec::with_capacity(n + 2);
    for (i, c) in pcs.into_iter().enumerate() {
        out.push(c);
        let (a, b) = (ends[i].1, ends[(i + 1) % n].0);
        if p.chart.on_one_pole(a, b)
            && let Some(seg) = segment(a, b)
        {
            out.push(seg);
        }
    }
    out
}
