//! IGES writing of a B-rep model: every face a trimmed surface (144) whose surface (128) is
//! the face's surface bit for bit, with one curve on surface (142) per edge loop; what the
//! format does not hold (shells, solids, shared edges, reversed faces) is named.

use std::path::Path;
use vericad::io::{iges, step};

fn public(name: &str) -> vericad::model::Model {
    let p = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/public")
        .join(name);
    step::read(&p).unwrap_or_else(|e| panic!("{name}: {e}"))
}

#[test]
fn faces_become_trimmed_surfaces_over_the_same_surfaces() {
    for name in [
        "abc-0000.step",
        "gmsh-t20_data.step",
        "gmsh-periodic_u_cst.step",
    ] {
        let m = public(name);
        let b = m.brep.as_ref().unwrap();
        let (text, notes) = iges::write::write(&m, name);
        let back = iges::from_str(&text, "written.igs").unwrap_or_else(|e| panic!("{name}: {e}"));
        let n = |t: &str| back.source_entities.get(t).copied().unwrap_or(0);
        assert_eq!(n("144 (form 0)"), b.faces.len(), "{name}: one 144 per face");
        let edge_loops = b
            .faces
            .iter()
            .flat_map(|f| &f.loops)
            .filter(|l| matches!(l.kind, vericad::brep::LoopKind::Edges(_)))
            .count();
        assert_eq!(
            n("142 (form 0)"),
            edge_loops,
            "{name}: one 142 per edge loop"
        );
        // The faces' surfaces, in order and bit for bit.
        assert_eq!(back.surfaces.len(), b.faces.len());
        for (f, s) in b.faces.iter().zip(&back.surfaces) {
            let a = &m.surfaces[f.surface.unwrap()].nurbs;
            let (pa, wa) = a.points_weights();
            let (pb, wb) = s.nurbs.points_weights();
            assert_eq!(pa, pb, "{name}: face {}", f.source);
            assert_eq!(wa, wb, "{name}: face {}", f.source);
            assert_eq!(a.hom.ku.knots(), s.nurbs.hom.ku.knots());
            assert_eq!(a.hom.kv.knots(), s.nurbs.hom.kv.knots());
        }
        let all = notes.join("\n");
        assert!(
            all.contains("shared edges and vertices are not kept"),
            "{name}: {all}"
        );
        let reversed = b.faces.iter().filter(|f| !f.same_sense).count();
        assert_eq!(
            all.contains("with same_sense .F."),
            reversed > 0,
            "{name}: {all}"
        );
    }
}
