//! Loops that run once round a closed surface, where they cross its seam, and the pcurves of
//! their arcs (evidence, sampled: see the module comment of [`super`]).

use crate::geom::dist;
use crate::spline::closure::Closure;
use crate::spline::interpolate::interpolate_with_parameters;
use crate::spline::project::{CurveFoot, descend, project};
use crate::spline::{NurbsCurve, NurbsSurface};

/// Samples along a closed edge when deciding whether it runs round a closed surface.
const SAMPLES: usize = 33;

/// Bisection steps locating a seam crossing.
const BISECTIONS: usize = 64;

/// Samples a piece of an arc's pcurve is first interpolated through.
const PIECE_SAMPLES: usize = 9;

/// Most samples a piece of an arc's pcurve is interpolated through before it is given up.
const MAX_ARC_SAMPLES: usize = 257;

/// A closed edge that runs once round direction `k` of a surface.
#[derive(Clone, Debug)]
pub(super) struct Round {
    /// The closed direction (0 = u, 1 = v).
    pub k: usize,
    /// The other parameter where the edge crosses the seam (the `k`-th parameter's low end).
    pub c: f64,
    /// The closed parameter increases along the edge's own direction.
    pub up: bool,
    /// The edge's curve parameter at the crossing.
    pub t: f64,
    /// The samples' parameters, the closed one unwrapped along the edge (no jump at the seam).
    pub samples: Vec<[f64; 2]>,
}

impl Round {
    /// The other parameter of the edge where the closed one is `x` (linear between samples).
    pub fn other_at(&self, x: f64, period: f64) -> f64 {
        let (k, r) = (self.k, 1 - self.k);
        let first = self.samples[0][k];
        // `x` moved into the sweep of the samples, which starts at `first`.
        let off = x - first;
        let x = if self.up {
            first + off.rem_euclid(period)
        } else {
            first - (-off).rem_euclid(period)
        };
        for w in self.samples.windows(2) {
            let (a, b) = (w[0][k], w[1][k]);
            if (a <= x && x <= b) || (b <= x && x <= a) {
                let f = if b == a { 0.0 } else { (x - a) / (b - a) };
                return w[0][r] + f * (w[1][r] - w[0][r]);
            }
        }
        self.samples[self.samples.len() - 1][r]
    }
    /// The least and greatest other parameter of the samples.
    pub fn other_range(&self) -> (f64, f64) {
        let r = 1 - self.k;
        self.samples
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
                (a.min(p[r]), b.max(p[r]))
            })
    }
}

/// The straight segment from `a` to `b` (degree 1 over `[0, 1]`).
pub(super) fn segment<const D: usize>(a: [f64; D], b: [f64; D]) -> Option<NurbsCurve<f64, D>> {
    NurbsCurve::new(vec![0.0, 0.0, 1.0, 1.0], 1, vec![a, b], vec![1.0, 1.0]).ok()
}

/// `x` moved by whole periods to the value nearest `near`.
pub(super) fn unwrap(x: f64, near: f64, period: f64) -> f64 {
    x - period * ((x - near) / period).round()
}

/// The parameter point with the `k`-th parameter `x` and the other `y`.
pub(super) fn at(k: usize, x: f64, y: f64) -> [f64; 2] {
    if k == 0 { [x, y] } else { [y, x] }
}

/// The domain of `s` as `[low, high]` per direction.
pub(super) fn bounds(s: &NurbsSurface<f64, 3>) -> ([f64; 2], [f64; 2]) {
    let (u0, u1, v0, v1) = s.hom.domain();
    ([u0, v0], [u1, v1])
}

/// Whether the closed curve `c` runs once round `s` in a closed direction: every sample
/// within `off` of its foot on `s`, the closed parameter (unwrapped) moving the same way at
/// every step and in all by one period (within 1e-6 of it), and the other, where it is closed
/// too, coming back without a turn. The crossing with the seam is then bisected. `Err` names
/// a loop that runs round but not so.
pub(super) fn runs_round(
    s: &NurbsSurface<f64, 3>,
    closure: &Closure,
    c: &NurbsCurve<f64, 3>,
    off: f64,
) -> Result<Option<Round>, String> {
    let (t0, t1) = c.hom.domain();
    let chart = Chart::new(s, closure);
    let (lo, hi) = (chart.lo, chart.hi);
    let ts: Vec<f64> = (0..SAMPLES)
        .map(|i| t0 + (t1 - t0) * i as f64 / (SAMPLES - 1) as f64)
        .collect();
    let mut uv: Vec<[f64; 2]> = Vec::with_capacity(SAMPLES);
    for t in &ts {
        let x = c.eval(t);
        let p = match uv.last() {
            Some(last) => chart.seeded(&x, *last),
            None => project(s, &x),
        };
        let on = dist(&s.eval(&p[0], &p[1]), &x) <= off;
        if !on {
            return Ok(None);
        }
        uv.push(p);
    }
    let closed = chart.closed;
    for k in 0..2 {
        let r = 1 - k;
        if !closed[k] {
            continue;
        }
        let period = |d: usize| hi[d] - lo[d];
        // Both parameters unwrapped along the samples where their direction is closed.
        let mut chain = vec![uv[0]];
        for p in &uv[1..] {
            let last = chain[chain.len() - 1];
            let mut q = *p;
            for d in 0..2 {
                if closed[d] {
                    q[d] = unwrap(q[d], last[d], period(d));
                }
            }
            chain.push(q);
        }
        let steps: Vec<f64> = chain.windows(2).map(|w| w[1][k] - w[0][k]).collect();
        let up = steps.iter().all(|d| *d > 0.0);
        let down = steps.iter().all(|d| *d < 0.0);
        let total = chain[SAMPLES - 1][k] - chain[0][k];
        let back = chain[SAMPLES - 1][r] - chain[0][r];
        let once = (total.abs() - period(k)).abs() <= 1e-6 * period(k);
        if !once {
            continue;
        }
        if !(up || down) {
            return Err("a loop runs round it, turning back on the way".into());
        }
        let back_again = back.abs() <= 1e-6 * period(r);
        if !back_again {
            return Err("a loop runs round it in both directions".into());
        }
        // The seam value the chain passes: the first `lo + m·period` at or beyond its start.
        let m = (chain[0][k] - lo[k]) / period(k);
        let m = if up { m.ceil() } else { m.floor() };
        let target = lo[k] + m * period(k);
        let passed = |x: f64| if up { x >= target } else { x <= target };
        let Some(i) = (0..SAMPLES - 1).find(|&i| passed(chain[i + 1][k])) else {
            return Err("a loop's seam crossing was not found".into());
        };
        let (mut a, mut b) = (ts[i], ts[i + 1]);
        let (ka, kb) = (chain[i][k], chain[i + 1][k]);
        if passed(ka) {
            b = a;
        }
        for _ in 0..BISECTIONS {
            if b - a <= 0.0 {
                break;
            }
            let mid = 0.5 * (a + b);
            if mid <= a || mid >= b {
                break;
            }
            let guess = ka + (mid - ts[i]) / (ts[i + 1] - ts[i]) * (kb - ka);
            let x = unwrap(
                chart.seeded(&c.eval(&mid), at(k, guess, chain[i][r]))[k],
                guess,
                period(k),
            );
            if passed(x) { b = mid } else { a = mid }
        }
        let foot = chart.seeded(&c.eval(&b), at(k, kb, chain[i + 1][r]));
        return Ok(Some(Round {
            k,
            c: foot[r],
            up,
            t: b,
            samples: chain,
        }));
    }
    Ok(None)
}

/// A surface with its domain and closed directions (found once, not per search).
struct Chart<'a> {
    s: &'a NurbsSurface<f64, 3>,
    lo: [f64; 2],
    hi: [f64; 2],
    closed: [bool; 2],
}

impl<'a> Chart<'a> {
    fn new(s: &'a NurbsSurface<f64, 3>, closure: &Closure) -> Chart<'a> {
        let (lo, hi) = bounds(s);
        Chart {
            s,
            lo,
            hi,
            closed: [closure.seam_u, closure.seam_v],
        }
    }
    /// The parameters of a closest point of the surface to `x` near `seed` (its closed
    /// parameters taken modulo their periods): damped Gauss–Newton from the seed, or the
    /// global search ([`project`]) where the descent stops on a border of a closed direction
    /// or moves more than a quarter of the domain (a search figure: the pcurves made from
    /// these points are checked against the edges themselves).
    fn seeded(&self, x: &[f64; 3], seed: [f64; 2]) -> [f64; 2] {
        let (lo, hi) = (self.lo, self.hi);
        let start: [f64; 2] = std::array::from_fn(|j| {
            if self.closed[j] {
                lo[j] + (seed[j] - lo[j]).rem_euclid(hi[j] - lo[j])
            } else {
                seed[j].clamp(lo[j], hi[j])
            }
        });
        let (uv, _) = descend(self.s, x, start, &[lo[0], hi[0], lo[1], hi[1]]);
        let on_seam = |j: usize| self.closed[j] && (uv[j] == lo[j] || uv[j] == hi[j]);
        let far = (0..2).any(|j| (uv[j] - start[j]).abs() > 0.25 * (hi[j] - lo[j]));
        if on_seam(0) || on_seam(1) || far || !uv.iter().all(|v| v.is_finite()) {
            project(self.s, x)
        } else {
            uv
        }
    }
    /// The parameters of `arc`'s point at `t`, the closed one (`k`) unwrapped to the value
    /// nearest `near`'s (which also seeds the search).
    fn foot(&self, arc: &NurbsCurve<f64, 3>, k: usize, t: f64, near: [f64; 2]) -> [f64; 2] {
        let p = self.seeded(&arc.eval(&t), near);
        at(k, unwrap(p[k], near[k], self.hi[k] - self.lo[k]), p[1 - k])
    }
}

/// The curve parameters in `(a, b)` where `arc` crosses a knot line of `s` (inside each
/// knot span the surface is smooth, so is the arc's pcurve; across one it need not be).
/// `scan` holds the arc's parameters at `ts` (unwrapped).
fn knot_crossings(
    c: &Chart,
    arc: &NurbsCurve<f64, 3>,
    k: usize,
    ts: &[f64],
    scan: &[[f64; 2]],
) -> Vec<f64> {
    let lo = c.lo;
    let period = c.hi[k] - lo[k];
    let lines = [c.s.hom.ku.interior_breaks(), c.s.hom.kv.interior_breaks()];
    let mut out = Vec::new();
    for (i, w) in scan.windows(2).enumerate() {
        for d in 0..2 {
            let (x, y) = (w[0][d], w[1][d]);
            // The closed direction's knots repeat every period.
            let shifts: Vec<f64> = if d == k {
                let lo_m = ((x.min(y) - lo[k]) / period).floor() as i64;
                let hi_m = ((x.max(y) - lo[k]) / period).floor() as i64;
                (lo_m..=hi_m).map(|m| m as f64 * period).collect()
            } else {
                vec![0.0]
            };
            for kappa in lines[d]
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
                    let q = c.foot(arc, k, mid, w[0])[d];
                    if (q - kappa) * (x - kappa) > 0.0 {
                        a = mid
                    } else {
                        b = mid
                    }
                }
                out.push(0.5 * (a + b));
            }
        }
    }
    out
}

/// The cubic pcurve of `arc` over `[a, b]` from `from`, pinned to `end` when given: through
/// projected samples, doubled until its image halfway between them lies within `off` of the
/// arc (module comment of [`super`]). A doubling keeps the samples it has and adds the
/// halfway ones.
#[allow(clippy::too_many_arguments)]
fn piece(
    c: &Chart,
    arc: &NurbsCurve<f64, 3>,
    k: usize,
    a: f64,
    b: f64,
    from: [f64; 2],
    end: Option<[f64; 2]>,
    off: f64,
) -> Option<(NurbsCurve<f64, 2>, [f64; 2])> {
    let (lo, hi) = (c.lo, c.hi);
    let near = CurveFoot::new(arc);
    let at_f = |f: f64| a + (b - a) * f;
    // Samples at the fractions `i / (n − 1)`, the first `from`.
    let mut n = PIECE_SAMPLES;
    let mut pts = vec![from];
    for i in 1..n {
        let last = pts[i - 1];
        pts.push(c.foot(arc, k, at_f(i as f64 / (n - 1) as f64), last));
    }
    while n <= MAX_ARC_SAMPLES {
        let f: Vec<f64> = (0..n).map(|i| i as f64 / (n - 1) as f64).collect();
        let mut fitted = pts.clone();
        if let Some(e) = end {
            fitted[n - 1] = e;
        }
        let fit = interpolate_with_parameters(&fitted, &f, 3).ok()?;
        let pc = NurbsCurve::new(
            fit.knots.knots().to_vec(),
            fit.knots.degree(),
            fit.control.clone(),
            vec![1.0; fit.control.len()],
        )
        .ok()?;
        let close = f.windows(2).all(|w| {
            let q = pc.eval(&(0.5 * (w[0] + w[1])));
            let q = [q[0].clamp(lo[0], hi[0]), q[1].clamp(lo[1], hi[1])];
            near.closest(&c.s.eval(&q[0], &q[1])).2 <= off
        });
        if close {
            return Some((pc, fitted[n - 1]));
        }
        let m = 2 * n - 1;
        let mut more = Vec::with_capacity(m);
        for (i, p) in pts.iter().enumerate() {
            if i > 0 {
                let last = more[more.len() - 1];
                more.push(c.foot(arc, k, at_f((2 * i - 1) as f64 / (m - 1) as f64), last));
            }
            more.push(*p);
        }
        (pts, n) = (more, m);
    }
    None
}

/// The pcurve on `s` of `arc`, a piece of a loop running round direction `k`: from `from`
/// (its start's parameters, the closed one already unwrapped along the loop) to its end,
/// pinned to `end` when given. A straight segment where the other parameter stays within 1e-8
/// of its range of a constant; otherwise cubic pieces between the arc's crossings with the
/// surface's knot lines, joined (C0 at the joints). Returns the pcurve and its end.
pub(super) fn arc_pcurve(
    s: &NurbsSurface<f64, 3>,
    arc: &NurbsCurve<f64, 3>,
    k: usize,
    from: [f64; 2],
    end: Option<[f64; 2]>,
    off: f64,
) -> Option<(NurbsCurve<f64, 2>, [f64; 2])> {
    let c = Chart::new(s, &Closure::of(s));
    let (lo, hi) = (c.lo, c.hi);
    let r = 1 - k;
    let (t0, t1) = arc.hom.domain();
    let n = 4 * SAMPLES;
    let ts: Vec<f64> = (0..n)
        .map(|i| t0 + (t1 - t0) * i as f64 / (n - 1) as f64)
        .collect();
    let mut scan = vec![from];
    for t in &ts[1..] {
        let last = scan[scan.len() - 1];
        scan.push(c.foot(arc, k, *t, last));
    }
    let last = end.unwrap_or(scan[n - 1]);
    if scan
        .iter()
        .all(|p| (p[r] - from[r]).abs() <= 1e-8 * (hi[r] - lo[r]))
    {
        return segment(from, last).map(|l| (l, last));
    }
    let mut cuts = knot_crossings(&c, arc, k, &ts, &scan);
    let tiny = 1e-9 * (t1 - t0);
    cuts.retain(|t| *t > t0 + tiny && *t < t1 - tiny);
    cuts.sort_by(f64::total_cmp);
    cuts.dedup_by(|x, y| (*x - *y).abs() <= tiny);
    let mut bounds = vec![t0];
    bounds.extend(cuts);
    bounds.push(t1);
    let mut x = from;
    let mut out: Option<NurbsCurve<f64, 2>> = None;
    let pieces = bounds.len() - 1;
    for (i, w) in bounds.windows(2).enumerate() {
        let e = if i + 1 == pieces { end } else { None };
        let (pc, y) = piece(&c, arc, k, w[0], w[1], x, e, off)?;
        out = Some(match out {
            None => pc,
            Some(c) => c.joined(&pc).ok()?,
        });
        x = y;
    }
    out.map(|c| (c, x))
}
