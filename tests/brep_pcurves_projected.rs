//! Pcurves the writers make by projecting edges onto faces that have none
//! (`brep::pcurve::Pcurves`), with a proven bound on how far each one's image lies from its
//! edge. Oracle from the construction: a spherical triangle bounded by three arcs of great
//! circles on a sphere of radius `R` placed in a tilted frame, so that no arc is a parameter
//! line of the sphere's NURBS form and the arcs cross its knot lines. A point's distance from
//! a great circle (normal `n`) has the closed form `√((|x − (x·n)n| − R)² + (x·n)²)`; the
//! spherical triangle's area is `R²·E`, `E` its spherical excess (Girard).

use vericad::brep::pcurve::Pcurves;
use vericad::geom::{Point, cross, dot};
use vericad::io::iges::write::BrepForm;
use vericad::io::{iges, step};

const R: f64 = 3.0;

fn unit(x: [f64; 3]) -> [f64; 3] {
    x.scale(&(1.0 / dot(&x, &x).sqrt()))
}

/// The sphere's frame: axis (1, 2, 2)/3, reference direction (2, −2, 1)/3; the triangle
/// lies round their cross product, about 25° wide, across the sphere's equator (a knot line
/// of its NURBS form) and away from its seam.
fn corners() -> [[f64; 3]; 3] {
    let (z, x) = (
        [1.0, 2.0, 2.0].scale(&(1.0 / 3.0)),
        [2.0, -2.0, 1.0].scale(&(1.0 / 3.0)),
    );
    let y = cross(&z, &x);
    // Counter-clockwise seen from outside the sphere (x × z = −y).
    [330.0f64, 210.0, 90.0].map(|deg| {
        let t = deg.to_radians();
        unit(y.add(&x.scale(&(0.45 * t.cos())).add(&z.scale(&(0.45 * t.sin()))))).scale(&R)
    })
}

fn triangle_text() -> String {
    let p = corners();
    let mut d = String::from(
        "#1=CARTESIAN_POINT('',(0.,0.,0.));\n#2=DIRECTION('',(1.,2.,2.));\n#3=DIRECTION('',(2.,-2.,1.));\n#4=AXIS2_PLACEMENT_3D('',#1,#2,#3);\n",
    );
    d += &format!("#5=SPHERICAL_SURFACE('',#4,{R:?});\n");
    for (i, q) in p.iter().enumerate() {
        d += &format!(
            "#{}=CARTESIAN_POINT('',({:?},{:?},{:?}));\n#{}=VERTEX_POINT('',#{});\n",
            10 + 2 * i,
            q[0],
            q[1],
            q[2],
            11 + 2 * i,
            10 + 2 * i
        );
    }
    for i in 0..3 {
        let (a, b) = (p[i], p[(i + 1) % 3]);
        let n = unit(cross(&a, &b));
        let r = unit(a);
        let k = 20 + 10 * i;
        d += &format!(
            "#{k}=DIRECTION('',({:?},{:?},{:?}));\n#{}=DIRECTION('',({:?},{:?},{:?}));\n#{}=AXIS2_PLACEMENT_3D('',#1,#{k},#{});\n#{}=CIRCLE('',#{},{R:?});\n#{}=EDGE_CURVE('',#{},#{},#{},.T.);\n#{}=ORIENTED_EDGE('',*,*,#{},.T.);\n",
            n[0],
            n[1],
            n[2],
            k + 1,
            r[0],
            r[1],
            r[2],
            k + 2,
            k + 1,
            k + 3,
            k + 2,
            k + 4,
            11 + 2 * i,
            11 + 2 * ((i + 1) % 3),
            k + 3,
            k + 5,
            k + 4
        );
    }
    d += "#60=EDGE_LOOP('',(#25,#35,#45));\n#61=FACE_OUTER_BOUND('',#60,.T.);\n#62=ADVANCED_FACE('triangle',(#61),#5,.T.);\n#63=OPEN_SHELL('',(#62));\n";
    format!(
        "ISO-10303-21;\nHEADER;\nFILE_SCHEMA(('AUTOMOTIVE_DESIGN'));\nENDSEC;\nDATA;\n{d}ENDSEC;\nEND-ISO-10303-21;\n"
    )
}

/// Every projected pcurve carries a bound within the model tolerance, and the bound holds:
/// its image, at 2001 points, lies within it of the great circle (closed form), and its ends
/// within it of the edge's vertices.
#[test]
fn projected_pcurves_on_a_spherical_triangle_are_proven_and_the_proof_holds() {
    let m = step::from_str(&triangle_text(), "triangle.step").unwrap();
    let b = m.brep.as_ref().unwrap();
    assert_eq!((b.faces.len(), b.edges.len()), (1, 3));
    let s = &m.surfaces[b.faces[0].surface.unwrap()].nurbs;
    let mut pcs = Pcurves::new(b, &m);
    let off = b.tolerance.max(1e-8 * b.extent());
    let p = corners();
    for e in 0..3 {
        let pc = pcs.get(e, 0).expect("a projected pcurve");
        let r = pcs.bound(e, 0).expect("a proven bound");
        assert!(r <= off, "edge {e}: bound {r:e} above {off:e}");
        let edge = &b.edges[e];
        let (a, z) = (b.vertices[edge.start].point, b.vertices[edge.end].point);
        let n = unit(cross(&a, &z));
        let (f0, f1) = pc.hom.domain();
        let mut worst: f64 = 0.0;
        for i in 0..=2000 {
            let q = pc.eval(&(f0 + (f1 - f0) * i as f64 / 2000.0));
            let x = s.eval(&q[0], &q[1]);
            let h = dot(&x, &n);
            let radial = x.sub(&n.scale(&h));
            worst = worst.max(((dot(&radial, &radial).sqrt() - R).powi(2) + h * h).sqrt());
        }
        assert!(
            worst <= r,
            "edge {e}: {worst:e} from its circle, bound {r:e}"
        );
        let ends = [pc.eval(&f0), pc.eval(&f1)].map(|q| s.eval(&q[0], &q[1]));
        assert!(vericad::geom::dist(&ends[0], &p[e]) <= r + 1e-12);
        assert!(vericad::geom::dist(&ends[1], &p[(e + 1) % 3]) <= r + 1e-12);
    }
    let note = pcs.note().unwrap();
    assert!(
        note.contains("3 of 3 edge-surface pairs; 3 proven"),
        "{note}"
    );
}

/// Girard: the area of a spherical triangle is `R²(α + β + γ − π)`.
fn girard_area() -> f64 {
    let p = corners().map(unit);
    let angle = |a: [f64; 3], b: [f64; 3], c: [f64; 3]| {
        let t1 = unit(cross(&cross(&a, &b), &a));
        let t2 = unit(cross(&cross(&a, &c), &a));
        dot(&t1, &t2).clamp(-1.0, 1.0).acos()
    };
    let e = angle(p[0], p[1], p[2]) + angle(p[1], p[2], p[0]) + angle(p[2], p[0], p[1])
        - std::f64::consts::PI;
    R * R * e
}

/// Written as STEP and as both IGES forms, the face carries the pcurves (three `PCURVE`s; a
/// 142 with a parameter-space curve) and reads back with Girard's area.
#[test]
fn the_triangle_written_with_its_pcurves_keeps_girards_area() {
    let m = step::from_str(&triangle_text(), "triangle.step").unwrap();
    let want = girard_area();
    let area = |m: &vericad::model::Model| -> f64 {
        let b = m.brep.as_ref().unwrap();
        vericad::tessellate::face_areas(m, b)
            .iter()
            .map(|f| f.area.unwrap_or_else(|| panic!("{f:?}")))
            .sum()
    };
    assert!(
        (area(&m) - want).abs() <= 1e-5 * want,
        "{} vs {want}",
        area(&m)
    );
    let (text, notes) = step::write::write(&m, "triangle");
    assert_eq!(text.matches("PCURVE(").count(), 3, "{notes:?}");
    let back = step::from_str(&text, "triangle-written.step").unwrap();
    assert!((area(&back) - want).abs() <= 1e-5 * want);
    for form in [BrepForm::BrepEntities, BrepForm::TrimmedSurfaces] {
        let (text, notes) = iges::write::write_with(&m, "triangle", form);
        assert!(
            notes.iter().any(|n| n.contains("3 proven")),
            "{form:?}: {notes:?}"
        );
        assert!(!notes.iter().any(|n| n.contains("model-space curves only")));
        let back = iges::from_str(&text, "triangle.igs").unwrap();
        assert!((area(&back) - want).abs() <= 1e-5 * want, "{form:?}");
    }
}
