//! A model without gaps has no artificial projection, on its border included: a 3 × 3 set
//! of bilinear patches of a height field, boundary polylines along its outer border through
//! the patch corners (which lie on the patches). There every offset segment meets the outer
//! edge of a border triangle exactly, where rounding alone used to decide the hit.

use vericad::approx::coons::Params;
use vericad::approx::coons::approximant::approximate;
use vericad::approx::coons::boundary::BoundarySpec;
use vericad::model::{Model, Surface};
use vericad::spline::construct::bilinear;

fn height(x: f64, y: f64) -> [f64; 3] {
    [x, y, 0.8 * (0.3 * x).sin() * (0.4 * y).cos()]
}

#[test]
fn border_points_of_a_gapless_model_are_hits() {
    let mut surfaces = Vec::new();
    for i in 0..3 {
        for j in 0..3 {
            let (x, y) = (i as f64, j as f64);
            let s = bilinear(
                height(x, y),
                height(x + 1.0, y),
                height(x, y + 1.0),
                height(x + 1.0, y + 1.0),
            )
            .unwrap();
            surfaces.push(Surface::new(format!("p{i}{j}"), s));
        }
    }
    let m = Model {
        surfaces,
        ..Default::default()
    };
    let side =
        |f: &dyn Fn(f64) -> [f64; 3]| -> Vec<[f64; 3]> { (0..=3).map(|k| f(k as f64)).collect() };
    let text = serde_json::json!({"curves": [
        {"polyline": side(&|t| height(t, 0.0))},
        {"polyline": side(&|t| height(3.0, t))},
        {"polyline": side(&|t| height(3.0 - t, 3.0))},
        {"polyline": side(&|t| height(0.0, 3.0 - t))},
    ]})
    .to_string();
    let spec = BoundarySpec::parse(&text).unwrap();
    for n in [6, 9, 12] {
        let p = Params {
            tol: 1e-1,
            m: n,
            n,
            max_resolution: n,
            ..Default::default()
        };
        let a = approximate(&m, &spec, &p).unwrap();
        let artificial = a.artificial.data.iter().filter(|x| **x).count();
        assert_eq!(artificial, 0, "{n} x {n}: {artificial} artificial points");
        // Every projected point lies on the height field's patches: its z is the bilinear
        // interpolation of the corner heights of the patch it falls in (x, y in [0, 3]).
        for q in &a.points.data {
            let (x, y) = (q[0].clamp(0.0, 3.0), q[1].clamp(0.0, 3.0));
            let (i, j) = ((x.floor() as usize).min(2), (y.floor() as usize).min(2));
            let (s, t) = (x - i as f64, y - j as f64);
            let z = |a: usize, b: usize| height((i + a) as f64, (j + b) as f64)[2];
            let zt = (1.0 - s) * (1.0 - t) * z(0, 0)
                + s * (1.0 - t) * z(1, 0)
                + (1.0 - s) * t * z(0, 1)
                + s * t * z(1, 1);
            assert!(
                (q[2] - zt).abs() <= 1e-9,
                "{q:?} off the patches by {}",
                q[2] - zt
            );
        }
    }
}
