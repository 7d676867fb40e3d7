//! Faces given by their own trim loops, for the end-to-end trim tests: a model of surfaces,
//! polygon loops of straight trim curves, and the distance from a point to a segment.
use vericad::model::{Model, Surface, TrimLoop};
use vericad::spline::{NurbsCurve, NurbsSurface};

pub fn model(surfaces: Vec<NurbsSurface<f64, 3>>) -> Model {
    Model {
        surfaces: surfaces
            .into_iter()
            .enumerate()
            .map(|(k, s)| Surface::new(format!("face {k}"), s))
            .collect(),
        ..Default::default()
    }
}
pub fn trim_line(a: [f64; 2], b: [f64; 2]) -> NurbsCurve<f64, 2> {
    NurbsCurve::new(vec![0.0, 0.0, 1.0, 1.0], 1, vec![a, b], vec![1.0, 1.0]).unwrap()
}
pub fn poly(p: &[[f64; 2]]) -> Vec<NurbsCurve<f64, 2>> {
    (0..p.len())
        .map(|k| trim_line(p[k], p[(k + 1) % p.len()]))
        .collect()
}
pub fn seg_dist(q: [f64; 3], a: [f64; 3], b: [f64; 3]) -> f64 {
    let ab = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let aq = [q[0] - a[0], q[1] - a[1], q[2] - a[2]];
    let l2: f64 = ab.iter().map(|x| x * x).sum();
    let t = if l2 > 0.0 {
        (0..3).map(|k| ab[k] * aq[k]).sum::<f64>() / l2
    } else {
        0.0
    };
    let t = t.clamp(0.0, 1.0);
    (0..3)
        .map(|k| (a[k] + t * ab[k] - q[k]).powi(2))
        .sum::<f64>()
        .sqrt()
}

/// Trim loops whose polygons cross, in the unit parameter square: an outer square
/// [0, 0.6]^2 and a "hole" [0.4, 0.8] x [0.2, 0.4] straddling its edge.
pub fn crossing_loops() -> Vec<TrimLoop> {
    vec![
        TrimLoop {
            outer: true,
            curves: poly(&[[0.0, 0.0], [0.6, 0.0], [0.6, 0.6], [0.0, 0.6]]),
        },
        TrimLoop {
            outer: false,
            curves: poly(&[[0.4, 0.2], [0.8, 0.2], [0.8, 0.4], [0.4, 0.4]]),
        },
    ]
}
