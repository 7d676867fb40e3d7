//! Which faces are bounded by their surface's own parameter rectangle (`brep::natural`), on
//! faces whose class is known from their construction and on public files classed by an
//! independent decision.
//!
//! - `tests/data/constructed/natural/` (written by `scripts/make_natural_faces.py`): whole
//!   cylinders and a whole cone between two circles — with one loop per circle and no seam
//!   edge, the circles' vertices away from the seam the NURBS form starts at, or with one
//!   loop through a seam edge — whole spheres (one meridian used twice, vertex loops at the
//!   poles), cones from their apex, a torus bounded by its seams are natural; a cylinder cut
//!   by two lines (an arc of 1.7 rad, one across the seam, one 0.01 rad short of the whole
//!   circle), a cylinder whose top edge touches the border only at its vertices, faces with a
//!   hole, a spherical cap are trimmed. The class is the file name's first word.
//! - Public files: the natural faces are those Open CASCADE 8.0.1 finds filling their
//!   parameter box that is their surface's whole rectangle (`scripts/occt_natural_faces.py`,
//!   which also confirms every constructed file's class).

use std::path::{Path, PathBuf};
use vericad::brep::natural::natural_faces;

fn natural_ids(path: &Path) -> Vec<String> {
    let m = vericad::io::read_model(path).unwrap();
    let b = m.brep.as_ref().expect("a B-rep");
    b.faces
        .iter()
        .zip(natural_faces(b, &m))
        .filter(|x| x.1)
        .map(|x| x.0.source.clone())
        .collect()
}

fn data(rel: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(rel)
}

#[test]
fn whole_faces_of_closed_surfaces_are_natural_and_cut_ones_trimmed() {
    let dir = data("constructed/natural");
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "step"))
        .collect();
    files.sort();
    assert_eq!(
        files.len(),
        17,
        "the constructed files in {}",
        dir.display()
    );
    let (mut natural, mut trimmed, mut wrong) = (0, 0, Vec::new());
    for f in &files {
        let name = f.file_name().unwrap().to_string_lossy().into_owned();
        let want = name.starts_with("natural-");
        assert!(want || name.starts_with("trimmed-"), "{name}");
        let m = vericad::io::read_model(f).unwrap();
        let b = m.brep.as_ref().unwrap();
        assert_eq!(b.faces.len(), 1, "{name}");
        if natural_faces(b, &m) != vec![want] {
            wrong.push(name.clone());
        }
        if want {
            natural += 1;
        } else {
            trimmed += 1;
        }
    }
    assert!(
        wrong.is_empty(),
        "classed against their construction: {wrong:?}"
    );
    assert_eq!((natural, trimmed), (10, 7));
}

#[test]
fn public_files_have_the_natural_faces_open_cascade_finds() {
    let cases: [(&str, &[&str]); 4] = [
        ("public/abc-0000.step", &["#102", "#106", "#122"]),
        (
            "public/gmsh-t20_data.step",
            &["#113", "#114", "#115", "#116", "#117", "#118"],
        ),
        ("public/occt-written/occt-assembly-cylinder.step", &["#35"]),
        ("public/gmsh-periodic_u_cst.step", &[]),
    ];
    for (file, want) in cases {
        let mut got = natural_ids(&data(file));
        got.sort();
        let mut want: Vec<String> = want.iter().map(|s| s.to_string()).collect();
        want.sort();
        assert_eq!(got, want, "{file}");
    }
}

/// A cone face bounded by one circle alone is the part between the circle and the apex: the
/// surface the reader makes for it reaches the apex, and the face's area is the cone's lateral
/// area `π r s` up to the circle (radius `r = 2 + tan 0.3` at height 1, half-angle 0.3,
/// slant `s = r / sin 0.3`; `scripts/make_natural_faces.py`). The reader used to make the
/// surface between the circle's own height and itself (the face's points span no height).
#[test]
fn a_cone_bounded_by_one_circle_runs_to_its_apex() {
    let path = data("constructed/natural/natural-cone-circle.step");
    let m = vericad::io::read_model(&path).unwrap();
    let b = m.brep.as_ref().unwrap();
    let areas = vericad::tessellate::face_areas(&m, b);
    let r = 2.0 + 0.3f64.tan();
    let exact = std::f64::consts::PI * r * r / 0.3f64.sin();
    let got = areas[0].area.expect("an area");
    assert!((got - exact).abs() <= 1e-9 * exact, "{got} against {exact}");
}
