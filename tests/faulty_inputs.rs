//! Faulty CAD files, one per defect class (`tests/data/faulty/README.md`): each gives a typed
//! error that names the entity, a warning that says what was not kept, or a correct reading —
//! never a panic, a hang, an unbounded allocation or silent loss.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};
use vericad::io::{ReadError, read_model};
use vericad::model::Model;

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/faulty")
        .join(name)
}

fn read(name: &str) -> Result<Model, ReadError> {
    read_model(&data(name))
}

/// The error of reading `name`, as text; panics (test failure) when it reads.
fn refused(name: &str) -> String {
    match read(name) {
        Ok(m) => panic!(
            "{name} was accepted: {} surfaces, {} curves, warnings {:?}",
            m.surfaces.len(),
            m.curves.len(),
            m.warnings
        ),
        Err(e) => e.to_string(),
    }
}

fn accepted(name: &str) -> Model {
    match read(name) {
        Ok(m) => m,
        Err(e) => panic!("{name} was refused: {e}"),
    }
}

fn assert_has(text: &str, parts: &[&str]) {
    for p in parts {
        assert!(text.contains(p), "expected {p:?} in: {text}");
    }
}

/// Runs `f` on another thread; `None` when it does not finish within `limit` (a hang).
fn within<T: Send + 'static>(limit: Duration, f: impl FnOnce() -> T + Send + 'static) -> Option<T> {
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        let _ = tx.send(f());
    });
    rx.recv_timeout(limit).ok()
}

/// The command-line tool, killed after `limit`: `(exit code, stdout, stderr)`, `None` on
/// timeout.
fn vericad(args: &[&str], limit: Duration) -> Option<(i32, String, String)> {
    let mut child = Command::new(env!("CARGO_BIN_EXE_vericad"))
        .args(args)
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let start = Instant::now();
    loop {
        if child.try_wait().unwrap().is_some() {
            let o = child.wait_with_output().unwrap();
            return Some((
                o.status.code().unwrap_or(-1),
                String::from_utf8_lossy(&o.stdout).into(),
                String::from_utf8_lossy(&o.stderr).into(),
            ));
        }
        if start.elapsed() > limit {
            let _ = child.kill();
            let _ = child.wait();
            return None;
        }
        std::thread::sleep(Duration::from_millis(20));
    }
}

fn tmp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("vericad-faulty-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

const MINUTE: Duration = Duration::from_secs(60);

#[test]
fn hollerith_counts_past_the_end_are_typed_errors() {
    let g = refused("hollerith-huge-G.igs");
    assert_has(
        &g,
        &["global section", "Hollerith count 18446744073709551615"],
    );
    let p = refused("hollerith-huge-P.igs");
    assert_has(&p, &["DE 1", "Hollerith count 18446744073709551615"]);
}

#[test]
fn reader_fuzz_artifacts_give_models_or_errors() {
    let dir = data("fuzz-artifacts/readers");
    for e in std::fs::read_dir(dir).unwrap() {
        let path = e.unwrap().path();
        let bytes = std::fs::read(&path).unwrap();
        let name = path.display().to_string();
        let done = within(MINUTE, move || {
            std::panic::catch_unwind(|| vericad::fuzz_entry::readers(&bytes)).is_ok()
        });
        assert_eq!(done, Some(true), "{name}: panicked or hung");
    }
}

#[test]
fn non_finite_geometry_is_refused_with_the_entity() {
    for (file, parts) in [
        ("weight-overflow.igs", &["DE 1", "w·p", "overflows"][..]),
        ("rational-overflow.step", &["#1", "w·p", "overflows"]),
        ("j-wover.json", &["surfaces[0]", "w·p", "overflows"]),
        (
            "knot-1e308.step",
            &["#1", "knot span", "wider than the f64 range"],
        ),
        ("j-knot.json", &["surfaces[0].knots_u", "knot span"]),
        (
            "transform-overflow.igs",
            &["DE 1", "transformation matrix DE 3"],
        ),
        ("rev-huge-axis.igs", &["DE 3", "overflow"]),
        (
            "rev-angle-nan-ish.igs",
            &["DE 1", "arc angles", "full turn"],
        ),
        ("huge-1e308.step", &["#1", "differences overflow"]),
    ] {
        let e = refused(file);
        assert_has(&e, parts);
    }
}

#[test]
fn every_accepted_model_is_finite() {
    for e in std::fs::read_dir(data("")).unwrap() {
        let path = e.unwrap().path();
        if path.is_dir() || path.extension().is_some_and(|x| x == "md") {
            continue;
        }
        if let Ok(m) = read_model(&path) {
            assert_eq!(m.validate(), Ok(()), "{}", path.display());
        }
    }
}

#[test]
fn huge_finite_coordinates_read_but_intersection_refuses_them() {
    let m = accepted("huge-1e300.step");
    let e = m.check_coordinate_range().unwrap_err();
    assert_has(&e.to_string(), &["surface 0", "#1", "supported range"]);
    assert!(accepted("plane-z0.step").check_coordinate_range().is_ok());
    let a = data("huge-1e300.step");
    let b = data("plane-z0.step");
    let (code, _, err) =
        vericad(&["ssi", a.to_str().unwrap(), b.to_str().unwrap()], MINUTE).expect("ssi returns");
    assert_eq!(code, 2, "{err}");
    assert_has(&err, &["huge-1e300.step", "supported range"]);
}

#[test]
fn domain_curve_touching_the_domain_edge_from_outside_is_out_of_domain_at_once() {
    let s = accepted("yang.json").surfaces[0].nurbs.clone();
    let c = match &accepted("cos-hang.json").curves[0].geometry {
        vericad::model::CurveGeometry::Domain(d) => d.clone(),
        _ => panic!("not a domain curve"),
    };
    let r = within(MINUTE, move || {
        vericad::curve_on_surface::approximate(&s, &c, &Default::default())
    })
    .expect("curve on surface returns");
    assert!(
        matches!(
            r,
            Err(vericad::curve_on_surface::CosError::OutOfDomain { .. })
        ),
        "{r:?}"
    );
}

#[test]
fn curve_on_surface_fuzz_artifacts_return() {
    for e in std::fs::read_dir(data("fuzz-artifacts/curve_on_surface")).unwrap() {
        let path = e.unwrap().path();
        let bytes = std::fs::read(&path).unwrap();
        let name = path.display().to_string();
        let done = within(MINUTE, move || {
            std::panic::catch_unwind(|| vericad::fuzz_entry::curve_on_surface(&bytes)).is_ok()
        });
        assert_eq!(done, Some(true), "{name}: panicked or hung");
    }
}

/// The domain curve with control points (0.25, 0.75), (−0.25, −0.25), (0.25, 0.75) runs along
/// a straight line and back: zero speed at t = 1/2 (a cusp, on the edge u = 0) and a reversal
/// where the closed curve joins itself. Neither corner can be removed by splitting; each side
/// of each corner is split at most `MAX_SPLIT_DEPTH` times, not thousands of times.
#[test]
fn a_curve_doubling_back_leaves_two_corners_after_bounded_splitting() {
    use vericad::curve_on_surface::g1::MAX_SPLIT_DEPTH;
    let s = accepted("yang.json").surfaces[0].nurbs.clone();
    let c = match &accepted("cusp-closed.json").curves[0].geometry {
        vericad::model::CurveGeometry::Domain(d) => d.clone(),
        _ => panic!("not a domain curve"),
    };
    let prm = vericad::curve_on_surface::Params {
        eps_d: 1e-2,
        ..Default::default()
    };
    let r = within(MINUTE, move || {
        vericad::curve_on_surface::approximate(&s, &c, &prm)
    })
    .expect("curve on surface returns")
    .expect("a result");
    assert_eq!(r.certificate.unresolved_junctions, 2);
    assert!(
        r.steps.g1.splits <= 2 * 2 * MAX_SPLIT_DEPTH as usize,
        "{} splits",
        r.steps.g1.splits
    );
    assert!(r.certificate.hausdorff_bound <= 1e-2);
}

#[test]
fn nested_composite_curves_exhaust_a_budget() {
    let e = refused("composite-fanout-1e6.igs");
    assert_has(&e, &["DE ", "expansion budget"]);
    // 1e12 segments: must fail fast, not grow without bound (run as a process to kill it).
    let f = data("composite-fanout-1e12.igs");
    let (code, _, err) = vericad(&["info", f.to_str().unwrap()], MINUTE).expect("info returns");
    assert_eq!(code, 2, "{err}");
    assert_has(&err, &["expansion budget"]);
}

#[test]
fn binary_stl_with_a_solid_header_is_read_as_binary_or_refused() {
    let m = accepted("bunny-solidhdr-trailing.stl");
    assert_eq!(m.triangulations[0].triangles.len(), 4968);
    assert!(
        m.warnings
            .iter()
            .any(|w| w.contains("1 byte(s) of padding")),
        "{:?}",
        m.warnings
    );
    let e = refused("claims-10GB-solidhdr.stl");
    assert_has(&e, &["claims 200000000 triangles", "134 bytes"]);
}

#[test]
fn truncated_ascii_stl_is_not_silently_shorter() {
    let e = refused("trunc33-gmsh-surface1.stl");
    assert_has(&e, &["truncated", "26 complete triangles"]);
    let m = accepted("ascii-no-endsolid.stl");
    assert_eq!(m.triangulations[0].triangles.len(), 2);
    assert!(
        m.warnings
            .iter()
            .any(|w| w.contains("endsolid") && w.contains("2 complete triangles")),
        "{:?}",
        m.warnings
    );
}

#[test]
fn duplicate_step_ids_are_refused() {
    assert_has(&refused("dup-id.step"), &["#100 is defined twice"]);
    assert_has(&refused("dup-id-surface.step"), &["#1 is defined twice"]);
}

#[test]
fn skipped_entities_are_named_in_the_warnings() {
    let m = accepted("curve-invalid-dropped.step");
    assert_eq!(m.curves.len(), 1);
    let w = m.warnings.join("\n");
    assert_has(&w, &["#203", "#204"]);

    // The rectangular trimmed surface is converted; the offset surface is named.
    let m = accepted("bare-rts-offset.step");
    let w = m.warnings.join("\n");
    assert_has(&w, &["OFFSET_SURFACE", "#17"]);
    assert!(!w.contains("#15"), "{w}");
    assert_eq!(m.surfaces.len(), 1);
    assert_eq!(m.surfaces[0].source.as_deref(), Some("#15"));

    // A 510 face whose loop (DE 5) is one line from a vertex to another: the B-rep is read and
    // the open loop named with its face.
    let m = accepted("brep-510-face.igs");
    let w = m.warnings.join("\n");
    assert_has(&w, &["face DE 1", "DE 5", "loop is open"]);

    assert_has(&refused("degfrac.step"), &["#1", "1.7", "not an integer"]);
}

#[test]
fn degenerate_analytic_data_is_refused_or_reported() {
    assert_has(&refused("sphere-r0.step"), &["#14", "sphere radius"]);
    assert_has(
        &refused("transform-singular.igs"),
        &["DE 1", "DE 3", "singular"],
    );
    let m = accepted("collapsed-point.step");
    assert!(
        m.warnings
            .iter()
            .any(|w| w.contains("#1") && w.contains("single point")),
        "{:?}",
        m.warnings
    );
}

#[test]
fn convert_reports_what_the_output_cannot_hold() {
    let d = tmp("convert");
    let out = d.join("curves.step");
    let (code, _, err) = vericad(
        &[
            "convert",
            data("curve2d.json").to_str().unwrap(),
            out.to_str().unwrap(),
        ],
        MINUTE,
    )
    .unwrap();
    assert_eq!(code, 0, "{err}");
    assert_has(&err, &["1 domain curve(s)", "c2d", "patch set"]);
}

#[test]
fn binary_stl_beyond_f32_is_refused_and_the_previous_output_kept() {
    let d = tmp("stl-binary");
    let out = d.join("t.stl");
    std::fs::write(&out, b"previous good output").unwrap();
    let (code, _, err) = vericad(
        &[
            "convert",
            "--format",
            "stl-binary",
            data("ascii-1e308-tri.stl").to_str().unwrap(),
            out.to_str().unwrap(),
        ],
        MINUTE,
    )
    .unwrap();
    assert_eq!(code, 2, "{err}");
    assert_has(&err, &["f32 range"]);
    assert_eq!(std::fs::read(&out).unwrap(), b"previous good output");
}

#[test]
fn outputs_are_replaced_atomically() {
    let d = tmp("atomic");
    let out = d.join("m.json");
    std::fs::write(&out, "old").unwrap();
    vericad::io::write_atomic(&out, "new").unwrap();
    assert_eq!(std::fs::read_to_string(&out).unwrap(), "new");
    let left: Vec<_> = std::fs::read_dir(&d).unwrap().collect();
    assert_eq!(left.len(), 1, "temporary files left behind");
    // A write that cannot happen leaves the old file as it was.
    let dir_as_file = d.join("m.json").join("x");
    assert!(vericad::io::write_atomic(&dir_as_file, "x").is_err());
    assert_eq!(std::fs::read_to_string(&out).unwrap(), "new");
}

#[test]
fn step_writer_keeps_conversion_based_units() {
    for unit in ["mile", "mil", "inch", "foot"] {
        let mut m = accepted("ok-bilinear.step");
        m.unit = Some(unit.into());
        let d = tmp("units");
        let out = d.join(format!("{unit}.step"));
        let w = vericad::io::write_model(&out, &m).unwrap();
        assert!(w.iter().all(|x| !x.contains("unit")), "{w:?}");
        assert_eq!(read_model(&out).unwrap().unit.as_deref(), Some(unit));
    }
}

fn repaired(name: &str) -> vericad::repair::RepairReport {
    let patches = accepted(name)
        .surfaces
        .into_iter()
        .map(|s| s.nurbs)
        .collect();
    vericad::repair::repair(
        patches,
        &Default::default(),
        &Default::default(),
        &|_: &str| {},
    )
    .unwrap()
    .report
}

#[test]
fn repair_finds_the_same_feature_edge_at_any_scale() {
    let small = repaired("two-patches-1.json");
    let huge = repaired("two-patches-1e80.json");
    assert_eq!(small.feature_edges, 1);
    assert_eq!(huge.edges_connected, small.edges_connected);
    assert_eq!(huge.feature_edges, small.feature_edges);
    assert_eq!(huge.patches_out, small.patches_out);
    assert!(huge.gaps_left.is_empty());
}

#[test]
fn t_junction_splitting_is_bounded() {
    let r = repaired("soup-model.json");
    // 2 input patches, at most 4 splits each.
    assert!(r.t_junctions <= 8, "{} splits", r.t_junctions);
    assert!(r.patches_out <= 10, "{} patches out", r.patches_out);
    assert!(
        r.not_done.iter().any(|n| n.contains("split budget")),
        "{:?}",
        r.not_done
    );
}

#[test]
fn feature_overrides_naming_no_edge_are_refused() {
    let patches: Vec<_> = accepted("two-patches-1.json")
        .surfaces
        .into_iter()
        .map(|s| s.nurbs)
        .collect();
    for bad in [(7, 0), (0, 4)] {
        let ov = vericad::repair::features::FeatureOverrides {
            add: vec![bad],
            remove: vec![],
        };
        let r = vericad::repair::repair(patches.clone(), &Default::default(), &ov, &|_: &str| {});
        let e = r.err().expect("refused").to_string();
        assert_has(
            &e,
            &["feature override", &format!("[{}, {}]", bad.0, bad.1)],
        );
    }
}

#[test]
fn absurd_thread_counts_are_bad_input() {
    let f = data("plane-z0.step");
    let (code, _, err) =
        vericad(&["ssi", f.to_str().unwrap(), "--threads", "100000"], MINUTE).expect("ssi returns");
    assert_eq!(code, 2, "{err}");
    assert_has(&err, &["--threads"]);
}

/// The normal of a surface with coordinates near 1e300: S_u = (2e300, 0, 2e300) and
/// S_v = (0, 2e300, 0) at the centre, so the unit normal is (−1, 0, 1)/√2 — not NaN from
/// an overflowing cross product.
#[test]
fn eval_normal_of_huge_coordinates_is_finite() {
    let m = accepted("huge-1e300.step");
    let r = vericad::model::eval::eval_surface(&m, 0, &[0.5, 0.5]).unwrap();
    let n = r.normal.expect("a normal");
    let h = std::f64::consts::FRAC_1_SQRT_2;
    for (x, y) in n.iter().zip([-h, 0.0, h]) {
        assert!((x - y).abs() < 1e-15, "{n:?}");
    }
    assert!(r.f64_error.is_finite());
}

/// Models built in code bypass the readers' checks; the intersection re-checks them and
/// refuses a non-finite control point or one beyond the coordinate range with a typed error
/// naming the surface, instead of panicking in an exact lift.
#[test]
fn ssi_refuses_models_built_in_code_with_non_finite_or_huge_points() {
    use vericad::ssi::{SsiError, SsiParams, intersect_models, intersect_pair_canonical};
    let good = accepted("plane-z0.step");
    for (bad, want) in [(f64::NAN, "not finite"), (1e200, "supported range")] {
        let mut m = good.clone();
        m.surfaces[0].nurbs.hom.net[1].wp[2] = bad;
        let r = intersect_models(&good, Some(&m), &SsiParams::default(), &|_, _| {});
        match r {
            Err(SsiError::Input(e)) => assert_has(&e, &["surface 0"]),
            other => panic!("{bad}: {:?}", other.map(|r| r.summary.branches)),
        }
        let r = intersect_pair_canonical(
            &good.surfaces[0].nurbs,
            &m.surfaces[0].nurbs,
            (0, 1),
            &SsiParams::default(),
            None,
        );
        match r {
            Err(SsiError::Input(e)) => assert_has(&e, &["surface 1", want]),
            other => panic!("{bad}: {:?}", other.map(|r| r.branches.len())),
        }
    }
}

/// abc-0000.step has 10 faces whose orientation is reversed (`same_sense = .F.`). With its
/// B-rep, the STEP writer keeps each face's `same_sense` (read back: the same 10 faces) and
/// the IGES writer the orientation flags of its shells (514); without the B-rep the writers
/// store surfaces, not faces, and say so for each of them.
#[test]
fn writers_report_the_face_orientation_they_cannot_hold() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/public/abc-0000.step");
    let m = read_model(&src).unwrap();
    assert_eq!(m.surfaces.iter().filter(|s| s.reversed).count(), 10);
    let d = tmp("orientation");
    for ext in ["step", "igs"] {
        let w = vericad::io::write_model(&d.join(format!("abc.{ext}")), &m).unwrap();
        assert!(w.iter().all(|x| !x.contains("reversed")), "{ext}: {w:?}");
    }
    let back = read_model(&d.join("abc.step")).unwrap();
    assert_eq!(back.surfaces.iter().filter(|s| s.reversed).count(), 10);
    let surfaces_only = vericad::model::Model {
        brep: None,
        ..m.clone()
    };
    for ext in ["step", "igs"] {
        let w = vericad::io::write_model(&d.join(format!("abc-surfaces.{ext}")), &surfaces_only)
            .unwrap();
        assert!(
            w.iter()
                .any(|x| x.contains("10 reversed face(s)") && x.contains("orientation")),
            "{ext}: {w:?}"
        );
    }
    // JSON keeps it.
    let out = d.join("abc.json");
    let w = vericad::io::write_model(&out, &m).unwrap();
    assert!(w.iter().all(|x| !x.contains("reversed")), "{w:?}");
    let back = read_model(&out).unwrap();
    assert_eq!(back.surfaces.iter().filter(|s| s.reversed).count(), 10);
}

/// IGES keeps units without a flag of their own by name (Global parameter 15, flag 3).
#[test]
fn iges_writer_keeps_units() {
    for unit in ["mile", "mil", "inch", "foot", "m", "mm"] {
        let mut m = accepted("ok-bilinear.step");
        m.unit = Some(unit.into());
        let out = tmp("iges-units").join(format!("{unit}.igs"));
        let w = vericad::io::write_model(&out, &m).unwrap();
        assert!(w.iter().all(|x| !x.contains("unit")), "{w:?}");
        assert_eq!(
            read_model(&out).unwrap().unit.as_deref(),
            Some(unit),
            "{unit}"
        );
    }
}

/// A foreign polyline without points is refused (exit 2) naming the curve, not certified
/// vacuously as "within tol".
#[test]
fn certify_ssi_refuses_an_empty_polyline() {
    let d = tmp("empty-polyline");
    let curves = d.join("curves.json");
    std::fs::write(&curves, "[[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]], []]").unwrap();
    let (code, out, err) = vericad(
        &[
            "certify-ssi",
            data("plane-z0.step").to_str().unwrap(),
            data("ok-bilinear.step").to_str().unwrap(),
            "--curves",
            curves.to_str().unwrap(),
        ],
        MINUTE,
    )
    .expect("certify-ssi returns");
    assert_eq!(code, 2, "{out}{err}");
    assert_has(&err, &["curve 1", "no points"]);
}
