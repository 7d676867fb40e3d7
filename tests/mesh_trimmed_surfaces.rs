//! Surfaces with their own trim loops (JSON `trim_loops`, IGES 144 not sewn into a B-rep)
//! written to a mesh format: triangulated inside their loops, as B-rep faces are. Before,
//! they were written untrimmed with a warning. Areas from the constructions: the plane
//! [0, 10]^2 trimmed to [1, 9]^2 minus the hole [4, 6]^2 (60), the hole alone (96: the face
//! is the domain minus it), a cylinder of radius 1 and height 1 trimmed to the band between
//! two loops winding around its seam at heights 0.2 and 0.8 (2 pi 0.6, chords of a measured
//! chordal deviation below 1e-4), and loops that cross (written untrimmed, named: 100).
mod common;
use common::trims::{crossing_loops, model, poly, trim_line};
use std::f64::consts::PI;
use vericad::model::{Model, TrimLoop};
use vericad::spline::construct::{Frame, bilinear, cylinder};
use vericad::tessellate::surfaces::mesh_surfaces;

fn area(m: &Model, tol: Option<f64>) -> (f64, Vec<String>) {
    let (t, _, notes) = mesh_surfaces(m, tol, false);
    let v = &t.vertices;
    let a = t
        .triangles
        .iter()
        .map(|x| {
            let [p, q, r] = x.map(|i| v[i as usize]);
            let (a, b) = (
                [0, 1, 2].map(|k| q[k] - p[k]),
                [0, 1, 2].map(|k| r[k] - p[k]),
            );
            let c = [
                a[1] * b[2] - a[2] * b[1],
                a[2] * b[0] - a[0] * b[2],
                a[0] * b[1] - a[1] * b[0],
            ];
            0.5 * (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt()
        })
        .sum();
    (a, notes)
}

fn plane() -> Model {
    model(vec![
        bilinear([0., 0., 0.], [10., 0., 0.], [0., 10., 0.], [10., 10., 0.]).unwrap(),
    ])
}

fn hole() -> TrimLoop {
    TrimLoop {
        outer: false,
        curves: poly(&[[0.4, 0.4], [0.4, 0.6], [0.6, 0.6], [0.6, 0.4]]),
    }
}

#[test]
fn a_plane_trimmed_to_a_square_minus_a_hole() {
    let mut m = plane();
    m.surfaces[0].trim_loops = vec![
        TrimLoop {
            outer: true,
            curves: poly(&[[0.1, 0.1], [0.9, 0.1], [0.9, 0.9], [0.1, 0.9]]),
        },
        hole(),
    ];
    let (a, notes) = area(&m, None);
    assert!(notes.is_empty(), "{notes:?}");
    assert!((a - 60.0).abs() < 1e-9, "{a}");
}

#[test]
fn a_plane_with_only_a_hole_is_the_domain_minus_it() {
    let mut m = plane();
    m.surfaces[0].trim_loops = vec![hole()];
    let (a, notes) = area(&m, None);
    assert!(notes.is_empty(), "{notes:?}");
    assert!((a - 96.0).abs() < 1e-9, "{a}");
}

#[test]
fn a_cylinder_band_between_loops_winding_around_the_seam() {
    let cyl = cylinder(&Frame::WORLD, 1.0, 0.0, 1.0).unwrap();
    let (u0, u1, _, _) = cyl.hom.domain();
    let mut m = model(vec![cyl]);
    m.surfaces[0].trim_loops = vec![
        TrimLoop {
            outer: true,
            curves: vec![trim_line([u0, 0.2], [u1, 0.2])],
        },
        TrimLoop {
            outer: false,
            curves: vec![trim_line([u1, 0.8], [u0, 0.8])],
        },
    ];
    let (a, notes) = area(&m, Some(1e-4));
    assert!(notes.is_empty(), "{notes:?}");
    let want = 2.0 * PI * 0.6;
    // Inscribed: below the true area, by at most the chords' sag over the band's perimeter.
    assert!(
        a <= want && want - a < 1e-4 * 2.0 * 2.0 * PI * 3.0,
        "{a} vs {want}"
    );
}

#[test]
fn crossing_loops_are_written_untrimmed_and_named() {
    let mut m = plane();
    m.surfaces[0].trim_loops = crossing_loops();
    let (a, notes) = area(&m, None);
    assert!((a - 100.0).abs() < 1e-9, "{a}");
    assert!(
        notes.len() == 1 && notes[0].contains("written untrimmed"),
        "{notes:?}"
    );
}
