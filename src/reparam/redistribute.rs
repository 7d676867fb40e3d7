//! Step 3 of the RCA parametrization, an addition to the paper (named as such): before the
//! relaxation of [`super::interior`], the points of each row and column slide along it to
//! their arc-length fractions. The paper's relaxation propagates one neighbour at a time and
//! needed millions of moves on a 13 × 16 grid without it; after it, the relaxation only
//! polishes. `Params::sweeps = 0` leaves it out (the paper's method alone).

use super::ReparamError;
use super::interior::{Grid, eval, lerp2};
use crate::geom::dist;
use crate::spline::NurbsSurface;

/// Sub-samples per grid step of a line in [`redistribute`].
const LINE_SAMPLES: usize = 16;

/// Move the interior points of every row (then every column) along the domain polyline
/// through the line's current points, so that their arc lengths on S (of the polyline's
/// image, sampled `LINE_SAMPLES` times per step) are the fractions `ξ_i` (`η_j`) of the
/// line's length; `sweeps` alternations, stopping early when no point moves by more than
/// `1e-12` of the domain. Points stay on S (they move in the domain). An addition to the
/// paper: it puts the relaxation's start near the target, line by line, so that the
/// relaxation (which propagates one neighbour at a time) only polishes.
pub fn redistribute(
    s: &NurbsSurface<f64, 3>,
    g: &mut Grid,
    sweeps: usize,
) -> Result<(), ReparamError> {
    let (u0, u1, v0, v1) = s.hom.domain();
    let (n, m) = (g.xi.len(), g.eta.len());
    for _ in 0..sweeps {
        let mut moved: f64 = 0.0;
        for dir in 0..2 {
            let lines = if dir == 0 { m } else { n };
            for l in 1..lines.saturating_sub(1) {
                let idx = |k: usize| if dir == 0 { (k, l) } else { (l, k) };
                let t = if dir == 0 { &g.xi } else { &g.eta };
                let len = t.len();
                let mut dom = vec![];
                for k in 0..len - 1 {
                    let (a, b) = (idx(k), idx(k + 1));
                    for q in 0..LINE_SAMPLES {
                        dom.push(lerp2(
                            g.uv[a.0][a.1],
                            g.uv[b.0][b.1],
                            q as f64 / LINE_SAMPLES as f64,
                        ));
                    }
                }
                let last = idx(len - 1);
                dom.push(g.uv[last.0][last.1]);
                let pts = dom
                    .iter()
                    .map(|&p| eval(s, p))
                    .collect::<Result<Vec<_>, _>>()?;
                let mut cum = vec![0.0];
                for w in pts.windows(2) {
                    cum.push(cum.last().unwrap_or(&0.0) + dist(&w[0], &w[1]));
                }
                let total = *cum.last().unwrap_or(&0.0);
                if !(total > 0.0 && total.is_finite()) {
                    continue;
                }
                let targets: Vec<f64> = t.iter().map(|x| x * total).collect();
                let mut q = 0;
                for k in 1..len - 1 {
                    while q + 2 < cum.len() && cum[q + 1] < targets[k] {
                        q += 1;
                    }
                    let span = cum[q + 1] - cum[q];
                    let a = if span > 0.0 {
                        ((targets[k] - cum[q]) / span).clamp(0.0, 1.0)
                    } else {
                        0.0
                    };
                    let mut p = lerp2(dom[q], dom[q + 1], a);
                    p = [p[0].clamp(u0, u1), p[1].clamp(v0, v1)];
                    let (i, j) = idx(k);
                    let old = g.uv[i][j];
                    moved = moved.max(
                        ((p[0] - old[0]) / (u1 - u0))
                            .abs()
                            .max(((p[1] - old[1]) / (v1 - v0)).abs()),
                    );
                    g.uv[i][j] = p;
                    g.x[i][j] = eval(s, p)?;
                }
            }
        }
        if moved <= 1e-12 {
            break;
        }
    }
    Ok(())
}
