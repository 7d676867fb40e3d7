//! `certify-ssi` on trimmed faces: a foreign curve is within tol only where the true
//! intersection point near it lies inside both faces' trim loops. The truth comes from the
//! construction (a line where two planes meet, a circle where a plane meets a sphere, the
//! trims as parameter rectangles), not from vericad's output.

mod common;
use vericad::model::{Model, Surface, TrimLoop};
use vericad::spline::construct::{Frame, bilinear, sphere};
use vericad::spline::{NurbsCurve, NurbsSurface};
use vericad::ssi::SsiParams;
use vericad::ssi::foreign::{CertifyReport, ForeignInput, PointStatus, certify};

const TOL: f64 = 1e-6;

fn line(a: [f64; 2], b: [f64; 2]) -> NurbsCurve<f64, 2> {
    NurbsCurve::new(vec![0.0, 0.0, 1.0, 1.0], 1, vec![a, b], vec![1.0, 1.0]).unwrap()
}

fn rect(outer: bool, u0: f64, u1: f64, v0: f64, v1: f64) -> TrimLoop {
    TrimLoop {
        outer,
        curves: vec![
            line([u0, v0], [u1, v0]),
            line([u1, v0], [u1, v1]),
            line([u1, v1], [u0, v1]),
            line([u0, v1], [u0, v0]),
        ],
    }
}

fn one(name: &str, s: NurbsSurface<f64, 3>, trims: Vec<TrimLoop>) -> Model {
    let mut f = Surface::new(name, s);
    f.trim_loops = trims;
    Model {
        surfaces: vec![f],
        ..Default::default()
    }
}

fn run(a: &Model, b: &Model, curves: &[Vec<[f64; 3]>]) -> CertifyReport {
    let prm = SsiParams {
        tol: TOL,
        ..Default::default()
    };
    let r = vericad::ssi::intersect_models(a, Some(b), &prm, &|_, _| {}).unwrap();
    let foreign: Vec<ForeignInput> = curves
        .iter()
        .enumerate()
        .map(|(i, c)| (format!("c{i}"), "polyline", c.clone()))
        .collect();
    certify(a, Some(b), &foreign, &r, TOL, 100.0 * TOL, &|_, _| {})
}

/// A rotated frame (about (2, −1, 2)/3 by 0.9 rad) at `o`.
fn frame(o: [f64; 3]) -> Frame {
    let (c, s) = (0.45f64.cos(), 0.45f64.sin());
    common::shapes::frame_of([c, 2.0 / 3.0 * s, -1.0 / 3.0 * s, 2.0 / 3.0 * s], o)
}

/// Points `f.at(x, 0, 0)` for `x` from `x0` to `x1`.
fn segment(f: &Frame, x0: f64, x1: f64, n: usize) -> Vec<[f64; 3]> {
    (0..=n)
        .map(|k| f.at(x0 + (x1 - x0) * k as f64 / n as f64, 0.0, 0.0))
        .collect()
}

/// The plane `z = 0` of the frame over `[−1, 1]²`, trimmed to `u ≤ 0.5` (`x ≤ 0`), against
/// the untrimmed plane `y = 0` over `x, z ∈ [−1, 1]`: the faces meet along `x ∈ [−1, 0]` of
/// the frame's x axis; the surfaces along `x ∈ [−1, 1]`.
#[test]
fn line_beyond_a_trim_is_outside_the_faces() {
    let f = frame([0.3, -0.2, 0.5]);
    let a = one(
        "half plane",
        bilinear(
            f.at(-1.0, -1.0, 0.0),
            f.at(1.0, -1.0, 0.0),
            f.at(-1.0, 1.0, 0.0),
            f.at(1.0, 1.0, 0.0),
        )
        .unwrap(),
        vec![rect(true, 0.0, 0.5, 0.0, 1.0)],
    );
    let b = one(
        "wall",
        bilinear(
            f.at(-1.0, 0.0, -1.0),
            f.at(1.0, 0.0, -1.0),
            f.at(-1.0, 0.0, 1.0),
            f.at(1.0, 0.0, 1.0),
        )
        .unwrap(),
        vec![],
    );
    let inside = segment(&f, -1.0, -5e-5, 40);
    let outside = segment(&f, 0.1, 0.9, 16);
    let across = segment(&f, -0.9, 0.9, 18);

    // The faces' line, up to 5e-5 of the trim (within the match distance 1e-4): within tol,
    // nothing missing, certified: vericad's coverage decides the pairs the trim runs through
    // with the trim edge's crossing with the wall found near its output, and the border
    // crossings beyond the trim left out as outside the faces.
    let r = run(&a, &b, std::slice::from_ref(&inside));
    assert_eq!(r.curves[0].status, "within_tol", "{r}");
    assert_eq!(r.curves[0].points_on_curve, inside.len());
    assert_eq!(r.missing_branches + r.partial_branches, 0, "{r}");
    assert!(r.certified, "{r}");

    // On both surfaces, beyond the trim: every point outside the faces, none accepted, and
    // vericad's branch (on x ≤ 0) missing.
    let r = run(&a, &b, std::slice::from_ref(&outside));
    let c = &r.curves[0];
    assert_eq!(c.status, "outside_faces", "{r}");
    assert_eq!(c.points_outside_faces, outside.len(), "{r}");
    assert_eq!(c.points_on_curve, 0);
    assert!(
        c.issues
            .iter()
            .all(|i| i.status == PointStatus::OutsideFaces && i.reason == "outside_faces")
    );
    assert_eq!(r.missing_branches, 1, "{r}");
    assert!(!r.certified);

    // Across the trim: the points with x < 0 accepted, those with x > 0 outside, the one at
    // x = 0 (on the trim's edge) neither.
    let r = run(&a, &b, std::slice::from_ref(&across));
    let c = &r.curves[0];
    assert_eq!(c.points_on_curve, 9, "{r}");
    assert_eq!(c.points_outside_faces, 9, "{r}");
    assert_eq!(c.points_uncertified, 1, "{r}");
    assert!(!r.certified);
    assert!(r.notes.iter().any(|n| n.contains("trimmed faces (1)")));
}

/// A sphere of radius 2 cut by the plane `z = 0.7` of a rotated frame, the plane face with a
/// hole `u ∈ [0.45, 0.55]` (`|x| < 0.3`): the circle of radius `√3.51` loses its two stretches
/// over the hole. The whole circle is not within tol of the faces (its points over the hole
/// are outside them); the two arcs outside the hole are.
#[test]
fn circle_over_a_hole_is_outside_the_faces() {
    let f = frame([-0.4, 0.1, 0.2]);
    let h = 0.7;
    let a = one("sphere", sphere(&f, 2.0).unwrap(), vec![]);
    let b = one(
        "plane with a hole",
        bilinear(
            f.at(-3.0, -3.0, h),
            f.at(3.0, -3.0, h),
            f.at(-3.0, 3.0, h),
            f.at(3.0, 3.0, h),
        )
        .unwrap(),
        vec![
            rect(true, 0.0, 1.0, 0.0, 1.0),
            rect(false, 0.45, 0.55, 0.05, 0.95),
        ],
    );
    let rho = (4.0 - h * h).sqrt();
    let at = |phi: f64| f.at(rho * phi.cos(), rho * phi.sin(), h);
    let n = 360;
    let circle: Vec<[f64; 3]> = (0..=n)
        .map(|k| at(std::f64::consts::TAU * k as f64 / n as f64 + 0.001))
        .collect();
    // Over the hole: |ρ cos φ| < 0.3.
    let over_hole = circle
        .iter()
        .filter(|p| {
            let d: [f64; 3] = std::array::from_fn(|i| p[i] - f.o[i]);
            let x = d[0] * f.x[0] + d[1] * f.x[1] + d[2] * f.x[2];
            x.abs() < 0.3 - 1e-3
        })
        .count();
    assert!(over_hole > 20);
    let r = run(&a, &b, std::slice::from_ref(&circle));
    let c = &r.curves[0];
    assert_eq!(c.status, "outside_faces", "{r}");
    assert!(c.points_outside_faces >= over_hole, "{r}");
    assert!(
        c.points_outside_faces + c.points_uncertified <= over_hole + 4,
        "{r}"
    );
    assert!(!r.certified);

    // The two arcs outside the hole (|x| ≥ 0.3 + 1e-9 ⟺ |cos φ| ≥ (0.3 + 1e-9)/ρ), each ending
    // 1e-5 of arc short of the trim's edge: within tol; vericad's two arcs found; certified:
    // the pairs of pieces the hole's edge runs through are decided with the edge's crossings
    // with the other surface found near the output, and the circle's border crossings over
    // the hole left out as outside the face.
    let c0 = ((0.3 + 1e-9) / rho).acos() - 1e-5 / rho;
    let arc = |from: f64, to: f64| -> Vec<[f64; 3]> {
        (0..=200)
            .map(|k| at(from + (to - from) * k as f64 / 200.0))
            .collect()
    };
    let arcs = [
        arc(-c0, c0),
        arc(std::f64::consts::PI - c0, std::f64::consts::PI + c0),
    ];
    let r = run(&a, &b, &arcs);
    for c in &r.curves {
        assert_eq!(c.status, "within_tol", "{r}");
    }
    assert_eq!(r.missing_branches + r.partial_branches, 0, "{r}");
    assert!(r.certified, "{r}");
}

/// One-file mode on a real B-rep (abc-0000.step: planes, cylinders, tori, spheres, trimmed):
/// points sampled on the 3D curves of edges two faces share, where those faces meet by
/// construction of the solid. Their true intersection point lies on both faces' trim
/// boundaries, so none is `on_curve` or `outside_faces`, none is proven `off`: all 84 points
/// of 12 edges are `shared_edge` (within tol of both nearest faces, on a trim polygon's edge).
/// With every box taken as inside the faces (the trims not decided), points are accepted
/// `on_curve` from the untrimmed surfaces and the test fails.
#[test]
fn shared_edges_of_a_trimmed_solid_are_not_certified_curves() {
    use vericad::brep::LoopKind;
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/public/abc-0000.step");
    let m = vericad::io::read_model(&path).unwrap();
    let brep = m.brep.as_ref().unwrap();
    let mut uses = vec![std::collections::BTreeSet::new(); brep.edges.len()];
    for f in &brep.faces {
        for l in &f.loops {
            if let LoopKind::Edges(es) = &l.kind {
                for o in es {
                    uses[o.edge].insert(f.surface);
                }
            }
        }
    }
    let curves: Vec<Vec<[f64; 3]>> = brep
        .edges
        .iter()
        .zip(&uses)
        .filter(|(e, u)| u.len() == 2 && e.curve.is_some())
        .take(12)
        .map(|(e, _)| {
            let c = &e.curve.as_ref().unwrap().nurbs;
            let (t0, t1) = c.hom.domain();
            (1..8)
                .map(|k| c.eval(&(t0 + (t1 - t0) * k as f64 / 8.0)))
                .collect()
        })
        .collect();
    assert!(curves.len() >= 8, "{} shared edges", curves.len());
    let prm = SsiParams {
        tol: TOL,
        ..Default::default()
    };
    let r = vericad::ssi::intersect_models(&m, None, &prm, &|_, _| {}).unwrap();
    let foreign: Vec<ForeignInput> = curves
        .iter()
        .enumerate()
        .map(|(i, c)| (format!("edge {i}"), "polyline", c.clone()))
        .collect();
    let rep = certify(&m, None, &foreign, &r, TOL, 100.0 * TOL, &|_, _| {});
    let (mut shared, mut total) = (0, 0);
    for c in &rep.curves {
        assert_eq!(c.points_on_curve, 0, "{rep}");
        assert_eq!(c.points_off, 0, "{rep}");
        assert_eq!(c.points_outside_faces, 0, "{rep}");
        shared += c.points_shared_edge;
        total += c.points_checked;
    }
    assert_eq!(shared, total, "{rep}");
    assert!(!rep.certified);
}
