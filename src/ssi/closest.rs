//! Global certified distance from a point to a set of NURBS faces.
//!
//! # Distance (branch and bound)
//!
//! Every face is cut into its Bézier pieces (exact rational knot insertion, every control
//! point then enclosed in an outward-rounded interval: `super::coverage::roots`); pieces
//! are quartered by de Casteljau at ½ in interval arithmetic, so each piece stands for the
//! exact sub-patch. For a query point `x` and a piece `P`:
//!
//! * **lower bound**: `P` lies in the convex hull of its enclosed Cartesian control points
//!   (positive weights, checked), hence in their box; the distance from `x` to that box,
//!   rounded down, is a lower bound on `dist(x, P)`. When a direction `e` is known (from `x`
//!   to the best point so far, or from the centre of the piece's box to `x`),
//!   `min_i e·(x − P_i) / |e|` (rounded down) is one too: the hull lies beyond that plane.
//! * **upper bound**: the corner control points of a Bézier piece are points of the surface;
//!   the largest distance from `x` to a corner's enclosure, rounded up, bounds
//!   `dist(x, S)` from above. So does the enclosure of `S(u, v)` at a parameter found by
//!   Gauss–Newton ([`super::enclose::enclose_point`]).
//!
//! The pieces of all faces (faces first as single entries bounded by the box of their
//! pieces, so far faces are never opened) are kept in a heap by lower bound; the lowest is
//! taken and split until it cannot be below the best upper bound by more than `eps`, or the
//! budget runs out. The returned `[lower, upper]` holds `dist(x, ∪ faces)` whatever the
//! budget: the lower end is the least lower bound of the pieces still open, which is at most
//! the lower bound of the piece holding a closest point. No local search decides anything;
//! there is no local-minimum trap (poles, seams, several near faces).

use super::coverage::patch::{Box3, IPatch, V, box_of};
use super::coverage::roots;
use super::enclose::enclose_point;
use crate::scalar::Interval;
use crate::spline::NurbsSurface;
use std::cmp::Ordering;
use std::collections::BinaryHeap;

fn iv(x: f64) -> Interval {
    Interval::point(x)
}

/// A face prepared for distance queries: its enclosed Bézier pieces.
pub struct IvSurface {
    pub s: NurbsSurface<f64, 3>,
    pieces: Vec<(IPatch, [f64; 4])>,
    /// Parameter domain `[u0, u1, v0, v1]`.
    pub dom: [f64; 4],
    /// Box of all enclosed control points (`None`: no enclosure, weights not positive).
    pub hull: Option<Box3>,
}

impl IvSurface {
    pub fn new(s: &NurbsSurface<f64, 3>) -> IvSurface {
        let pieces: Vec<(IPatch, [f64; 4])> =
            roots(s).iter().map(|c| (c.patch.clone(), c.uv)).collect();
        let (u0, u1, v0, v1) = s.hom.domain();
        let mut hull: Option<Box3> = Some(([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]));
        for (p, _) in &pieces {
            hull = match (hull, p.cartesian().map(|q| box_of(&q))) {
                (Some(a), Some(b)) => Some((
                    std::array::from_fn(|k| a.0[k].min(b.0[k])),
                    std::array::from_fn(|k| a.1[k].max(b.1[k])),
                )),
                _ => None,
            };
        }
        IvSurface {
            s: s.clone(),
            dom: [u0, u1, v0, v1],
            hull: hull.filter(|h| h.0[0] <= h.1[0]),
            pieces,
        }
    }

    /// Enclosure of the surface point `S(u, v)`.
    pub fn point(&self, uv: &[f64; 2]) -> Option<V> {
        enclose_point(&self.s, iv(uv[0]), iv(uv[1]))
    }
}

/// Largest distance from `x` to a point of the box of `p`, rounded up.
pub(crate) fn far_upper(x: &[f64; 3], p: &V) -> f64 {
    let mut s = iv(0.0);
    for k in 0..3 {
        let d = (iv(x[k]) - p[k]).mag();
        s = s + iv(d).sqr();
    }
    if !s.is_finite() {
        return f64::INFINITY;
    }
    s.hi.sqrt().next_up()
}

/// Distance from `x` to the box `b`, rounded down.
pub(crate) fn box_lower(x: &[f64; 3], b: &Box3) -> f64 {
    let mut s = iv(0.0);
    for k in 0..3 {
        let g = (iv(b.0[k]) - iv(x[k])).lo.max((iv(x[k]) - iv(b.1[k])).lo);
        if g > 0.0 {
            s = s + iv(g).sqr();
        }
    }
    if s.lo <= 0.0 {
        0.0
    } else {
        s.lo.sqrt().next_down().max(0.0)
    }
}

/// `min_i e·(x − p_i) / |e|`, rounded down (a lower bound on the distance from `x` to the
/// hull of the points when positive); 0 when not positive.
fn dir_lower(x: &[f64; 3], e: &[f64; 3], pts: &[V]) -> f64 {
    let ee = e.map(iv);
    let n2 = ee[0].sqr() + ee[1].sqr() + ee[2].sqr();
    if n2.lo.partial_cmp(&(0.0)) != Some(std::cmp::Ordering::Greater) || !n2.is_finite() {
        return 0.0;
    }
    let mut m = f64::INFINITY;
    for p in pts {
        let t = (0..3).fold(iv(0.0), |a, k| a + ee[k] * (iv(x[k]) - p[k]));
        m = m.min(t.lo);
    }
    if m.partial_cmp(&(0.0)) != Some(std::cmp::Ordering::Greater) {
        return 0.0;
    }
    (m / n2.hi.sqrt().next_up()).next_down().max(0.0)
}

/// The result of a distance query.
#[derive(Clone, Copy, Debug)]
pub struct Closest {
    /// Proven `lower <= dist(x, faces) <= upper`.
    pub lower: f64,
    pub upper: f64,
    /// Face and parameters of the point that gives `upper`.
    pub face: usize,
    pub uv: [f64; 2],
    /// Pieces examined.
    pub pieces: usize,
}

struct Node {
    lower: f64,
    face: usize,
    /// `None`: the whole face, not yet opened.
    piece: Option<(IPatch, [f64; 4], u32)>,
}
impl PartialEq for Node {
    fn eq(&self, o: &Self) -> bool {
        self.lower == o.lower
    }
}
impl Eq for Node {}
impl PartialOrd for Node {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}
impl Ord for Node {
    fn cmp(&self, o: &Self) -> Ordering {
        // Min-heap on the lower bound.
        o.lower.total_cmp(&self.lower)
    }
}

/// Budget of a distance query.
#[derive(Clone, Copy, Debug)]
pub struct ClosestParams {
    /// Stop when `upper − lower <= eps`.
    pub eps: f64,
    /// Pieces examined at most.
    pub max_pieces: usize,
}

/// Proven bounds on the distance from `x` to the union of `faces` (only those with
/// `use_face(i)`), by branch and bound (module comment). `None` when no face is used.
pub fn closest(
    faces: &[IvSurface],
    x: &[f64; 3],
    prm: &ClosestParams,
    use_face: &dyn Fn(usize) -> bool,
) -> Option<Closest> {
    if !x.iter().all(|c| c.is_finite()) {
        return None;
    }
    let mut heap = BinaryHeap::new();
    for (i, f) in faces.iter().enumerate() {
        if use_face(i) {
            heap.push(Node {
                lower: f.hull.as_ref().map_or(0.0, |h| box_lower(x, h)),
                face: i,
                piece: None,
            });
        }
    }
    if heap.is_empty() {
        return None;
    }
    let mut best = Closest {
        lower: 0.0,
        upper: f64::INFINITY,
        face: usize::MAX,
        uv: [0.0; 2],
        pieces: 0,
    };
    // Lower bounds of pieces that cannot be refined further (kept for soundness).
    let mut stuck = f64::INFINITY;
    let mut newton_at = 4usize;
    let mut lower = 0.0;
    let mut exhausted = true;
    while let Some(n) = heap.pop() {
        if n.lower.min(stuck) >= best.upper - prm.eps {
            lower = n.lower.min(stuck);
            exhausted = false;
            break;
        }
        if best.pieces >= prm.max_pieces {
            lower = n.lower.min(stuck);
            exhausted = false;
            break;
        }
        let f = &faces[n.face];
        let kids: Vec<(IPatch, [f64; 4], u32)> = match n.piece {
            None => f.pieces.iter().map(|(p, r)| (p.clone(), *r, 0)).collect(),
            Some((p, r, depth)) => {
                best.pieces += 1;
                if depth >= 48 {
                    stuck = stuck.min(n.lower);
                    continue;
                }
                let [u0, u1, v0, v1] = r;
                let (um, vm) = (0.5 * (u0 + u1), 0.5 * (v0 + v1));
                let [a, b, c, d] = p.quarters();
                vec![
                    (a, [u0, um, v0, vm], depth + 1),
                    (b, [u0, um, vm, v1], depth + 1),
                    (c, [um, u1, v0, vm], depth + 1),
                    (d, [um, u1, vm, v1], depth + 1),
                ]
            }
        };
        for (p, r, depth) in kids {
            let pts = p.cartesian();
            if let Some(pts) = &pts {
                // Corners are surface points: upper bounds.
                for (i, j, uv) in [
                    (0, 0, [r[0], r[2]]),
                    (p.p, 0, [r[1], r[2]]),
                    (0, p.q, [r[0], r[3]]),
                    (p.p, p.q, [r[1], r[3]]),
                ] {
                    let d = far_upper(x, &pts[p.at(i, j)]);
                    if d < best.upper {
                        (best.upper, best.face, best.uv) = (d, n.face, uv);
                    }
                }
            }
            let lo = match &pts {
                None => 0.0,
                Some(pts) => {
                    let bx = box_of(pts);
                    let mut l = box_lower(x, &bx);
                    // The direction from the piece's centre to x: nearly normal to a small
                    // piece near its closest point, so the bound is close to the distance.
                    let e: [f64; 3] = std::array::from_fn(|k| x[k] - 0.5 * (bx.0[k] + bx.1[k]));
                    l = l.max(dir_lower(x, &e, pts));
                    if best.face != usize::MAX && best.upper > 0.0 {
                        let foot = faces[best.face].s.eval(&best.uv[0], &best.uv[1]);
                        let e: [f64; 3] = std::array::from_fn(|k| x[k] - foot[k]);
                        l = l.max(dir_lower(x, &e, pts));
                    }
                    l
                }
            };
            if lo <= best.upper {
                heap.push(Node {
                    lower: lo,
                    face: n.face,
                    piece: Some((p, r, depth)),
                });
            }
        }
        if best.pieces >= newton_at && best.face != usize::MAX {
            newton_at *= 8;
            let g = &faces[best.face];
            let (uv, _) = crate::spline::project::descend(&g.s, x, best.uv, &g.dom);
            if let Some(p) = g.point(&uv) {
                let d = far_upper(x, &p);
                if d < best.upper {
                    (best.upper, best.uv) = (d, uv);
                }
            }
        }
    }
    if exhausted {
        // Every piece was discarded: its lower bound exceeded the best upper bound.
        lower = best.upper.min(stuck);
    }
    best.lower = lower.min(best.upper).max(0.0);
    (best.face != usize::MAX).then_some(best)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spline::construct::{Frame, sphere};

    fn frame() -> Frame {
        let (c, s) = (0.6f64, 0.8f64);
        Frame {
            o: [0.3, -0.2, 0.1],
            x: [c, s, 0.0],
            y: [-s * 0.6, c * 0.6, 0.8],
            z: [s * 0.8, -c * 0.8, 0.6],
        }
    }

    /// The bounds hold the true distance to a sphere (|‖x − o‖ − r|), near the pole too.
    #[test]
    fn sphere_distance_is_enclosed() {
        let f = frame();
        let s = IvSurface::new(&sphere(&f, 1.0).unwrap());
        let prm = ClosestParams {
            eps: 1e-9,
            max_pieces: 20_000,
        };
        for (a, b, c) in [
            (0.0, 0.0, 1.0 + 1e-5),
            (1e-3, 0.0, 1.0),
            (0.3, -0.4, 0.2),
            (2.0, 1.0, -1.0),
            (0.0, 0.0, 0.0),
            (0.0, 0.0, -1.0),
        ] {
            let x = f.at(a, b, c);
            let r = closest(std::slice::from_ref(&s), &x, &prm, &|_| true).unwrap();
            let truth = (a * a + b * b + c * c).sqrt() - 1.0;
            let truth = truth.abs();
            assert!(
                r.lower <= truth + 1e-12 && truth <= r.upper + 1e-12,
                "{r:?} {truth}"
            );
            // At the centre every point is closest: the budget ends the search (still sound).
            if c != 0.0 {
                assert!(r.upper - r.lower <= 1e-8, "{r:?}");
            }
        }
    }

    #[test]
    fn enclosure_holds_evaluation_and_derivatives() {
        let s = sphere(&frame(), 2.0).unwrap();
        for k in 0..50 {
            let (u, v) = (k as f64 / 49.0, (k * 13 % 50) as f64 / 49.0);
            let h = 1e-6;
            let enc = super::super::enclose::enclose_jet(
                &s,
                Interval::new(u - h, u + h).max_in(0.0, 1.0),
                Interval::new(v - h, v + h).max_in(0.0, 1.0),
            )
            .unwrap();
            let (p, su, sv) = super::super::refine::point_d1(&s, u, v);
            for c in 0..3 {
                assert!(enc.s[c].lo <= p[c] && p[c] <= enc.s[c].hi);
                let tol = 1e-9 * (1.0 + su[c].abs() + sv[c].abs());
                assert!(enc.su[c].lo - tol <= su[c] && su[c] <= enc.su[c].hi + tol);
                assert!(enc.sv[c].lo - tol <= sv[c] && sv[c] <= enc.sv[c].hi + tol);
            }
        }
    }

    trait Clip {
        fn max_in(self, a: f64, b: f64) -> Interval;
    }
    impl Clip for Interval {
        fn max_in(self, a: f64, b: f64) -> Interval {
            Interval::new(self.lo.max(a), self.hi.min(b))
        }
    }
}
