//! STEP writer: the model as AP214 entities. A model with a B-rep is written with its
//! topology (`super::write_topology`); otherwise its B-spline surfaces and curves form a
//! geometric set (rational ones as complex instances). Reals are written with the shortest
//! decimal that reads back to the same double, so a write/read round trip keeps every bit.

use crate::model::Model;
use crate::spline::{NurbsCurve, NurbsSurface};
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

/// A parenthesised, comma-separated Part 21 list.
pub(super) fn list<T>(xs: &[T], f: impl Fn(&T) -> String) -> String {
    format!("({})", xs.iter().map(f).collect::<Vec<_>>().join(","))
}

/// A list of instance references `(#1,#2)`.
pub(super) fn refs(ids: &[u64]) -> String {
    list(ids, |i| format!("#{i}"))
}

/// A Part 21 string literal's contents (quotes doubled).
pub(super) fn text(s: &str) -> String {
    s.replace('\'', "''")
}

/// The DATA section being written: instances numbered from 1 in the order they are added.
#[derive(Default)]
pub(super) struct Out {
    pub(super) data: String,
    id: u64,
}

impl Out {
    /// A fresh instance id (the instance is written later with [`Out::put`]).
    pub(super) fn next(&mut self) -> u64 {
        self.id += 1;
        self.id
    }
    /// Write instance `#id = body;`.
    pub(super) fn put(&mut self, id: u64, body: &str) {
        let _ = writeln!(self.data, "#{id}={body};");
    }
    /// Write `body` as a new instance; returns its id.
    pub(super) fn add(&mut self, body: &str) -> u64 {
        let i = self.next();
        self.put(i, body);
        i
    }
    /// A `cartesian_point` (2D or 3D).
    pub(super) fn point(&mut self, p: &[f64]) -> u64 {
        self.add(&format!("CARTESIAN_POINT('',{})", list(p, |x| real(*x))))
    }
    /// A B-spline surface (a complex rational instance when its weights are not all 1).
    pub(super) fn surface(&mut self, s: &NurbsSurface<f64, 3>, name: &str) -> u64 {
        let h = &s.hom;
        let (pts, w) = s.points_weights();
        let nv = h.nv();
        let ids: Vec<u64> = pts.iter().map(|p| self.point(p)).collect();
        let net = list(&ids.chunks(nv).collect::<Vec<_>>(), |r| refs(r));
        let (mu, ku) = knots_mults(h.ku.knots());
        let (mv, kv) = knots_mults(h.kv.knots());
        let (p, q) = h.degrees();
        let ml = |m: &[usize]| list(m, |x| x.to_string());
        let kl = |k: &[f64]| list(k, |x| real(*x));
        let name = text(name);
        if s.is_polynomial() && w.first() == Some(&1.0) {
            self.add(&format!(
                "B_SPLINE_SURFACE_WITH_KNOTS('{name}',{p},{q},{net},.UNSPECIFIED.,.F.,.F.,.F.,{},{},{},{},.UNSPECIFIED.)",
                ml(&mu),
                ml(&mv),
                kl(&ku),
                kl(&kv)
            ))
        } else {
            let wl = list(&w.chunks(nv).collect::<Vec<_>>(), |r| list(r, |x| real(*x)));
            self.add(&format!(
                "(BOUNDED_SURFACE() B_SPLINE_SURFACE({p},{q},{net},.UNSPECIFIED.,.F.,.F.,.F.) B_SPLINE_SURFACE_WITH_KNOTS({},{},{},{},.UNSPECIFIED.) GEOMETRIC_REPRESENTATION_ITEM() RATIONAL_B_SPLINE_SURFACE({wl}) REPRESENTATION_ITEM('{name}') SURFACE())",
                ml(&mu),
                ml(&mv),
                kl(&ku),
                kl(&kv)
            ))
        }
    }
    /// A B-spline curve in space or in a parameter plane (a complex rational instance when its
    /// weights are not all 1).
    pub(super) fn curve<const D: usize>(&mut self, g: &NurbsCurve<f64, D>, name: &str) -> u64 {
        let (pts, w) = g.points_weights();
        let ids: Vec<u64> = pts.iter().map(|p| self.point(p)).collect();
        let (mu, ku) = knots_mults(g.hom.knots.knots());
        let cl = refs(&ids);
        let name = text(name);
        if w.iter().all(|x| *x == 1.0) {
            self.add(&format!(
                "B_SPLINE_CURVE_WITH_KNOTS('{name}',{},{cl},.UNSPECIFIED.,.F.,.F.,{},{},.UNSPECIFIED.)",
                g.hom.degree(),
                list(&mu, |x| x.to_string()),
                list(&ku, |x| real(*x))
            ))
        } else {
            self.add(&format!(
                "(BOUNDED_CURVE() B_SPLINE_CURVE({},{cl},.UNSPECIFIED.,.F.,.F.) B_SPLINE_CURVE_WITH_KNOTS({},{},.UNSPECIFIED.) CURVE() GEOMETRIC_REPRESENTATION_ITEM() RATIONAL_B_SPLINE_CURVE({}) REPRESENTATION_ITEM('{name}'))",
                g.hom.degree(),
                list(&mu, |x| x.to_string()),
                list(&ku, |x| real(*x)),
                list(&w, |x| real(*x))
            ))
        }
    }
    /// Units (`unit`, the model's length unit; radian; steradian), the representation context,
    /// the product structure Open CASCADE and other systems need to transfer a shape, and the
    /// shape representation `rep_type` of `items`. `uncertainty` is the length uncertainty
    /// declared (1e-7 when `None`).
    pub(super) fn shape(
        &mut self,
        unit: &str,
        uncertainty: Option<f64>,
        rep_type: &str,
        items: &[u64],
    ) {
        let (mm, u1, u2, u3, u4, c1) = (
            self.next(),
            self.next(),
            self.next(),
            self.next(),
            self.next(),
            self.next(),
        );
        let mut ids = [0u64; 10];
        for i in &mut ids {
            *i = self.next();
        }
        let [app, apd, pc, p, pdf, pdc, pd, pds, rep, sdr] = ids;
        self.put(mm, "(LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.))");
        match conversion_unit(unit) {
            Some((nm, f)) => {
                let dim = self.add("DIMENSIONAL_EXPONENTS(1.,0.,0.,0.,0.,0.,0.)");
                let mwu = self.add(&format!(
                    "LENGTH_MEASURE_WITH_UNIT(LENGTH_MEASURE({f}),#{mm})"
                ));
                self.put(
                    u1,
                    &format!(
                        "(CONVERSION_BASED_UNIT('{nm}',#{mwu}) LENGTH_UNIT() NAMED_UNIT(#{dim}))"
                    ),
                );
            }
            None => {
                let prefix = match unit {
                    "m" => "$",
                    "cm" => ".CENTI.",
                    "km" => ".KILO.",
                    "um" => ".MICRO.",
                    _ => ".MILLI.",
                };
                self.put(
                    u1,
                    &format!("(LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT({prefix},.METRE.))"),
                );
            }
        }
        self.put(u2, "(NAMED_UNIT(*) PLANE_ANGLE_UNIT() SI_UNIT($,.RADIAN.))");
        self.put(
            u3,
            "(NAMED_UNIT(*) SI_UNIT($,.STERADIAN.) SOLID_ANGLE_UNIT())",
        );
        self.put(
            u4,
            &format!(
                "UNCERTAINTY_MEASURE_WITH_UNIT(LENGTH_MEASURE({}),#{u1},'distance_accuracy_value','')",
                uncertainty.map_or_else(|| "1.E-07".to_string(), real)
            ),
        );
        self.put(
            c1,
            &format!(
                "(GEOMETRIC_REPRESENTATION_CONTEXT(3) GLOBAL_UNCERTAINTY_ASSIGNED_CONTEXT((#{u4})) GLOBAL_UNIT_ASSIGNED_CONTEXT((#{u1},#{u2},#{u3})) REPRESENTATION_CONTEXT('',''))"
            ),
        );
        self.put(app, "APPLICATION_CONTEXT('automotive_design')");
        self.put(
            apd,
            &format!(
                "APPLICATION_PROTOCOL_DEFINITION('international standard','automotive_design',2000,#{app})"
            ),
        );
        self.put(pc, &format!("PRODUCT_CONTEXT('',#{app},'mechanical')"));
        self.put(p, &format!("PRODUCT('vericad','vericad','',(#{pc}))"));
        self.put(pdf, &format!("PRODUCT_DEFINITION_FORMATION('','',#{p})"));
        self.put(
            pdc,
            &format!("PRODUCT_DEFINITION_CONTEXT('part definition',#{app},'design')"),
        );
        self.put(
            pd,
            &format!("PRODUCT_DEFINITION('design','',#{pdf},#{pdc})"),
        );
        self.put(pds, &format!("PRODUCT_DEFINITION_SHAPE('','',#{pd})"));
        self.put(rep, &format!("{rep_type}('',{},#{c1})", refs(items)));
        self.put(
            sdr,
            &format!("SHAPE_DEFINITION_REPRESENTATION(#{pds},#{rep})"),
        );
    }
    /// The whole exchange file: header and the DATA section.
    pub(super) fn finish(self, name: &str, description: &str) -> String {
        format!(
            "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION(('{description}'),'2;1');\nFILE_NAME('{}','',(''),(''),'vericad','vericad','');\nFILE_SCHEMA(('AUTOMOTIVE_DESIGN'));\nENDSEC;\nDATA;\n{}ENDSEC;\nEND-ISO-10303-21;\n",
            text(name),
            self.data
        )
    }
}

/// The model as STEP text, and what the file does not hold (see `super::write_topology` for
/// a model with a B-rep; without one, surfaces and 3D curves in a geometric set).
pub fn write(m: &Model, name: &str) -> (String, Vec<String>) {
    if let Some(b) = &m.brep {
        return super::write_topology::write(m, b, name);
    }
    let mut o = Out::default();
    let mut items = Vec::new();
    for s in &m.surfaces {
        items.push(o.surface(&s.nurbs, &s.name));
    }
    for c in &m.curves {
        // Domain curves are written as 3D curves with z = 0 (the IGES convention for curves
        // in a surface's parameter space).
        items.push(o.curve(&c.geometry.to_space(), &c.name));
    }
    let gs = o.add(&format!("GEOMETRIC_SET('',{})", refs(&items)));
    o.shape(
        m.unit.as_deref().unwrap_or("mm"),
        None,
        "GEOMETRICALLY_BOUNDED_SURFACE_SHAPE_REPRESENTATION",
        &[gs],
    );
    (o.finish(name, "vericad geometry"), Vec::new())
}

/// The model as STEP text ([`fn@write`] without its notes).
pub fn to_string(m: &Model, name: &str) -> String {
    write(m, name).0
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
