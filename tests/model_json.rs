//! The native model format: every malformed file in `tests/data/malformed` is refused with a
//! typed error naming the file, the JSON path and the reason (expectations, written by hand,
//! in `EXPECTED.json`); valid models round-trip bit for bit.

use std::collections::BTreeMap;
use vericad::model::json;

#[derive(serde::Deserialize)]
struct Expect {
    path: String,
    reason_contains: String,
}

#[test]
fn malformed_files_get_path_precise_errors() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/malformed");
    let exp: BTreeMap<String, Expect> =
        serde_json::from_str(&std::fs::read_to_string(dir.join("EXPECTED.json")).unwrap()).unwrap();
    assert!(exp.len() >= 18);
    for (name, e) in &exp {
        let path = dir.join(name);
        let err = json::read(&path).expect_err(name);
        assert!(
            err.file.ends_with(name.as_str()),
            "{name}: file {}",
            err.file
        );
        assert_eq!(err.path, e.path, "{name}: {err}");
        assert!(
            err.reason.contains(&e.reason_contains),
            "{name}: reason '{}' lacks '{}'",
            err.reason,
            e.reason_contains
        );
    }
}

#[test]
fn missing_file_is_an_error_not_a_panic() {
    let e = json::read(std::path::Path::new("/nonexistent/model.json")).unwrap_err();
    assert_eq!(e.path, "(file)");
}

#[test]
fn round_trip_is_bit_exact() {
    let text = r#"{"unit":"mm","curves":[
        {"name":"d","degree":3,"knots":[0,0,0,0,0.1234567890123,1,1,1,1],
         "control_points":[[0.1,2.2204460492503099e-16],[0.30000000000000004,0.7],[0.9,1e-300],[0.5,0.5],[1,1]],
         "weights":[1,0.7071067811865476,2,1,3]}],
      "surfaces":[{"name":"s","degree_u":2,"degree_v":1,"knots_u":[0,0,0,0.5,1,1,1],"knots_v":[-3,-3,7,7],
         "control_points":[[[0,0,0],[0,1,1e10]],[[1,0,0.1],[1,1,-0.2]],[[2,0,3],[2,1,1]],[[3,0,0],[3,1,5.5]]],
         "weights":[[1,2],[3,4],[0.5,0.25],[1,1]]}],
      "patch_sets":[{"name":"all","surfaces":[0]}]}"#;
    let m = json::from_str(text, "rt").unwrap();
    let again = json::from_str(&json::to_string(&m), "rt2").unwrap();
    assert_eq!(m, again);
    // Bits, not just values: compare every control point and knot through to_bits
    // (2.2204460492503099e-16 is a value serde_json's fast float parser rounds wrongly
    // without its `float_roundtrip` feature).
    let (c1, _) = match &m.curves[0].geometry {
        vericad::model::CurveGeometry::Domain(d) => d.points_weights(),
        _ => unreachable!(),
    };
    let (c2, _) = match &again.curves[0].geometry {
        vericad::model::CurveGeometry::Domain(d) => d.points_weights(),
        _ => unreachable!(),
    };
    assert_eq!(c1[0][1].to_bits(), 2.2204460492503099e-16f64.to_bits());
    assert_eq!(c1[0][1].to_bits(), c2[0][1].to_bits());
    let (p1, w1) = m.surfaces[0].nurbs.points_weights();
    let (p2, w2) = again.surfaces[0].nurbs.points_weights();
    for (a, b) in p1
        .iter()
        .flatten()
        .chain(&w1)
        .zip(p2.iter().flatten().chain(&w2))
    {
        assert_eq!(a.to_bits(), b.to_bits());
    }
}

#[test]
fn embedded_default_model_is_valid() {
    let m = json::from_str(vericad::demo::DEFAULT_MODEL, "embedded").unwrap();
    assert_eq!(m.surfaces.len(), 1);
    assert_eq!(m.curves.len(), 1);
}
