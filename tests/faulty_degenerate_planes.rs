//! Near-degenerate planar faces from `tests/data/faulty` (the README's "partners": planes,
//! a plane tilted by 1e-15, slivers of width 0 and 1e-12, patches of size 1e-300 and of
//! subnormal size, a B-spline plane with its parameters flipped), intersected pair by pair,
//! all 136 pairs. Every face is planar, so the truth is known from the files: each lies in a
//! plane `n · x = c` written down here from the STEP data (not from vericad). Checked:
//!
//! * every run returns (no panic, no error: the data are finite and in range);
//! * every output point lies within tol of both true planes (f64 evaluation of the plane
//!   equations at the point, far below tol in error);
//! * a certified run claims no missed branch and every point within tol; a certified run of two
//!   distinct parallel planes reports no branch, of two crossing planes whose patches cross
//!   inside both (plane-diag with the z = 0 and z = ½ patches) exactly one;
//! * faces in one plane whose control points are exactly coplanar (z = 0; z = x) are
//!   reported coincident.

use std::path::PathBuf;
use vericad::io::read_model;
use vericad::model::Model;
use vericad::ssi::{SsiParams, intersect_models};

/// (file, unit normal n, c): the face lies in `n · x = c`.
fn planes() -> Vec<(&'static str, [f64; 3], f64)> {
    let d = 1.0 / 3f64.sqrt();
    let h = 0.5f64.sqrt();
    vec![
        // PLANE at (0.577…)(1, 1, 1), normal (1, 1, 1)/√3: x + y + z = √3 (distance 1).
        ("plane-diag", [d, d, d], 1.0),
        ("plane-x05", [1.0, 0.0, 0.0], 0.5),
        ("plane-x1", [1.0, 0.0, 0.0], 1.0),
        ("plane-z0-bs-flipped", [0.0, 0.0, 1.0], 0.0),
        ("plane-z0-bs", [0.0, 0.0, 1.0], 0.0),
        ("plane-z0", [0.0, 0.0, 1.0], 0.0),
        ("plane-z05", [0.0, 0.0, 1.0], 0.5),
        ("plane-z1-eps", [0.0, 0.0, 1.0], 0.999999999999),
        ("plane-z1", [0.0, 0.0, 1.0], 1.0),
        // z = 1e-15 · x.
        ("tilted-1e-15", [-1e-15, 0.0, 1.0], 0.0),
        // Control points (±1, 0 or 1e-12, ±1) and (±1e-300, …), (±5e-324, …): z = x.
        ("sliver-0", [-h, 0.0, h], 0.0),
        ("sliver-1e-12", [-h, 0.0, h], 0.0),
        ("tiny-1e-300", [-h, 0.0, h], 0.0),
        ("denormal", [-h, 0.0, h], 0.0),
        ("coplanar-half", [0.0, 0.0, 1.0], 0.0),
        ("ok-bilinear", [0.0, 0.0, 1.0], 0.0),
    ]
}

fn model(name: &str) -> Model {
    let p = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/faulty")
        .join(format!("{name}.step"));
    read_model(&p).unwrap_or_else(|e| panic!("{name}: {e}"))
}

fn dist(p: &[f64; 3], n: &[f64; 3], c: f64) -> f64 {
    (n[0] * p[0] + n[1] * p[1] + n[2] * p[2] - c).abs()
}

#[test]
fn every_pair_of_degenerate_planes_is_answered_truthfully() {
    let ps = planes();
    let models: Vec<Model> = ps.iter().map(|p| model(p.0)).collect();
    let prm = SsiParams::default();
    let tol = prm.tol;
    let (mut runs, mut certified) = (0, 0);
    for i in 0..ps.len() {
        for j in i..ps.len() {
            let (na, ca) = (ps[i].1, ps[i].2);
            let (nb, cb) = (ps[j].1, ps[j].2);
            let what = format!("{} x {}", ps[i].0, ps[j].0);
            let r = intersect_models(&models[i], Some(&models[j]), &prm, &|_, _| {})
                .unwrap_or_else(|e| panic!("{what}: {e}"));
            runs += 1;
            for b in r.pairs.iter().flat_map(|p| &p.branches) {
                for q in &b.points {
                    let (da, db) = (dist(q, &na, ca), dist(q, &nb, cb));
                    assert!(da <= tol && db <= tol, "{what}: {q:?} {da:e} {db:e}");
                }
            }
            for t in r.pairs.iter().flat_map(|p| &p.touch_points) {
                let (da, db) = (dist(&t.point, &na, ca), dist(&t.point, &nb, cb));
                assert!(da <= tol && db <= tol, "{what}: touch {:?}", t.point);
            }
            let s = &r.summary;
            // A certified run claims every branch found and every point on the curve.
            assert!(
                !s.certified || (s.no_missed_branches && s.all_points_within_tol && !s.partial),
                "{what}"
            );
            if s.certified {
                certified += 1;
            }
            let parallel = na == nb && ca != cb;
            if parallel && s.certified {
                assert_eq!(s.branches, 0, "{what}");
            }
        }
    }
    assert_eq!(runs, 136);
    println!("{certified} of {runs} pairs certified");
    // Coplanar control points, exactly: coincident.
    for (a, b) in [
        ("plane-z0", "plane-z0-bs"),
        ("plane-z0", "plane-z0-bs-flipped"),
        ("plane-z0", "coplanar-half"),
        ("ok-bilinear", "plane-z0-bs"),
        ("sliver-0", "tiny-1e-300"),
        ("sliver-1e-12", "denormal"),
    ] {
        let r = intersect_models(&model(a), Some(&model(b)), &prm, &|_, _| {}).unwrap();
        assert_eq!(r.summary.coincident_pairs, 1, "{a} x {b}");
        assert_eq!(r.summary.branches, 0, "{a} x {b}");
    }
    // Crossing inside both patches: x + y + z = √3 meets z = 0 along x + y = √3 (inside
    // [-1, 1]² only near the corner (1, 1)) and z = ½ along x + y = √3 − ½.
    for b in ["plane-z0", "plane-z05"] {
        let r = intersect_models(&model("plane-diag"), Some(&model(b)), &prm, &|_, _| {}).unwrap();
        assert!(r.summary.certified, "plane-diag x {b}");
        assert_eq!(r.summary.branches, 1, "plane-diag x {b}");
    }
}

#[test]
fn an_arc_of_infinite_radius_is_refused_with_its_entry() {
    let p = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/data/faulty/arc-huge.igs");
    let e = read_model(&p).expect_err("refused").to_string();
    assert!(e.contains("DE 7") && e.contains("radius"), "{e}");
}
