//! Curves on rational surfaces: the certificate against closed forms.
//!
//! A sphere of radius 3 built as the tensor product of the standard NURBS circle (9 points,
//! weights `1, √2/2, …`) and half circle, in a frame tilted against its axis. Its points are
//! known without the library's evaluator: on each quarter arc the NURBS parameter gives the
//! point `((1−s)² + √2 s(1−s), √2 s(1−s) + s²) / ((1−s)² + √2 s(1−s) + s²)`, whose angle
//! turns by quarters. So the exact image `S(D(t))` of a domain curve is computed here from
//! angles, and the output curve is checked two ways:
//! - **on the surface**: every point of every output segment (a rational Bézier curve,
//!   evaluated here by its own de Casteljau) is at distance 3 from the centre, up to the
//!   printed rounding the certificate states;
//! - **Hausdorff**: samples of each curve projected onto the other (nearest sample, then a
//!   golden-section search on the parameter) stay within the proven bound, which stays
//!   within `ε_D`.
//!
//! Domain curves run next to the pole (where `S_u` vanishes) and along the seam, and the
//! same sphere with every weight scaled by `1e6` (the same surface) must certify alike.

mod common;
use common::curves::{dist, project, segment_point};
use vericad::curve_on_surface::{Arithmetic, CurveOnSurface, Params, approximate};
use vericad::spline::{NurbsCurve, NurbsSurface};

const R: f64 = 3.0;
const CENTRE: [f64; 3] = [1.0, -2.0, 0.5];

/// An orthonormal frame tilted against every axis (rows are the images of x, y, z).
fn frame() -> [[f64; 3]; 3] {
    let (a, b) = (0.7f64, 0.4f64);
    let rz = [
        [a.cos(), -a.sin(), 0.0],
        [a.sin(), a.cos(), 0.0],
        [0.0, 0.0, 1.0],
    ];
    let rx = [
        [1.0, 0.0, 0.0],
        [0.0, b.cos(), -b.sin()],
        [0.0, b.sin(), b.cos()],
    ];
    std::array::from_fn(|i| std::array::from_fn(|j| (0..3).map(|k| rz[i][k] * rx[k][j]).sum()))
}

fn place(p: [f64; 3]) -> [f64; 3] {
    let m = frame();
    std::array::from_fn(|i| CENTRE[i] + R * (0..3).map(|k| m[i][k] * p[k]).sum::<f64>())
}

fn sphere(weight_scale: f64) -> NurbsSurface<f64, 3> {
    let h = 0.5f64.sqrt();
    let cu = [
        (1., 0., 1.),
        (1., 1., h),
        (0., 1., 1.),
        (-1., 1., h),
        (-1., 0., 1.),
        (-1., -1., h),
        (0., -1., 1.),
        (1., -1., h),
        (1., 0., 1.),
    ];
    let cv = [
        (0., -1., 1.),
        (1., -1., h),
        (1., 0., 1.),
        (1., 1., h),
        (0., 1., 1.),
    ];
    let (mut pts, mut w) = (Vec::new(), Vec::new());
    for (x, y, wu) in cu {
        for (rho, z, wv) in cv {
            pts.push(place([x * rho, y * rho, z]));
            w.push(wu * wv * weight_scale);
        }
    }
    let ku = vec![0., 0., 0., 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1., 1., 1.];
    let kv = vec![0., 0., 0., 0.5, 0.5, 1., 1., 1.];
    NurbsSurface::new(ku, 2, kv, 2, 9, 5, pts, w).unwrap()
}

/// Angle of the NURBS quarter arc at its local parameter `s` (closed form, see the doc).
fn quarter_angle(s: f64) -> f64 {
    let r2 = 2f64.sqrt();
    let (a, b) = ((1.0 - s) * (1.0 - s), s * s);
    let m = r2 * s * (1.0 - s);
    (m + b).atan2(a + m)
}

/// The sphere's point at `(u, v)`, from angles (independent of the library's evaluator).
fn true_point(u: f64, v: f64) -> [f64; 3] {
    let qu = (4.0 * u).floor().clamp(0.0, 3.0);
    let theta = qu * std::f64::consts::FRAC_PI_2 + quarter_angle(4.0 * u - qu);
    let qv = (2.0 * v).floor().clamp(0.0, 1.0);
    let phi = -std::f64::consts::FRAC_PI_2
        + qv * std::f64::consts::FRAC_PI_2
        + quarter_angle(2.0 * v - qv);
    place([theta.cos() * phi.cos(), theta.sin() * phi.cos(), phi.sin()])
}

fn cubic(points: Vec<[f64; 2]>) -> NurbsCurve<f64, 2> {
    let n = points.len();
    let mut knots = vec![0.0; 4];
    for i in 1..n - 3 {
        knots.push(i as f64 / (n - 3) as f64);
    }
    knots.extend([1.0; 4]);
    NurbsCurve::new(knots, 3, points, vec![1.0; n]).unwrap()
}

/// Runs the checks of the module doc; returns (bound, measured Hausdorff).
fn check(s: &NurbsSurface<f64, 3>, d: &NurbsCurve<f64, 2>, eps: f64) -> (f64, f64) {
    check_with(
        s,
        d,
        Params {
            eps_d: eps,
            ..Params::default()
        },
    )
}

fn check_with(s: &NurbsSurface<f64, 3>, d: &NurbsCurve<f64, 2>, params: Params) -> (f64, f64) {
    let eps = params.eps_d;
    let r: CurveOnSurface = approximate(s, d, &params).unwrap();
    eprintln!("{} segments in {:.1} ms", r.num_segments, r.elapsed_ms);
    let c = &r.certificate;
    assert!(
        c.hausdorff_bound <= eps,
        "bound {} > eps {eps}",
        c.hausdorff_bound
    );
    assert!(
        c.control_point_rounding < 1e-12,
        "rounding {}",
        c.control_point_rounding
    );
    let curves: Vec<(Vec<[f64; 3]>, Vec<f64>)> = r
        .segments
        .iter()
        .map(|g| {
            (
                g.control_points.clone(),
                g.weights.clone().expect("rational output"),
            )
        })
        .collect();
    for (_, w) in &curves {
        assert!(w.iter().all(|w| *w > 0.0), "weights {w:?}");
    }
    // On the sphere: |C(t) − centre| = R up to the stated rounding.
    for (p, w) in &curves {
        for i in 0..=40 {
            let x = segment_point(p, Some(w), i as f64 / 40.0);
            let off = (dist(&x, &CENTRE) - R).abs();
            assert!(
                off <= c.control_point_rounding + 1e-13,
                "off the sphere by {off:e}"
            );
        }
    }
    // Hausdorff, both ways, by projection.
    let img = |t: f64| {
        let uv = d.eval(&t);
        true_point(uv[0], uv[1])
    };
    let (t0, t1) = d.hom.domain();
    let mut measured = 0.0f64;
    // Every point of a segment is within its control polygon's length `L` of its first
    // control point, so segments with `|x − P_0| − L` above the distance to some first
    // control point cannot hold the nearest point.
    let reach: Vec<f64> = curves
        .iter()
        .map(|(p, _)| p.windows(2).map(|w| dist(&w[0], &w[1])).sum())
        .collect();
    for i in 0..=600 {
        let x = img(t0 + (t1 - t0) * i as f64 / 600.0);
        let to_first: Vec<f64> = curves.iter().map(|(p, _)| dist(&p[0], &x)).collect();
        let upper = to_first.iter().copied().fold(f64::INFINITY, f64::min);
        let near = curves
            .iter()
            .enumerate()
            .filter(|(k, _)| to_first[*k] - reach[*k] <= upper)
            .map(|(_, (p, w))| project(&|t| segment_point(p, Some(w), t), &x, 0.0, 1.0, 8))
            .fold(f64::INFINITY, f64::min);
        measured = measured.max(near);
    }
    for (p, w) in &curves {
        for i in 0..=8 {
            let x = segment_point(p, Some(w), i as f64 / 8.0);
            measured = measured.max(project(&img, &x, t0, t1, 400));
        }
    }
    // The printed curves are within `control_point_rounding` of the certified ones (rational
    // output: that is the curve distance), and the measurement itself runs in f64 on
    // coordinates of size ~5 (a few ulps; a domain curve that is its own chord has a bound of
    // 0 and measures ~2e-15).
    assert!(
        measured <= c.hausdorff_bound + c.control_point_rounding + 1e-14,
        "measured {measured:e} > bound {:e}",
        c.hausdorff_bound
    );
    (c.hausdorff_bound, measured)
}

#[test]
fn sphere_curves_certified_against_closed_forms() {
    let s = sphere(1.0);
    // A wave across three quadrants in u, climbing to within 0.03 of the pole in v.
    let wave = cubic(vec![
        [0.05, 0.2],
        [0.2, 0.6],
        [0.35, 0.3],
        [0.5, 0.8],
        [0.65, 0.97],
        [0.8, 0.5],
    ]);
    let (b, m) = check(&s, &wave, 1e-4);
    eprintln!("wave: bound {b:.3e}, measured {m:.3e}");
    // Along the seam u = 0 and back into the domain.
    let seam = cubic(vec![[0.0, 0.1], [0.0, 0.4], [0.1, 0.6], [0.0, 0.9]]);
    let (b, m) = check(&s, &seam, 1e-5);
    eprintln!("seam: bound {b:.3e}, measured {m:.3e}");
}

#[test]
fn scaled_weights_certify_the_same_surface() {
    let curve = cubic(vec![[0.1, 0.3], [0.4, 0.45], [0.6, 0.2], [0.9, 0.6]]);
    let (b1, m1) = check(&sphere(1.0), &curve, 1e-4);
    let (b2, m2) = check(&sphere(1e6), &curve, 1e-4);
    eprintln!("weights x1: {b1:.3e} / {m1:.3e}; x1e6: {b2:.3e} / {m2:.3e}");
    assert!(
        (m1 - m2).abs() <= 1e-9,
        "same surface, same curve: {m1:e} vs {m2:e}"
    );
}

/// The exact arithmetic (Rational throughout, the reference) certifies rational surfaces
/// too, under the same closed-form checks.
#[test]
fn exact_arithmetic_on_the_sphere() {
    let curve = cubic(vec![[0.1, 0.3], [0.2, 0.45], [0.3, 0.2], [0.4, 0.6]]);
    let params = Params {
        eps_d: 1e-2,
        arithmetic: Arithmetic::Exact,
        ..Params::default()
    };
    let (b, m) = check_with(&sphere(1.0), &curve, params);
    eprintln!("exact: bound {b:.3e}, measured {m:.3e}");
}

/// Step 3 for rational patches: on every Bézier cell of the sphere, the proven Lipschitz
/// bounds (eq. 12 of `Q` and `W` combined, and the local bound on sub-rectangles) are at least
/// the difference quotients `|S(x) − S(y)| / |x − y|` measured with the closed-form points.
#[test]
fn rational_lipschitz_bounds_hold_against_closed_form_quotients() {
    use vericad::curve_on_surface::float::cells::FCells;
    let s = sphere(1.0);
    let h = &s.hom;
    let net: Vec<[f64; 3]> = h.net.iter().map(|x| x.wp).collect();
    let w: Vec<f64> = h.net.iter().map(|x| x.w).collect();
    let bs = vericad::spline::BSplineSurface {
        ku: h.ku.clone(),
        kv: h.kv.clone(),
        net,
    };
    let cells = FCells::rational(&bs, &w);
    let mut rng = 0x2545_f491_4f6c_dd1du64;
    let mut next = || {
        rng ^= rng << 13;
        rng ^= rng >> 7;
        rng ^= rng << 17;
        (rng >> 11) as f64 / (1u64 << 53) as f64
    };
    let (mut worst_ratio, mut checked) = (0.0f64, 0);
    for (i, u) in cells.u_breaks.windows(2).enumerate() {
        for (j, v) in cells.v_breaks.windows(2).enumerate() {
            let c = cells.get(i * (cells.v_breaks.len() - 1) + j).unwrap();
            for sub in 0..4 {
                // The whole cell, then sub-rectangles of a quarter, a tenth, a hundredth.
                let frac = [1.0, 0.25, 0.1, 0.01][sub];
                let (a, b) = (
                    u[0] + (u[1] - u[0]) * (1.0 - frac) * next(),
                    v[0] + (v[1] - v[0]) * (1.0 - frac) * next(),
                );
                let r = [a, a + (u[1] - u[0]) * frac, b, b + (v[1] - v[0]) * frac];
                let k = cells.lipschitz_on(r, true).unwrap();
                assert!(k <= c.eq12 * (1.0 + 1e-12));
                for _ in 0..200 {
                    let x = [r[0] + (r[1] - r[0]) * next(), r[2] + (r[3] - r[2]) * next()];
                    let y = [r[0] + (r[1] - r[0]) * next(), r[2] + (r[3] - r[2]) * next()];
                    let d = ((x[0] - y[0]).powi(2) + (x[1] - y[1]).powi(2)).sqrt();
                    if d < 1e-9 {
                        continue;
                    }
                    let q = dist(&true_point(x[0], x[1]), &true_point(y[0], y[1])) / d;
                    assert!(q <= k, "quotient {q} above the bound {k} on {r:?}");
                    worst_ratio = worst_ratio.max(q / k);
                    checked += 1;
                }
            }
        }
    }
    eprintln!("{checked} quotients, largest quotient / bound {worst_ratio:.3}");
    assert!(
        worst_ratio > 0.2,
        "the bounds are not absurdly loose: {worst_ratio}"
    );
}

/// The B-spline form (segments joined, weights rescaled at the joints) is the same curve:
/// on the sphere within the stated rounding at every segment, evaluated piece by piece here.
#[test]
fn bspline_form_keeps_the_rational_curve() {
    let curve = cubic(vec![[0.05, 0.2], [0.3, 0.7], [0.6, 0.4], [0.9, 0.85]]);
    let r = approximate(
        &sphere(1.0),
        &curve,
        &Params {
            eps_d: 1e-4,
            ..Params::default()
        },
    )
    .unwrap();
    let b = &r.bspline;
    let w = b.weights.as_ref().expect("rational");
    let p = b.degree;
    assert_eq!(b.control_points.len(), r.num_segments * p + 1);
    for k in 0..r.num_segments {
        let cps = &b.control_points[k * p..=k * p + p];
        let ws = &w[k * p..=k * p + p];
        for i in 0..=10 {
            let x = segment_point(cps, Some(ws), i as f64 / 10.0);
            let y = r.segments[k].eval(i as f64 / 10.0);
            assert!(dist(&x, &y) <= 1e-12, "segment {k}: {x:?} vs {y:?}");
            let off = (dist(&x, &CENTRE) - R).abs();
            assert!(
                off <= r.certificate.control_point_rounding + 1e-13,
                "{off:e}"
            );
        }
    }
}

/// The f64 split decides, without the exact rerun, domain curves that the enclosures alone
/// leave undecided: one along the knot line `u = 0.25` (every control point on it), one
/// ending exactly on the knot line `v = 0.5` with its other control points on one side, and
/// one along the domain's border (the seam `u = 0`). Each is certified under the closed-form
/// checks of [`check_with`], in f64, and so is the exact arithmetic's result (the reference).
#[test]
fn split_shortcuts_decide_without_the_exact_rerun() {
    let s = sphere(1.0);
    let cases = [
        (
            "along u = 0.25",
            cubic(vec![[0.25, 0.1], [0.25, 0.3], [0.25, 0.35], [0.25, 0.45]]),
        ),
        (
            "ending on v = 0.5",
            cubic(vec![[0.3, 0.2], [0.35, 0.3], [0.4, 0.45], [0.45, 0.5]]),
        ),
        (
            "along the seam u = 0",
            cubic(vec![[0.0, 0.6], [0.0, 0.7], [0.0, 0.8], [0.0, 0.9]]),
        ),
    ];
    for (name, d) in cases {
        let f64_params = Params {
            eps_d: 1e-3,
            ..Params::default()
        };
        let r = approximate(&s, &d, &f64_params).unwrap();
        assert!(
            r.certificate.arithmetic.starts_with("f64"),
            "{name}: {}",
            r.certificate.arithmetic
        );
        check_with(&s, &d, f64_params);
        // The exact arithmetic (the reference) certifies it under the same checks.
        let (b, m) = check_with(
            &s,
            &d,
            Params {
                arithmetic: Arithmetic::Exact,
                ..f64_params
            },
        );
        eprintln!(
            "{name}: f64 {} segments; exact bound {b:.2e}, measured {m:.2e}",
            r.num_segments
        );
    }
}
