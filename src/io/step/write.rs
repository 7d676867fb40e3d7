//! STEP writer: B-spline surfaces and curves of a model as an AP214 geometric set (rational
//! ones as complex instances). Reals are written with the shortest decimal that reads back
//! to the same double, so a write/read round trip keeps every bit.

use crate::model::Model;
use std::fmt::Write;

/// A real in Part 21 syntax (always with a decimal point).
pub fn real(x: f64) -> String {
    let s = format!("{x:?}");
    let s = s.replace('e', "E");
    match s.find('E') {
        Some(i) if !s[..i].contains('.') => format!("{}.{}", &s[..i], &s[i..]),
        _ if !s.contains('.') && !s.contains('E') => format!("{s}."),
        _ => s,
    }
}

fn knots_mults(k: &[f64]) -> (Vec<usize>, Vec<f64>) {
    let mut m: Vec<usize> = Vec::new();
    let mut v: Vec<f64> = Vec::new();
    for &x in k {
        if v.last() == Some(&x) {
            *m.last_mut().unwrap_or(&mut 0) += 1;
        } else {
            v.push(x);
            m.push(1);
        }
    }
    (m, v)
}

fn list<T>(xs: &[T], f: impl Fn(&T) -> String) -> String {
    format!("({})", xs.iter().map(f).collect::<Vec<_>>().join(","))
}

/// Write the model's surfaces and 3D curves.
pub fn to_string(m: &Model, name: &str) -> String {
    let mut out = String::new();
    let mut id = 0u64;
    let mut next = || {
        id += 1;
        id
    };
    let mut data = String::new();
    let mut items = Vec::new();
    let point = |data: &mut String, p: &[f64; 3], next: &mut dyn FnMut() -> u64| {
        let i = next();
        let _ = writeln!(
            data,
            "#{i}=CARTESIAN_POINT('',({},{},{}));",
            real(p[0]),
            real(p[1]),
            real(p[2])
        );
        i
    };
    for s in &m.surfaces {
        let h = &s.nurbs.hom;
        let (pts, w) = s.nurbs.points_weights();
        let nv = h.nv();
        let ids: Vec<u64> = pts.iter().map(|p| point(&mut data, p, &mut next)).collect();
        let net = list(&ids.chunks(nv).collect::<Vec<_>>(), |r| {
            list(r, |i| format!("#{i}"))
        });
        let (mu, ku) = knots_mults(h.ku.knots());
        let (mv, kv) = knots_mults(h.kv.knots());
        let (p, q) = h.degrees();
        let i = next();
        let ml = |m: &[usize]| list(m, |x| x.to_string());
        let kl = |k: &[f64]| list(k, |x| real(*x));
        if s.nurbs.is_polynomial() && w.first() == Some(&1.0) {
            let _ = writeln!(
                data,
                "#{i}=B_SPLINE_SURFACE_WITH_KNOTS('{}',{p},{q},{net},.UNSPECIFIED.,.F.,.F.,.F.,{},{},{},{},.UNSPECIFIED.);",
                s.name.replace('\'', "''"),
                ml(&mu),
                ml(&mv),
                kl(&ku),
                kl(&kv)
            );
        } else {
            let wl = list(&w.chunks(nv).collect::<Vec<_>>(), |r| list(r, |x| real(*x)));
            let _ = writeln!(
                data,
                "#{i}=(BOUNDED_SURFACE() B_SPLINE_SURFACE({p},{q},{net},.UNSPECIFIED.,.F.,.F.,.F.) B_SPLINE_SURFACE_WITH_KNOTS({},{},{},{},.UNSPECIFIED.) GEOMETRIC_REPRESENTATION_ITEM() RATIONAL_B_SPLINE_SURFACE({wl}) REPRESENTATION_ITEM('{}') SURFACE());",
                ml(&mu),
                ml(&mv),
                kl(&ku),
                kl(&kv),
                s.name.replace('\'', "''")
            );
        }
        items.push(i);
    }
    for c in &m.curves {
        // Domain curves are written as 3D curves with z = 0 (the IGES convention for curves
        // in a surface's parameter space).
        let lifted = c.geometry.to_space();
        let g = &lifted;
        let (pts, w) = g.points_weights();
        let ids: Vec<u64> = pts.iter().map(|p| point(&mut data, p, &mut next)).collect();
        let (mu, ku) = knots_mults(g.hom.knots.knots());
        let i = next();
        let cl = list(&ids, |i| format!("#{i}"));
        if w.iter().all(|x| *x == 1.0) {
            let _ = writeln!(
                data,
                "#{i}=B_SPLINE_CURVE_WITH_KNOTS('{}',{},{cl},.UNSPECIFIED.,.F.,.F.,{},{},.UNSPECIFIED.);",
                c.name.replace('\'', "''"),
                g.hom.degree(),
                list(&mu, |x| x.to_string()),
                list(&ku, |x| real(*x))
            );
        } else {
            let _ = writeln!(
                data,
                "#{i}=(BOUNDED_CURVE() B_SPLINE_CURVE({},{cl},.UNSPECIFIED.,.F.,.F.) B_SPLINE_CURVE_WITH_KNOTS({},{},.UNSPECIFIED.) CURVE() GEOMETRIC_REPRESENTATION_ITEM() RATIONAL_B_SPLINE_CURVE({}) REPRESENTATION_ITEM('{}'));",
                g.hom.degree(),
                list(&mu, |x| x.to_string()),
                list(&ku, |x| real(*x)),
                list(&w, |x| real(*x)),
                c.name.replace('\'', "''")
            );
        }
        items.push(i);
    }
    let gs = next();
    let _ = writeln!(
        data,
        "#{gs}=GEOMETRIC_SET('',{});",
        list(&items, |i| format!("#{i}"))
    );
    // Product structure and units, so that other systems transfer the set as a shape.
    let mut n = || next();
    let (mm, u1, u2, u3, u4, c1) = (n(), n(), n(), n(), n(), n());
    let (app, apd, pc, p, pdf, pdc, pd, pds, rep, sdr) =
        (n(), n(), n(), n(), n(), n(), n(), n(), n(), n());
    let _ = writeln!(
        data,
        "#{mm}=(LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.));"
    );
    let u = m.unit.as_deref().unwrap_or("mm");
    match conversion_unit(u) {
        Some((nm, f)) => {
            let (dim, mwu) = (n(), n());
            let _ = writeln!(data, "#{dim}=DIMENSIONAL_EXPONENTS(1.,0.,0.,0.,0.,0.,0.);");
            let _ = writeln!(
                data,
                "#{mwu}=LENGTH_MEASURE_WITH_UNIT(LENGTH_MEASURE({f}),#{mm});"
            );
            let _ = writeln!(
                data,
                "#{u1}=(CONVERSION_BASED_UNIT('{nm}',#{mwu}) LENGTH_UNIT() NAMED_UNIT(#{dim}));"
            );
        }
        None => {
            let prefix = match u {
                "m" => "$",
                "cm" => ".CENTI.",
                "km" => ".KILO.",
                "um" => ".MICRO.",
                _ => ".MILLI.",
            };
            let _ = writeln!(
                data,
                "#{u1}=(LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT({prefix},.METRE.));"
            );
        }
    }
    let _ = writeln!(
        data,
        "#{u2}=(NAMED_UNIT(*) PLANE_ANGLE_UNIT() SI_UNIT($,.RADIAN.));"
    );
    let _ = writeln!(
        data,
        "#{u3}=(NAMED_UNIT(*) SI_UNIT($,.STERADIAN.) SOLID_ANGLE_UNIT());"
    );
    let _ = writeln!(
        data,
        "#{u4}=UNCERTAINTY_MEASURE_WITH_UNIT(LENGTH_MEASURE(1.E-07),#{u1},'distance_accuracy_value','');"
    );
    let _ = writeln!(
        data,
        "#{c1}=(GEOMETRIC_REPRESENTATION_CONTEXT(3) GLOBAL_UNCERTAINTY_ASSIGNED_CONTEXT((#{u4})) GLOBAL_UNIT_ASSIGNED_CONTEXT((#{u1},#{u2},#{u3})) REPRESENTATION_CONTEXT('',''));"
    );
    let _ = writeln!(data, "#{app}=APPLICATION_CONTEXT('automotive_design');");
    let _ = writeln!(
        data,
        "#{apd}=APPLICATION_PROTOCOL_DEFINITION('international standard','automotive_design',2000,#{app});"
    );
    let _ = writeln!(data, "#{pc}=PRODUCT_CONTEXT('',#{app},'mechanical');");
    let _ = writeln!(data, "#{p}=PRODUCT('vericad','vericad','',(#{pc}));");
    let _ = writeln!(data, "#{pdf}=PRODUCT_DEFINITION_FORMATION('','',#{p});");
    let _ = writeln!(
        data,
        "#{pdc}=PRODUCT_DEFINITION_CONTEXT('part definition',#{app},'design');"
    );
    let _ = writeln!(data, "#{pd}=PRODUCT_DEFINITION('design','',#{pdf},#{pdc});");
    let _ = writeln!(data, "#{pds}=PRODUCT_DEFINITION_SHAPE('','',#{pd});");
    let _ = writeln!(
        data,
        "#{rep}=GEOMETRICALLY_BOUNDED_SURFACE_SHAPE_REPRESENTATION('',(#{gs}),#{c1});"
    );
    let _ = writeln!(
        data,
        "#{sdr}=SHAPE_DEFINITION_REPRESENTATION(#{pds},#{rep});"
    );
    let _ = writeln!(
        out,
        "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION(('vericad geometry'),'2;1');\nFILE_NAME('{}','',(''),(''),'vericad','vericad','');\nFILE_SCHEMA(('AUTOMOTIVE_DESIGN'));\nENDSEC;\nDATA;",
        name.replace('\'', "''")
    );
    out.push_str(&data);
    out.push_str("ENDSEC;\nEND-ISO-10303-21;\n");
    out
}

/// Length units written as a CONVERSION_BASED_UNIT: STEP name and millimetres per unit.
pub fn conversion_unit(u: &str) -> Option<(&'static str, &'static str)> {
    Some(match u {
        "inch" | "in" => ("INCH", "25.4"),
        "foot" | "ft" => ("FOOT", "304.8"),
        "mile" => ("MILE", "1609344."),
        "mil" => ("MIL", "0.0254"),
        "microinch" => ("MICROINCH", "0.0000254"),
        _ => return None,
    })
}

/// Whether the writer stores unit `u` (the SI units and [`conversion_unit`]s).
pub fn unit_supported(u: &str) -> bool {
    conversion_unit(u).is_some() || matches!(u, "m" | "mm" | "cm" | "km" | "um")
}
