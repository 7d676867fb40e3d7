//! Part 21 parser: simple and complex instances, strings, typed values, located faults.

use vericad::io::step::part21::{Entity, Value, parse};
#[test]
fn parses_simple_complex_and_faults() {
    let t = "ISO-10303-21;\nHEADER;FILE_SCHEMA(('CONFIG_CONTROL_DESIGN'));ENDSEC;\nDATA;\n#1=CARTESIAN_POINT('a''b',(0.,1.5E1,-2));\n/* c */ #2=( BOUNDED_SURFACE() B_SPLINE_SURFACE(1,1,((#1,#1),(#1,#1)),.UNSPECIFIED.,.F.,.F.,.F.) );\n#3=X(LENGTH_MEASURE(1.),$,*);\nENDSEC;END-ISO-10303-21;";
    let p = parse(t).unwrap();
    assert_eq!(p.schema, vec!["CONFIG_CONTROL_DESIGN"]);
    assert_eq!(
        *p.entities.get(&1).unwrap(),
        Entity::Simple(
            "CARTESIAN_POINT".into(),
            vec![
                Value::Str("a'b".into()),
                Value::List(vec![Value::Real(0.0), Value::Real(15.0), Value::Int(-2)].into())
            ]
            .into()
        )
    );
    assert!(p.entities.get(&2).unwrap().is("B_SPLINE_SURFACE"));
    assert_eq!(
        p.entities.get(&3).unwrap().part("X").unwrap()[0].num(),
        Some(1.0)
    );
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
        assert_eq!(p.entities.get(&id).unwrap().name(), "POINT");
    }
    assert_eq!(
        p.entities.get(&2).unwrap().part("POINT").unwrap()[0],
        Value::Str("it's\nmulti".into())
    );
    assert_eq!(
        p.entities.get(&9).unwrap().part("POINT").unwrap()[1].enumeration(),
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
        assert_eq!(p.entities.get(&(2 * i + 1)).unwrap().name(), want);
        assert_eq!(p.entities.get(&(2 * i + 2)).unwrap().name(), want);
        let e = p.entities.get(&(2 * i + 1)).unwrap().part(&want).unwrap()[0].enumeration();
        assert_eq!(e, Some(format!("E{i}").as_str()));
    }
}

/// Nested lists of reals are kept as numbers and read back through `numbers` exactly as
/// written; a list mixing an integer, a nested empty list, an argument list of reals and a
/// typed parameter of reals stay lists of values; `list` refuses a list of reals (its items
/// are not values) and `numbers` refuses a list holding a non-number.
#[test]
fn lists_of_reals_are_kept_as_numbers() {
    let t = "ISO-10303-21;\nHEADER;ENDSEC;\nDATA;\n\
             #1=CARTESIAN_POINT('',(0.1,-2.5E-300,1.7976931348623157E308));\n\
             #2=X((1.,2),(),((0.5,0.25),(1.0)));\n\
             #3=Y(1.5,2.5);\n\
             #4=Z(PLANE_ANGLE_MEASURE(0.5,0.25),('a',1.));\n\
             ENDSEC;END-ISO-10303-21;";
    let p = parse(t).unwrap();
    let c = &p.entities.get(&1).unwrap().part("CARTESIAN_POINT").unwrap()[1];
    assert!(matches!(c, Value::Reals(_)), "{c:?}");
    assert_eq!(c.numbers(), Some(vec![0.1, -2.5e-300, f64::MAX]));
    assert_eq!(
        c.list_numbers(),
        Some(vec![Some(0.1), Some(-2.5e-300), Some(f64::MAX)])
    );
    assert!(c.list().is_none());
    let x = p.entities.get(&2).unwrap().part("X").unwrap();
    assert!(matches!(&x[0], Value::List(v) if v.len() == 2));
    assert_eq!(x[0].numbers(), Some(vec![1.0, 2.0]));
    assert!(matches!(&x[1], Value::List(v) if v.is_empty()));
    let rows = x[2].list().unwrap();
    assert_eq!(rows[0].numbers(), Some(vec![0.5, 0.25]));
    assert_eq!(rows[1].numbers(), Some(vec![1.0]));
    // Argument lists are lists of values, whatever they hold.
    let y = p.entities.get(&3).unwrap().part("Y").unwrap();
    assert_eq!(y.len(), 2);
    assert_eq!(y[1].num(), Some(2.5));
    let z = p.entities.get(&4).unwrap().part("Z").unwrap();
    match &z[0] {
        Value::Typed(t) => {
            assert_eq!(&*t.0, "PLANE_ANGLE_MEASURE");
            assert_eq!(t.1.len(), 2);
            assert_eq!(t.1[1].num(), Some(0.25));
        }
        v => panic!("expected a typed parameter, got {v:?}"),
    }
    assert_eq!(z[1].numbers(), None);
    assert_eq!(z[1].list_numbers(), Some(vec![None, Some(1.0)]));
}

#[test]
fn lists_of_references_are_kept_as_ids() {
    let t = "ISO-10303-21;\nHEADER;ENDSEC;\nDATA;\n\
             #1=EDGE_LOOP('',(#10,#11,#12));\n\
             #2=NET('',((#1,#2),(#3,#4)),(#5,$),(),(#6,1.5));\n\
             #3=T(ITEMS(#7,#8),#9);\n\
             ENDSEC;END-ISO-10303-21;";
    let p = parse(t).unwrap();
    let refs = |v: &Value| v.list_refs().map(|l| l.collect::<Vec<_>>());
    let l = &p.entities.get(&1).unwrap().part("EDGE_LOOP").unwrap()[1];
    assert!(matches!(l, Value::Refs(_)), "{l:?}");
    assert_eq!(refs(l), Some(vec![Some(10), Some(11), Some(12)]));
    assert_eq!(l.list_refs().unwrap().len(), 3);
    assert!(l.list().is_none() && l.numbers().is_none());
    let mut all = Vec::new();
    l.refs(&mut all);
    assert_eq!(all, vec![10, 11, 12]);
    let n = p.entities.get(&2).unwrap().part("NET").unwrap();
    // A list of lists of references: rows kept as ids, the outer list a list of values.
    let rows = n[1].list().unwrap();
    assert_eq!(refs(&rows[0]), Some(vec![Some(1), Some(2)]));
    assert_eq!(refs(&rows[1]), Some(vec![Some(3), Some(4)]));
    // Not all references: a list of values, read item by item.
    assert!(matches!(&n[2], Value::List(_)));
    assert_eq!(refs(&n[2]), Some(vec![Some(5), None]));
    assert_eq!(refs(&n[3]), Some(vec![]));
    assert_eq!(refs(&n[4]), Some(vec![Some(6), None]));
    assert_eq!(refs(&Value::Ref(1)), None);
    assert_eq!(p.entities.get(&2).unwrap().refs(), vec![1, 2, 3, 4, 5, 6]);
    // A typed parameter's arguments stay values; the argument list of an instance too.
    let a = p.entities.get(&3).unwrap().part("T").unwrap();
    match &a[0] {
        Value::Typed(t) => assert_eq!(
            t.1.iter().map(|v| v.reference()).collect::<Vec<_>>(),
            vec![Some(7), Some(8)]
        ),
        v => panic!("expected a typed parameter, got {v:?}"),
    }
    assert_eq!(a[1].reference(), Some(9));
}
