//! The output set `O` — the reported branch polylines (closed ones closed) and touching
//! points — and the rigorous test "every point of a box lies within `d` of `O`".
//!
//! Distance to one segment is a convex function, so its largest value over a box is taken at
//! a corner: a box lies within `d` of a segment when all eight corners do. For a corner `c`,
//! any point `s(t)` of the segment bounds the distance from above; `t` is chosen by rounded
//! projection and `‖c − s(t)‖` is bounded with a forward error bound ([`dist_upper`]), so the
//! test never says "near" wrongly. A control-point hull is decided the same way over its
//! points' boxes, each taken inside a ball: the distance is 1-Lipschitz, so every point of
//! the ball lies within `dist(centre) + radius` (one distance per control point instead of
//! eight, for boxes a few ulps wide).
//!
//! **Chords** ([`Near::with_chords`]). Let `p_i, …, p_j` be consecutive vertices of an output
//! polyline and `δ ≥ max_m dist(p_m, line p_i p_j)`. Every point `x` of the chord `[p_i, p_j]`
//! lies within `δ` of the polyline: the plane through `x` perpendicular to the chord separates
//! `p_i` from `p_j`, so the polyline meets it at some `y` on a segment `[p_m, p_{m+1}]`; the
//! distance to the line is convex along that segment, so `dist(y, line) ≤ δ`, and `x` is the
//! foot of `y` on the line, so `‖x − y‖ = dist(y, line) ≤ δ`. Hence a point within `d − δ` of
//! the chord is within `d` of the polyline (triangle inequality), and a box or hull can be
//! decided against a chord with the slack `δ` (taken as the rounded-up distance to the chord
//! *segment*, which is at least the distance to its line). Chords let a piece lying along the
//! output be decided whole where it spans several short segments (a curve piece straddling a
//! vertex is otherwise never within `d` of *one* segment, whatever its size).

use super::patch::{Box3, V};

/// Segments of the output with a bounding-volume tree over their boxes.
/// The entry that decided the last query of a run of queries ([`Near::net_within_hinted`]).
#[derive(Debug, Default)]
pub struct Hint(std::cell::Cell<Option<u32>>);

impl Hint {
    /// A hint naming entry `s` (any index: one out of range is ignored).
    pub fn at(s: u32) -> Hint {
        Hint(std::cell::Cell::new(Some(s)))
    }
}

pub struct Near {
    segs: Vec<([f64; 3], [f64; 3])>,
    /// Per entry of `segs`: `δ` (0 for an output segment, the chord bound for a chord).
    slack: Vec<f64>,
    /// Tree nodes: box, and either two children or a range of `order`.
    nodes: Vec<Node>,
    order: Vec<u32>,
}

struct Node {
    b: Box3,
    /// The largest extent of one segment's box per axis, over the node's segments.
    ext: [f64; 3],
    kids: Option<(u32, u32)>,
    range: (u32, u32),
}

/// A ball: centre and radius (every point of it within the radius of the centre).
type Ball = ([f64; 3], f64);

/// A ball holding the box `p`: its rounded midpoint, and as radius the sum over the axes of
/// the larger distance to the box's ends, rounded up (a point box gives radius 0).
fn ball(p: &V) -> Ball {
    let c: [f64; 3] = std::array::from_fn(|k| 0.5 * p[k].lo + 0.5 * p[k].hi);
    let h: [f64; 3] = std::array::from_fn(|k| {
        let e = (p[k].hi - c[k]).max(c[k] - p[k].lo);
        if e > 0.0 { e.next_up() } else { 0.0 }
    });
    // The sum of the half-widths bounds the Euclidean length (no squares: nothing to
    // underflow); each sum rounded up.
    let r = if h.iter().all(|x| *x == 0.0) {
        0.0
    } else {
        ((h[0] + h[1]).next_up() + h[2]).next_up()
    };
    (c, r)
}

fn seg_box(s: &([f64; 3], [f64; 3])) -> Box3 {
    (
        std::array::from_fn(|k| s.0[k].min(s.1[k])),
        std::array::from_fn(|k| s.0[k].max(s.1[k])),
    )
}

/// The parameter `t ∈ [0, 1]` of the point of the segment `p q` nearest to `c` (f64; 0 when
/// the segment is a point or the division is not finite), and `q − p`.
fn foot(c: &[f64; 3], p: &[f64; 3], q: &[f64; 3]) -> (f64, [f64; 3]) {
    let d: [f64; 3] = std::array::from_fn(|k| q[k] - p[k]);
    let e: [f64; 3] = std::array::from_fn(|k| c[k] - p[k]);
    let dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    let t = if dd > 0.0 {
        ((e[0] * d[0] + e[1] * d[1] + e[2] * d[2]) / dd).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (if t.is_finite() { t } else { 0.0 }, d)
}

/// Upper bound on the distance from `c` to the segment `[p, q]`: the distance from `c` to the
/// point `x = p + (q − p) t` of the segment, `t ∈ [0, 1]` the `f64` foot of `foot` (taken as
/// the exact number it is, so `x` lies on the segment), computed in `f64` and enlarged by a
/// forward error bound. With `u = 2⁻⁵³`, each rounding `fl(a ∘ b) = (a ∘ b)(1 + δ)`,
/// `|δ| ≤ u`, so its error is at most `u′ |fl(a ∘ b)|`, `u′ = u / (1 − u)`:
///
/// * per coordinate, `d̂ = fl(q − p)`, `ŷ = fl(d̂ t)`, `x̂ = fl(p + ŷ)`, `ê = fl(c − x̂)`:
///   `|ŷ − (q − p) t| ≤ u′|ŷ| + t u′|d̂| ≤ 2.01 u |ŷ|` (as `|d̂ t| ≤ |ŷ| / (1 − u)`), and so
///   `|ê − e| ≤ E = 2.1 u (|ê| + |x̂| + |ŷ|)` for `e = c − x`; a product `ŷ` that underflows
///   has an absolute error below the smallest normal number `ν`, added then (sums and
///   differences that underflow are exact);
/// * `ŝ = fl(√fl(Σ ê_k²))` satisfies `‖ê‖ ≤ ŝ (1 − u)⁻¹ (1 − γ₃)^(−1/2) ≤ ŝ (1 + 3u)`, plus
///   `√(3 · 2⁻¹⁰⁷⁴) < 10⁻¹⁶⁰` when a non-zero `ê_k` is small enough for its square to underflow;
///
/// so `‖c − x‖ ≤ ŝ (1 + 8u) + 2 Σ_k E_k` (+ the underflow terms), the margins covering the
/// roundings of this expression too, which is rounded up once more at the end. When every
/// term is zero the distance is exactly zero (every step was exact). Infinity when a square
/// or the sum overflows (no claim).
pub fn dist_upper(c: &[f64; 3], p: &[f64; 3], q: &[f64; 3]) -> f64 {
    const U: f64 = f64::EPSILON / 2.0;
    let (t, d) = foot(c, p, q);
    let mut s = 0.0;
    let mut err = 0.0;
    let mut tiny = false;
    for k in 0..3 {
        let y = d[k] * t;
        let x = p[k] + y;
        let e = c[k] - x;
        s += e * e;
        err += e.abs() + x.abs() + y.abs();
        if y != 0.0 && y.abs() < f64::MIN_POSITIVE {
            err += f64::MIN_POSITIVE / (4.2 * U);
        }
        tiny |= e != 0.0 && e.abs() < 1e-150;
    }
    let bound = s.sqrt() * (1.0 + 8.0 * U) + 4.2 * U * err + if tiny { 1e-160 } else { 0.0 };
    if bound == 0.0 {
        0.0
    } else if bound.is_finite() {
        bound.next_up()
    } else {
        f64::INFINITY
    }
}

impl Near {
    pub fn new(segs: Vec<([f64; 3], [f64; 3])>) -> Near {
        let segs: Vec<_> = segs
            .into_iter()
            .filter(|s| s.0.iter().chain(&s.1).all(|x| x.is_finite()))
            .collect();
        let slack = vec![0.0; segs.len()];
        Near::build_all(segs, slack)
    }
    /// The output segments `segs` and chords over runs of 2, 4, …, 64 consecutive segments
    /// (`segs[k].1 == segs[k + 1].0` exactly) whose slack `δ` is at most `d / 2` (see the
    /// module comment). A chord of `L` segments starts every `L / 2` segments, so any part of
    /// the polyline at most `L / 2` segments long lies under one chord.
    pub fn with_chords(segs: Vec<([f64; 3], [f64; 3])>, d: f64) -> Near {
        let segs: Vec<_> = segs
            .into_iter()
            .filter(|s| s.0.iter().chain(&s.1).all(|x| x.is_finite()))
            .collect();
        let mut slack = vec![0.0; segs.len()];
        let mut chords = Vec::new();
        let mut start = 0;
        while start < segs.len() {
            let mut end = start + 1;
            while end < segs.len() && segs[end - 1].1 == segs[end].0 {
                end += 1;
            }
            let pts: Vec<[f64; 3]> = std::iter::once(segs[start].0)
                .chain(segs[start..end].iter().map(|s| s.1))
                .collect();
            // `kept[i]`: the chord of the last length from vertex `i` was kept. A chord of
            // length 2L from `i` (a multiple of L) is tried only when both chords of length L
            // it spans, from `i` and `i + L`, were kept: where the curve bends enough to fail
            // a chord, a chord twice as long over it mostly fails too (on curved output at
            // small `d`, no chord of 4 segments passes at all). Which chords are tried changes
            // only how often a box is decided by one, never what a kept chord claims.
            let mut kept = vec![true; pts.len()];
            let mut len = 2;
            while len <= 64 && len < pts.len() {
                let mut now = vec![false; pts.len()];
                let mut any = false;
                let mut i = 0;
                while i + len < pts.len() {
                    let half = len / 2;
                    let tried = kept[i] && kept.get(i + half).copied().unwrap_or(false);
                    if tried {
                        let (p, q) = (pts[i], pts[i + len]);
                        let mut delta = 0.0f64;
                        for m in &pts[i + 1..i + len] {
                            delta = delta.max(dist_upper(m, &p, &q));
                            if delta > 0.5 * d {
                                break;
                            }
                        }
                        if delta <= 0.5 * d {
                            chords.push(((p, q), delta));
                            now[i] = true;
                            any = true;
                        }
                    }
                    i += half;
                }
                if !any {
                    break;
                }
                kept = now;
                len *= 2;
            }
            start = end;
        }
        let mut segs = segs;
        for (c, delta) in chords {
            segs.push(c);
            slack.push(delta);
        }
        Near::build_all(segs, slack)
    }
    fn build_all(segs: Vec<([f64; 3], [f64; 3])>, slack: Vec<f64>) -> Near {
        let mut n = Near {
            order: (0..segs.len() as u32).collect(),
            segs,
            slack,
            nodes: Vec::new(),
        };
        if !n.segs.is_empty() {
            n.build(0, n.segs.len());
        }
        n
    }
    fn build(&mut self, lo: usize, hi: usize) -> u32 {
        let mut b: Box3 = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        let mut ext = [0.0f64; 3];
        for &i in &self.order[lo..hi] {
            let s = seg_box(&self.segs[i as usize]);
            for k in 0..3 {
                b.0[k] = b.0[k].min(s.0[k]);
                b.1[k] = b.1[k].max(s.1[k]);
                ext[k] = ext[k].max(s.1[k] - s.0[k]);
            }
        }
        let id = self.nodes.len() as u32;
        self.nodes.push(Node {
            b,
            ext,
            kids: None,
            range: (lo as u32, hi as u32),
        });
        if hi - lo > 4 {
            let axis = (0..3)
                .max_by(|&x, &y| (b.1[x] - b.0[x]).total_cmp(&(b.1[y] - b.0[y])))
                .unwrap_or(0);
            let mid = (lo + hi) / 2;
            let segs = &self.segs;
            let key = |i: &u32| {
                let s = &segs[*i as usize];
                s.0[axis] + s.1[axis]
            };
            self.order[lo..hi].select_nth_unstable_by(mid - lo, |a, b| key(a).total_cmp(&key(b)));
            let l = self.build(lo, mid);
            let r = self.build(mid, hi);
            self.nodes[id as usize].kids = Some((l, r));
        }
        id
    }
    /// Whether every point of box `b` is proven within `d` of the output (of one output
    /// segment, or of one chord with its slack).
    pub fn box_within(&self, b: &Box3, d: f64) -> bool {
        let corners: Vec<Ball> = (0..8)
            .map(|m| {
                let c = std::array::from_fn(|k| if m >> k & 1 == 0 { b.0[k] } else { b.1[k] });
                (c, 0.0)
            })
            .collect();
        self.hull_within(&corners, b, d, &Hint::default())
    }
    /// Whether the convex hull of enclosed control points (each an interval box, given as
    /// Cartesian enclosures) is proven within `d` of the output (one segment, or one chord with
    /// its slack). A piece with positive weights lies in that hull, and the distance to a
    /// segment is convex, so its largest value over the hull is taken at a point of one of the
    /// boxes; each box is taken within a ball around its midpoint.
    pub fn net_within(&self, pts: &[V], d: f64) -> bool {
        self.net_within_hinted(pts, d, &Hint::default())
    }
    /// [`Near::net_within`], trying first the entry that decided the last call given the
    /// same `hint` and the entries listed beside it (a query along a curve is usually decided
    /// by the segment or chord that decided its neighbour, or the next one). The hint only
    /// orders the search: the same test decides.
    pub fn net_within_hinted(&self, pts: &[V], d: f64, hint: &Hint) -> bool {
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        let mut balls = Vec::with_capacity(pts.len());
        for p in pts {
            for k in 0..3 {
                lo[k] = lo[k].min(p[k].lo);
                hi[k] = hi[k].max(p[k].hi);
            }
            balls.push(ball(p));
        }
        self.hull_within(&balls, &(lo, hi), d, hint)
    }
    /// Whether every ball (centre, radius) is proven within `d` of entry `s` (a segment, or
    /// a chord with its slack): the distance to a segment is 1-Lipschitz, so a point of the
    /// ball is within `dist(centre) + radius`; the sum with the slack is rounded up.
    fn entry_holds(&self, s: u32, balls: &[Ball], d: f64) -> bool {
        let (p, q) = &self.segs[s as usize];
        let slack = self.slack[s as usize];
        balls.iter().all(|(c, r)| {
            let far = ((dist_upper(c, p, q) + r).next_up() + slack).next_up();
            far <= d
        })
    }
    fn hull_within(&self, balls: &[Ball], b: &Box3, d: f64, hint: &Hint) -> bool {
        if self.nodes.is_empty()
            || balls.is_empty()
            || !balls
                .iter()
                .all(|(c, r)| r.is_finite() && c.iter().all(|x| x.is_finite()))
        {
            return false;
        }
        // The hinted entry, then its neighbours in the list (the next part along a curve is
        // usually under the next segment or chord of the same run).
        if let Some(s) = hint.0.get() {
            for t in [s, s.wrapping_add(1), s.wrapping_sub(1)] {
                if (t as usize) < self.segs.len() && self.entry_holds(t, balls, d) {
                    hint.0.set(Some(t));
                    return true;
                }
            }
        }
        let mut stack = vec![0u32];
        while let Some(i) = stack.pop() {
            let n = &self.nodes[i as usize];
            // A segment within d of all corners has its box within d of the query box, and
            // the query box (the corners' box) lies in the segment's box grown by d: no
            // wider on any axis than the segment's extent plus 2d. (A prune only skips
            // candidates, it never decides "near": rounding here cannot make a false claim.)
            if (0..3).any(|k| {
                n.b.1[k] < b.0[k] - d
                    || n.b.0[k] > b.1[k] + d
                    || b.1[k] - b.0[k] > n.ext[k] + 2.0 * d
            }) {
                continue;
            }
            match n.kids {
                Some((l, r)) => {
                    stack.push(l);
                    stack.push(r);
                }
                None => {
                    for &s in &self.order[n.range.0 as usize..n.range.1 as usize] {
                        if self.entry_holds(s, balls, d) {
                            hint.0.set(Some(s));
                            return true;
                        }
                    }
                }
            }
        }
        false
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::Interval;

    #[test]
    fn box_near_a_polyline() {
        let segs: Vec<_> = (0..100)
            .map(|i| ([i as f64, 0.0, 0.0], [i as f64 + 1.0, 0.0, 0.0]))
            .collect();
        let n = Near::new(segs);
        assert!(n.box_within(&([10.2, -0.1, -0.1], [10.4, 0.1, 0.1]), 0.15));
        // Corner distance is sqrt(0.02) = 0.1414..: refused just below it.
        assert!(!n.box_within(&([10.2, -0.1, -0.1], [10.4, 0.1, 0.1]), 0.141));
        // A box spanning a vertex of the polyline: within d of one segment only if it fits.
        assert!(!n.box_within(&([10.5, 2.0, 0.0], [10.6, 2.1, 0.0]), 1.0));
        assert!(!Near::new(Vec::new()).box_within(&([0.0; 3], [0.0; 3]), 1.0));
        assert!(n.box_within(&([0.0; 3], [0.0; 3]), 1e-300));
    }

    /// Every corner of a box lies within the ball's radius of its centre (exact rationals), for
    /// boxes a few ulps wide and wide ones, at magnitudes 1e-300 … 1e300, subnormal widths
    /// included; a point box is a ball of radius 0.
    #[test]
    fn ball_holds_its_box() {
        use num_rational::BigRational;
        let q = |x: f64| BigRational::from_float(x).unwrap();
        let mut r = crate::spline::test_params::rng(0xba11);
        for k in 0..3000 {
            let scale = 10f64.powi((k % 61) * 10 - 300);
            let p: V = std::array::from_fn(|_| {
                let lo = (r() - 0.5) * scale;
                let hi = match k % 3 {
                    0 => lo.next_up().next_up(),
                    1 => lo + r() * scale,
                    _ => lo + f64::from_bits(1 + (r() * 8.0) as u64),
                };
                Interval::new(lo, hi.max(lo))
            });
            let (c, rad) = ball(&p);
            let r2 = q(rad) * q(rad);
            for m in 0..8 {
                let d2: BigRational = (0..3)
                    .map(|i| {
                        let e = if m >> i & 1 == 0 { p[i].lo } else { p[i].hi };
                        let v = q(e) - q(c[i]);
                        &v * &v
                    })
                    .sum();
                assert!(d2 <= r2, "{p:?}: corner {m} outside radius {rad} of {c:?}");
            }
        }
        let x = [Interval::point(1.5); 3];
        assert_eq!(ball(&x), ([1.5; 3], 0.0));
    }

    /// Against the exact distance to the segment (rationals: the exact foot, clamped): the
    /// bound is never below it, at magnitudes 1e-300 … 1e300, points on, near and far from the
    /// segment, degenerate segments included; and it is tight (within 1e-12 relative plus
    /// 1e-14 of the coordinates' magnitude).
    #[test]
    fn dist_upper_is_an_upper_bound() {
        use num_rational::BigRational;
        use num_traits::{One, ToPrimitive, Zero};
        let r = |x: f64| BigRational::from_float(x).unwrap();
        let mut x = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        for k in 0..3000 {
            let scale = 10f64.powi((k % 61) * 10 - 300);
            let p = [next() * scale, next() * scale, next() * scale];
            let q = if k % 17 == 0 {
                p
            } else {
                [next() * scale, next() * scale, next() * scale]
            };
            let t = next() + 0.5;
            let off = [0.0, 1e-12, 1e-6, 1.0][k as usize % 4] * scale;
            let c: [f64; 3] = std::array::from_fn(|i| p[i] + t * (q[i] - p[i]) + off * next());
            let u = dist_upper(&c, &p, &q);
            if u.is_infinite() {
                // Only where the squares overflow (no claim).
                assert!(scale > 1e150, "{c:?} {p:?} {q:?}");
                continue;
            }
            let (pr, qr, cr) = (p.map(r), q.map(r), c.map(r));
            let d: Vec<BigRational> = (0..3).map(|i| &qr[i] - &pr[i]).collect();
            let e: Vec<BigRational> = (0..3).map(|i| &cr[i] - &pr[i]).collect();
            let dd: BigRational = d.iter().map(|v| v * v).sum();
            let ed: BigRational = (0..3).map(|i| &e[i] * &d[i]).sum();
            let tt = if dd.is_zero() {
                BigRational::zero()
            } else {
                (ed / dd).max(BigRational::zero()).min(BigRational::one())
            };
            let dist2: BigRational = (0..3)
                .map(|i| {
                    let v = &e[i] - &tt * &d[i];
                    &v * &v
                })
                .sum();
            let ur = r(u);
            assert!(
                dist2 <= &ur * &ur,
                "{c:?} {p:?} {q:?}: bound {u} below the distance"
            );
            let exact = dist2.to_f64().unwrap().sqrt();
            let m = c
                .iter()
                .chain(&p)
                .chain(&q)
                .fold(0.0f64, |m, v| m.max(v.abs()));
            assert!(
                u <= exact * (1.0 + 1e-12) + 1e-14 * m + 1e-159,
                "{u} vs {exact}"
            );
        }
    }
}
