//! IGES writer: rational B-spline surfaces (128) and curves (126) of a model; a B-rep's faces
//! as trimmed surfaces (`super::write_faces`). Reals are written with the shortest decimal
//! that reads back to the same double (round trips keep every bit).

use crate::model::{CurveGeometry, Model};
use std::collections::BTreeSet;

pub(super) fn real(x: f64) -> String {
    let s = format!("{x:?}").replace('e', "E");
    if s.contains('.') || s.contains('E') {
        s
    } else {
        format!("{s}.")
    }
}

/// Lay out free-format text into 64-column P lines with the DE back pointer.
fn p_lines(text: &str, de: usize, seq: &mut usize, out: &mut Vec<String>) -> usize {
    let mut count = 0;
    let mut line = String::new();
    for tok in text.split_inclusive([',', ';']) {
        if line.len() + tok.len() > 64 {
            out.push(format!("{line:<64} {de:>7}P{:>7}", *seq));
            *seq += 1;
            count += 1;
            line.clear();
        }
        line.push_str(tok);
    }
    if !line.is_empty() {
        out.push(format!("{line:<64} {de:>7}P{:>7}", *seq));
        *seq += 1;
        count += 1;
    }
    count
}

fn hol(s: &str) -> String {
    format!("{}H{s}", s.len())
}

/// Parameter text of a 126 entity.
pub(super) fn curve_126(g: &crate::spline::NurbsCurve<f64, 3>) -> String {
    let (pts, w) = g.points_weights();
    let k = pts.len() - 1;
    let mut t = format!(
        "126,{k},{},0,0,{},0,",
        g.hom.degree(),
        if w.iter().all(|x| *x == w[0]) { 1 } else { 0 }
    );
    for x in g.hom.knots.knots() {
        t += &format!("{},", real(*x));
    }
    for x in &w {
        t += &format!("{},", real(*x));
    }
    for p in &pts {
        t += &format!("{},{},{},", real(p[0]), real(p[1]), real(p[2]));
    }
    let (a, b) = g.hom.domain();
    t += &format!("{},{},0.,0.,1.;", real(a), real(b));
    t
}

/// Entity type, parameter text, directory status and form number of each entity, in DE
/// order.
pub(super) type Params = Vec<(i64, String, &'static str, u8)>;

/// Status of independent entities and of entities used by others (physically dependent,
/// parametric use).
const INDEPENDENT: &str = "00000000";
pub(super) const DEPENDENT: &str = "00010500";

/// Parameter text of a 128 entity.
pub(super) fn surface_128(s: &crate::spline::NurbsSurface<f64, 3>) -> String {
    let h = &s.hom;
    let (pts, w) = s.points_weights();
    let (nu, nv) = (h.nu(), h.nv());
    let (p, q) = h.degrees();
    let rational = !s.is_polynomial() || w[0] != 1.0;
    let mut t = format!(
        "128,{},{},{p},{q},0,0,{},0,0,",
        nu - 1,
        nv - 1,
        if rational { 0 } else { 1 }
    );
    for k in h.ku.knots().iter().chain(h.kv.knots()) {
        t += &format!("{},", real(*k));
    }
    for jv in 0..nv {
        for iu in 0..nu {
            t += &format!("{},", real(w[iu * nv + jv]));
        }
    }
    for jv in 0..nv {
        for iu in 0..nu {
            let c = pts[iu * nv + jv];
            t += &format!("{},{},{},", real(c[0]), real(c[1]), real(c[2]));
        }
    }
    let (u0, u1, v0, v1) = h.domain();
    t += &format!("{},{},{},{};", real(u0), real(u1), real(v0), real(v1));
    t
}

/// The model as IGES text ([`fn@write`] without its notes).
pub fn to_string(m: &Model, name: &str) -> String {
    write(m, name).0
}

/// How a B-rep is written.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum BrepForm {
    /// The B-rep entities (186/514/510/508/504/502; `super::write_brep`): shells, solids,
    /// edges shared between faces.
    #[default]
    BrepEntities,
    /// Trimmed surfaces (144 over 128, a 142 per loop; `super::write_faces`): the form most
    /// IGES readers take; no shells, solids or shared edges, and loops whose edges have no
    /// pcurve are left for the reader to project.
    TrimmedSurfaces,
}

/// Write the model with its B-rep (if any) as B-rep entities ([`write_with`]).
pub fn write(m: &Model, name: &str) -> (String, Vec<String>) {
    write_with(m, name, BrepForm::default())
}

/// Write the model: a B-rep in the form `form`, the other surfaces as 128 (144 with
/// 142/102/126 when they have trim loops) and 3D curves (126); and what the file does not
/// hold.
pub fn write_with(m: &Model, name: &str, form: BrepForm) -> (String, Vec<String>) {
    let mut params: Params = Vec::new();
    let mut notes = Vec::new();
    let as_faces = match (&m.brep, form) {
        (Some(b), BrepForm::TrimmedSurfaces) => {
            super::write_faces::faces(m, b, &mut params, &mut notes)
        }
        (Some(b), BrepForm::BrepEntities) => super::write_brep::brep(m, b, &mut params, &mut notes),
        (None, _) => BTreeSet::new(),
    };
    let de_next = |params: &Params| 2 * params.len() + 1;
    for (si, s) in m.surfaces.iter().enumerate() {
        if as_faces.contains(&si) {
            continue;
        }
        let t = surface_128(&s.nurbs);
        let trimmed = !s.trim_loops.is_empty();
        let sde = de_next(&params);
        params.push((128, t, if trimmed { "00010000" } else { INDEPENDENT }, 0));
        if trimmed {
            let (mut outer, mut holes) = (None, Vec::new());
            for l in &s.trim_loops {
                let mut des = Vec::new();
                for c in &l.curves {
                    des.push(de_next(&params));
                    params.push((
                        126,
                        curve_126(&CurveGeometry::Domain(c.clone()).to_space()),
                        DEPENDENT,
                        0,
                    ));
                }
                let bde = if des.len() == 1 {
                    des[0]
                } else {
                    let d = de_next(&params);
                    let list: Vec<String> = des.iter().map(|x| x.to_string()).collect();
                    params.push((
                        102,
                        format!("102,{},{};", des.len(), list.join(",")),
                        DEPENDENT,
                        0,
                    ));
                    d
                };
                let cde = de_next(&params);
                params.push((142, format!("142,1,{sde},{bde},0,1;"), DEPENDENT, 0));
                if l.outer && outer.is_none() {
                    outer = Some(cde);
                } else {
                    holes.push(cde);
                }
            }
            let hs: String = holes.iter().map(|h| format!(",{h}")).collect();
            params.push((
                144,
                format!(
                    "144,{sde},{},{},{}{hs};",
                    usize::from(outer.is_some()),
                    holes.len(),
                    outer.unwrap_or(0)
                ),
                INDEPENDENT,
                0,
            ));
        }
    }
    for c in &m.curves {
        // Domain curves are written as 3D curves with z = 0 (the IGES convention for curves
        // in a surface's parameter space).
        let lifted = c.geometry.to_space();
        let g = &lifted;
        params.push((126, curve_126(g), INDEPENDENT, 0));
    }
    let mut d = Vec::new();
    let mut p = Vec::new();
    let mut pseq = 1;
    for (i, (ty, t, status, form)) in params.iter().enumerate() {
        let de = 2 * i + 1;
        let start = pseq;
        let n = p_lines(t, de, &mut pseq, &mut p);
        d.push(format!(
            "{ty:>8}{start:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}D{:>7}",
            0, 0, 0, 0, 0, 0, status, de
        ));
        d.push(format!(
            "{ty:>8}{:>8}{:>8}{n:>8}{form:>8}{:>8}{:>8}{:>8}{:>8}D{:>7}",
            0,
            0,
            "",
            "",
            "",
            0,
            de + 1
        ));
    }
    let unit = m.unit.as_deref().unwrap_or("mm");
    let flag = match unit {
        "inch" | "in" => 1,
        "mm" => 2,
        "ft" | "foot" => 4,
        "mile" => 5,
        "m" => 6,
        "km" => 7,
        "mil" => 8,
        "um" => 9,
        "cm" => 10,
        "microinch" => 11,
        // Any other unit: flag 3, named in Global parameter 15.
        _ => 3,
    };
    let g = format!(
        "1H,,1H;,{},{},{},{},32,38,6,308,15,{},1.0,{flag},{},1,0.0,15H20260101.000000,1.0E-9,0.0,0H,0H,11,0,15H20260101.000000;",
        hol("vericad"),
        hol(name),
        hol("vericad"),
        hol("vericad"),
        hol("vericad"),
        hol(&unit.to_uppercase())
    );
    let mut gl = Vec::new();
    let mut gseq = 1;
    p_lines_global(&g, &mut gseq, &mut gl);
    let mut out = String::new();
    out += &format!("{:<72}S{:>7}\n", "vericad IGES export", 1);
    for l in &gl {
        out += l;
        out.push('\n');
    }
    for l in d.iter().chain(&p) {
        out += l;
        out.push('\n');
    }
    out += &format!(
        "S{:>7}G{:>7}D{:>7}P{:>7}{:>40}T{:>7}\n",
        1,
        gl.len(),
        d.len(),
        p.len(),
        "",
        1
    );
    (out, notes)
}

fn p_lines_global(text: &str, seq: &mut usize, out: &mut Vec<String>) {
    let mut line = String::new();
    for tok in text.split_inclusive([',', ';']) {
        if line.len() + tok.len() > 72 {
            out.push(format!("{line:<72}G{:>7}", *seq));
            *seq += 1;
            line.clear();
        }
        line.push_str(tok);
    }
    if !line.is_empty() {
        out.push(format!("{line:<72}G{:>7}", *seq));
        *seq += 1;
    }
}
