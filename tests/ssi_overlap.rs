//! Overlapping curved surfaces, truth from the construction: two patches of the unit
//! cylinder about the z axis over angles [0°, 90°] × z [0, 1] and [45°, 135°] × z [0.3, 1.3]
//! (different control nets: neither identical nor coplanar) share exactly the region
//! angles [45°, 90°] × z [0.3, 1]. Negative controls: surfaces that touch along a line, or
//! are near but apart, must not be called overlapping.

use vericad::model::{Model, Surface};
use vericad::spline::NurbsSurface;
use vericad::spline::construct::{Frame, arc, extrude};
use vericad::ssi::coincide::CoincidenceKind;
use vericad::ssi::{SsiParams, SsiResult, intersect_models};

fn cyl(r: f64, centre: [f64; 2], a0: f64, a1: f64, z0: f64, h: f64) -> NurbsSurface<f64, 3> {
    let f = Frame {
        o: [centre[0], centre[1], z0],
        x: [1.0, 0.0, 0.0],
        y: [0.0, 1.0, 0.0],
        z: [0.0, 0.0, 1.0],
    };
    let c = arc(&f, r, a0.to_radians(), a1.to_radians()).unwrap();
    extrude(&c, &[0.0, 0.0, h]).unwrap()
}

fn run(a: NurbsSurface<f64, 3>, b: NurbsSurface<f64, 3>) -> SsiResult {
    let m = |s| Model {
        surfaces: vec![Surface::new("s", s)],
        ..Default::default()
    };
    intersect_models(&m(a), Some(&m(b)), &SsiParams::default(), &|_, _| {}).unwrap()
}

/// Angle (degrees) and height of a point of the unit cylinder.
fn angle_z(p: [f64; 3]) -> (f64, f64) {
    (p[1].atan2(p[0]).to_degrees(), p[2])
}

#[test]
fn overlapping_cylinder_patches_are_reported_as_overlap() {
    let a = cyl(1.0, [0.0, 0.0], 0.0, 90.0, 0.0, 1.0);
    let b = cyl(1.0, [0.0, 0.0], 45.0, 135.0, 0.3, 1.0);
    let r = run(a.clone(), b.clone());
    let p = &r.pairs[0];
    let c = p.coincident.as_ref().expect("overlap reported");
    assert_eq!(c.kind, CoincidenceKind::Overlap);
    let o = c.overlap.as_ref().unwrap();
    // The box of overlap samples on A lies inside the true overlap (angle monotone in u, z
    // linear in v: the region is a parameter rectangle), and covers it up to a grid step or two.
    let step_deg = 90.0 / 16.0;
    let (mut lo_a, mut hi_a, mut lo_z, mut hi_z) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for u in [o.uv_a[0], o.uv_a[1]] {
        for v in [o.uv_a[2], o.uv_a[3]] {
            let (ang, z) = angle_z(a.eval(&u, &v));
            assert!((45.0 - 1e-6..=90.0 + 1e-6).contains(&ang), "angle {ang}");
            assert!((0.3 - 1e-9..=1.0 + 1e-9).contains(&z), "z {z}");
            lo_a = lo_a.min(ang);
            hi_a = hi_a.max(ang);
            lo_z = lo_z.min(z);
            hi_z = hi_z.max(z);
        }
    }
    assert!(
        lo_a <= 45.0 + 2.0 * step_deg && hi_a >= 90.0 - 1e-6,
        "{lo_a}..{hi_a}"
    );
    assert!(
        lo_z <= 0.3 + 2.0 / 16.0 && hi_z >= 1.0 - 1e-9,
        "{lo_z}..{hi_z}"
    );
    assert!(o.max_distance <= 1e-6);
    assert!(o.branches_removed > 0, "the spurious branches were counted");
    // Whatever branches remain lie outside the overlap box on A.
    for br in &p.branches {
        assert!(
            br.uv_a.iter().any(|x| !(o.uv_a[0] < x[0]
                && x[0] < o.uv_a[1]
                && o.uv_a[2] < x[1]
                && x[1] < o.uv_a[3])),
            "a branch inside the overlap remains"
        );
    }
    assert!(!r.summary.certified);
    assert!(
        r.summary
            .certificate
            .iter()
            .any(|l| l.starts_with("OVERLAP"))
    );
    // Symmetric: the same boxes, sides exchanged.
    let r2 = run(b, a);
    let o2 = r2.pairs[0]
        .coincident
        .as_ref()
        .unwrap()
        .overlap
        .as_ref()
        .unwrap();
    assert_eq!((o2.uv_a, o2.uv_b), (o.uv_b, o.uv_a));
}

#[test]
fn contact_along_a_line_or_a_near_miss_is_not_an_overlap() {
    // A cylinder of radius 0.5 inside the unit one, touching it along the line x = 1.
    let a = cyl(1.0, [0.0, 0.0], -60.0, 60.0, 0.0, 1.0);
    let inner = cyl(0.5, [0.5, 0.0], -60.0, 60.0, 0.0, 1.0);
    let r = run(a.clone(), inner);
    assert!(r.pairs.iter().all(|p| p.coincident.is_none()));
    // A concentric cylinder 1e-3 larger: parallel normals everywhere, no common point.
    let outer = cyl(1.0 + 1e-3, [0.0, 0.0], -60.0, 60.0, 0.0, 1.0);
    let r = run(a, outer);
    assert!(r.pairs.iter().all(|p| p.coincident.is_none()));
    assert_eq!(r.summary.branches, 0);
}
