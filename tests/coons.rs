//! Projected Coons patches with multiquadric gap filling (paper A §3) on the situations of
//! the paper's Figures 8–11, with truth independent of the construction: distances to a
//! sphere and to planes are analytic, the oscillating surface is a graph `z = f(x, y)` whose
//! vertical distance bounds the true one; the multiquadric on a plane and on Franke's test
//! functions; bad inputs.

mod common;

use vericad::approx::coons::boundary::{BoundarySpec, CurveRef, CurveSpec};
use vericad::approx::coons::discrete::Grid;
use vericad::approx::coons::multiquadric::{fill, interpolate};
use vericad::approx::coons::{Approximant, CoonsError, Params, approximate, bicubic};
use vericad::geom::{Point, cross, norm};
use vericad::model::{Curve, CurveGeometry, Model, Surface};
use vericad::spline::construct::{Frame, arc, bilinear, revolve_curve_range};
use vericad::spline::{NurbsCurve, NurbsSurface};

/// The unit sphere between longitudes `a0..a1` and latitudes ±0.6.
fn sphere_piece(a0: f64, a1: f64) -> NurbsSurface<f64, 3> {
    let meridian_plane = Frame {
        o: [0.0; 3],
        x: [1.0, 0.0, 0.0],
        y: [0.0, 0.0, 1.0],
        z: [0.0, -1.0, 0.0],
    };
    let profile = arc(&meridian_plane, 1.0, -0.6, 0.6).unwrap();
    revolve_curve_range(&[0.0; 3], &[0.0, 0.0, 1.0], &profile, a0, a1).unwrap()
}

/// Latitude circle `φ` from longitude `a0` to `a1`.
fn latitude(phi: f64, a0: f64, a1: f64) -> NurbsCurve<f64, 3> {
    let f = Frame {
        o: [0.0, 0.0, phi.sin()],
        ..Frame::WORLD
    };
    arc(&f, phi.cos(), a0, a1).unwrap()
}

/// Meridian at longitude `a` from latitude `p0` to `p1`.
fn meridian(a: f64, p0: f64, p1: f64) -> NurbsCurve<f64, 3> {
    let x = [a.cos(), a.sin(), 0.0];
    let y = [0.0, 0.0, 1.0];
    let f = Frame {
        o: [0.0; 3],
        x,
        y,
        z: cross(&x, &y),
    };
    arc(&f, 1.0, p0, p1).unwrap()
}

fn curve(name: &str, c: NurbsCurve<f64, 3>) -> Curve {
    Curve {
        name: name.into(),
        geometry: CurveGeometry::Space(c),
    }
}

fn by_index(i: usize) -> CurveSpec {
    CurveSpec {
        curve: Some(CurveRef::Index(i)),
        polyline: None,
        reversed: false,
        name: None,
    }
}

fn polyline(pts: Vec<[f64; 3]>) -> CurveSpec {
    CurveSpec {
        curve: None,
        polyline: Some(pts),
        reversed: false,
        name: None,
    }
}

/// The sphere model with the patch's four boundary curves (longitudes 0.2..1.3, latitudes
/// ±0.4) as model curves 0–3, in loop order but with curves 2 and 3 in their own direction.
fn sphere_model(pieces: &[(f64, f64)]) -> (Model, BoundarySpec) {
    let mut m = Model::default();
    for (k, (a0, a1)) in pieces.iter().enumerate() {
        m.surfaces.push(Surface::new(
            format!("sphere piece {k}"),
            sphere_piece(*a0, *a1),
        ));
    }
    m.curves = vec![
        curve("south", latitude(-0.4, 0.2, 1.3)),
        curve("east", meridian(1.3, -0.4, 0.4)),
        curve("north", latitude(0.4, 0.2, 1.3)),
        curve("west", meridian(0.2, -0.4, 0.4)),
    ];
    let spec = BoundarySpec {
        curves: (0..4).map(by_index).collect(),
    };
    (m, spec)
}

/// Largest of `f` over an `k × k` lattice of the approximant's domain, restricted by `keep`.
fn dense_max(
    s: &NurbsSurface<f64, 3>,
    k: usize,
    f: impl Fn(&[f64; 3]) -> f64,
    keep: impl Fn(&[f64; 3]) -> bool,
) -> f64 {
    let mut worst: f64 = 0.0;
    for i in 0..=k {
        for j in 0..=k {
            let p = s.eval(&(i as f64 / k as f64), &(j as f64 / k as f64));
            if keep(&p) {
                worst = worst.max(f(&p));
            }
        }
    }
    worst
}

fn sphere_distance(p: &[f64; 3]) -> f64 {
    (norm(p) - 1.0).abs()
}

/// `s_u` just left and right of every interior knot line `ξ_I` (and `s_v` across `η_J`):
/// the largest jump relative to the derivative's size.
fn c1_jump(ap: &Approximant) -> f64 {
    let s = &ap.surface;
    let (m, n) = (ap.report.m, ap.report.n);
    let eps = 1e-9;
    let mut worst: f64 = 0.0;
    for i in 1..m {
        let u = i as f64 / m as f64;
        for k in 0..=20 {
            let v = k as f64 / 20.0;
            let l = s.derivatives2(&(u - eps), &v)[1];
            let r = s.derivatives2(&(u + eps), &v)[1];
            worst = worst.max(norm(&l.sub(&r)) / norm(&l).max(1e-300));
        }
    }
    for j in 1..n {
        let v = j as f64 / n as f64;
        for k in 0..=20 {
            let u = k as f64 / 20.0;
            let l = s.derivatives2(&u, &(v - eps))[2];
            let r = s.derivatives2(&u, &(v + eps))[2];
            worst = worst.max(norm(&l.sub(&r)) / norm(&l).max(1e-300));
        }
    }
    worst
}

/// Figure 8: part of a single patch — the sphere, analytic distance.
#[test]
fn figure8_part_of_a_single_patch() {
    let (model, spec) = sphere_model(&[(0.0, 1.6)]);
    let params = Params {
        tol: 1e-4,
        ..Default::default()
    };
    let ap = approximate(&model, &spec, &params).unwrap();
    let r = &ap.report;
    eprintln!("figure 8: {:?}", r.rounds);
    assert!(r.within_tol, "{}", r.reason);
    assert_eq!(r.fill.filled, 0);
    assert!(r.proven.interpolates_grid_points);
    // The pipeline's measured distances agree with the analytic ones.
    for s in &ap.samples {
        let d = s.distance.unwrap();
        assert!(
            (d - sphere_distance(&s.point)).abs() < 1e-9,
            "{d} vs {}",
            sphere_distance(&s.point)
        );
    }
    // Dense samples, analytic distance: within the tolerance.
    let dense = dense_max(&ap.surface, 100, sphere_distance, |_| true);
    eprintln!(
        "figure 8: dense analytic max {dense:.3e}, M×N {}×{}",
        r.m, r.n
    );
    assert!(dense <= params.tol, "{dense}");
    // Grid points lie on the sphere (projected and refined).
    for p in &ap.points.data {
        assert!(sphere_distance(p) < 1e-12);
    }
    // The proven claims, checked independently: the surface passes through the grid
    // points, and its boundary stays within the hull bound of the boundary polylines.
    let (m, n) = (r.m, r.n);
    for i in 0..=m {
        for j in 0..=n {
            let q = ap
                .surface
                .eval(&(i as f64 / m as f64), &(j as f64 / n as f64));
            assert!(norm(&q.sub(ap.points.at(i, j))) < 1e-12);
        }
    }
    let bound = r.proven.boundary_hull_bound;
    let poly: Vec<[f64; 3]> = (0..=m).map(|i| *ap.points.at(i, 0)).collect();
    let mut seen: f64 = 0.0;
    for k in 0..=1000 {
        let q = ap.surface.eval(&(k as f64 / 1000.0), &0.0);
        let d = poly
            .windows(2)
            .map(|w| vericad::geom::dist_to_segment(&q, &w[0], &w[1]))
            .fold(f64::INFINITY, f64::min);
        seen = seen.max(d);
    }
    eprintln!("figure 8: boundary hull bound {bound:.3e}, seen {seen:.3e}");
    assert!(seen <= bound && bound < 0.05, "{seen} {bound}");
    // The boundary stays near the boundary curves: corners are the curves' ends.
    let corner = ap.surface.eval(&0.0, &0.0);
    let expect = [
        0.4f64.cos() * 0.2f64.cos(),
        0.4f64.cos() * 0.2f64.sin(),
        -(0.4f64.sin()),
    ];
    assert!(norm(&corner.sub(&expect)) < 1e-12);
}

/// Figure 9: two patches with a gap — bridged, within tolerance away from it, C1 across.
#[test]
fn figure9_two_patches_with_a_gap() {
    let (model, spec) = sphere_model(&[(0.0, 0.65), (0.85, 1.6)]);
    let params = Params {
        tol: 1e-4,
        ..Default::default()
    };
    let ap = approximate(&model, &spec, &params).unwrap();
    let r = &ap.report;
    eprintln!("figure 9: {:?} fill {:?}", r.rounds, r.fill);
    assert!(r.fill.filled > 0, "the gap must be filled");
    assert!(r.evidence.skipped_gap > 0);
    assert!(r.within_tol, "{}", r.reason);
    let h = 1.1 / r.m as f64;
    let away = |p: &[f64; 3]| {
        let a = p[1].atan2(p[0]);
        a < 0.65 - h || a > 0.85 + h
    };
    let near = |p: &[f64; 3]| !away(p);
    let dense_away = dense_max(&ap.surface, 120, sphere_distance, away);
    let dense_gap = dense_max(&ap.surface, 120, sphere_distance, near);
    eprintln!(
        "figure 9: M×N {}×{}, away from the gap {dense_away:.3e}, over the gap {dense_gap:.3e}",
        r.m, r.n
    );
    assert!(dense_away <= params.tol, "{dense_away}");
    // The bridge follows the sphere closely (the fill interpolates t smoothly).
    assert!(dense_gap <= 0.01, "{dense_gap}");
    let jump = c1_jump(&ap);
    eprintln!(
        "figure 9: C1 jump {jump:.3e}, control-net defect {:.3e}",
        r.c1_defect
    );
    assert!(jump < 1e-6, "{jump}");
}

fn plane_b(x: f64) -> f64 {
    0.2 * (x - 0.5)
}

/// Figure 10: two intersecting planes; the boundary runs along their upper envelope.
#[test]
fn figure10_intersecting_surfaces() {
    let mut model = Model::default();
    let (lo, hi) = (-0.2, 1.2);
    model.surfaces.push(Surface::new(
        "z = 0",
        bilinear([lo, lo, 0.0], [hi, lo, 0.0], [lo, hi, 0.0], [hi, hi, 0.0]).unwrap(),
    ));
    model.surfaces.push(Surface::new(
        "z = 0.2 (x - 0.5)",
        bilinear(
            [lo, lo, plane_b(lo)],
            [hi, lo, plane_b(hi)],
            [lo, hi, plane_b(lo)],
            [hi, hi, plane_b(hi)],
        )
        .unwrap(),
    ));
    let env = |x: f64, y: f64| [x, y, plane_b(x).max(0.0)];
    let spec = BoundarySpec {
        curves: vec![
            polyline(vec![env(0.0, 0.0), env(0.5, 0.0), env(1.0, 0.0)]),
            polyline(vec![env(1.0, 0.0), env(1.0, 1.0)]),
            polyline(vec![env(1.0, 1.0), env(0.5, 1.0), env(0.0, 1.0)]),
            polyline(vec![env(0.0, 1.0), env(0.0, 0.0)]),
        ],
    };
    let params = Params {
        tol: 1e-3,
        ..Default::default()
    };
    let ap = approximate(&model, &spec, &params).unwrap();
    let r = &ap.report;
    eprintln!("figure 10: {:?}", r.rounds);
    let truth = |p: &[f64; 3]| {
        p[2].abs()
            .min((p[2] - plane_b(p[0])).abs() / 1.04f64.sqrt())
    };
    for s in &ap.samples {
        let d = s.distance.unwrap();
        assert!(
            (d - truth(&s.point)).abs() < 1e-9,
            "{d} vs {}",
            truth(&s.point)
        );
    }
    let dense = dense_max(&ap.surface, 100, truth, |_| true);
    eprintln!(
        "figure 10: M×N {}×{}, dense analytic max {dense:.3e}, {}",
        r.m, r.n, r.reason
    );
    if r.within_tol {
        assert!(dense <= 2.0 * params.tol, "{dense}");
    } else {
        assert!(r.reason.contains("maximum resolution"), "{}", r.reason);
    }
}

/// Figure 11: a highly oscillating bicubic graph `z = f(x, y)` (Greville abscissae, so
/// `x = u`, `y = v`); the vertical distance `|z − f(x, y)|` bounds the true distance.
#[test]
fn figure11_highly_oscillating_surface() {
    let n = 15;
    let mut knots = vec![0.0; 4];
    for k in 1..n - 3 {
        knots.push(k as f64 / (n - 3) as f64);
    }
    knots.extend([1.0; 4]);
    let greville: Vec<f64> = (0..n)
        .map(|i| (knots[i + 1] + knots[i + 2] + knots[i + 3]) / 3.0)
        .collect();
    let mut pts = Vec::new();
    for i in 0..n {
        for j in 0..n {
            let sign = if (i + j) % 2 == 0 { 1.0 } else { -1.0 };
            pts.push([greville[i], greville[j], 0.05 * sign]);
        }
    }
    let s = NurbsSurface::new(knots.clone(), 3, knots, 3, n, n, pts, vec![1.0; n * n]).unwrap();
    let f = |x: f64, y: f64| s.eval(&x, &y)[2];
    let side = |k: usize| -> Vec<[f64; 3]> {
        (0..=200)
            .map(|i| {
                let t = 0.1 + 0.8 * i as f64 / 200.0;
                let (x, y) = match k {
                    0 => (t, 0.1),
                    1 => (0.9, t),
                    2 => (1.0 - t, 0.9),
                    _ => (0.1, 1.0 - t),
                };
                [x, y, f(x, y)]
            })
            .collect()
    };
    let model = Model {
        surfaces: vec![Surface::new("oscillating", s.clone())],
        ..Default::default()
    };
    let spec = BoundarySpec {
        curves: (0..4).map(|k| polyline(side(k))).collect(),
    };
    let params = Params {
        tol: 1e-3,
        max_resolution: 64,
        ..Default::default()
    };
    let ap = approximate(&model, &spec, &params).unwrap();
    let r = &ap.report;
    eprintln!("figure 11: {:?}, {}", r.rounds, r.reason);
    assert!(r.rounds.len() >= 2, "the resolution must be raised");
    for w in r.rounds.windows(2) {
        assert!(w[1].m >= w[0].m && w[1].n >= w[0].n && (w[1].m, w[1].n) != (w[0].m, w[0].n));
    }
    // Each measured distance is at most the independent upper bound.
    for sm in &ap.samples {
        let d = sm.distance.unwrap();
        let vertical = (sm.point[2] - f(sm.point[0], sm.point[1])).abs();
        assert!(d <= vertical + 1e-12, "measured {d} > vertical {vertical}");
    }
    assert!(
        r.within_tol || r.reason.contains("maximum resolution"),
        "{}",
        r.reason
    );
    if r.within_tol {
        assert!(r.evidence.max_error <= params.tol);
    }
}

/// The bicubic interpolant reproduces a plane (tangent scheme and twist rule are exact on
/// affine data) and is C1 by the knot-line derivative test.
#[test]
fn bicubic_reproduces_a_plane() {
    let (m, n) = (5, 7);
    let map = |u: f64, v: f64| {
        [
            1.0 + 2.0 * u - 0.5 * v,
            -1.0 + 0.3 * u + 1.7 * v,
            0.25 + u + v,
        ]
    };
    let mut y = Grid::filled(m, n, [0.0; 3]);
    for i in 0..=m {
        for j in 0..=n {
            y.set(i, j, map(i as f64 / m as f64, j as f64 / n as f64));
        }
    }
    let s = bicubic::interpolant(&y).unwrap();
    for i in 0..=40 {
        for j in 0..=40 {
            let (u, v) = (i as f64 / 40.0, j as f64 / 40.0);
            assert!(norm(&s.eval(&u, &v).sub(&map(u, v))) < 1e-13);
        }
    }
}

/// The multiquadric fill reproduces a plane through a hole to 1e-9.
#[test]
fn multiquadric_reproduces_a_plane() {
    let (m, n) = (20, 16);
    let plane = |u: f64, v: f64| 0.3 + 0.2 * u - 0.7 * v;
    let mut known = Grid::filled(m, n, None);
    let mut hole = 0;
    for i in 0..=m {
        for j in 0..=n {
            let (u, v) = (i as f64 / m as f64, j as f64 / n as f64);
            if (u - 0.45).powi(2) + (v - 0.55).powi(2) < 0.05 {
                hole += 1;
            } else {
                known.set(i, j, Some(plane(u, v)));
            }
        }
    }
    let (t, stats) = fill(&known, 8, 1.0, -0.5, true).unwrap();
    assert_eq!(stats.filled, hole);
    let mut worst: f64 = 0.0;
    for i in 0..=m {
        for j in 0..=n {
            worst = worst.max((t.at(i, j) - plane(i as f64 / m as f64, j as f64 / n as f64)).abs());
        }
    }
    eprintln!(
        "plane: {hole} filled, max error {worst:.3e}, max condition {:.3e}",
        stats.max_condition
    );
    assert!(worst < 1e-9, "{worst}");
}

/// Franke's (1982) test functions F1–F6.
fn franke(k: usize, x: f64, y: f64) -> f64 {
    let r2 = (x - 0.5).powi(2) + (y - 0.5).powi(2);
    match k {
        1 => {
            0.75 * (-((9.0 * x - 2.0).powi(2) + (9.0 * y - 2.0).powi(2)) / 4.0).exp()
                + 0.75 * (-(9.0 * x + 1.0).powi(2) / 49.0 - (9.0 * y + 1.0) / 10.0).exp()
                + 0.5 * (-((9.0 * x - 7.0).powi(2) + (9.0 * y - 3.0).powi(2)) / 4.0).exp()
                - 0.2 * (-(9.0 * x - 4.0).powi(2) - (9.0 * y - 7.0).powi(2)).exp()
        }
        2 => ((9.0 * y - 9.0 * x).tanh() + 1.0) / 9.0,
        3 => (1.25 + (5.4 * y).cos()) / (6.0 * (1.0 + (3.0 * x - 1.0).powi(2))),
        4 => (-81.0 / 16.0 * r2).exp() / 3.0,
        5 => (-81.0 / 4.0 * r2).exp() / 3.0,
        _ => (64.0 - 81.0 * r2).sqrt() / 9.0 - 0.5,
    }
}

/// Franke's functions on a 33 × 33 grid with a round hole (radius 0.12 about (0.4, 0.6)):
/// max and RMS error of the fill at the hole's points (the table in docs/coons.md).
#[test]
fn multiquadric_on_franke_functions() {
    let m = 32;
    for linear in [true, false] {
        for k in 1..=6 {
            let mut known = Grid::filled(m, m, None);
            for i in 0..=m {
                for j in 0..=m {
                    let (u, v) = (i as f64 / m as f64, j as f64 / m as f64);
                    if (u - 0.4).powi(2) + (v - 0.6).powi(2) >= 0.0144 {
                        known.set(i, j, Some(franke(k, u, v)));
                    }
                }
            }
            let (t, stats) = fill(&known, 8, 1.0, -0.5, linear).unwrap();
            let (mut worst, mut sum2, mut count) = (0.0f64, 0.0, 0);
            for i in 0..=m {
                for j in 0..=m {
                    if known.at(i, j).is_none() {
                        let e = (t.at(i, j) - franke(k, i as f64 / m as f64, j as f64 / m as f64))
                            .abs();
                        worst = worst.max(e);
                        sum2 += e * e;
                        count += 1;
                    }
                }
            }
            let rms = (sum2 / count as f64).sqrt();
            eprintln!(
                "Franke F{k} (linear part {linear}): {count} hole points, max {worst:.3e}, rms {rms:.3e}, condition ≤ {:.2e}",
                stats.max_condition
            );
            assert!(worst < 0.05, "F{k}: {worst}");
        }
    }
}

/// The plain interpolant is exact at its centres.
#[test]
fn multiquadric_interpolates_its_centres() {
    let c = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [0.7, 0.6], [0.2, 0.9]];
    let v = [1.0, -2.0, 0.5, 3.0, 0.0];
    for linear in [false, true] {
        let ip = interpolate(&c, &v, 0.1, -0.5, linear).unwrap();
        for (p, val) in c.iter().zip(&v) {
            assert!((ip.eval(p) - val).abs() < 1e-12);
        }
    }
}

/// Collinear centres (decided exactly) leave the linear part undetermined: it is dropped,
/// and the interpolant is still exact at the centres.
#[test]
fn multiquadric_on_collinear_centres() {
    let c = [
        [0.0, 0.25],
        [0.125, 0.25],
        [0.25, 0.25],
        [0.375, 0.25],
        [0.5, 0.25],
    ];
    let v = [0.1, 0.2, 0.4, 0.3, 0.0];
    let ip = interpolate(&c, &v, 0.0625, -0.5, true).unwrap();
    assert!(!ip.has_linear_part());
    for (p, val) in c.iter().zip(&v) {
        assert!((ip.eval(p) - val).abs() < 1e-12);
    }
}

fn square(z: f64, s: f64) -> Vec<CurveSpec> {
    let p = |x: f64, y: f64| [x * s, y * s, z];
    vec![
        polyline(vec![p(0.0, 0.0), p(1.0, 0.0)]),
        polyline(vec![p(1.0, 0.0), p(1.0, 1.0)]),
        polyline(vec![p(1.0, 1.0), p(0.0, 1.0)]),
        polyline(vec![p(0.0, 1.0), p(0.0, 0.0)]),
    ]
}

fn plane_model() -> Model {
    Model {
        surfaces: vec![Surface::new(
            "plane",
            bilinear(
                [-1.0, -1.0, 0.0],
                [2.0, -1.0, 0.0],
                [-1.0, 2.0, 0.0],
                [2.0, 2.0, 0.0],
            )
            .unwrap(),
        )],
        ..Default::default()
    }
}

fn run(curves: Vec<CurveSpec>, params: &Params) -> Result<Approximant, CoonsError> {
    approximate(&plane_model(), &BoundarySpec { curves }, params)
}

#[test]
fn bad_input_is_a_typed_error_naming_the_curve() {
    let p = Params::default();
    // A plane square works (sanity of the fixture).
    assert!(run(square(0.0, 1.0), &p).unwrap().report.within_tol);
    // Not closing: the third curve moved.
    let mut c = square(0.0, 1.0);
    c[2] = polyline(vec![[1.0, 1.2, 0.0], [0.0, 1.2, 0.0]]);
    c[2].name = Some("top".into());
    match run(c, &p) {
        Err(CoonsError::NotClosed { from, to, .. }) => {
            assert!(from == "top" || to == "top", "{from} {to}")
        }
        other => panic!("{other:?}"),
    }
    // A zero-length side.
    let mut c = square(0.0, 1.0);
    c.insert(1, polyline(vec![[1.0, 0.0, 0.0], [1.0, 0.0, 0.0]]));
    c.remove(2);
    c[1].name = Some("point".into());
    c[2] = polyline(vec![[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]);
    match run(c, &p) {
        Err(CoonsError::Degenerate { curve, .. }) => assert_eq!(curve, "point"),
        other => panic!("{other:?}"),
    }
    // A self-crossing loop (a bow tie).
    let mut c = vec![
        polyline(vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]]),
        polyline(vec![[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]),
        polyline(vec![[0.0, 1.0, 0.0], [1.0, 1.0, 0.0]]),
        polyline(vec![[1.0, 1.0, 0.0], [0.0, 0.0, 0.0]]),
    ];
    c[1].name = Some("diagonal 1".into());
    c[3].name = Some("diagonal 2".into());
    match run(c, &p) {
        Err(CoonsError::SelfCrossing { a, b }) => {
            assert!(a.contains("diagonal") || b.contains("diagonal"), "{a} {b}")
        }
        Err(CoonsError::Flat(names)) => assert!(names.contains("diagonal"), "{names}"),
        other => panic!("{other:?}"),
    }
    // Far from every surface.
    match run(square(50.0, 1.0), &p) {
        Err(CoonsError::FarFromSurfaces { curves, .. }) => assert!(curves.contains("#0")),
        other => panic!("{other:?}"),
    }
    // M or N zero.
    for (m, n) in [(0, 8), (8, 0)] {
        let q = Params {
            m,
            n,
            ..Default::default()
        };
        assert!(matches!(
            run(square(0.0, 1.0), &q),
            Err(CoonsError::Resolution { .. })
        ));
    }
    // A curve index the model does not have, a domain curve, a non-finite point.
    let mut m = plane_model();
    m.curves.push(Curve {
        name: "domain".into(),
        geometry: CurveGeometry::Domain(
            NurbsCurve::new(
                vec![0.0, 0.0, 1.0, 1.0],
                1,
                vec![[0.0, 0.0], [1.0, 0.0]],
                vec![1.0, 1.0],
            )
            .unwrap(),
        ),
    });
    let mut c = square(0.0, 1.0);
    c[0] = by_index(7);
    assert!(
        matches!(approximate(&m, &BoundarySpec { curves: c }, &p), Err(CoonsError::Curve { curve, .. }) if curve == "#0")
    );
    let mut c = square(0.0, 1.0);
    c[1] = by_index(0);
    assert!(
        matches!(approximate(&m, &BoundarySpec { curves: c }, &p), Err(CoonsError::Curve { curve, .. }) if curve.contains("#1"))
    );
    let mut c = square(0.0, 1.0);
    c[3] = polyline(vec![[0.0, 1.0, 0.0], [f64::NAN, 0.5, 0.0], [0.0, 0.0, 0.0]]);
    assert!(matches!(run(c, &p), Err(CoonsError::Curve { curve, .. }) if curve == "#3"));
    // Three curves; a tolerance that is NaN.
    let mut c = square(0.0, 1.0);
    c.pop();
    assert!(matches!(run(c, &p), Err(CoonsError::Boundary(_))));
    let q = Params {
        tol: f64::NAN,
        ..Default::default()
    };
    assert!(matches!(
        run(square(0.0, 1.0), &q),
        Err(CoonsError::Tolerance(_))
    ));
    // Bad JSON names its path.
    match BoundarySpec::parse(r#"{"curves": [{"curve": 0, "colour": 1}]}"#) {
        Err(CoonsError::Boundary(msg)) => assert!(msg.contains("curves[0]"), "{msg}"),
        other => panic!("{other:?}"),
    }
}

#[test]
fn boundary_file_format() {
    let spec = BoundarySpec::parse(
        r#"{"curves": [{"curve": 3}, {"curve": "wing", "reversed": true}, {"polyline": [[0,0,0],[1,0,0]]}, {"curve": 1, "name": "left"}]}"#,
    )
    .unwrap();
    assert_eq!(spec.curves[0].curve, Some(CurveRef::Index(3)));
    assert_eq!(spec.curves[1].curve, Some(CurveRef::Name("wing".into())));
    assert!(spec.curves[1].reversed);
    assert_eq!(spec.curves[2].polyline.as_ref().map(|p| p.len()), Some(2));
    assert_eq!(spec.curves[3].name.as_deref(), Some("left"));
}

fn fuselage() -> Model {
    let p = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/public/occt-bug28366_fuselage.stp");
    vericad::io::read_model(&p).unwrap()
}

/// Polyline along an iso-curve of surface `s`: `(u, v)` from `a` to `b`, 40 segments.
fn iso(m: &Model, s: usize, a: [f64; 2], b: [f64; 2]) -> Vec<[f64; 3]> {
    (0..=40)
        .map(|k| {
            let t = k as f64 / 40.0;
            let (u, v) = (a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]));
            m.surfaces[s].nurbs.eval(&u, &v)
        })
        .collect()
}

fn joined(mut a: Vec<[f64; 3]>, b: Vec<[f64; 3]>) -> Vec<[f64; 3]> {
    a.pop();
    a.extend(b);
    a
}

/// The fuselage's top around the joint of its front and rear sections: four patches
/// (0, 1 in front, 4, 5 behind), boundaries along iso-curves sampled as polylines.
fn fuselage_top(m: &Model) -> BoundarySpec {
    BoundarySpec {
        curves: vec![
            polyline(joined(
                iso(m, 0, [2.5, 0.5], [3.0, 0.5]),
                iso(m, 4, [0.0, 0.5], [0.5, 0.5]),
            )),
            polyline(joined(
                iso(m, 4, [0.5, 0.5], [0.5, 1.0]),
                iso(m, 5, [0.5, 0.0], [0.5, 0.5]),
            )),
            polyline(joined(
                iso(m, 5, [0.5, 0.5], [0.0, 0.5]),
                iso(m, 1, [3.0, 0.5], [2.5, 0.5]),
            )),
            polyline(joined(
                iso(m, 1, [2.5, 0.5], [2.5, 0.0]),
                iso(m, 0, [2.5, 1.0], [2.5, 0.5]),
            )),
        ],
    }
}

/// Real data: an approximant over four patches of the fuselage (Open CASCADE's
/// bug28366): grid points on the patches, the measured error within tolerance, and every
/// measured distance checked against a second, independent projection start.
#[test]
fn fuselage_part() {
    let m = fuselage();
    let spec = fuselage_top(&m);
    let params = Params {
        tol: 1e-5,
        ..Default::default()
    };
    let t0 = std::time::Instant::now();
    let ap = approximate(&m, &spec, &params).unwrap();
    let r = &ap.report;
    eprintln!(
        "fuselage: {:?}, {} surfaces, {} triangles, {}, {:.2} s",
        r.rounds,
        r.surfaces_considered.len(),
        r.triangles,
        r.reason,
        t0.elapsed().as_secs_f64()
    );
    assert!(r.within_tol, "{}", r.reason);
    assert_eq!(r.fill.filled, 0);
    for k in [0, 1, 4, 5] {
        assert!(r.surfaces_considered.contains(&k));
    }
    // Independent check of the measured distances: the closest point from the global
    // multi-start search of every original surface is never much closer.
    for s in ap.samples.iter().step_by(3) {
        let d = s.distance.unwrap();
        let best = m
            .surfaces
            .iter()
            .map(|f| {
                let uv = vericad::spline::project::project(&f.nurbs, &s.point);
                norm(&f.nurbs.eval(&uv[0], &uv[1]).sub(&s.point))
            })
            .fold(f64::INFINITY, f64::min);
        assert!(d <= best + 1e-9, "measured {d} > {best}");
    }
}

fn vericad(args: &[&str]) -> (i32, String, String) {
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_vericad"))
        .args(args)
        .output()
        .unwrap();
    (
        o.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&o.stdout).into(),
        String::from_utf8_lossy(&o.stderr).into(),
    )
}

/// `vericad coons` end to end on the fuselage: exit 0, the surface written as IGES reads
/// back equal to the library's approximant, the report and the VTK view written; exit 3
/// when the maximum resolution stops it; exit 2 on bad boundary files; exit 1 when an
/// output is not writable (checked before the work).
#[test]
fn cli_coons() {
    let dir = std::env::temp_dir().join(format!("vericad-coons-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let model_path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/public/occt-bug28366_fuselage.stp");
    let model = fuselage();
    let spec = fuselage_top(&model);
    let boundary = dir.join("boundary.json");
    let curves: Vec<String> = spec
        .curves
        .iter()
        .map(|c| {
            format!(
                "{{\"polyline\": {}}}",
                serde_json::to_string(c.polyline.as_ref().unwrap()).unwrap()
            )
        })
        .collect();
    std::fs::write(
        &boundary,
        format!("{{\"curves\": [{}]}}", curves.join(", ")),
    )
    .unwrap();
    let (out, report, vtk) = (
        dir.join("patch.igs"),
        dir.join("report.json"),
        dir.join("view.vtp"),
    );
    let s = |p: &std::path::Path| p.to_str().unwrap().to_string();
    let (code, stdout, stderr) = vericad(&[
        "coons",
        &s(&model_path),
        "--boundary",
        &s(&boundary),
        "--tol",
        "1e-4",
        "--out",
        &s(&out),
        "--report",
        &s(&report),
        "--vtk",
        &s(&vtk),
    ]);
    assert_eq!(code, 0, "{stdout}\n{stderr}");
    assert!(
        stdout.contains("proven: interpolates the grid points: true"),
        "{stdout}"
    );
    let lib = approximate(
        &model,
        &spec,
        &Params {
            tol: 1e-4,
            ..Default::default()
        },
    )
    .unwrap();
    let back = vericad::io::read_model(&out).unwrap();
    assert_eq!(back.surfaces.len(), 1);
    for (u, v) in [(0.0, 0.0), (0.3, 0.7), (1.0, 0.5), (0.55, 1.0)] {
        let d = norm(
            &back.surfaces[0]
                .nurbs
                .eval(&u, &v)
                .sub(&lib.surface.eval(&u, &v)),
        );
        assert!(d < 1e-9, "{d}");
    }
    let rep: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
    assert_eq!(
        rep["approximant"]["within_tol"],
        serde_json::Value::Bool(true)
    );
    assert!(
        std::fs::read_to_string(&vtk)
            .unwrap()
            .contains("Name=\"part\"")
    );
    // The maximum resolution reached: exit 3, and said.
    let (code, stdout, _) = vericad(&[
        "coons",
        &s(&model_path),
        "--boundary",
        &s(&boundary),
        "--tol",
        "1e-7",
        "--max-resolution",
        "16",
    ]);
    assert_eq!(code, 3);
    assert!(stdout.contains("maximum resolution 16 reached"), "{stdout}");
    // Bad boundary file: three curves; a missing file; M = 0.
    let three = dir.join("three.json");
    std::fs::write(
        &three,
        format!("{{\"curves\": [{}]}}", curves[..3].join(", ")),
    )
    .unwrap();
    let (code, _, stderr) = vericad(&["coons", &s(&model_path), "--boundary", &s(&three)]);
    assert_eq!(code, 2, "{stderr}");
    assert!(stderr.contains("expected 4 boundary curves"), "{stderr}");
    let (code, _, _) = vericad(&[
        "coons",
        &s(&model_path),
        "--boundary",
        &s(&dir.join("none.json")),
    ]);
    assert_eq!(code, 2);
    let (code, _, stderr) = vericad(&[
        "coons",
        &s(&model_path),
        "--boundary",
        &s(&boundary),
        "--m",
        "0",
    ]);
    assert_eq!(code, 2);
    assert!(stderr.contains("resolution M = 0"), "{stderr}");
    // An output in a directory that does not exist: refused before the work.
    let (code, _, stderr) = vericad(&[
        "coons",
        &s(&model_path),
        "--boundary",
        &s(&boundary),
        "--out",
        &s(&dir.join("no/such/dir/p.igs")),
    ]);
    assert_eq!(code, 1, "{stderr}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// Real data across a crease: the fuselage's rear section is only C0 along its first
/// interior knot line (`x = 156.79`, tangents 4.9° apart — computed here from the data), so
/// a C1 approximant spanning it cannot reach a tight tolerance: the maximum resolution is
/// reached and said, and the worst sample lies at the crease.
#[test]
fn fuselage_across_a_crease() {
    let m = fuselage();
    let s4 = &m.surfaces[4].nurbs;
    let (l, r) = (
        s4.derivatives2(&(1.0 - 1e-9), &0.5)[1],
        s4.derivatives2(&(1.0 + 1e-9), &0.5)[1],
    );
    let angle = (vericad::geom::dot(&l, &r) / (norm(&l) * norm(&r)))
        .clamp(-1.0, 1.0)
        .acos();
    assert!(angle.to_degrees() > 4.0, "{}", angle.to_degrees());
    let crease_x = s4.eval(&1.0, &0.5)[0];
    let iso80 = |s: usize, a: [f64; 2], b: [f64; 2]| -> Vec<[f64; 3]> {
        (0..=80)
            .map(|k| {
                let t = k as f64 / 80.0;
                m.surfaces[s]
                    .nurbs
                    .eval(&(a[0] + t * (b[0] - a[0])), &(a[1] + t * (b[1] - a[1])))
            })
            .collect()
    };
    let (ua, ub, va) = (1.0, 2.5, 0.1);
    let spec = BoundarySpec {
        curves: vec![
            polyline(joined(
                iso80(0, [ua, va], [3.0, va]),
                iso80(4, [0.0, va], [ub, va]),
            )),
            polyline(joined(
                iso80(4, [ub, va], [ub, 1.0]),
                iso80(5, [ub, 0.0], [ub, 1.0 - va]),
            )),
            polyline(joined(
                iso80(5, [ub, 1.0 - va], [0.0, 1.0 - va]),
                iso80(1, [3.0, 1.0 - va], [ua, 1.0 - va]),
            )),
            polyline(joined(
                iso80(1, [ua, 1.0 - va], [ua, 0.0]),
                iso80(0, [ua, 1.0], [ua, va]),
            )),
        ],
    };
    let params = Params {
        tol: 1e-3,
        max_resolution: 64,
        ..Default::default()
    };
    let t0 = std::time::Instant::now();
    let ap = approximate(&m, &spec, &params).unwrap();
    let r = &ap.report;
    let errors: Vec<(usize, usize, f64)> =
        r.rounds.iter().map(|x| (x.m, x.n, x.max_error)).collect();
    eprintln!(
        "fuselage across the crease: {errors:?}, {:.2} s",
        t0.elapsed().as_secs_f64()
    );
    assert!(!r.within_tol);
    assert!(
        r.reason.contains("maximum resolution 64 reached"),
        "{}",
        r.reason
    );
    let worst = ap
        .samples
        .iter()
        .max_by(|a, b| {
            a.distance
                .unwrap_or(0.0)
                .total_cmp(&b.distance.unwrap_or(0.0))
        })
        .unwrap();
    let cell = (r.boundary_lengths[0] / r.m as f64).max(r.boundary_lengths[2] / r.m as f64);
    assert!(
        (worst.point[0] - crease_x).abs() < 2.0 * cell,
        "worst at x = {}, crease at {crease_x}",
        worst.point[0]
    );
}

/// Random and hostile boundaries never panic: polylines with repeated, huge, tiny,
/// non-finite or random points, random M, N, K and tolerances; every outcome is a result or
/// a typed error.
#[test]
fn hostile_boundaries_never_panic() {
    let mut rng = common::Rng(0xC0045);
    let model = plane_model();
    let specials = [
        0.0,
        -0.0,
        1e-300,
        1e300,
        f64::MAX,
        f64::MIN_POSITIVE,
        f64::NAN,
        f64::INFINITY,
        1.0,
        0.5,
    ];
    let mut outcomes = std::collections::BTreeMap::new();
    for case in 0..200 {
        let mut curves = square(rng.range(-0.5, 0.5), rng.range(1e-9, 3.0));
        for _ in 0..rng.below(4) {
            let k = rng.below(4);
            let mut pts = curves[k].polyline.clone().unwrap();
            let q = rng.below(pts.len());
            match rng.below(4) {
                0 => pts[q][rng.below(3)] = specials[rng.below(specials.len())],
                1 => pts.insert(q, pts[q]),
                2 => pts.push([
                    rng.range(-2.0, 2.0),
                    rng.range(-2.0, 2.0),
                    rng.range(-1.0, 1.0),
                ]),
                _ => pts.truncate(1),
            }
            curves[k] = polyline(pts);
        }
        if rng.below(10) == 0 {
            curves.truncate(rng.below(5));
        }
        let params = Params {
            tol: [1e-3, 1e-3, 1e-3, 0.0, f64::NAN, 1e-12, 10.0][rng.below(7)],
            m: rng.below(12),
            n: 1 + rng.below(12),
            max_resolution: 1 + rng.below(32),
            k_nearest: 1 + rng.below(12),
            ..Default::default()
        };
        let r = std::panic::catch_unwind(|| {
            approximate(
                &model,
                &BoundarySpec {
                    curves: curves.clone(),
                },
                &params,
            )
        });
        assert!(r.is_ok(), "case {case} panicked: {curves:?} {params:?}");
        let key = match r {
            Ok(Ok(_)) => "approximant".to_string(),
            Ok(Err(e)) => format!("{e:?}")
                .split([' ', '(', '{'])
                .next()
                .unwrap_or("")
                .to_string(),
            Err(_) => "panic".into(),
        };
        *outcomes.entry(key).or_insert(0) += 1;
    }
    eprintln!("{outcomes:?}");
    assert!(
        outcomes.get("approximant").is_some_and(|n| *n >= 20),
        "{outcomes:?}"
    );
}

/// The fuzz target's body over a seed and byte-level mutations of it.
#[test]
fn coons_boundary_fuzz_entry_survives_mutations() {
    let seed = br#"{"curves": [{"polyline": [[0,0,0],[1,0,0]]}, {"polyline": [[1,0,0],[1,1,0.2]]}, {"polyline": [[1,1,0.2],[0,1,0]]}, {"polyline": [[0,1,0],[0,0,0]], "reversed": false}]}"#;
    vericad::fuzz_entry::coons_boundary(seed);
    let mut rng = common::Rng(7);
    for _ in 0..300 {
        let mut s = seed.to_vec();
        for _ in 0..1 + rng.below(3) {
            let k = rng.below(s.len());
            s[k] = b"0123456789.-e,[]{}\" 1"[rng.below(20)];
        }
        vericad::fuzz_entry::coons_boundary(&s);
    }
}

/// A gap made by trimming (IGES-style loops in the parameter plane): two faces on the same
/// hyperbolic paraboloid `z = 0.3 x y` (`x = u`, `y = v`), trimmed to `x ≤ 0.45` and
/// `x ≥ 0.55`. Grid points over the trimmed-away strip must be artificial, the others hits;
/// the fill bridges the strip on the paraboloid.
#[test]
fn gap_made_by_trimming() {
    use vericad::model::TrimLoop;
    let s = bilinear(
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [1.0, 1.0, 0.3],
    )
    .unwrap();
    let rect = |x0: f64, x1: f64| TrimLoop {
        outer: true,
        curves: [[x0, 0.0], [x1, 0.0], [x1, 1.0], [x0, 1.0]]
            .iter()
            .zip([[x1, 0.0], [x1, 1.0], [x0, 1.0], [x0, 0.0]].iter())
            .map(|(a, b)| {
                NurbsCurve::new(vec![0.0, 0.0, 1.0, 1.0], 1, vec![*a, *b], vec![1.0, 1.0]).unwrap()
            })
            .collect(),
    };
    let mut a = Surface::new("x ≤ 0.45", s.clone());
    a.trim_loops = vec![rect(0.0, 0.45)];
    let mut b = Surface::new("x ≥ 0.55", s);
    b.trim_loops = vec![rect(0.55, 1.0)];
    let model = Model {
        surfaces: vec![a, b],
        ..Default::default()
    };
    let f = |x: f64, y: f64| [x, y, 0.3 * x * y];
    let line = |p: [f64; 2], q: [f64; 2]| {
        polyline(
            (0..=20)
                .map(|k| {
                    let t = k as f64 / 20.0;
                    f(p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1]))
                })
                .collect(),
        )
    };
    let spec = BoundarySpec {
        curves: vec![
            line([0.1, 0.1], [0.9, 0.1]),
            line([0.9, 0.1], [0.9, 0.9]),
            line([0.9, 0.9], [0.1, 0.9]),
            line([0.1, 0.9], [0.1, 0.1]),
        ],
    };
    let params = Params {
        tol: 1e-4,
        m: 16,
        n: 8,
        ..Default::default()
    };
    let ap = approximate(&model, &spec, &params).unwrap();
    let r = &ap.report;
    eprintln!("trimmed gap: {:?}", r.rounds);
    assert!(r.fill.filled > 0);
    let h = 0.8 / r.m as f64 / 4.0;
    for i in 0..=r.m {
        let row: String = (0..=r.n)
            .map(|j| if *ap.artificial.at(i, j) { 'A' } else { '.' })
            .collect();
        eprintln!("{:.3} {row}", ap.coons.at(i, 0)[0]);
    }
    for (x, art) in ap.coons.data.iter().zip(&ap.artificial.data) {
        if x[0] > 0.45 + h && x[0] < 0.55 - h {
            assert!(*art, "{x:?} over the trimmed strip must be artificial");
        }
        if x[0] < 0.45 - h || x[0] > 0.55 + h {
            assert!(!*art, "{x:?} over a face must be a hit");
        }
    }
    // Bridged on the paraboloid (vertical distance bounds the distance).
    let dense = dense_max(
        &ap.surface,
        80,
        |p| (p[2] - 0.3 * p[0] * p[1]).abs(),
        |_| true,
    );
    eprintln!("trimmed gap: dense vertical max {dense:.3e}");
    assert!(dense < 1e-4, "{dense}");
}
