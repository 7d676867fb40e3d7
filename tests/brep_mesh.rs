//! Trimmed tessellation of STEP B-reps: crack-free (shared edges use the same vertices on both
//! faces), watertight where the shell is closed (every mesh edge used by exactly two
//! triangles, once in each direction), and trimmed areas against analytic values.

use std::collections::BTreeMap;
use std::path::Path;
use vericad::io::step;
use vericad::tessellate::{MeshParams, mesh_brep};

fn model(name: &str) -> vericad::model::Model {
    let p = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/public")
        .join(name);
    step::read(&p).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// Uses of each mesh edge `(a, b)`.
type Uses = BTreeMap<(u32, u32), usize>;

/// Uses of each undirected mesh edge, and of each directed one.
fn edge_uses(tris: &[[u32; 3]]) -> (Uses, Uses) {
    let mut und = BTreeMap::new();
    let mut dir = BTreeMap::new();
    for t in tris {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            *und.entry((a.min(b), a.max(b))).or_insert(0) += 1;
            *dir.entry((a, b)).or_insert(0) += 1;
        }
    }
    (und, dir)
}

/// Signed volume enclosed by a triangulation (divergence theorem; positive when the
/// triangles face outward).
fn volume(t: &vericad::model::Triangulation) -> f64 {
    t.triangles
        .iter()
        .map(|tri| {
            let [a, b, c] = tri.map(|i| t.vertices[i as usize]);
            let cr = vericad::geom::cross(&b, &c);
            vericad::geom::dot(&a, &cr) / 6.0
        })
        .sum()
}

fn watertight(name: &str) -> f64 {
    let m = model(name);
    let b = m.brep.as_ref().unwrap();
    assert!(
        b.shells.iter().all(|s| s.closed),
        "{name}: every shell closed"
    );
    let mesh = mesh_brep(&m, b, &MeshParams::default());
    let issues = mesh.issues(b);
    for (f, r) in b.faces.iter().zip(&mesh.faces) {
        eprintln!("{name} {} {:?}", f.source, r.as_ref().map(|x| x.1));
    }
    assert!(issues.is_empty(), "{issues:?}");
    let (und, dir) = edge_uses(&mesh.triangulation.triangles);
    let bad: Vec<_> = und.iter().filter(|(_, n)| **n != 2).collect();
    assert!(
        bad.is_empty(),
        "{} of {} edges not used twice: {:?}",
        bad.len(),
        und.len(),
        &bad[..bad.len().min(20)]
    );
    let twice: Vec<_> = dir.iter().filter(|(_, n)| **n != 1).collect();
    assert!(
        twice.is_empty(),
        "directed edges used twice (inconsistent orientation): {:?}",
        &twice[..twice.len().min(10)]
    );
    volume(&mesh.triangulation)
}

/// Volumes of the files' solids from Open CASCADE 8.0.1 (`BRepGProp::VolumeProperties`,
/// relative precision 1e-9, in mm³): the mesh volume (chordal, default sampling) must be close
/// and positive (faces oriented outward).
fn close_to(name: &str, mesh_volume_mm3: f64, occt: f64, rel: f64) {
    let d = (mesh_volume_mm3 - occt).abs() / occt;
    eprintln!("{name}: mesh volume {mesh_volume_mm3} mm³, Open CASCADE {occt}: {d:e}");
    assert!(
        d < rel,
        "{name}: mesh volume {mesh_volume_mm3} vs Open CASCADE {occt}: {d:e}"
    );
}

#[test]
fn abc_is_watertight() {
    let v = watertight("abc-0000.step") * 1e9; // m³ to mm³
    // Chords of at most 15° of turn cut 1.1% off this part's mostly curved solids.
    close_to("abc-0000.step", v, 3166280.0220566047, 2e-2);
}

#[test]
fn t20_is_watertight() {
    let v = watertight("gmsh-t20_data.step");
    close_to("gmsh-t20_data.step", v, 18384.504524105512, 1e-2);
}

#[test]
fn periodic_is_watertight() {
    let v = watertight("gmsh-periodic_u_cst.step");
    close_to("gmsh-periodic_u_cst.step", v, 13429.869097403192, 1e-2);
}

#[test]
fn abc_converts_to_a_watertight_stl() {
    // Written by the converter, read back by the STL reader (vertices welded by position):
    // every directed edge is matched by its reverse, so the surface is closed and consistently
    // oriented. Its six solids touch one another (e.g. along a circle on z = 0.10456), so after
    // welding a few edges are used four times — by two closed solids, twice each.
    let m = model("abc-0000.step");
    let dir = std::env::temp_dir().join(format!("vericad-brep-mesh-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("abc.stl");
    vericad::io::write_model(&out, &m).unwrap();
    let back = vericad::io::stl::read(&out).unwrap();
    let t = &back.triangulations[0];
    let (und, dir_uses) = edge_uses(&t.triangles);
    let odd: Vec<_> = und.iter().filter(|(_, n)| **n % 2 != 0).collect();
    assert!(odd.is_empty(), "{odd:?}");
    for ((a, b), n) in &dir_uses {
        assert_eq!(dir_uses.get(&(*b, *a)), Some(n), "edge {a}-{b}");
    }
    let twice = und.values().filter(|&&n| n == 2).count();
    assert!(
        twice + 4 >= und.len(),
        "{} of {} edges used twice",
        twice,
        und.len()
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// A STEP file of one face: `face` and `bounds` around the sphere or plane below.
fn one_face(data: &str) -> vericad::model::Model {
    let text = format!(
        "ISO-10303-21;\nHEADER;\nFILE_SCHEMA(('AUTOMOTIVE_DESIGN'));\nENDSEC;\nDATA;
#1=CARTESIAN_POINT('',(0.,0.,0.));
#2=DIRECTION('',(0.,0.,1.));
#3=DIRECTION('',(1.,0.,0.));
#4=AXIS2_PLACEMENT_3D('',#1,#2,#3);
#5=PLANE('',#4);
#6=SPHERICAL_SURFACE('',#4,2.);
#10=CARTESIAN_POINT('',(2.,0.,0.));
#11=VERTEX_POINT('',#10);
#12=CIRCLE('',#4,2.);
#13=EDGE_CURVE('',#11,#11,#12,.T.);
#14=ORIENTED_EDGE('',*,*,#13,.T.);
#15=EDGE_LOOP('',(#14));
#16=FACE_OUTER_BOUND('',#15,.T.);
#20=CARTESIAN_POINT('',(0.,0.,2.));
#21=VERTEX_POINT('',#20);
#22=VERTEX_LOOP('',#21);
#23=FACE_BOUND('',#22,.T.);
{data}
ENDSEC;\nEND-ISO-10303-21;\n"
    );
    step::from_str(&text, "one-face.step").unwrap()
}

fn area_of(m: &vericad::model::Model) -> f64 {
    let b = m.brep.as_ref().unwrap();
    let a = vericad::tessellate::face_areas(m, b);
    assert_eq!(a.len(), 1);
    a[0].area.unwrap_or_else(|| panic!("{:?}", a[0].note))
}

#[test]
fn a_disc_has_area_pi_r_squared() {
    let m = one_face("#30=ADVANCED_FACE('',(#16),#5,.T.);");
    let a = area_of(&m);
    let exact = std::f64::consts::PI * 4.0;
    assert!((a - exact).abs() / exact < 1e-9, "{a} vs {exact}");
}

#[test]
fn a_hemisphere_to_its_pole_has_area_two_pi_r_squared() {
    // Walking the equator counter-clockwise about +z with the outward normal, the face is
    // on the left: the upper hemisphere, closed at the pole (0, 0, 2) by the vertex loop.
    let m = one_face("#30=ADVANCED_FACE('',(#16,#23),#6,.T.);");
    let a = area_of(&m);
    let exact = 2.0 * std::f64::consts::PI * 4.0;
    assert!((a - exact).abs() / exact < 1e-6, "{a} vs {exact}");
    let b = m.brep.as_ref().unwrap();
    let mesh = mesh_brep(&m, b, &MeshParams::default());
    let t = &mesh.triangulation;
    assert!(t.vertices.iter().all(|p| p[2] >= -1e-12), "upper half only");
    // Outward: the volume of the hemisphere closed by its base disc is positive, and the
    // triangles' normals point away from the centre.
    for tri in &t.triangles {
        let [a, b, c] = tri.map(|i| t.vertices[i as usize]);
        let n = vericad::geom::cross(
            &vericad::geom::Point::sub(&b, &a),
            &vericad::geom::Point::sub(&c, &a),
        );
        let centroid = [
            (a[0] + b[0] + c[0]) / 3.0,
            (a[1] + b[1] + c[1]) / 3.0,
            (a[2] + b[2] + c[2]) / 3.0,
        ];
        assert!(vericad::geom::dot(&n, &centroid) > 0.0);
    }
    // The reversed face (same_sense .F.) without the vertex loop: the lower hemisphere,
    // closed at the south pole.
    let m = one_face("#30=ADVANCED_FACE('',(#16),#6,.F.);");
    let a = area_of(&m);
    assert!((a - exact).abs() / exact < 1e-6, "{a} vs {exact}");
    let b = m.brep.as_ref().unwrap();
    let mesh = mesh_brep(&m, b, &MeshParams::default());
    assert!(
        mesh.triangulation.vertices.iter().all(|p| p[2] <= 1e-12),
        "lower half only"
    );
}

/// The z component of the first triangle's normal.
fn normal_z(m: &vericad::model::Model) -> f64 {
    let mesh = mesh_brep(m, m.brep.as_ref().unwrap(), &MeshParams::default());
    let t = &mesh.triangulation;
    let [a, b, c] = t.triangles[0].map(|i| t.vertices[i as usize]);
    vericad::geom::cross(
        &vericad::geom::Point::sub(&b, &a),
        &vericad::geom::Point::sub(&c, &a),
    )[2]
}

#[test]
fn faces_turn_with_same_sense_and_with_oriented_faces_in_the_shell() {
    // The disc's loop runs counter-clockwise about +z: with same_sense .T. on the plane
    // (normal +z) the triangles face +z; same_sense .F. and a shell's ORIENTED_FACE .F. each
    // turn them over.
    let up = one_face("#30=ADVANCED_FACE('',(#16),#5,.T.);\n#31=OPEN_SHELL('',(#30));");
    assert!(normal_z(&up) > 0.0);
    let down = one_face("#30=ADVANCED_FACE('',(#16),#5,.F.);\n#31=OPEN_SHELL('',(#30));");
    assert!(normal_z(&down) < 0.0);
    let turned = one_face(
        "#30=ADVANCED_FACE('',(#16),#5,.T.);\n#32=ORIENTED_FACE('',*,#30,.F.);\n#31=OPEN_SHELL('',(#32));",
    );
    assert!(normal_z(&turned) < 0.0);
    assert_eq!(
        turned.brep.as_ref().unwrap().shells[0].faces,
        vec![(0, false)]
    );
}

#[test]
fn trimmed_areas_agree_with_open_cascade() {
    // Total face areas from Open CASCADE 8.0.1 (`BRepGProp::SurfaceProperties`, relative
    // precision 1e-9, mm²) for the public files with topology.
    for (name, to_mm2, occt) in [
        ("abc-0000.step", 1e6, 404864.5993),
        ("gmsh-periodic_u_cst.step", 1.0, 27087.80537),
        ("gmsh-t20_data.step", 1.0, 6365.476297),
    ] {
        let m = model(name);
        let a: f64 = vericad::tessellate::face_areas(&m, m.brep.as_ref().unwrap())
            .iter()
            .map(|f| f.area.unwrap())
            .sum::<f64>()
            * to_mm2;
        let d = (a - occt).abs() / occt;
        assert!(d < 1e-5, "{name}: {a} vs {occt}: {d:e}");
    }
}

#[test]
fn reader_fuzz_artifacts_read_as_step_never_panic_in_the_mesher() {
    // Every reader artifact read as STEP text: an error or a model; a B-rep gets checked and
    // triangulated without a panic.
    let dir =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/faulty/fuzz-artifacts/readers");
    let mut read = 0;
    for f in std::fs::read_dir(&dir).unwrap() {
        let bytes = std::fs::read(f.unwrap().path()).unwrap();
        read += 1;
        if let Ok(m) = step::from_str(&String::from_utf8_lossy(&bytes), "artifact.step")
            && let Some(b) = &m.brep
        {
            let _ = b.check();
            let _ = mesh_brep(&m, b, &MeshParams::default());
        }
    }
    assert!(read > 0);
}

mod corrupted {
    //! abc-0000.step with references rewired at random (dangling, cyclic, wrong types, edges
    //! moved between loops): reading, checking and triangulating never panic and end soon.
    use super::*;
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]
        #[test]
        fn rewired_references_never_panic(edits in proptest::collection::vec((0usize..4000, 1u32..900), 1..12)) {
            let p = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/public/abc-0000.step");
            let text = std::fs::read_to_string(p).unwrap();
            // Positions of references in the DATA section ('#' not starting a line).
            let refs: Vec<usize> = text
                .match_indices('#')
                .map(|(i, _)| i)
                .filter(|&i| i > 0 && text.as_bytes()[i - 1] != b'\n')
                .collect();
            let mut t = text.clone().into_bytes();
            let mut out = String::new();
            let mut last = 0;
            let mut chosen: Vec<(usize, u32)> = edits.iter().map(|(k, v)| (refs[k % refs.len()], *v)).collect();
            chosen.sort();
            chosen.dedup_by_key(|c| c.0);
            for (pos, v) in chosen {
                let end = pos + 1 + t[pos + 1..].iter().take_while(|c| c.is_ascii_digit()).count();
                out.push_str(std::str::from_utf8(&t[last..pos]).unwrap());
                out.push_str(&format!("#{v}"));
                last = end;
            }
            out.push_str(std::str::from_utf8(&t[last..]).unwrap());
            t.clear();
            let start = std::time::Instant::now();
            if let Ok(m) = step::from_str(&out, "rewired.step")
                && let Some(b) = &m.brep
            {
                let _ = b.check();
                let _ = mesh_brep(&m, b, &MeshParams::default());
            }
            prop_assert!(start.elapsed().as_secs_f64() < 10.0);
        }
    }
}
