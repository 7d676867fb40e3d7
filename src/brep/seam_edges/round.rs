//! Loops that run once round a closed surface and where they cross its seam (evidence,
//! sampled: see the module comment of [`super`]).

use crate::brep::pcurve::project::{Chart, unwrap};
use crate::geom::dist;
use crate::spline::closure::Closure;
use crate::spline::project::project;
use crate::spline::{NurbsCurve, NurbsSurface};

/// Samples along a closed edge when deciding whether it runs round a closed surface.
const SAMPLES: usize = 33;

/// Bisection steps locating a seam crossing.
const BISECTIONS: usize = 64;

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
