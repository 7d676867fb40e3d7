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

/// A frame with a random origin and random orthonormal axes.
fn random_frame(r: &mut impl FnMut() -> f64) -> Frame {
    let mut v = || [2.0 * r() - 1.0, 2.0 * r() - 1.0, 2.0 * r() - 1.0];
    let unit = |a: [f64; 3]| {
        let n = crate::geom::norm(&a);
        a.map(|c| c / n)
    };
    let o = v();
    let z = unit(v());
    let w = v();
    let x = unit(w.sub(&z.scale(&dot(&w, &z))));
    let y = crate::geom::cross(&z, &x);
    Frame { o, x, y, z }
}

/// The warm-started feet ([`feet_of`]) give the boundary parameters that the grid search
/// ([`SurfaceFoot::closest`]) gives for every sample — along seams, across them, up to poles,
/// and for samples a little off the surface — and so the same new seam. Cylinders, cones,
/// spheres and tori in random frames; paths drawn in the parameter domain, so the true
/// parameters are known and the grid search's are checked against them too.
#[test]
fn warm_started_feet_give_the_grid_searchs_parameters() {
    use crate::spline::construct::{cone, sphere};
    let mut r = crate::spline::test_params::rng(0x5ea_5eed);
    let (mut checked, mut moved) = (0, 0);
    for case in 0..40 {
        let f = random_frame(&mut r);
        let s = match case % 4 {
            0 => cylinder(&f, 0.5 + r(), -1.0, 2.0).unwrap(),
            1 => cone(&f, 1.0 + r(), 0.2 + 0.5 * r(), -0.5, 1.0).unwrap(),
            2 => sphere(&f, 0.5 + 2.0 * r()).unwrap(),
            _ => torus(&f, 3.0 + r(), 0.5 + r()).unwrap(),
        };
        let closure = Closure::of(&s);
        let (u0, u1, v0, v1) = s.hom.domain();
        let at = |a: f64, b: f64| [u0 + (u1 - u0) * a, v0 + (v1 - v0) * b];
        // Paths in the unit square: along the seam, up to it from both sides, across the
        // middle, to a border row (a sphere's pole), and a closed loop's pieces around it.
        let (a, b) = (0.1 + 0.3 * r(), 0.2 + 0.6 * r());
        let paths: [([f64; 2], [f64; 2]); 7] = [
            ([0.0, 0.1], [0.0, 0.9]),
            ([1.0 - a, b], [1.0, b]),
            ([0.0, b], [a, 0.5 * b]),
            ([a, 0.1], [1.0 - a, 0.9]),
            ([0.5, b], [0.5, 1.0]),
            ([0.7, 0.9 * b], [1.0, 0.0]),
            ([0.0, 1.0], [0.3, 0.05]),
        ];
        // Every other frame a face that spans the seam: its boundary near it on both sides,
        // a wide gap in the middle (the seam is to be moved there).
        let paths: Vec<_> = if (case / 4) % 2 == 0 {
            paths.to_vec()
        } else {
            [1, 2, 0, 6].map(|i| paths[i]).to_vec()
        };
        let size = 10.0;
        let near = 1e-9 * size;
        let mut pts = Vec::new();
        let mut truth = Vec::new();
        for (p, q) in paths {
            for k in 0..EDGE_SAMPLES {
                let t = k as f64 / (EDGE_SAMPLES - 1) as f64;
                let uv = at(p[0] + (q[0] - p[0]) * t, p[1] + (q[1] - p[1]) * t);
                let x = s.eval(&uv[0], &uv[1]);
                truth.push(uv);
                // Every third sample a little off the surface (within the tolerance).
                let off = if k % 3 == 0 { 0.3 * near } else { 0.0 };
                pts.push(x.map(|c| c + off));
            }
        }
        let warm = feet_of(&s, &pts, near, &closure);
        let mut grid = SurfaceFoot::new(&s);
        let dom = [u0, u1, v0, v1];
        for d in 0..2 {
            if !(if d == 0 {
                closure.seam_u
            } else {
                closure.seam_v
            }) {
                continue;
            }
            let (lo, hi) = (dom[2 * d], dom[2 * d + 1]);
            let on_seam = |t: f64| t - lo <= 1e-9 * (hi - lo) || hi - t <= 1e-9 * (hi - lo);
            let mut pw = Vec::new();
            let mut pg = Vec::new();
            for ((x, q), uv) in pts.iter().zip(&warm).zip(&truth) {
                let g = grid.closest(x);
                let (tw, tg) = (parameter(&s, x, *q, d), parameter(&s, x, g, d));
                // At a pole every parameter gives the point: nothing to compare.
                let pole = (0..4).any(|k| {
                    closure.degenerate[k]
                        && (g[k / 2] - dom[k]).abs() <= 1e-6 * (dom[k | 1] - dom[k & 2])
                });
                if !pole {
                    assert_eq!(on_seam(tw), on_seam(tg), "case {case}, d {d}: {tw} {tg}");
                    if !on_seam(tg) {
                        assert!(
                            (tw - tg).abs() <= 1e-9 * (hi - lo),
                            "case {case}: {tw} {tg}"
                        );
                        // The true parameter, up to the period.
                        let e = (tg - uv[d]).abs();
                        let e = e.min(hi - lo - e);
                        assert!(e <= 1e-6 * (hi - lo), "case {case}: {tg} {} ", uv[d]);
                        checked += 1;
                    }
                }
                pw.push(tw);
                pg.push(tg);
            }
            let (nw, ng) = (new_seam(pw, lo, hi), new_seam(pg, lo, hi));
            assert_eq!(nw.is_some(), ng.is_some(), "case {case}, d {d}");
            if let (Some(a), Some(b)) = (nw, ng) {
                moved += 1;
                assert!((a - b).abs() <= 1e-9 * (hi - lo), "case {case}: {a} {b}");
            }
        }
    }
    assert!(checked > 10_000, "{checked} parameters compared");
    assert!(moved >= 20, "{moved} seams moved");
}
