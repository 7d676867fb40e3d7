//! STEP writing with topology: a public STEP file with a B-rep is read, written and read back,
//! and the read-back B-rep is compared with the original file's reading — the same faces,
//! loops, edges and vertices, every edge used by the same faces in the same places, the same
//! orientations, surfaces and edge curves bit for bit, and the same trimmed areas. What the
//! writer cannot hold (a face without a surface, a loop over an edge without a curve) is
//! named in its notes.

use std::collections::BTreeMap;
use std::path::Path;
use vericad::brep::{Brep, LoopKind};
use vericad::io::step;
use vericad::model::Model;

fn public(name: &str) -> Model {
    let p = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/public")
        .join(name);
    step::read(&p).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// Write `m` as STEP and read it back; the writer's notes too.
fn round_trip(m: &Model, name: &str) -> (Model, Vec<String>) {
    let (text, notes) = step::write::write(m, name);
    let back = step::from_str(&text, "written.step").unwrap_or_else(|e| panic!("{name}: {e}"));
    (back, notes)
}

fn bits<const D: usize>(pts: &[[f64; D]], w: &[f64]) -> Vec<u64> {
    pts.iter()
        .flat_map(|p| p.iter().map(|x| x.to_bits()))
        .chain(w.iter().map(|x| x.to_bits()))
        .collect()
}

/// A one-to-one correspondence built up pair by pair; a pair that contradicts an earlier
/// one fails the test.
fn pair(
    map: &mut BTreeMap<usize, usize>,
    inverse: &mut BTreeMap<usize, usize>,
    a: usize,
    b: usize,
    what: &str,
) {
    assert_eq!(
        *map.entry(a).or_insert(b),
        b,
        "{what} {a} maps to two items"
    );
    assert_eq!(*inverse.entry(b).or_insert(a), a, "two {what}s map to {b}");
}

/// Compare the read-back B-rep `y` (of model `my`) with the original `x` (of `mx`).
fn same_brep(name: &str, mx: &Model, x: &Brep, my: &Model, y: &Brep) {
    let (cx, cy) = (x.counts(), y.counts());
    assert_eq!(
        (
            cx.solids,
            cx.closed_shells,
            cx.open_shells,
            cx.faces,
            cx.loops,
            cx.vertex_loops,
            cx.edges,
            cx.vertices
        ),
        (
            cy.solids,
            cy.closed_shells,
            cy.open_shells,
            cy.faces,
            cy.loops,
            cy.vertex_loops,
            cy.edges,
            cy.vertices
        ),
        "{name}: counts"
    );
    assert_eq!(x.faces.len(), y.faces.len());
    let (mut em, mut ei, mut vm, mut vi) = Default::default();
    // Uses of each edge: (face, loop, position, forward); the written file's keyed by its own
    // edge numbers.
    let mut uses_x: BTreeMap<usize, Vec<(usize, usize, usize, bool)>> = BTreeMap::new();
    let mut uses_y: BTreeMap<usize, Vec<(usize, usize, usize, bool)>> = BTreeMap::new();
    for (f, (fx, fy)) in x.faces.iter().zip(&y.faces).enumerate() {
        assert_eq!(
            fx.same_sense, fy.same_sense,
            "{name}: face {} same_sense",
            fx.source
        );
        assert_eq!(
            fx.loops.len(),
            fy.loops.len(),
            "{name}: face {} loops",
            fx.source
        );
        // The face's surface, bit for bit.
        let (sx, sy) = (
            &mx.surfaces[fx.surface.unwrap()].nurbs,
            &my.surfaces[fy.surface.unwrap()].nurbs,
        );
        let (px, wx) = sx.points_weights();
        let (py, wy) = sy.points_weights();
        assert_eq!(
            sx.hom.degrees(),
            sy.hom.degrees(),
            "{name}: face {}",
            fx.source
        );
        assert_eq!(
            bits(&px, &wx),
            bits(&py, &wy),
            "{name}: face {} surface",
            fx.source
        );
        let kb = |k: &[f64]| k.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
        assert_eq!(kb(sx.hom.ku.knots()), kb(sy.hom.ku.knots()));
        assert_eq!(kb(sx.hom.kv.knots()), kb(sy.hom.kv.knots()));
        for (l, (lx, ly)) in fx.loops.iter().zip(&fy.loops).enumerate() {
            assert_eq!(
                (lx.outer, lx.orientation),
                (ly.outer, ly.orientation),
                "{name}: face {} loop {l}",
                fx.source
            );
            match (&lx.kind, &ly.kind) {
                (LoopKind::Vertex(a), LoopKind::Vertex(b)) => {
                    pair(&mut vm, &mut vi, *a, *b, "vertex")
                }
                (LoopKind::Edges(a), LoopKind::Edges(b)) => {
                    assert_eq!(
                        a.len(),
                        b.len(),
                        "{name}: face {} loop {l} length",
                        fx.source
                    );
                    for (k, (oa, ob)) in a.iter().zip(b).enumerate() {
                        assert_eq!(
                            oa.forward, ob.forward,
                            "{name}: face {} loop {l} edge {k}",
                            fx.source
                        );
                        pair(&mut em, &mut ei, oa.edge, ob.edge, "edge");
                        uses_x
                            .entry(oa.edge)
                            .or_default()
                            .push((f, l, k, oa.forward));
                        uses_y
                            .entry(ob.edge)
                            .or_default()
                            .push((f, l, k, ob.forward));
                        let (ea, eb) = (&x.edges[oa.edge], &y.edges[ob.edge]);
                        pair(&mut vm, &mut vi, ea.start, eb.start, "vertex");
                        pair(&mut vm, &mut vi, ea.end, eb.end, "vertex");
                    }
                }
                _ => panic!("{name}: face {} loop {l}: kinds differ", fx.source),
            }
        }
    }
    // Every edge of the original is used in the same places, the same way round, as the
    // written edge it corresponds to (so it is shared by the same faces).
    for (e, u) in &uses_x {
        assert_eq!(
            Some(u),
            uses_y.get(&em[e]),
            "{name}: uses of edge {}",
            x.edges[*e].source
        );
    }
    assert_eq!(em.len(), x.edges.len(), "{name}: every edge reached");
    let shared = uses_x
        .values()
        .filter(|u| u.len() == 2 && u[0].0 != u[1].0)
        .count();
    assert!(shared > 0, "{name}: some edges are shared by two faces");
    // Vertices and edge curves, bit for bit.
    for (a, b) in &vm {
        assert_eq!(
            x.vertices[*a].point.map(f64::to_bits),
            y.vertices[*b].point.map(f64::to_bits)
        );
    }
    for (a, b) in &em {
        let (ca, cb) = (
            x.edges[*a].curve.as_ref().unwrap(),
            y.edges[*b].curve.as_ref().unwrap(),
        );
        let (pa, wa) = ca.nurbs.points_weights();
        let (pb, wb) = cb.nurbs.points_weights();
        assert_eq!(
            bits(&pa, &wa),
            bits(&pb, &wb),
            "{name}: edge {} curve",
            x.edges[*a].source
        );
        assert_eq!(ca.nurbs.hom.knots.knots(), cb.nurbs.hom.knots.knots());
    }
    // Shells (faces and their orientation in the shell) and solids.
    for (sx, sy) in x.shells.iter().zip(&y.shells) {
        assert_eq!(
            (sx.closed, &sx.faces),
            (sy.closed, &sy.faces),
            "{name}: shell {}",
            sx.source
        );
    }
    for (sx, sy) in x.solids.iter().zip(&y.solids) {
        assert_eq!(
            (sx.outer, &sx.voids),
            (sy.outer, &sy.voids),
            "{name}: solid {}",
            sx.source
        );
    }
    // No new topology fault.
    assert_eq!(
        x.report.issues.len(),
        y.report.issues.len(),
        "{name}: issues {:?}",
        y.report.issues
    );
}

fn check_file(name: &str) {
    let m = public(name);
    let (back, notes) = round_trip(&m, name);
    eprintln!("{name}: {notes:?}");
    assert_eq!(m.unit, back.unit, "{name}: unit");
    let (x, y) = (m.brep.as_ref().unwrap(), back.brep.as_ref().unwrap());
    same_brep(name, &m, x, &back, y);
    // Trimmed areas of the original file's faces and of the written ones.
    let ax = vericad::tessellate::face_areas(&m, x);
    let ay = vericad::tessellate::face_areas(&back, y);
    assert_eq!(ax.len(), ay.len());
    for (a, b) in ax.iter().zip(&ay) {
        let (a, b) = (a.area.unwrap(), b.area.unwrap());
        assert!((a - b).abs() <= 1e-12 * a.abs(), "{name}: area {a} vs {b}");
    }
}

#[test]
fn abc_round_trips_with_its_topology() {
    check_file("abc-0000.step");
}

#[test]
fn t20_round_trips_with_its_topology() {
    check_file("gmsh-t20_data.step");
}

#[test]
fn periodic_round_trips_with_its_topology() {
    check_file("gmsh-periodic_u_cst.step");
}

#[test]
fn the_written_file_declares_topology_units_and_uncertainty() {
    let m = public("gmsh-periodic_u_cst.step");
    let (text, _) = step::write::write(&m, "p");
    for e in [
        "MANIFOLD_SOLID_BREP(",
        "CLOSED_SHELL(",
        "ADVANCED_FACE(",
        "FACE_OUTER_BOUND(",
        "EDGE_LOOP(",
        "ORIENTED_EDGE(",
        "EDGE_CURVE(",
        "VERTEX_POINT(",
        "ADVANCED_BREP_SHAPE_REPRESENTATION(",
        "SHAPE_DEFINITION_REPRESENTATION(",
    ] {
        assert!(text.contains(e), "{e}");
    }
    // Four edges in the file, each one EDGE_CURVE however many loops use it.
    assert_eq!(text.matches("=EDGE_CURVE(").count(), 4);
    // The file's own uncertainty (0.01 mm), not a default.
    assert!(text.contains("LENGTH_MEASURE(0.01)"), "uncertainty");
    assert!(text.contains("SI_UNIT(.MILLI.,.METRE.)"));
}

fn step_text(data: &str) -> String {
    format!(
        "ISO-10303-21;\nHEADER;\nFILE_SCHEMA(('AUTOMOTIVE_DESIGN'));\nENDSEC;\nDATA;\n{data}\nENDSEC;\nEND-ISO-10303-21;\n"
    )
}

/// A unit square in z = 0 bounded by one loop, used by two faces: one on a plane, one on an
/// offset surface (not converted: the face has no surface); and a third face whose only loop
/// uses a polyline edge (not converted: the edge has no curve). The shell uses the first face
/// reversed.
const FAULTY: &str = "#1=CARTESIAN_POINT('',(0.,0.,0.));
#2=DIRECTION('',(0.,0.,1.));
#3=DIRECTION('',(1.,0.,0.));
#4=AXIS2_PLACEMENT_3D('',#1,#2,#3);
#5=PLANE('',#4);
#6=OFFSET_SURFACE('',#5,1.,.F.);
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
#35=POLYLINE('',(#11,#12));
#41=EDGE_CURVE('',#21,#22,#31,.T.);
#42=EDGE_CURVE('',#22,#23,#32,.T.);
#43=EDGE_CURVE('',#24,#23,#33,.T.);
#44=EDGE_CURVE('',#21,#24,#34,.T.);
#45=EDGE_CURVE('',#21,#22,#35,.T.);
#51=ORIENTED_EDGE('',*,*,#41,.T.);
#52=ORIENTED_EDGE('',*,*,#42,.T.);
#53=ORIENTED_EDGE('',*,*,#43,.F.);
#54=ORIENTED_EDGE('',*,*,#44,.F.);
#55=ORIENTED_EDGE('',*,*,#45,.T.);
#56=ORIENTED_EDGE('',*,*,#42,.T.);
#57=ORIENTED_EDGE('',*,*,#43,.F.);
#58=ORIENTED_EDGE('',*,*,#44,.F.);
#60=EDGE_LOOP('',(#51,#52,#53,#54));
#61=FACE_OUTER_BOUND('',#60,.T.);
#62=EDGE_LOOP('',(#55,#56,#57,#58));
#63=FACE_OUTER_BOUND('',#62,.T.);
#70=ADVANCED_FACE('',(#61),#5,.T.);
#71=ADVANCED_FACE('',(#61),#6,.T.);
#72=ADVANCED_FACE('',(#63),#5,.F.);
#80=ORIENTED_FACE('',*,#70,.F.);
#81=OPEN_SHELL('',(#80,#71,#72));";

#[test]
fn what_the_writer_cannot_hold_is_named() {
    let m = step::from_str(&step_text(FAULTY), "faulty.step").unwrap();
    let b = m.brep.as_ref().unwrap();
    assert_eq!(b.faces.len(), 3);
    assert!(
        b.faces[1].surface.is_none(),
        "the offset surface is not converted"
    );
    let (back, notes) = round_trip(&m, "faulty");
    let all = notes.join("\n");
    assert!(all.contains("face #71 not written"), "{all}");
    assert!(
        all.contains("loop #63 of face #72 not written: its edge #45 has no 3D curve or vertex"),
        "{all}"
    );
    assert!(all.contains("shell #81 written without face #71"), "{all}");
    assert!(
        all.contains("face #72 not written: none of its loops"),
        "{all}"
    );
    // Face #70 remains, with its loop; its shell used it reversed, so it is written reversed
    // (`same_sense` negated, not as an `oriented_face`): it points the same way.
    let y = back.brep.as_ref().unwrap();
    assert_eq!(y.faces.len(), 1);
    assert_eq!(y.shells[0].faces, vec![(0, true)]);
    assert_eq!((y.faces[0].loops.len(), y.edges.len()), (1, 4));
    assert!(!y.faces[0].same_sense);
    assert_eq!(
        b.shells[0].faces.iter().find(|f| f.0 == 0),
        Some(&(0, false))
    );
    assert!(b.faces[0].same_sense);
    assert!(y.report.issues.is_empty(), "{:?}", y.report.issues);
}

#[test]
fn a_model_without_a_brep_keeps_the_geometric_set() {
    let m = public("occt-bug28366_fuselage.stp");
    assert!(m.brep.is_none());
    let (text, notes) = step::write::write(&m, "f");
    assert!(notes.is_empty());
    assert!(text.contains("GEOMETRIC_SET(") && !text.contains("ADVANCED_FACE("));
    let back = step::from_str(&text, "f.step").unwrap();
    assert_eq!(back.surfaces.len(), m.surfaces.len());
}

/// The pcurves the writer adds share their edge's parameter and lie under the original file's
/// edge curves: on planar faces the surface at the pcurve's point is the edge curve's point
/// (1e-9 of the model's size), on curved faces (pcurves made by projection, each with a proven
/// bound at equal parameters, `spline::pcurve_bound`) within the model tolerance, at every
/// sample.
#[test]
fn pcurves_added_by_the_writer_map_onto_the_edges() {
    for name in [
        "abc-0000.step",
        "gmsh-t20_data.step",
        "gmsh-periodic_u_cst.step",
    ] {
        let m = public(name);
        let x = m.brep.as_ref().unwrap();
        assert!(
            x.edges.iter().all(|e| e.pcurves.is_empty()),
            "{name}: the file has no pcurves"
        );
        let (back, _) = round_trip(&m, name);
        let y = back.brep.as_ref().unwrap();
        let scale = 1.0
            + x.vertices
                .iter()
                .flat_map(|v| v.point)
                .fold(0.0, |a: f64, c| a.max(c.abs()));
        let mut checked = 0;
        // Edges correspond by index (the writer keeps the order the reader found them in).
        for (ex, ey) in x.edges.iter().zip(&y.edges) {
            let c = &ex.curve.as_ref().unwrap().nurbs;
            for pc in &ey.pcurves {
                let vericad::brep::PCurveGeometry::Nurbs(p) = &pc.geometry else {
                    panic!("{name}: a line pcurve")
                };
                let face = y
                    .faces
                    .iter()
                    .find(|f| f.surface_source == pc.surface_source)
                    .unwrap();
                let s = &back.surfaces[face.surface.unwrap()].nurbs;
                let (t0, t1) = c.hom.domain();
                assert_eq!(p.hom.domain(), (t0, t1));
                // Exact where the plane's inverse maps the edge (the writer's choice there).
                let planar = vericad::brep::pcurve::AffinePatch::new(s)
                    .and_then(|a| a.pcurve(c))
                    .is_some();
                let tol = if planar {
                    1e-9 * scale
                } else {
                    x.tolerance.max(1e-8 * x.extent())
                };
                for k in 0..=16 {
                    let t = t0 + (t1 - t0) * k as f64 / 16.0;
                    let uv = p.eval(&t);
                    let d = vericad::geom::dist(&s.eval(&uv[0], &uv[1]), &c.eval(&t));
                    assert!(d <= tol, "{name}: edge {} at {t}: {d}", ex.source);
                }
                checked += 1;
            }
        }
        eprintln!("{name}: {checked} pcurves");
        assert!(checked > 0, "{name}: no pcurve written");
    }
}

/// A B-rep built by hand with indices outside its vertex list: the writers name the loops they
/// leave out instead of failing.
#[test]
fn dangling_vertex_indices_are_named_not_a_panic() {
    let mut m = public("gmsh-periodic_u_cst.step");
    let b = m.brep.as_mut().unwrap();
    b.edges[0].start = 999;
    b.vertices.truncate(b.vertices.len() - 1);
    let (text, notes) = step::write::write(&m, "x");
    assert!(
        notes
            .iter()
            .any(|n| n.contains("has no 3D curve or vertex")),
        "{notes:?}"
    );
    step::from_str(&text, "x.step").unwrap();
    let (igs, notes) = vericad::io::iges::write::write_with(
        &m,
        "x",
        vericad::io::iges::write::BrepForm::BrepEntities,
    );
    assert!(
        notes
            .iter()
            .any(|n| n.contains("has no 3D curve or vertex")),
        "{notes:?}"
    );
    vericad::io::iges::from_str(&igs, "x.igs").unwrap();
    // As trimmed surfaces the faces hold their own curves, not the vertices.
    let (igs, _) = vericad::io::iges::write::write(&m, "x");
    vericad::io::iges::from_str(&igs, "x.igs").unwrap();
}
