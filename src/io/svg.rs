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

/// Render as an SVG document: u to the right, v up, one scale on both axes (the domain's
/// true aspect), the domain's border with tick labels along both axes, and a legend.
pub fn render(p: &DomainPlot) -> String {
    let (w, h, m, legend) = (900.0, 800.0, 60.0, 180.0);
    let [u0, u1, v0, v1] = p.domain;
    let (du, dv) = ((u1 - u0).max(1e-300), (v1 - v0).max(1e-300));
    let scale = ((w - 2.0 * m - legend) / du).min((h - 2.0 * m) / dv);
    let x = |u: f64| m + (u - u0) * scale;
    let y = |v: f64| h - m - (v - v0) * scale;
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
    // Axes: the domain's border, ticks at nice steps, labels u and v.
    let _ = writeln!(
        s,
        r##"<rect x="{:.2}" y="{:.2}" width="{:.2}" height="{:.2}" fill="none" stroke="#444" stroke-width="1"/>"##,
        x(u0),
        y(v1),
        du * scale,
        dv * scale
    );
    // Ticks at multiples of a nice step, labelled with as many decimals as the step has.
    let ticks = |a: f64, b: f64| -> Vec<(f64, String)> {
        let step = crate::io::picture::nice_length((b - a) / 4.0);
        let decimals = (-step.log10().floor()).max(0.0) as usize;
        let first = (a / step).ceil() as i64;
        (first..first + 20)
            .map(|k| k as f64 * step)
            .take_while(|t| *t <= b + 1e-9 * step)
            .map(|t| (t, format!("{t:.decimals$}")))
            .collect()
    };
    let _ = writeln!(
        s,
        r##"<g font-family="sans-serif" font-size="11" fill="#444">"##
    );
    for (t, label) in ticks(u0, u1) {
        let _ = writeln!(
            s,
            r##"<line x1="{0:.2}" y1="{1:.2}" x2="{0:.2}" y2="{2:.2}" stroke="#444"/><text x="{0:.2}" y="{3:.2}" text-anchor="middle">{4}</text>"##,
            x(t),
            y(v0),
            y(v0) + 5.0,
            y(v0) + 18.0,
            label
        );
    }
    for (t, label) in ticks(v0, v1) {
        let _ = writeln!(
            s,
            r##"<line x1="{0:.2}" y1="{1:.2}" x2="{2:.2}" y2="{1:.2}" stroke="#444"/><text x="{3:.2}" y="{4:.2}" text-anchor="end">{5}</text>"##,
            x(u0),
            y(t),
            x(u0) - 5.0,
            x(u0) - 8.0,
            y(t) + 4.0,
            label
        );
    }
    let _ = writeln!(
        s,
        r#"<text x="{:.2}" y="{:.2}" text-anchor="middle" font-size="13">u</text><text x="{:.2}" y="{:.2}" text-anchor="middle" font-size="13">v</text>"#,
        x(0.5 * (u0 + u1)),
        y(v0) + 36.0,
        x(u0) - 44.0,
        y(0.5 * (v0 + v1))
    );
    let _ = writeln!(s, "</g>");
    let lx = w - legend + 10.0;
    let _ = writeln!(
        s,
        r##"<g font-family="sans-serif" font-size="12"><line x1="{lx}" y1="{m}" x2="{0}" y2="{m}" stroke="#bbb"/><text x="{1}" y="{2}">knot lines</text><line x1="{lx}" y1="{3}" x2="{0}" y2="{3}" stroke="#1f77b4" stroke-width="2"/><text x="{1}" y="{4}">domain curve</text><line x1="{lx}" y1="{5}" x2="{0}" y2="{5}" stroke="#d62728"/><text x="{1}" y="{6}">polyline and vertices</text></g>"##,
        lx + 20.0,
        lx + 26.0,
        m + 4.0,
        m + 20.0,
        m + 24.0,
        m + 40.0,
        m + 44.0
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

/// `t` with XML's special characters escaped (text and attribute values).
pub(crate) fn xml_escape(t: &str) -> String {
    t.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One scale on both axes (a 2 × 1 domain is drawn twice as wide as high), ticks with
    /// clean labels, the title escaped.
    #[test]
    fn true_aspect_and_axes() {
        let curve = [[0.0, 0.0], [2.0, 1.0]];
        let s = render(&DomainPlot {
            domain: [0.0, 2.0, 0.0, 1.0],
            u_knots: &[1.0],
            v_knots: &[],
            curve: &curve,
            polyline: &curve,
            title: "a < b",
        });
        let rect = s.lines().find(|l| l.starts_with("<rect x=")).unwrap();
        let num = |name: &str| -> f64 {
            let at = rect.find(&format!(" {name}=\"")).unwrap() + name.len() + 3;
            rect[at..at + rect[at..].find('"').unwrap()]
                .parse()
                .unwrap()
        };
        assert!((num("width") - 2.0 * num("height")).abs() < 1e-9, "{rect}");
        for label in [">0.0<", ">0.5<", ">1.0<", ">1.5<", ">2.0<"] {
            assert!(s.contains(label), "{label}");
        }
        assert!(!s.contains("0000000001"));
        assert!(s.contains("a &lt; b"));
    }
}
