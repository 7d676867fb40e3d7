//! Real CAD files written by other tools (`tests/data/public`): every file loads, with the face
//! counts and surface kinds Open CASCADE reports (the table in shared/data/README.md, copied
//! here by hand); round trips keep every bit; analytic conversions are exact.

use std::path::PathBuf;
use vericad::io::{iges, read_model, step};
use vericad::model::{Model, SurfaceKind};

fn data(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/public")
        .join(name)
}

fn count(m: &Model, k: SurfaceKind) -> usize {
    m.surfaces.iter().filter(|s| s.kind == k).count()
}

/// A table row.
type Row = (
    &'static str,
    usize,
    Option<(usize, usize)>,
    usize,
    usize,
    usize,
    usize,
    usize,
);

/// (file, faces, B-spline non-rational, B-spline rational or None when the README does not
/// split them, planes, spheres, cones, tori)
#[test]
fn every_shared_file_loads_with_the_readme_counts() {
    let table: [Row; 8] = [
        ("gmsh-t20_data.step", 21, Some((7, 14)), 21, 0, 0, 0, 0),
        ("gmsh-cube1000.igs", 6, None, 6, 0, 0, 0, 0),
        (
            "gmsh-sphere_Rhino3D_default.igs",
            1,
            Some((0, 1)),
            1,
            0,
            0,
            0,
            0,
        ),
        ("gmsh-periodic_u_cst.step", 3, None, 2, 1, 0, 0, 0),
        ("occt-BUC50025.igs", 7, None, 7, 0, 0, 0, 0),
        ("occt-bad_header.igs", 1, None, 1, 0, 0, 0, 0),
        ("occt-bug28366_fuselage.stp", 8, None, 8, 0, 0, 0, 0),
        ("abc-0000.step", 25, None, 2, 8, 7, 5, 3),
    ];
    for (f, faces, split, bspline, planes, spheres, cones, tori) in table {
        let m = read_model(&data(f)).unwrap_or_else(|e| panic!("{f}: {e}"));
        assert_eq!(m.surfaces.len(), faces, "{f}: faces");
        assert_eq!(count(&m, SurfaceKind::BSpline), bspline, "{f}: B-spline");
        assert_eq!(count(&m, SurfaceKind::Plane), planes, "{f}: planes");
        assert_eq!(count(&m, SurfaceKind::Sphere), spheres, "{f}: spheres");
        assert_eq!(count(&m, SurfaceKind::Cone), cones, "{f}: cones");
        assert_eq!(count(&m, SurfaceKind::Torus), tori, "{f}: tori");
        if let Some((poly, rat)) = split {
            let b: Vec<_> = m
                .surfaces
                .iter()
                .filter(|s| s.kind == SurfaceKind::BSpline)
                .collect();
            assert_eq!(
                b.iter().filter(|s| s.nurbs.is_polynomial()).count(),
                poly,
                "{f}: non-rational"
            );
            assert_eq!(
                b.iter().filter(|s| !s.nurbs.is_polynomial()).count(),
                rat,
                "{f}: rational"
            );
        }
        // Every surface evaluates to finite points over its domain.
        for s in &m.surfaces {
            let (u0, u1, v0, v1) = s.nurbs.hom.domain();
            for i in 0..=4 {
                for j in 0..=4 {
                    let p = s.nurbs.eval(
                        &(u0 + (u1 - u0) * i as f64 / 4.0),
                        &(v0 + (v1 - v0) * j as f64 / 4.0),
                    );
                    assert!(p.iter().all(|x| x.is_finite()), "{f}: {}", s.name);
                }
            }
        }
    }
    // Units, and the source entity counts the README names.
    for (f, u) in [
        ("gmsh-t20_data.step", "mm"),
        ("abc-0000.step", "m"),
        ("occt-bug28366_fuselage.stp", "foot"),
        ("gmsh-cube1000.igs", "mm"),
    ] {
        assert_eq!(
            read_model(&data(f)).unwrap().unit.as_deref(),
            Some(u),
            "{f}"
        );
    }
    let cube = read_model(&data("gmsh-cube1000.igs")).unwrap();
    let n126: usize = cube
        .source_entities
        .iter()
        .filter(|(k, _)| k.starts_with("126 "))
        .map(|(_, n)| n)
        .sum();
    assert_eq!(n126, 48, "gmsh-cube1000.igs: 48 entities 126");
    let stl = read_model(&data("gmsh-surface1.stl")).unwrap();
    let t = &stl.triangulations[0];
    assert!(!t.triangles.is_empty());
    assert!(
        t.vertices.len() < 3 * t.triangles.len(),
        "vertices are welded"
    );
}

fn same_bits(a: &Model, b: &Model) {
    assert_eq!(a.surfaces.len(), b.surfaces.len());
    for (x, y) in a.surfaces.iter().zip(&b.surfaces) {
        let (hx, hy) = (&x.nurbs.hom, &y.nurbs.hom);
        assert_eq!(hx.degrees(), hy.degrees());
        let bits = |k: &[f64]| k.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(hx.ku.knots()), bits(hy.ku.knots()));
        assert_eq!(bits(hx.kv.knots()), bits(hy.kv.knots()));
        let (px, wx) = x.nurbs.points_weights();
        let (py, wy) = y.nurbs.points_weights();
        for (p, q) in px.iter().zip(&py) {
            assert_eq!(p.map(f64::to_bits), q.map(f64::to_bits));
        }
        assert_eq!(bits(&wx), bits(&wy));
    }
}

#[test]
fn iges_and_step_round_trips_keep_every_bit() {
    for f in [
        "occt-BUC50025.igs",
        "gmsh-sphere_Rhino3D_default.igs",
        "gmsh-cube1000.igs",
    ] {
        let m = read_model(&data(f)).unwrap();
        let again = iges::from_str(&iges::write::to_string(&m, f), "rt.igs").unwrap();
        same_bits(&m, &again);
    }
    for f in [
        "gmsh-t20_data.step",
        "occt-bug28366_fuselage.stp",
        "abc-0000.step",
    ] {
        let m = read_model(&data(f)).unwrap();
        let again = step::from_str(&step::write::to_string(&m, f), "rt.step").unwrap();
        same_bits(&m, &again);
    }
}

/// Spheres and tori of abc-0000.step: the converted NURBS agree with the STEP entity's own
/// radii (and placement origin) at many parameters.
#[test]
fn analytic_conversions_match_their_closed_forms() {
    let text = std::fs::read_to_string(data("abc-0000.step")).unwrap();
    let p = step::part21::parse(&text).unwrap();
    let m = step::from_str(&text, "abc").unwrap();
    let mut checked = 0;
    for s in &m.surfaces {
        let face: u64 = s.source.as_ref().unwrap()[1..].parse().unwrap();
        let sid = p
            .entities
            .get(&face)
            .unwrap()
            .part("ADVANCED_FACE")
            .unwrap()[2]
            .reference()
            .unwrap();
        let e = p.entities.get(&sid).unwrap();
        let origin = |a: &[step::part21::Value]| {
            let pl = p.entities.get(&a[1].reference().unwrap()).unwrap();
            let loc = p
                .entities
                .get(
                    &pl.part("AXIS2_PLACEMENT_3D").unwrap()[1]
                        .reference()
                        .unwrap(),
                )
                .unwrap();
            let c: Vec<f64> = loc.part("CARTESIAN_POINT").unwrap()[1].numbers().unwrap();
            [c[0], c[1], c[2]]
        };
        let samples = |f: &dyn Fn([f64; 3]) -> f64| {
            for i in 0..=24 {
                for j in 0..=24 {
                    let x = s.nurbs.eval(&(i as f64 / 24.0), &(j as f64 / 24.0));
                    let d = f(x);
                    assert!(
                        d.abs() < 1e-12 * (1.0 + x.iter().map(|c| c.abs()).fold(0.0, f64::max)),
                        "{}: {d}",
                        s.name
                    );
                }
            }
        };
        if let Some(a) = e.part("SPHERICAL_SURFACE") {
            let (o, r) = (origin(a), a[2].num().unwrap());
            samples(&|x| vericad::geom::dist(&x, &o) - r);
            checked += 1;
        }
        if let Some(a) = e.part("TOROIDAL_SURFACE") {
            let (o, big, small) = (origin(a), a[2].num().unwrap(), a[3].num().unwrap());
            // Distance to the torus's core circle requires the axis; check the weaker but
            // exact invariant |x - o| ∈ [R - r, R + r].
            samples(&|x| {
                let d = vericad::geom::dist(&x, &o);
                if d < big - small - 1e-12 {
                    d - (big - small)
                } else if d > big + small + 1e-12 {
                    d - (big + small)
                } else {
                    0.0
                }
            });
            checked += 1;
        }
    }
    assert_eq!(checked, 10, "7 spheres and 3 tori");
}

#[test]
fn malformed_files_get_located_errors() {
    let e = step::from_str(
        "ISO-10303-21;\nDATA;\n#1=CARTESIAN_POINT('',(0.,1.);\nENDSEC;",
        "bad.step",
    )
    .unwrap_err();
    assert!(e.location.starts_with("line"), "{e}");
    let e = step::from_str(
        "DATA;\n#1=ADVANCED_FACE('',(),#9,.T.);\nENDSEC;",
        "bad.step",
    )
    .unwrap_err();
    assert_eq!(e.location, "#9", "{e}");
    let e = iges::from_str("short line\n", "bad.igs").unwrap_err();
    assert_eq!(e.location, "line 1");
    // A 128 whose parameter list is cut short.
    let good = std::fs::read_to_string(data("occt-bad_header.igs")).unwrap();
    let cut: String = good
        .lines()
        .filter(|l| !(l.len() >= 73 && &l[72..73] == "P") || l.contains("128,"))
        .collect::<Vec<_>>()
        .join("\n");
    assert!(iges::from_str(&cut, "cut.igs").is_err());
    assert!(matches!(
        read_model(std::path::Path::new("x.dwg")),
        Err(vericad::io::ReadError::UnknownFormat(_))
    ));
}

/// IGES trims: each face of the cube (143 bounded by 141) keeps one closed outer loop of four
/// parameter-space curves; the loops survive the JSON format.
#[test]
fn iges_trim_loops_are_kept_and_closed() {
    let m = read_model(&data("gmsh-cube1000.igs")).unwrap();
    for s in &m.surfaces {
        assert_eq!(s.trim_loops.len(), 1, "{}", s.name);
        let l = &s.trim_loops[0];
        assert!(l.outer);
        assert_eq!(l.curves.len(), 4);
        let ends: Vec<([f64; 2], [f64; 2])> = l
            .curves
            .iter()
            .map(|c| {
                let (a, b) = c.hom.domain();
                (c.eval(&a), c.eval(&b))
            })
            .collect();
        for k in 0..4 {
            let (e, s2) = (ends[k].1, ends[(k + 1) % 4].0);
            assert!(
                (e[0] - s2[0]).abs() + (e[1] - s2[1]).abs() < 1e-9,
                "{}: loop open between curves {k} and {}",
                s.name,
                (k + 1) % 4
            );
        }
    }
    let again = vericad::model::json::from_str(&vericad::model::json::to_string(&m), "rt").unwrap();
    assert_eq!(
        again
            .surfaces
            .iter()
            .map(|s| s.trim_loops.clone())
            .collect::<Vec<_>>(),
        m.surfaces
            .iter()
            .map(|s| s.trim_loops.clone())
            .collect::<Vec<_>>()
    );
}

/// occt-bad_header.igs has the invalid units flag 0: read as the IGES default, inch (as Open
/// CASCADE reads it), with a warning; written back with flag 1, in either IGES form.
#[test]
fn invalid_iges_units_flag_falls_back_to_inch_with_a_warning() {
    let m = read_model(&data("occt-bad_header.igs")).unwrap();
    assert_eq!(m.unit.as_deref(), Some("inch"));
    assert!(
        m.warnings.iter().any(|w| w.contains("units flag")),
        "{:?}",
        m.warnings
    );
    let brep = iges::write::write_with(&m, "x", iges::write::BrepForm::BrepEntities).0;
    let again = iges::from_str(&brep, "x.igs").unwrap();
    assert_eq!(again.unit.as_deref(), Some("inch"));
    assert!(again.warnings.is_empty(), "{:?}", again.warnings);
    // As a trimmed surface: the face sewn from the file's trims has no pcurve, so its 142
    // holds the model-space boundary only, which the reader sews again (and says so).
    let faces = iges::write::write_with(&m, "x", iges::write::BrepForm::TrimmedSurfaces).0;
    let again = iges::from_str(&faces, "x.igs").unwrap();
    assert_eq!(again.unit.as_deref(), Some("inch"));
    assert!(
        again.warnings.iter().all(|w| !w.contains("units")),
        "{:?}",
        again.warnings
    );
    assert_eq!(again.brep.as_ref().map(|b| b.faces.len()), Some(1));
}

/// No public file has a face spanning the seam of its surface's NURBS form: none is
/// re-parametrized on reading (brep::seams), so every public model keeps its parameters.
#[test]
fn no_public_surface_is_reparametrized() {
    for e in std::fs::read_dir(data("")).unwrap() {
        let p = e.unwrap().path();
        let ext = p.extension().and_then(|x| x.to_str()).unwrap_or("");
        if !["step", "stp", "igs", "iges"].contains(&ext) {
            continue;
        }
        let m = read_model(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()));
        assert!(
            !m.warnings
                .iter()
                .any(|w| w.contains("re-parametrized so that their seam")),
            "{}",
            p.display()
        );
    }
}
