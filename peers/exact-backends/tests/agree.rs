//! Every backend computes exactly what num-rational computes, and the kernels are right
//! (checked in exact arithmetic against independent routes). No timing here.

use exact_backends::backends::{BigRational, MalachiteRational, RBig, Ratio05, RugRational};
use exact_backends::inputs::{ORIENT_EXACT, ORIENT_NEAR, ORIENT_RANDOM};
use exact_backends::*;

type Q = BigRational;

fn same_as_num_rational<T: Exact>() {
    let reference = Inputs::<Q>::new().results();
    let got = Inputs::<T>::new().results();
    assert_eq!(got.len(), reference.len());
    for ((k, r), (k2, g)) in reference.iter().zip(&got) {
        assert_eq!(k, k2);
        assert_eq!(r.len(), g.len(), "{}: {k}: count", T::NAME);
        for (i, (x, y)) in r.iter().zip(g).enumerate() {
            assert_eq!(x, y, "{}: {k}: value {i}", T::NAME);
        }
    }
    // Signs too (the orient3d kernel proper).
    assert_eq!(
        Inputs::<T>::new().run_orient3d(),
        Inputs::<Q>::new().run_orient3d()
    );
}

#[test]
fn num_rational_on_bigint_05_agrees() {
    same_as_num_rational::<Ratio05>();
}
#[test]
fn rug_agrees() {
    same_as_num_rational::<RugRational>();
}
#[test]
fn dashu_agrees() {
    same_as_num_rational::<RBig>();
}
#[test]
fn malachite_agrees() {
    same_as_num_rational::<MalachiteRational>();
}

/// Every backend's f64 conversion is the exact dyadic value (the same string as
/// num-rational's `from_float`), on awkward values too.
fn conversions<T: Exact>() {
    let xs = [
        0.0,
        -0.0,
        1.0,
        -1.0,
        0.1,
        -0.3,
        1e-300,
        -5e-324,
        f64::MIN_POSITIVE,
        f64::MAX,
        f64::MIN,
        2f64.powi(60),
        123456.789,
        -1.0 / 3.0,
    ];
    for x in xs {
        assert_eq!(
            T::from_f64(x).to_num_den(),
            Q::from_f64(x).to_num_den(),
            "{} {x:e}",
            T::NAME
        );
    }
}

#[test]
fn conversions_are_exact() {
    conversions::<Ratio05>();
    conversions::<RugRational>();
    conversions::<RBig>();
    conversions::<MalachiteRational>();
    assert_eq!(Q::from_f64(0.1).to_num_den().1, (1u64 << 55).to_string());
}

#[test]
fn orient3d_cases_have_the_intended_signs() {
    let s = Inputs::<Q>::new().run_orient3d();
    assert_eq!(s.len(), ORIENT_RANDOM + ORIENT_NEAR + ORIENT_EXACT);
    assert!(s[..ORIENT_RANDOM].iter().all(|&x| x != 0));
    assert!(
        s[ORIENT_RANDOM + ORIENT_NEAR..].iter().all(|&x| x == 0),
        "exactly coplanar"
    );
    // A plain sanity case: d above the plane z = 0 seen counter-clockwise.
    let p = |x: f64, y: f64, z: f64| lift3::<Q>(&[x, y, z]);
    assert_eq!(
        orient3d(
            &p(0., 0., 0.),
            &p(1., 0., 0.),
            &p(0., 1., 0.),
            &p(0., 0., 1.)
        ),
        1
    );
    assert_eq!(
        orient3d(
            &p(0., 0., 0.),
            &p(0., 1., 0.),
            &p(1., 0., 0.),
            &p(0., 0., 1.)
        ),
        -1
    );
}

/// The quarter nets reproduce the patch: quarter `(a, b)` at `(s, t)` equals the patch at
/// `((a + s)/2, (b + t)/2)`.
#[test]
fn half_split_reproduces_the_patch() {
    let inp = Inputs::<Q>::new();
    let q = |x: f64| Q::from_f64(x);
    let params = [0.0, 0.25, 1.0 / 3.0, 0.7, 1.0];
    for net in &inp.nets {
        let quarters = half_split(net, &inp.half);
        for (k, quarter) in quarters.iter().enumerate() {
            let (a, b) = ((k / 2) as f64, (k % 2) as f64);
            for &s in &params {
                for &t in &params {
                    let (qs, qt) = (q(s), q(t));
                    let u = q(a).add(&qs).mul(&inp.half);
                    let v = q(b).add(&qt).mul(&inp.half);
                    assert_eq!(quarter.eval(&qs, &qt), net.eval(&u, &v));
                }
            }
        }
    }
}

/// The chord composition equals the Bernstein-product route exactly, and evaluates to the
/// patch along the chord; degrees 6 and 8.
#[test]
fn compose_line_is_the_patch_along_the_chord() {
    let inp = Inputs::<Q>::new();
    for (chords, deg) in [(&inp.chords6, 6), (&inp.chords8, 8)] {
        for (s, a, b) in chords {
            let c = compose_line(s, a, b);
            assert_eq!(c.len(), deg + 1);
            assert_eq!(c, compose_line_by_products(s, a, b));
            for k in 0..=7 {
                let t = Q::from_i64(k).div(&Q::from_i64(7));
                let u = a[0].add(&b[0].sub(&a[0]).mul(&t));
                let v = a[1].add(&b[1].sub(&a[1]).mul(&t));
                assert_eq!(eval(&c, &t), s.eval(&u, &v));
            }
        }
    }
}

#[test]
fn binomials() {
    assert_eq!(
        (0..=8).map(|k| binomial(8, k)).collect::<Vec<_>>(),
        [1, 8, 28, 56, 70, 56, 28, 8, 1]
    );
}
