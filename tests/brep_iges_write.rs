//! IGES writing of a B-rep model (IGES 5.3 B-rep entities): one vertex list (502), one edge
//! list (504) holding each edge once, a loop (508) per loop, a face (510) per face whose surface
//! (128) is the face's surface bit for bit, a shell (514) per shell and a solid (186) per solid —
//! counts from the STEP file's reading with its seams made explicit; and what cannot be
//! written is named.

use std::path::Path;
use vericad::brep::LoopKind;
use vericad::brep::seam_edges::explicit_seams;
use vericad::io::iges::write::BrepForm;
use vericad::io::{iges, step};

fn public(name: &str) -> vericad::model::Model {
    let p = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/public")
        .join(name);
    step::read(&p).unwrap_or_else(|e| panic!("{name}: {e}"))
}

#[test]
fn the_brep_is_written_as_iges_brep_entities() {
    for name in [
        "abc-0000.step",
        "gmsh-t20_data.step",
        "gmsh-periodic_u_cst.step",
    ] {
        let m = public(name);
        // What is written: the B-rep with its seams made explicit (tests/brep_seam_edges.rs),
        // pole edges as vertex uses (not in the edge list).
        let seamed = explicit_seams(&m, m.brep.as_ref().unwrap(), &mut Vec::new());
        let b = &seamed.brep;
        let (text, notes) = iges::write::write_with(&m, name, BrepForm::BrepEntities);
        // The one note: pcurves made by projection, every one proven.
        let (projected, rest): (Vec<_>, Vec<_>) = notes
            .iter()
            .partition(|n| n.starts_with("pcurves made by projecting"));
        assert!(rest.is_empty(), "{name}: {rest:?}");
        for p in projected {
            let counts: Vec<usize> = p
                .split(|c: char| !c.is_ascii_digit())
                .filter(|w| !w.is_empty())
                .take(3)
                .map(|w| w.parse().unwrap())
                .collect();
            assert!(
                counts[0] == counts[1] && counts[1] == counts[2] && !p.contains("left to"),
                "{name}: {p}"
            );
        }
        let back = iges::from_str(&text, "written.igs").unwrap_or_else(|e| panic!("{name}: {e}"));
        let n = |t: &str| back.source_entities.get(t).copied().unwrap_or(0);
        let loops: usize = b.faces.iter().map(|f| f.loops.len()).sum();
        let closed = b.shells.iter().filter(|s| s.closed).count();
        assert_eq!(
            (
                n("502 (form 1)"),
                n("504 (form 1)"),
                n("508 (form 1)"),
                n("510 (form 1)")
            ),
            (1, 1, loops, b.faces.len()),
            "{name}"
        );
        assert_eq!(
            (n("514 (form 1)"), n("514 (form 2)"), n("186 (form 0)")),
            (closed, b.shells.len() - closed, b.solids.len()),
            "{name}"
        );
        // Every edge once in the edge list, every vertex once in the vertex list.
        let flat: String = text
            .lines()
            .filter(|l| l.len() == 80 && &l[72..73] == "P")
            .map(|l| l[..64].trim_end())
            .collect();
        assert!(
            flat.contains(&format!("504,{},", b.edges.len() - seamed.poles.len())),
            "{name}: edge list"
        );
        assert!(
            flat.contains(&format!("502,{},", b.vertices.len())),
            "{name}: vertex list"
        );
        // Each edge use is one 508 entry.
        let uses: usize = b
            .faces
            .iter()
            .flat_map(|f| &f.loops)
            .map(|l| match &l.kind {
                LoopKind::Edges(e) => e.len(),
                LoopKind::Vertex(_) => 0,
            })
            .sum();
        assert_eq!(uses, b.counts().oriented_edges, "{name}");
        // The faces' surfaces, in order and bit for bit.
        assert_eq!(back.surfaces.len(), b.faces.len());
        for (f, s) in b.faces.iter().zip(&back.surfaces) {
            let a = &m.surfaces[f.surface.unwrap()].nurbs;
            let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            let (pa, wa) = a.points_weights();
            let (pb, wb) = s.nurbs.points_weights();
            assert_eq!(
                bits(&pa.concat()),
                bits(&pb.concat()),
                "{name}: face {}",
                f.source
            );
            assert_eq!(bits(&wa), bits(&wb), "{name}: face {}", f.source);
            assert_eq!(bits(a.hom.ku.knots()), bits(s.nurbs.hom.ku.knots()));
            assert_eq!(bits(a.hom.kv.knots()), bits(s.nurbs.hom.kv.knots()));
        }
    }
}

#[test]
fn a_face_without_a_surface_is_named() {
    // A unit square on a plane and the same loop on an offset surface (not converted).
    let data = "#1=CARTESIAN_POINT('',(0.,0.,0.));
#2=DIRECTION('',(0.,0.,1.));
#3=DIRECTION('',(1.,0.,0.));
#4=AXIS2_PLACEMENT_3D('',#1,#2,#3);
#5=PLANE('',#4);
#6=OFFSET_SURFACE('',#5,1.,.F.);
#11=CARTESIAN_POINT('',(0.,0.,0.));
#12=CARTESIAN_POINT('',(1.,0.,0.));
#21=VERTEX_POINT('',#11);
#22=VERTEX_POINT('',#12);
#26=VECTOR('',#3,1.);
#31=LINE('',#11,#26);
#32=CIRCLE('',#4,0.5);
#41=EDGE_CURVE('',#21,#22,#31,.T.);
#42=EDGE_CURVE('',#22,#21,#32,.T.);
#51=ORIENTED_EDGE('',*,*,#41,.T.);
#52=ORIENTED_EDGE('',*,*,#42,.T.);
#60=EDGE_LOOP('',(#51,#52));
#61=FACE_OUTER_BOUND('',#60,.T.);
#70=ADVANCED_FACE('',(#61),#5,.T.);
#71=ADVANCED_FACE('',(#61),#6,.T.);
#80=OPEN_SHELL('',(#70,#71));";
    let text = format!(
        "ISO-10303-21;\nHEADER;\nFILE_SCHEMA(('AUTOMOTIVE_DESIGN'));\nENDSEC;\nDATA;\n{data}\nENDSEC;\nEND-ISO-10303-21;\n"
    );
    let m = step::from_str(&text, "t.step").unwrap();
    let (igs, notes) = iges::write::write_with(&m, "t", BrepForm::BrepEntities);
    let all = notes.join("\n");
    assert!(
        all.contains("face #71 not written: its surface #6 was not converted"),
        "{all}"
    );
    assert!(all.contains("shell #80 written without face #71"), "{all}");
    let back = iges::from_str(&igs, "t.igs").unwrap();
    assert_eq!(back.source_entities.get("510 (form 1)"), Some(&1));
    assert_eq!(back.source_entities.get("514 (form 2)"), Some(&1));
}
