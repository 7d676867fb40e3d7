//! Knot vectors with an outer knot beyond a domain end of multiplicity p (as periodic
//! surfaces are written by some systems: `(-1, 0, 0, 0, 1, …, 8, 8, 8, 9)`), and closed
//! curves restarted at another point (`NurbsCurve::joined`), checked against a
//! Cox–de Boor evaluation written here from the definition.

use vericad::spline::NurbsCurve;

/// `N_{i,p}(t)` by the recurrence (0/0 = 0), right-continuous, the last span closed.
fn basis(k: &[f64], i: usize, p: usize, t: f64) -> f64 {
    if p == 0 {
        let last = k.iter().rposition(|x| *x < k[k.len() - 1]).unwrap_or(0);
        return if (k[i] <= t && t < k[i + 1]) || (i == last && t == k[i + 1]) {
            1.0
        } else {
            0.0
        };
    }
    let mut s = 0.0;
    if k[i + p] > k[i] {
        s += (t - k[i]) / (k[i + p] - k[i]) * basis(k, i, p - 1, t);
    }
    if k[i + p + 1] > k[i + 1] {
        s += (k[i + p + 1] - t) / (k[i + p + 1] - k[i + 1]) * basis(k, i + 1, p - 1, t);
    }
    s
}

fn reference(k: &[f64], p: usize, pts: &[[f64; 2]], t: f64) -> [f64; 2] {
    let mut out = [0.0; 2];
    for (i, q) in pts.iter().enumerate() {
        let b = basis(k, i, p, t);
        out[0] += b * q[0];
        out[1] += b * q[1];
    }
    out
}

#[test]
fn an_outer_knot_beyond_a_end_of_multiplicity_p_changes_nothing_on_the_domain() {
    let k = vec![-1.0, 0.0, 0.0, 0.0, 1.0, 2.5, 3.0, 3.0, 3.0, 4.0];
    let pts = [
        [0.0, 0.0],
        [1.0, 2.0],
        [2.0, -1.0],
        [3.0, 3.0],
        [4.0, 0.5],
        [5.0, 1.0],
    ];
    let c = NurbsCurve::new(k.clone(), 3, pts.to_vec(), vec![1.0; 6]).unwrap();
    assert_eq!(c.hom.domain(), (0.0, 3.0));
    // Stored clamped: the outer knots are the domain ends.
    assert_eq!(c.hom.knots.knots()[0], 0.0);
    assert_eq!(*c.hom.knots.knots().last().unwrap(), 3.0);
    for i in 0..=60 {
        let t = 3.0 * i as f64 / 60.0;
        let (a, b) = (c.eval(&t), reference(&k, 3, &pts, t));
        assert!(
            (a[0] - b[0]).abs() < 1e-12 && (a[1] - b[1]).abs() < 1e-12,
            "t = {t}: {a:?} vs {b:?}"
        );
    }
    // The ends interpolate the end control points (as for a clamped vector).
    assert_eq!(c.eval(&0.0), pts[0]);
    assert!(vericad::geom::dist(&c.eval(&3.0), &pts[5]) < 1e-15);
}

#[test]
fn a_closed_curve_restarted_at_another_point_is_the_same_circle() {
    let f = vericad::spline::construct::Frame::WORLD;
    let circle = vericad::spline::construct::arc(&f, 2.0, 0.0, std::f64::consts::TAU).unwrap();
    let (d0, d1) = circle.hom.domain();
    let cut = d0 + 0.37 * (d1 - d0);
    let head = NurbsCurve {
        hom: circle.hom.sub_curve(&cut, &d1).unwrap(),
    };
    let tail = NurbsCurve {
        hom: circle.hom.sub_curve(&d0, &cut).unwrap(),
    };
    let c = head.joined(&tail).unwrap();
    let (e0, e1) = c.hom.domain();
    assert!(vericad::geom::dist(&c.eval(&e0), &circle.eval(&cut)) < 1e-14);
    assert!(vericad::geom::dist(&c.eval(&e1), &circle.eval(&cut)) < 1e-14);
    for i in 0..=200 {
        let t = e0 + (e1 - e0) * i as f64 / 200.0;
        let p = c.eval(&t);
        let r = vericad::geom::norm(&p);
        assert!((r - 2.0).abs() < 1e-14, "t = {t}: radius {r}");
    }
    // Degrees must agree.
    let line = NurbsCurve::new(
        vec![0.0, 0.0, 1.0, 1.0],
        1,
        vec![[0.0; 3], [1.0; 3]],
        vec![1.0; 2],
    )
    .unwrap();
    assert!(head.joined(&line).is_err());
}
