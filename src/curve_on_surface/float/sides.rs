//! Step 2, f64 path — classify each segment's piece single-/double-sided exactly (the hull
//! signs by the exact `orient2d`, a crossing proven by certified opposite values of the
//! enclosed `f`, otherwise the exact analysis of [`fn@crate::predicates::single_sided`]), for
//! the f64 control points of the piece (the midpoints of its enclosures, i.e. the piece as
//! rounded to f64), and split a double-sided one at every crossing with its chord. The certificate does not rest on this step — every final segment's bound is
//! computed from the enclosures — it is the paper's step that keeps Theorem 1 applicable.

use super::cells::FCells;
use super::distance::{split_at, sub_curve};
use super::{FSeg, Piece};
use crate::curve_on_surface::sidedness::SidednessStats;
use crate::predicates::single_sided::{Sidedness, single_sided, split_parameters};
use crate::scalar::Scalar;

/// The classification with a certified shortcut for the double-sided case: the hull test
/// (exact `orient2d` signs of the Bernstein coefficients of `f(t) = (C(t) - P_0) × (P_n - P_0)`)
/// decides single-sided pieces as in [`single_sided`]; when it does not, `f` is enclosed at
/// 65 parameters (interval coefficients, interval de Casteljau) and two certified values of
/// opposite sign prove a crossing (intermediate value theorem): the piece is double-sided,
/// and the crossings bracketed by the certified sign changes are located by f64 bisection
/// (where to split is a choice, not a claim). `None`: no certified sign change — the exact
/// analysis decides.
fn classify_fast(c: &[[f64; 2]]) -> Option<Vec<f64>> {
    use super::ibez::{I, blossom};
    use crate::predicates::orient::orient2d;
    let n = c.len() - 1;
    if c[0] == c[n] || n > 30 {
        return None;
    }
    let (mut pos, mut neg) = (false, false);
    for p in &c[1..n] {
        match orient2d(&c[0], &c[n], p).flip() {
            crate::Sign::Positive => pos = true,
            crate::Sign::Negative => neg = true,
            crate::Sign::Zero => {}
        }
    }
    if !(pos && neg) {
        return Some(vec![]);
    }
    let pt = |p: &[f64; 2]| [I::point(p[0]), I::point(p[1])];
    let (p0, pn) = (pt(&c[0]), pt(&c[n]));
    let chord = [pn[0] - p0[0], pn[1] - p0[1]];
    let b: Vec<[I; 1]> = c
        .iter()
        .map(|p| {
            let q = pt(p);
            let d = [q[0] - p0[0], q[1] - p0[1]];
            [d[0] * chord[1] - d[1] * chord[0]]
        })
        .collect();
    let k = 64;
    let value = |t: f64| {
        let ts = vec![I::point(t); n];
        blossom(&b, &ts)[0]
    };
    let sign = |x: I| {
        if x.is_pos() {
            1
        } else if x.is_neg() {
            -1
        } else {
            0
        }
    };
    let mids: Vec<f64> = b.iter().map(|x| x[0].mid()).collect();
    let f64_value = |t: f64| {
        let mut w = mids.clone();
        for r in 1..=n {
            for i in 0..=n - r {
                w[i] = (1.0 - t) * w[i] + t * w[i + 1];
            }
        }
        w[0]
    };
    let mut roots = Vec::new();
    let mut last: Option<(f64, i8)> = None;
    for i in 1..k {
        let t = i as f64 / k as f64;
        let sg = sign(value(t));
        if sg == 0 {
            continue;
        }
        if let Some((t0, s0)) = last
            && s0 != sg
        {
            let (mut lo, mut hi) = (t0, t);
            for _ in 0..52 {
                let m = 0.5 * (lo + hi);
                if (f64_value(m) > 0.0) == (s0 > 0) {
                    lo = m;
                } else {
                    hi = m;
                }
            }
            roots.push(0.5 * (lo + hi));
        }
        last = Some((t, sg));
    }
    if roots.is_empty() { None } else { Some(roots) }
}

/// Split every segment until its (rounded) piece is single-sided (bounded rounds).
pub fn make_single_sided(
    segs: Vec<FSeg>,
    pieces: &[Piece],
    cells: &FCells,
) -> (Vec<FSeg>, SidednessStats) {
    let mut stats = SidednessStats::default();
    let mut work = segs;
    for round in 0..4 {
        let mut out = Vec::with_capacity(work.len());
        let mut changed = false;
        for s in work {
            let c: Vec<[f64; 2]> = sub_curve(&s, pieces).m;
            let fast = classify_fast(&c);
            let class = match &fast {
                Some(r) if r.is_empty() => Sidedness::SingleSided {
                    decided_by_hull: true,
                },
                Some(r) => Sidedness::DoubleSided { crossings: r.len() },
                None => single_sided(&c),
            };
            let roots: Vec<f64> = match class {
                Sidedness::SingleSided { .. } => {
                    if round == 0 {
                        stats.single_sided += 1;
                    }
                    out.push(s);
                    continue;
                }
                Sidedness::DegenerateChord => {
                    stats.closed_split += 1;
                    vec![0.5]
                }
                Sidedness::DoubleSided { .. } if round == 3 => {
                    stats.residual_double_sided += 1;
                    out.push(s);
                    continue;
                }
                Sidedness::DoubleSided { .. } => {
                    stats.double_sided_split += 1;
                    match fast {
                        Some(r) => r,
                        None => split_parameters(&c, 2f64.powi(-40))
                            .into_iter()
                            .map(|(lo, hi)| (Scalar::to_f64(&lo) + Scalar::to_f64(&hi)) / 2.0)
                            .collect(),
                    }
                }
            };
            // Split at each root, left to right (later roots re-expressed locally).
            let mut rest = s;
            for r in roots {
                let local = (s.t0 + (s.t1 - s.t0) * r - rest.t0) / (rest.t1 - rest.t0);
                match split_at(&rest, local, pieces, cells) {
                    Some((l, rr)) => {
                        changed = true;
                        out.push(l);
                        rest = rr;
                    }
                    None => break,
                }
            }
            out.push(rest);
        }
        work = out;
        if !changed {
            break;
        }
    }
    (work, stats)
}
