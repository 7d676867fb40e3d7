//! SSI on the public CAD files in tests/data/public and through the command line: runs complete
//! without error, every point carries a proven bound within tol of both surfaces (and a curve
//! certificate or a reason why not), results are the same for
//! every thread count, the time limit yields a marked partial result.

use std::path::{Path, PathBuf};
use vericad::ssi::{SsiParams, intersect_models};

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/public")
        .join(name)
}

fn no_progress(_: usize, _: usize) {}

/// The faces' whole surfaces intersected (`--untrimmed`): adjacent faces' surfaces cross
/// along and beyond their shared edges, which gives many branches to check.
fn check_file(name: &str, min_branches: usize) {
    let m = vericad::io::read_model(&data(name)).expect("readable");
    let prm = SsiParams {
        respect_trims: false,
        ..Default::default()
    };
    let r = intersect_models(&m, None, &prm, &no_progress).expect("intersection completes");
    assert!(!r.summary.partial);
    // Faces whose borders are one curve (the fuselage's G1 joins, t20's neighbouring
    // faces) meet along it: reported as common borders, not branches (`common_borders`);
    // faces touching along a curve otherwise as tangent contacts (`tangent_contact`).
    assert!(
        r.summary.branches + r.summary.tangent_contact_pairs + r.summary.common_borders
            >= min_branches,
        "{name}: {} branches, {} tangent contacts, {} common borders",
        r.summary.branches,
        r.summary.tangent_contact_pairs,
        r.summary.common_borders
    );
    // Every point within tol of both surfaces at its own parameters. Not every point is
    // proven near the intersection *curve*: adjacent faces meet along their common edges,
    // where the curve runs along a domain border or the faces are tangent; those points are
    // uncertified (counted), and `all_points_within_tol` (a claim about the curve) is false.
    assert!(
        r.summary.dist_max <= prm.tol,
        "{name}: {}",
        r.summary.dist_max
    );
    let branches: Vec<_> = r.pairs.iter().flat_map(|p| &p.branches).collect();
    let unproven: usize = branches.iter().map(|b| b.curve_uncertified_points).sum();
    assert_eq!(unproven, r.summary.points_curve_uncertified, "{name}");
    assert_eq!(
        r.summary.all_points_within_tol,
        unproven == 0 && r.summary.dist_curve_max.is_some_and(|d| d <= prm.tol),
        "{name}"
    );
    for b in &branches {
        assert_eq!(b.curve_radius.len(), b.points.len(), "{name}");
        assert_eq!(
            b.curve_radius.iter().filter(|x| x.is_none()).count(),
            b.curve_uncertified_points
        );
    }
    for p in &r.pairs {
        assert_eq!(
            p.stats.inconsistent_triangle_pairs,
            0,
            "{name} {:?}",
            (p.a, p.b)
        );
    }
    // VTK output renders every branch and every common border as a line.
    let vtp = vericad::ssi::job::to_vtp(&r, &m, None);
    let lines = r.summary.branches + r.summary.common_borders;
    assert!(vtp.contains(&format!("NumberOfLines=\"{lines}\"")));
}

#[test]
fn fuselage_faces_intersect() {
    // 12 adjacent face pairs meet tangentially along their borders (measured sine of the
    // normals' angle at most 2.4e-7): common borders (14 with the two G0 ones).
    check_file("occt-bug28366_fuselage.stp", 12);
}

#[test]
fn t20_faces_intersect() {
    check_file("gmsh-t20_data.step", 10);
}

/// t20 is one closed shell of 21 faces and 48 edges (a valid solid): intersecting its faces
/// (not their whole surfaces) gives no branch, and the intersection along the edges is listed
/// as shared edges, each an EDGE_CURVE or VERTEX_POINT of the file (ids read here from the
/// file's text, not through the reader).
#[test]
fn t20_solid_has_no_self_intersection() {
    let path = data("gmsh-t20_data.step");
    let text = std::fs::read_to_string(&path).unwrap();
    let ids_of = |kind: &str| -> std::collections::BTreeSet<String> {
        text.lines()
            .filter(|l| l.contains(&format!("={kind}(")))
            .filter_map(|l| l.split('=').next().map(|s| s.trim().to_string()))
            .collect()
    };
    let edges = ids_of("EDGE_CURVE");
    let vertices = ids_of("VERTEX_POINT");
    assert_eq!(edges.len(), 48);
    let m = vericad::io::read_model(&path).unwrap();
    let r = intersect_models(&m, None, &SsiParams::default(), &no_progress).unwrap();
    assert_eq!(
        r.summary.branches, 0,
        "a valid solid's faces meet only along shared edges"
    );
    // Faces joined tangentially (G1) touch along their shared edge: listed with the edge,
    // not as a tangent contact.
    assert_eq!(r.summary.tangent_contact_pairs, 0);
    let mut found = std::collections::BTreeSet::new();
    for p in &r.pairs {
        for e in p.faces.iter().flat_map(|f| &f.shared_edges) {
            assert!(
                edges.contains(&e.edge) || vertices.contains(&e.edge),
                "{} is not an edge or vertex of the file",
                e.edge
            );
            // Tubes the coverage used are listed with their reach even without points.
            assert!(e.max_distance <= e.within);
            if edges.contains(&e.edge) && e.points > 0 {
                found.insert(e.edge.clone());
            }
        }
    }
    // Every edge joins two faces whose surfaces meet along it; along a tangent (G1) edge the
    // surfaces' intersection is degenerate (touch points, a tangent contact or nothing), so
    // not every edge need carry curve points.
    assert!(found.len() >= 24, "{} of 48 edges found", found.len());
    let touch_on_edges: usize = r
        .pairs
        .iter()
        .filter_map(|p| p.faces.as_ref())
        .map(|f| f.touch_points_on_shared_edges)
        .sum();
    assert!(touch_on_edges > 0);
    // Untrimmed, the same faces give branches.
    let untrimmed = SsiParams {
        respect_trims: false,
        ..Default::default()
    };
    let u = intersect_models(&m, None, &untrimmed, &no_progress).unwrap();
    assert!(u.summary.branches >= 10);
}

fn branches_json(r: &vericad::ssi::SsiResult) -> String {
    let b: Vec<_> = r
        .pairs
        .iter()
        .map(|p| (&p.branches, &p.touch_points))
        .collect();
    serde_json::to_string(&b).unwrap()
}

#[test]
fn same_result_for_every_thread_count() {
    let m = vericad::io::read_model(&data("gmsh-t20_data.step")).unwrap();
    let prm = SsiParams::default();
    let run = |n: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build()
            .unwrap();
        pool.install(|| intersect_models(&m, None, &prm, &no_progress).unwrap())
    };
    let one = branches_json(&run(1));
    assert_eq!(one, branches_json(&run(2)));
    assert_eq!(one, branches_json(&run(3)));
}

#[test]
fn time_limit_gives_a_marked_partial_result() {
    let m = vericad::io::read_model(&data("gmsh-t20_data.step")).unwrap();
    let prm = SsiParams {
        time_limit: Some(1e-9),
        ..Default::default()
    };
    let r = intersect_models(&m, None, &prm, &no_progress).unwrap();
    assert!(r.summary.partial);
    assert!(r.summary.pairs_not_run > 0);
    assert!(
        r.summary
            .certificate
            .iter()
            .any(|c| c.starts_with("PARTIAL"))
    );
}

#[test]
fn stl_meshes_intersect_in_mesh_mode() {
    // The STL surface against a plane through the middle of its bounding box, both as meshes.
    let a = vericad::io::read_model(&data("gmsh-surface1.stl")).unwrap();
    let t = &a.triangulations[0];
    let (lo, hi) =
        t.vertices
            .iter()
            .fold(([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]), |(l, h), p| {
                (
                    std::array::from_fn(|k| l[k].min(p[k])),
                    std::array::from_fn(|k| h[k].max(p[k])),
                )
            });
    let k = (0..3)
        .max_by(|&x, &y| (hi[x] - lo[x]).total_cmp(&(hi[y] - lo[y])))
        .unwrap();
    let c = 0.5 * (lo[k] + hi[k]) + 1e-3 * (hi[k] - lo[k]);
    let (i, j) = ((k + 1) % 3, (k + 2) % 3);
    let corner = |a: f64, b: f64| {
        let mut p = [0.0; 3];
        p[k] = c;
        p[i] = a;
        p[j] = b;
        p
    };
    let pad = |x: usize| (hi[x] - lo[x]).max(1.0);
    let plane = vericad::model::Triangulation {
        name: "plane".into(),
        vertices: vec![
            corner(lo[i] - pad(i), lo[j] - pad(j)),
            corner(hi[i] + pad(i), lo[j] - pad(j)),
            corner(hi[i] + pad(i), hi[j] + pad(j)),
            corner(lo[i] - pad(i), hi[j] + pad(j)),
        ],
        triangles: vec![[0, 1, 2], [0, 2, 3]],
    };
    let b = vericad::model::Model {
        triangulations: vec![plane],
        ..Default::default()
    };
    let r = intersect_models(&a, Some(&b), &SsiParams::default(), &no_progress).unwrap();
    assert!(r.summary.branches >= 1);
    for br in r.pairs.iter().flat_map(|p| &p.branches) {
        for p in &br.points {
            assert!(
                (p[k] - c).abs() <= br.dist_b_max + 1e-12 * c.abs().max(1.0),
                "{p:?} off the plane"
            );
        }
        if !br.closed {
            assert!(
                br.ends
                    .iter()
                    .all(|e| *e != vericad::ssi::EndKind::Unexplained),
                "{:?}",
                br.ends
            );
        }
    }
}

#[test]
fn cli_writes_json_vtk_and_iges() {
    let dir = std::env::temp_dir().join(format!("vericad-ssi-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (json, vtk, iges) = (dir.join("r.json"), dir.join("r.vtp"), dir.join("r.igs"));
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_vericad"))
        .args([
            "ssi",
            data("gmsh-t20_data.step").to_str().unwrap(),
            "--tol",
            "1e-6",
            "--untrimmed",
            "--out",
        ])
        .arg(&json)
        .arg("--vtk")
        .arg(&vtk)
        .arg("--iges")
        .arg(&iges)
        .arg("--fits")
        .output()
        .unwrap();
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    // Exit 0 exactly when the run is certified, 3 when it finished uncertified (t20's
    // adjacent faces meet along shared edges, which the coverage cannot certify).
    let certified = v["summary"]["certified"].as_bool().unwrap();
    assert_eq!(
        out.status.code(),
        Some(if certified { 0 } else { 3 }),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let pairs = v["pairs"].as_array().unwrap();
    let b = pairs
        .iter()
        .find_map(|p| p["branches"].as_array().filter(|b| !b.is_empty()))
        .unwrap();
    for key in [
        "closed",
        "points",
        "uv_a",
        "uv_b",
        "dist_a_max",
        "dist_b_max",
        "ends",
    ] {
        assert!(b[0].get(key).is_some(), "branch lacks {key}");
    }
    assert!(v["summary"]["branches"].as_u64().unwrap() > 0);
    // The IGES curves read back as many curves as branches with a fit.
    let m = vericad::io::read_model(&iges).unwrap();
    let fitted = pairs
        .iter()
        .flat_map(|p| p["branches"].as_array().unwrap())
        .filter(|b| !b["fit"].is_null())
        .count();
    assert!(fitted > 0, "branches carry fits");
    assert_eq!(m.curves.len(), fitted);
    assert!(std::fs::read_to_string(&vtk).unwrap().starts_with("<?xml"));
    // Bad tolerance: exit code 2 with a message.
    let bad = std::process::Command::new(env!("CARGO_BIN_EXE_vericad"))
        .args([
            "ssi",
            data("gmsh-t20_data.step").to_str().unwrap(),
            "--tol",
            "-1",
        ])
        .output()
        .unwrap();
    assert_eq!(bad.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&bad.stderr).contains("tolerance"));
    std::fs::remove_dir_all(&dir).ok();
}

/// `certify-ssi` on vericad's own result (all within tol, nothing missing), on the result
/// with one branch removed (that branch reported missing), and on the IGES fits.
#[test]
fn certify_foreign_results() {
    use vericad::model::{Model, Surface};
    use vericad::spline::construct::{Frame, cylinder};
    let dir = std::env::temp_dir().join(format!("vericad-cert-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let z = Frame {
        o: [0.0; 3],
        x: [1.0, 0.0, 0.0],
        y: [0.0, 1.0, 0.0],
        z: [0.0, 0.0, 1.0],
    };
    let fx = Frame {
        o: [-3.0, 0.0, 0.0],
        x: [0.0, 1.0, 0.0],
        y: [0.0, 0.0, 1.0],
        z: [1.0, 0.0, 0.0],
    };
    let model = |s| Model {
        surfaces: vec![Surface::new("cyl", s)],
        ..Default::default()
    };
    let (fa, fb) = (dir.join("a.json"), dir.join("b.json"));
    vericad::io::write_model(&fa, &model(cylinder(&z, 1.0, -3.0, 3.0).unwrap())).unwrap();
    vericad::io::write_model(&fb, &model(cylinder(&fx, 0.6, 0.0, 6.0).unwrap())).unwrap();
    let exe = env!("CARGO_BIN_EXE_vericad");
    let (res, igs) = (dir.join("r.json"), dir.join("r.igs"));
    let st = std::process::Command::new(exe)
        .args([
            "ssi",
            fa.to_str().unwrap(),
            fb.to_str().unwrap(),
            "--tol",
            "1e-7",
            "--out",
            res.to_str().unwrap(),
            "--iges",
            igs.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert!(
        st.status.success(),
        "{}",
        String::from_utf8_lossy(&st.stderr)
    );
    let run: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&res).unwrap()).unwrap();
    assert_eq!(run["summary"]["certified"], true, "{}", run["summary"]);
    let certify = |curves: &Path, code: i32| -> serde_json::Value {
        let out = std::process::Command::new(exe)
            .args([
                "certify-ssi",
                fa.to_str().unwrap(),
                fb.to_str().unwrap(),
                "--curves",
                curves.to_str().unwrap(),
                "--tol",
                "1e-7",
                "--json",
            ])
            .output()
            .unwrap();
        assert_eq!(
            out.status.code(),
            Some(code),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        serde_json::from_slice(&out.stdout).unwrap()
    };
    let own = certify(&res, 0);
    assert_eq!(own["curves"].as_array().unwrap().len(), 2);
    assert_eq!(own["curves_within_tol"], 2, "{own}");
    assert_eq!(own["missing_branches"], 0);
    // Drop the second branch.
    let mut v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&res).unwrap()).unwrap();
    v["pairs"][0]["branches"].as_array_mut().unwrap().pop();
    let half = dir.join("half.json");
    std::fs::write(&half, v.to_string()).unwrap();
    let h = certify(&half, 3);
    assert_eq!(h["missing_branches"], 1, "{h}");
    // The IGES fits: spline curves checked at samples, close to both cylinders.
    // Fits sampled between their interpolated points exceed 1e-7: exit 3 (not within tol).
    let f = certify(&igs, 3);
    assert!(
        f["curves_within_tol"].as_u64() < Some(f["curves"].as_array().unwrap().len() as u64)
            || f["missing_branches"].as_u64() > Some(0)
            || f["partial_branches"].as_u64() > Some(0),
        "exit 3 must have a reason: {f}"
    );
    for c in f["curves"].as_array().unwrap() {
        assert_eq!(c["kind"], "spline");
        assert!(
            c["dist_a_max"].as_f64().unwrap() < 1e-5 && c["dist_b_max"].as_f64().unwrap() < 1e-5,
            "{c}"
        );
    }
    // A malformed foreign file is bad input.
    let bad = dir.join("bad.json");
    std::fs::write(&bad, "[[[1, 2]]]").unwrap();
    let out = std::process::Command::new(exe)
        .args([
            "certify-ssi",
            fa.to_str().unwrap(),
            fb.to_str().unwrap(),
            "--curves",
            bad.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert_eq!(
        out.status.code(),
        Some(2),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    std::fs::remove_dir_all(&dir).ok();
}
