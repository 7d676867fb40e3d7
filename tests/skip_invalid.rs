//! Reading with invalid faces skipped (`--skip-invalid`, `io::ReadOptions`): one face of a
//! real STEP part and of a real IGES part is made invalid by reversing two of its knots in the
//! file text; by default the file is refused naming the entity; when skipping, every other face
//! is read exactly as from the intact file, the skipped one is accounted `invalid` with its id,
//! named in a warning and kept in the B-rep as a face with an `InvalidSurface` issue.

use std::path::Path;
use std::process::Command;
use vericad::io::ReadOptions;
use vericad::model::Model;

fn public(name: &str) -> String {
    let p = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/public")
        .join(name);
    std::fs::read_to_string(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()))
}

const SKIP: ReadOptions = ReadOptions {
    skip_invalid_faces: true,
};

/// The surfaces of `m` by source id, with their control points and weights.
fn by_source(m: &Model) -> Vec<(String, Vec<[f64; 3]>, Vec<f64>)> {
    m.surfaces
        .iter()
        .map(|s| {
            let (p, w) = s.nurbs.points_weights();
            (s.source.clone().unwrap_or_default(), p, w)
        })
        .collect()
}

/// What a lenient read of the corrupted text must hold against the strict read of the intact
/// text: exactly one face fewer, all others bit for bit, the missing one named invalid.
fn check_one_face_skipped(intact: &Model, skipped: &Model, kind: &str, reason_part: &str) {
    let all = by_source(intact);
    let kept = by_source(skipped);
    assert_eq!(kept.len() + 1, all.len());
    let missing: Vec<_> = all.iter().filter(|s| !kept.contains(s)).collect();
    assert_eq!(missing.len(), 1, "exactly one face differs");
    let face = &missing[0].0;
    assert!(
        skipped
            .warnings
            .iter()
            .any(|w| w.starts_with("invalid face")
                && w.contains(face.as_str())
                && w.contains(reason_part)),
        "a warning names {face}: {:?}",
        skipped.warnings
    );
    skipped.accounts.check().expect("the accounts balance");
    let acc = &skipped.accounts.kinds[kind];
    assert_eq!(acc.invalid.len(), 1, "{acc:?}");
    assert!(acc.invalid[0].reason.contains(reason_part), "{acc:?}");
    assert_eq!(
        acc.converted + 1,
        intact.accounts.kinds[kind].converted,
        "{acc:?}"
    );
}

#[test]
fn a_step_part_with_one_invalid_face_is_read_without_it() {
    let text = public("gmsh-t20_data.step");
    let knots = "(2.09439510241284,3.14159264302763)";
    assert_eq!(text.matches(knots).count(), 1);
    let bad = text.replace(knots, "(3.14159264302763,2.09439510241284)");
    let intact = vericad::io::step::from_str(&text, "t20").expect("the intact part reads");
    let refused = vericad::io::step::from_str_with(&bad, "t20", ReadOptions::default())
        .expect_err("by default a file with an invalid face is refused");
    assert!(refused.location.starts_with('#'), "{refused}");
    let m = vericad::io::step::from_str_with(&bad, "t20", SKIP).expect("read, skipping");
    check_one_face_skipped(&intact, &m, "B_SPLINE_SURFACE_WITH_KNOTS", "knot");
    // The B-rep keeps every face; the skipped one carries the issue, naming its face.
    let (bi, bs) = (intact.brep.as_ref().unwrap(), m.brep.as_ref().unwrap());
    assert_eq!(bs.faces.len(), bi.faces.len());
    let issues: Vec<_> = (bs.report.issues.iter())
        .filter(|i| matches!(i.kind, vericad::brep::IssueKind::InvalidSurface(_)))
        .collect();
    assert_eq!(issues.len(), 1, "{issues:?}");
    let face = issues[0].face.as_deref().expect("the issue names its face");
    assert!(
        m.warnings
            .iter()
            .any(|w| w.contains(&format!("face {face}"))),
        "{:?}",
        m.warnings
    );
}

#[test]
fn an_iges_part_with_one_invalid_face_is_read_without_it() {
    let text = public("gmsh-cube1000.igs");
    // The first B-spline surface (128): its u knots 0, 0, 1, 1 become 0, 0, 1, 0.5.
    let line = text.lines().find(|l| l.starts_with("128,")).unwrap();
    let fixed = line.replacen("0.0D0,0.0D0,1.0D0,1.0D0", "0.0D0,0.0D0,1.0D0,0.5D0", 1);
    assert_ne!(fixed, line);
    assert_eq!(fixed.len(), line.len());
    let bad = text.replacen(line, &fixed, 1);
    let intact = vericad::io::iges::from_str(&text, "cube").expect("the intact part reads");
    let refused = vericad::io::iges::from_str_with(&bad, "cube", ReadOptions::default())
        .expect_err("by default a file with an invalid face is refused");
    assert!(refused.location.starts_with("DE"), "{refused}");
    let m = vericad::io::iges::from_str_with(&bad, "cube", SKIP).expect("read, skipping");
    check_one_face_skipped(&intact, &m, "143", "knot");
}

/// The flag on the command line: refused (exit 2) without it, read with it, the invalid face
/// counted in `info`'s accounts line.
#[test]
fn the_command_line_flag_skips_and_reports() {
    let text = public("gmsh-t20_data.step");
    let bad = text.replace(
        "(2.09439510241284,3.14159264302763)",
        "(3.14159264302763,2.09439510241284)",
    );
    let dir = std::env::temp_dir().join(format!("vericad-skip-invalid-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let f = dir.join("t20-bad.step");
    std::fs::write(&f, bad).unwrap();
    let run = |skip: bool| {
        let mut c = Command::new(env!("CARGO_BIN_EXE_vericad"));
        c.arg("info").arg(&f);
        if skip {
            c.arg("--skip-invalid");
        }
        c.output().expect("vericad runs")
    };
    let strict = run(false);
    assert_eq!(strict.status.code(), Some(2));
    let lenient = run(true);
    assert_eq!(lenient.status.code(), Some(0));
    let out = String::from_utf8_lossy(&lenient.stdout);
    assert!(out.contains("1 invalid"), "{out}");
    assert!(out.contains("skipped (--skip-invalid)"), "{out}");
    std::fs::remove_dir_all(&dir).ok();
}
