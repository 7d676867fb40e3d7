//! Views of a reparametrization: a uniform parameter grid mapped onto the given surface S
//! and onto the new surface R, as an SVG (orthographic projection along the mean normal,
//! side by side) and as VTK PolyData (`.vtp`: both surfaces as quads and both grids as line
//! cells, with cell arrays `surface` (0 = S, 1 = R) and `spacing_ratio` (the ratio of
//! [`super::quality`] of each grid step; −1 on quads)).

use super::quality::ratios;
use crate::geom::{Point, cross, dot, norm};
use crate::spline::NurbsSurface;
use std::fmt::Write;

/// Points of the `n × n` uniform parameter grid's iso-lines, each sampled `per` times per
/// grid step: `u = const` lines, then `v = const` lines.
fn iso_lines(s: &NurbsSurface<f64, 3>, n: usize, per: usize) -> Vec<Vec<[f64; 3]>> {
    let (u0, u1, v0, v1) = s.hom.domain();
    let at = |a: f64, b: f64| s.eval(&(u0 + (u1 - u0) * a), &(v0 + (v1 - v0) * b));
    let fine = n * per;
    let mut out = vec![];
    for i in 0..=n {
        let a = i as f64 / n as f64;
        out.push((0..=fine).map(|k| at(a, k as f64 / fine as f64)).collect());
    }
    for j in 0..=n {
        let b = j as f64 / n as f64;
        out.push((0..=fine).map(|k| at(k as f64 / fine as f64, b)).collect());
    }
    out
}

/// An orthonormal view basis `(e1, e2)` perpendicular to the mean unit normal of `s`
/// (isometric when the normals cancel, e.g. on a closed surface).
fn view(s: &NurbsSurface<f64, 3>) -> ([f64; 3], [f64; 3]) {
    let (u0, u1, v0, v1) = s.hom.domain();
    let mut n = [0.0; 3];
    for i in 0..=4 {
        for j in 0..=4 {
            let (u, v) = (
                u0 + (u1 - u0) * (0.1 + 0.2 * i as f64),
                v0 + (v1 - v0) * (0.1 + 0.2 * j as f64),
            );
            if let Some(nn) = s.unit_normal(&u, &v)
                && nn.iter().all(|x| x.is_finite())
            {
                n = n.add(&nn);
            }
        }
    }
    let l = norm(&n);
    let n = if l > 5.0 {
        n.scale(&(1.0 / l))
    } else {
        [1.0 / 3f64.sqrt(); 3]
    };
    let a = if n[0].abs() < 0.6 {
        [1.0, 0.0, 0.0]
    } else {
        [0.0, 1.0, 0.0]
    };
    let e1 = cross(&a, &n);
    let e1 = e1.scale(&(1.0 / norm(&e1)));
    (e1, cross(&n, &e1))
}

/// One face of the SVG: the given and the new surface and a title for each.
pub struct Panel<'a> {
    pub given: &'a NurbsSurface<f64, 3>,
    pub new: &'a NurbsSurface<f64, 3>,
    pub titles: [String; 2],
}

/// The SVG: per face one row, S's uniform parameter grid on the left, R's on the right, in
/// the same projection and scale.
pub fn svg(panels: &[Panel], n: usize) -> String {
    let (pw, ph, m, top) = (500.0, 500.0, 20.0, 40.0);
    let rows = panels.len().max(1) as f64;
    let (w, h) = (2.0 * pw, rows * (ph + top) + 30.0);
    let mut out = String::new();
    let _ = writeln!(
        out,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}">"#
    );
    let _ = writeln!(out, r#"<rect width="100%" height="100%" fill="white"/>"#);
    for (row, p) in panels.iter().enumerate() {
        let oy = row as f64 * (ph + top);
        let (e1, e2) = view(p.given);
        let ls = iso_lines(p.given, n, 4);
        let lr = iso_lines(p.new, n, 4);
        let proj = |q: &[f64; 3]| [dot(q, &e1), -dot(q, &e2)];
        let mut lo = [f64::INFINITY; 2];
        let mut hi = [f64::NEG_INFINITY; 2];
        for q in ls.iter().chain(&lr).flatten() {
            let q = proj(q);
            if q.iter().all(|x| x.is_finite()) {
                for k in 0..2 {
                    lo[k] = lo[k].min(q[k]);
                    hi[k] = hi[k].max(q[k]);
                }
            }
        }
        let ext = (hi[0] - lo[0]).max(hi[1] - lo[1]);
        let sc = if ext.is_finite() && ext > 0.0 {
            (pw - 2.0 * m) / ext
        } else {
            1.0
        };
        for (panel, (lines, title)) in [(&ls, &p.titles[0]), (&lr, &p.titles[1])]
            .into_iter()
            .enumerate()
        {
            let ox = panel as f64 * pw;
            let _ = writeln!(
                out,
                r#"<text x="{:.1}" y="{:.1}" font-family="sans-serif" font-size="13">{}</text>"#,
                ox + m,
                oy + 24.0,
                escape(title)
            );
            for (k, l) in lines.iter().enumerate() {
                let pts: Vec<String> = l
                    .iter()
                    .map(proj)
                    .filter(|q| q.iter().all(|x| x.is_finite()))
                    .map(|q| {
                        format!(
                            "{:.2},{:.2}",
                            ox + m + (q[0] - lo[0]) * sc,
                            oy + top + m + (q[1] - lo[1]) * sc
                        )
                    })
                    .collect();
                let color = if k <= n { "#1f77b4" } else { "#d62728" };
                let _ = writeln!(
                    out,
                    r#"<polyline points="{}" fill="none" stroke="{color}" stroke-width="1"/>"#,
                    pts.join(" ")
                );
            }
        }
    }
    let _ = writeln!(
        out,
        r#"<text x="{m}" y="{:.1}" font-family="sans-serif" font-size="12">uniform {n}×{n} parameter grids: blue u = const, red v = const; orthographic view along the mean normal</text>"#,
        h - 10.0
    );
    out.push_str("</svg>\n");
    out
}

fn escape(t: &str) -> String {
    t.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// The VTK PolyData document for faces `(face index, S, R)` (see the module documentation;
/// the cell array `face` holds the face index).
pub fn vtk(faces: &[(usize, &NurbsSurface<f64, 3>, &NurbsSurface<f64, 3>)], n: usize) -> String {
    use crate::io::vtk::{Array, PolyData, render};
    let mut pd = PolyData::default();
    let (mut face, mut surface, mut ratio) = (vec![], vec![], vec![]);
    // Quads first: cell data runs over polys, then lines.
    for &(f, s, r) in faces {
        for (id, x) in [(0.0, s), (1.0, r)] {
            let q = pd.add_surface(x, 32);
            face.extend(std::iter::repeat_n(f as f64, q));
            surface.extend(std::iter::repeat_n(id, q));
            ratio.extend(std::iter::repeat_n(-1.0, q));
        }
    }
    for &(f, s, r) in faces {
        for (id, x) in [(0.0, s), (1.0, r)] {
            let lines = iso_lines(x, n, 1);
            let rs = ratios(x, n);
            for (l, rl) in lines.iter().zip(&rs) {
                for (k, w) in l.windows(2).enumerate() {
                    pd.add_polyline(w);
                    face.push(f as f64);
                    surface.push(id);
                    ratio.push(rl.get(k).copied().unwrap_or(-1.0));
                }
            }
        }
    }
    for (name, values) in [
        ("face", face),
        ("surface", surface),
        ("spacing_ratio", ratio),
    ] {
        pd.cell_data.push(Array {
            name: name.into(),
            values,
        });
    }
    render(&pd)
}
