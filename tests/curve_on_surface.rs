//! Curves on B-spline surfaces (Yang et al. 2008): Table 2 reproduction and a Table 1–style
//! experiment, plus the scaling of eq. (12) and the error cases.

use vericad::curve_on_surface::{Bound, CosError, Params, approximate};
use vericad::geom::{Point, lift_point};
use vericad::model::{CurveGeometry, json};
use vericad::scalar::{Rational, ratio};
use vericad::spline::{NurbsCurve, NurbsSurface};

fn table2() -> (NurbsSurface<f64, 3>, NurbsCurve<f64, 2>) {
    let m = json::from_str(vericad::demo::DEFAULT_MODEL, "embedded").unwrap();
    let CurveGeometry::Domain(c) = m.curves[0].geometry.clone() else {
        panic!()
    };
    (m.surfaces[0].nurbs.clone(), c)
}

/// The Table 2 run at the paper's tolerances (ε_D = 1e-3, ε_T = 10°), local bound.
fn table2_at_paper_tolerances(
    s: &NurbsSurface<f64, 3>,
    c: &NurbsCurve<f64, 2>,
) -> vericad::curve_on_surface::CurveOnSurface {
    let p = Params {
        eps_d: 1e-3,
        eps_t_deg: 10.0,
        evidence_samples: 32,
        ..Params::default()
    };
    approximate(s, c, &p).unwrap()
}

#[test]
fn table2_reproduction() {
    let (s, c) = table2();
    let eq12 = approximate(
        &s,
        &c,
        &Params {
            eps_d: 1e-3,
            eps_t_deg: 10.0,
            bound: Bound::PaperEq12,
            ..Params::default()
        },
    )
    .unwrap();
    println!("with the paper's eq. (12) bound:\n{eq12}");
    let r = table2_at_paper_tolerances(&s, &c);
    println!("with the local bound:\n{r}");
    let dr = vericad::curve_on_surface::renner::degree_reduction(&s, &c, 1e-3).unwrap();
    println!(
        "degree reduction baseline (paper: degree 3, 7 segments, 16 control points, 0.63e-4 from S): \
         degree {}, {} segments, {} control points as a C1 cubic B-spline ({} as a Bézier chain; \
         junction tangents within {:.1e}°), {:.2e} from S, {:.2e} from the exact image (sampled)",
        dr.degree,
        dr.segments,
        dr.control_points_bspline,
        dr.control_points,
        dr.max_junction_angle_deg,
        dr.max_distance_to_surface_sampled,
        dr.max_deviation_sampled
    );
    // The baseline meets its tolerance at its samples and, unlike the blossomed segments,
    // does not lie on S (its distance to S is measured, and not negligible).
    assert_eq!(dr.exact_degree, 8);
    // S is C1 and D smooth, so the exact image is C1 and the Hermite cubics meet with
    // parallel tangents: the chain is a C1 cubic B-spline with double interior knots.
    assert!(
        dr.max_junction_angle_deg < 1e-3,
        "{}",
        dr.max_junction_angle_deg
    );
    assert_eq!(dr.control_points_bspline, 2 * dr.segments + 2);
    assert!(dr.max_deviation_sampled <= 1e-3);
    assert!(dr.max_distance_to_surface_sampled > 1e-6);
    assert!(dr.segments >= 1 && dr.segments < r.num_segments);
    println!("                 paper (Yang et al. Table 2)   vericad");
    println!(
        "degree           4                            {}",
        r.bspline.degree
    );
    println!(
        "control points   33                           {}",
        r.num_control_points
    );
    println!(
        "segments         8                            {}",
        r.num_segments
    );
    println!(
        "distance to S    0                            {} (exact)",
        r.certificate.distance_to_surface
    );
    println!(
        "continuity       10°-G1                       {:.2}°-G1",
        r.certificate.max_angle_deg
    );
    println!(
        "time (ms)        15 (Pentium IV 2 GHz)        {:.2}",
        r.elapsed_ms
    );
    assert_eq!(r.bspline.degree, 4);
    // The paper reports 8 segments; a proven 1e-3 bound needs more on this data (see
    // `paper_segment_count_cannot_meet_its_tolerance`). Same order as the local bound's
    // measured need, and far below eq. (12)'s.
    assert!(r.num_segments <= 64, "{} segments", r.num_segments);
    assert!(r.num_segments < eq12.num_segments);
    assert!(eq12.certificate.hausdorff_bound <= 1e-3);
    assert!(r.certificate.hausdorff_bound <= 1e-3);
    assert!(r.certificate.max_angle_deg <= 10.0);
    assert!(r.evidence.max_distance_sampled <= r.certificate.hausdorff_bound);
    assert!(r.bspline.joints_exact);
    // Distance to S exactly 0: every exact segment equals S(chord(t)) at rational t.
    let net: Vec<[Rational; 3]> = s
        .hom
        .net
        .iter()
        .map(|h| lift_point(&h.project().unwrap()))
        .collect();
    let sq = vericad::spline::BezierSurface::new(2, 2, net).unwrap();
    for seg in &r.segments {
        let a: [Rational; 2] = lift_point(&seg.domain[0]);
        let b: [Rational; 2] = lift_point(&seg.domain[1]);
        let exact = vericad::spline::compose::compose_line(&sq, &a, &b);
        for k in 0..=10i64 {
            let t = ratio(k, 10);
            let uv = a.lerp(&b, &t);
            assert_eq!(exact.eval(&t), sq.eval(&uv[0], &uv[1]));
        }
    }
}

/// The paper's Table 2 row: 8 segments at ε_D = 1e-3. Take 8 chords at uniform parameters
/// of the domain curve and *measure* (evidence, dense sampling) how far their images on S lie
/// from the exact image: far above 1e-3, while vericad's certified result stays below it.
#[test]
fn paper_segment_count_cannot_meet_its_tolerance() {
    let (s, c) = table2();
    let (pts, _) = s.points_weights();
    let bs = vericad::spline::BSplineSurface {
        ku: s.hom.ku.clone(),
        kv: s.hom.kv.clone(),
        net: pts,
    };
    let worst = vericad::curve_on_surface::evidence::uniform_chord_deviation(&bs, &c, 8);
    println!("8 uniform chords: measured deviation {worst:.3e} (paper: 8 segments within 1e-3)");
    assert!(worst > 5e-3, "{worst}");
    // However the chords are placed: the greedy covering by the longest chords whose images
    // stay within 1e-3 (measured) needs several times the paper's 8, and vericad's certified
    // count stays within twice that measured floor.
    let floor = vericad::curve_on_surface::evidence::greedy_chord_count(&bs, &c, 1e-3);
    let r = table2_at_paper_tolerances(&s, &c);
    println!(
        "fewest chords within 1e-3 (greedy, measured): {floor}; vericad (certified): {}",
        r.num_segments
    );
    assert!(floor > 2 * 8, "{floor}");
    assert!(r.num_segments >= floor && r.num_segments <= 2 * floor);
}

use vericad::curve_on_surface::examples::{closed_curve, face_like as face};

/// Table 1–style experiment: the measured error never exceeds the tolerance; the table of
/// tolerance, proven bound, measured error and tightness is printed.
#[test]
fn table1_experiment_measured_error_within_tolerance() {
    let (s, c) = (face(), closed_curve());
    println!(
        "tolerance   segments  proven bound  measured (evidence)  measured/tolerance  max angle"
    );
    for eps in [1.0, 0.5, 0.3, 0.1, 0.01, 0.001, 0.0001] {
        let r = approximate(
            &s,
            &c,
            &Params {
                eps_d: eps,
                eps_t_deg: 10.0,
                evidence_samples: 16,
                ..Params::default()
            },
        )
        .unwrap();
        println!(
            "{eps:<11} {:<9} {:<13.3e} {:<20.3e} {:<19.3} {:.2}",
            r.num_segments,
            r.certificate.hausdorff_bound,
            r.evidence.max_distance_sampled,
            r.evidence.max_distance_sampled / eps,
            r.certificate.max_angle_deg
        );
        assert!(r.certificate.hausdorff_bound <= eps);
        assert!(r.evidence.max_distance_sampled <= eps);
        assert!(r.bspline.joints_exact);
        assert_eq!(r.certificate.unresolved_junctions, 0);
        assert!(r.certificate.max_angle_deg <= 10.0);
    }
}

/// The scaling of eq. (12): on a patch with very unequal knot spans, measured Lipschitz
/// quotients |S(x) - S(y)| / |x - y| (global parameters) never exceed the bound, and the
/// unscaled ([0,1]²) bound would be violated.
#[test]
fn eq12_scaling_bounds_measured_quotients() {
    use vericad::curve_on_surface::cells::Cells;
    let (s, _) = table2();
    // Same geometry, domain [0, 0.01] × [0, 7]: derivatives in u grow by 100, in v shrink by 7.
    let (pts, w) = s.points_weights();
    let sk = NurbsSurface::new(
        vec![0., 0., 0., 0.01, 0.01, 0.01],
        2,
        vec![0., 0., 0., 7., 7., 7.],
        2,
        3,
        3,
        pts,
        w,
    )
    .unwrap();
    let (p, _) = sk.points_weights();
    let bs = vericad::spline::BSplineSurface {
        ku: sk.hom.ku.clone(),
        kv: sk.hom.kv.clone(),
        net: p,
    };
    let cells = Cells::new(&bs, None, 1.0).unwrap();
    let k_scaled = cells.cells[0].lipschitz;
    let mut worst = 0.0f64;
    let mut r = 1u64;
    let mut rnd = || {
        r = r
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (r >> 11) as f64 / (1u64 << 53) as f64
    };
    for _ in 0..20000 {
        let (u, v) = (rnd() * 0.01, rnd() * 7.0);
        let (du, dv) = ((rnd() - 0.5) * 1e-5, (rnd() - 0.5) * 1e-3);
        let (u2, v2) = ((u + du).clamp(0.0, 0.01), (v + dv).clamp(0.0, 7.0));
        let a = bs.eval(&u, &v);
        let b = bs.eval(&u2, &v2);
        let dxy = ((u2 - u).powi(2) + (v2 - v).powi(2)).sqrt();
        if dxy > 0.0 {
            worst = worst.max(vericad::geom::dist(&a, &b) / dxy);
        }
    }
    println!("max measured quotient {worst:.4}, scaled bound {k_scaled:.4}");
    assert!(worst <= k_scaled);
    // The unscaled bound (as for [0,1]²) is ~100x too small here.
    let unscaled = {
        let c1 = Cells::new(
            &{
                let (p, _) = s.points_weights();
                vericad::spline::BSplineSurface {
                    ku: s.hom.ku.clone(),
                    kv: s.hom.kv.clone(),
                    net: p,
                }
            },
            None,
            1.0,
        )
        .unwrap();
        c1.cells[0].lipschitz
    };
    assert!(
        worst > unscaled,
        "quotient {worst} should exceed the unscaled bound {unscaled}"
    );
}

#[test]
fn bad_inputs_get_typed_errors() {
    let (s, _) = table2();
    // A domain curve leaving [0,1]².
    let out = NurbsCurve::new(
        vec![0., 0., 1., 1.],
        1,
        vec![[0.5, 0.5], [1.5, 0.5]],
        vec![1.0, 1.0],
    )
    .unwrap();
    assert!(matches!(
        approximate(&s, &out, &Params::default()),
        Err(CosError::OutOfDomain { .. })
    ));
    let (_, c) = table2();
    // A rational surface: both arithmetics certify it, on the same chords.
    let (pts, mut w) = s.points_weights();
    w[4] = 2.0;
    let k = vec![0., 0., 0., 1., 1., 1.];
    let rs = NurbsSurface::new(k.clone(), 2, k, 2, 3, 3, pts, w).unwrap();
    let exact = Params {
        arithmetic: vericad::curve_on_surface::Arithmetic::Exact,
        ..Params::default()
    };
    let (re, rf) = (
        approximate(&rs, &c, &exact).unwrap(),
        approximate(&rs, &c, &Params::default()).unwrap(),
    );
    for r in [&re, &rf] {
        assert!(r.certificate.hausdorff_bound <= Params::default().eps_d);
        assert!(r.segments.iter().all(|s| s.weights.is_some()));
    }
    // The chord ends agree but for the rounding of D's values (the exact path rounds exact
    // values, the f64 path computes them in f64).
    assert_eq!(re.domain_polyline.len(), rf.domain_polyline.len());
    for (a, b) in re.domain_polyline.iter().zip(&rf.domain_polyline) {
        assert!((a[0] - b[0]).abs() <= 1e-15 && (a[1] - b[1]).abs() <= 1e-15);
    }
    for (a, b) in re.segments.iter().zip(&rf.segments) {
        for t in [0.0, 0.3, 0.7, 1.0] {
            let (x, y) = (a.eval(t), b.eval(t));
            let d = ((x[0] - y[0]).powi(2) + (x[1] - y[1]).powi(2) + (x[2] - y[2]).powi(2)).sqrt();
            assert!(d <= 1e-13, "exact and f64 segments differ by {d:e}");
        }
    }
    // Bad tolerances.
    for (e, t) in [
        (0.0, 10.0),
        (f64::NAN, 10.0),
        (1e-3, -1.0),
        (1e-3, 180.0),
        (1e-3, 200.0),
        (1e-3, f64::INFINITY),
        (f64::INFINITY, 10.0),
    ] {
        assert!(matches!(
            approximate(
                &s,
                &c,
                &Params {
                    eps_d: e,
                    eps_t_deg: t,
                    ..Params::default()
                }
            ),
            Err(CosError::Tolerance(..))
        ));
    }
}

/// Degenerate positions relative to knot lines of the 17 × 17 surface (knots at i/14):
/// a curve running exactly along the knot line u = 1/2, and a parabola touching it
/// tangentially at t = 1/2 (a double root of u(t) - 1/2: no crossing, Sturm path).
#[test]
fn curves_along_and_tangent_to_knot_lines() {
    let s = face();
    let along = NurbsCurve::new(
        vec![0., 0., 1., 1.],
        1,
        vec![[0.5, 0.1], [0.5, 0.9]],
        vec![1.0; 2],
    )
    .unwrap();
    // u(t) = 0.3 (1-t)² + 1.4 t (1-t) + 0.3 t² reaches 0.5 exactly at t = 1/2 (tangent).
    let touch = NurbsCurve::new(
        vec![0., 0., 0., 1., 1., 1.],
        2,
        vec![[0.3, 0.2], [0.7, 0.5], [0.3, 0.8]],
        vec![1.0; 3],
    )
    .unwrap();
    for (name, c) in [("along", along), ("tangent", touch)] {
        let r = approximate(
            &s,
            &c,
            &Params {
                eps_d: 1e-3,
                evidence_samples: 32,
                ..Params::default()
            },
        )
        .unwrap_or_else(|e| panic!("{name}: {e}"));
        assert!(r.certificate.hausdorff_bound <= 1e-3, "{name}");
        // Evidence is f64 sampling: allow its own rounding noise above an exact bound of ~0.
        assert!(
            r.evidence.max_distance_sampled <= r.certificate.hausdorff_bound + 1e-14,
            "{name}: {} > {}",
            r.evidence.max_distance_sampled,
            r.certificate.hausdorff_bound
        );
        assert!(r.bspline.joints_exact, "{name}");
        println!(
            "{name}: {} segments, proven {:.3e}, measured {:.3e}",
            r.num_segments, r.certificate.hausdorff_bound, r.evidence.max_distance_sampled
        );
        // Every chord stays inside one patch: both ends in the same knot rectangle.
        let cell = |x: f64| (x * 14.0).floor().min(13.0);
        for seg in &r.segments {
            let [a, b] = seg.domain;
            let (ca, cb) = ((cell(a[0]), cell(a[1])), (cell(b[0]), cell(b[1])));
            let on_line = |x: f64| (x * 14.0).fract() == 0.0;
            assert!(
                ca == cb || on_line(a[0]) || on_line(a[1]) || on_line(b[0]) || on_line(b[1]),
                "{name}: {a:?} -> {b:?}"
            );
        }
    }
}
