//! The readers' accounts of every curve kind and every IGES entry (`Model::accounts`): for
//! every STEP and IGES file under `tests/data/public` and `tests/data/faulty` that reads,
//! each kind balances and its `read` equals the count found by scanning the file text here,
//! independently of the reader (STEP: each ISO 10303-42 curve kind; IGES: every entity type
//! of the directory section). Hand-made files check the outcomes known from construction:
//! free curves of kinds not converted are unsupported with their ids, curves of edges are
//! used; IGES colour definitions are unsupported attributes, transforms used; and the IGES
//! status field is read right-aligned (IGES 5.3 §2.2.4.4.9), so a 126 curve is free exactly
//! when its subordinate switch is `00`.

use std::path::{Path, PathBuf};
mod common;
use common::scan::{iges_counts, step_count, step_instances};
use vericad::model::Model;
use vericad::model::accounting::Skipped;

/// ISO 10303-42 curve kinds (the instantiable subtypes of `curve`).
const STEP_CURVES: [&str; 25] = [
    "B_SPLINE_CURVE_WITH_KNOTS",
    "BEZIER_CURVE",
    "UNIFORM_CURVE",
    "QUASI_UNIFORM_CURVE",
    "LINE",
    "CIRCLE",
    "ELLIPSE",
    "HYPERBOLA",
    "PARABOLA",
    "POLYLINE",
    "TRIMMED_CURVE",
    "COMPOSITE_CURVE",
    "COMPOSITE_CURVE_ON_SURFACE",
    "COMPOSITE_CURVE_SEGMENT",
    "BOUNDARY_CURVE",
    "OUTER_BOUNDARY_CURVE",
    "PCURVE",
    "BOUNDED_PCURVE",
    "DEGENERATE_PCURVE",
    "SURFACE_CURVE",
    "SEAM_CURVE",
    "INTERSECTION_CURVE",
    "BOUNDED_SURFACE_CURVE",
    "OFFSET_CURVE_3D",
    "OFFSET_CURVE_2D",
];

fn data(dir: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(dir)
}

/// Every file under `dir` (recursively) whose extension is one of `exts`.
fn files(dir: &Path, exts: &[&str], out: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            files(&p, exts, out);
        } else if p
            .extension()
            .and_then(|x| x.to_str())
            .is_some_and(|x| exts.contains(&x.to_ascii_lowercase().as_str()))
        {
            out.push(p);
        }
    }
}

fn all(exts: &[&str]) -> Vec<PathBuf> {
    let mut out = Vec::new();
    files(&data("public"), exts, &mut out);
    files(&data("faulty"), exts, &mut out);
    out.sort();
    out
}

fn balanced(file: &str, m: &Model) {
    m.accounts.check().unwrap_or_else(|e| panic!("{file}: {e}"));
}

fn ids(v: &[Skipped]) -> Vec<&str> {
    v.iter().map(|s| s.id.as_str()).collect()
}

#[test]
fn every_step_curve_kind_is_accounted_in_every_file() {
    let (mut read, mut curves) = (0, 0);
    for p in all(&["step", "stp"]) {
        let name = p.display().to_string();
        let text = String::from_utf8_lossy(&std::fs::read(&p).unwrap()).into_owned();
        let Ok(m) = vericad::io::step::read(&p) else {
            continue;
        };
        read += 1;
        balanced(&name, &m);
        let inst = step_instances(&text);
        for k in STEP_CURVES {
            let n = step_count(&inst, k);
            let a = m.accounts.kinds.get(k);
            assert_eq!(a.map_or(0, |a| a.read), n, "{name}: {k}");
            curves += n;
        }
    }
    assert!(read >= 10, "{read} STEP files read");
    assert!(curves > 300, "{curves} curve instances");
}

#[test]
fn every_iges_entry_is_accounted_in_every_file() {
    let mut read = 0;
    for p in all(&["igs", "iges"]) {
        let name = p.display().to_string();
        let text = String::from_utf8_lossy(&std::fs::read(&p).unwrap()).into_owned();
        let Ok(m) = vericad::io::iges::read(&p) else {
            continue;
        };
        read += 1;
        balanced(&name, &m);
        let counts = iges_counts(&text);
        let kinds: Vec<String> = counts.keys().map(|t| t.to_string()).collect();
        let mut accounted: Vec<String> = m.accounts.kinds.keys().cloned().collect();
        accounted.sort_by_key(|k| k.parse::<i64>().unwrap());
        assert_eq!(accounted, kinds, "{name}");
        for (t, n) in counts {
            assert_eq!(m.accounts.kinds[&t.to_string()].read, n, "{name}: {t}");
        }
    }
    assert!(read >= 10, "{read} IGES files read");
}

/// A STEP file of `data` lines.
fn step(data: &str) -> Model {
    let text = format!(
        "ISO-10303-21;\nHEADER;\nFILE_SCHEMA(('AUTOMOTIVE_DESIGN'));\nENDSEC;\nDATA;\n{data}ENDSEC;\nEND-ISO-10303-21;\n"
    );
    let m = vericad::io::step::from_str(&text, "x.step").unwrap();
    balanced("x.step", &m);
    m
}

const FRAME: &str = "#1=CARTESIAN_POINT('',(0.,0.,0.));\n#2=DIRECTION('',(0.,0.,1.));\n\
    #3=DIRECTION('',(1.,0.,0.));\n#4=AXIS2_PLACEMENT_3D('',#1,#2,#3);\n\
    #5=VECTOR('',#3,1.);\n#6=CARTESIAN_POINT('',(1.,0.,0.));\n";

#[test]
fn free_curves_of_kinds_not_converted_are_unsupported_with_ids() {
    // A wireframe: a free line and circle in a curve set of a shape representation, a
    // polyline, and a trimmed curve whose basis is a second line (used by the trim).
    let m = step(&format!(
        "{FRAME}#10=LINE('',#1,#5);\n#11=CIRCLE('',#4,2.);\n\
         #12=POLYLINE('',(#1,#6));\n#13=LINE('',#6,#5);\n\
         #14=TRIMMED_CURVE('',#13,(PARAMETER_VALUE(0.)),(PARAMETER_VALUE(1.)),.T.,.PARAMETER.);\n\
         #15=GEOMETRIC_CURVE_SET('',(#10,#11,#14));\n\
         #16=SHAPE_REPRESENTATION('',(#15,#12,#4),#17);\n"
    ));
    let k = &m.accounts.kinds;
    assert_eq!(ids(&k["LINE"].unsupported), ["#10"]);
    assert_eq!((k["LINE"].read, k["LINE"].used), (2, 1));
    assert_eq!(ids(&k["CIRCLE"].unsupported), ["#11"]);
    assert_eq!(ids(&k["POLYLINE"].unsupported), ["#12"]);
    assert_eq!(ids(&k["TRIMMED_CURVE"].unsupported), ["#14"]);
    assert!(k["LINE"].unsupported[0].reason.contains("free curve"));
    assert_eq!(m.accounts.total().unsupported.len(), 4);
    assert!(m.curves.is_empty());
    let lines = m.accounts.lines().join("\n");
    assert!(lines.contains("POLYLINE: read 1, converted 0, used 0, unsupported 1 (#12)"));
}

#[test]
fn curves_of_edges_are_used_and_refused_ones_named() {
    // abc-0000.step: a part of 33 edges whose curves are its 12 lines and 21 circles, every
    // one the geometry of an edge (counted in the text below).
    let p = data("public").join("abc-0000.step");
    let text = std::fs::read_to_string(&p).unwrap();
    let m = vericad::io::step::read(&p).unwrap();
    let inst = step_instances(&text);
    let (lines, circles) = (step_count(&inst, "LINE"), step_count(&inst, "CIRCLE"));
    assert_eq!((lines, circles), (12, 21));
    assert_eq!(step_count(&inst, "EDGE_CURVE"), lines + circles);
    let k = &m.accounts.kinds;
    assert_eq!((k["LINE"].used, k["CIRCLE"].used), (lines, circles));
    // One face whose edge lies on a hyperbola (not converted by the edge reader): the
    // hyperbola is refused with the B-rep reader's reason, not counted as used.
    let m = step(&format!(
        "{FRAME}#20=HYPERBOLA('',#4,1.,1.);\n#21=VERTEX_POINT('',#1);\n\
         #22=EDGE_CURVE('',#21,#21,#20,.T.);\n#23=ORIENTED_EDGE('',*,*,#22,.T.);\n\
         #24=EDGE_LOOP('',(#23));\n#25=FACE_OUTER_BOUND('',#24,.T.);\n#26=PLANE('',#4);\n\
         #27=ADVANCED_FACE('',(#25),#26,.T.);\n"
    ));
    let h = &m.accounts.kinds["HYPERBOLA"];
    assert_eq!(h.read, 1);
    assert_eq!(h.used, 0);
    let refused: Vec<&Skipped> = h.unsupported.iter().chain(&h.invalid).collect();
    assert_eq!(refused.len(), 1);
    assert_eq!(refused[0].id, "#20");
    assert!(
        refused[0].reason.contains("HYPERBOLA"),
        "{}",
        refused[0].reason
    );
}

/// `gmsh-cube1000.igs` with the status fields (columns 65–72) of directory lines `des`
/// replaced.
fn cube_with_status(changes: &[(&str, &str)]) -> Model {
    let text = std::fs::read_to_string(data("public").join("gmsh-cube1000.igs")).unwrap();
    let mut lines: Vec<String> = text.lines().map(String::from).collect();
    for (de, status) in changes {
        let d = lines
            .iter()
            .position(|l| l.len() >= 80 && l[72..80] == format!("D{de:>7}"))
            .expect("directory line");
        assert_eq!(lines[d][0..8].trim(), "126");
        lines[d].replace_range(64..72, status);
    }
    let m = vericad::io::iges::from_str(&lines.join("\n"), "x.igs").unwrap();
    balanced("x.igs", &m);
    m
}

/// DE numbers of the 126 entries of `gmsh-cube1000.igs`, from the text.
fn cube_126() -> Vec<String> {
    let text = std::fs::read_to_string(data("public").join("gmsh-cube1000.igs")).unwrap();
    text.lines()
        .filter(|l| l.len() >= 80 && &l[72..73] == "D" && l[0..8].trim() == "126")
        .map(|l| l[73..80].trim().to_string())
        .filter(|s| s.parse::<usize>().unwrap() % 2 == 1)
        .collect()
}

#[test]
fn iges_status_is_read_right_aligned() {
    let des = cube_126();
    assert_eq!(des.len(), 48);
    // As published: every 126 is physically dependent (status 00010001 or 00010501): part
    // of a face's boundary, not a free curve.
    let m = vericad::io::iges::read(&data("public").join("gmsh-cube1000.igs")).unwrap();
    assert!(m.curves.is_empty());
    assert_eq!(m.accounts.kinds["126"].used, 48);
    // Leading blanks instead of zeros: `   10000` is 00010000, still dependent.
    let m = cube_with_status(&[(&des[0], "   10000"), (&des[1], "   10501")]);
    assert!(m.curves.is_empty());
    assert_eq!(m.accounts.kinds["126"].used, 48);
    // An independent curve (subordinate switch 00), with leading blanks or zeros.
    let m = cube_with_status(&[(&des[0], "       0"), (&des[5], "00000001")]);
    let names: Vec<String> = m.curves.iter().map(|c| c.name.clone()).collect();
    assert_eq!(names, [format!("DE {}", des[0]), format!("DE {}", des[5])]);
    assert_eq!(
        (
            m.accounts.kinds["126"].converted,
            m.accounts.kinds["126"].used
        ),
        (2, 46)
    );
}

#[test]
fn iges_colours_are_unsupported_attributes() {
    // gmsh-sphere_Rhino3D_default.igs: one 128 surface, six colour definitions (314) and
    // six properties (406), counted in the text.
    let p = data("public").join("gmsh-sphere_Rhino3D_default.igs");
    let counts = iges_counts(&std::fs::read_to_string(&p).unwrap());
    assert_eq!((counts[&314], counts[&406]), (6, 6));
    let m = vericad::io::iges::read(&p).unwrap();
    let k = &m.accounts.kinds;
    assert_eq!(k["314"].unsupported.len(), 6);
    assert!(k["314"].unsupported[0].reason.contains("colour definition"));
    assert_eq!(k["406"].unsupported.len(), 6);
    assert_eq!(k["128"].converted, 1);
    // Transformation matrices (124) are used by the entries whose directory field 7
    // (columns 49–56 of the first line) points to them, counted in the text.
    let p = data("public").join("occt-written/abc-0000-faces.igs");
    let text = std::fs::read_to_string(&p).unwrap();
    let (mut matrices, mut targets) = (Vec::new(), std::collections::BTreeSet::new());
    for l in text.lines().filter(|l| l.len() >= 80 && &l[72..73] == "D") {
        let seq: usize = l[73..80].trim().parse().unwrap();
        if seq % 2 == 1 {
            if l[0..8].trim() == "124" {
                matrices.push(seq);
            }
            targets.insert(l[48..56].trim().parse::<usize>().unwrap_or(0));
        }
    }
    let pointed = matrices.iter().filter(|d| targets.contains(d)).count();
    assert!(pointed > 0);
    let m = vericad::io::iges::read(&p).unwrap();
    let a = &m.accounts.kinds["124"];
    assert_eq!((a.read, a.used), (matrices.len(), pointed));
    assert_eq!(a.unsupported.len(), matrices.len() - pointed);
}

#[test]
fn iges_entries_without_parameter_data_are_invalid_with_ids() {
    // The parameter line of colour DE 1 (columns 65–72 hold the DE it belongs to) removed:
    // the entry is still in the directory, so the account must name it.
    let p = data("public").join("gmsh-sphere_Rhino3D_default.igs");
    let text = std::fs::read_to_string(&p).unwrap();
    let kept: Vec<&str> = text
        .lines()
        .filter(|l| {
            !(l.len() >= 80 && &l[72..73] == "P" && l[64..72].trim().parse::<u32>() == Ok(1))
        })
        .collect();
    assert_eq!(kept.len() + 1, text.lines().count());
    let m = vericad::io::iges::from_str(&kept.join("\n"), "x.igs").unwrap();
    balanced("x.igs", &m);
    let a = &m.accounts.kinds["314"];
    assert_eq!((a.read, a.unsupported.len()), (6, 5));
    assert_eq!(ids(&a.invalid), ["DE 1"]);
    assert!(a.invalid[0].reason.contains("no parameter data"));
}
