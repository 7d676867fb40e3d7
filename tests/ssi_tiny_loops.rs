//! Small loops found by the adaptive refinement of undecided coverage regions
//! (src/ssi/regions.rs): the dome `z = r² − ((x−½)² + (y−½)²)` over the unit square against the
//! 100 × 100 plane `z = 0` meets it in the circle of radius `r` about `(½, ½, 0)` (truth from
//! the construction). From `r = 1e-4` down the first triangulation cannot see the loop (the
//! dome stands `r²` ≤ 1e-8 above the plane, far below the mesh flatness); the run must still
//! find it and certify it: one closed branch, every vertex within its proven curve radius of
//! the true circle, every point of the true circle within the match distance of the output.

mod common;
use vericad::model::{Model, Surface};
use vericad::spline::NurbsSurface;
use vericad::ssi::{SsiParams, SsiResult, intersect_models};

const TOL: f64 = 1e-7;

fn dome(c: f64) -> NurbsSurface<f64, 3> {
    common::shapes::dome(c, 1.0)
}

fn run(c: f64) -> SsiResult {
    let big = common::shapes::square(50.0);
    let m = |s| Model {
        surfaces: vec![Surface::new("face", s)],
        ..Default::default()
    };
    let prm = SsiParams {
        tol: TOL,
        ..Default::default()
    };
    intersect_models(&m(dome(c)), Some(&m(big)), &prm, &|_, _| {}).unwrap()
}

/// Distance from `x` to the circle of radius `r` about `(½, ½, 0)` in `z = 0` (`x − ½` is
/// exact for `x` in [¼, 1]; the rounding of the rest is far below the radii compared).
fn to_circle(x: &[f64; 3], r: f64) -> f64 {
    let rho = (x[0] - 0.5).hypot(x[1] - 0.5);
    (rho - r).hypot(x[2])
}

fn to_segment(x: &[f64; 3], p: &[f64; 3], q: &[f64; 3]) -> f64 {
    let d: [f64; 3] = std::array::from_fn(|k| q[k] - p[k]);
    let dd: f64 = d.iter().map(|c| c * c).sum();
    let t = if dd > 0.0 {
        ((0..3).map(|k| (x[k] - p[k]) * d[k]).sum::<f64>() / dd).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (0..3)
        .map(|k| (x[k] - p[k] - t * d[k]).powi(2))
        .sum::<f64>()
        .sqrt()
}

#[test]
fn small_loops_are_found_and_certified() {
    for r in [1e-1, 1e-2, 1e-3, 1e-4, 1e-5, 1e-6] {
        let res = run(r * r);
        let s = &res.summary;
        let p = &res.pairs[0];
        let cov = p.coverage.as_ref().unwrap();
        println!(
            "r {r:e}: certified {}, branches {}, points {}, dist_curve_max {:?}, refinement {:?}",
            s.certified,
            p.branches.len(),
            s.points,
            s.dist_curve_max,
            cov.refinement
        );
        assert!(s.certified && cov.no_missed_branches, "r {r:e}: {s:?}");
        assert_eq!(p.branches.len(), 1, "r {r:e}");
        let b = &p.branches[0];
        assert!(b.closed);
        // Every vertex within its proven radius of the true circle.
        for (x, rad) in b.points.iter().zip(&b.curve_radius) {
            let rad = rad.expect("every point certified");
            let d = to_circle(x, r);
            assert!(
                d <= rad + 1e-18,
                "r {r:e}: {x:?} is {d:e} from the circle, radius {rad:e}"
            );
            assert!(rad <= TOL);
        }
        // Every point of the true circle near the output polygon (the loop is whole).
        let n = b.points.len();
        let worst = (0..1000)
            .map(|k| {
                let a = std::f64::consts::TAU * k as f64 / 1000.0;
                let c = [0.5 + r * a.cos(), 0.5 + r * a.sin(), 0.0];
                (0..n)
                    .map(|i| to_segment(&c, &b.points[i], &b.points[(i + 1) % n]))
                    .fold(f64::INFINITY, f64::min)
            })
            .fold(0.0f64, f64::max);
        assert!(
            worst <= cov.match_distance,
            "r {r:e}: circle point {worst:e} from the output"
        );
    }
}

/// The dome just below the plane (no intersection) and touching it at its top (one contact
/// point, which no mesh crossing shows): never a certified run with a branch that is not
/// there, never a certified run that misses the contact.
#[test]
fn no_loop_is_invented() {
    for c in [-1e-8, -1e-10] {
        let res = run(c);
        assert!(res.summary.certified, "{c}: {:?}", res.summary);
        assert!(res.pairs[0].branches.is_empty() && res.pairs[0].touch_points.is_empty());
    }
    let res = run(0.0);
    let p = &res.pairs[0];
    let at_top = p
        .touch_points
        .iter()
        .any(|t| to_circle(&t.point, 0.0) <= 1e-6)
        || p.branches
            .iter()
            .any(|b| b.points.iter().any(|x| to_circle(x, 0.0) <= 1e-6));
    assert!(!res.summary.certified || at_top, "{:?}", res.summary);
}
