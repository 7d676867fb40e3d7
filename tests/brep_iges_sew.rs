//! IGES files of trimmed (144) or bounded (143) faces carry no topology: every face has its own
//! copies of its boundary curves. vericad sews them into a B-rep (shared edges, vertices, a
//! shell). Oracles: the cube's construction (gmsh-cube1000.igs, a 500 mm cube from I-DEAS:
//! 8 corners, 12 edges, 6 faces of 500 × 500) and, for t20 written by Open CASCADE 8.0.1 in
//! faces mode (`IGESControl_Writer("MM", 0)`: 144/142 over 128, tests/data/public/occt-written),
//! the topology of the STEP original as Open CASCADE reads it (21 faces, 22 wires, 48 edges,
//! 28 vertices, one closed shell; face area 6365.476296 mm²).

use std::path::Path;
use vericad::geom::Point;

fn model(rel: &str) -> vericad::model::Model {
    let p = Path::new(env!("CARGO_MANIFEST_DIR")).join(rel);
    vericad::io::read_model(&p).unwrap_or_else(|e| panic!("{rel}: {e}"))
}

fn watertight(m: &vericad::model::Model) -> usize {
    let b = m.brep.as_ref().unwrap();
    let mesh = vericad::tessellate::mesh_brep(m, b, &Default::default());
    assert!(mesh.faces.iter().all(|f| f.is_ok()), "{:?}", mesh.issues(b));
    let mut uses = std::collections::BTreeMap::new();
    for t in &mesh.triangulation.triangles {
        for k in 0..3 {
            let (a, c) = (t[k], t[(k + 1) % 3]);
            *uses.entry((a.min(c), a.max(c))).or_insert(0) += 1;
        }
    }
    uses.values().filter(|n| **n != 2).count()
}

#[test]
fn the_cube_is_sewn_into_a_closed_shell_of_its_twelve_edges() {
    let m = model("tests/data/public/gmsh-cube1000.igs");
    let b = m.brep.as_ref().expect("a sewn B-rep");
    assert_eq!(b.faces.len(), 6);
    assert_eq!(b.edges.len(), 12);
    assert_eq!(b.vertices.len(), 8);
    assert_eq!(b.shells.len(), 1);
    assert!(b.shells[0].closed);
    let all: Vec<(usize, bool)> = (0..6).map(|i| (i, true)).collect();
    assert!(b.edge_uses(&all).values().all(|n| *n == 2));
    // The vertices are a cube's corners (the part is turned in space): from each corner three
    // others at the side 500, three at 500√2, one at 500√3.
    for v in &b.vertices {
        let mut d: Vec<f64> = b
            .vertices
            .iter()
            .map(|w| vericad::geom::dist(&v.point, &w.point))
            .filter(|d| *d > 0.0)
            .collect();
        d.sort_by(f64::total_cmp);
        let want = [
            1.0,
            1.0,
            1.0,
            2f64.sqrt(),
            2f64.sqrt(),
            2f64.sqrt(),
            3f64.sqrt(),
        ];
        assert_eq!(d.len(), 7);
        for (x, w) in d.iter().zip(want) {
            assert!((x - 500.0 * w).abs() < 1e-3, "{:?}: {d:?}", v.point);
        }
    }
    // Every edge is a side of the cube: 500 long between its vertices.
    for e in &b.edges {
        let d = vericad::geom::dist(&b.vertices[e.start].point, &b.vertices[e.end].point);
        assert!((d - 500.0).abs() < 1e-3, "edge {}: {d}", e.source);
    }
    let area: f64 = vericad::tessellate::face_areas(&m, b)
        .iter()
        .map(|f| f.area.unwrap())
        .sum();
    assert!((area - 1.5e6).abs() / 1.5e6 < 1e-6, "area {area}");
    assert_eq!(watertight(&m), 0);
}

#[test]
fn a_cube_intersected_with_itself_has_no_branch() {
    // Before sewing, the one-file run reported two branches along a shared edge.
    let m = model("tests/data/public/gmsh-cube1000.igs");
    let prm = vericad::ssi::SsiParams {
        tol: 1e-6,
        ..Default::default()
    };
    let r = vericad::ssi::intersect_models(&m, None, &prm, &|_, _| {}).unwrap();
    assert_eq!(r.summary.branches, 0);
}

#[test]
fn t20_written_as_trimmed_faces_is_sewn_back_into_its_solids_topology() {
    let m = model("tests/data/public/occt-written/gmsh-t20_data-faces.igs");
    let b = m.brep.as_ref().expect("a sewn B-rep");
    assert_eq!(b.faces.len(), 21);
    let loops: usize = b.faces.iter().map(|f| f.loops.len()).sum();
    assert_eq!(loops, 22);
    assert_eq!(b.edges.len(), 48);
    assert_eq!(b.vertices.len(), 28);
    assert!(b.shells[0].closed);
    let area: f64 = vericad::tessellate::face_areas(&m, b)
        .iter()
        .map(|f| f.area.unwrap())
        .sum();
    let occt = 6365.476295748658;
    assert!((area - occt).abs() / occt < 1e-5, "area {area}");
    assert_eq!(watertight(&m), 0);
    // Shared edges join points of both faces' boundaries: each edge's curve ends at its
    // vertices within the sewing tolerance.
    for e in &b.edges {
        let c = &e.curve.as_ref().unwrap().nurbs;
        let (t0, t1) = c.hom.domain();
        let gap = vericad::geom::dist(&c.eval(&t0), &b.vertices[e.start].point)
            .max(vericad::geom::dist(&c.eval(&t1), &b.vertices[e.end].point));
        assert!(gap <= b.tolerance, "{}: {gap:e}", e.source);
        let mid = c.eval(&(0.5 * (t0 + t1)));
        assert!(mid.iter().all(|x| x.is_finite()));
        let _ = mid.sub(&mid);
    }
}

/// The IGES lines with field `k` of the parameter line of the 142 at directory entry `de`
/// ("142,CRTN,SPTR,BPTR,CPTR,PREF;") set to 0.
fn with_142_field<'a>(lines: impl Iterator<Item = &'a str>, de: usize, k: usize) -> Vec<String> {
    lines
        .map(|l| {
            if l.get(72..73) == Some("P") && l[64..72].trim() == de.to_string() {
                let mut f: Vec<String> = l[..64].trim_end().split(',').map(String::from).collect();
                if f[0] == "142" && f.len() >= 6 {
                    f[k] = "0".into();
                }
                format!("{:<64}{}", f.join(","), &l[64..])
            } else {
                l.to_string()
            }
        })
        .collect()
}

#[test]
fn a_face_without_model_space_curves_is_built_from_its_parameter_space_curve() {
    // occt-bad_header.igs: one 144 face whose 142 prefers its parameter-space curve: sewn
    // alone, four free edges, an open shell.
    let m = model("tests/data/public/occt-bad_header.igs");
    let b = m.brep.as_ref().unwrap();
    assert_eq!(b.faces.len(), 1);
    assert!(!b.shells[0].closed);
    assert_eq!(m.surfaces[0].trim_loops.len(), 1);
    // A 144 whose 142 names no model-space curve (CPTR 0): no B-rep, a warning says why.
    let text = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/public/occt-bad_header.igs"),
    )
    .unwrap();
    let de_142 = text
        .lines()
        .filter(|l| l.get(72..73) == Some("D"))
        .step_by(2)
        .find(|l| l[..8].trim() == "142")
        .map(|l| l[73..80].trim().parse::<usize>().unwrap())
        .unwrap();
    // The 142's parameter line: "142,CRTN,SPTR,BPTR,CPTR,PREF;" — set CPTR to 0.
    let lines = with_142_field(text.lines(), de_142, 4);
    let m = vericad::io::iges::from_str(&lines.join("\n"), "no-cptr.igs").unwrap();
    // The parameter-space curve alone: the boundary is built on the surface from it.
    let b = m
        .brep
        .as_ref()
        .expect("a B-rep from the parameter-space curve");
    assert_eq!((b.faces.len(), b.edges.len()), (1, 4));
    assert!(
        m.warnings.iter().any(|w| w.contains("gives alone")),
        "{:?}",
        m.warnings
    );
    assert_eq!(m.surfaces[0].trim_loops.len(), 1);
    // With a parameter-space curve that cannot be mapped (here: none, BPTR 0) and no
    // model-space curve either: no B-rep, a warning says why, the trims stay.
    let none = with_142_field(lines.iter().map(String::as_str), de_142, 3);
    let m = vericad::io::iges::from_str(&none.join("\n"), "no-curves.igs").unwrap();
    assert!(m.brep.is_none());
    assert!(
        m.warnings.iter().any(|w| w.contains("no B-rep")),
        "{:?}",
        m.warnings
    );
}

#[test]
fn surfaces_of_revolution_and_planes_carry_their_faces_boundaries() {
    // abc-0000 written by Open CASCADE in faces mode: spheres, cones and tori as surfaces of
    // revolution (120) placed by their own transformation matrices (124), planes as 108
    // entities. Every sewn vertex lies on the surfaces of the faces using it (distance by
    // projection, within 1e-6 of the part's size) — a 120 built without its own
    // transformation puts it millimetres away.
    let m = model("tests/data/public/occt-written/abc-0000-faces.igs");
    let b = m.brep.as_ref().expect("a sewn B-rep");
    assert_eq!(b.faces.len(), 25);
    // The original has 51 edges and 39 vertices (Open CASCADE); its six solids touch: three
    // vertex pairs and one edge pair coincide (within 1e-3 mm), which sewing merges.
    assert_eq!(b.vertices.len(), 39 - 3);
    assert_eq!(b.edges.len(), 51 - 1);
    let mut size: f64 = 0.0;
    for v in &b.vertices {
        for w in &b.vertices {
            size = size.max(vericad::geom::dist(&v.point, &w.point));
        }
    }
    let mut checked = 0;
    for f in &b.faces {
        let s = &m.surfaces[f.surface.unwrap()].nurbs;
        let vericad::brep::LoopKind::Edges(es) = &f.loops[0].kind else {
            panic!("a vertex loop")
        };
        for o in es {
            let p = b.vertices[b.edges[o.edge].start].point;
            let uv = vericad::spline::project::project(s, &p);
            let d = vericad::geom::dist(&s.eval(&uv[0], &uv[1]), &p);
            assert!(d <= 1e-6 * size, "{}: {d:e}", f.source);
            checked += 1;
        }
    }
    assert!(checked >= 50, "{checked}");
}
