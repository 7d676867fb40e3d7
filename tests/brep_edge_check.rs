//! Do the edges lie on their faces (`vericad info`, `brep::edge_check`)? On the public parts
//! every edge-face pair is proven within the model tolerance; an edge moved off its faces by
//! a known vector is reported, with a measurement no larger than the move; the IGES file whose
//! trims prefer their 2D curves has its edges built on the surface from them, and the same file
//! preferring its far 3D copies has every pair listed, none dropped.

use vericad::brep::edge_check::check_edges;
use vericad::geom::Hom;

fn read(path: &str) -> vericad::model::Model {
    let p = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(path);
    vericad::io::read_model(&p).unwrap()
}

#[test]
fn public_parts_have_every_edge_proven_on_its_faces() {
    for (file, pairs) in [
        ("tests/data/public/abc-0000.step", 66),
        ("tests/data/public/gmsh-t20_data.step", 96),
        ("tests/data/public/gmsh-periodic_u_cst.step", 6),
        ("tests/data/public/gmsh-cube1000.igs", 24),
    ] {
        let m = read(file);
        let c = check_edges(m.brep.as_ref().unwrap(), &m);
        assert_eq!(c.pairs, pairs, "{file}");
        assert_eq!(c.proven, c.pairs, "{file}: {:?}", c.not_proven);
        assert!(c.largest_bound <= c.tolerance, "{file}");
    }
}

/// One edge of abc-0000 translated by `v` (|v| = 1e-5, the model tolerance is 5.7e-9): the
/// pairs of that edge are no longer proven and their measured distance is at most `|v|` plus
/// the model tolerance (within which every pair was proven before); every other pair stays
/// proven.
#[test]
fn an_edge_moved_off_its_faces_is_reported() {
    let mut m = read("tests/data/public/abc-0000.step");
    let v = [3e-6, -4e-6, 1e-5 * (1.0f64 - 0.09 - 0.16).sqrt()];
    let norm = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    let b = m.brep.as_mut().unwrap();
    let tol = b.tolerance.max(1e-8 * b.extent());
    // The first edge with a curve that two faces use.
    let e = (0..b.edges.len())
        .find(|&e| {
            b.edges[e].curve.is_some()
                && b.faces
                    .iter()
                    .filter(|f| {
                        f.loops.iter().any(|l| match &l.kind {
                            vericad::brep::LoopKind::Edges(o) => o.iter().any(|x| x.edge == e),
                            _ => false,
                        })
                    })
                    .count()
                    == 2
        })
        .unwrap();
    let c = b.edges[e].curve.as_mut().unwrap();
    for h in c.nurbs.hom.control.iter_mut() {
        let w = h.w;
        *h = Hom {
            wp: std::array::from_fn(|k| h.wp[k] + w * v[k]),
            w,
        };
    }
    let source = b.edges[e].source.clone();
    let m = m;
    let checks = check_edges(m.brep.as_ref().unwrap(), &m);
    let moved: Vec<_> = checks
        .not_proven
        .iter()
        .filter(|x| x.edge == source)
        .collect();
    assert_eq!(moved.len(), 2, "{:?}", checks.not_proven);
    assert_eq!(
        checks.not_proven.len(),
        2,
        "only the moved edge: {:?}",
        checks.not_proven
    );
    for x in &moved {
        assert!(x.measured.unwrap() <= norm + tol + 1e-15, "{x:?}");
    }
    assert!(moved.iter().any(|x| x.above_tolerance), "{moved:?}");
}

/// occt-bad_header.igs with its 142's PREF (the last field of `142,CRTN,SPTR,BPTR,CPTR,PREF;`)
/// set to `pref`.
fn bad_header_with_pref(pref: &str) -> vericad::model::Model {
    let p = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/public/occt-bad_header.igs");
    let text = std::fs::read_to_string(p).unwrap();
    let old = "142,0,1,11,21,1;";
    assert!(text.contains(old));
    let t = text.replace(old, &format!("142,0,1,11,21,{pref};"));
    vericad::io::iges::from_str(&t, "bad_header.igs").unwrap()
}

/// The file's surface (DE 1, a rational 128 of degrees 1 × 2 over [0, 1]², control points
/// and weights as printed in the file, u varying fastest), evaluated here by its Bernstein
/// form: independent of the reader and of the B-spline code.
fn bad_header_surface(u: f64, v: f64) -> [f64; 3] {
    let p = [
        [[0.0, 0.0, 20.0], [10.0, 0.0, 0.0]],
        [[0.0, 0.0, 20.0], [8.6, 5.0, 0.0]],
        [[0.0, 0.0, 20.0], [5.0, 8.6, 0.0]],
    ];
    let w = [[1.0, 1.0], [1.0, 0.8], [1.0, 1.0]];
    let bu = [1.0 - u, u];
    let bv = [(1.0 - v) * (1.0 - v), 2.0 * v * (1.0 - v), v * v];
    let (mut num, mut den) = ([0.0; 3], 0.0);
    for j in 0..3 {
        for i in 0..2 {
            let c = bu[i] * bv[j] * w[j][i];
            den += c;
            for k in 0..3 {
                num[k] += c * p[j][i][k];
            }
        }
    }
    num.map(|x| x / den)
}

/// Its 142 prefers the parameter-space curve (PREF = 1; the model-space copy DE 21 is the unit
/// square, 8 units from the surface): the edges are built on the surface from the four
/// parameter-space lines (0.3, 0)–(0.7, 0)–(0.7, 1)–(0.3, 1). Each edge's ends are the images
/// of two consecutive corners and its points at 1/4, 1/2, 3/4 of its domain the images of the
/// line's points there (the edge keeps the line's parameter), by the file's surface evaluated
/// independently; every pair is proven on its face; the trimmed area is Open CASCADE's
/// (`BRepGProp::SurfaceProperties` of the file read by `IGESControl_Reader`, 27700.860280610286
/// mm², divided by 25.4²).
#[test]
fn a_preferred_parameter_space_curve_builds_edges_on_the_face() {
    let m = bad_header_with_pref("1");
    let b = m.brep.as_ref().unwrap();
    assert_eq!(b.edges.len(), 4);
    let corners = [[0.3, 0.0], [0.7, 0.0], [0.7, 1.0], [0.3, 1.0]];
    let mut used = [false; 4];
    for e in &b.edges {
        let c = &e.curve.as_ref().unwrap().nurbs;
        let (t0, t1) = c.hom.domain();
        let at = |f: f64| c.eval(&(t0 + f * (t1 - t0)));
        let close = |a: [f64; 3], b: [f64; 3]| (0..3).all(|k| (a[k] - b[k]).abs() <= 1e-12 * 20.0);
        let mut found = false;
        for k in 0..4 {
            let (a, z) = (corners[k], corners[(k + 1) % 4]);
            for (s, f) in [(a, z), (z, a)] {
                let line =
                    |x: f64| bad_header_surface(s[0] + x * (f[0] - s[0]), s[1] + x * (f[1] - s[1]));
                if [0.0, 0.25, 0.5, 0.75, 1.0]
                    .iter()
                    .all(|&x| close(at(x), line(x)))
                {
                    assert!(!used[k], "line {k} twice");
                    used[k] = true;
                    found = true;
                }
            }
        }
        assert!(found, "edge {} is not the image of a trim line", e.source);
    }
    assert_eq!(used, [true; 4]);
    let c = check_edges(b, &m);
    assert_eq!((c.pairs, c.proven), (4, 4), "{:?}", c.not_proven);
    assert!(
        m.warnings
            .iter()
            .any(|w| w.contains("142 PREF = 1") && w.contains("DE 23")),
        "{:?}",
        m.warnings
    );
    let area = vericad::tessellate::face_areas(&m, b)[0].area.unwrap();
    let occt = 27700.860280610286 / (25.4 * 25.4);
    assert!((area - occt).abs() <= 1e-9 * occt, "{area} vs {occt}");
}

/// The same file preferring its model-space copy (PREF = 2): the edges are that copy, far
/// from the surface, and every pair is listed, none dropped.
#[test]
fn far_trim_curves_are_listed() {
    let m = bad_header_with_pref("2");
    let c = check_edges(m.brep.as_ref().unwrap(), &m);
    assert_eq!(c.pairs, 4);
    assert_eq!(c.not_proven.len(), 4);
    assert!(
        c.not_proven
            .iter()
            .all(|x| x.above_tolerance && x.face == "DE 25")
    );
}
