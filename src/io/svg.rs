//! SVG plots of parameter-domain results: knot lines of the surface, the domain curve, and
//! the domain polyline with its vertices.

use std::fmt::Write;

/// A parameter-domain plot.
pub struct DomainPlot<'a> {
    /// `(u0, u1, v0, v1)` of the surface.
    pub domain: [f64; 4],
    pub u_knots: &'a [f64],
    pub v_knots: &'a [f64],
    /// The domain curve, sampled.
    pub curve: &'a [[f64; 2]],
    /// The approximating polyline.
    pub polyline: &'a [[f64; 2]],
    pub title: &'a str,
}

/// Render as an SVG document (u to the right, v up).
pub fn render(p: &DomainPlot) -> String {
    let (w, h, m) = (800.0, 800.0, 40.0);
    let [u0, u1, v0, v1] = p.domain;
    let x = |u: f64| m + (u - u0) / (u1 - u0) * (w - 2.0 * m);
    let y = |v: f64| h - m - (v - v0) / (v1 - v0) * (h - 2.0 * m);
    let mut s = String::new();
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}">"#
    );
    let _ = writeln!(s, r#"<rect width="100%" height="100%" fill="white"/>"#);
    let _ = writeln!(
        s,
        r#"<text x="{m}" y="24" font-family="sans-serif" font-size="14">{}</text>"#,
        xml_escape(p.title)
    );
    for &k in p.u_knots {
        let _ = writeln!(
            s,
            r##"<line x1="{0:.2}" y1="{1:.2}" x2="{0:.2}" y2="{2:.2}" stroke="#bbb" stroke-width="1"/>"##,
            x(k),
            y(v0),
            y(v1)
        );
    }
    for &k in p.v_knots {
        let _ = writeln!(
            s,
            r##"<line x1="{1:.2}" y1="{0:.2}" x2="{2:.2}" y2="{0:.2}" stroke="#bbb" stroke-width="1"/>"##,
            y(k),
            x(u0),
            x(u1)
        );
    }
    let path = |pts: &[[f64; 2]]| {
        pts.iter()
            .map(|q| format!("{:.3},{:.3}", x(q[0]), y(q[1])))
            .collect::<Vec<_>>()
            .join(" ")
    };
    let _ = writeln!(
        s,
        r##"<polyline points="{}" fill="none" stroke="#1f77b4" stroke-width="2"/>"##,
        path(p.curve)
    );
    let _ = writeln!(
        s,
        r##"<polyline points="{}" fill="none" stroke="#d62728" stroke-width="1"/>"##,
        path(p.polyline)
    );
    for q in p.polyline {
        let _ = writeln!(
            s,
            r##"<circle cx="{:.3}" cy="{:.3}" r="2" fill="#d62728"/>"##,
            x(q[0]),
            y(q[1])
        );
    }
    s.push_str("</svg>\n");
    s
}

fn xml_escape(t: &str) -> String {
    t.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}
