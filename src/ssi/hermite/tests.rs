use super::*;
use crate::spline::test_params::rng;

fn p7(x: [f64; 3]) -> P7 {
    [x[0], x[1], x[2], 0.0, 0.0, 0.0, 0.0]
}

/// On a circular arc of angle θ the piece is the classical cubic arc (handle
/// `(4/3) r tan(θ/4)`): its largest radial error is `r · 2.7e-4` for a quarter circle (the
/// known figure for that approximation) and falls with `θ⁶`.
#[test]
fn circular_arcs_have_the_sixth_order_error() {
    let r = 2.0;
    let arc = |theta: f64| {
        let at = |a: f64| p7([r * a.cos(), r * a.sin(), 0.0]);
        let tan = |a: f64| p7([-a.sin(), a.cos(), 0.0]);
        let h = Piece::cubic(&at(0.0), &tan(0.0), &at(theta), &tan(theta)).unwrap();
        (0..=1000)
            .map(|i| {
                let x = h.eval(i as f64 / 1000.0);
                ((x[0] * x[0] + x[1] * x[1]).sqrt() - r).abs()
            })
            .fold(0.0f64, f64::max)
    };
    let quarter = arc(std::f64::consts::FRAC_PI_2);
    assert!(
        (quarter / r - 2.7245e-4).abs() < 1e-7,
        "quarter circle error {}",
        quarter / r
    );
    for theta in [0.4, 0.2, 0.1] {
        let ratio = arc(theta) / arc(theta / 2.0);
        assert!((ratio - 64.0).abs() < 2.0, "θ {theta}: ratio {ratio}");
    }
}

/// Without both jets, or with a tangent far from the chord, the piece is the chord: linear in
/// every packed coordinate.
#[test]
fn missing_jets_give_the_chord() {
    let (p, q) = (
        [0.0, 0.0, 0.0, 0.1, 0.2, 0.3, 0.4],
        [1.0, 2.0, 0.0, 0.5, 0.6, 0.7, 0.8],
    );
    let j = [0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0];
    for h in [
        Piece::new(&p, None, &q, None),
        Piece::new(&p, Some(&j), &q, None),
        Piece::new(&p, Some(&j), &q, Some(&j)),
    ] {
        assert_eq!(h, Piece::chord(&p, &q));
        for t in [0.0, 0.25, 0.5, 0.9, 1.0] {
            let x = h.eval(t);
            for k in 0..7 {
                assert!((x[k] - (p[k] + t * (q[k] - p[k]))).abs() < 1e-15);
            }
        }
    }
    assert!(Piece::cubic(&p, &j, &q, &j).is_none());
}

/// The polyline of [`densify`] lies within its proven distance of the piece and the piece
/// within it of the polyline, checked by projecting dense samples both ways (Newton on the
/// piece; closed form on the chords), on random pieces with random jets.
#[test]
fn densified_polylines_are_within_their_bound() {
    let mut r = rng(11);
    for _ in 0..200 {
        let p: P7 = std::array::from_fn(|_| r() * 4.0 - 2.0);
        let q: P7 = std::array::from_fn(|k| p[k] + r() * 2.0 - 1.0);
        let dir = |r: &mut dyn FnMut() -> f64| -> P7 {
            std::array::from_fn(|k| q[k] - p[k] + 0.6 * (r() - 0.5) * if k < 3 { 1.0 } else { 0.0 })
        };
        let (a, b) = (dir(&mut r), dir(&mut r));
        let n = |v: &P7| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        let (a, b) = (a.map(|x| x / n(&a)), b.map(|x| x / n(&b)));
        let Some(h) = Piece::cubic(&p, &a, &q, &b) else {
            continue;
        };
        let delta = 10f64.powf(-2.0 - 5.0 * r());
        let (pts, proven) = densify(&h, delta, 1 << 20);
        assert!(proven <= delta * (1.0 + 1e-9), "{proven} > {delta}");
        let to_poly = |x: &[f64; 3]| {
            pts.windows(2)
                .map(|w| crate::geom::dist_to_segment(x, &w[0], &w[1]))
                .fold(f64::INFINITY, f64::min)
        };
        for i in 0..=400 {
            let x = h.eval(i as f64 / 400.0);
            let d = to_poly(&[x[0], x[1], x[2]]);
            assert!(d <= proven, "piece to polyline {d} > {proven}");
        }
        for w in pts.windows(2).step_by(pts.len() / 50 + 1) {
            let m: [f64; 3] = std::array::from_fn(|k| 0.5 * (w[0][k] + w[1][k]));
            let d = h.dist(&m);
            assert!(d <= proven, "chord midpoint to piece {d} > {proven}");
        }
    }
}

/// The jet of the plane `z = 0` (bilinear over `[-3, 3]²`) against the cylinder
/// `x² + y² = 1`, `z ∈ [-1, 1]`, on their common unit circle: the unit tangent is horizontal
/// and perpendicular to the radius; the plane's rates are `(t_x, t_y) / 6` (its
/// parametrization is affine); the cylinder's height rate is 0 and its rates map onto `t`.
/// Where the plane `x = 1` touches the cylinder along a line, there is no jet.
#[test]
fn the_jet_of_a_plane_and_a_cylinder_is_the_circles_tangent() {
    use crate::spline::construct::{Frame, bilinear, cylinder};
    let plane = bilinear(
        [-3.0, -3.0, 0.0],
        [3.0, -3.0, 0.0],
        [-3.0, 3.0, 0.0],
        [3.0, 3.0, 0.0],
    )
    .unwrap();
    let cyl = cylinder(&Frame::WORLD, 1.0, -1.0, 1.0).unwrap();
    let d = crate::ssi::refine::domain(&cyl);
    let vm = 0.5 * (d[2] + d[3]);
    for i in 0..24 {
        let u = d[0] + (d[1] - d[0]) * (i as f64 + 0.3) / 24.0;
        let x = cyl.eval(&u, &vm);
        assert!(
            x[2].abs() < 1e-14,
            "the cylinder's middle is not at z = 0: {x:?}"
        );
        let uv_p = [(x[0] + 3.0) / 6.0, (x[1] + 3.0) / 6.0];
        let j = tangent_jet(&plane, &cyl, &uv_p, &[u, vm]).expect("a transversal crossing");
        let t = [j[0], j[1], j[2]];
        assert!(
            (norm(&t) - 1.0).abs() < 1e-14 && t[2].abs() < 1e-14,
            "{t:?}"
        );
        assert!(
            (t[0] * x[0] + t[1] * x[1]).abs() < 1e-13,
            "not tangent: {t:?} at {x:?}"
        );
        assert!((j[3] - t[0] / 6.0).abs() < 1e-14 && (j[4] - t[1] / 6.0).abs() < 1e-14);
        assert!(j[6].abs() < 1e-13, "height rate {}", j[6]);
        let (_, su, sv) = point_d1(&cyl, u, vm);
        for k in 0..3 {
            assert!((su[k] * j[5] + sv[k] * j[6] - t[k]).abs() < 1e-13);
        }
    }
    let touching = bilinear(
        [1.0, -3.0, -3.0],
        [1.0, 3.0, -3.0],
        [1.0, -3.0, 3.0],
        [1.0, 3.0, 3.0],
    )
    .unwrap();
    let u = (0..2000)
        .map(|i| d[0] + (d[1] - d[0]) * i as f64 / 2000.0)
        .min_by(|a, b| {
            let (pa, pb) = (cyl.eval(a, &vm), cyl.eval(b, &vm));
            (pb[0]).total_cmp(&pa[0])
        })
        .unwrap();
    let x = cyl.eval(&u, &vm);
    assert!(x[0] > 0.99999, "{x:?}");
    let uv = [(x[1] + 3.0) / 6.0, (x[2] + 3.0) / 6.0];
    assert!(tangent_jet(&touching, &cyl, &uv, &[u, vm]).is_none());
}
