//! The coverage certificate on trimmed faces, against constructions whose faces' intersection
//! is known: a dome meeting a plane in a circle of radius 0.2, the plane trimmed to a small
//! island the circle runs through (or misses); a floor trimmed to an island under a vertical
//! wall. The faces are given to the certificate by this file's own tests on an axis-aligned
//! rectangle (not the library's polygon code). With the faces' part of the curve absent from
//! the output the run must never be certified; with it present, or with nothing in the faces,
//! it is certified (the trim-loop crossings decide the pairs the island's edges run through).

mod common;
use common::shapes::dome;
use std::sync::Arc;
use vericad::spline::NurbsSurface;
use vericad::spline::construct::bilinear;
use vericad::ssi::coverage::{CoverageOut, FaceRestriction, OutsideFaces, coverage};
use vericad::ssi::report::BranchOut;

/// An axis-aligned rectangle `[u0, u1] × [v0, v1]` in a parameter plane.
#[derive(Clone, Copy, Debug)]
struct Rect([f64; 4]);

/// Widening of boxes in the tests below (the library's faces use 1e-9 of the domain).
const W: f64 = 1e-9;

impl Rect {
    fn holds(&self, p: &[f64; 2]) -> bool {
        let r = self.0;
        r[0] <= p[0] && p[0] <= r[1] && r[2] <= p[1] && p[1] <= r[3]
    }
    fn box_outside(&self, b: &[f64; 4]) -> bool {
        let r = self.0;
        b[1] + W < r[0] || r[1] < b[0] - W || b[3] + W < r[2] || r[3] < b[2] - W
    }
    fn box_inside(&self, b: &[f64; 4]) -> bool {
        let r = self.0;
        r[0] < b[0] - W && b[1] + W < r[1] && r[2] < b[2] - W && b[3] + W < r[3]
    }
    /// The rectangle's sides meeting the box widened by `W` (each side is its own bounding
    /// box, so the overlap test is exact).
    fn sides_meeting(&self, b: &[f64; 4]) -> Vec<([f64; 2], [f64; 2], [f64; 2])> {
        let [u0, u1, v0, v1] = self.0;
        [
            ([u0, v0], [u1, v0]),
            ([u1, v0], [u1, v1]),
            ([u1, v1], [u0, v1]),
            ([u0, v1], [u0, v0]),
        ]
        .into_iter()
        .filter(|(p, q)| {
            let sb = [
                p[0].min(q[0]),
                p[0].max(q[0]),
                p[1].min(q[1]),
                p[1].max(q[1]),
            ];
            !(sb[1] < b[0] - W || b[1] + W < sb[0] || sb[3] < b[2] - W || b[3] + W < sb[2])
        })
        .map(|(p, q)| (p, q, [0.0; 2]))
        .collect()
    }
}

/// The faces: surface A trimmed to `ra` (or whole), B to `rb`.
fn faces(ra: Option<Rect>, rb: Option<Rect>) -> (FaceRestriction, OutsideFaces) {
    let out_a = move |b: &[f64; 4]| ra.is_some_and(|r| r.box_outside(b));
    let out_b = move |b: &[f64; 4]| rb.is_some_and(|r| r.box_outside(b));
    let restrict = FaceRestriction {
        inside: Arc::new(move |a, b| {
            ra.is_none_or(|r| r.holds(a)) && rb.is_none_or(|r| r.holds(b))
        }),
        meets: Arc::new(move |a, b| !out_a(a) && !out_b(b)),
        shared: Arc::new(|_| false),
        pair_inside: Arc::new(move |a, b| {
            ra.is_none_or(|r| r.box_inside(a)) && rb.is_none_or(|r| r.box_inside(b))
        }),
        outside_a: Arc::new(out_a),
        outside_b: Arc::new(out_b),
        inside_a: Arc::new(move |b| ra.is_none_or(|r| r.box_inside(b))),
        inside_b: Arc::new(move |b| rb.is_none_or(|r| r.box_inside(b))),
        edges_a: Arc::new(move |b| ra.map_or_else(Vec::new, |r| r.sides_meeting(b))),
        edges_b: Arc::new(move |b| rb.map_or_else(Vec::new, |r| r.sides_meeting(b))),
    };
    let outside = OutsideFaces(Arc::new(move |a, b| out_a(a) || out_b(b)));
    (restrict, outside)
}

fn run(
    a: &NurbsSurface<f64, 3>,
    b: &NurbsSurface<f64, 3>,
    branches: &[BranchOut],
    (ra, rb): (Option<Rect>, Option<Rect>),
) -> CoverageOut {
    let (restrict, outside) = faces(ra, rb);
    let mut prm = common::coverage_params(1e-6);
    prm.restrict = Some(restrict);
    prm.outside = Some(outside);
    coverage(a, b, branches, &[], &prm)
}

/// The dome `z = c − k((x − ½)² + (y − ½)²)` over the unit square (its parameters are x, y)
/// against the plane `z = 0` over `[−1, 1]²` (parameters `s = (x + 1)/2`, `t = (y + 1)/2`):
/// they meet in the circle of radius 0.2 about `(½, ½, 0)`.
fn dome_and_floor() -> (NurbsSurface<f64, 3>, NurbsSurface<f64, 3>) {
    let floor = bilinear(
        [-1.0, -1.0, 0.0],
        [1.0, -1.0, 0.0],
        [-1.0, 1.0, 0.0],
        [1.0, 1.0, 0.0],
    )
    .unwrap();
    (dome(0.04, 1.0), floor)
}

/// The circle's arc from angle `f` to `g`, `n` chords, with both surfaces' parameters.
fn arc(f: f64, g: f64, n: usize) -> BranchOut {
    let mut b = BranchOut::default();
    for k in 0..=n {
        let a = f + (g - f) * k as f64 / n as f64;
        let (x, y) = (0.5 + 0.2 * a.cos(), 0.5 + 0.2 * a.sin());
        b.points.push([x, y, 0.0]);
        b.uv_a.push([x, y]);
        b.uv_b.push([(x + 1.0) / 2.0, (y + 1.0) / 2.0]);
    }
    b.closed = (g - f - std::f64::consts::TAU).abs() < 1e-15;
    if b.closed {
        b.points.pop();
        b.uv_a.pop();
        b.uv_b.pop();
    }
    b
}

/// The island on the floor in its own parameters, from a box in x, y.
fn island(x0: f64, x1: f64, y0: f64, y1: f64) -> Rect {
    Rect([
        (x0 + 1.0) / 2.0,
        (x1 + 1.0) / 2.0,
        (y0 + 1.0) / 2.0,
        (y1 + 1.0) / 2.0,
    ])
}

#[test]
fn an_island_the_loop_runs_through_is_certified_only_with_its_arc() {
    let (a, b) = dome_and_floor();
    let tau = std::f64::consts::TAU;
    // The circle crosses x ∈ [0.65, 0.75], y ∈ [0.45, 0.55] near (0.7, 0.5).
    let isl = Some(island(0.65, 0.75, 0.45, 0.55));
    let whole = arc(0.0, tau, 4096);

    let none = run(&a, &b, &[], (None, isl));
    assert!(!none.no_missed_branches, "nothing reported: {none:?}");
    assert!(none.uncertified > 0);

    // The circle without the part near angle 0 (the island's): not certified.
    let gap = arc(0.6, tau - 0.6, 4096);
    let part = run(&a, &b, &[gap], (None, isl));
    assert!(!part.no_missed_branches, "island's arc absent: {part:?}");

    // The whole circle: the faces keep its part in the island (and the chords leaving it).
    let all = run(&a, &b, std::slice::from_ref(&whole), (None, isl));
    assert!(all.no_missed_branches, "{all:?}");
    assert!(all.transversal_with_trim_loops > 0, "{all:?}");
    assert!(all.trim_edge_searches > 0);
}

#[test]
fn an_island_the_loop_misses_is_certified_with_nothing_reported() {
    let (a, b) = dome_and_floor();
    // Inside the circle (x, y within 0.1 of the centre: 0.14 < 0.2) and outside it.
    for isl in [island(0.45, 0.55, 0.45, 0.55), island(0.05, 0.15, 0.8, 0.9)] {
        let c = run(&a, &b, &[], (None, Some(isl)));
        assert!(c.no_missed_branches, "{isl:?}: {c:?}");
    }
}

#[test]
fn a_tiny_island_on_the_loop_is_never_certified_empty() {
    let (a, b) = dome_and_floor();
    for w in [1e-2, 1e-3, 1e-4] {
        // A square of side w about the circle's point at angle 0.3.
        let (x, y) = (0.5 + 0.2 * 0.3f64.cos(), 0.5 + 0.2 * 0.3f64.sin());
        let isl = island(x - w / 2.0, x + w / 2.0, y - w / 2.0, y + w / 2.0);
        let c = run(&a, &b, &[], (None, Some(isl)));
        assert!(!c.no_missed_branches, "side {w}: {c:?}");
    }
}

/// A floor `z = 0` over `[−1, 1]²` trimmed to an island, under the wall `x = x0`; the faces
/// meet in the island's part of the line `x = x0, z = 0`.
#[test]
fn a_wall_over_a_trimmed_floor() {
    let floor = bilinear(
        [-1.0, -1.0, 0.0],
        [1.0, -1.0, 0.0],
        [-1.0, 1.0, 0.0],
        [1.0, 1.0, 0.0],
    )
    .unwrap();
    let isl = Some(island(-0.2, 0.2, -0.2, 0.2));
    let line = |x0: f64, y0: f64, y1: f64| -> BranchOut {
        let mut b = BranchOut::default();
        for k in 0..=400 {
            let y = y0 + (y1 - y0) * k as f64 / 400.0;
            b.points.push([x0, y, 0.0]);
            b.uv_a.push([(x0 + 1.0) / 2.0, (y + 1.0) / 2.0]);
            b.uv_b.push([(y + 1.0) / 2.0, 0.5]);
        }
        b
    };
    for (x0, crosses) in [(0.1, true), (0.5, false), (-0.19, true)] {
        let wall = bilinear(
            [x0, -1.0, -1.0],
            [x0, 1.0, -1.0],
            [x0, -1.0, 1.0],
            [x0, 1.0, 1.0],
        )
        .unwrap();
        let empty = run(&floor, &wall, &[], (isl, None));
        assert_eq!(empty.no_missed_branches, !crosses, "x0 = {x0}: {empty:?}");
        let full = run(&floor, &wall, &[line(x0, -1.0, 1.0)], (isl, None));
        assert!(full.no_missed_branches, "x0 = {x0}: {full:?}");
        if crosses {
            // Only the part beyond the island reported.
            let beyond = run(&floor, &wall, &[line(x0, 0.3, 1.0)], (isl, None));
            assert!(!beyond.no_missed_branches, "x0 = {x0}: {beyond:?}");
        }
    }
}
