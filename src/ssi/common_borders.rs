//! Faces with a border in common: two surfaces whose border curves are one curve, piece by
//! piece, within a proven gap ([`crate::spline::border_match`]) — two solids of an assembly
//! meeting along a circle, neighbouring patches of a surface model, a floor and a wall.
//!
//! Along such a border the intersection lies on the border of both parameter domains, where
//! the triangulations meet edge to edge: what the mesh pipeline traced there was rows of
//! zero-length fragments and tangential points (abc-0000: 16 two-point branches, or nothing
//! at all for a border shared exactly). Here the border is reported as what it is:
//!
//! * **exact** (`gap` 0, the same curve on both surfaces, proven in rational arithmetic):
//!   every point of the border lies on both surfaces, so it is part of the intersection. Each
//!   listed point `x` has parameters on A's border, and `|x − S_A(u, v)|` is bounded rigorously
//!   ([`super::certify`]): that bound is its proven distance to the intersection curve
//!   (`curve_radius_max`), since `S_A(u, v)` is a common point of both faces.
//! * **within** `gap` (`0 < gap ≤ tol`): every point of A's border lies within `gap` of B's
//!   border (proven), but whether the surfaces meet there is not decided: the points are
//!   listed, not certified, and the run is not certified.
//!
//! The border's polyline (its points, chords split until their midpoints are measured within
//! `d / 8` of the curve, at most 12 times per chord and 20,000 points per border: past that
//! coarser) is part of the output the coverage certificate refers to
//! ([`super::coverage`]): a pair of pieces whose every common point lies within the match
//! distance `d` of it is decided *near the output*, as near a branch. Traced branch points and
//! touch points within `d` of a border polyline are moved into it (counted): they are that
//! border, found again by the meshes.

use super::certify::ExactSurface;
use super::coverage::near::Near;
use super::report::{EndKind, PairOut};
use super::trims::clip_mask_as;
use crate::geom::dist;
use crate::spline::NurbsSurface;
use crate::spline::border_match::BorderMatch;
use serde::Serialize;

/// Largest sine of the normals' angle at a point of a *tangent* border (measured).
const TANGENT_SIN: f64 = 1e-3;
/// Length of a tangent border not outside the faces, in match distances, past which its
/// coverage is out of reach ([`out_of_reach`]).
const TANGENT_SPAN: f64 = 1e5;
/// The coverage's box budget for a pair whose borders are out of reach.
pub const OUT_OF_REACH_BOXES: usize = 10_000;

/// Most points listed per border.
const MAX_POINTS: usize = 20_000;
/// Deepest chord split below the first eight per piece.
const MAX_DEPTH: u32 = 12;

/// A border two faces have in common (see the module comment).
#[derive(Clone, Debug, Serialize)]
pub struct CommonBorderOut {
    /// Which border of each face (`u_min`, `u_max`, `v_min`, `v_max`).
    pub border_a: &'static str,
    pub border_b: &'static str,
    /// B's border runs the other way.
    pub reversed: bool,
    /// Proven upper bound on the distance between the two borders at corresponding points.
    pub gap: f64,
    /// The borders are one curve (`gap` 0): every point of it lies on both surfaces.
    pub exact: bool,
    /// The polyline along A's border.
    pub points: Vec<[f64; 3]>,
    pub uv_a: Vec<[f64; 2]>,
    pub uv_b: Vec<[f64; 2]>,
    /// Largest proven distance of a point to each surface at its own parameters.
    pub dist_a_max: f64,
    pub dist_b_max: f64,
    /// Exact borders: the largest proven distance of a point to the intersection curve (the
    /// border point at its parameters on A, a common point of both faces). `None` for a border
    /// within a gap, or where a bound could not be proven.
    pub curve_radius_max: Option<f64>,
    /// Traced branch points and touch points within the match distance of the polyline,
    /// moved into it.
    pub branch_points_moved: usize,
    pub touch_points_moved: usize,
}

impl CommonBorderOut {
    /// Every point of the border is proven on the intersection curve.
    pub fn certified(&self) -> bool {
        self.exact && self.curve_radius_max.is_some()
    }
    /// The polyline's segments.
    pub fn segments(&self) -> impl Iterator<Item = ([f64; 3], [f64; 3])> + '_ {
        self.points.windows(2).map(|w| (w[0], w[1]))
    }
    /// The part made of the points with `keep` set, as borders of their own (runs of one
    /// point dropped).
    pub fn split(&self, keep: &[bool]) -> Vec<CommonBorderOut> {
        let mut runs: Vec<Vec<usize>> = vec![Vec::new()];
        for (i, k) in keep.iter().enumerate().take(self.points.len()) {
            match (k, runs.last_mut()) {
                (true, Some(r)) => r.push(i),
                (false, Some(r)) if !r.is_empty() => runs.push(Vec::new()),
                _ => {}
            }
        }
        runs.into_iter()
            .filter(|r| r.len() >= 2)
            .map(|r| CommonBorderOut {
                points: r.iter().map(|&i| self.points[i]).collect(),
                uv_a: r.iter().map(|&i| self.uv_a[i]).collect(),
                uv_b: r.iter().map(|&i| self.uv_b[i]).collect(),
                ..self.clone()
            })
            .collect()
    }
}

/// The polyline of border match `m`: per piece of A's border eight chords, each split until
/// its midpoint lies within `d / 8` of the curve's point there (measured), and the points'
/// proven distances.
pub fn sample(
    m: &BorderMatch,
    (sa, sb): (&NurbsSurface<f64, 3>, &NurbsSurface<f64, 3>),
    (ea, eb): (&ExactSurface, &ExactSurface),
    d: f64,
) -> CommonBorderOut {
    let (da, db) = (sa.hom.domain(), sb.hom.domain());
    let at = |t: f64| {
        let ua = m.a.at(t, da);
        (sa.eval(&ua[0], &ua[1]), t)
    };
    let mut ts: Vec<f64> = Vec::new();
    for p in &m.pieces {
        let (t0, t1) = (p[0], p[1]);
        for k in 0..8 {
            let (a, b) = (
                t0 + (t1 - t0) * k as f64 / 8.0,
                t0 + (t1 - t0) * (k + 1) as f64 / 8.0,
            );
            split(&at, (at(a), at(b)), d / 8.0, 0, &mut ts);
        }
    }
    if let Some(p) = m.pieces.last() {
        ts.push(p[1]);
    }
    if ts.len() > MAX_POINTS {
        let step = ts.len().div_ceil(MAX_POINTS);
        let last = ts[ts.len() - 1];
        ts = ts.into_iter().step_by(step).collect();
        ts.push(last);
    }
    let mut out = CommonBorderOut {
        border_a: m.a.label(),
        border_b: m.b.label(),
        reversed: m.reversed,
        gap: m.gap,
        exact: m.exact,
        points: Vec::with_capacity(ts.len()),
        uv_a: Vec::with_capacity(ts.len()),
        uv_b: Vec::with_capacity(ts.len()),
        dist_a_max: 0.0,
        dist_b_max: 0.0,
        curve_radius_max: None,
        branch_points_moved: 0,
        touch_points_moved: 0,
    };
    let mut proven = true;
    for t in ts {
        let ua = m.a.at(t, da);
        let ub = m.b.at(m.map(t), db);
        let x = sa.eval(&ua[0], &ua[1]);
        let (ba, bb) = (ea.distance_bound(&x, &ua), eb.distance_bound(&x, &ub));
        proven &= ba.is_some();
        out.dist_a_max = out.dist_a_max.max(ba.unwrap_or(f64::INFINITY));
        out.dist_b_max = out.dist_b_max.max(bb.unwrap_or(f64::INFINITY));
        out.points.push(x);
        out.uv_a.push(ua);
        out.uv_b.push(ub);
    }
    if m.exact && proven {
        out.curve_radius_max = Some(out.dist_a_max);
    }
    out
}

/// Whether deciding the coverage along the pair's borders is out of reach, so that its box
/// budget is better cut to [`OUT_OF_REACH_BOXES`]: along a border where the faces are tangent
/// (normals' sine at most 1e-3 at one of its points, measured) no pair of pieces next to it
/// has separated normal cones, and pieces are decided only once within `d` of the border —
/// bands of pieces shrinking towards it, about `L / d` of them for a length `L`. Out of reach
/// when such a border runs more than `1e5 d` where the faces are not ruled out (`outside`, the
/// coverage's own test, on each chord's parameter boxes). A budget only: whatever the answer,
/// the coverage decides each pair by its theorem or lists it.
pub fn out_of_reach(
    borders: &[CommonBorderOut],
    (sa, sb): (&NurbsSurface<f64, 3>, &NurbsSurface<f64, 3>),
    outside: Option<&super::coverage::OutsideFaces>,
    d: f64,
) -> bool {
    let tangent = |c: &CommonBorderOut| {
        (0..c.points.len()).step_by(16).any(|i| {
            super::overlap::sine_and_gap(sa, sb, &c.uv_a[i], &c.uv_b[i])
                .is_some_and(|(sin, _)| sin <= TANGENT_SIN)
        })
    };
    let span = |c: &CommonBorderOut| -> f64 {
        (1..c.points.len())
            .filter(|&i| {
                let bx = |p: &[f64; 2], q: &[f64; 2]| {
                    [
                        p[0].min(q[0]),
                        p[0].max(q[0]),
                        p[1].min(q[1]),
                        p[1].max(q[1]),
                    ]
                };
                let (ba, bb) = (
                    bx(&c.uv_a[i - 1], &c.uv_a[i]),
                    bx(&c.uv_b[i - 1], &c.uv_b[i]),
                );
                !outside.is_some_and(|o| (o.0)(&ba, &bb))
            })
            .map(|i| dist(&c.points[i - 1], &c.points[i]))
            .sum()
    };
    borders
        .iter()
        .any(|c| tangent(c) && span(c) > TANGENT_SPAN * d)
}

/// Deepest bisection of a chord by [`clip_to_faces`].
const CLIP_DEPTH: u32 = 24;

/// A point of a border: model point, parameters on A and on B.
type At = ([f64; 3], [f64; 2], [f64; 2]);

/// The parts of border `c` on both faces, with the number of points removed. `meets`: whether
/// parameter boxes on A and on B meet both faces (the faces' test, with its margin);
/// `shared`: whether a point lies on an edge or vertex the faces share (those points are that
/// edge). A point is kept when it is on both faces and not shared, and so are both ends of a
/// chord that *matters*: its parameter segments meet both faces, and, bisected (the midpoint on
/// A's border: the border is a parameter line of A and affine on each piece of B's, so the
/// midpoints of the parameter segments are the border's points), some part of it at depth
/// 24 still meets both faces without both its ends shared. So a stretch of the
/// border on both faces shorter than a chord — a face trimmed to a thin strip across it — is
/// kept, and one that reaches the faces only inside a shared vertex's tube (two faces of a
/// solid meeting at a corner) is not.
pub fn clip_to_faces(
    c: &CommonBorderOut,
    (sa, _sb): (&NurbsSurface<f64, 3>, &NurbsSurface<f64, 3>),
    meets: &dyn Fn(&[f64; 4], &[f64; 4]) -> bool,
    shared: &dyn Fn(&[f64; 3]) -> bool,
) -> (Vec<CommonBorderOut>, usize) {
    let n = c.points.len();
    let at = |i: usize| -> At { (c.points[i], c.uv_a[i], c.uv_b[i]) };
    let point_box = |p: &[f64; 2]| [p[0], p[0], p[1], p[1]];
    let sh: Vec<bool> = c.points.iter().map(shared).collect();
    let mut keep: Vec<bool> = (0..n)
        .map(|i| !sh[i] && meets(&point_box(&c.uv_a[i]), &point_box(&c.uv_b[i])))
        .collect();
    for i in 0..n.saturating_sub(1) {
        if !(keep[i] && keep[i + 1]) && matters(sa, at(i), at(i + 1), meets, shared, CLIP_DEPTH) {
            keep[i] = true;
            keep[i + 1] = true;
        }
    }
    let removed = keep.iter().filter(|k| !**k).count();
    (c.split(&keep), removed)
}

/// Whether some part of the chord `p q` meets both faces (see [`clip_to_faces`]).
fn matters(
    sa: &NurbsSurface<f64, 3>,
    p: At,
    q: At,
    meets: &dyn Fn(&[f64; 4], &[f64; 4]) -> bool,
    shared: &dyn Fn(&[f64; 3]) -> bool,
    depth: u32,
) -> bool {
    let span = |a: &[f64; 2], b: &[f64; 2]| {
        [
            a[0].min(b[0]),
            a[0].max(b[0]),
            a[1].min(b[1]),
            a[1].max(b[1]),
        ]
    };
    if !meets(&span(&p.1, &q.1), &span(&p.2, &q.2)) || (shared(&p.0) && shared(&q.0)) {
        return false;
    }
    if depth == 0 {
        return true;
    }
    let mid = |a: &[f64; 2], b: &[f64; 2]| [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])];
    let (ua, ub) = (mid(&p.1, &q.1), mid(&p.2, &q.2));
    let m: At = (sa.eval(&ua[0], &ua[1]), ua, ub);
    matters(sa, p, m, meets, shared, depth - 1) || matters(sa, m, q, meets, shared, depth - 1)
}

/// Push the parameters of the chord `(a, b)` split until its midpoint is within `e` of the
/// curve's point at the middle parameter (all but `b`'s).
fn split(
    at: &impl Fn(f64) -> ([f64; 3], f64),
    (a, b): (([f64; 3], f64), ([f64; 3], f64)),
    e: f64,
    depth: u32,
    ts: &mut Vec<f64>,
) {
    let mid = at(0.5 * (a.1 + b.1));
    let chord_mid: [f64; 3] = std::array::from_fn(|k| 0.5 * (a.0[k] + b.0[k]));
    if depth < MAX_DEPTH && dist(&mid.0, &chord_mid) > e {
        split(at, (a, mid), e, depth + 1, ts);
        split(at, (mid, b), e, depth + 1, ts);
    } else {
        ts.push(a.1);
    }
}

/// Move the traced branch points and touch points of `out` lying within `reach` of one of
/// its common borders' polylines into that border (branches cut there get
/// [`EndKind::CommonBorder`] ends).
pub fn absorb(out: &mut PairOut, reach: f64) {
    if out.common_borders.is_empty() {
        return;
    }
    let near: Vec<Near> = out
        .common_borders
        .iter()
        .map(|c| Near::new(c.segments().collect()))
        .collect();
    let owner = |x: &[f64; 3]| near.iter().position(|n| n.box_within(&(*x, *x), reach));
    let mut moved_b = vec![0usize; near.len()];
    let mut moved_t = vec![0usize; near.len()];
    let mut branches = Vec::with_capacity(out.branches.len());
    for b in &out.branches {
        let owners: Vec<Option<usize>> = b.points.iter().map(owner).collect();
        // A cut run keeps the first point within reach on each side, so that the branch
        // reaches the border's reach (and a lone point between two cuts is not dropped).
        let n = owners.len();
        let free = |i: usize| owners.get(i).is_some_and(|o| o.is_none());
        let keep: Vec<bool> = (0..n)
            .map(|i| {
                let (prev, next) = if b.closed {
                    ((i + n - 1) % n, (i + 1) % n)
                } else {
                    (i.wrapping_sub(1), i + 1)
                };
                free(i) || free(prev) || free(next)
            })
            .collect();
        for (o, k) in owners.iter().zip(&keep) {
            if let (Some(o), false) = (o, k) {
                moved_b[*o] += 1;
            }
        }
        branches.extend(clip_mask_as(b, &keep, EndKind::CommonBorder));
    }
    out.branches = branches;
    out.touch_points.retain(|t| match owner(&t.point) {
        Some(k) => {
            moved_t[k] += 1;
            false
        }
        None => true,
    });
    for (k, c) in out.common_borders.iter_mut().enumerate() {
        c.branch_points_moved += moved_b[k];
        c.touch_points_moved += moved_t[k];
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spline::border_match::common_borders;
    use crate::spline::construct::bilinear;

    /// The floor and wall of an L share their edge exactly: the polyline runs along the line
    /// x = z = 0 from y = 0 to 1 with every point's curve radius proven tiny, and its
    /// parameters on the wall land on the wall's border.
    #[test]
    fn l_shape_border_is_sampled_and_certified() {
        let floor = bilinear(
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [1.0, 1.0, 0.0],
        )
        .unwrap();
        let wall = bilinear(
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 0.0],
            [0.0, 1.0, 1.0],
            [0.0, 0.0, 1.0],
        )
        .unwrap();
        let m = common_borders(&floor, &wall, 1e-6);
        let (ea, eb) = (ExactSurface::new(&floor), ExactSurface::new(&wall));
        let c = sample(&m[0], (&floor, &wall), (&ea, &eb), 1e-5);
        assert!(c.certified());
        assert!(c.curve_radius_max.is_some_and(|r| r <= 1e-13));
        assert_eq!(c.points.first(), Some(&[0.0, 0.0, 0.0]));
        assert_eq!(c.points.last(), Some(&[0.0, 1.0, 0.0]));
        for (x, ub) in c.points.iter().zip(&c.uv_b) {
            assert!(x[0] == 0.0 && x[2] == 0.0);
            assert_eq!(ub[1], 0.0);
            assert!((ub[0] - (1.0 - x[1])).abs() <= 1e-15);
        }
        let keep: Vec<bool> = (0..c.points.len()).map(|i| i % 5 != 2).collect();
        let parts = c.split(&keep);
        assert!(parts.iter().all(|p| p.points.len() >= 2));
    }
}
