//! Knot insertion, Bézier extraction and sub-patch extraction leave the shape unchanged:
//! checked exactly in Rational on random splines (property tests).

use proptest::prelude::*;
use vericad::geom::lift_point;
use vericad::scalar::{Rational, lift, ratio};
use vericad::spline::{BSplineCurve, BSplineSurface};

type Q = Rational;

fn knots(p: usize, n: usize, inner: &[u8]) -> Vec<Q> {
    // Interior knots on a 1/16 grid of [0, 1] (repeats allowed up to the validator's limit).
    let mut v: Vec<u8> = inner.iter().map(|x| 1 + x % 15).take(n - p - 1).collect();
    v.sort();
    let mut k = vec![Q::ZERO; p + 1];
    k.extend(v.iter().map(|&x| ratio(x as i64, 16)));
    k.extend(vec![Q::ONE; p + 1]);
    k
}

fn params(m: usize) -> Vec<Q> {
    (0..=m).map(|i| ratio(i as i64, m as i64)).collect()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(60))]

    #[test]
    fn curve_insertion_and_extraction_are_exact(
        p in 1usize..=4, extra in 0usize..5,
        inner in proptest::collection::vec(any::<u8>(), 8),
        pts in proptest::collection::vec(proptest::array::uniform3(-50i32..50), 12),
        ins in proptest::collection::vec((1u8..63, 1usize..4), 1..4),
    ) {
        let n = p + 1 + extra;
        let k = knots(p, n, &inner);
        prop_assume!(vericad::spline::KnotVector::new(k.clone(), p, n).is_ok());
        let ctrl: Vec<[Q; 3]> = pts[..n].iter().map(|c| lift_point(&[c[0] as f64, c[1] as f64, c[2] as f64])).collect();
        let c = BSplineCurve::new(k, p, ctrl).unwrap();
        let mut c2 = c.clone();
        for (t, r) in &ins {
            c2 = c2.insert_knot(&ratio(*t as i64, 64), *r);
        }
        let pieces = c.bezier_pieces();
        for t in params(40) {
            let x = c.eval(&t);
            prop_assert_eq!(&c2.eval(&t), &x);
            let pc = pieces.iter().find(|b| b.t0 <= t && t <= b.t1).unwrap();
            let s = (t.clone() - pc.t0.clone()) / (pc.t1.clone() - pc.t0.clone());
            prop_assert_eq!(&pc.curve.eval(&s), &x);
        }
    }

    #[test]
    fn surface_patches_and_subpatch_are_exact(
        p in 1usize..=3, q in 1usize..=3, eu in 0usize..3, ev in 0usize..3,
        inner in proptest::collection::vec(any::<u8>(), 8),
        z in proptest::collection::vec(-20i32..20, 64),
        (a, b) in (1u8..8, 9u8..16),
    ) {
        let (nu, nv) = (p + 1 + eu, q + 1 + ev);
        let (ku, kv) = (knots(p, nu, &inner), knots(q, nv, &inner[4..]));
        prop_assume!(vericad::spline::KnotVector::new(ku.clone(), p, nu).is_ok());
        prop_assume!(vericad::spline::KnotVector::new(kv.clone(), q, nv).is_ok());
        let net: Vec<[Q; 3]> = (0..nu * nv)
            .map(|k| lift_point(&[(k / nv) as f64, (k % nv) as f64, z[k % 64] as f64]))
            .collect();
        let s = BSplineSurface::new(ku, p, kv, q, nu, nv, net).unwrap();
        let patches = s.bezier_patches();
        let (lo, hi) = (ratio(a as i64, 16), ratio(b as i64, 16));
        let sub = s.sub_patch(&lo, &hi, &lo, &hi).unwrap();
        for u in params(8) {
            for v in params(8) {
                let x = s.eval(&u, &v);
                let bp = patches.iter().find(|b| b.u0 <= u && u <= b.u1 && b.v0 <= v && v <= b.v1).unwrap();
                let lu = (u.clone() - bp.u0.clone()) / (bp.u1.clone() - bp.u0.clone());
                let lv = (v.clone() - bp.v0.clone()) / (bp.v1.clone() - bp.v0.clone());
                prop_assert_eq!(&bp.patch.eval(&lu, &lv), &x);
                if lo <= u && u <= hi && lo <= v && v <= hi {
                    prop_assert_eq!(&sub.eval(&u, &v), &x);
                }
            }
        }
    }
}

/// A NURBS surface split into Bézier patches stays exact too (homogeneous points).
#[test]
fn rational_bezier_extraction_is_exact() {
    use vericad::spline::NurbsSurface;
    let k: Vec<Q> = [0., 0., 0., 0.5, 1., 1., 1.]
        .iter()
        .map(|&x| lift(x))
        .collect();
    let pts: Vec<[Q; 3]> = (0..16)
        .map(|i| lift_point(&[(i / 4) as f64, (i % 4) as f64, ((i * 7) % 5) as f64]))
        .collect();
    let w: Vec<Q> = (0..16).map(|i| lift(1.0 + (i % 3) as f64 * 0.5)).collect();
    let s = NurbsSurface::new(k.clone(), 2, k, 2, 4, 4, pts, w).unwrap();
    let patches = s.hom.bezier_patches();
    assert_eq!(patches.len(), 4);
    for u in params(12) {
        for v in params(12) {
            let x = s.eval(&u, &v);
            let bp = patches
                .iter()
                .find(|b| b.u0 <= u && u <= b.u1 && b.v0 <= v && v <= b.v1)
                .unwrap();
            let lu = (u.clone() - bp.u0.clone()) / (bp.u1.clone() - bp.u0.clone());
            let lv = (v.clone() - bp.v0.clone()) / (bp.v1.clone() - bp.v0.clone());
            assert_eq!(bp.patch.eval(&lu, &lv).project().unwrap(), x);
        }
    }
}
