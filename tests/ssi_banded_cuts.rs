//! Faces whose winding loops are closed into one polygon by a cut across the seam, where the
//! straight cut from a loop's first point runs through the face's other loops: a loop that
//! folds back (an S-fold of arcs on a torus, `fold_*.step`), and a hole lying across the cut
//! (`band_hole.step`). The crossing polygon took a pocket of the face for its complement and
//! such runs were certified with a closed loop absent (or present, outside the face). The
//! polygons are now checked not to cross, and the cuts tried from other points of the loops.
//!
//! Ground truth from the construction (torus R = 3, r = 1 about the z axis; the files'
//! generator placed each plane patch 0.005 inside the tangent plane at a chosen torus point,
//! so that their intersection is one closed loop around that point, within 0.3 of it: semi-axes
//! sqrt(2 · 0.005 · rho) for the principal radii rho = 1 and (3 + cos v) / cos v):
//! * `cap_pocket.json` around P(u = 292 deg, v = 0.55): in the face of `fold_comp.step` (the
//!   torus minus the band between the circle v = 0.1 and the folded loop; on the meridian
//!   u = 292 deg the face covers v in [0.4, 0.7] and [1.0, 2 pi + 0.1]), not in the face of
//!   `fold_band.step` (the band itself);
//! * `cap_h5.json` around a point of the hole (u about 5 deg, v about 0) of `band_hole.step`,
//!   the band |v| <= 30 deg minus the hole |u|, |v| <= 10 deg: not in the face.
use vericad::ssi::{SsiParams, intersect_models};

fn read(name: &str) -> vericad::model::Model {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/review4")
        .join(name);
    vericad::io::read_model(&path).unwrap()
}

/// (no missed branches claimed, certified, output points) of `a` against `b`.
fn run(a: &str, b: &str) -> (bool, bool, Vec<[f64; 3]>) {
    let r = intersect_models(&read(a), Some(&read(b)), &SsiParams::default(), &|_, _| {})
        .expect("runs");
    let pts = r
        .pairs
        .iter()
        .flat_map(|p| p.branches.iter().flat_map(|b| b.points.clone()))
        .collect();
    (r.summary.no_missed_branches, r.summary.certified, pts)
}

fn torus(u: f64, v: f64) -> [f64; 3] {
    let w = 3.0 + v.cos();
    [w * u.cos(), w * u.sin(), v.sin()]
}

#[test]
fn a_loop_in_the_pocket_of_a_folded_complement_is_found() {
    let (claimed, _, pts) = run("fold_comp.step", "cap_pocket.json");
    let c = torus((17.0f64 + 275.0).to_radians(), 0.55);
    let near = |p: &[f64; 3]| (0..3).map(|k| (p[k] - c[k]).powi(2)).sum::<f64>().sqrt() < 0.3;
    assert!(pts.iter().all(near), "an output point far from the loop");
    assert!(
        !claimed || !pts.is_empty(),
        "FALSE CLAIM: the loop around {c:?} lies in the face, the output is empty"
    );
    assert!(
        claimed,
        "the face is outlined (a cut from another point of the loops)"
    );
}

#[test]
fn a_loop_in_the_pocket_is_not_in_the_folded_band() {
    let (claimed, _, pts) = run("fold_band.step", "cap_pocket.json");
    assert!(pts.is_empty(), "output outside the face: {:?}", &pts[..1]);
    assert!(claimed);
}

#[test]
fn a_loop_in_a_hole_across_the_cut_is_not_in_the_face() {
    let (claimed, _, pts) = run("band_hole.step", "cap_h5.json");
    assert!(pts.is_empty(), "output in the hole: {:?}", &pts[..1]);
    assert!(claimed);
}

/// An IGES face on a cylinder (radius 2) whose one loop, an ellipse about (theta, z) =
/// (1.2, 2) with half-axes 0.7 and 1.0, is declared outer (510 OF = 1) but runs clockwise
/// about the surface's normal (written so for a face whose normal opposes the surface's). The
/// orientation says the face is the rest of the cylinder, the declaration the ellipse: either
/// is possible, and a run against the plane z = 2 (the truth under the declaration: the arc
/// theta in [0.5, 1.9]; under the orientation, the rest of the circle) was certified with the
/// rest. It is outlined by the orientation and not certified, the reason said.
#[test]
fn a_declared_outer_loop_running_clockwise_on_a_closed_surface_is_not_certified() {
    let r = intersect_models(
        &read("cyl_ellipse_cw_outer.igs"),
        Some(&read("plane_z2.json")),
        &SsiParams::default(),
        &|_, _| {},
    )
    .expect("runs");
    assert!(!r.summary.certified);
    assert!(
        r.summary
            .certificate
            .iter()
            .any(|c| c.contains("outlined against what their files declare")),
        "{:?}",
        r.summary.certificate
    );
}
