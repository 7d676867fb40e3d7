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
                Value::List(vec![Value::Real(0.0), Value::Real(15.0), Value::Int(-2)].into())
            ]
            .into()
        )
    );
    assert!(p.entities[&2].is("B_SPLINE_SURFACE"));
    assert_eq!(p.entities[&3].part("X").unwrap()[0].num(), Some(1.0));
    assert!(parse("DATA;\n#1=A((1,2);\nENDSEC;").is_err());
    assert!(parse("no data").is_err());
    assert_eq!(parse("DATA;\n#1=A(1e999);\nENDSEC;").unwrap_err().line, 2);
}

/// Ids out of file order, a duplicate met only after the order broke (both lines named),
/// lower-case names, escaped quotes and strings spanning lines (line numbers after them).
#[test]
fn ids_out_of_order_duplicates_names_and_lines() {
    let t = "DATA;\n#5=point('x',(1.,2.,3.));\n#2=POINT('it''s\nmulti',(0,0,0));\n#9=Point($,.t.);\nENDSEC;";
    let p = parse(t).unwrap();
    assert_eq!(
        p.entities.keys().copied().collect::<Vec<_>>(),
        vec![2, 5, 9]
    );
    for id in [2, 5, 9] {
        assert_eq!(p.entities[&id].name(), "POINT");
    }
    assert_eq!(
        p.entities[&2].part("POINT").unwrap()[0],
        Value::Str("it's\nmulti".into())
    );
    assert_eq!(
        p.entities[&9].part("POINT").unwrap()[1].enumeration(),
        Some("T")
    );
    // #5 first on line 2, again on line 5 after #2 (line 3, its string ending on line 4).
    let dup = "DATA;\n#5=A(1);\n#2=B('a\nb');\n#5=C(2);\nENDSEC;";
    let e = parse(dup).unwrap_err();
    assert_eq!(e.line, 5, "{e}");
    assert!(
        e.reason.contains("#5 is defined twice (first on line 2)"),
        "{e}"
    );
    // In order, the duplicate still named with both lines.
    let e = parse("DATA;\n#1=A(1);\n#1=A(2);\nENDSEC;").unwrap_err();
    assert_eq!(
        (e.line, e.reason.contains("first on line 2")),
        (3, true),
        "{e}"
    );
    // Too many digits in a reference: a typed fault, not a wrap-around.
    assert!(parse("DATA;\n#1=A(#99999999999999999999999);\nENDSEC;").is_err());
    assert!(parse("DATA;\n#1=A('open);\nENDSEC;").is_err());
}

/// More distinct names than the parser keeps for sharing: every instance still has its own
/// name, upper-cased, and the later ones equal by value.
#[test]
fn many_distinct_names_are_all_read() {
    let mut t = String::from("DATA;\n");
    for i in 0..6000 {
        t.push_str(&format!(
            "#{}=name_{i}(.e{i}.);\n#{}=NAME_{i}(1);\n",
            2 * i + 1,
            2 * i + 2
        ));
    }
    t.push_str("ENDSEC;");
    let p = parse(&t).unwrap();
    assert_eq!(p.entities.len(), 12000);
    for i in [0, 4095, 4096, 5999] {
        let want = format!("NAME_{i}");
        assert_eq!(p.entities[&(2 * i + 1)].name(), want);
        assert_eq!(p.entities[&(2 * i + 2)].name(), want);
        let e = p.entities[&(2 * i + 1)].part(&want).unwrap()[0].enumeration();
        assert_eq!(e, Some(format!("E{i}").as_str()));
    }
}
