//! Bad and hostile input to the Coons-patch approximation: typed errors naming the curve,
//! the boundary file format, random and non-finite boundaries, the fuzz target's body.

mod common;

use common::coons::{by_index, plane_model, polyline, square};
use vericad::approx::coons::boundary::{BoundarySpec, CurveRef, CurveSpec};
use vericad::approx::coons::{Approximant, CoonsError, Params, approximate};
use vericad::model::{Curve, CurveGeometry};
use vericad::spline::NurbsCurve;

fn run(curves: Vec<CurveSpec>, params: &Params) -> Result<Approximant, CoonsError> {
    approximate(&plane_model(), &BoundarySpec { curves }, params)
}

#[test]
fn bad_input_is_a_typed_error_naming_the_curve() {
    let p = Params::default();
    // A plane square works (sanity of the fixture).
    assert!(run(square(0.0, 1.0), &p).unwrap().report.within_tol);
    // Not closing: the third curve moved.
    let mut c = square(0.0, 1.0);
    c[2] = polyline(vec![[1.0, 1.2, 0.0], [0.0, 1.2, 0.0]]);
    c[2].name = Some("top".into());
    match run(c, &p) {
        Err(CoonsError::NotClosed { from, to, .. }) => {
            assert!(from == "top" || to == "top", "{from} {to}")
        }
        other => panic!("{other:?}"),
    }
    // A zero-length side.
    let mut c = square(0.0, 1.0);
    c.insert(1, polyline(vec![[1.0, 0.0, 0.0], [1.0, 0.0, 0.0]]));
    c.remove(2);
    c[1].name = Some("point".into());
    c[2] = polyline(vec![[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]);
    match run(c, &p) {
        Err(CoonsError::Degenerate { curve, .. }) => assert_eq!(curve, "point"),
        other => panic!("{other:?}"),
    }
    // A self-crossing loop (a bow tie).
    let mut c = vec![
        polyline(vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]]),
        polyline(vec![[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]),
        polyline(vec![[0.0, 1.0, 0.0], [1.0, 1.0, 0.0]]),
        polyline(vec![[1.0, 1.0, 0.0], [0.0, 0.0, 0.0]]),
    ];
    c[1].name = Some("diagonal 1".into());
    c[3].name = Some("diagonal 2".into());
    match run(c, &p) {
        Err(CoonsError::SelfCrossing { a, b }) => {
            assert!(a.contains("diagonal") || b.contains("diagonal"), "{a} {b}")
        }
        Err(CoonsError::Flat(names)) => assert!(names.contains("diagonal"), "{names}"),
        other => panic!("{other:?}"),
    }
    // Far from every surface.
    match run(square(50.0, 1.0), &p) {
        Err(CoonsError::FarFromSurfaces { curves, .. }) => assert!(curves.contains("#0")),
        other => panic!("{other:?}"),
    }
    // M or N zero.
    for (m, n) in [(0, 8), (8, 0)] {
        let q = Params {
            m,
            n,
            ..Default::default()
        };
        assert!(matches!(
            run(square(0.0, 1.0), &q),
            Err(CoonsError::Resolution { .. })
        ));
    }
    // A curve index the model does not have, a domain curve, a non-finite point.
    let mut m = plane_model();
    m.curves.push(Curve {
        name: "domain".into(),
        geometry: CurveGeometry::Domain(
            NurbsCurve::new(
                vec![0.0, 0.0, 1.0, 1.0],
                1,
                vec![[0.0, 0.0], [1.0, 0.0]],
                vec![1.0, 1.0],
            )
            .unwrap(),
        ),
    });
    let mut c = square(0.0, 1.0);
    c[0] = by_index(7);
    assert!(
        matches!(approximate(&m, &BoundarySpec { curves: c }, &p), Err(CoonsError::Curve { curve, .. }) if curve == "#0")
    );
    let mut c = square(0.0, 1.0);
    c[1] = by_index(0);
    assert!(
        matches!(approximate(&m, &BoundarySpec { curves: c }, &p), Err(CoonsError::Curve { curve, .. }) if curve.contains("#1"))
    );
    let mut c = square(0.0, 1.0);
    c[3] = polyline(vec![[0.0, 1.0, 0.0], [f64::NAN, 0.5, 0.0], [0.0, 0.0, 0.0]]);
    assert!(matches!(run(c, &p), Err(CoonsError::Curve { curve, .. }) if curve == "#3"));
    // Three curves; a tolerance that is NaN.
    let mut c = square(0.0, 1.0);
    c.pop();
    assert!(matches!(run(c, &p), Err(CoonsError::Boundary(_))));
    let q = Params {
        tol: f64::NAN,
        ..Default::default()
    };
    assert!(matches!(
        run(square(0.0, 1.0), &q),
        Err(CoonsError::Tolerance(_))
    ));
    // Bad JSON names its path.
    match BoundarySpec::parse(r#"{"curves": [{"curve": 0, "colour": 1}]}"#) {
        Err(CoonsError::Boundary(msg)) => assert!(msg.contains("curves[0]"), "{msg}"),
        other => panic!("{other:?}"),
    }
}

#[test]
fn boundary_file_format() {
    let spec = BoundarySpec::parse(
        r#"{"curves": [{"curve": 3}, {"curve": "wing", "reversed": true}, {"polyline": [[0,0,0],[1,0,0]]}, {"curve": 1, "name": "left"}]}"#,
    )
    .unwrap();
    assert_eq!(spec.curves[0].curve, Some(CurveRef::Index(3)));
    assert_eq!(spec.curves[1].curve, Some(CurveRef::Name("wing".into())));
    assert!(spec.curves[1].reversed);
    assert_eq!(spec.curves[2].polyline.as_ref().map(|p| p.len()), Some(2));
    assert_eq!(spec.curves[3].name.as_deref(), Some("left"));
}

/// Random and hostile boundaries never panic: polylines with repeated, huge, tiny,
/// non-finite or random points, random M, N, K and tolerances; every outcome is a result or
/// a typed error.
#[test]
fn hostile_boundaries_never_panic() {
    let mut rng = common::Rng(0xC0045);
    let model = plane_model();
    let specials = [
        0.0,
        -0.0,
        1e-300,
        1e300,
        f64::MAX,
        f64::MIN_POSITIVE,
        f64::NAN,
        f64::INFINITY,
        1.0,
        0.5,
    ];
    let mut outcomes = std::collections::BTreeMap::new();
    for case in 0..200 {
        let mut curves = square(rng.range(-0.5, 0.5), rng.range(1e-9, 3.0));
        for _ in 0..rng.below(4) {
            let k = rng.below(4);
            let mut pts = curves[k].polyline.clone().unwrap();
            let q = rng.below(pts.len());
            match rng.below(4) {
                0 => pts[q][rng.below(3)] = specials[rng.below(specials.len())],
                1 => pts.insert(q, pts[q]),
                2 => pts.push([
                    rng.range(-2.0, 2.0),
                    rng.range(-2.0, 2.0),
                    rng.range(-1.0, 1.0),
                ]),
                _ => pts.truncate(1),
            }
            curves[k] = polyline(pts);
        }
        if rng.below(10) == 0 {
            curves.truncate(rng.below(5));
        }
        let params = Params {
            tol: [1e-3, 1e-3, 1e-3, 0.0, f64::NAN, 1e-12, 10.0][rng.below(7)],
            m: rng.below(12),
            n: 1 + rng.below(12),
            max_resolution: 1 + rng.below(32),
            k_nearest: 1 + rng.below(12),
            ..Default::default()
        };
        let r = std::panic::catch_unwind(|| {
            approximate(
                &model,
                &BoundarySpec {
                    curves: curves.clone(),
                },
                &params,
            )
        });
        assert!(r.is_ok(), "case {case} panicked: {curves:?} {params:?}");
        let key = match r {
            Ok(Ok(_)) => "approximant".to_string(),
            Ok(Err(e)) => format!("{e:?}")
                .split([' ', '(', '{'])
                .next()
                .unwrap_or("")
                .to_string(),
            Err(_) => "panic".into(),
        };
        *outcomes.entry(key).or_insert(0) += 1;
    }
    eprintln!("{outcomes:?}");
    assert!(
        outcomes.get("approximant").is_some_and(|n| *n >= 20),
        "{outcomes:?}"
    );
}

/// The fuzz target's body over a seed and byte-level mutations of it.
#[test]
fn coons_boundary_fuzz_entry_survives_mutations() {
    let seed = br#"{"curves": [{"polyline": [[0,0,0],[1,0,0]]}, {"polyline": [[1,0,0],[1,1,0.2]]}, {"polyline": [[1,1,0.2],[0,1,0]]}, {"polyline": [[0,1,0],[0,0,0]], "reversed": false}]}"#;
    vericad::fuzz_entry::coons_boundary(seed);
    let mut rng = common::Rng(7);
    for _ in 0..300 {
        let mut s = seed.to_vec();
        for _ in 0..1 + rng.below(3) {
            let k = rng.below(s.len());
            s[k] = b"0123456789.-e,[]{}\" 1"[rng.below(20)];
        }
        vericad::fuzz_entry::coons_boundary(&s);
    }
}
