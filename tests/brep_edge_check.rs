//! Do the edges lie on their faces (`vericad info`, `brep::edge_check`)? On the public parts
//! every edge-face pair is proven within the model tolerance; an edge moved off its faces by
//! a known vector is reported, with a measurement no larger than the move; and the IGES file
//! whose 3D trim curves lie far from their surface (it prefers the 2D ones) has every pair
//! listed, none dropped.

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

#[test]
fn far_trim_curves_are_listed() {
    let m = read("tests/data/public/occt-bad_header.igs");
    let c = check_edges(m.brep.as_ref().unwrap(), &m);
    assert_eq!(c.pairs, 4);
    assert_eq!(c.not_proven.len(), 4);
    assert!(
        c.not_proven
            .iter()
            .all(|x| x.above_tolerance && x.face == "DE 25")
    );
}
