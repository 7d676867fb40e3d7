//! Real data for the Coons-patch approximation: four patches of the fuselage (Open
//! CASCADE's bug28366), the same across its C0 crease, and `vericad coons` end to end.

mod common;
use common::cli::vericad;

use common::coons::{fuselage, fuselage_top, joined, polyline};
use vericad::approx::coons::boundary::BoundarySpec;
use vericad::approx::coons::{Params, approximate};
use vericad::geom::{Point, norm};

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
