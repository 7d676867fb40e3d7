//! The readers' entity accounts (`Model::accounts`): for every public STEP and IGES file the
//! account of each kind balances (read = converted + used + unsupported + invalid) and its
//! `read` equals the number of instances of that kind found by scanning the file text here
//! (independently of the reader); faulty files name their invalid and unsupported entities
//! by id; `vericad info` prints the account and `info --json` carries it.

use std::path::{Path, PathBuf};
mod common;
use common::scan::{iges_counts, step_count, step_instances};
use vericad::model::Model;
use vericad::model::accounting::KindAccount;

fn path(dir: &str, name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(dir)
        .join(name)
}

/// STEP surface and free-curve kinds the account must cover whenever the file holds them.
const STEP_KINDS: [&str; 15] = [
    "B_SPLINE_SURFACE_WITH_KNOTS",
    "RECTANGULAR_TRIMMED_SURFACE",
    "PLANE",
    "CYLINDRICAL_SURFACE",
    "CONICAL_SURFACE",
    "SPHERICAL_SURFACE",
    "TOROIDAL_SURFACE",
    "SURFACE_OF_REVOLUTION",
    "SURFACE_OF_LINEAR_EXTRUSION",
    "OFFSET_SURFACE",
    "CURVE_BOUNDED_SURFACE",
    "DEGENERATE_TOROIDAL_SURFACE",
    "SURFACE_REPLICA",
    "ORIENTED_SURFACE",
    "B_SPLINE_CURVE_WITH_KNOTS",
];

/// IGES surface, face and curve entity types the account must cover.
const IGES_KINDS: [i64; 22] = [
    100, 102, 104, 108, 110, 112, 114, 118, 120, 122, 126, 128, 130, 140, 143, 144, 190, 192, 194,
    196, 198, 510,
];

fn balanced(file: &str, m: &Model) {
    m.accounts.check().unwrap_or_else(|e| panic!("{file}: {e}"));
    for (k, a) in &m.accounts.kinds {
        assert_eq!(
            a.read,
            a.converted + a.used + a.unsupported.len() + a.invalid.len(),
            "{file}: {k}"
        );
    }
}

fn read_of(m: &Model, kind: &str) -> usize {
    m.accounts.kinds.get(kind).map_or(0, |a| a.read)
}

#[test]
fn public_step_files_account_for_every_instance() {
    let mut checked = 0;
    for name in [
        "abc-0000.step",
        "gmsh-periodic_u_cst.step",
        "gmsh-t20_data.step",
        "occt-bug28366_fuselage.stp",
    ] {
        let p = path("public", name);
        let text = std::fs::read_to_string(&p).unwrap();
        let m = vericad::io::step::read(&p).unwrap();
        balanced(name, &m);
        let inst = step_instances(&text);
        assert!(!inst.is_empty(), "{name}");
        for k in STEP_KINDS {
            assert_eq!(read_of(&m, k), step_count(&inst, k), "{name}: {k}");
        }
        // Kinds the reader added (face surfaces of other types) match the text too.
        for (k, a) in &m.accounts.kinds {
            assert_eq!(a.read, step_count(&inst, k), "{name}: {k}");
            checked += a.read;
        }
        // Every converted free curve is a model curve.
        let curves = m
            .accounts
            .kinds
            .get("B_SPLINE_CURVE_WITH_KNOTS")
            .map_or(0, |a| a.converted);
        assert_eq!(curves, m.curves.len(), "{name}");
        assert!(m.accounts.total().converted > 0, "{name}");
    }
    assert!(checked > 0);
}

#[test]
fn public_iges_files_account_for_every_entry() {
    for name in [
        "gmsh-cube1000.igs",
        "gmsh-sphere_Rhino3D_default.igs",
        "occt-BUC50025.igs",
        "occt-bad_header.igs",
    ] {
        let p = path("public", name);
        let text = std::fs::read_to_string(&p).unwrap();
        let m = vericad::io::iges::read(&p).unwrap();
        balanced(name, &m);
        let counts = iges_counts(&text);
        assert!(!counts.is_empty(), "{name}");
        for t in IGES_KINDS {
            let k = t.to_string();
            assert_eq!(
                read_of(&m, &k),
                counts.get(&t).copied().unwrap_or(0),
                "{name}: {k}"
            );
        }
        // Converted faces and surfaces are the model's surfaces, converted 126 its curves.
        let conv = |a: &KindAccount| a.converted;
        let surfaces: usize = m
            .accounts
            .kinds
            .iter()
            .filter(|(k, _)| *k != "126")
            .map(|(_, a)| conv(a))
            .sum();
        assert_eq!(surfaces, m.surfaces.len(), "{name}");
        assert_eq!(
            m.accounts.kinds.get("126").map_or(0, conv),
            m.curves.len(),
            "{name}"
        );
    }
}

fn ids(v: &[vericad::model::accounting::Skipped]) -> Vec<&str> {
    v.iter().map(|s| s.id.as_str()).collect()
}

#[test]
fn faulty_files_name_their_invalid_and_unsupported_entities() {
    // Two B-spline curves with decreasing knots and a degree beyond the points: invalid.
    let m = vericad::io::step::read(&path("faulty", "curve-invalid-dropped.step")).unwrap();
    balanced("curve-invalid-dropped.step", &m);
    let c = &m.accounts.kinds["B_SPLINE_CURVE_WITH_KNOTS"];
    assert_eq!((c.read, c.converted), (3, 1));
    assert_eq!(ids(&c.invalid), ["#203", "#204"]);
    assert!(c.invalid.iter().all(|s| !s.reason.is_empty()));
    assert_eq!(m.accounts.kinds["B_SPLINE_SURFACE_WITH_KNOTS"].converted, 1);

    // Offset surface unsupported; the trimmed cylinder converted, its basis used; the
    // offset's basis sphere used.
    let m = vericad::io::step::read(&path("faulty", "bare-rts-offset.step")).unwrap();
    balanced("bare-rts-offset.step", &m);
    let k = &m.accounts.kinds;
    assert_eq!(ids(&k["OFFSET_SURFACE"].unsupported), ["#17"]);
    assert_eq!(k["RECTANGULAR_TRIMMED_SURFACE"].converted, 1);
    assert_eq!(k["CYLINDRICAL_SURFACE"].used, 1);
    assert_eq!(k["SPHERICAL_SURFACE"].used, 1);
    assert_eq!(m.accounts.total().unsupported.len(), 1);

    // A B-rep face (510) on a 128 surface, its edge a 110 line.
    let m = vericad::io::iges::read(&path("faulty", "brep-510-face.igs")).unwrap();
    balanced("brep-510-face.igs", &m);
    let k = &m.accounts.kinds;
    assert_eq!((k["510"].read, k["510"].converted), (1, 1));
    assert_eq!((k["128"].read, k["128"].used), (1, 1));
    assert_eq!((k["110"].read, k["110"].used), (1, 1));
}

#[test]
fn unconverted_surfaces_are_named_unsupported() {
    // A bare patch set: an extrusion of a circle (profile not a B-spline: not converted)
    // and a plane.
    let text = "ISO-10303-21;\nHEADER;\nFILE_SCHEMA(('AUTOMOTIVE_DESIGN'));\nENDSEC;\nDATA;\n\
        #1=CARTESIAN_POINT('',(0.,0.,0.));\n#2=DIRECTION('',(0.,0.,1.));\n\
        #3=DIRECTION('',(1.,0.,0.));\n#4=AXIS2_PLACEMENT_3D('',#1,#2,#3);\n\
        #5=CIRCLE('',#4,1.);\n#6=VECTOR('',#2,2.);\n\
        #7=SURFACE_OF_LINEAR_EXTRUSION('',#5,#6);\n#8=PLANE('',#4);\n\
        ENDSEC;\nEND-ISO-10303-21;\n";
    let m = vericad::io::step::from_str(text, "x.step").unwrap();
    balanced("x.step", &m);
    let k = &m.accounts.kinds;
    assert_eq!(ids(&k["SURFACE_OF_LINEAR_EXTRUSION"].unsupported), ["#7"]);
    assert_eq!(k["PLANE"].converted, 1);
    assert_eq!(m.surfaces.len(), 1);
    let inst = step_instances(text);
    assert_eq!(step_count(&inst, "PLANE"), 1);
    assert_eq!(step_count(&inst, "SURFACE_OF_LINEAR_EXTRUSION"), 1);
}

#[test]
fn step_scan_sees_complex_instances_and_skips_strings() {
    let text = "DATA;\n#1=(BOUNDED_SURFACE()B_SPLINE_SURFACE(1,1,((#2)),.U.,.F.,.F.,.F.)\
        B_SPLINE_SURFACE_WITH_KNOTS((2),(2),(0.,1.),(0.,1.),.U.));\n\
        #3=PLANE('a;#4=PLANE(',#5);\nENDSEC;";
    let inst = step_instances(text);
    assert_eq!(inst.len(), 2);
    assert_eq!(step_count(&inst, "B_SPLINE_SURFACE_WITH_KNOTS"), 1);
    assert_eq!(step_count(&inst, "BOUNDED_SURFACE"), 1);
    assert_eq!(step_count(&inst, "PLANE"), 1);
}

#[test]
fn independent_iges_entries_not_converted_are_named_unsupported() {
    // The first line (DE 3) of a public file marked independent (status field, columns
    // 65–72, all zeros): a free line, which the reader does not convert on its own.
    let text = std::fs::read_to_string(path("public", "occt-bad_header.igs")).unwrap();
    let mut lines: Vec<String> = text.lines().map(String::from).collect();
    let d3 = lines
        .iter()
        .position(|l| l.len() >= 80 && &l[72..80] == "D      3")
        .expect("DE 3");
    assert_eq!(lines[d3][0..8].trim(), "110");
    lines[d3].replace_range(64..72, "00000000");
    let m = vericad::io::iges::from_str(&lines.join("\n"), "x.igs").unwrap();
    balanced("x.igs", &m);
    let a = &m.accounts.kinds["110"];
    assert_eq!(ids(&a.unsupported), ["DE 3"]);
    assert_eq!((a.read, a.used), (8, 7));
    assert_eq!(iges_counts(&text)[&110], 8);
}

fn vericad(args: &[&str]) -> String {
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_vericad"))
        .args(args)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    String::from_utf8(o.stdout).unwrap()
}

#[test]
fn info_prints_the_accounts() {
    let f = path("faulty", "bare-rts-offset.step");
    let f = f.to_str().unwrap();
    let text = vericad(&["info", f]);
    assert!(
        text.contains("OFFSET_SURFACE: read 1, converted 0, used 0, unsupported 1 (#17)"),
        "{text}"
    );
    assert!(
        text.contains(
            "total: 4 entities of 4 kind(s) read, 1 converted, 2 used, 1 unsupported, 0 invalid"
        ),
        "{text}"
    );
    let json: serde_json::Value = serde_json::from_str(&vericad(&["info", f, "--json"])).unwrap();
    let k = &json["accounts"]["kinds"];
    assert_eq!(k["OFFSET_SURFACE"]["unsupported"][0]["id"], "#17");
    assert_eq!(k["CYLINDRICAL_SURFACE"]["used"], 1);
    assert_eq!(k["RECTANGULAR_TRIMMED_SURFACE"]["converted"], 1);
}
