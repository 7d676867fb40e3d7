//! The coverage certificate against constructions whose true intersection is known: a dome
//! over a plane (one loop of known radius, from 0.2 down to 1e-4), spheres in rotated frames
//! cut by planes at heights sweeping through the poles, tangent contact. The certificate may
//! refuse (uncertified), but it must never claim that no branch is missing while a branch is
//! absent from the output.

mod common;
use common::shapes::{dome, frame_of, rotated, square};
use vericad::spline::NurbsSurface;
use vericad::spline::construct::{bilinear, sphere};
use vericad::ssi::coverage::{CoverageParams, coverage};
use vericad::ssi::report::SingularKind::TouchingPoint;
use vericad::ssi::{PairOut, SsiParams, intersect_pair_canonical};

/// Biquadratic dome `z = c − k((x−½)² + (y−½)²)` over the unit square: it meets `z = 0` in
/// the circle of radius `√(c/k)` about `(½, ½, 0)`.
fn big_plane() -> NurbsSurface<f64, 3> {
    square(50.0)
}

fn cparams(d: f64) -> CoverageParams {
    common::coverage_params(d)
}

/// With nothing reported, a loop of any radius must leave the certificate refused, with an
/// uncertified region at the loop.
#[test]
fn a_loop_missing_from_the_output_is_never_certified() {
    for radius in [0.2, 1e-2, 1e-3, 1e-4] {
        let k = 1.0;
        let c = radius * radius * k;
        let (a, b) = (dome(c, k), big_plane());
        let cov = coverage(&a, &b, &[], &[], &cparams(1e-6));
        assert!(!cov.no_missed_branches, "radius {radius}: {cov:?}");
        assert!(cov.uncertified > 0);
        // Some listed region is at the loop: its point within a few radii of the circle's
        // centre, or its parameter box on the dome holding the circle's centre.
        let at_loop = cov.uncertified_regions.iter().any(|r| {
            let near_point = r.point.is_some_and(|p| {
                ((p[0] - 0.5).powi(2) + (p[1] - 0.5).powi(2)).sqrt() <= radius + 1e-3
                    && p[2].abs() <= 1e-3
            });
            let box_holds =
                r.uv_a[0] <= 0.5 && 0.5 <= r.uv_a[1] && r.uv_a[2] <= 0.5 && 0.5 <= r.uv_a[3];
            near_point || box_holds
        });
        assert!(at_loop, "radius {radius}: {:?}", cov.uncertified_regions);
    }
}

/// Tubes (one-file B-rep runs: the edges faces share) excuse what lies in them and nothing
/// else: a loop missing from the output is accounted for by a tube around its own circle, and
/// refused when the tube is shifted off it or is too thin to hold it.
#[test]
fn a_tube_excuses_only_the_loop_inside_it() {
    let radius = 0.2;
    let (a, b) = (dome(radius * radius, 1.0), big_plane());
    let circle = |dx: f64| -> Vec<([f64; 3], [f64; 3])> {
        let p = |k: usize| {
            let t = std::f64::consts::TAU * k as f64 / 512.0;
            [0.5 + dx + radius * t.cos(), 0.5 + radius * t.sin(), 0.0]
        };
        (0..512).map(|k| (p(k), p(k + 1))).collect()
    };
    let with_tubes = |tubes: Vec<vericad::ssi::coverage::TubeLine>| {
        let mut prm = cparams(1e-6);
        prm.tubes = std::sync::Arc::new(tubes);
        coverage(&a, &b, &[], &[], &prm)
    };
    let on_loop = with_tubes(vec![(circle(0.0), 1e-3)]);
    assert!(on_loop.no_missed_branches, "{on_loop:?}");
    assert!(on_loop.near_shared_edges + on_loop.crossing_boxes_near_shared_edges > 0);
    assert_eq!(
        on_loop.free
            + on_loop.near_output
            + on_loop.near_shared_edges
            + on_loop.transversal
            + on_loop.uncertified,
        on_loop.pairs
    );
    for (what, tubes) in [
        ("shifted by 0.05", vec![(circle(0.05), 1e-3)]),
        (
            "a vertex at the centre, reach 0.1",
            vec![(vec![([0.5, 0.5, 0.0], [0.5, 0.5, 0.0])], 0.1)],
        ),
    ] {
        let cov = with_tubes(tubes);
        assert!(!cov.no_missed_branches, "{what}: {cov:?}");
        assert!(cov.uncertified > 0, "{what}");
    }
}

/// The dome entirely above the plane: nothing to find, and the certificate proves it.
#[test]
fn nothing_to_find_is_certified() {
    let cov = coverage(&dome(-0.01, 1.0), &big_plane(), &[], &[], &cparams(1e-6));
    // c < 0: the dome's top is below the plane... so it is wholly below: no intersection.
    assert!(cov.no_missed_branches, "{cov:?}");
    assert_eq!(cov.uncertified, 0);
}

fn run(a: &NurbsSurface<f64, 3>, b: &NurbsSurface<f64, 3>, tol: f64) -> PairOut {
    let prm = SsiParams {
        tol,
        ..Default::default()
    };
    intersect_pair_canonical(a, b, (0, 1), &prm, None).expect("runs")
}

/// The whole pipeline on the dome: whenever it claims completeness, a branch lies on the
/// true circle (checked against the construction).
#[test]
fn dome_loops_found_or_refused() {
    for radius in [0.2, 1e-1, 1e-2, 1e-3, 1e-4] {
        let tol = 1e-7;
        let r = run(&dome(radius * radius, 1.0), &big_plane(), tol);
        let cov = r.coverage.as_ref().unwrap();
        let on_circle = r.branches.iter().any(|b| {
            b.points.iter().all(|p| {
                let rho = ((p[0] - 0.5).powi(2) + (p[1] - 0.5).powi(2)).sqrt();
                (rho - radius).abs() <= 1e-6 && p[2].abs() <= 1e-6
            })
        }) || r.touch_points.iter().any(|t| {
            let rho = ((t.point[0] - 0.5).powi(2) + (t.point[1] - 0.5).powi(2)).sqrt();
            rho <= radius + 1e-5
        });
        eprintln!(
            "radius {radius}: {} branches, {} touch, certified {}, {} uncertified, pairs {}, {:.3} s",
            r.branches.len(),
            r.touch_points.len(),
            cov.no_missed_branches,
            cov.uncertified,
            cov.pairs,
            cov.seconds
        );
        for g in cov.uncertified_regions.iter().take(4) {
            eprintln!("   {g:?} out-dist {:?}", g.point.map(|p| out_dist(&r, &p)));
        }
        for b in &r.branches {
            eprintln!(
                "   branch closed {} n {} chord {:e} refused {} dist {:e}",
                b.closed,
                b.points.len(),
                b.max_chord_deviation,
                b.refused_insertions,
                b.dist_a_max.max(b.dist_b_max)
            );
        }
        assert!(
            !cov.no_missed_branches || on_circle,
            "radius {radius}: certified complete without the loop: {:?}",
            r.branches
                .iter()
                .map(|b| b.points.len())
                .collect::<Vec<_>>()
        );
    }
}

fn out_dist(r: &PairOut, p: &[f64; 3]) -> f64 {
    let mut best = f64::INFINITY;
    for b in &r.branches {
        let n = b.points.len();
        for k in 0..n {
            let (a, c) = (b.points[k], b.points[(k + 1) % n]);
            let d: [f64; 3] = std::array::from_fn(|i| c[i] - a[i]);
            let e: [f64; 3] = std::array::from_fn(|i| p[i] - a[i]);
            let dd = d.iter().map(|x| x * x).sum::<f64>();
            let t = if dd > 0.0 {
                ((0..3).map(|i| e[i] * d[i]).sum::<f64>() / dd).clamp(0.0, 1.0)
            } else {
                0.0
            };
            best = best.min(
                (0..3)
                    .map(|i| (e[i] - t * d[i]).powi(2))
                    .sum::<f64>()
                    .sqrt(),
            );
        }
    }
    best
}

/// Spheres in rotated frames cut by the plane through `o + h·z` normal to the frame's z:
/// heights sweep through the poles. Certified complete ⇒ a branch on the true circle.
#[test]
fn rotated_spheres_cut_near_the_poles() {
    let r0 = 2.0;
    for (seed, h) in [
        (1u64, 1.999),
        (2, -1.99),
        (3, 1.9),
        (4, 0.0),
        (5, 1.9999),
        (6, -1.5),
    ] {
        let f = rotated(seed);
        let s = sphere(&f, r0).unwrap();
        let e = 3.0;
        let at = |a: f64, b: f64| f.at(a, b, h);
        let p = bilinear(at(-e, -e), at(e, -e), at(-e, e), at(e, e)).unwrap();
        let tol = 1e-7;
        let r = run(&s, &p, tol);
        let cov = r.coverage.as_ref().unwrap();
        let rho = (r0 * r0 - h * h).sqrt();
        // Distance of a point to the true circle, in the frame's coordinates.
        let circle_dist = |q: &[f64; 3]| {
            let d: [f64; 3] = std::array::from_fn(|k| q[k] - f.o[k]);
            let dot = |u: &[f64; 3]| d[0] * u[0] + d[1] * u[1] + d[2] * u[2];
            let (a, b, c) = (dot(&f.x), dot(&f.y), dot(&f.z));
            (((a * a + b * b).sqrt() - rho).powi(2) + (c - h).powi(2)).sqrt()
        };
        let found = r
            .branches
            .iter()
            .any(|b| b.points.iter().all(|q| circle_dist(q) <= 1e-6));
        eprintln!(
            "seed {seed} h {h}: {} branches ({} closed), certified {}, uncertified {}, pairs {}, {:.3} s, crossing boxes {} near {} examined {} transversal {} near {}",
            r.branches.len(),
            r.branches.iter().filter(|b| b.closed).count(),
            cov.no_missed_branches,
            cov.uncertified,
            cov.pairs,
            cov.seconds,
            cov.crossing_boxes,
            cov.crossing_boxes_near_output,
            cov.pairs_examined,
            cov.transversal,
            cov.near_output
        );
        for g in cov.uncertified_regions.iter().take(4) {
            eprintln!(
                "   {g:?} {:?} out {:?}",
                g.point.map(|p| circle_dist(&p)),
                g.point.map(|p| out_dist(&r, &p))
            );
        }
        assert!(!cov.no_missed_branches || found, "seed {seed} h {h}");
        // One closed loop in every placement (poles and seams welded).
        assert_eq!(r.branches.len(), 1, "seed {seed} h {h}");
        assert!(r.branches[0].closed && found, "seed {seed} h {h}");
        // Certified complete away from the extreme cases (the equator lies on a knot line
        // of the sphere; h = 1.9999 is 1e-4 from the pole).
        if ![0.0, 1.9999].contains(&h) {
            assert!(cov.no_missed_branches, "seed {seed} h {h}");
        }
    }
}

/// A sphere against itself and two overlapping coplanar squares: reported as coincident
/// (proven exactly), with no curves, and the run not certified as curves.
#[test]
fn coincident_faces_are_reported_not_traced() {
    use vericad::model::{Model, Surface};
    use vericad::ssi::coincide::CoincidenceKind;
    let f = rotated(7);
    let s = sphere(&f, 1.5).unwrap();
    let r = run(&s, &s, 1e-6);
    assert_eq!(
        r.coincident.as_ref().unwrap().kind,
        CoincidenceKind::Identical
    );
    assert!(r.branches.is_empty() && r.touch_points.is_empty());
    let z = |x: f64, y: f64| [x, y, 0.5 * x - 0.25 * y];
    let a = bilinear(z(0.0, 0.0), z(1.0, 0.0), z(0.0, 1.0), z(1.0, 1.0)).unwrap();
    let b = bilinear(z(0.5, 0.5), z(1.5, 0.5), z(0.5, 1.5), z(1.5, 1.5)).unwrap();
    let r = run(&a, &b, 1e-6);
    assert_eq!(
        r.coincident.as_ref().unwrap().kind,
        CoincidenceKind::Coplanar
    );
    let m = Model {
        surfaces: vec![Surface::new("a", a), Surface::new("b", b)],
        ..Default::default()
    };
    let res = vericad::ssi::intersect_models(&m, None, &SsiParams::default(), &|_, _| {}).unwrap();
    assert_eq!(res.summary.coincident_pairs, 1);
    assert!(!res.summary.certified && !res.summary.no_missed_branches);
}

use proptest::prelude::*;

proptest! {
    #![proptest_config(ProptestConfig::with_cases(10))]
    /// Spheres of radius 2 in random frames cut by planes at random heights (through the
    /// poles, beyond them, near tangency): every claim the run makes is checked against the
    /// construction — "no branch missed" only with a branch on the true circle (or no circle
    /// at all), every certified point within its proven radius of the circle, and nothing
    /// reported where the plane misses the sphere.
    #[test]
    fn random_rotated_spheres_and_planes(
        q in prop::array::uniform4(-1.0f64..1.0),
        o in prop::array::uniform3(-1.0f64..1.0),
        hk in -2300i32..2300,
    ) {
        prop_assume!(q.iter().map(|x| x * x).sum::<f64>() > 0.01);
        let f = frame_of(q, o);
        let r0 = 2.0;
        let h = hk as f64 / 1000.0;
        let s = sphere(&f, r0).unwrap();
        let e = 3.0;
        let at = |a: f64, b: f64| f.at(a, b, h);
        let p = bilinear(at(-e, -e), at(e, -e), at(-e, e), at(e, e)).unwrap();
        let r = run(&s, &p, 1e-7);
        let circle_dist = |x: &[f64; 3]| {
            let d: [f64; 3] = std::array::from_fn(|k| x[k] - f.o[k]);
            let dot = |u: &[f64; 3]| d[0] * u[0] + d[1] * u[1] + d[2] * u[2];
            let (a, b, c) = (dot(&f.x), dot(&f.y), dot(&f.z));
            let rho = (r0 * r0 - h * h).max(0.0).sqrt();
            (((a * a + b * b).sqrt() - rho).powi(2) + (c - h).powi(2)).sqrt()
        };
        // The frame is orthonormal only up to rounding: allow 1e-9 for it.
        let slack = 1e-9;
        if h.abs() > r0 + 1e-3 {
            prop_assert!(r.branches.is_empty(), "h {h}: the plane misses the sphere");
        }
        for b in &r.branches {
            for (x, rad) in b.points.iter().zip(&b.curve_radius) {
                if let Some(rad) = rad {
                    prop_assert!(circle_dist(x) <= rad + slack, "h {h}: {x:?} {rad}");
                }
            }
        }
        let cov = r.coverage.as_ref().unwrap();
        let certified_points: usize =
            r.branches.iter().map(|b| b.curve_radius.iter().flatten().count()).sum();
        eprintln!(
            "h {h}: {} branches, {certified_points} certified points, no missed branches {}",
            r.branches.len(),
            cov.no_missed_branches
        );
        if cov.no_missed_branches && h.abs() < r0 - 1e-3 {
            let found = r
                .branches
                .iter()
                .any(|b| b.points.iter().all(|x| circle_dist(x) <= 1e-6));
            prop_assert!(found, "h {h}: complete claimed, circle absent");
        }
    }
}

/// Faces proven to have no common point before anything is traced: the pieces subdivided
/// until every pair is free. A square inside a sphere (in a rotated frame, their boxes
/// overlapping) and domes 0.1, 1e-3 and 1e-5 below a plane are; a dome touching the plane at
/// its apex or crossing it is never called disjoint: the whole pipeline runs, and finds the
/// loop (radius 0.1), or the apex as a proven touching point.
#[test]
fn disjoint_faces_are_proven_so_before_tracing() {
    let f = rotated(3);
    let s = sphere(&f, 2.0).unwrap();
    let sq = bilinear(
        f.at(-0.5, -0.5, 0.3),
        f.at(0.5, -0.5, 0.3),
        f.at(-0.5, 0.5, 0.3),
        f.at(0.5, 0.5, 0.3),
    )
    .unwrap();
    for (a, b, disjoint, branches, touches) in [
        (&s, &sq, true, 0, 0),
        (&dome(-0.1, 1.0), &big_plane(), true, 0, 0),
        (&dome(-1e-3, 1.0), &big_plane(), true, 0, 0),
        (&dome(-1e-5, 1.0), &big_plane(), true, 0, 0),
        (&dome(0.0, 1.0), &big_plane(), false, 0, 1),
        (&dome(0.01, 1.0), &big_plane(), false, 1, 0),
    ] {
        let r = run(a, b, 1e-7);
        assert_eq!(r.stats.proven_disjoint, disjoint, "{:?}", r.stats);
        assert_eq!(r.branches.len(), branches);
        let cov = r.coverage.as_ref().unwrap();
        // The apex contact (a mesh vertex whose facets all lean by 35°, seeded by the vertex
        // normals): found, proven a touching point, and the run certified.
        assert_eq!(
            r.touch_points.len(),
            touches,
            "{:?} {cov:?}",
            r.touch_points
        );
        for t in &r.touch_points {
            let touching = t.singular.as_ref().is_some_and(|s| s.kind == TouchingPoint);
            assert!(touching, "{t:?}");
            assert!(
                t.point[2].abs() < 1e-9 && (t.point[0] - 0.5).abs() < 1e-6,
                "{t:?}"
            );
            assert!(cov.no_missed_branches, "{cov:?}");
        }
        if disjoint {
            assert!(cov.no_missed_branches, "{cov:?}");
            assert_eq!(cov.pairs, cov.free);
            assert_eq!(r.stats.triangles_a + r.stats.triangles_b, 0);
        } else {
            assert!(r.stats.triangles_a > 0);
        }
    }
}
