//! Part 21 parser: simple and complex instances, strings, typed values, located faults.

use vericad::io::step::part21::{Entity, Value, parse};
#[test]
fn parses_simple_complex_and_faults() {
    let t = "ISO-10303-21;\nHEADER;FILE_SCHEMA(('CONFIG_CONTROL_DESIGN'));ENDSEC;\nDATA;\n#1=CARTESIAN_POINT('a''b',(0.,1.5E1,-2));\n/* c */ #2=( BOUNDED_SURFACE() B_SPLINE_SURFACE(1,1,((#1,#1),(#1,#1)),.UNSPECIFIED.,.F.,.F.,.F.) );\n#3=X(LENGTH_MEASURE(1.),$,*);\nENDSEC;END-ISO-10303-21;";
    let p = parse(t).unwrap();
    assert_eq!(p.schema, vec!["CONFIG_CONTROL_DESIGN"]);
    assert_eq!(
        p.entities[&1],
        Entity::Simple(
            "CARTESIAN_POINT".into(),
            vec![
                Value::Str("a'b".into()),
                Value::List(vec![Value::Real(0.0), Value::Real(15.0), Value::Int(-2)])
            ]
        )
    );
    assert!(p.entities[&2].is("B_SPLINE_SURFACE"));
    assert_eq!(p.entities[&3].part("X").unwrap()[0].num(), Some(1.0));
    assert!(parse("DATA;\n#1=A((1,2);\nENDSEC;").is_err());
    assert!(parse("no data").is_err());
    assert_eq!(parse("DATA;\n#1=A(1e999);\nENDSEC;").unwrap_err().line, 2);
}
