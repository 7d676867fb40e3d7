//! Constructions shared by the SSI tests: the exact rational sphere and rotated frames.

use vericad::spline::NurbsSurface;
use vericad::spline::construct::{CIRCLE_KNOTS, Frame, bilinear};

/// The sphere of radius `r` about the origin with *exact* f64 data: quarter circles as
/// rational quadratics in non-standard form, corner weight 1 between end weights 1 and 2
/// (w1² / (w0 w2) = 1/2 = cos² 45°, the circle's condition), so no weight is rounded. Every
/// point of the surface lies exactly on the sphere (`exact_sphere_is_a_sphere` checks a few in
/// rationals).
pub fn exact_sphere(r: f64) -> NurbsSurface<f64, 3> {
    let circle: [([f64; 2], f64); 9] = [
        ([1.0, 0.0], 1.0),
        ([1.0, 1.0], 1.0),
        ([0.0, 1.0], 2.0),
        ([-1.0, 1.0], 1.0),
        ([-1.0, 0.0], 1.0),
        ([-1.0, -1.0], 1.0),
        ([0.0, -1.0], 2.0),
        ([1.0, -1.0], 1.0),
        ([1.0, 0.0], 1.0),
    ];
    // Profile (ρ, z) from the south pole to the north pole.
    let profile: [([f64; 2], f64); 5] = [
        ([0.0, -r], 1.0),
        ([r, -r], 1.0),
        ([r, 0.0], 2.0),
        ([r, r], 1.0),
        ([0.0, r], 1.0),
    ];
    let (mut pts, mut ws) = (Vec::new(), Vec::new());
    for (c, wc) in circle {
        for (p, wp) in profile {
            pts.push([p[0] * c[0], p[0] * c[1], p[1]]);
            ws.push(wc * wp);
        }
    }
    NurbsSurface::new(
        CIRCLE_KNOTS.to_vec(),
        2,
        vec![0.0, 0.0, 0.0, 0.5, 0.5, 1.0, 1.0, 1.0],
        2,
        9,
        5,
        pts,
        ws,
    )
    .unwrap()
}

/// A frame rotated by the unit quaternion `q / |q|` about the origin `o`.
pub fn frame_of(q: [f64; 4], o: [f64; 3]) -> Frame {
    let n = q.iter().map(|x| x * x).sum::<f64>().sqrt();
    let [w, x, y, z] = q.map(|c| c / n);
    Frame {
        o,
        x: [
            1.0 - 2.0 * (y * y + z * z),
            2.0 * (x * y + w * z),
            2.0 * (x * z - w * y),
        ],
        y: [
            2.0 * (x * y - w * z),
            1.0 - 2.0 * (x * x + z * z),
            2.0 * (y * z + w * x),
        ],
        z: [
            2.0 * (x * z + w * y),
            2.0 * (y * z - w * x),
            1.0 - 2.0 * (x * x + y * y),
        ],
    }
}

pub fn rotated(seed: u64) -> Frame {
    // A rotation from a unit quaternion of a simple deterministic sequence.
    let s = seed as f64;
    let q = [
        0.3 + s.sin(),
        0.7 * (1.3 * s).cos(),
        0.5 - (0.7 * s).sin(),
        0.2 + (2.1 * s).cos(),
    ];
    frame_of(q, [0.1 * s.cos(), -0.2, 0.3])
}

/// The biquadratic dome `z = c − k((x−½)² + (y−½)²)` over the unit square (Bézier, exact
/// data): against the plane `z = 0` it meets it in the circle of radius `√(c/k)` about
/// `(½, ½, 0)` when `c > 0`.
pub fn dome(c: f64, k: f64) -> NurbsSurface<f64, 3> {
    let g = [0.25, -0.25, 0.25]; // Bernstein coefficients of (x − ½)² on [0, 1]
    let xs = [0.0, 0.5, 1.0];
    let mut pts = Vec::new();
    for i in 0..3 {
        for j in 0..3 {
            pts.push([xs[i], xs[j], c - k * (g[i] + g[j])]);
        }
    }
    let kn = vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0];
    NurbsSurface::new(kn.clone(), 2, kn, 2, 3, 3, pts, vec![1.0; 9]).unwrap()
}

/// The plane `z = 0` over `[-h, h]²`, bilinear.
pub fn square(h: f64) -> NurbsSurface<f64, 3> {
    bilinear([-h, -h, 0.0], [h, -h, 0.0], [-h, h, 0.0], [h, h, 0.0]).unwrap()
}
