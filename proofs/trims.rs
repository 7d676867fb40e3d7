//! The face restriction of `ssi` (`ssi/trims.rs`): a parameter point is inside a trimmed
//! face when the even-odd rule over its loop polygons says so (`FaceRegion::inside`), decided
//! with exact orientation signs. Branches are clipped, and touch points and regions dropped,
//! on this decision.

use crate::common::{Q, Rng, cases, q};
use vericad::tessellate::domain::BoundaryPoint;
use vericad::tessellate::region::FaceRegion;

/// Whether `p` lies on the closed segment `ab`, exactly.
fn on_segment(p: &[f64; 2], a: &[f64; 2], b: &[f64; 2]) -> bool {
    let (px, py, ax, ay, bx, by) = (q(p[0]), q(p[1]), q(a[0]), q(a[1]), q(b[0]), q(b[1]));
    let cross = (&bx - &ax) * (&py - &ay) - (&by - &ay) * (&px - &ax);
    if cross != q(0.0) {
        return false;
    }
    let within = |x: &Q, u: &Q, v: &Q| (x >= u && x <= v) || (x >= v && x <= u);
    within(&px, &ax, &bx) && within(&py, &ay, &by)
}

/// The exact even-odd parity of `p` against `polys` (a ray towards +x, half-open in y);
/// `None` when `p` lies on a polygon's boundary (where either answer is the convention).
fn exact_parity(p: &[f64; 2], polys: &[Vec<[f64; 2]>]) -> Option<bool> {
    let mut odd = false;
    for poly in polys {
        for k in 0..poly.len() {
            let (a, b) = (&poly[k], &poly[(k + 1) % poly.len()]);
            if on_segment(p, a, b) {
                return None;
            }
            if (a[1] > p[1]) != (b[1] > p[1]) {
                let x = q(a[0]) + (q(p[1]) - q(a[1])) * (q(b[0]) - q(a[0])) / (q(b[1]) - q(a[1]));
                if x > q(p[0]) {
                    odd = !odd;
                }
            }
        }
    }
    Some(odd)
}

/// `FaceRegion::inside` equals the exact even-odd parity at every point off the boundary,
/// and says inside at every point on an edge that is not horizontal (the crossing test meets
/// it with a zero orientation).
pub fn prop_inside_is_exact(polys: &[Vec<[f64; 2]>], p: &[f64; 2]) {
    let bp: Vec<Vec<BoundaryPoint>> = polys
        .iter()
        .map(|l| l.iter().map(|uv| BoundaryPoint::straight(*uv, 0)).collect())
        .collect();
    let r = FaceRegion::new(0, &bp, [None, None], [-1e300, 1e300, -1e300, 1e300]);
    match exact_parity(p, polys) {
        Some(odd) => assert_eq!(r.inside(p), odd, "{p:?} in {polys:?}"),
        None => {
            let on_slanted = polys.iter().any(|poly| {
                (0..poly.len()).any(|k| {
                    let (a, b) = (&poly[k], &poly[(k + 1) % poly.len()]);
                    (a[1] > p[1]) != (b[1] > p[1]) && on_segment(p, a, b)
                })
            });
            if on_slanted {
                assert!(r.inside(p), "{p:?} on an edge of {polys:?}");
            }
        }
    }
}

fn coord(rng: &mut Rng, kind: u64) -> f64 {
    match kind {
        0 => rng.int(-4, 4) as f64,
        1 => rng.range(-1.0, 1.0),
        2 => rng.int(-4, 4) as f64 * 0.25 + rng.int(-1, 1) as f64 * 2f64.powi(-50),
        _ => rng.scaled(30),
    }
}

fn polygon(rng: &mut Rng, kind: u64) -> Vec<[f64; 2]> {
    let n = 3 + rng.below(6) as usize;
    (0..n)
        .map(|_| [coord(rng, kind), coord(rng, kind)])
        .collect()
}

/// Query points: random, at vertices, at exact and rounded points of edges, one ulp off
/// them, and at a vertex's height (the half-open rule's cases).
fn query(rng: &mut Rng, polys: &[Vec<[f64; 2]>], kind: u64) -> [f64; 2] {
    let poly = &polys[rng.below(polys.len() as u64) as usize];
    let k = rng.below(poly.len() as u64) as usize;
    let (a, b) = (poly[k], poly[(k + 1) % poly.len()]);
    match rng.below(6) {
        0 => a,
        1 => [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])],
        2 => {
            let t = rng.unit();
            [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])]
        }
        3 => [0.5 * (a[0] + b[0]), (0.5 * (a[1] + b[1])).next_up()],
        4 => [coord(rng, kind), a[1]],
        _ => [coord(rng, kind), coord(rng, kind)],
    }
}

#[test]
fn inside_is_the_exact_even_odd_rule() {
    let n = cases(10_000, 2_000_000);
    let mut rng = Rng::new(11);
    let (mut off, mut on) = (0usize, 0usize);
    for i in 0..n {
        let kind = (i % 4) as u64;
        let loops = 1 + rng.below(3) as usize;
        let polys: Vec<Vec<[f64; 2]>> = (0..loops).map(|_| polygon(&mut rng, kind)).collect();
        let p = query(&mut rng, &polys, kind);
        match exact_parity(&p, &polys) {
            Some(_) => off += 1,
            None => on += 1,
        }
        prop_inside_is_exact(&polys, &p);
    }
    // Both kinds of query occur often: the harness is not vacuous.
    assert!(
        off > n / 4 && on > n / 20,
        "{off} off, {on} on the boundary"
    );
}

/// Whether the closed segment `ab` meets the closed box `lo..hi`, exactly (Liang–Barsky in
/// rationals).
fn segment_meets_box_exact(a: &[f64; 2], b: &[f64; 2], lo: &[f64; 2], hi: &[f64; 2]) -> bool {
    let (mut t0, mut t1) = (q(0.0), q(1.0));
    for d in 0..2 {
        let delta = q(b[d]) - q(a[d]);
        for (p, r) in [
            (-delta.clone(), q(a[d]) - q(lo[d])),
            (delta, q(hi[d]) - q(a[d])),
        ] {
            if p == q(0.0) {
                if r < q(0.0) {
                    return false;
                }
            } else {
                let x = r / p.clone();
                if p < q(0.0) {
                    if x > t0 {
                        t0 = x;
                    }
                } else if x < t1 {
                    t1 = x;
                }
            }
        }
    }
    t0 <= t1
}

/// The box tests the coverage certificate decides trimmed pairs with, on the box as given
/// (taken as exact): `edges_meeting` returns every polygon edge that meets the box (exact
/// test), with shift 0; `box_outside` only when no edge meets the box and a point of it is
/// outside by the exact parity (so no point of it is in the face); `box_inside` only when
/// no edge meets it and a point of it is inside (so every point is).
pub fn prop_box_tests_are_conservative(polys: &[Vec<[f64; 2]>], b: &[f64; 4]) -> (bool, bool) {
    let bp: Vec<Vec<BoundaryPoint>> = polys
        .iter()
        .map(|l| l.iter().map(|uv| BoundaryPoint::straight(*uv, 0)).collect())
        .collect();
    let r = FaceRegion::new(0, &bp, [None, None], [-1e300, 1e300, -1e300, 1e300]);
    let (lo, hi) = ([b[0], b[2]], [b[1], b[3]]);
    let meeting: Vec<([f64; 2], [f64; 2])> = polys
        .iter()
        .flat_map(|poly| (0..poly.len()).map(move |k| (poly[k], poly[(k + 1) % poly.len()])))
        .filter(|(a, c)| segment_meets_box_exact(a, c, &lo, &hi))
        .collect();
    let got = r.edges_meeting(b, 0.0);
    for (a, c) in &meeting {
        assert!(
            got.iter()
                .any(|(x, y, s)| x == a && y == c && *s == [0.0, 0.0]),
            "edge {a:?} {c:?} meets {b:?} but is not returned"
        );
    }
    // A corner of the box, and its centre, by the exact parity.
    let probes = [
        [b[0], b[2]],
        [b[1], b[3]],
        [0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3])],
    ];
    let outside = r.box_outside(b, 0.0);
    let inside = r.box_inside(b);
    if outside || inside {
        assert!(meeting.is_empty(), "{b:?} decided but {meeting:?} meet it");
        for p in &probes {
            if let Some(odd) = exact_parity(p, polys) {
                assert_eq!(
                    odd, inside,
                    "{p:?} of {b:?}: outside {outside} inside {inside}"
                );
            }
        }
    }
    (outside, inside)
}

/// Boxes around edges and vertices (a few ulps wide up to wide), at large offsets (where an
/// ulp of a coordinate is far larger than a fraction of the box), against random polygons.
#[test]
fn box_tests_are_conservative() {
    let n = cases(10_000, 1_000_000);
    let mut rng = Rng::new(23);
    let (mut decided, mut undecided) = (0usize, 0usize);
    for i in 0..n {
        let kind = (i % 4) as u64;
        let offset = if i % 3 == 0 { 2f64.powi(30) } else { 0.0 };
        let loops = 1 + rng.below(3) as usize;
        let polys: Vec<Vec<[f64; 2]>> = (0..loops)
            .map(|_| {
                polygon(&mut rng, kind)
                    .into_iter()
                    .map(|p| [p[0] + offset, p[1] + offset])
                    .collect()
            })
            .collect();
        let c = query(&mut rng, &polys, kind);
        let w = match rng.below(4) {
            0 => 0.0,
            1 => 4.0 * f64::EPSILON * c[0].abs().max(c[1].abs()).max(1.0),
            2 => rng.range(0.0, 0.01),
            _ => rng.range(0.0, 2.0),
        };
        let (dx, dy) = (rng.range(-1.0, 1.0) * w, rng.range(-1.0, 1.0) * w);
        let b = [
            (c[0] + dx - w).min(c[0] + dx + w),
            (c[0] + dx - w).max(c[0] + dx + w),
            (c[1] + dy - w).min(c[1] + dy + w),
            (c[1] + dy - w).max(c[1] + dy + w),
        ];
        let (o, ins) = prop_box_tests_are_conservative(&polys, &b);
        if o || ins {
            decided += 1;
        } else {
            undecided += 1;
        }
    }
    // Both outcomes occur often: the harness is not vacuous.
    assert!(
        decided > n / 10 && undecided > n / 10,
        "{decided} decided, {undecided} not"
    );
}
