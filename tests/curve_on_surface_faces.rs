//! Certified curves along a real part's face boundaries: every edge of every face's outer
//! loop of gmsh-t20_data.step (21 faces; 14 on rational surfaces — cylinders, cones, tori —
//! and planes), as chains of Bézier segments exactly on the face's surface.
//!
//! The certificate claims: the output is within `ε` of the image of the edge's polynomial
//! pcurve, and within `bound_to_edge = ε + δ` of the edge's 3D curve (`δ`: the pcurve's
//! proven distance to the edge). The test measures the second claim itself, by projection
//! both ways: samples of each output segment (evaluated here by de Casteljau on homogeneous
//! points) onto the edge's 3D curve, and samples of the edge onto the output segments; the
//! edge is the file's data (the library's NURBS evaluation of it is the only shared code).

mod common;
use common::curves::{project, segment_point};
use vericad::brep::pcurve::Pcurves;
use vericad::curve_on_surface::Params;
use vericad::curve_on_surface::face::face_curves;

fn read(name: &str) -> vericad::model::Model {
    let p = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/public")
        .join(name);
    vericad::io::read_model(&p).unwrap()
}

/// Every edge use of the loops of `file` (outer loops only when `outer_only`) certified at
/// `ε = 1e-4 ×` the part's size, `ε + δ` within `ε` and the model tolerance, and the distance
/// between output and edge measured within it. Returns (edge uses, rational faces, pieces
/// cut at a seam, largest measured / proven, largest `ε + δ`, the file's uncertainty).
fn check_part(file: &str, outer_only: bool) -> (usize, usize, usize, f64, f64, f64) {
    let m = read(file);
    let b = m.brep.as_ref().unwrap();
    let mut pcs = Pcurves::new(b, &m);
    let eps = 1e-4 * b.extent();
    let params = Params {
        eps_d: eps,
        ..Params::default()
    };
    let (mut rational_faces, mut edges, mut cut, mut worst_ratio) = (0, 0, 0, 0.0f64);
    let mut largest = 0.0f64;
    for fi in 0..b.faces.len() {
        let f = face_curves(b, &m, fi, &params, &mut pcs).unwrap();
        rational_faces += usize::from(f.rational);
        for l in f.loops.iter().filter(|l| l.outer || !outer_only) {
            for e in &l.edges {
                edges += 1;
                assert!(
                    !e.curves.is_empty(),
                    "face {} edge {}: {:?} / {:?}",
                    f.face,
                    e.edge,
                    e.error,
                    e.pcurve_unproven
                );
                cut += usize::from(e.curves.len() > 1);
                for r in &e.curves {
                    assert!(r.certificate.hausdorff_bound <= eps);
                    assert_eq!(r.segments.iter().all(|s| s.weights.is_some()), f.rational);
                }
                let total = e.bound_to_edge.unwrap_or_else(|| {
                    panic!("face {} edge {}: {:?}", f.face, e.edge, e.pcurve_unproven)
                });
                // δ is accepted within the model tolerance (at least 1e-8 of the size).
                let off = b.tolerance.max(1e-8 * b.extent());
                assert!(
                    total <= eps + off,
                    "face {} edge {}: bound {total:e} above ε + the model tolerance",
                    f.face,
                    e.edge,
                );
                largest = largest.max(total);
                // The measurement: output ↔ edge, by projection both ways.
                let ei = b.edges.iter().position(|x| x.source == e.edge).unwrap();
                let arc = &b.edges[ei].curve.as_ref().unwrap().nurbs;
                let (t0, t1) = arc.hom.domain();
                let on_edge = |t: f64| arc.eval(&t);
                let segments: Vec<_> = e.curves.iter().flat_map(|r| &r.segments).collect();
                let mut measured = 0.0f64;
                for s in &segments {
                    let w = s.weights.as_deref();
                    for i in 0..=8 {
                        let x = segment_point(&s.control_points, w, i as f64 / 8.0);
                        measured = measured.max(project(&on_edge, &x, t0, t1, 400));
                    }
                }
                for i in 0..=100 {
                    let x = on_edge(t0 + (t1 - t0) * i as f64 / 100.0);
                    let near = segments
                        .iter()
                        .map(|s| {
                            let w = s.weights.as_deref();
                            project(&|t| segment_point(&s.control_points, w, t), &x, 0.0, 1.0, 8)
                        })
                        .fold(f64::INFINITY, f64::min);
                    measured = measured.max(near);
                }
                // The measurement runs in f64 on coordinates of the part's size: its own
                // rounding (a few ulps of `extent`) is allowed for. Edges off their face by
                // `δ` itself measure `δ` to many digits (abc-0000: 4.401e-11 for 4.401e-11).
                assert!(
                    measured <= total + 1e-13 * b.extent(),
                    "face {} edge {}: measured {measured:e} > proven {total:e}",
                    f.face,
                    e.edge
                );
                worst_ratio = worst_ratio.max(measured / total);
            }
        }
    }
    (
        edges,
        rational_faces,
        cut,
        worst_ratio,
        largest,
        b.tolerance,
    )
}

#[test]
fn t20_every_outer_loop_certified_and_measured() {
    let (edges, rational, cut, ratio, largest, tol) = check_part("gmsh-t20_data.step", true);
    eprintln!(
        "t20: {edges} outer-loop edge uses, {rational} rational faces, {cut} cut at a seam; largest measured/proven {ratio:.3}, largest bound {largest:.2e}"
    );
    assert_eq!((edges, rational), (94, 14));
    // The file's uncertainty (0.074 mm) covers every certified curve.
    assert!(largest <= tol, "{largest:e} > {tol:e}");
}

/// abc-0000.step: every loop, with the closed edges whose projection crosses the surface's
/// seam (full circles on cylinders and tori) cut there into two curves.
#[test]
fn abc0000_every_loop_certified_and_measured() {
    let (edges, rational, cut, ratio, largest, _) = check_part("abc-0000.step", false);
    eprintln!(
        "abc-0000: {edges} edge uses, {rational} rational faces, {cut} cut at a seam; largest measured/proven {ratio:.3}, largest bound {largest:.2e}"
    );
    assert_eq!(edges, 66);
    assert!(cut >= 7, "the seam-crossing circles are cut: {cut}");
}

/// The command line: every face of t20, the report as JSON (exit 0: all certified), the
/// curves as IGES read back with their weights; a face that does not exist is bad input.
#[test]
fn t20_faces_from_the_command_line() {
    let file = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/public/gmsh-t20_data.step");
    let d = std::env::temp_dir().join(format!("vericad-cos-faces-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    let igs = d.join("t20-curves.igs");
    let run = |face: &str, extra: &[&str]| {
        let o = std::process::Command::new(env!("CARGO_BIN_EXE_vericad"))
            .args([
                "curve-on-surface",
                "--surface",
                file.to_str().unwrap(),
                "--face",
                face,
            ])
            .args(extra)
            .output()
            .unwrap();
        (
            o.status.code(),
            String::from_utf8_lossy(&o.stdout).to_string(),
            String::from_utf8_lossy(&o.stderr).to_string(),
        )
    };
    let (code, out, err) = run(
        "all",
        &["--tol", "5e-3", "--json", "--iges", igs.to_str().unwrap()],
    );
    assert_eq!(code, Some(0), "{err}");
    let r: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(r["faces"].as_array().unwrap().len(), 21);
    assert_eq!(
        (r["certified"].as_u64(), r["edges"].as_u64()),
        (Some(96), Some(96))
    );
    let back = vericad::io::read_model(&igs).unwrap();
    assert_eq!(back.curves.len(), 96);
    let rational = back
        .curves
        .iter()
        .filter(|c| match &c.geometry {
            vericad::model::CurveGeometry::Space(n) => {
                n.points_weights().1.iter().any(|w| *w != 1.0)
            }
            _ => false,
        })
        .count();
    assert!(
        rational > 0,
        "the curves on rational faces keep their weights"
    );
    let (code, _, err) = run("#999999", &[]);
    assert_eq!(code, Some(2), "{err}");
    assert!(err.contains("no face with source id"), "{err}");
    std::fs::remove_dir_all(&d).ok();
}
