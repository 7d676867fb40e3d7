//! Shared constructions of the Coons-patch tests: boundary specs, a plane model, the
//! fuselage (Open CASCADE's bug28366) with boundaries along iso-curves of its patches, and
//! the largest of a function over a dense lattice of an approximant.

use vericad::approx::coons::boundary::{BoundarySpec, CurveRef, CurveSpec};
use vericad::model::{Model, Surface};
use vericad::spline::NurbsSurface;
use vericad::spline::construct::bilinear;

pub fn by_index(i: usize) -> CurveSpec {
    CurveSpec {
        curve: Some(CurveRef::Index(i)),
        polyline: None,
        reversed: false,
        name: None,
    }
}

pub fn polyline(pts: Vec<[f64; 3]>) -> CurveSpec {
    CurveSpec {
        curve: None,
        polyline: Some(pts),
        reversed: false,
        name: None,
    }
}

pub fn square(z: f64, s: f64) -> Vec<CurveSpec> {
    let p = |x: f64, y: f64| [x * s, y * s, z];
    vec![
        polyline(vec![p(0.0, 0.0), p(1.0, 0.0)]),
        polyline(vec![p(1.0, 0.0), p(1.0, 1.0)]),
        polyline(vec![p(1.0, 1.0), p(0.0, 1.0)]),
        polyline(vec![p(0.0, 1.0), p(0.0, 0.0)]),
    ]
}

pub fn plane_model() -> Model {
    Model {
        surfaces: vec![Surface::new(
            "plane",
            bilinear(
                [-1.0, -1.0, 0.0],
                [2.0, -1.0, 0.0],
                [-1.0, 2.0, 0.0],
                [2.0, 2.0, 0.0],
            )
            .unwrap(),
        )],
        ..Default::default()
    }
}

pub fn fuselage() -> Model {
    let p = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/public/occt-bug28366_fuselage.stp");
    vericad::io::read_model(&p).unwrap()
}

/// Polyline along an iso-curve of surface `s`: `(u, v)` from `a` to `b`, 40 segments.
pub fn iso(m: &Model, s: usize, a: [f64; 2], b: [f64; 2]) -> Vec<[f64; 3]> {
    (0..=40)
        .map(|k| {
            let t = k as f64 / 40.0;
            let (u, v) = (a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]));
            m.surfaces[s].nurbs.eval(&u, &v)
        })
        .collect()
}

pub fn joined(mut a: Vec<[f64; 3]>, b: Vec<[f64; 3]>) -> Vec<[f64; 3]> {
    a.pop();
    a.extend(b);
    a
}

/// The fuselage's top around the joint of its front and rear sections: four patches
/// (0, 1 in front, 4, 5 behind), boundaries along iso-curves sampled as polylines.
pub fn fuselage_top(m: &Model) -> BoundarySpec {
    BoundarySpec {
        curves: vec![
            polyline(joined(
                iso(m, 0, [2.5, 0.5], [3.0, 0.5]),
                iso(m, 4, [0.0, 0.5], [0.5, 0.5]),
            )),
            polyline(joined(
                iso(m, 4, [0.5, 0.5], [0.5, 1.0]),
                iso(m, 5, [0.5, 0.0], [0.5, 0.5]),
            )),
            polyline(joined(
                iso(m, 5, [0.5, 0.5], [0.0, 0.5]),
                iso(m, 1, [3.0, 0.5], [2.5, 0.5]),
            )),
            polyline(joined(
                iso(m, 1, [2.5, 0.5], [2.5, 0.0]),
                iso(m, 0, [2.5, 1.0], [2.5, 0.5]),
            )),
        ],
    }
}

/// Largest of `f` over an `k × k` lattice of the approximant's domain, restricted by `keep`.
pub fn dense_max(
    s: &NurbsSurface<f64, 3>,
    k: usize,
    f: impl Fn(&[f64; 3]) -> f64,
    keep: impl Fn(&[f64; 3]) -> bool,
) -> f64 {
    let mut worst: f64 = 0.0;
    for i in 0..=k {
        for j in 0..=k {
            let p = s.eval(&(i as f64 / k as f64), &(j as f64 / k as f64));
            if keep(&p) {
                worst = worst.max(f(&p));
            }
        }
    }
    worst
}
