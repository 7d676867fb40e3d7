//! STEP topology into the B-rep model: counts on the public files against Open CASCADE's
//! reading, edge geometry against analytic values, and faulty topology (open loops,
//! dangling references, cycles, wrong types) reported per face with the entity id.

use std::path::Path;
use vericad::brep::{Brep, CurveKind, IssueKind, LoopKind, PCurveGeometry};
use vericad::geom::dist;
use vericad::io::step;

fn public(name: &str) -> Brep {
    let p = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/public")
        .join(name);
    let m = step::read(&p).unwrap_or_else(|e| panic!("{name}: {e}"));
    m.brep.unwrap_or_else(|| panic!("{name}: no B-rep"))
}

/// Counts Open CASCADE 8.0.1 (`STEPControl_Reader`, `TopExp::MapShapes`) reports for the
/// public files, recorded from `scripts/occt_brep_counts.py` (see docs/brep.md): faces,
/// wires, edges, vertices, seam edges and degenerate edges it has after its shape healing,
/// and the boundary components without seams (invariant under that healing).
struct Occt {
    faces: usize,
    wires: usize,
    edges: usize,
    vertices: usize,
    seams: usize,
    degenerate: usize,
    components: usize,
}

fn compare(name: &str, o: Occt, healed: bool) {
    let b = public(name);
    let c = b.counts();
    assert_eq!(c.faces, o.faces, "{name}: faces");
    assert_eq!(c.boundary_components, o.components, "{name}: components");
    assert_eq!(
        c.edges as i64 - c.seam_edges as i64 - c.vertices as i64,
        o.edges as i64 - o.seams as i64 - o.degenerate as i64 - o.vertices as i64,
        "{name}: edges - seams - vertices"
    );
    if !healed {
        assert_eq!(c.loops, o.wires, "{name}: loops");
        assert_eq!(c.edges, o.edges, "{name}: edges");
        assert_eq!(c.vertices, o.vertices, "{name}: vertices");
        assert_eq!(c.seam_edges, o.seams, "{name}: seams");
    }
    assert!(
        b.report.issues.iter().all(|i| !matches!(
            i.kind,
            IssueKind::OpenLoop { .. } | IssueKind::EdgeUse { .. }
        )),
        "{name}: {:?}",
        b.report.issues
    );
    assert_eq!(c.edges_without_curve, 0, "{name}");
}

#[test]
fn t20_counts_equal_open_cascade() {
    // Open CASCADE adds nothing here: every count compares directly.
    let o = Occt {
        faces: 21,
        wires: 22,
        edges: 48,
        vertices: 28,
        seams: 0,
        degenerate: 0,
        components: 22,
    };
    compare("gmsh-t20_data.step", o, false);
    let c = public("gmsh-t20_data.step").counts();
    assert_eq!((c.solids, c.closed_shells), (1, 1));
}

#[test]
fn abc_counts_equal_open_cascade_up_to_its_healing() {
    let o = Occt {
        faces: 25,
        wires: 26,
        edges: 58,
        vertices: 39,
        seams: 11,
        degenerate: 7,
        components: 30,
    };
    compare("abc-0000.step", o, true);
    let b = public("abc-0000.step");
    let c = b.counts();
    // The file's own topology: 6 solids of one closed shell each; 7 vertex loops (sphere
    // poles), one per degenerate edge Open CASCADE makes of them.
    assert_eq!((c.solids, c.closed_shells, c.vertex_loops), (6, 6, 7));
    // Every closed shell uses each of its edges exactly twice.
    for s in &b.shells {
        assert!(
            b.edge_uses(&s.faces).values().all(|&n| n == 2),
            "{}",
            s.source
        );
    }
}

#[test]
fn periodic_counts_equal_open_cascade_up_to_its_healing() {
    let o = Occt {
        faces: 3,
        wires: 4,
        edges: 6,
        vertices: 4,
        seams: 2,
        degenerate: 2,
        components: 4,
    };
    compare("gmsh-periodic_u_cst.step", o, true);
    assert_eq!(public("gmsh-periodic_u_cst.step").counts().seam_edges, 2);
}

#[test]
fn a_bare_patch_set_has_no_brep() {
    let p =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/public/occt-bug28366_fuselage.stp");
    let m = step::read(&p).unwrap();
    // Open CASCADE makes 8 faces with natural bounds; the file has 8 surfaces, no topology.
    assert_eq!(m.surfaces.len(), 8);
    assert!(m.brep.is_none());
}

#[test]
fn every_edge_curve_runs_from_its_start_vertex_to_its_end_vertex() {
    // Largest vertex-to-curve-end distance allowed: the uncertainty each file declares
    // (UNCERTAINTY_MEASURE_WITH_UNIT), except abc-0000.step's 1e-17, below the f64 spacing of
    // its coordinates: there the vertices of edge #580 lie 2.2e-11 m off its curve, the
    // largest distance measured; 1e-10 m is allowed.
    for (name, tol) in [
        ("abc-0000.step", 1e-10),
        ("gmsh-t20_data.step", 0.0741808824497),
        ("gmsh-periodic_u_cst.step", 0.01),
    ] {
        let b = public(name);
        for e in &b.edges {
            let c = e.curve.as_ref().unwrap();
            let (t0, t1) = c.nurbs.hom.domain();
            let a = dist(&c.nurbs.eval(&t0), &b.vertices[e.start].point);
            let z = dist(&c.nurbs.eval(&t1), &b.vertices[e.end].point);
            assert!(a.max(z) <= tol, "{name} {}: {a:e} {z:e}", e.source);
            assert!(
                (a.max(z) - c.vertex_gap).abs() <= 1e-15,
                "{name} {}",
                e.source
            );
        }
    }
}

/// A minimal STEP file around `data` (instances only).
fn step_text(data: &str) -> String {
    format!(
        "ISO-10303-21;\nHEADER;\nFILE_SCHEMA(('AUTOMOTIVE_DESIGN'));\nENDSEC;\nDATA;\n{data}\nENDSEC;\nEND-ISO-10303-21;\n"
    )
}

/// A unit square face in z = 0 bounded by four lines, with `extra` instances and the loop's
/// edge list `loop_edges` (default `#41,#42,#43,#44`).
fn square(loop_edges: &str, extra: &str) -> String {
    step_text(&format!(
        "#1=CARTESIAN_POINT('',(0.,0.,0.));
#2=DIRECTION('',(0.,0.,1.));
#3=DIRECTION('',(1.,0.,0.));
#4=AXIS2_PLACEMENT_3D('',#1,#2,#3);
#5=PLANE('',#4);
#11=CARTESIAN_POINT('',(0.,0.,0.));
#12=CARTESIAN_POINT('',(1.,0.,0.));
#13=CARTESIAN_POINT('',(1.,1.,0.));
#14=CARTESIAN_POINT('',(0.,1.,0.));
#21=VERTEX_POINT('',#11);
#22=VERTEX_POINT('',#12);
#23=VERTEX_POINT('',#13);
#24=VERTEX_POINT('',#14);
#25=DIRECTION('',(0.,1.,0.));
#26=VECTOR('',#3,1.);
#27=VECTOR('',#25,1.);
#31=LINE('',#11,#26);
#32=LINE('',#12,#27);
#33=LINE('',#14,#26);
#34=LINE('',#11,#27);
#41=EDGE_CURVE('',#21,#22,#31,.T.);
#42=EDGE_CURVE('',#22,#23,#32,.T.);
#43=EDGE_CURVE('',#24,#23,#33,.T.);
#44=EDGE_CURVE('',#21,#24,#34,.T.);
#51=ORIENTED_EDGE('',*,*,#41,.T.);
#52=ORIENTED_EDGE('',*,*,#42,.T.);
#53=ORIENTED_EDGE('',*,*,#43,.F.);
#54=ORIENTED_EDGE('',*,*,#44,.F.);
#60=EDGE_LOOP('',({loop_edges}));
#61=FACE_OUTER_BOUND('',#60,.T.);
#70=ADVANCED_FACE('',(#61),#5,.T.);
#80=OPEN_SHELL('',(#70));
{extra}"
    ))
}

fn read_text(text: &str) -> vericad::model::Model {
    step::from_str(text, "test.step").unwrap_or_else(|e| panic!("{e}"))
}

fn issues(b: &Brep) -> String {
    b.report
        .issues
        .iter()
        .map(|i| i.to_string())
        .collect::<Vec<_>>()
        .join("\n")
}

#[test]
fn a_square_face_reads_with_its_loop_and_lines() {
    let m = read_text(&square("#51,#52,#53,#54", ""));
    let b = m.brep.unwrap();
    assert!(b.report.issues.is_empty(), "{}", issues(&b));
    let c = b.counts();
    assert_eq!(
        (c.faces, c.loops, c.edges, c.vertices, c.open_shells),
        (1, 1, 4, 4, 1)
    );
    assert_eq!(b.faces[0].source, "#70");
    assert_eq!(b.faces[0].surface, Some(0));
    let LoopKind::Edges(es) = &b.faces[0].loops[0].kind else {
        panic!()
    };
    assert_eq!(es.len(), 4);
    assert!(!es[2].forward);
    // Each line segment is exactly one unit long.
    for e in &b.edges {
        let n = &e.curve.as_ref().unwrap().nurbs;
        assert_eq!(n.hom.degree(), 1);
        let (t0, t1) = n.hom.domain();
        assert_eq!(dist(&n.eval(&t0), &n.eval(&t1)), 1.0, "{}", e.source);
    }
}

#[test]
fn an_open_loop_is_reported_with_the_face_and_loop() {
    // #52 is missing: #51 ends at #22, #53 (reversed) begins at #23.
    let m = read_text(&square("#51,#53,#54", ""));
    let s = issues(m.brep.as_ref().unwrap());
    assert!(
        s.contains("face #70: #60: loop is open") && s.contains("#22") && s.contains("#23"),
        "{s}"
    );
    assert!(m.warnings.iter().any(|w| w.contains("loop is open")));
}

#[test]
fn a_dangling_reference_is_reported_not_a_panic() {
    let m = read_text(&square(
        "#51,#52,#53,#55",
        "#55=ORIENTED_EDGE('',*,*,#99,.T.);",
    ));
    let b = m.brep.unwrap();
    let s = issues(&b);
    assert!(
        s.contains("#55") && s.contains("missing instance #99"),
        "{s}"
    );
    // The loop is refused, the face kept without it, and both are named.
    assert!(
        b.report.entities["EDGE_LOOP"]
            .invalid
            .contains(&"#60".to_string())
    );
    assert_eq!(b.faces[0].loops.len(), 0);
    assert!(s.contains("face has no bounds"), "{s}");
}

#[test]
fn a_cycle_of_oriented_edges_ends_with_an_issue() {
    let m = read_text(&square(
        "#51,#52,#53,#55",
        "#55=ORIENTED_EDGE('',*,*,#56,.T.);\n#56=ORIENTED_EDGE('',*,*,#55,.T.);",
    ));
    let s = issues(m.brep.as_ref().unwrap());
    assert!(s.contains("#55") && s.contains("nest deeper"), "{s}");
}

#[test]
fn a_cycle_of_trimmed_curves_ends_with_an_issue() {
    let text = square("#51,#52,#53,#54", "")
        .replace(
            "#41=EDGE_CURVE('',#21,#22,#31,.T.);",
            "#41=EDGE_CURVE('',#21,#22,#90,.T.);\n#90=TRIMMED_CURVE('',#91,(),(),.T.,.UNSPECIFIED.);\n#91=TRIMMED_CURVE('',#90,(),(),.T.,.UNSPECIFIED.);",
        );
    let b = read_text(&text).brep.unwrap();
    let s = issues(&b);
    assert!(s.contains("#90") && s.contains("nest deeper"), "{s}");
    assert_eq!(b.counts().edges_without_curve, 1);
}

#[test]
fn a_wrong_entity_type_is_named() {
    let m = read_text(&square("#51,#52,#53,#1", ""));
    let s = issues(m.brep.as_ref().unwrap());
    assert!(
        s.contains("#1") && s.contains("CARTESIAN_POINT") && s.contains("expected ORIENTED_EDGE"),
        "{s}"
    );
}

#[test]
fn unused_topology_is_listed_as_not_read() {
    let m = read_text(&square(
        "#51,#52,#53,#54",
        "#95=VERTEX_POINT('',#11);\n#96=EDGE_CURVE('',#21,#95,#31,.T.);",
    ));
    let b = m.brep.unwrap();
    assert_eq!(b.report.entities["EDGE_CURVE"].not_read, vec!["#96"]);
    assert_eq!(b.report.entities["VERTEX_POINT"].not_read, vec!["#95"]);
    assert!(
        m.warnings
            .iter()
            .any(|w| w.contains("EDGE_CURVE not read") && w.contains("#96"))
    );
}

#[test]
fn circles_ellipses_surface_curves_and_pcurves() {
    // A unit-radius disc face on z = 0: one closed circle edge through vertex (1,0,0),
    // given as a SURFACE_CURVE with a 2D line pcurve, and an ellipse edge (semi-axes 2, 1)
    // from (2,0,0) to (0,1,0) as a TRIMMED_CURVE, reversed (same_sense .F.).
    let text = step_text(
        "#1=CARTESIAN_POINT('',(0.,0.,0.));
#2=DIRECTION('',(0.,0.,1.));
#3=DIRECTION('',(1.,0.,0.));
#4=AXIS2_PLACEMENT_3D('',#1,#2,#3);
#5=PLANE('',#4);
#10=CARTESIAN_POINT('',(1.,0.,0.));
#11=VERTEX_POINT('',#10);
#12=CIRCLE('',#4,1.);
#13=CARTESIAN_POINT('',(0.,0.));
#14=DIRECTION('',(1.,0.));
#15=VECTOR('',#14,2.);
#16=LINE('',#13,#15);
#17=DEFINITIONAL_REPRESENTATION('',(#16),#99);
#18=PCURVE('',#5,#17);
#19=SURFACE_CURVE('',#12,(#18),.CURVE_3D.);
#20=EDGE_CURVE('',#11,#11,#19,.T.);
#21=ORIENTED_EDGE('',*,*,#20,.T.);
#22=EDGE_LOOP('',(#21));
#23=FACE_OUTER_BOUND('',#22,.T.);
#24=ADVANCED_FACE('',(#23),#5,.T.);
#30=CARTESIAN_POINT('',(2.,0.,0.));
#31=CARTESIAN_POINT('',(0.,1.,0.));
#32=VERTEX_POINT('',#30);
#33=VERTEX_POINT('',#31);
#34=ELLIPSE('',#4,2.,1.);
#35=TRIMMED_CURVE('',#34,(PARAMETER_VALUE(0.)),(PARAMETER_VALUE(1.5707963267949)),.T.,.PARAMETER.);
#36=EDGE_CURVE('',#33,#32,#35,.F.);
#37=ORIENTED_EDGE('',*,*,#36,.T.);
#38=VERTEX_LOOP('',#32);
#39=FACE_BOUND('',#38,.T.);",
    )
    .replace("#24=ADVANCED_FACE('',(#23),#5,.T.);", "#24=ADVANCED_FACE('',(#23),#5,.T.);\n#40=EDGE_LOOP('',(#37));\n#41=FACE_BOUND('',#40,.T.);\n#42=ADVANCED_FACE('',(#39,#41),#5,.F.);");
    let m = read_text(&text);
    let b = m.brep.unwrap();
    let circle = b.edges.iter().find(|e| e.source == "#20").unwrap();
    let c = circle.curve.as_ref().unwrap();
    assert_eq!(c.kind, CurveKind::Circle);
    assert_eq!(c.source, "#12");
    // A full turn: every point at distance 1 from the centre, the curve closed at (1,0,0).
    let (t0, t1) = c.nurbs.hom.domain();
    for i in 0..=64 {
        let t = t0 + (t1 - t0) * i as f64 / 64.0;
        let p = c.nurbs.eval(&t);
        assert!((dist(&p, &[0.0; 3]) - 1.0).abs() < 1e-14, "{p:?}");
    }
    // A quarter point is (0,1,0): counter-clockwise about +z.
    let q = c.nurbs.eval(&(t0 + (t1 - t0) / 4.0));
    assert!(dist(&q, &[0.0, 1.0, 0.0]) < 1e-14, "{q:?}");
    assert_eq!(circle.pcurves.len(), 1);
    assert_eq!(circle.pcurves[0].surface_source, "#5");
    assert_eq!(
        circle.pcurves[0].geometry,
        PCurveGeometry::Line {
            origin: [0.0, 0.0],
            direction: [2.0, 0.0]
        }
    );
    let ell = b.edges.iter().find(|e| e.source == "#36").unwrap();
    let c = ell.curve.as_ref().unwrap();
    assert_eq!(c.kind, CurveKind::Ellipse);
    // From the start vertex (0,1,0) to the end vertex (2,0,0), on x²/4 + y² = 1.
    let (t0, t1) = c.nurbs.hom.domain();
    assert!(dist(&c.nurbs.eval(&t0), &[0.0, 1.0, 0.0]) < 1e-15);
    assert!(dist(&c.nurbs.eval(&t1), &[2.0, 0.0, 0.0]) < 1e-15);
    for i in 0..=16 {
        let p = c.nurbs.eval(&(t0 + (t1 - t0) * i as f64 / 16.0));
        assert!((p[0] * p[0] / 4.0 + p[1] * p[1] - 1.0).abs() < 1e-14);
        assert!(
            p[0] >= -1e-15 && p[1] >= -1e-15,
            "{p:?}: the quarter in x, y >= 0"
        );
    }
    let counts = b.counts();
    assert_eq!((counts.faces, counts.loops, counts.vertex_loops), (2, 3, 1));
    for t in [
        "SURFACE_CURVE",
        "PCURVE",
        "TRIMMED_CURVE",
        "ELLIPSE",
        "CIRCLE",
        "VERTEX_LOOP",
    ] {
        assert_eq!(b.report.entities[t].converted, 1, "{t}");
    }
}

#[test]
fn an_unsupported_edge_curve_is_counted_with_its_id() {
    let text = square("#51,#52,#53,#54", "#90=POLYLINE('',(#11,#12));").replace(
        "#41=EDGE_CURVE('',#21,#22,#31,.T.);",
        "#41=EDGE_CURVE('',#21,#22,#90,.T.);",
    );
    let b = read_text(&text).brep.unwrap();
    assert_eq!(b.report.entities["POLYLINE"].unsupported, vec!["#90"]);
    assert!(issues(&b).contains("face #70: #90: curve of type POLYLINE is not supported"));
    assert_eq!(b.counts().edges_without_curve, 1);
}

mod random_graphs {
    //! Random entity graphs of topology and edge-geometry instances referring to each other at
    //! random (dangling references, cycles, wrong types, self-references): reading, checking,
    //! counting and triangulating never panic and end at once.
    use proptest::prelude::*;
    use vericad::io::step;

    /// Instance `id` of kind `k` with references `r` (ids, possibly missing or cyclic).
    fn instance(id: u32, k: u8, r: &[u32]) -> String {
        let a = |i: usize| r[i % r.len()];
        match k % 14 {
            0 => format!("#{id}=VERTEX_POINT('',#{});", [1, 2, 3][a(0) as usize % 3]),
            1 => format!("#{id}=EDGE_CURVE('',#{},#{},#{},.T.);", a(0), a(1), a(2)),
            2 => format!("#{id}=ORIENTED_EDGE('',*,*,#{},.F.);", a(0)),
            3 => format!("#{id}=EDGE_LOOP('',(#{},#{},#{}));", a(0), a(1), a(2)),
            4 => format!("#{id}=FACE_OUTER_BOUND('',#{},.T.);", a(0)),
            5 => format!(
                "#{id}=ADVANCED_FACE('',(#{},#{}),#{},.T.);",
                a(0),
                a(1),
                [4, 5][a(2) as usize % 2]
            ),
            6 => format!("#{id}=CLOSED_SHELL('',(#{},#{}));", a(0), a(1)),
            7 => format!("#{id}=MANIFOLD_SOLID_BREP('',#{});", a(0)),
            8 => format!("#{id}=TRIMMED_CURVE('',#{},(),(),.F.,.UNSPECIFIED.);", a(0)),
            9 => format!("#{id}=SURFACE_CURVE('',#{},(#{}),.CURVE_3D.);", a(0), a(1)),
            10 => format!("#{id}=VERTEX_LOOP('',#{});", a(0)),
            11 => format!("#{id}=PCURVE('',#{},#{});", a(0), a(1)),
            12 => format!("#{id}=ORIENTED_FACE('',*,#{},.F.);", a(0)),
            _ => format!("#{id}=CIRCLE('',#7,{}.);", 1 + a(0) % 3),
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(200))]
        #[test]
        fn random_topology_never_panics(kinds in proptest::collection::vec((any::<u8>(), proptest::collection::vec(1u32..45, 3)), 1..30)) {
            let mut data = String::from(
                "#1=CARTESIAN_POINT('',(1.,0.,0.));\n#2=CARTESIAN_POINT('',(0.,1.,0.));\n#3=CARTESIAN_POINT('',(0.,0.,1.));\n\
                 #6=DIRECTION('',(0.,0.,1.));\n#8=DIRECTION('',(1.,0.,0.));\n#7=AXIS2_PLACEMENT_3D('',#1,#6,#8);\n\
                 #4=PLANE('',#7);\n#5=SPHERICAL_SURFACE('',#7,1.);\n",
            );
            for (i, (k, r)) in kinds.iter().enumerate() {
                data += &instance(10 + i as u32, *k, r);
                data.push('\n');
            }
            let text = format!("ISO-10303-21;\nHEADER;\nFILE_SCHEMA(('X'));\nENDSEC;\nDATA;\n{data}ENDSEC;\nEND-ISO-10303-21;\n");
            let start = std::time::Instant::now();
            if let Ok(m) = step::from_str(&text, "random.step")
                && let Some(b) = &m.brep
            {
                let _ = b.check();
                let _ = b.counts();
                let _ = vericad::tessellate::mesh_brep(&m, b, &vericad::tessellate::MeshParams::default());
            }
            prop_assert!(start.elapsed().as_secs_f64() < 5.0);
        }
    }
}

/// A cylinder face from −1 to +1 rad about its placement's x direction (where the cylinder's
/// NURBS form starts): its seam is moved out of the face, so the face has one region and its
/// trimmed area is the constructed r·Δθ·h = 8 (tests/data/constructed/README.md).
#[test]
fn a_face_spanning_its_cylinders_start_direction_has_its_area() {
    let p = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/constructed/cylinder-face-across-seam.step");
    let m = vericad::io::read_model(&p).unwrap();
    let b = m.brep.as_ref().unwrap();
    let areas = vericad::tessellate::face_areas(&m, b);
    assert_eq!(areas.len(), 1);
    let a = areas[0]
        .area
        .unwrap_or_else(|| panic!("no area: {:?}", areas[0].note));
    assert!((a - 8.0).abs() <= 1e-6 * 8.0, "{a}");
}
