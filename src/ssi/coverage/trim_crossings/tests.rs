use super::*;
use crate::geom::{Hom, lift_point};
use crate::scalar::{Rational, lift};
use crate::spline::NurbsSurface;
use std::rc::Rc;

type Q = Rational;

fn contains(i: &Interval, x: &Q) -> bool {
    lift::<Q>(i.lo) <= *x && *x <= lift::<Q>(i.hi)
}

/// A rational bicubic × biquadratic surface on two knot spans each way, with knots that are
/// not dyadic (so the pieces' places are enclosed, not exact) and uneven weights.
fn surface() -> NurbsSurface<f64, 3> {
    let (nu, nv) = (5, 4);
    let mut pts = Vec::new();
    let mut w = Vec::new();
    for i in 0..nu {
        for j in 0..nv {
            let (x, y) = (i as f64 * 0.7, j as f64 * 1.3);
            pts.push([x, y, (x * 1.7 + y * 0.9).sin() + 0.1 * (i * j) as f64]);
            w.push(1.0 + 0.37 * ((i + 2 * j) % 3) as f64);
        }
    }
    let ku = vec![0.1, 0.1, 0.1, 0.1, 0.43, 0.9, 0.9, 0.9, 0.9];
    let kv = vec![-1.0, -1.0, -1.0, 0.3, 1.7, 1.7, 1.7];
    NurbsSurface::new(ku, 3, kv, 2, nu, nv, pts, w).unwrap()
}

/// The exact point of the surface at the exact parameters `(u, v)`.
fn exact_point(s: &NurbsSurface<f64, 3>, u: &Q, v: &Q) -> [Q; 3] {
    let e = s.hom.map(
        |k| lift::<Q>(*k),
        |h| Hom {
            wp: lift_point(&h.wp),
            w: lift(h.w),
        },
    );
    let h = e.eval(u, v);
    std::array::from_fn(|k| h.wp[k].clone() / h.w.clone())
}

/// Every point the exact surface takes on an edge's part in a piece lies in the convex hull
/// of the image's enclosed control points — checked on their box, at 33 exact points of the
/// edge (rationals, not rounded) inside the piece's exact box, for the root pieces and for
/// pieces two and five halvings down, against edges crossing them in several directions.
#[test]
fn the_image_holds_the_exact_surface_along_the_edge() {
    let s = surface();
    let kept = std::cell::Cell::new(0);
    let mut cells: Vec<Rc<Cell>> = crate::ssi::coverage::roots(&s);
    let mut deep = cells.clone();
    for _ in 0..5 {
        deep = deep.iter().flat_map(|c| c.kids(&kept).to_vec()).collect();
        cells.extend(deep.iter().take(6).cloned());
    }
    // The last two shifted: the edge's exact points minus the shift are on the piece.
    let edges = [
        ([0.05, -1.2], [0.95, 1.8], [0.0, 0.0]),
        ([0.9, -1.0], [0.1, 1.7], [0.0, 0.0]),
        ([0.2, 0.25], [0.8, 0.35], [0.0, 0.0]),
        ([0.44 + 0.7, -0.9], [0.44 + 0.7, 1.6], [0.7, 0.0]),
        ([0.3001, 0.3 - 0.3], [0.31, 0.31 - 0.3], [0.0, -0.3]),
    ];
    let mut checked = 0;
    for c in &cells {
        // The exact box of the piece: its span and dyadic part.
        let ex = |k: usize, f: f64| -> Q {
            let (k0, k1) = (lift::<Q>(c.span[2 * k]), lift::<Q>(c.span[2 * k + 1]));
            k0.clone() + (k1 - k0) * lift::<Q>(f)
        };
        let (eu0, eu1) = (ex(0, c.frac[0]), ex(0, c.frac[1]));
        let (ev0, ev1) = (ex(1, c.frac[2]), ex(1, c.frac[3]));
        for e in &edges {
            let img = edge_image(c, e);
            let pts = img.as_ref().and_then(|i| i.cartesian());
            for k in 0..=32 {
                let t = lift::<Q>(k as f64) / lift::<Q>(32.0);
                let p: [Q; 2] = std::array::from_fn(|d| {
                    lift::<Q>(e.0[d]) + t.clone() * (lift::<Q>(e.1[d]) - lift::<Q>(e.0[d]))
                        - lift::<Q>(e.2[d])
                });
                let inside = eu0 <= p[0] && p[0] <= eu1 && ev0 <= p[1] && p[1] <= ev1;
                if !inside {
                    continue;
                }
                let pts = pts
                    .as_ref()
                    .unwrap_or_else(|| panic!("no image of {e:?} on {:?}", c.uv));
                let x = exact_point(&s, &p[0], &p[1]);
                for d in 0..3 {
                    let lo = pts.iter().map(|q| q[d].lo).fold(f64::INFINITY, f64::min);
                    let hi = pts
                        .iter()
                        .map(|q| q[d].hi)
                        .fold(f64::NEG_INFINITY, f64::max);
                    assert!(
                        contains(&Interval::new(lo, hi), &x[d]),
                        "{e:?} at t = {k}/32 on {:?}",
                        c.uv
                    );
                }
                checked += 1;
            }
        }
    }
    assert!(checked > 150, "{checked} points checked");
}

/// The interval composition encloses the exact one ([`crate::spline::compose::compose_line`]
/// in rationals) on a rational patch and a segment given by exact ends.
#[test]
fn interval_composition_encloses_the_exact_composition() {
    use crate::spline::bezier_surface::BezierSurface;
    use crate::spline::compose::compose_line as exact_line;
    let (p, q) = (3, 2);
    let mut net = Vec::new();
    let mut ipatch = IPatch {
        p,
        q,
        x: Vec::new(),
        w: Vec::new(),
    };
    for i in 0..=p {
        for j in 0..=q {
            let w = 0.5 + 0.25 * ((i * 3 + j) % 4) as f64;
            let x = [
                i as f64 * 0.3 - j as f64,
                (i * j) as f64 * 0.1,
                0.7 * j as f64 + 0.01,
            ];
            net.push(Hom {
                wp: x.map(|c| lift::<Q>(c) * lift::<Q>(w)),
                w: lift::<Q>(w),
            });
            // The homogeneous point enclosed outward.
            ipatch.x.push(std::array::from_fn(|c| {
                Interval::point(x[c]) * Interval::point(w)
            }));
            ipatch.w.push(Interval::point(w));
        }
    }
    let s = BezierSurface::new(p, q, net).unwrap();
    let (a, b) = ([0.125, 0.9375], [1.0625, -0.0625]);
    let exact = exact_line(&s, &a.map(lift::<Q>), &b.map(lift::<Q>));
    let got = compose_line(&ipatch, a.map(Interval::point), b.map(Interval::point));
    assert_eq!(got.x.len(), p + q + 1);
    for (k, h) in exact.control.iter().enumerate() {
        for c in 0..3 {
            assert!(contains(&got.x[k][c], &h.wp[c]), "control point {k}");
            assert!(got.x[k][c].hi - got.x[k][c].lo < 1e-13);
        }
        assert!(contains(&got.w[k], &h.w), "weight {k}");
    }
}

/// A segment that misses a piece has no image; one along its border has one.
#[test]
fn segments_missing_the_piece_have_no_image() {
    let s = surface();
    let root = &crate::ssi::coverage::roots(&s)[0];
    let [u0, u1, v0, v1] = root.uv;
    assert!(edge_image(root, &([u1 + 0.1, v0], [u1 + 0.2, v1], [0.0; 2])).is_none());
    assert!(edge_image(root, &([u0, v0], [u0, v1], [0.0; 2])).is_some());
    assert!(
        edge_image(
            root,
            &([u0 - 1.0, v0 - 1.0], [u0 - 0.5, v1 + 1.0], [0.0; 2])
        )
        .is_none()
    );
}
