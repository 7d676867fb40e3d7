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

/// The entry that decided the last query of a run of queries ([`Near::net_within_hinted`]).
#[derive(Debug, Default)]
pub struct Hint(std::cell::Cell<Option<u32>>);

impl Hint {
    /// A hint naming entry `s` (any index: one out of range is ignored).
    pub fn at(s: u32) -> Hint {
        Hint(std::cell::Cell::new(Some(s)))
    }
}

/// Segments of the output (and chords over them) with a bounding-volume tree over their boxes.
pub struct Near {
    segs: Vec<Segment>,
    /// Per entry of `segs`: `δ` (0 for an output segment, the chord bound for a chord).
    slack: Vec<f64>,
    /// Tree nodes: box, and either two children or a range of entries.
    nodes: Vec<Node>,
    /// Per entry: the previous and the next entry of the same kind along the output (output
    /// segments; chords of one length), `u32::MAX` for none — tried after a hinted entry.
    along: Vec<[u32; 2]>,
}

struct Node {
    b: Box3,
    /// The largest extent of one segment's box per axis, over the node's segments.
    ext: [f64; 3],
    kids: Option<(u32, u32)>,
    range: (u32, u32),
}

/// A segment (a point as a zero-length one).
pub type Segment = ([f64; 3], [f64; 3]);

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

fn seg_box(s: &Segment) -> Box3 {
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
    pub fn new(segs: Vec<Segment>) -> Near {
        let segs: Vec<_> = segs
            .into_iter()
            .filter(|s| s.0.iter().chain(&s.1).all(|x| x.is_finite()))
            .collect();
        let slack = vec![0.0; segs.len()];
        let along = (0..segs.len() as u32)
            .map(|i| [i.wrapping_sub(1), i + 1])
            .collect();
        Near::build_all(segs, slack, along)
    }
    /// The output segments `segs` and chords over runs of 2, 4, …, 64 consecutive segments
    /// (`segs[k].1 == segs[k + 1].0` exactly) whose slack `δ` is at most `d / 2` (see the
    /// module comment). A chord of `L` segments starts every `L / 2` segments, so any part of
    /// the polyline at most `L / 2` segments long lies under one chord.
    pub fn with_chords(segs: Vec<Segment>, d: f64) -> Near {
        let segs: Vec<_> = segs
            .into_iter()
            .filter(|s| s.0.iter().chain(&s.1).all(|x| x.is_finite()))
            .collect();
        // Chords with the index of the segment they start at and their kind (2^kind
        // segments).
        let mut chords: Vec<(usize, u32, Segment, f64)> = Vec::new();
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
                            chords.push((start + i, len.trailing_zeros(), (p, q), delta));
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
        // Every segment followed by the chords that start at it (shortest first), so that
        // consecutive entries lie close together along the output (see [`Near::build`]).
        chords.sort_by_key(|c| c.0);
        let n = segs.len() + chords.len();
        let (mut all, mut slack) = (Vec::with_capacity(n), Vec::with_capacity(n));
        let mut along = vec![[u32::MAX; 2]; n];
        // The last entry placed per kind (0: segments, k: chords of 2^k segments).
        let mut last = [u32::MAX; 8];
        let mut place = |kind: u32, all_len: usize| {
            let (pos, k) = (all_len as u32, kind as usize);
            if let Some(prev) = last.get(k).copied().filter(|&p| p != u32::MAX) {
                along[prev as usize][1] = pos;
                along[pos as usize][0] = prev;
            }
            if let Some(l) = last.get_mut(k) {
                *l = pos;
            }
        };
        let mut next = chords.into_iter().peekable();
        for (k, s) in segs.into_iter().enumerate() {
            place(0, all.len());
            all.push(s);
            slack.push(0.0);
            while let Some((_, kind, c, delta)) = next.next_if(|c| c.0 == k) {
                place(kind, all.len());
                all.push(c);
                slack.push(delta);
            }
        }
        Near::build_all(all, slack, along)
    }
    fn build_all(segs: Vec<Segment>, slack: Vec<f64>, along: Vec<[u32; 2]>) -> Near {
        let mut n = Near {
            along,
            segs,
            slack,
            nodes: Vec::new(),
        };
        if !n.segs.is_empty() {
            n.build(0, n.segs.len());
        }
        n
    }
    /// The tree over the entries `lo..hi` in their order: consecutive entries of a polyline
    /// (and its chords) lie close together, so halves of a range make compact boxes without a
    /// sort; a node's box and extents are its children's merged. The tree only orders and
    /// prunes the search (see [`Near::hull_within`]).
    fn build(&mut self, lo: usize, hi: usize) -> u32 {
        let id = self.nodes.len() as u32;
        self.nodes.push(Node {
            b: ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]),
            ext: [0.0; 3],
            kids: None,
            range: (lo as u32, hi as u32),
        });
        let mut b: Box3 = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        let mut ext = [0.0f64; 3];
        let mut merge = |c: &Box3, e: &[f64; 3]| {
            for k in 0..3 {
                b.0[k] = b.0[k].min(c.0[k]);
                b.1[k] = b.1[k].max(c.1[k]);
                ext[k] = ext[k].max(e[k]);
            }
        };
        if hi - lo > 4 {
            let mid = (lo + hi) / 2;
            let l = self.build(lo, mid);
            let r = self.build(mid, hi);
            for c in [l, r] {
                let n = &self.nodes[c as usize];
                merge(&n.b, &n.ext);
            }
            self.nodes[id as usize].kids = Some((l, r));
        } else {
            for seg in &self.segs[lo..hi] {
                let s = seg_box(seg);
                merge(&s, &std::array::from_fn(|k| s.1[k] - s.0[k]));
            }
        }
        let n = &mut self.nodes[id as usize];
        n.b = b;
        n.ext = ext;
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
            let [prev, next] = self.along.get(s as usize).copied().unwrap_or([u32::MAX; 2]);
            for t in [s, next, prev] {
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
                    for s in n.range.0..n.range.1 {
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
mod tests;
