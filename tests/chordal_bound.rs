//! The proven chordal bound of a tessellation (`src/tessellate/bound.rs`) against surfaces
//! whose distance function is known in closed form: a sphere and a torus in rotated frames.
//! Every point of every triangle (a barycentric grid of 66 points each) must lie within the
//! bound of the true surface, and every sampled point of the surface within it of the mesh;
//! and the bound must be useful (within a small factor of the measured deviation).

use vericad::geom::triangle::closest_point;
use vericad::geom::{dist, norm};
use vericad::model::{Model, Surface, Triangulation};
use vericad::spline::construct::{Frame, sphere, torus};
use vericad::tessellate::surfaces::mesh_surfaces;

fn frame() -> Frame {
    // A rotation by 120° about (1, 1, 1) (its axes permuted) and an offset origin.
    Frame {
        o: [0.3, -1.7, 2.2],
        x: [0.0, 1.0, 0.0],
        y: [0.0, 0.0, 1.0],
        z: [1.0, 0.0, 0.0],
    }
}

/// Local coordinates of `p` in `f`.
fn local(f: &Frame, p: &[f64; 3]) -> [f64; 3] {
    let d = [p[0] - f.o[0], p[1] - f.o[1], p[2] - f.o[2]];
    let dot = |a: &[f64; 3]| a[0] * d[0] + a[1] * d[1] + a[2] * d[2];
    [dot(&f.x), dot(&f.y), dot(&f.z)]
}

/// Largest true distance from the mesh's points (66 per triangle) to the surface.
fn mesh_to_surface(t: &Triangulation, d: &dyn Fn(&[f64; 3]) -> f64) -> f64 {
    let n = 10;
    let mut worst = 0.0f64;
    for tri in &t.triangles {
        let p = tri.map(|i| t.vertices[i as usize]);
        for i in 0..=n {
            for j in 0..=n - i {
                let (a, b) = (i as f64 / n as f64, j as f64 / n as f64);
                let c = 1.0 - a - b;
                let x: [f64; 3] = std::array::from_fn(|k| a * p[0][k] + b * p[1][k] + c * p[2][k]);
                worst = worst.max(d(&x));
            }
        }
    }
    worst
}

/// Largest distance from the surface's points `pts` to the mesh (closest point on every
/// triangle, brute force).
fn surface_to_mesh(t: &Triangulation, pts: &[[f64; 3]]) -> f64 {
    pts.iter()
        .map(|s| {
            t.triangles
                .iter()
                .map(|tri| {
                    let p = tri.map(|i| t.vertices[i as usize]);
                    dist(s, &closest_point(s, &p[0], &p[1], &p[2]).0)
                })
                .fold(f64::INFINITY, f64::min)
        })
        .fold(0.0, f64::max)
}

fn check(m: &Model, tol: f64, d: &dyn Fn(&[f64; 3]) -> f64) -> (f64, f64) {
    let (t, c, _) = mesh_surfaces(m, Some(tol), true);
    let c = c.unwrap();
    let proven = c.proven.expect("asked for");
    assert_eq!(
        c.unbounded, 0,
        "every triangle lies in one knot span: {c:?}"
    );
    let worst = mesh_to_surface(&t, d);
    assert!(
        worst <= proven,
        "mesh point {worst:e} from the surface, bound {proven:e}"
    );
    // Surface points on a parameter grid (the surface's own evaluation; its error is at
    // rounding level, far below the figures compared).
    let s = &m.surfaces[0].nurbs;
    let (u0, u1, v0, v1) = s.hom.domain();
    let k = 37;
    let pts: Vec<[f64; 3]> = (0..=k)
        .flat_map(|i| (0..=k).map(move |j| (i, j)))
        .map(|(i, j)| {
            let u = u0 + (u1 - u0) * (i as f64 + 0.37) / (k as f64 + 1.0);
            let v = v0 + (v1 - v0) * (j as f64 + 0.61) / (k as f64 + 1.0);
            s.eval(&u, &v)
        })
        .collect();
    let back = surface_to_mesh(&t, &pts);
    assert!(
        back <= proven,
        "surface point {back:e} from the mesh, bound {proven:e}"
    );
    // Useful: not far above what is measured.
    assert!(
        proven <= 4.0 * c.measured.max(worst),
        "bound {proven:e} against measured {:e} (true {worst:e})",
        c.measured
    );
    (proven, worst)
}

#[test]
fn a_sphere_mesh_lies_within_its_proven_bound_both_ways() {
    let f = frame();
    let m = Model {
        surfaces: vec![Surface::new("sphere", sphere(&f, 1.5).unwrap())],
        ..Default::default()
    };
    let on = |p: &[f64; 3]| (dist(p, &f.o) - 1.5).abs();
    let (proven, worst) = check(&m, 2e-2, &on);
    assert!(worst > 1e-3, "the mesh is not trivially fine: {worst:e}");
    assert!(proven < 1e-1, "{proven:e}");
}

#[test]
fn a_torus_mesh_lies_within_its_proven_bound_both_ways() {
    let f = frame();
    let (major, minor) = (2.0, 0.6);
    let m = Model {
        surfaces: vec![Surface::new("torus", torus(&f, major, minor).unwrap())],
        ..Default::default()
    };
    let on = |p: &[f64; 3]| {
        let q = local(&f, p);
        let rho = norm(&[q[0], q[1], 0.0]);
        ((rho - major).hypot(q[2]) - minor).abs()
    };
    let (proven, worst) = check(&m, 2e-3, &on);
    assert!(worst > 1e-4, "the mesh is not trivially fine: {worst:e}");
    assert!(proven < 1e-2, "{proven:e}");
}
