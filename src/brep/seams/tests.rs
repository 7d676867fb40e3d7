use super::*;
use crate::geom::dist;
use crate::spline::NurbsCurve;
use crate::spline::construct::{Frame, cylinder, extrude, torus};

#[test]
fn the_new_seam_is_in_the_widest_gap_only_when_the_boundary_spans_the_old_one() {
    // Points on both sides close to the seam, a wide gap in the middle.
    let spans = vec![0.001, 0.1, 0.2, 0.8, 0.9, 0.995];
    assert_eq!(new_seam(spans, 0.0, 1.0), Some(0.5));
    // Away from the seam on one side: nothing to move.
    assert_eq!(new_seam(vec![0.1, 0.2, 0.3], 0.0, 1.0), None);
    // Points on the seam itself do not count.
    assert_eq!(new_seam(vec![0.0, 1.0, 0.2, 0.3], 0.0, 1.0), None);
    // Covering everything: no gap of a tenth of the period.
    let all: Vec<f64> = (1..100).map(|k| k as f64 / 100.0).collect();
    assert_eq!(new_seam(all, 0.0, 1.0), None);
}

/// Re-parametrized surfaces are the same surfaces point for point: `S'(t') = S(t')` for
/// `t' ≤ u_max`, `S(t' − period)` beyond (u for a cylinder, v for a torus).
#[test]
fn a_reseamed_surface_is_the_same_surface() {
    let f = Frame {
        o: [0.5, -1.0, 2.0],
        x: [0.0, 1.0, 0.0],
        y: [0.0, 0.0, 1.0],
        z: [1.0, 0.0, 0.0],
    };
    // A closed rational profile whose end weights differ (1 and 2, the same point): its
    // seam rows' weights differ by a common factor.
    let profile = NurbsCurve::new(
        vec![0.0, 0.0, 0.0, 0.3, 0.7, 1.0, 1.0, 1.0],
        2,
        vec![
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [-1.0, 1.0, 0.0],
            [-1.0, -1.0, 0.0],
            [1.0, 0.0, 0.0],
        ],
        vec![1.0, 0.8, 1.5, 0.6, 2.0],
    )
    .unwrap();
    let swept = extrude(&profile, &[0.0, 0.0, 1.0]).unwrap();
    assert!(Closure::of(&swept).seam_u);
    for (s, d) in [
        (cylinder(&f, 2.0, -1.0, 3.0).unwrap(), 0),
        (torus(&f, 3.0, 1.0).unwrap(), 1),
        (swept, 0),
    ] {
        let (u0, u1, v0, v1) = s.hom.domain();
        let (lo, hi) = if d == 0 { (u0, u1) } else { (v0, v1) };
        let t = lo + 0.37 * (hi - lo);
        let r = reseamed(&s, d, t).unwrap();
        let (a0, a1, b0, b1) = r.hom.domain();
        let (nlo, nhi) = if d == 0 { (a0, a1) } else { (b0, b1) };
        assert!((nlo - t).abs() <= 1e-15 && (nhi - (t + hi - lo)).abs() <= 1e-12);
        for i in 0..=20 {
            for j in 0..=20 {
                let (x, y) = (i as f64 / 20.0, j as f64 / 20.0);
                let (u, v) = (a0 + (a1 - a0) * x, b0 + (b1 - b0) * y);
                let back = |w: f64| if w > hi { w - (hi - lo) } else { w };
                let (ou, ov) = if d == 0 { (back(u), v) } else { (u, back(v)) };
                let e = dist(&r.eval(&u, &v), &s.eval(&ou, &ov));
                assert!(e <= 1e-12, "{d}: at ({u}, {v}) {e:e}");
            }
        }
    }
}
