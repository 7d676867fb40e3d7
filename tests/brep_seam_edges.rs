//! Faces bounded by loops that run round a closed surface with no seam edge (a band between
//! two circles, a cap between a circle and a pole), as STEP allows: the IGES writer gives
//! them an explicit seam (`brep::seam_edges`). Oracles: Archimedes' zone area `2πRh` for
//! zones of a sphere cut by parallel planes (whatever the planes' tilt against the sphere's
//! own axis), and Open CASCADE's reading of abc-0000.step (26 wires; total face area
//! 404864.5993 mm², `BRepGProp`, as in tests/brep_occt_written.rs).

use std::f64::consts::PI;
use std::path::Path;
use vericad::brep::{Brep, LoopKind, OrientedEdge};
use vericad::io::iges::write::BrepForm;
use vericad::io::{iges, step};
use vericad::spline::NurbsCurve;
use vericad::spline::project::CurveFoot;

/// Sphere radius of [`zones`].
const R: f64 = 2.0;
/// Heights of the two cutting planes along [`AXIS`] of [`zones`].
const Z1: f64 = -0.5;
const Z2: f64 = 1.2;

/// The cutting planes' normal (the sphere's own axis is (1, 2, 2)/3, 21° away from it).
const AXIS: [f64; 3] = [0.0, 0.6, 0.8];

/// A closed shell of three faces on one sphere of radius `R`: the cap above `Z2` (closed by
/// a vertex loop at the apex `R·AXIS`), the band between `Z1` and `Z2`, the cap below `Z1`
/// (vertex loop at `−R·AXIS`). The circles' frames have axis `AXIS`; the sphere's frame does
/// not, so no circle is a parameter line of the sphere's NURBS form.
fn zones() -> vericad::model::Model {
    step::from_str(&zones_text(), "zones.step").unwrap()
}

/// The STEP text of [`zones`].
fn zones_text() -> String {
    let r = |z: f64| (R * R - z * z).sqrt();
    let [a, b, c] = AXIS;
    let data = format!(
        "#1=CARTESIAN_POINT('',(0.,0.,0.));
#2=DIRECTION('',(1.,2.,2.));
#3=DIRECTION('',(2.,-2.,1.));
#4=AXIS2_PLACEMENT_3D('',#1,#2,#3);
#5=SPHERICAL_SURFACE('',#4,{R:?});
#6=DIRECTION('',({a:?},{b:?},{c:?}));
#7=DIRECTION('',(1.,0.,0.));
#10=CARTESIAN_POINT('',({x1:?},{y1:?},{w1:?}));
#11=AXIS2_PLACEMENT_3D('',#10,#6,#7);
#12=CIRCLE('',#11,{r1:?});
#13=CARTESIAN_POINT('',({r1:?},{y1:?},{w1:?}));
#14=VERTEX_POINT('',#13);
#15=EDGE_CURVE('',#14,#14,#12,.T.);
#20=CARTESIAN_POINT('',({x2:?},{y2:?},{w2:?}));
#21=AXIS2_PLACEMENT_3D('',#20,#6,#7);
#22=CIRCLE('',#21,{r2:?});
#23=CARTESIAN_POINT('',({r2:?},{y2:?},{w2:?}));
#24=VERTEX_POINT('',#23);
#25=EDGE_CURVE('',#24,#24,#22,.T.);
#30=CARTESIAN_POINT('',({pa:?},{pb:?},{pc:?}));
#31=VERTEX_POINT('',#30);
#32=VERTEX_LOOP('',#31);
#33=CARTESIAN_POINT('',({na:?},{nb:?},{nc:?}));
#34=VERTEX_POINT('',#33);
#35=VERTEX_LOOP('',#34);
#40=ORIENTED_EDGE('',*,*,#25,.T.);
#41=EDGE_LOOP('',(#40));
#42=FACE_OUTER_BOUND('',#41,.T.);
#43=FACE_BOUND('',#32,.T.);
#44=ADVANCED_FACE('top',(#42,#43),#5,.T.);
#50=ORIENTED_EDGE('',*,*,#15,.T.);
#51=EDGE_LOOP('',(#50));
#52=FACE_OUTER_BOUND('',#51,.T.);
#53=ORIENTED_EDGE('',*,*,#25,.F.);
#54=EDGE_LOOP('',(#53));
#55=FACE_BOUND('',#54,.T.);
#56=ADVANCED_FACE('band',(#52,#55),#5,.T.);
#60=ORIENTED_EDGE('',*,*,#15,.F.);
#61=EDGE_LOOP('',(#60));
#62=FACE_OUTER_BOUND('',#61,.T.);
#63=FACE_BOUND('',#35,.T.);
#64=ADVANCED_FACE('bottom',(#62,#63),#5,.T.);
#70=CLOSED_SHELL('',(#44,#56,#64));",
        x1 = 0.0,
        y1 = Z1 * b,
        w1 = Z1 * c,
        r1 = r(Z1),
        x2 = 0.0,
        y2 = Z2 * b,
        w2 = Z2 * c,
        r2 = r(Z2),
        pa = R * a,
        pb = R * b,
        pc = R * c,
        na = -R * a,
        nb = -R * b,
        nc = -R * c,
    );
    format!(
        "ISO-10303-21;\nHEADER;\nFILE_SCHEMA(('AUTOMOTIVE_DESIGN'));\nENDSEC;\nDATA;\n{data}\nENDSEC;\nEND-ISO-10303-21;\n"
    )
}

fn areas(m: &vericad::model::Model) -> Vec<f64> {
    let b = m.brep.as_ref().unwrap();
    vericad::tessellate::face_areas(m, b)
        .iter()
        .map(|f| f.area.unwrap_or_else(|| panic!("{f:?}")))
        .collect()
}

#[test]
fn sphere_zones_written_as_iges_keep_archimedes_areas() {
    let m = zones();
    let (text, notes) = iges::write::write_with(&m, "zones", BrepForm::BrepEntities);
    assert!(notes.is_empty(), "{notes:?}");
    let back = iges::from_str(&text, "zones.igs").unwrap();
    let b = back.brep.as_ref().unwrap();
    assert_eq!(b.faces.len(), 3);
    // One loop per face: each has its seam now.
    for f in &b.faces {
        assert_eq!(f.loops.len(), 1, "face {}", f.source);
    }
    let exact = [R - Z2, Z2 - Z1, R + Z1].map(|h| 2.0 * PI * R * h);
    let got = areas(&back);
    for (g, e) in got.iter().zip(exact) {
        assert!((g - e).abs() / e < 1e-5, "{got:?} vs {exact:?}");
    }
    // The STEP reading itself (no seams) has the same areas.
    for (g, e) in areas(&m).iter().zip(exact) {
        assert!((g - e).abs() / e < 1e-5, "read: {g} vs {e}");
    }
}

/// The start vertex of use `o`.
fn start(b: &Brep, o: &OrientedEdge) -> usize {
    let e = &b.edges[o.edge];
    if o.forward { e.start } else { e.end }
}

/// Every loop of every face chains vertex to vertex; every pcurve of a rebuilt loop starts
/// where the one before ended, lies in the surface's domain and maps onto its edge's curve.
fn check_rebuilt(m: &vericad::model::Model, name: &str) -> usize {
    let b0 = m.brep.as_ref().unwrap();
    let mut notes = Vec::new();
    let s = vericad::brep::seam_edges::explicit_seams(m, b0, &mut notes);
    assert!(notes.is_empty(), "{name}: {notes:?}");
    let b = &s.brep;
    let off = (100.0 * b0.tolerance).max(1e-6 * b0.extent());
    // Every edge's curve, and the curve run backwards (as loops use it), is a valid NURBS
    // curve: the arcs of cut circles keep proper knot vectors.
    for e in &b.edges {
        let c = &e.curve.as_ref().unwrap().nurbs;
        for c in [c.clone(), c.reversed()] {
            let (pts, w) = c.points_weights();
            let again = NurbsCurve::new(c.hom.knots.knots().to_vec(), c.hom.degree(), pts, w);
            assert!(again.is_ok(), "{name}: edge {}: {again:?}", e.source);
        }
    }
    for (fi, f) in b.faces.iter().enumerate() {
        let surface = &m.surfaces[f.surface.unwrap()].nurbs;
        let (u0, u1, v0, v1) = surface.hom.domain();
        for l in &f.loops {
            let LoopKind::Edges(oes) = &l.kind else {
                continue;
            };
            let n = oes.len();
            for i in 0..n {
                let (o, next) = (&oes[i], &oes[(i + 1) % n]);
                let e = &b.edges[o.edge];
                let end = if o.forward { e.end } else { e.start };
                assert_eq!(end, start(b, next), "{name}: face {}", f.source);
                let Some(pc) = s.pcurves.get(&(fi, o.edge, o.forward)) else {
                    continue;
                };
                let pn = &s.pcurves[&(fi, next.edge, next.forward)];
                let (a, z) = pc.hom.domain();
                let gap = vericad::geom::dist(&pc.eval(&z), &pn.eval(&pn.hom.domain().0));
                assert!(
                    gap <= 1e-12,
                    "{name}: face {}: pcurves {gap:e} apart",
                    f.source
                );
                let curve = &e.curve.as_ref().unwrap().nurbs;
                let foot = CurveFoot::new(curve);
                for j in 0..=32 {
                    let q = pc.eval(&(a + (z - a) * j as f64 / 32.0));
                    let inside = |x: f64, lo: f64, hi: f64| x >= lo - 1e-9 && x <= hi + 1e-9;
                    assert!(
                        inside(q[0], u0, u1) && inside(q[1], v0, v1),
                        "{name}: {q:?}"
                    );
                    let q = [q[0].clamp(u0, u1), q[1].clamp(v0, v1)];
                    let d = foot.closest(&surface.eval(&q[0], &q[1])).2;
                    assert!(
                        d <= off,
                        "{name}: face {}: pcurve {d:e} off its edge",
                        f.source
                    );
                }
            }
        }
    }
    s.faces
}

#[test]
fn rebuilt_loops_chain_in_space_and_in_parameters() {
    assert_eq!(check_rebuilt(&zones(), "zones"), 3);
    let p = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/public/abc-0000.step");
    let m = step::read(&p).unwrap();
    assert!(check_rebuilt(&m, "abc-0000") > 0);
}

#[test]
fn abc_0000_written_as_iges_has_open_cascades_wires_and_area() {
    let p = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/public/abc-0000.step");
    let m = step::read(&p).unwrap();
    let (text, notes) = iges::write::write_with(&m, "abc-0000", BrepForm::BrepEntities);
    // The one note: the pcurves made by projection (tests/brep_pcurves_projected.rs).
    assert!(
        notes
            .iter()
            .all(|n| n.starts_with("pcurves made by projecting") && !n.contains("left to")),
        "{notes:?}"
    );
    let back = iges::from_str(&text, "abc-0000.igs").unwrap();
    let b = back.brep.as_ref().unwrap();
    let loops: usize = b.faces.iter().map(|f| f.loops.len()).sum();
    assert_eq!((b.faces.len(), loops), (25, 26));
    // The file is in metres; Open CASCADE's figure is in mm².
    let total: f64 = areas(&back).iter().sum::<f64>() * 1e6;
    let occt = 404864.5993;
    assert!((total - occt).abs() / occt < 1e-5, "{total} vs {occt}");
}

#[test]
fn sphere_caps_written_as_step_close_at_the_poles_of_the_spheres_nurbs_form() {
    // The caps' vertex loops (at the apexes ±R·AXIS) are written at the poles of the sphere's
    // NURBS form, ±R·(1, 2, 2)/3 from its frame, where Open CASCADE's STEP reader looks for
    // them (it read the top cap's complement, 40.21 where 10.05 is right, from the apex).
    let m = zones();
    let (text, notes) = step::write::write(&m, "zones");
    let moved = notes
        .iter()
        .filter(|n| n.contains("written at the pole"))
        .count();
    assert_eq!(moved, 2, "{notes:?}");
    let back = step::from_str(&text, "zones-written.step").unwrap();
    let b = back.brep.as_ref().unwrap();
    let north = [2.0 / 3.0, 4.0 / 3.0, 4.0 / 3.0].map(|x| x * R / 2.0);
    let mut poles = Vec::new();
    for f in &b.faces {
        for l in &f.loops {
            if let LoopKind::Vertex(v) = l.kind {
                poles.push(b.vertices[v].point);
            }
        }
    }
    assert_eq!(poles.len(), 2);
    for (p, sign) in poles.iter().zip([1.0, -1.0]) {
        let want = north.map(|x| sign * x);
        assert!(
            vericad::geom::dist(p, &want) <= 1e-12 * R,
            "{p:?} vs {want:?}"
        );
    }
    let exact = [R - Z2, Z2 - Z1, R + Z1].map(|h| 2.0 * PI * R * h);
    for (g, e) in areas(&back).iter().zip(exact) {
        assert!((g - e).abs() / e < 1e-5, "{g} vs {e}");
    }
}

#[test]
fn sphere_zones_written_as_trimmed_surfaces_keep_archimedes_areas() {
    // Entity 144 per face, one 142 per loop with its model-space and parameter-space curves;
    // vericad reads the file back as trimmed surfaces and sews them into faces.
    let m = zones();
    let (text, notes) = iges::write::write_with(&m, "zones", BrepForm::TrimmedSurfaces);
    assert!(
        notes.iter().all(|n| n.contains("trimmed surfaces (144)")),
        "{notes:?}"
    );
    let back = iges::from_str(&text, "zones.igs").unwrap();
    assert_eq!(back.source_entities.get("144 (form 0)"), Some(&3));
    assert_eq!(back.source_entities.get("142 (form 0)"), Some(&3));
    let b = back
        .brep
        .as_ref()
        .expect("trimmed surfaces are sewn into a B-rep");
    assert_eq!(b.faces.len(), 3);
    let exact = [R - Z2, Z2 - Z1, R + Z1].map(|h| 2.0 * PI * R * h);
    let got = areas(&back);
    for (g, e) in got.iter().zip(exact) {
        assert!((g - e).abs() / e < 1e-5, "{got:?} vs {exact:?}");
    }
}

#[test]
fn faces_on_the_other_side_of_their_loops_are_written_as_read_and_named() {
    // The band's two bounds reversed: the face would be what lies outside the band (two
    // caps, not one region of the parameter rectangle); the top cap's bound reversed: the
    // face would lie on the side of its circle away from its vertex loop. Neither is rebuilt.
    let text = zones_text()
        .replace(
            "#52=FACE_OUTER_BOUND('',#51,.T.);",
            "#52=FACE_OUTER_BOUND('',#51,.F.);",
        )
        .replace("#55=FACE_BOUND('',#54,.T.);", "#55=FACE_BOUND('',#54,.F.);")
        .replace(
            "#42=FACE_OUTER_BOUND('',#41,.T.);",
            "#42=FACE_OUTER_BOUND('',#41,.F.);",
        );
    let m = step::from_str(&text, "flipped.step").unwrap();
    let mut notes = Vec::new();
    let s = vericad::brep::seam_edges::explicit_seams(&m, m.brep.as_ref().unwrap(), &mut notes);
    let all = notes.join("\n");
    assert!(
        all.contains("face #56: ") && all.contains("outside the band"),
        "{all}"
    );
    assert!(
        all.contains("face #44: ") && all.contains("away from the vertex loop"),
        "{all}"
    );
    assert_eq!(s.faces, 1, "only the bottom cap is rebuilt: {all}");
}
