//! The command-line tool end to end: exit codes distinguish bad input (2) from failure (1).

mod common;
use common::cli::vericad;

/// Two bilinear planes over [−1, 1]² as model files in `d`: z = 0, and the plane tilted about
/// the x axis (z from −0.5 to 0.5); they meet along the x axis.
fn two_planes(d: &std::path::Path) -> (std::path::PathBuf, std::path::PathBuf) {
    let plane = |z0: f64, z1: f64| {
        format!(
            r#"{{"format": "vericad-model", "version": 1, "surfaces": [{{"degree_u": 1, "degree_v": 1,
            "knots_u": [0, 0, 1, 1], "knots_v": [0, 0, 1, 1],
            "control_points": [[[-1, -1, {z0}], [-1, 1, {z1}]], [[1, -1, {z0}], [1, 1, {z1}]]]}}]}}"#
        )
    };
    let (a, b) = (d.join("a.json"), d.join("b.json"));
    std::fs::write(&a, plane(0.0, 0.0)).unwrap();
    std::fs::write(&b, plane(-0.5, 0.5)).unwrap();
    (a, b)
}

/// The children of the SVG group `<g id="ID" ...>`, one per line as the pictures write them.
fn svg_group<'a>(text: &'a str, id: &str) -> Vec<&'a str> {
    let head = format!("<g id=\"{id}\"");
    text.lines()
        .skip_while(|l| !l.starts_with(&head))
        .skip(1)
        .take_while(|l| !l.starts_with("</g>"))
        .collect()
}

fn tmp(name: &str) -> std::path::PathBuf {
    let d = std::env::temp_dir().join(format!("vericad-cli-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

#[test]
fn demo_runs_and_writes_its_outputs() {
    let out = tmp("demo");
    let (code, stdout, _) = vericad(&["demo", "--out", out.to_str().unwrap()]);
    assert_eq!(code, 0);
    assert!(
        stdout.contains("degree 8 with 9 control points"),
        "{stdout}"
    );
    assert!(stdout.contains("50/50"), "{stdout}");
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("demo-report.json")).unwrap())
            .unwrap();
    assert_eq!(report["composition"]["exact_agreements"], 50);
    // The written curve is a valid model that vericad reads back.
    let (code, stdout, _) = vericad(&[
        "info",
        out.join("demo-exact-curve.json").to_str().unwrap(),
        "--json",
    ]);
    assert_eq!(code, 0);
    let info: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    assert_eq!(info["curves"][0]["degree"], 8);
    assert_eq!(info["curves"][0]["control_points"], 9);
}

#[test]
fn bad_input_exits_2_with_a_located_message() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/malformed");
    let (code, _, stderr) = vericad(&["info", dir.join("negative-weight.json").to_str().unwrap()]);
    assert_eq!(code, 2);
    assert!(stderr.contains("surfaces[0].weights[1][1]"), "{stderr}");
    let (code, _, _) = vericad(&["info", "/nonexistent.json"]);
    assert_eq!(code, 2);
    let (code, _, _) = vericad(&["frobnicate"]);
    assert_eq!(code, 2);
}

#[test]
fn eval_reports_exact_and_f64_points() {
    let d = tmp("eval");
    let f = d.join("m.json");
    std::fs::write(&f, vericad::demo::DEFAULT_MODEL).unwrap();
    let (code, stdout, stderr) = vericad(&[
        "eval",
        f.to_str().unwrap(),
        "--surface",
        "0",
        "--uv",
        "0.25,0.5",
        "--json",
    ]);
    assert_eq!(code, 0, "{stderr}");
    let r: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    let err = r["f64_error"].as_f64().unwrap();
    assert!(err < 1e-14, "{err}");
    let (code, _, stderr) = vericad(&[
        "eval",
        f.to_str().unwrap(),
        "--surface",
        "0",
        "--uv",
        "1.5,0.5",
    ]);
    assert_eq!(code, 2);
    assert!(stderr.contains("outside the domain"), "{stderr}");
    let (code, _, _) = vericad(&["eval", f.to_str().unwrap(), "--curve", "0", "--t", "0.3"]);
    assert_eq!(code, 0);
    let (code, _, _) = vericad(&["eval", f.to_str().unwrap(), "--surface", "7", "--uv", "0,0"]);
    assert_eq!(code, 2);
}

/// The subcommands `vericad --help` lists.
fn subcommands() -> Vec<String> {
    let (code, stdout, _) = vericad(&["--help"]);
    assert_eq!(code, 0);
    stdout
        .split("Commands:")
        .nth(1)
        .expect("a command list")
        .split("Options:")
        .next()
        .unwrap()
        .lines()
        .filter_map(|l| l.split_whitespace().next())
        .filter(|c| *c != "help")
        .map(str::to_string)
        .collect()
}

/// Every subcommand: help exits 0, every argument and option has a description, the README
/// names the command, and no help text says a step "is not implemented".
#[test]
fn every_subcommand_has_true_help() {
    let readme =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/README.md")).unwrap();
    let subs = subcommands();
    assert!(subs.len() >= 9, "{subs:?}");
    for sub in &subs {
        let (code, stdout, _) = vericad(&[sub, "--help"]);
        assert_eq!(code, 0);
        assert!(stdout.contains("Usage"), "{sub}");
        assert!(
            readme.contains(&format!("vericad {sub}")),
            "README does not name `vericad {sub}`"
        );
        assert!(!stdout.contains("not implemented"), "{sub}: {stdout}");
        let lines: Vec<&str> = stdout.lines().collect();
        for (i, l) in lines.iter().enumerate() {
            let t = l.trim_start();
            let header = l.starts_with("  ") && (t.starts_with('<') || t.starts_with('-'));
            if !header || t.starts_with("-h, --help") || t.starts_with("-V, --version") {
                continue;
            }
            let inline = t.split("  ").skip(1).any(|x| !x.trim().is_empty());
            let below = lines.get(i + 1).is_some_and(|n| {
                let ind = n.len() - n.trim_start().len();
                ind > l.len() - t.len() + 2 && !n.trim().is_empty()
            });
            assert!(inline || below, "{sub}: `{}` has no description", t.trim());
        }
    }
}

/// Negative numbers reach the command's own check (a clear message, exit 2), not the
/// argument parser's "unexpected argument".
#[test]
fn negative_numbers_get_a_clear_message() {
    let m = tmp("neg").join("m.json");
    std::fs::write(&m, vericad::demo::DEFAULT_MODEL).unwrap();
    let ms = m.to_str().unwrap();
    let cases: Vec<Vec<&str>> = vec![
        vec![
            "curve-on-surface",
            "--surface",
            ms,
            "--curve",
            ms,
            "--tol",
            "-1",
        ],
        vec![
            "curve-on-surface",
            "--surface",
            ms,
            "--curve",
            ms,
            "--angle",
            "-5",
        ],
        vec!["ssi", ms, "--time-limit", "-5"],
        vec!["ssi", ms, "--flatness", "-1"],
        vec!["ssi", ms, "--tol", "-1"],
        vec!["repair", ms, "--u1", "-1"],
        vec!["reparam", ms, "--tol", "-1"],
    ];
    for c in cases {
        let (code, _, stderr) = vericad(&c);
        assert_eq!(code, 2, "{c:?}: {stderr}");
        assert!(!stderr.contains("unexpected argument"), "{c:?}: {stderr}");
    }
}

#[test]
fn curve_on_surface_writes_result_and_svg() {
    let d = tmp("cos");
    let m = d.join("m.json");
    std::fs::write(&m, vericad::demo::DEFAULT_MODEL).unwrap();
    let (out, svg) = (d.join("r.json"), d.join("d.svg"));
    let (code, stdout, stderr) = vericad(&[
        "curve-on-surface",
        "--surface",
        &format!("{}:0", m.display()),
        "--curve",
        m.to_str().unwrap(),
        "--tol",
        "1e-2",
        "--angle",
        "10",
        "--out",
        out.to_str().unwrap(),
        "--svg",
        svg.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{stderr}");
    assert!(stdout.contains("certified"), "{stdout}");
    let r: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    for key in [
        "segments",
        "domain_polyline",
        "num_segments",
        "num_control_points",
        "certificate",
        "evidence",
    ] {
        assert!(r.get(key).is_some(), "missing {key}");
    }
    for key in ["eps_d", "eps_t_deg", "hausdorff_bound", "max_angle_deg"] {
        assert!(
            r["certificate"].get(key).is_some(),
            "missing certificate.{key}"
        );
    }
    let bound = r["certificate"]["hausdorff_bound"].as_f64().unwrap();
    assert!(bound <= 1e-2);
    assert!(std::fs::read_to_string(&svg).unwrap().starts_with("<svg"));
    // The evidence is measured only when asked for, and then lies within the proven bound.
    assert_eq!(r["evidence"]["measured"], false);
    assert_eq!(r["evidence"]["samples"], 0);
    assert!(stdout.contains("evidence: not measured"), "{stdout}");
    let ev = d.join("ev.json");
    let ms = m.to_str().unwrap();
    let cos = |extra: &[&str]| {
        let mut args = vec![
            "curve-on-surface",
            "--surface",
            ms,
            "--curve",
            ms,
            "--tol",
            "1e-2",
        ];
        args.extend_from_slice(extra);
        vericad(&args)
    };
    let (code, stdout, stderr) = cos(&["--evidence", "--out", ev.to_str().unwrap()]);
    assert_eq!(code, 0, "{stderr}");
    assert!(
        stdout.contains("evidence (measured, not proof)"),
        "{stdout}"
    );
    let e: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&ev).unwrap()).unwrap();
    assert_eq!(e["evidence"]["measured"], true);
    let segs = e["num_segments"].as_u64().unwrap();
    // 32 samples per segment (33 points) each way by default.
    assert!(e["evidence"]["samples"].as_u64().unwrap() >= 33 * segs);
    let measured = e["evidence"]["max_distance_sampled"].as_f64().unwrap();
    assert!(measured > 0.0 && measured <= bound, "{measured} vs {bound}");
    assert_eq!(
        e["certificate"]["hausdorff_bound"],
        r["certificate"]["hausdorff_bound"]
    );
    // The 3D picture: one polyline per segment, green (all within ε_d), the legend counting.
    let pic = d.join("p.svg");
    let (code, _, stderr) = cos(&["--svg-3d", pic.to_str().unwrap(), "--view", "20,35"]);
    assert_eq!(code, 0, "{stderr}");
    let text = std::fs::read_to_string(&pic).unwrap();
    let n = r["num_segments"].as_u64().unwrap() as usize;
    let curves = svg_group(&text, "curves");
    assert_eq!(curves.len(), n);
    assert!(curves.iter().all(|l| l.contains("stroke=\"#009646\"")));
    assert!(text.contains(&format!("segments with proven bound within ε_d ({n})")));
    // IGES and VTK outputs: the curve reads back as one 126 of the reported degree; the VTK
    // has one polyline and one proven bound per segment.
    let (igs, vtp) = (d.join("c.igs"), d.join("c.vtp"));
    let (code, _, stderr) = vericad(&[
        "curve-on-surface",
        "--surface",
        m.to_str().unwrap(),
        "--curve",
        m.to_str().unwrap(),
        "--tol",
        "1e-2",
        "--iges",
        igs.to_str().unwrap(),
        "--vtk",
        vtp.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{stderr}");
    let back = vericad::io::read_model(&igs).unwrap();
    let vericad::model::CurveGeometry::Space(c) = &back.curves[0].geometry else {
        panic!("space curve expected")
    };
    assert_eq!(c.hom.degree(), 4);
    let n = r["num_segments"].as_u64().unwrap();
    let v = std::fs::read_to_string(&vtp).unwrap();
    assert!(v.contains(&format!("NumberOfLines=\"{n}\"")));
    assert!(v.contains("Name=\"certified\""));
    // Bad input: a surface index that does not exist, a tolerance that is not positive.
    let (code, _, stderr) = vericad(&[
        "curve-on-surface",
        "--surface",
        &format!("{}:5", m.display()),
        "--curve",
        m.to_str().unwrap(),
    ]);
    assert_eq!(code, 2, "{stderr}");
    let (code, _, _) = vericad(&[
        "curve-on-surface",
        "--surface",
        m.to_str().unwrap(),
        "--curve",
        m.to_str().unwrap(),
        "--tol",
        "-1",
    ]);
    assert_eq!(code, 2);
}

#[test]
fn convert_and_curve_on_surface_from_iges_and_step() {
    let d = tmp("convert");
    let m = d.join("m.json");
    std::fs::write(&m, vericad::demo::DEFAULT_MODEL).unwrap();
    for ext in ["igs", "step"] {
        let f = d.join(format!("m.{ext}"));
        let (code, _, stderr) = vericad(&["convert", m.to_str().unwrap(), f.to_str().unwrap()]);
        assert_eq!(code, 0, "{stderr}");
        // The domain curve travels as a z = 0 curve (IGES convention) and is read back as one.
        let (code, stdout, stderr) = vericad(&[
            "curve-on-surface",
            "--surface",
            f.to_str().unwrap(),
            "--curve",
            f.to_str().unwrap(),
            "--tol",
            "1e-2",
            "--json",
        ]);
        assert_eq!(code, 0, "{ext}: {stderr}");
        let r: serde_json::Value = serde_json::from_str(&stdout).unwrap();
        assert!(r["certificate"]["hausdorff_bound"].as_f64().unwrap() <= 1e-2);
    }
    let (code, _, _) = vericad(&[
        "convert",
        m.to_str().unwrap(),
        d.join("m.dwg").to_str().unwrap(),
    ]);
    assert_eq!(code, 2);
    // Surfaces without a B-rep to STL: each surface triangulated whole.
    let stl = d.join("m.stl");
    let (code, _, stderr) = vericad(&["convert", m.to_str().unwrap(), stl.to_str().unwrap()]);
    assert_eq!(code, 0, "{stderr}");
    let text = std::fs::read_to_string(&stl).unwrap();
    assert!(
        text.matches("facet normal").count() >= 2 * 16 * 16,
        "{}",
        text.len()
    );
}

#[test]
fn viewing_formats_are_consistent() {
    let d = tmp("view");
    let src =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/public/abc-0000.step");
    let (vtp, obj) = (d.join("a.vtp"), d.join("a.obj"));
    for out in [&vtp, &obj] {
        let (code, _, stderr) = vericad(&["convert", src.to_str().unwrap(), out.to_str().unwrap()]);
        assert_eq!(code, 0, "{stderr}");
    }
    // The 25 trimmed faces as one triangulation (shared edge vertices): the same points and
    // triangles in both files as the library's trimmed tessellation gives.
    let m = vericad::io::read_model(&src).unwrap();
    let mesh = vericad::tessellate::mesh_brep(
        &m,
        m.brep.as_ref().unwrap(),
        &vericad::tessellate::MeshParams::default(),
    );
    let (np, nt) = (
        mesh.triangulation.vertices.len(),
        mesh.triangulation.triangles.len(),
    );
    let v = std::fs::read_to_string(&vtp).unwrap();
    assert!(
        v.contains(&format!("NumberOfPoints=\"{np}\""))
            && v.contains(&format!("NumberOfPolys=\"{nt}\"")),
        "{np} {nt}"
    );
    let o = std::fs::read_to_string(&obj).unwrap();
    assert_eq!(o.lines().filter(|l| l.starts_with("v ")).count(), np);
    assert_eq!(o.lines().filter(|l| l.starts_with("f ")).count(), nt);
    // Plot3D in: an ASCII single-block grid becomes one bilinear surface.
    let p3d = d.join("g.xyz");
    std::fs::write(&p3d, "2 2\n0 1 0 1\n0 0 1 1\n0 0 0 1\n").unwrap();
    let (code, stdout, _) = vericad(&["info", p3d.to_str().unwrap(), "--json"]);
    assert_eq!(code, 0);
    let info: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    assert_eq!(info["surfaces"][0]["degree"], serde_json::json!([1, 1]));
}

#[test]
fn convert_format_override_and_binary_stl() {
    let d = tmp("fmt");
    let src = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/public/gmsh-surface1.stl");
    let ascii = vericad::io::read_model(&src).unwrap();
    let bin = d.join("b.stl");
    let (code, _, stderr) = vericad(&[
        "convert",
        src.to_str().unwrap(),
        bin.to_str().unwrap(),
        "--format",
        "stl-binary",
    ]);
    assert_eq!(code, 0, "{stderr}");
    let back = vericad::io::read_model(&bin).unwrap();
    let (a, b) = (&ascii.triangulations[0], &back.triangulations[0]);
    assert_eq!(
        (a.vertices.len(), a.triangles.len()),
        (b.vertices.len(), b.triangles.len())
    );
    // Binary STL stores f32: coordinates agree to f32 rounding.
    for (p, q) in a.vertices.iter().zip(&b.vertices) {
        for k in 0..3 {
            assert!((p[k] - q[k]).abs() <= p[k].abs() * 1e-7 + 1e-30);
        }
    }
    let out = d.join("noext");
    let igs = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/public/occt-BUC50025.igs");
    let (code, _, _) = vericad(&[
        "convert",
        igs.to_str().unwrap(),
        out.to_str().unwrap(),
        "--format",
        "step",
    ]);
    assert_eq!(code, 0);
    assert_eq!(vericad::io::step::read(&out).unwrap().surfaces.len(), 7);
}

/// A STEP B-rep converted to IGES: the B-rep entities (186 per solid, 510 per face) by
/// default, trimmed surfaces (144, one per face) with `--format iges-faces`; the warnings say
/// which.
#[test]
fn convert_writes_iges_trimmed_surfaces_or_brep_entities() {
    let d = tmp("iges-forms");
    let src =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/public/abc-0000.step");
    let brep = d.join("brep.igs");
    let (code, _, stderr) = vericad(&["convert", src.to_str().unwrap(), brep.to_str().unwrap()]);
    assert_eq!(code, 0, "{stderr}");
    assert!(!stderr.contains("trimmed surfaces"), "{stderr}");
    let faces = d.join("faces.igs");
    let (code, _, stderr) = vericad(&[
        "convert",
        src.to_str().unwrap(),
        faces.to_str().unwrap(),
        "--format",
        "iges-faces",
    ]);
    assert_eq!(code, 0, "{stderr}");
    assert!(stderr.contains("25 trimmed surfaces (144)"), "{stderr}");
    let n = |path: &std::path::Path, ty: &str| {
        let m = vericad::io::read_model(path).unwrap();
        m.source_entities.get(ty).copied().unwrap_or(0)
    };
    assert_eq!(
        (n(&faces, "144 (form 0)"), n(&faces, "186 (form 0)")),
        (25, 0)
    );
    assert_eq!(
        (n(&brep, "510 (form 1)"), n(&brep, "186 (form 0)")),
        (25, 6)
    );
}

/// Output paths are checked before the intersection starts: an unwritable `--out` fails at
/// once (exit 1, "cannot write"), and no partial file is left.
#[test]
fn ssi_checks_outputs_before_the_work() {
    let d = tmp("unwritable");
    let src = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/public/gmsh-t20_data.step");
    let out = d.join("no-such-dir").join("r.json");
    let (code, _, stderr) =
        vericad(&["ssi", src.to_str().unwrap(), "--out", out.to_str().unwrap()]);
    assert_eq!(code, 1, "{stderr}");
    assert!(stderr.contains("cannot write"), "{stderr}");
    assert!(
        !stderr.contains("face pairs"),
        "no work before the check: {stderr}"
    );
    assert!(!out.exists());
}

/// `--no-certify` gives the same branches without the certificates, and says so: exit 3,
/// `certified` and `no_missed_branches` false, every point `not_requested`.
#[test]
fn ssi_without_certificates_says_so() {
    let d = tmp("no-certify");
    let (a, b) = two_planes(&d);
    let run = |extra: &[&str]| -> (i32, String, serde_json::Value) {
        let out = d.join("r.json");
        let mut args = vec![
            "ssi",
            a.to_str().unwrap(),
            b.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ];
        args.extend_from_slice(extra);
        let (code, stdout, _) = vericad(&args);
        let v: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
        (code, stdout, v)
    };
    let (code, _, on) = run(&[]);
    assert_eq!(code, 0);
    assert_eq!(on["summary"]["certified"], true);
    let (code, stdout, off) = run(&["--no-certify"]);
    assert_eq!(code, 3, "{stdout}");
    assert!(stdout.contains("--no-certify"), "{stdout}");
    let s = &off["summary"];
    assert_eq!(s["certified"], false);
    assert_eq!(s["no_missed_branches"], false);
    assert!(s["dist_curve_max"].is_null());
    assert_eq!(s["branches"], on["summary"]["branches"]);
    assert_eq!(s["points_curve_uncertified"], s["points"]);
    let br = &off["pairs"][0]["branches"][0];
    let reasons = br["curve_uncertified"].as_array().unwrap();
    assert_eq!(reasons.len(), br["points"].as_array().unwrap().len());
    assert!(
        reasons.iter().all(|r| r["reason"] == "not_requested"),
        "{reasons:?}"
    );
}

/// `--svg` draws the run: the branch over the faces in the colour of its certificate, a legend
/// that counts the points, and a scale bar that measures the drawing — the planes meet along
/// the x axis from −1 to 1, so the branch is 2 model units long on the page, whatever the view.
#[test]
fn ssi_picture_shows_the_branch_to_scale() {
    let d = tmp("picture");
    let (a, b) = two_planes(&d);
    let svg = d.join("r.svg");
    let run = |extra: &[&str]| -> (i32, String, String) {
        let mut args = vec![
            "ssi",
            a.to_str().unwrap(),
            b.to_str().unwrap(),
            "--svg",
            svg.to_str().unwrap(),
            "--json",
        ];
        args.extend_from_slice(extra);
        let (code, stdout, stderr) = vericad(&args);
        (
            code,
            stdout,
            stderr + &std::fs::read_to_string(&svg).unwrap_or_default(),
        )
    };
    // The numbers of a `points="x,y x,y ..."` attribute.
    let points = |line: &str| -> Vec<[f64; 2]> {
        let at = line.find("points=\"").unwrap() + 8;
        let end = at + line[at..].find('"').unwrap();
        line[at..end]
            .split_whitespace()
            .map(|p| {
                let (x, y) = p.split_once(',').unwrap();
                [x.parse().unwrap(), y.parse().unwrap()]
            })
            .collect()
    };
    let attr = |line: &str, name: &str| -> f64 {
        let at = line.find(&format!(" {name}=\"")).unwrap() + name.len() + 3;
        let end = at + line[at..].find('"').unwrap();
        line[at..end].parse().unwrap()
    };
    for view in ["-60,25", "0,90", "35,-10"] {
        let (code, stdout, text) = run(&["--view", view]);
        assert_eq!(code, 0, "{text}");
        let v: serde_json::Value = serde_json::from_str(&stdout).unwrap();
        let n = v["summary"]["points"].as_u64().unwrap();
        assert!(text.starts_with("<svg") && text.trim_end().ends_with("</svg>"));
        let curves = svg_group(&text, "curves");
        assert_eq!(curves.len(), 1, "one branch, all one status: {curves:?}");
        assert!(
            curves[0].contains("stroke=\"#009646\""),
            "green: {}",
            curves[0]
        );
        assert!(
            text.contains(&format!("points proven within tol of the curve ({n})")),
            "legend counts the points"
        );
        let pts = points(curves[0]);
        assert_eq!(pts.len() as u64, n);
        let (p, q) = (pts[0], pts[pts.len() - 1]);
        let page_len = ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2)).sqrt();
        let bar = text
            .lines()
            .find(|l| l.contains("<g id=\"scale\""))
            .unwrap();
        let bar_px = attr(bar, "x2") - attr(bar, "x1");
        let label = &bar[bar.find("<text").unwrap()..];
        let at = label.find('>').unwrap() + 1;
        let bar_len: f64 = label[at..]
            .split_whitespace()
            .next()
            .unwrap()
            .parse()
            .unwrap();
        let measured = page_len / bar_px * bar_len;
        // From straight above the x axis is seen at full length; at an angle, shorter.
        let (az, el) = view.split_once(',').unwrap();
        let (az, el): (f64, f64) = (az.parse().unwrap(), el.parse().unwrap());
        let (az, el) = (az.to_radians(), el.to_radians());
        // |x projected| = √(sin² az + (sin el cos az)²).
        let seen = 2.0 * (az.sin().powi(2) + (el.sin() * az.cos()).powi(2)).sqrt();
        assert!(
            (measured - seen).abs() <= 0.01 * seen,
            "{view}: {measured} vs {seen}"
        );
    }
    let (code, _, text) = run(&["--no-certify"]);
    assert_eq!(code, 3);
    assert!(text.contains("points not proven against the curve ("));
    assert!(text.contains("stroke=\"#d71e1e\""), "red where not proven");
    let (code, _, stderr) = run(&["--view", "0,95"]);
    assert_eq!(code, 2, "{stderr}");
    assert!(stderr.contains("--view"), "{stderr}");
}

/// `repair --svg` writes the picture; an unwritable output fails before the work (exit 1,
/// "cannot write"), leaving no other output behind.
#[test]
fn repair_picture_and_outputs_checked_first() {
    let d = tmp("repair-svg");
    let src = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/public/gmsh-t20_data.step");
    let svg = d.join("r.svg");
    // t20's faces are mostly trimmed: the patch-set repair only when asked for.
    let (code, stdout, stderr) = vericad(&[
        "repair",
        src.to_str().unwrap(),
        "--patches",
        "--svg",
        svg.to_str().unwrap(),
        "--view",
        "30,40",
    ]);
    assert_eq!(code, 0, "{stderr}");
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(text.starts_with("<svg") && text.contains("output patches ("));
    assert!(stdout.contains("patches:"), "{stdout}");
    assert!(stdout.contains("trims ignored: 15 of 21 faces"), "{stdout}");
    let (code, stdout, stderr) = vericad(&[
        "repair",
        src.to_str().unwrap(),
        "--svg",
        svg.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{stderr}");
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(
        text.starts_with("<svg")
            && text.contains("faces (21), one colour each, inside their trims")
    );
    assert!(stdout.contains("faces: 21 (15 trimmed"), "{stdout}");
    let report = d.join("report.json");
    let bad = d.join("no-such-dir").join("r.svg");
    let (code, _, stderr) = vericad(&[
        "repair",
        src.to_str().unwrap(),
        "--report",
        report.to_str().unwrap(),
        "--svg",
        bad.to_str().unwrap(),
    ]);
    assert_eq!(code, 1, "{stderr}");
    assert!(stderr.contains("cannot write"), "{stderr}");
    assert!(!report.exists(), "no output written before the failure");
}

/// `--pretty` (any command) indents every value; the text parses to the same result.
#[test]
fn pretty_json_is_the_same_result_indented() {
    let d = tmp("pretty");
    let m = d.join("m.json");
    std::fs::write(&m, vericad::demo::DEFAULT_MODEL).unwrap();
    let ms = m.to_str().unwrap();
    let args = ["curve-on-surface", "--surface", ms, "--curve", ms, "--json"];
    let (code, plain, _) = vericad(&args);
    assert_eq!(code, 0);
    let mut with = args.to_vec();
    with.push("--pretty");
    let (code, pretty, _) = vericad(&with);
    assert_eq!(code, 0);
    assert!(pretty.lines().count() > 2 * plain.lines().count());
    let strip = |t: &str| {
        let mut v: serde_json::Value = serde_json::from_str(t).unwrap();
        v["elapsed_ms"] = serde_json::Value::Null;
        v["evidence"]["elapsed_ms"] = serde_json::Value::Null;
        v
    };
    assert_eq!(strip(&plain), strip(&pretty));
}

/// The JSON result writes a point per line (arrays of numbers inline) and leaves the fitted
/// cubics out unless `--fits` asks for them; both forms parse as the same points.
#[test]
fn ssi_json_is_compact_and_fits_are_on_request() {
    let d = tmp("fits");
    let (a, b) = two_planes(&d);
    let run = |name: &str, extra: &[&str]| -> (String, serde_json::Value) {
        let out = d.join(name);
        let mut args = vec![
            "ssi",
            a.to_str().unwrap(),
            b.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ];
        args.extend_from_slice(extra);
        let (code, _, stderr) = vericad(&args);
        assert!(code == 0 || code == 3, "{stderr}");
        let text = std::fs::read_to_string(&out).unwrap();
        let v: serde_json::Value = serde_json::from_str(&text).unwrap();
        (text, v)
    };
    let (text, plain) = run("plain.json", &[]);
    let (_, full) = run("full.json", &["--fits"]);
    let branches = |v: &serde_json::Value| -> Vec<serde_json::Value> {
        v["pairs"]
            .as_array()
            .unwrap()
            .iter()
            .flat_map(|p| p["branches"].as_array().unwrap().clone())
            .collect()
    };
    let (bp, bf) = (branches(&plain), branches(&full));
    assert!(!bp.is_empty(), "the planes meet");
    assert_eq!(bp.len(), bf.len());
    for (x, y) in bp.iter().zip(&bf) {
        assert!(x["fit"].is_null(), "no fit by default");
        assert!(
            y["fit"]["control_points"]
                .as_array()
                .is_some_and(|c| !c.is_empty())
        );
        assert_eq!(x["points"], y["points"]);
    }
    // No line holds a lone coordinate: every point is written on one line.
    let lone = text
        .lines()
        .filter(|l| l.trim().trim_end_matches(',').parse::<f64>().is_ok())
        .count();
    assert_eq!(lone, 0);
}

/// Human summaries speak the user's language: no Rust Debug text (`Some(`, `None`, enum
/// variants with braces, quoted map keys).
#[test]
fn human_output_has_no_debug_text() {
    let data = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/public/");
    let d = tmp("human");
    let runs: Vec<Vec<String>> = vec![
        vec!["demo".into(), "--out".into(), d.to_string_lossy().into()],
        vec!["info".into(), format!("{data}abc-0000.step")],
        vec!["info".into(), format!("{data}gmsh-t20_data.step")],
        vec!["ssi".into(), format!("{data}gmsh-periodic_u_cst.step")],
        vec![
            "ssi".into(),
            format!("{data}gmsh-periodic_u_cst.step"),
            "--untrimmed".into(),
        ],
    ];
    for r in runs {
        let args: Vec<&str> = r.iter().map(String::as_str).collect();
        let (code, stdout, stderr) = vericad(&args);
        assert!(code == 0 || code == 3, "{args:?}: {stderr}");
        for bad in [
            "Some(",
            "None",
            " { ",
            "{\"",
            "[Boundary",
            "[TrimBoundary",
            "[Tangential",
        ] {
            assert!(
                !stdout.contains(bad),
                "{args:?} prints Debug text `{bad}`:\n{stdout}"
            );
        }
    }
}

/// Completion scripts and man pages come from the command line's own definition: every
/// subcommand (as `vericad --help` lists it) appears in the bash and fish scripts and has its
/// own page, and an unknown shell is bad input.
#[test]
fn completions_and_man_pages_cover_every_command() {
    let commands = subcommands();
    assert!(commands.len() >= 14, "{commands:?}");
    for shell in ["bash", "fish"] {
        let (code, text, _) = vericad(&["completions", shell]);
        assert_eq!(code, 0);
        for c in &commands {
            assert!(text.contains(c.as_str()), "{shell}: {c} missing");
        }
    }
    assert_eq!(vericad(&["completions", "tcsh"]).0, 2);
    let dir = std::env::temp_dir().join(format!("vericad-man-{}", std::process::id()));
    assert_eq!(vericad(&["man", "--out", dir.to_str().unwrap()]).0, 0);
    for c in &commands {
        let page = std::fs::read_to_string(dir.join(format!("vericad-{c}.1"))).unwrap();
        assert!(page.starts_with(".ie") && page.contains(".TH"), "{c}");
    }
    assert!(vericad(&["man"]).1.contains(".TH vericad 1"));
    let _ = std::fs::remove_dir_all(&dir);
}
