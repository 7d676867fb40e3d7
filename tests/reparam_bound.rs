//! The proven deviation bound of the reparametrization (`reparam::bound`) against
//! independent oracles: for surfaces whose point set is known analytically (a rectangle in a
//! plane, a quarter cylinder, a sphere patch), the exact distance of dense samples of the new
//! surface N to that set must not exceed `e_max_proven`; and the bound must not be loose
//! (ratio to the sampled evidence). A grid that breaks a hypothesis gives no bound and a
//! reason.

use std::f64::consts::PI;
use vericad::reparam::{Params, Reparametrized, bound, reparametrize};

mod common;
use common::reparam::{lattice, pole_sphere_patch, quarter_cylinder, separable_plane};

/// The proven bound (when there is one) is at least the oracle distance of every sample of N
/// to the analytic set; the figures are printed (the docs' table is this output).
fn check(
    name: &str,
    r: &Reparametrized,
    oracle: impl Fn([f64; 3]) -> f64,
    tol: f64,
) -> Option<f64> {
    let rep = &r.report;
    let b = rep.bound.as_ref().expect("bound computed");
    let mut worst: f64 = 0.0;
    for (s, t) in lattice(200) {
        worst = worst.max(oracle(r.surface.eval(&s, &t)));
    }
    eprintln!(
        "{name}: proven {:?} (reason {:?}), evidence {:.3e}, oracle {worst:.3e}, boxes {} \
         (budget reached {}), target {:.2e}, bound {:.3} s of {:.3} s, ctrl {:?}",
        b.e_max_proven,
        b.reason,
        rep.deviation.e_max,
        b.boxes,
        b.budget_reached,
        b.target,
        b.seconds,
        rep.seconds,
        rep.control_points_after
    );
    assert!(
        worst <= rep.deviation.e_max * 1.5 + 1e-12,
        "{name}: evidence"
    );
    if let Some(proven) = b.e_max_proven {
        assert!(
            worst <= proven,
            "{name}: oracle {worst:e} above the proven {proven:e}"
        );
        assert!(proven >= rep.deviation.e_max * (1.0 - 1e-6), "{name}");
        assert_eq!(rep.within_tol_proven, proven <= tol);
    } else {
        assert!(b.reason.is_some() && !rep.within_tol_proven);
    }
    b.e_max_proven
}

/// Product weights on a rectangular net: the set is the rectangle `[0,4] × [0,2]`.
#[test]
fn separable_plane_bound() {
    let s = separable_plane();
    let p = Params {
        tol: 1e-5,
        ..Params::default()
    };
    let r = reparametrize(&s, &p).unwrap();
    // Exact distance to the rectangle.
    let rect = |x: [f64; 3]| {
        let dx = (x[0] - x[0].clamp(0.0, 4.0)).abs();
        let dy = (x[1] - x[1].clamp(0.0, 2.0)).abs();
        dx.hypot(dy).hypot(x[2])
    };
    check("separable plane", &r, rect, p.tol);
}

/// The quarter cylinder `r = 2`, `0 ≤ θ ≤ π/2`, `0 ≤ z ≤ 3`, Möbius-reparametrized arc and
/// non-uniform axial weights. Exact distance to the patch:
/// `sqrt(r² + R² − 2 r R cos Δθ + Δz²)` with `Δθ`, `Δz` the excess over the ranges.
#[test]
fn cylinder_bound_against_the_exact_distance() {
    let (rad, h, rho) = (2.0, 3.0, 5.0);
    let s = quarter_cylinder(rad, h, rho);
    let p = Params {
        tol: 1e-4,
        ..Params::default()
    };
    let r = reparametrize(&s, &p).unwrap();
    let patch = |x: [f64; 3]| {
        let rr = x[0].hypot(x[1]);
        let th = x[1].atan2(x[0]);
        let dth = th - th.clamp(0.0, PI / 2.0);
        let dz = x[2] - x[2].clamp(0.0, h);
        (rr * rr + rad * rad - 2.0 * rr * rad * dth.cos())
            .max(0.0)
            .sqrt()
            .hypot(dz)
    };
    check("cylinder", &r, patch, p.tol);
}

/// A sphere patch from the equator to the north pole (a pole border): every point of N is at
/// least `||x| − R|` from the sphere, so that is a lower bound of its distance to the patch.
#[test]
fn sphere_patch_with_a_pole_bound() {
    let s = pole_sphere_patch();
    let p = Params {
        tol: 1e-4,
        ..Params::default()
    };
    let r = reparametrize(&s, &p).unwrap();
    assert_eq!(r.report.poles, [false, true, false, false]);
    check(
        "sphere",
        &r,
        |x| (vericad::geom::norm(&x) - 1.5).abs(),
        p.tol,
    );
}

/// A grid whose boundary point has left its side of the domain: the degree argument does
/// not apply, so there is no bound, and the reason says which point.
#[test]
fn a_grid_off_its_side_has_no_bound() {
    let s = vericad::spline::construct::cylinder(
        &vericad::spline::construct::Frame::WORLD,
        1.0,
        0.0,
        1.0,
    )
    .unwrap();
    let p = Params {
        tol: 1e-3,
        ..Params::default()
    };
    let r = reparametrize(&s, &p).unwrap();
    let mut g = r.grid.clone();
    g.uv[2][0][1] += 1e-3;
    let b = bound::prove(&s, &r.surface, &g, 1e-3, 10_000);
    assert!(b.e_max_proven.is_none());
    let why = b.reason.unwrap();
    assert!(why.contains("grid point (2, 0)"), "{why}");
    // The pipeline's own run with the bound off reports the evidence as the decider.
    let off = Params {
        prove_bound: false,
        ..p
    };
    let r = reparametrize(&s, &off).unwrap();
    assert!(r.report.bound.is_none() && r.report.decided_by == "evidence");
    assert!(r.report.within_tol && !r.report.within_tol_proven);
}

/// A plane parametrized uniformly (a bilinear patch): N and φ are exact up to rounding, the
/// bound is proven far below ε, and it decides.
#[test]
fn bilinear_plane_is_proven_within_tolerance() {
    let s = vericad::spline::construct::bilinear(
        [0.0, 0.0, 0.0],
        [2.0, 0.0, 0.0],
        [0.0, 1.0, 0.5],
        [2.0, 1.0, 0.5],
    )
    .unwrap();
    let p = Params {
        tol: 1e-6,
        ..Params::default()
    };
    let r = reparametrize(&s, &p).unwrap();
    let n = [0.0, -0.5, 1.0];
    let len = 1.25f64.sqrt();
    let plane = |x: [f64; 3]| ((x[1] * n[1] + x[2] * n[2]) / len).abs();
    let b = check("bilinear plane", &r, plane, p.tol).expect("proven");
    assert!(b <= p.tol && r.report.within_tol_proven && r.report.decided_by == "proven");
}

/// The B-spline faces of the gmsh t20 model at ε = 1e-4: how many get a proven bound ≤ ε,
/// and the time with and without the bound (the docs' table is this output).
#[test]
fn t20_faces_bound() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/public/gmsh-t20_data.step");
    let m = vericad::io::read_model(&path).unwrap();
    let on = Params::default();
    let off = Params {
        prove_bound: false,
        ..Params::default()
    };
    let (mut faces, mut proven_le, mut t_on, mut t_off) = (0, 0, 0.0, 0.0);
    eprintln!(
        "| face | E_max (evidence) | e_max_proven | boxes | bound s | run s | run s without |"
    );
    for (k, f) in m.surfaces.iter().enumerate() {
        let (Ok(a), Ok(b)) = (reparametrize(&f.nurbs, &on), reparametrize(&f.nurbs, &off)) else {
            continue;
        };
        faces += 1;
        let bd = a.report.bound.as_ref().unwrap();
        if bd.e_max_proven.is_some_and(|x| x <= on.tol) {
            proven_le += 1;
        }
        if let Some(x) = bd.e_max_proven {
            assert!(x >= a.report.deviation.e_max * (1.0 - 1e-6));
        }
        t_on += a.report.seconds;
        t_off += b.report.seconds;
        eprintln!(
            "| {k} | {:.2e} | {} | {} | {:.3} | {:.3} | {:.3} |",
            a.report.deviation.e_max,
            bd.e_max_proven
                .map_or(format!("none: {:?}", bd.reason), |x| format!("{x:.2e}")),
            bd.boxes,
            bd.seconds,
            a.report.seconds,
            b.report.seconds
        );
    }
    eprintln!(
        "t20: {proven_le} of {faces} faces proven ≤ ε; {t_on:.2} s with the bound, {t_off:.2} s without"
    );
    assert_eq!(faces, 21);
}
